"""Run checks over many paths: collect G-code files from folders, apply the configuration that belongs
to each file, spread the work over processes, and return results in a stable order."""

from __future__ import annotations

import os
import re
import stat
from collections import deque
from collections.abc import Callable, Collection, Iterable, Iterator
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, TypedDict

from gclint.checkout import inside as _inside
from gclint.config import ConfigError, apply, clear_found, config_for, severities_above
from gclint.engine import FileResult, Linter, Options
from gclint.excludes import TOOL_FOLDER, Excluder, Exclusion, LeftOut
from gclint.machine.linuxcnc_ini import clear as _forget_machine_configs
from gclint.machine.linuxcnc_ini import machine_codes
from gclint.syntax.source import NotGcode, Source, SourceError
from gclint.trust import Refusal, guard, keep_raised, security_only

if TYPE_CHECKING:
    from gclint.cache import ResultCache

GCODE_EXTENSIONS = (".gcode", ".gco", ".gc", ".g", ".nc", ".ngc", ".cnc", ".tap")
# Packages and encodings that carry a job (an Ultimaker Format Package and a Bambu/Orca ".gcode.3mf" are ZIP
# archives with the G-code inside; ".bgcode" is Prusa's binary G-code; ".gx" is FlashForge's G-code behind a binary
# header and thumbnail): found by a walk so that the check says it cannot read them (exit 2), never passed in silence.
PACKAGE_EXTENSIONS = (".ufp", ".gcode.3mf", ".bgcode", ".gx")
_TRAILING = re.compile(r"[\s.]+\Z")


class RunOptions(TypedDict, total=False):
    """The keyword arguments ``run`` and ``results`` share (one run's settings, passed to either)."""

    explicit_config: str | None
    jobs: int
    stdin_name: str
    progress: Callable[[FileResult], None] | None
    cache: ResultCache | None
    security_only: Collection[str]
    links: dict[str, str] | None


def is_job_name(name: str) -> bool:
    """Whether a walk takes the file ``name`` for a job: a G-code extension in any case, also before
    trailing blanks and dots (Windows and FAT drop them: ``job.gcode `` reaches the printer as
    ``job.gcode``)."""
    return _TRAILING.sub("", name.lower()).endswith(GCODE_EXTENSIONS + PACKAGE_EXTENSIONS)


def collect(
    paths: Iterable[str],
    notes: list[str] | None = None,
    excluder: Excluder | None = None,
    left_out: list[LeftOut] | None = None,
    roots: dict[str, str] | None = None,
    security_only: list[LeftOut] | None = None,
    links: dict[str, str] | None = None,
) -> tuple[list[str], list[FileResult]]:
    """Expand folders into their G-code files (sorted; hidden folders included, excluded and .gitignored
    paths left out, symbolic links to folders not followed: as ruff does; files git tracks are never left
    out by .gitignore or the default tool folders).

    Returns the files to check and results for the paths that cannot be checked (missing, empty or
    unreadable folder, a pipe or device found in a folder, a link to a file outside the repository).
    ``notes`` receives what was left out on purpose (links to folders), for the user; ``left_out`` the
    G-code files excluded, and why; ``security_only`` the files a configuration found beside them would
    exclude (checked by the SC rules alone); ``links`` the links to files inside the repository that are
    checked, with the file each points to (their text is never shown); ``roots`` each file found in a folder
    with the real path of the folder it was found in.
    """
    excluder = excluder if excluder is not None else Excluder()
    notes = notes if notes is not None else []
    left_out = left_out if left_out is not None else []
    roots = roots if roots is not None else {}
    security_only = security_only if security_only is not None else []
    links = links if links is not None else {}
    files: list[str] = []
    problems: list[FileResult] = []
    seen: set[str] = set()
    for path in paths:
        if path == "-":
            files.append(path)
            continue
        if os.path.islink(path) and os.path.isdir(path) and excluder.forced(path):
            # (what pre-commit names is held to what a walk finds, and a walk does not follow a link to a folder:
            # it may lead out of the checkout, and --fix would write there)
            problems.append(
                FileResult(path, error=f"{path}: a symbolic link to a folder, not followed (name the folder)")
            )
            continue
        if os.path.isdir(path):
            walk = _Walk(path, excluder, problems, notes, left_out, roots, security_only, links)
            walk.run()
            if not walk.found and not walk.skipped and len(problems) == walk.problems_before:
                problems.append(
                    FileResult(path, error=f"{path}: no G-code files in this folder ({' '.join(GCODE_EXTENSIONS)})")
                )
            for f in walk.found:
                if f not in seen:
                    seen.add(f)
                    files.append(f)
        elif os.path.lexists(path):
            why = excluder.excluded(path, False, named=True)
            if why is not None:  # --force-exclude: named, but excluded (as pre-commit passes every staged file)
                left_out.append(LeftOut(path, why))
                continue
            if excluder.forced(path):  # what pre-commit names is held to what a walk would find
                found = excluder.security_only(path, False, named=True)
                if found is not None:
                    security_only.append(LeftOut(path, found))
                problem = _link(path, excluder, links, None)
                if problem is not None:
                    problems.append(problem)
                    continue
                kind = _not_regular(path)
                if kind is not None:  # (a pipe named by pre-commit would wait forever for a writer)
                    problems.append(FileResult(path, error=f"{path}: {kind}, not a file: not read"))
                    continue
            if path not in seen:
                seen.add(path)
                files.append(path)
        else:
            problems.append(FileResult(path, error=f"{path}: no such file or folder"))
    files = _once(files, links, notes)
    notes.extend(excluder.notes)
    excluder.notes.clear()
    return files, problems


def _link(path: str, excluder: Excluder, links: dict[str, str], top: str | None) -> FileResult | None:
    """For a symbolic link to a file: recorded in ``links`` when it points inside the repository it is in
    (the folder holding ``.git``; else ``top``, the folder walked, or the working folder), else the error
    that it is not read.  None for anything that is not a link."""
    try:
        if not os.path.islink(path):
            return None
    except OSError:
        return None
    folder = os.path.dirname(os.path.abspath(path))
    repository = excluder.repository_root(folder)
    checkout = os.path.realpath(repository if repository is not None else top if top is not None else os.getcwd())
    target = os.path.realpath(path)
    if not _inside(target, checkout):
        return FileResult(
            path,
            error=f"{path}: a symbolic link to a file outside this checkout ({target}): not read; check that"
            " file by its own name, or exclude the link on the command line or with --config",
        )
    links[path] = target
    return None


def _once(files: list[str], links: dict[str, str], notes: list[str]) -> list[str]:
    """``files`` without the links to a file that is checked already (by its own name or through an
    earlier link): a file is checked once, and ``--fix`` writes it once."""
    if not links:
        return files
    seen: dict[tuple[int, int], str] = {}
    for path in files:
        if path != "-" and path not in links:
            key = _identity(path)
            if key is not None:
                seen.setdefault(key, path)
    out = []
    for path in files:
        if path in links:
            key = _identity(path)
            if key is not None and key in seen:
                notes.append(f"{path}: a link to {seen[key]}, which is checked: not checked twice")
                del links[path]
                continue
            if key is not None:
                seen[key] = path
        out.append(path)
    return out


def _identity(path: str) -> tuple[int, int] | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return st.st_dev, st.st_ino


# Entries listed, in all, to count the G-code files of excluded folders (a gitignored output folder, a
# node_modules inside a jobs folder); past it an excluded folder is named rather than counted.
COUNT_BUDGET = 100_000


class _Walk:
    """One folder walk: depth first, files of a folder before its sub-folders, each sorted by name.

    A folder that cannot be read is a problem (exit 2), never skipped in silence; links to folders are not
    followed (no loops), with a note; a link to a file outside the repository is not read (a committed link
    must not pull ~/.ssh/id_ed25519 into a report, nor let a fix write outside the tree) and is a problem;
    one inside it is checked under its own name.  Excluded folders are entered only to find the files git
    tracks in them (checked unless the user's own patterns exclude them), the files a configuration found
    beside them would exclude (checked by the SC rules alone) and to count the G-code files left out; a
    tool folder where one is expected (.venv, node_modules beside .git, or at the top of a folder outside
    any repository) is not counted at all."""

    def __init__(
        self,
        top: str,
        excluder: Excluder,
        problems: list[FileResult],
        notes: list[str],
        left_out: list[LeftOut],
        roots: dict[str, str],
        security_only: list[LeftOut],
        links: dict[str, str],
    ) -> None:
        self.top = top
        self.top_real = os.path.realpath(top)
        repository = excluder.repository_root(top)
        self.outside_repository = repository is None
        self.excluder = excluder
        self.problems = problems
        self.problems_before = len(problems)
        self.notes = notes
        self.left_out = left_out
        self.roots = roots
        self.security_only = security_only
        self.links = links
        self.found: list[str] = []
        self.skipped = 0  # G-code files found but not checked (excluded): the folder is not empty
        self.budget = COUNT_BUDGET

    def run(self) -> None:
        # (folder, why it is excluded, the found configuration's pattern that names it)
        stack: list[tuple[str, Exclusion | None, Exclusion | None]] = [(self.top, None, None)]
        while stack:
            folder, inherited, downgraded = stack.pop()
            try:
                with os.scandir(folder) as listing:
                    entries = sorted(listing, key=lambda e: e.name)
            except OSError as exc:
                if inherited is None or downgraded is not None:
                    error = f"{folder}: cannot read this folder: {exc.strerror or exc}"
                    self.problems.append(FileResult(folder, error=error))
                elif not inherited.quiet:
                    self._leave_out(LeftOut(_shown(folder), inherited, folder=True))
                continue
            if inherited is not None and not inherited.quiet:
                self.budget -= len(entries)
            subfolders = []
            for entry in entries:
                try:
                    if entry.is_dir(follow_symlinks=False):
                        enter, why = self._subfolder(entry.path, folder, inherited)
                        if enter:
                            down = downgraded or self.excluder.security_only(entry.path, True)
                            subfolders.append((entry.path, why, down))
                        continue
                    if entry.is_symlink() and entry.is_dir():
                        target = os.path.realpath(entry.path)
                        walked = target == self.top_real or target.startswith(self.top_real + os.sep)
                        if inherited is None and walked:  # (a folder this walk reads anyway: a loop)
                            self.notes.append(
                                f"{entry.path}: a symbolic link to a folder this walk checks anyway, not followed"
                            )
                        elif inherited is None:
                            # (the jobs behind it are reachable wherever the link resolves, a printer host's folder
                            # included: the gate does not pass them unread; the link may lead out of the checkout,
                            # so it is not followed)
                            self.problems.append(
                                FileResult(
                                    entry.path,
                                    error=f"{entry.path}: a symbolic link to a folder, not followed: name the folder it"
                                    " points to to check it, or exclude the link",
                                )
                            )
                        continue
                except OSError:
                    pass
                if is_job_name(entry.name):
                    self._file(entry, inherited, downgraded)
            stack.extend(reversed(subfolders))

    def _subfolder(self, path: str, parent: str, inherited: Exclusion | None) -> tuple[bool, Exclusion | None]:
        """Whether to enter the folder ``path``, and why it is excluded (None: it is walked as usual)."""
        own = self.excluder.why(path, True)
        if inherited is None:
            if own is None:
                return True, None
            why = own
            if own.by == TOOL_FOLDER and self._expected(parent):
                why = replace(own, quiet=True)
                self.left_out.append(LeftOut(_shown(path), why, folder=True))  # for -v
        elif own is not None and own.by == TOOL_FOLDER:  # a tool folder in an excluded folder: not counted
            if inherited.chosen:
                return False, None
            why = replace(inherited, quiet=True)
        elif own is not None and own.chosen and not inherited.chosen:
            why = own
        else:
            why = inherited
        assert why is not None
        if not why.chosen and self.excluder.holds_tracked(path):
            return True, why
        if why.quiet:
            return False, why
        if self.budget <= 0:
            self._leave_out(LeftOut(_shown(path), why, folder=True))
            return False, why
        return True, why

    def _expected(self, parent: str) -> bool:
        """Whether a tool folder in ``parent`` is where one is expected: beside ``.git``, or at the top of
        a walk outside any repository (``jobs/node_modules`` in a repository is not)."""
        return os.path.lexists(os.path.join(parent, ".git")) or (self.outside_repository and parent == self.top)

    def _file(self, entry: os.DirEntry, inherited: Exclusion | None, downgraded: Exclusion | None) -> None:
        path = entry.path
        own = None if inherited is not None and inherited.chosen else self.excluder.why(path, False)
        why = own if inherited is None or (own is not None and own.chosen) else inherited
        if why is not None and (why.chosen or not self.excluder.tracked(path)):
            if not why.quiet:
                self._leave_out(LeftOut(_shown(path), why))
            return
        down = downgraded or self.excluder.security_only(path, False)
        shown = _shown(path)
        try:
            link = entry.is_symlink()
        except OSError:
            link = False
        if link and (problem := _link(shown, self.excluder, self.links, self.top)) is not None:
            self.problems.append(problem)
            return
        kind = _not_regular(path)
        if kind is not None:
            self.problems.append(FileResult(path, error=f"{path}: not a regular file ({kind}): not read"))
            return
        if down is not None:
            self.security_only.append(LeftOut(shown, down))
        self.found.append(shown)
        self.roots[shown] = self.top_real

    def _leave_out(self, item: LeftOut) -> None:
        self.skipped += 1
        self.left_out.append(item)


def _shown(path: str) -> str:
    """A path as the user sees it: "a.gcode", not "./a.gcode" (as ruff)."""
    return path[2:] if path.startswith("./") else path


def outside_walk(path: str, roots: dict[str, str]) -> str | None:
    """For a file found in a folder walk: where it leads when that is now outside the walked folder (a
    link put there since it was walked), else None.  Nothing is written through such a link."""
    root = roots.get(path)
    if root is None:
        return None
    target = os.path.realpath(path)
    return None if _inside(target, root) else target


def _not_regular(path: str) -> str | None:
    """What ``path`` is when it is not a regular file (or a link to one): opening a pipe found in a folder
    would wait forever for a writer.  A dangling link counts as a file (checking it says "no such file")."""
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return None
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISFIFO(mode):
        return "a named pipe"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a file"


def options_for(path: str, base: Options, overrides: dict, explicit_config: str | None) -> Options:
    """Defaults, then the configuration file that applies to ``path``, then the command line.  A
    configuration found beside the files cannot switch security rules off (gclint.trust)."""
    return configured(path, base, overrides, explicit_config)[0]


def configured(path: str, base: Options, overrides: dict, explicit_config: str | None) -> tuple[Options, list[Refusal]]:
    """``options_for`` and what a found configuration asked of the security rules in vain."""
    config_path, table = config_for(path, explicit_config)
    options = base
    if config_path is not None:
        options = apply(options, table, config_path)
    if overrides and overrides.get("extend_known_codes"):  # adds to the configuration's codes
        overrides = {**overrides, "extend_known_codes": options.extend_known_codes + overrides["extend_known_codes"]}
    options = replace(options, **overrides) if overrides else options
    codes, inis = machine_codes(path)
    if codes:  # (the LinuxCNC machine's INI beside the job: its REMAP codes are known codes, DL001 only)
        options = replace(options, machine_codes=codes, machine_config=inis)
    if config_path is None or explicit_config is not None:
        return options, []
    said = (options.dialect_origin == "configuration" and "dialect" not in (overrides or {})) or (
        options.flavor_origin == "configuration" and "flavor" not in (overrides or {})
    )
    if said:  # the dialect (or the firmware, which names it) said by the found configuration: a change can add one
        options = replace(options, dialect_trusted=False)
    options, refused = guard(options, replace(base, **overrides) if overrides else base)
    return keep_raised(options, severities_above(config_path)), refused


_LINTERS: dict[str, Linter] = {}


def linter_for(options: Options) -> Linter:
    """The (per-process, cached) linter for ``options``."""
    return _linter(options)


def _linter(options: Options) -> Linter:
    key = options.cache_key()
    linter = _LINTERS.get(key)
    if linter is None:
        linter = _LINTERS[key] = Linter(options)
    return linter


def check_one(path: str, options: Options) -> FileResult:
    """Check one file with its options; never raises for a bad file."""
    return check_file(path, options)[0]


def check_file(path: str, options: Options) -> tuple[FileResult, str | None]:
    """Check one file; also returns the SHA-256 of exactly the bytes that were checked (None for pipes,
    devices and files not read to the end), which is what the result cache may store the result under.

    A line too long to hold is reported (SX001), not read whole: checking never needs the whole line.
    A slicer profile (a PrusaSlicer/OrcaSlicer ``.ini`` or ``.json``, a Cura ``.def.json``: gclint.profiles)
    is checked as one: the G-code of its custom settings, each finding where it is written in the profile."""
    if is_profile(path):
        from gclint.profiles.check import check_profile

        try:
            return check_profile(path, options, _linter(options)), None
        except RecursionError:
            return FileResult(path, error=f"{path}: nesting too deep to check"), None
        except Exception as exc:  # a bug in gclint itself: name the file, keep going with the others
            detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
            return FileResult(path, error=f"{path}: internal error while checking ({detail}); please report this"), None
    try:
        source = Source.open(path, digest=True, cut_long_lines=True)
    except NotGcode as exc:  # (binary: a magic number, NUL bytes)
        return _not_gcode(path, options, str(exc)), None
    except SourceError as exc:
        return FileResult.unreadable(path, exc), None
    try:
        result = _linter(options).check_source(source)
        if result.not_gcode:  # (text that says it is something else: a script, an INI file)
            return _not_gcode(path, options, result.error or path), None
        return result, source.sha256
    except SourceError as exc:
        return FileResult.unreadable(path, exc), None
    except RecursionError:
        return FileResult(path, error=f"{path}: nesting too deep to check"), None
    except MemoryError:
        return FileResult(path, error=f"{path}: out of memory while checking"), None
    except Exception as exc:  # a bug in gclint itself: name the file, keep going with the others
        detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
        return FileResult(path, error=f"{path}: internal error while checking ({detail}); please report this"), None
    finally:
        source.close()


PROFILE_EXTENSIONS = (".ini", ".json")  # slicer profiles (gclint.profiles), checked when named or --profiles


def is_profile(path: str) -> bool:
    """Whether ``path`` is a slicer profile gclint checks as one: a ``.ini`` or ``.json`` name, and text that
    a slicer wrote (an INI of LinuxCNC or any other program is not one)."""
    if path == "-" or not path.lower().rstrip(" .").endswith(PROFILE_EXTENSIONS):
        return False
    from gclint.profiles.reader import kind_of

    try:
        with open(path, "rb") as fh:
            head = fh.read(64 << 10)
    except OSError:
        return False
    return kind_of(path, head.decode("utf-8", "replace")) is not None


def _not_gcode(path: str, options: Options, reason: str) -> FileResult:
    """A file refused as not G-code: its SC findings as a firmware would read it, and an error (exit 2)."""
    from gclint.notgcode import scan

    try:
        return scan(path, _linter(security_only(options)), reason)
    except RecursionError:
        return FileResult(path, error=f"{reason}; nesting too deep to read")
    except Exception as exc:  # a bug in gclint itself: the file is still not passed
        detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
        return FileResult(path, error=f"{reason}; internal error while reading it ({detail}); please report this")


def run(
    files: list[str],
    base: Options,
    overrides: dict,
    explicit_config: str | None = None,
    jobs: int = 1,
    stdin_name: str = "-",
    progress: Callable[[FileResult], None] | None = None,
    cache: ResultCache | None = None,
    security_only: Collection[str] = (),
    links: dict[str, str] | None = None,
) -> list[FileResult]:
    """Check ``files``; results come back in the order of ``files``.

    With a ``cache``, files whose content, configuration and rule set are unchanged since the last run
    are not checked again.  ``security_only``: files checked by the SC rules alone (a configuration found
    beside them excludes them); ``links``: links checked under their own name, each with the file it points
    to (``through_link``).  (All results at once: ``results`` gives them one by one, in bounded memory.)
    """
    return list(
        results(files, base, overrides, explicit_config, jobs, stdin_name, progress, cache, security_only, links)
    )


@dataclass
class _Item:
    """One file of a run: its result when known before checking (a configuration error, the cache), else
    the task that checks it."""

    index: int
    path: str
    result: FileResult | None = None
    task: tuple[str, Options] | None = None
    key: str | None = None  # the cache key the result is stored under
    stdin: Linter | None = None  # standard input, checked in this process when its turn comes
    cached: bool = False
    target: str | None = None  # a link: the file it points to (its text is not shown)


def results(
    files: list[str],
    base: Options,
    overrides: dict,
    explicit_config: str | None = None,
    jobs: int = 1,
    stdin_name: str = "-",
    progress: Callable[[FileResult], None] | None = None,
    cache: ResultCache | None = None,
    security_only: Collection[str] = (),
    links: dict[str, str] | None = None,
) -> Iterator[FileResult]:
    """Check ``files``, giving each result as soon as it and those before it are known, in the order of
    ``files``.  Memory does not grow with the number of files: a few batches of files are checked ahead
    (read from the cache, or sent to the worker processes), not the whole run."""
    clear_found()
    _forget_machine_configs()
    links = links or {}
    items = _items(files, base, overrides, explicit_config, stdin_name, cache, frozenset(security_only), links)
    workers = min(jobs, len(files))
    if workers <= 1:
        for item in items:
            yield _finish(item, check_file(*item.task) if item.task is not None else None, stdin_name, cache, progress)
        return
    # batches of tasks per process call keep the inter-process traffic low for many small files; a batch
    # holds a few small files or one big one, and only one batch more than there are workers is in flight
    # (finished results wait in memory for their turn: each may hold up to MAX_FINDINGS findings)
    size = max(1, min(16, len(files) // (workers * 4)))
    batches = _batches(items, size)
    from concurrent.futures import ProcessPoolExecutor  # (here: a one-file check does not pay for multiprocessing)

    with ProcessPoolExecutor(max_workers=workers) as pool:
        window: deque = deque()

        def submit() -> None:
            batch = next(batches, None)
            if batch is not None:
                tasks = [item.task for item in batch if item.task is not None]
                window.append((batch, pool.submit(_check_tasks, tasks) if tasks else None))

        for _ in range(workers + 1):
            submit()
        while window:
            batch, future = window.popleft()
            submit()
            done = iter(future.result() if future is not None else ())
            for item in batch:
                yield _finish(item, next(done) if item.task is not None else None, stdin_name, cache, progress)


def _items(
    files: list[str],
    base: Options,
    overrides: dict,
    explicit_config: str | None,
    stdin_name: str,
    cache: ResultCache | None,
    security: frozenset[str],
    links: dict[str, str],
) -> Iterator[_Item]:
    for index, path in enumerate(files):
        item = _Item(index, path, target=links.get(path))
        try:
            # standard input is configured as the file it names (--stdin-filename), as ruff does
            named = stdin_name if path == "-" and stdin_name != "-" else path
            options = options_for(named, base, overrides, explicit_config)
        except ConfigError as exc:
            item.result = FileResult(path, error=str(exc))
            yield item
            continue
        if path in security:
            options = security_only(options)
        if path == "-":
            item.stdin = _linter(options)
        elif cache is not None and item.target is None:  # (a link's result is not the file's: not cached)
            key = cache.settings_key(options.cache_key(), [r.code for r in _linter(options).rule_classes])
            item.result = cache.get(path, key)
            item.cached = item.result is not None
            if item.result is None:
                item.key = key
                item.task = (path, options)
        else:
            item.task = (path, options)
        yield item


BATCH_BYTES = 64 << 10  # input bytes per batch of files sent to a worker (a bigger file is a batch alone)


def _batches(items: Iterator[_Item], size: int) -> Iterator[list[_Item]]:
    """Consecutive items, up to ``size`` tasks and BATCH_BYTES of input a batch (with the items known
    without checking between them)."""
    batch: list[_Item] = []
    tasks = 0
    volume = 0
    for item in items:
        if item.task is not None:
            try:
                length = os.path.getsize(item.path)
            except OSError:
                length = 0
            if tasks and volume + length > BATCH_BYTES:
                yield batch
                batch, tasks, volume = [], 0, 0
            tasks += 1
            volume += length
        batch.append(item)
        if tasks >= size:
            yield batch
            batch, tasks, volume = [], 0, 0
    if batch:
        yield batch


def _finish(
    item: _Item,
    checked: tuple[FileResult, str | None] | None,
    stdin_name: str,
    cache: ResultCache | None,
    progress: Callable[[FileResult], None] | None,
) -> FileResult:
    if item.stdin is not None:
        return _check_stdin(item.stdin, stdin_name)
    if checked is None:  # known before checking: a configuration error or the cache's
        assert item.result is not None
        if item.cached and progress is not None:
            progress(item.result)
        return item.result
    result, digest = checked
    if item.target is not None:
        result = through_link(result, item.target)
    if cache is not None and item.key is not None and digest is not None:
        cache.put(item.path, item.key, result, digest)
    if progress is not None:
        progress(result)
    return result


def through_link(result: FileResult, target: str) -> FileResult:
    """The result of checking a link inside the repository, as reported under the link's name: each
    finding with its rule's summary instead of its message, no line text, no fix (nothing is written
    through a link found in a folder), and nothing of how the file was read.  What the file it points
    to holds is never shown (a link to a checkout's .env must not put it in a SARIF report)."""
    from gclint.rules.base import all_rules

    where = _near(target)
    rules = all_rules()
    findings = []
    for f in result.findings:
        summary = rules[f.code].summary if f.code in rules else f.name
        message = f"{summary} (in {where}, which this link points to; its text is not shown)"
        findings.append(replace(f, message=message, source=None, fix=None))
    error = None
    if result.error is not None:
        what = "is not G-code" if result.not_gcode else "could not be checked"
        error = f"{result.path}: the file this link points to ({where}) {what}; check it by its own name to see why"
    return FileResult(result.path, findings, result.dialect, "", result.lines, error, None, None, result.not_gcode)


def _near(path: str) -> str:
    """``path`` relative to the working folder when it is inside it."""
    here = os.getcwd()
    return os.path.relpath(path, here) if _inside(path, os.path.realpath(here)) else path


def _check_stdin(linter: Linter, stdin_name: str) -> FileResult:
    try:
        return linter.check_source(Source(_stdin(), stdin_name, cut_long_lines=True))
    except SourceError as exc:
        return FileResult(stdin_name, error=str(exc))
    except Exception as exc:  # a bug in gclint itself: one line, no traceback
        detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
        error = f"{stdin_name}: internal error while checking ({detail}); please report this"
        return FileResult(stdin_name, error=error)


def _check_tasks(tasks: list[tuple[str, Options]]) -> list[tuple[FileResult, str | None]]:
    return [check_file(*task) for task in tasks]


def _stdin():
    from gclint.syntax.source import stdin

    return stdin()


def default_jobs() -> int:
    return os.cpu_count() or 1


__all__ = [
    "collect",
    "configured",
    "is_job_name",
    "run",
    "results",
    "check_one",
    "options_for",
    "outside_walk",
    "GCODE_EXTENSIONS",
    "default_jobs",
    "Path",
]
