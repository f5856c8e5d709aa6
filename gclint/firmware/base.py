"""What a firmware inventory is: the codes one real firmware documents, as data, and the marks in a file
(slicer settings, commands) that say the file was written for it.

An inventory is a set of normalised codes (``M862.3``, ``G28``) and of command words that are not G/M
codes (Klipper's ``SET_FAN_SPEED``, Prusa's ``PRUSA``).  Each module cites the section of
firmware source (repository and commit) it was taken from, and lists nothing that section does not list.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from gclint.dialects.base import Detection
from gclint.syntax.nodes import normalize_code


@dataclass(frozen=True)
class Firmware:
    """One firmware's inventory.

    ``dialect`` is the dialect gclint reads the firmware's files in.  A ``flavor`` is a firmware whose
    files are that dialect's with codes of its own (Prusa, Bambu, Klipper and FABlin read Marlin-flavour files):
    ``detection`` holds the marks gclint.context weighs to decide it, slicer settings in the head or at
    the end of the file (``patterns``) and commands in the content (``clues``).  The other inventories
    (RepRapFirmware, LinuxCNC, Smoothieware) are what their dialect's table is built from.
    """

    name: str
    title: str
    codes: frozenset[str]
    dialect: str
    words: frozenset[str] = frozenset()  # command words that are not G/M codes, upper case
    flavor: bool = False
    detection: Detection = Detection()
    source: str = ""
    marks_dialect: bool = True  # its codes count as the dialect's when gclint.context weighs a file
    plural: bool = False  # the title names several firmwares ("RepRap firmwares of ...": "have it")
    extended_commands: bool = False  # runs Klipper-style NAME KEY=VALUE commands (and macros named so)
    # what this firmware does otherwise than its dialect says (gclint.dialects.semantics field -> value): a file
    # read as written for it is read with these (``gclint.dialects.reading``)
    semantics: Mapping[str, object] = field(default_factory=dict)

    def knows(self, code: str) -> bool:
        """Whether the firmware documents ``code`` (a normalised code, or a command word in any case)."""
        return code in self.codes or code.upper() in self.words


_CODE = re.compile(r"([GMTDgmtd])([-+]?\d+(?:\.\d+)?)")
_WORD = re.compile(r"[A-Za-z_][\w.-]*")


def normal_code(text: str) -> str | None:
    """A code or command word as a file's command is looked up: ``"m0900"`` -> ``"M900"``, ``"my_macro"``
    -> ``"MY_MACRO"``; None when ``text`` is neither (``"M9 00"``, ``"=x"``)."""
    text = text.strip()
    m = _CODE.fullmatch(text)
    if m is not None:
        return normalize_code(m.group(1), m.group(2))
    return text.upper() if _WORD.fullmatch(text) else None


def code_set(*groups: str | Iterable[str]) -> frozenset[str]:
    """Normalised codes from space-separated strings or lists: ``"G28.140 M0862.3"`` -> ``{G28.14, M862.3}``.

    The parser normalises a code the same way (``gclint.syntax.nodes.normalize_code``: trailing zeros of
    a sub-code dropped), so the inventory's entries are the codes a file's commands are looked up as.
    """
    out: set[str] = set()
    for group in groups:
        for token in group.split() if isinstance(group, str) else group:
            out.add(normalize_code(token[0], token[1:]))
    return frozenset(out)
