"""Which paths a check leaves out, as ruff does: ``exclude`` (replaces the default folders),
``extend-exclude`` (adds to them), both globs relative to the configuration file that names them
(gclint.globs), the files ``.gitignore`` ignores (``respect-gitignore``, on by default; the ``.gitignore``
files of the folders up to the repository's root and ``.git/info/exclude``), and ``force-exclude`` to
apply it all to files named on the command line too (what pre-commit and editors pass).

Unlike ruff, a file that git tracks is never left out because of ``.gitignore`` or because it is in a tool
folder (``node_modules``, ``venv``, ...): a ``.gitignore`` is about untracked files, and a job committed
there is a job a CI gate must see.  Which files are tracked is asked of git once per repository
(``git ls-files``), only when something would be left out for those reasons; without git, the rules apply
to every file and the walk says what they left out.  What the user's own ``exclude``/``extend-exclude``
patterns name is left out, tracked or not.  ``LeftOut`` records each file left out, for the notes."""

from __future__ import annotations

import os
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from gclint import globs
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

    @property
    def chosen(self) -> bool:
        """The user's own patterns: they leave out tracked files too."""
        return self.by in ("exclude", "extend-exclude")

    def __str__(self) -> str:
        if self.by == ".gitignore":
            return "ignored by .gitignore"
        if self.by == TOOL_FOLDER:
            return f"in a tool folder ({self.pattern!r}, a default exclude)"
        return f"excluded by {self.by} {self.pattern!r}" + (f" ({self.source})" if self.source else "")


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


@dataclass
class Excluder:
    """Decides, path by path, whether the check leaves it out, and says why."""

    exclude: list[str] | None = None  # --exclude (replaces the configuration's and the defaults)
    extend_exclude: list[str] = field(default_factory=list)  # --extend-exclude
    force: bool | None = None  # --force-exclude (None: the configuration's, else off)
    respect_gitignore: bool | None = None  # --[no-]respect-gitignore (None: the configuration's, else on)
    explicit_config: str | None = None
    notes: list[str] = field(default_factory=list)  # what the user should know (git could not answer)
    _ignores: dict = field(default_factory=dict)  # .gitignore specs and repository roots, per path
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

    def why(self, path: str, is_dir: bool, named: bool = False) -> Exclusion | None:
        """Which rule matches ``path``, if any: the user's patterns first, then the default tool folders,
        then ``.gitignore`` (whether git tracks it is not asked here)."""
        try:
            config_path, table = config_for(path, self.explicit_config)
        except ConfigError:
            config_path, table = None, {}
        if named and not (self.force if self.force is not None else bool(table.get("force-exclude", False))):
            return None
        base = os.path.dirname(os.path.abspath(config_path)) if config_path is not None else os.getcwd()
        source = os.path.basename(config_path) if config_path is not None else ""
        chosen: list[tuple[str, str, str, str]] = []  # (pattern, relative to, by, source)
        defaults: list[str] = []
        if self.exclude is not None:
            chosen += [(p, os.getcwd(), "exclude", "command line") for p in self.exclude]
        elif isinstance(table.get("exclude"), list):
            chosen += [(p, base, "exclude", source) for p in table["exclude"]]
        else:
            defaults = list(DEFAULT_EXCLUDE)
        chosen += [(p, base, "extend-exclude", source) for p in table.get("extend-exclude") or []]
        chosen += [(p, base, "extend-exclude", "command line") for p in self.extend_exclude]
        # a walk never enters an excluded folder; a named file is excluded when it or a folder it is in is
        candidates = _self_and_parents(path) if named else [path]
        for pattern, where, by, origin in chosen:
            if any(globs.matches(pattern, globs.relative(c, where)) for c in candidates):
                return Exclusion(by, pattern, origin)
        for pattern in defaults:
            if any(globs.matches(pattern, globs.relative(c, base)) for c in candidates):
                return Exclusion(TOOL_FOLDER, pattern)
        respect = self.respect_gitignore
        if respect is None:
            respect = bool(table.get("respect-gitignore", True))
        if respect and self._gitignored(path, is_dir):
            return Exclusion(".gitignore")
        return None

    # -- what git tracks ------------------------------------------------------------------------------------------

    def tracked(self, path: str) -> bool:
        """Whether git tracks the file ``path`` (in its index: committed or added)."""
        found = self._tracked_at(path)
        return found is not None and found[1] in found[0][0]

    def holds_tracked(self, folder: str) -> bool:
        """Whether the folder ``folder`` holds files git tracks (at any depth)."""
        if os.path.basename(folder) == ".git":
            return False  # git never tracks its own folder: no need to ask
        found = self._tracked_at(folder)
        return found is not None and found[1] in found[0][1]

    def repository_root(self, folder: str) -> Path | None:
        """The root of the git repository ``folder`` is in (the folder holding ``.git``), or None."""
        return self._root_of(Path(os.path.abspath(folder)))

    def _tracked_at(self, path: str) -> tuple[tuple[frozenset[str], frozenset[str]], str] | None:
        target = Path(os.path.abspath(path))
        root = self._root_of(target.parent)
        if root is None:
            return None
        if root not in self._tracked:
            self._tracked[root] = self._ls_files(root)
        listing = self._tracked[root]
        return None if listing is None else (listing, target.relative_to(root).as_posix())

    def _ls_files(self, root: Path) -> tuple[frozenset[str], frozenset[str]] | None:
        """The files git tracks under ``root`` and the folders holding them (``/``-separated, relative),
        or None, with a note, when git cannot say."""
        env = {k: v for k, v in os.environ.items() if k not in _GIT_LOCATION_VARIABLES}
        env.update(GIT_OPTIONAL_LOCKS="0", GIT_TERMINAL_PROMPT="0")
        # core.fsmonitor names a program git runs when it reads the index: never one from the repository's
        # configuration (a folder from elsewhere may carry a .git of its own)
        command = ["git", "-c", "core.fsmonitor=false", "-C", str(root), "ls-files", "-z"]
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
            f"{root}: cannot tell which files git tracks ({why}): .gitignore and the default tool folders"
            " leave out tracked files too"
        )
        return None

    # -- .gitignore ---------------------------------------------------------------------------------------------

    def _gitignored(self, path: str, is_dir: bool) -> bool:
        target = Path(os.path.abspath(path))
        root = self._root_of(target.parent)
        if root is None:
            return False  # not in a git repository: .gitignore files mean nothing here
        folders = [target.parent, *(f for f in target.parent.parents if f.is_relative_to(root))]
        decision: bool | None = None
        root = folders[-1]
        checks = [(root, root / ".git" / "info" / "exclude")] + [(f, f / ".gitignore") for f in reversed(folders)]
        for folder, file in checks:  # the deepest decisive match wins, as in git
            spec = self._spec(file)
            if spec is None:
                continue
            rel = target.relative_to(folder).as_posix() + ("/" if is_dir else "")
            result = spec.check_file(rel)  # type: ignore[attr-defined]
            if result.include is not None:
                decision = result.include
        return bool(decision)

    def _root_of(self, folder: Path) -> Path | None:
        """The repository root (the folder holding ``.git``) at or above ``folder``, or None."""
        key = ("root", folder)
        if key not in self._ignores:
            parent = folder.parent
            if (folder / ".git").exists():
                found: Path | None = folder
            elif parent == folder:
                found = None
            else:
                found = self._root_of(parent)
            self._ignores[key] = found  # type: ignore[index]
        return self._ignores[key]  # type: ignore[index,return-value]

    def _spec(self, file: Path):
        if file not in self._ignores:
            spec = None
            try:
                lines = file.read_text(encoding="utf-8", errors="replace").splitlines()
            except OSError:
                lines = None
            if lines:
                import pathspec

                spec = pathspec.GitIgnoreSpec.from_lines(lines)
            self._ignores[file] = spec
        return self._ignores[file]


def _self_and_parents(path: str) -> list[str]:
    """``path`` and the folders it is in, up to the file system's root (absolute paths)."""
    absolute = Path(os.path.abspath(path))
    return [str(absolute), *(str(p) for p in absolute.parents)]
