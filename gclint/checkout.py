"""Where a checkout begins: the repository root above a folder (the folder holding ``.git``, a folder or a
worktree's file), found with one ``lstat`` per folder not asked about before, so that a walk through a
tree 1,500 folders deep stays linear."""

from __future__ import annotations

import os

_UNKNOWN = object()


class Roots:
    """Repository roots, remembered folder by folder (one per run: a checkout may change between runs)."""

    def __init__(self) -> None:
        self._known: dict[str, str | None] = {}

    def root_of(self, folder: str) -> str | None:
        """The repository root at or above the absolute folder ``folder``, or None."""
        chain = []
        at = folder
        found: object = _UNKNOWN
        while True:
            known = self._known.get(at, _UNKNOWN)
            if known is not _UNKNOWN:
                found = known
                break
            chain.append(at)
            if os.path.lexists(os.path.join(at, ".git")):
                found = at
                break
            parent = os.path.dirname(at)
            if parent == at:
                found = None
                break
            at = parent
        for at in chain:
            self._known[at] = found  # type: ignore[assignment]
        return found  # type: ignore[return-value]


def inside(path: str, folder: str) -> bool:
    """Whether the path ``path`` is ``folder`` or in it (both absolute, compared as written)."""
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


def escapes(folder: str) -> str | None:
    """Where ``folder`` really is, when it is named inside the checkout of the working folder (its
    repository, else the working folder itself) but a symbolic link on the way takes it outside: a
    committed ``.gclint_cache -> /home/runner/.ssh`` must not make gclint write there.  None otherwise
    (a folder named outside the checkout is the user's own choice)."""
    here = os.getcwd()
    checkout = Roots().root_of(here) or here
    given = os.path.abspath(folder)
    if not inside(given, checkout):
        return None
    real = os.path.realpath(given)
    return None if inside(real, os.path.realpath(checkout)) else real
