"""Which paths a check leaves out, as ruff does: ``exclude`` (replaces the default folders),
``extend-exclude`` (adds to them), both globs relative to the configuration file that names them
(gclint.globs), the files ``.gitignore`` ignores (``respect-gitignore``, on by default; the ``.gitignore``
files of the folders up to the repository's root and ``.git/info/exclude``, gclint.gitignore), and
``force-exclude`` to apply it all to files named on the command line too (what pre-commit and editors
pass).

Unlike ruff, a file that git tracks is never left out because of ``.gitignore`` or because it is in a tool
folder (``node_modules``, ``venv``, ...): a ``.gitignore`` is about untracked files, and a job committed
there is a job a CI gate must see.  Which files are tracked is asked of git once per repository
(``git ls-files``), only when something would be left out for those reasons; when git cannot answer (not
installed, "dubious ownership"), neither ``.gitignore`` nor the tool folders leave anything out there, and
one note says why.  What the user's own patterns name is left out, tracked or not: the command line's and
those of a configuration named by ``--config``.  A configuration found beside the files travels with them
(a pull request can add one), so its patterns do not leave files out of the security rules: the files they
name are checked by the SC rules alone (``Excluder.security_only``).  ``LeftOut`` records each file left
out, for the notes."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from gclint import globs
from gclint.checkout import Roots
from gclint.config import ConfigError, config_for

# Folders a walk never enters (like ruff's default excludes): version control and tool folders.
DEFAULT_EXCLUDE = (
    ".git",
    ".hg",
    ".svn",
    ".bzr",
    ".jj",
    ".venv",
    "venv",
    ".tox",
    ".nox",
    "node_modules",
    "__pycache__",
    ".mypy_cache",
    ".pytest_cache",
    ".ruff_cache",
    ".gclint_cache",
    "site-packages",
)
TOOL_FOLDER = "tool folder"  # what a default exclude leaves out
GIT_TIMEOUT = 20.0  # seconds for `git ls-files` (a huge repository lists in about one)
# git reads these to find another repository or index than the one holding the path: a hook (pre-commit)
# runs with some of them set, and the question here is about the repository at hand.
_GIT_LOCATION_VARIABLES = (
    "GIT_DIR",
    "GIT_WORK_TREE",
    "GIT_INDEX_FILE",
    "GIT_COMMON_DIR",
    "GIT_OBJECT_DIRECTORY",
    "GIT_ALTERNATE_OBJECT_DIRECTORIES",
    "GIT_NAMESPACE",
    "GIT_CEILING_DIRECTORIES",
    "GIT_DISCOVERY_ACROSS_FILESYSTEM",
)


@dataclass(frozen=True)
class Exclusion:
    """Why a path is left out."""

    by: str  # "exclude", "extend-exclude" (the user's patterns), ".gitignore" or TOOL_FOLDER
    pattern: str = ""
    source: str = ""  # the configuration file or "command line" the pattern comes from
    quiet: bool = False  # a tool folder where one is expected (.venv beside .git): said only with -v
    trusted: bool = True  # False: a configuration found beside the files (it cannot leave out jobs)

    @property
    def chosen(self) -> bool:
        """The user's own patterns: they leave out tracked files too."""
        return self.by in ("exclude", "extend-exclude")

    def __str__(self) -> str:
        if self.by == ".gitignore":
            return "ignored by .gitignore"
        if self.by == TOOL_FOLDER:
            return f"in a tool folder ({self.pattern!r}, a default exclude)"
        said = f"excluded by {self.by} {self.pattern!r}" + (f" ({self.source})" if self.source else "")
        if not self.trusted:
            said += ", a configuration found beside the files: the security rules check it all the same"
        return said


@dataclass(frozen=True)
class LeftOut:
    """A G-code file (or, ``folder``, a folder of them) that a check leaves out, and why."""

    path: str
    why: Exclusion
    folder: bool = False  # a folder: not walked (quiet), or whose G-code files were not all counted

    def describe(self) -> str:
        """One line for -v."""
        if self.folder and self.why.quiet:
            return f"{self.path}: a tool folder, not walked (its files tracked by git are checked)"
        if self.folder:
            return f"{self.path}: a folder {self.why}; its G-code files were not all counted"
        return f"{self.path}: {self.why}"


def summary(left_out: list[LeftOut], shown: int = 3) -> str:
    """``2 G-code files excluded (extend-exclude: jobs/a.gcode; .gitignore: out/b.gcode)``, or "" when
    nothing said is left out (the quiet tool folders are for -v only)."""
    said = [x for x in left_out if not x.why.quiet]
    if not said:
        return ""
    groups: dict[str, list[LeftOut]] = {}
    for x in said:
        groups.setdefault(x.why.by, []).append(x)
    parts = []
    for by, items in groups.items():
        names = [f"{x.path}{os.sep}... (not all counted)" if x.folder else x.path for x in items[:shown]]
        more = f" and {len(items) - shown} more" if len(items) > shown else ""
        parts.append(f"{by}: {', '.join(names)}{more}")
    files = sum(1 for x in said if not x.folder)
    count = f"{'at least ' if len(said) > files else ''}{files} G-code file{'' if files == 1 else 's'}"
    return f"{count} excluded ({'; '.join(parts)})"


def security_only_summary(items: list[LeftOut], shown: int = 3) -> str:
    """What configurations found beside the files tried to leave out, checked by the SC rules alone."""
    if not items:
        return ""
    sources: dict[str, list[LeftOut]] = {}
    for x in items:
        sources.setdefault(x.why.source, []).append(x)
    parts = []
    for source, group in sources.items():
        patterns = ", ".join(sorted({f"{x.why.by} {x.why.pattern!r}" for x in group}))
        names = ", ".join(x.path for x in group[:shown]) + (
            f" and {len(group) - shown} more" if len(group) > shown else ""
        )
        count = f"{len(group)} G-code file{'' if len(group) == 1 else 's'}"
        parts.append(f"{source} asks to exclude {count} ({patterns}: {names})")
    return (
        "; ".join(parts) + ": the security rules check them all the same (only their SC findings are reported),"
        " a configuration found beside the files cannot exclude jobs from them (the command line or a"
        " configuration named by --config can)"
    )


@dataclass
class Excluder:
    """Decides, path by path, whether the check leaves it out, and says why."""

    exclude: list[str] | None = None  # --exclude (replaces the configuration's and the defaults)
    extend_exclude: list[str] = field(default_factory=list)  # --extend-exclude
    force: bool | None = None  # --force-exclude (None: the configuration's, else off)
    respect_gitignore: bool | None = None  # --[no-]respect-gitignore (None: the configuration's, else on)
    explicit_config: str | None = None
    notes: list[str] = field(default_factory=list)  # what the user should know (git could not answer)
    _roots: Roots = field(default_factory=Roots)  # folder -> the repository root at or above it (or None)
    _specs: dict = field(default_factory=dict)  # folder -> the .gitignore files that apply in it
    _ignored_folders: dict = field(default_factory=dict)  # folder -> whether .gitignore ignores it
    _read: dict = field(default_factory=dict)  # .gitignore file -> its patterns (or None)
    _tracked: dict = field(default_factory=dict)  # repository root -> (tracked files, their folders) or None

    def reason(self, path: str, is_dir: bool, named: bool = False) -> str | None:
        """Why ``path`` is left out, or None (``excluded`` as a sentence)."""
        why = self.excluded(path, is_dir, named)
        return None if why is None else str(why)

    def excluded(self, path: str, is_dir: bool, named: bool = False) -> Exclusion | None:
        """Why ``path`` is left out, or None: ``why``, except that a file git tracks is never left out by
        ``.gitignore`` or a default tool folder.  ``named``: given on the command line (then only with
        force-exclude)."""
        why = self.why(path, is_dir, named)
        if why is not None and not why.chosen and not is_dir and self.tracked(path):
            return None
        return why

    def _table(self, path: str) -> tuple[str, str, dict]:
        """(the folder patterns are relative to, the configuration's name, its table) for ``path``."""
        try:
            config_path, table = config_for(path, self.explicit_config)
        except ConfigError:
            config_path, table = None, {}
        if config_path is None:
            return os.getcwd(), "", table
        return os.path.dirname(os.path.abspath(config_path)), _display(str(config_path)), table

    def forced(self, path: str) -> bool:
        """Whether excludes apply to ``path`` named on the command line (``--force-exclude``, or the
        configuration's ``force-exclude``): what pre-commit passes is then held to what a walk finds."""
        return self._forced(self._table(path)[2])

    def _forced(self, table: dict) -> bool:
        return self.force if self.force is not None else bool(table.get("force-exclude", False))

    def why(self, path: str, is_dir: bool, named: bool = False) -> Exclusion | None:
        """Which rule matches ``path``, if any: the user's patterns first (the command line's, then those
        of a configuration named by --config), then the default tool folders, then ``.gitignore`` (whether
        git tracks it is not asked here).  A configuration found beside the files leaves nothing out here
        (``security_only``)."""
        base, source, table = self._table(path)
        if named and not self._forced(table):
            return None
        trusted = self.explicit_config is not None
        chosen: list[tuple[str, str, str, str]] = []  # (pattern, relative to, by, source)
        here = os.getcwd()
        if self.exclude is not None:
            chosen += [(p, here, "exclude", "command line") for p in self.exclude]
        elif trusted and isinstance(table.get("exclude"), list):
            chosen += [(p, base, "exclude", source) for p in table["exclude"]]
        if trusted:
            chosen += [(p, base, "extend-exclude", source) for p in table.get("extend-exclude") or []]
        chosen += [(p, here, "extend-exclude", "command line") for p in self.extend_exclude]
        # a walk never enters an excluded folder; a named file is excluded when it or a folder it is in is
        candidates = _self_and_parents(path) if named else [path]
        for pattern, where, by, origin in chosen:
            if _any_match(pattern, candidates, where):
                return Exclusion(by, pattern, origin)
        if self.exclude is None and not isinstance(table.get("exclude"), list):
            for pattern in DEFAULT_EXCLUDE:
                if _any_match(pattern, candidates, base):
                    return Exclusion(TOOL_FOLDER, pattern)
        respect = self.respect_gitignore
        if respect is None:
            respect = bool(table.get("respect-gitignore", True))
        if respect and self._gitignored(path, is_dir):
            return Exclusion(".gitignore")
        return None

    def security_only(self, path: str, is_dir: bool, named: bool = False) -> Exclusion | None:
        """The pattern of a configuration found beside the files that names ``path`` (its ``exclude`` or
        ``extend-exclude``), or None.  Such a file is not left out: the SC rules alone check it."""
        if self.explicit_config is not None:
            return None
        base, source, table = self._table(path)
        if named and not self._forced(table):
            return None
        patterns = [] if self.exclude is not None else [("exclude", p) for p in table.get("exclude") or []]
        patterns += [("extend-exclude", p) for p in table.get("extend-exclude") or []]
        candidates = _self_and_parents(path) if named else [path]
        for by, pattern in patterns:
            if isinstance(pattern, str) and _any_match(pattern, candidates, base):
                return Exclusion(by, pattern, source, trusted=False)
        return None

    # -- what git tracks ------------------------------------------------------------------------------------------

    def tracked(self, path: str) -> bool:
        """Whether git tracks the file ``path`` (in its index: committed or added).  True too when git
        cannot say (not installed, "dubious ownership"): nothing is left out on a guess."""
        found = self._tracked_at(path)
        if found is None:
            return False
        listing, rel = found
        return listing is None or rel in listing[0]

    def holds_tracked(self, folder: str) -> bool:
        """Whether the folder ``folder`` holds files git tracks (at any depth; True when git cannot say)."""
        if os.path.basename(folder) == ".git":
            return False  # git never tracks its own folder: no need to ask
        found = self._tracked_at(folder)
        if found is None:
            return False
        listing, rel = found
        return listing is None or rel in listing[1]

    def repository_root(self, folder: str) -> Path | None:
        """The root of the git repository ``folder`` is in (the folder holding ``.git``), or None."""
        root = self._root_of(os.path.abspath(folder))
        return Path(root) if root is not None else None

    def _tracked_at(self, path: str) -> tuple[tuple[frozenset[str], frozenset[str]] | None, str] | None:
        """(what git tracks in the repository of ``path``, or None when git cannot say; ``path`` relative to
        its root), or None outside a repository."""
        target = os.path.abspath(path)
        root = self._root_of(os.path.dirname(target))
        if root is None:
            return None
        if root not in self._tracked:
            self._tracked[root] = self._ls_files(root)
        rel = target[len(root) :].lstrip(os.sep).replace(os.sep, "/") or "."
        return self._tracked[root], rel

    def _ls_files(self, root: str) -> tuple[frozenset[str], frozenset[str]] | None:
        """The files git tracks under ``root`` and the folders holding them (``/``-separated, relative),
        or None, with a note, when git cannot say."""
        env = {k: v for k, v in os.environ.items() if k not in _GIT_LOCATION_VARIABLES}
        env.update(GIT_OPTIONAL_LOCKS="0", GIT_TERMINAL_PROMPT="0")
        # core.fsmonitor names a program git runs when it reads the index: never one from the repository's
        # configuration (a folder from elsewhere may carry a .git of its own)
        command = ["git", "-c", "core.fsmonitor=false", "-C", root, "ls-files", "-z"]
        import subprocess  # (here: most checks never ask git)

        try:
            done = subprocess.run(
                command, capture_output=True, env=env, timeout=GIT_TIMEOUT, stdin=subprocess.DEVNULL, check=False
            )
        except FileNotFoundError:
            why = "git is not installed"
        except subprocess.TimeoutExpired:
            why = f"git ls-files took more than {GIT_TIMEOUT:g} s"
        except OSError as exc:
            why = f"git could not be run: {exc.strerror or exc}"
        else:
            if done.returncode == 0:
                files = frozenset(os.fsdecode(p) for p in done.stdout.split(b"\0") if p)
                folders = {"."}
                for name in files:
                    parts = name.split("/")[:-1]
                    for i in range(1, len(parts) + 1):
                        folders.add("/".join(parts[:i]))
                return files, frozenset(folders)
            detail = done.stderr.decode("utf-8", "replace").strip().splitlines()
            why = f"git ls-files failed: {detail[-1] if detail else f'exit {done.returncode}'}"
        self.notes.append(
            f"{root}: cannot tell which files git tracks ({why}): neither .gitignore nor the default tool folders"
            " leave anything out there, every G-code file in it is checked"
        )
        return None

    # -- .gitignore ---------------------------------------------------------------------------------------------

    def _gitignored(self, path: str, is_dir: bool) -> bool:
        """Whether a ``.gitignore`` (or ``.git/info/exclude``) ignores ``path`` or a folder it is in."""
        target = os.path.abspath(path)
        folder = os.path.dirname(target)
        root = self._root_of(folder)
        if root is None:
            return False  # not in a git repository: .gitignore files mean nothing here
        if target == root:
            return False
        return self._folder_ignored(folder, root) or self._decide(target, is_dir, folder, root)

    def _decide(self, target: str, is_dir: bool, folder: str, root: str) -> bool:
        """The deepest decisive pattern of the files that apply in ``folder`` (as git does)."""
        decision: bool | None = None
        for base, spec in self._specs_in(folder, root):
            rel = target[len(base) :].lstrip(os.sep).replace(os.sep, "/")
            said = spec.decide(rel, is_dir)
            if said is not None:
                decision = said
        return bool(decision)

    def _folder_ignored(self, folder: str, root: str) -> bool:
        """Whether ``folder`` or a folder above it (below ``root``) is ignored: git never looks inside an
        ignored folder, so nothing in it can be taken back by a ``!`` pattern.  Cached, folder by folder."""
        chain = []
        at = folder
        while at not in self._ignored_folders and at != root and os.path.dirname(at) != at:
            chain.append(at)
            at = os.path.dirname(at)
        known = self._ignored_folders.get(at, False)
        for at in reversed(chain):
            known = known or self._decide(at, True, os.path.dirname(at), root)
            self._ignored_folders[at] = known
        return known

    def _specs_in(self, folder: str, root: str) -> tuple:
        """(folder, patterns) of every ignore file that applies in ``folder``, the shallowest first."""
        chain = []
        at = folder
        while at not in self._specs and at != root and os.path.dirname(at) != at:
            chain.append(at)
            at = os.path.dirname(at)
        if at not in self._specs:  # the repository's root: .git/info/exclude, then its .gitignore
            found = [(at, self._spec(os.path.join(at, ".git", "info", "exclude")))]
            found.append((at, self._spec(os.path.join(at, ".gitignore"))))
            self._specs[at] = tuple((base, spec) for base, spec in found if spec is not None)
        specs = self._specs[at]
        for at in reversed(chain):
            spec = self._spec(os.path.join(at, ".gitignore"))
            specs = specs + ((at, spec),) if spec is not None else specs
            self._specs[at] = specs
        return specs

    def _root_of(self, folder: str) -> str | None:
        """The repository root (the folder holding ``.git``) at or above ``folder``, or None."""
        return self._roots.root_of(folder)

    def _spec(self, file: str):
        if file not in self._read:
            spec = None
            try:
                with open(file, encoding="utf-8", errors="replace") as fh:
                    lines = fh.read().splitlines()
            except OSError:
                lines = None
            if lines:
                from gclint.gitignore import GitIgnore

                spec = GitIgnore.from_lines(lines)
            self._read[file] = spec
        return self._read[file]


def _display(path: str) -> str:
    """A configuration file's name as the user reads it: relative to the working folder when inside it."""
    absolute, here = os.path.abspath(path), os.getcwd()
    return os.path.relpath(absolute, here) if absolute.startswith(here.rstrip(os.sep) + os.sep) else absolute


def _any_match(pattern: str, candidates: list[str], base: str) -> bool:
    here = os.getcwd()
    return any(globs.matches(pattern, _relative(c, base, here)) for c in candidates)


@lru_cache(maxsize=64)
def _relative(path: str, base: str, here: str) -> str:
    """``globs.relative`` (``path`` read from the folder ``here``), once per path and folder: a path is
    matched against every pattern."""
    return globs.relative(os.path.join(here, path), base)


def _self_and_parents(path: str) -> list[str]:
    """``path`` and the folders it is in, up to the file system's root (absolute paths)."""
    absolute = Path(os.path.abspath(path))
    return [str(absolute), *(str(p) for p in absolute.parents)]
