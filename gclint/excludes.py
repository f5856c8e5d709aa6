"""Which paths a check leaves out, as ruff does: ``exclude`` (replaces the default folders),
``extend-exclude`` (adds to them), both globs relative to the configuration file that names them
(gclint.globs), the files ``.gitignore`` ignores (``respect-gitignore``, on by default; the ``.gitignore``
files of the folders up to the repository's root and ``.git/info/exclude``), and ``force-exclude`` to
apply it all to files named on the command line too (what pre-commit and editors pass)."""

from __future__ import annotations

import os
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


@dataclass
class Excluder:
    """Decides, path by path, whether the check leaves it out, and says why."""

    exclude: list[str] | None = None  # --exclude (replaces the configuration's and the defaults)
    extend_exclude: list[str] = field(default_factory=list)  # --extend-exclude
    force: bool | None = None  # --force-exclude (None: the configuration's, else off)
    respect_gitignore: bool | None = None  # --[no-]respect-gitignore (None: the configuration's, else on)
    explicit_config: str | None = None
    _ignores: dict = field(default_factory=dict)  # .gitignore specs and repository roots, per path

    def reason(self, path: str, is_dir: bool, named: bool = False) -> str | None:
        """Why ``path`` is left out, or None.  ``named``: given on the command line (then only with
        force-exclude)."""
        try:
            config_path, table = config_for(path, self.explicit_config)
        except ConfigError:
            config_path, table = None, {}
        if named and not (self.force if self.force is not None else bool(table.get("force-exclude", False))):
            return None
        base = os.path.dirname(os.path.abspath(config_path)) if config_path is not None else os.getcwd()
        if self.exclude is not None:
            patterns, where = list(self.exclude), os.getcwd()
        else:
            patterns = list(table["exclude"]) if isinstance(table.get("exclude"), list) else list(DEFAULT_EXCLUDE)
            where = base
        extend = [*(table.get("extend-exclude") or []), *self.extend_exclude]
        # a walk never enters an excluded folder; a named file is excluded when it or a folder it is in is
        for candidate in _self_and_parents(path) if named else (path,):
            for pattern in patterns:
                if globs.matches(pattern, globs.relative(candidate, where)):
                    return f"excluded by {pattern!r}"
            for pattern in extend:
                if globs.matches(pattern, globs.relative(candidate, base)):
                    return f"excluded by {pattern!r}"
        respect = self.respect_gitignore
        if respect is None:
            respect = bool(table.get("respect-gitignore", True))
        if respect and self._gitignored(path, is_dir):
            return "ignored by .gitignore"
        return None

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
