"""The codes a LinuxCNC or Machinekit machine defines for itself, read from its INI file beside the job.

LinuxCNC runs a G or M code that its ``[RS274NGC]`` section remaps (``REMAP=M206 modalgroup=10 argspec=P
ngc=fancontrol``: docs/src/remap/remap.adoc, "Remapping codes") as the subroutine it names; without that line
the interpreter stops at the code ("Unknown M code used").  So a job beside (or below) such an INI file uses
codes its machine has, and DL001 does not report them (M100-M199, the user M-codes that run the program of
that name, are known to the dialect already: gclint.dialects.machinekit).

The INI is found as a configuration is: in the job's folder, else a parent, up to the repository root (outside a
repository, the job's folder and the one above it); the nearest folder holding a LinuxCNC INI (one with an
``[RS274NGC]`` section) wins, and every LinuxCNC INI there counts (a folder of machine variants).  The file
comes with the jobs, so it is read as data, bounded, never through a symbolic link, and it only tells DL001
which codes exist: it reaches no security rule.
"""

from __future__ import annotations

import os
import re

from gclint.checkout import Roots
from gclint.firmware import normal_code

MAX_BYTES = 1 << 20  # a LinuxCNC INI is a few KB
MAX_FILES = 16  # INI files read in one folder
MAX_CODES = 1000
_SECTION = re.compile(r"\s*\[([^\]\r\n]*)\]")
_REMAP = re.compile(r"\s*REMAP\s*=\s*([GM][0-9]{1,4}(?:\.[0-9]{1,3})?)(?![0-9.])", re.IGNORECASE)

_FOLDERS: dict[str, tuple[tuple[str, ...], tuple[str, ...]] | None] = {}  # folder -> (codes, INI files) or None
_ROOTS = Roots()


def clear() -> None:
    """Forget what was read (a run starts afresh: the INI files may have changed)."""
    _FOLDERS.clear()
    global _ROOTS
    _ROOTS = Roots()


def machine_codes(path: str) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The codes the machine configuration of the job ``path`` remaps, and the INI files that say so."""
    if path == "-":
        return (), ()
    folder = os.path.dirname(os.path.abspath(path))
    top = _ROOTS.root_of(folder)
    levels = None if top is not None else 2
    at = folder
    while True:
        found = _folder(at)
        if found is not None:
            return found
        parent = os.path.dirname(at)
        if levels is not None:
            levels -= 1
            if levels <= 0:
                break
        if parent == at or at == top:
            break
        at = parent
    return (), ()


def _folder(folder: str) -> tuple[tuple[str, ...], tuple[str, ...]] | None:
    if folder in _FOLDERS:
        return _FOLDERS[folder]
    answer = None
    try:
        with os.scandir(folder) as listing:
            names = sorted(
                e.name for e in listing if e.name.lower().endswith(".ini") and e.is_file(follow_symlinks=False)
            )
    except OSError:
        names = []
    codes: list[str] = []
    files: list[str] = []
    for name in names[:MAX_FILES]:
        remapped = _remaps(os.path.join(folder, name))
        if remapped is not None:
            files.append(os.path.join(folder, name))
            codes.extend(remapped)
    if files:
        answer = (tuple(dict.fromkeys(codes))[:MAX_CODES], tuple(files))
    _FOLDERS[folder] = answer
    return answer


def _remaps(path: str) -> list[str] | None:
    """The codes ``path`` remaps in its [RS274NGC] section; None when it is no LinuxCNC INI."""
    try:
        with open(path, "rb") as fh:
            data = fh.read(MAX_BYTES + 1)
    except OSError:
        return None
    if len(data) > MAX_BYTES:
        return None
    text = data.decode("utf-8", "replace")
    section = None
    linuxcnc = False
    codes: list[str] = []
    for line in text.splitlines():
        m = _SECTION.match(line)
        if m is not None:
            section = m.group(1).strip().upper()
            linuxcnc = linuxcnc or section == "RS274NGC"
            continue
        if section != "RS274NGC":
            continue
        m = _REMAP.match(line)
        if m is not None:
            code = normal_code(m.group(1))
            if code is not None:
                codes.append(code)
    return codes if linuxcnc else None
