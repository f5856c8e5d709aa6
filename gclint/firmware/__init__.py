"""Firmware inventories: the codes each real firmware documents, as data (each module names the firmware source it was
read from, by repository and commit; docs/sources.md, Firmware inventories).

A dialect (gclint/dialects/) says how a family of files is read and checked; an inventory says which
codes one firmware accepts.  Prusa (Buddy and MK3), Bambu, Klipper and FABlin (FABtotum) read Marlin-flavour
files: their inventories are *flavours* of the Marlin dialect.  gclint.context decides a file's flavour from its
slicer settings and content (``Context.flavor``), and DL001 does not report a code the flavour's firmware
documents.  The RepRapFirmware, LinuxCNC and Smoothieware inventories feed the tables of the dialects built
on them.

Adding a firmware is adding one module that builds a ``Firmware`` and listing it in ``_ALL``.
"""

from __future__ import annotations

from collections.abc import Iterable

from gclint.firmware.bambu import BAMBU
from gclint.firmware.base import Firmware, code_set, normal_code
from gclint.firmware.fablin import FABLIN
from gclint.firmware.klipper import KLIPPER
from gclint.firmware.linuxcnc import LINUXCNC
from gclint.firmware.machinekit_fdm import MACHINEKIT_FDM
from gclint.firmware.prusa_buddy import PRUSA_BUDDY
from gclint.firmware.prusa_mk3 import PRUSA_MK3
from gclint.firmware.reprap_2015 import REPRAP_2015
from gclint.firmware.reprapfirmware import REPRAPFIRMWARE
from gclint.firmware.smoothieware import SMOOTHIEWARE

__all__ = ["Firmware", "all_firmware", "code_set", "documenting", "flavors_of", "get", "normal_code"]

_ALL: tuple[Firmware, ...] = (
    PRUSA_BUDDY,
    PRUSA_MK3,
    BAMBU,
    KLIPPER,
    FABLIN,
    REPRAP_2015,
    REPRAPFIRMWARE,
    LINUXCNC,
    MACHINEKIT_FDM,
    SMOOTHIEWARE,
)
_BY_NAME = {f.name: f for f in _ALL}


def all_firmware() -> tuple[Firmware, ...]:
    return _ALL


def get(name: str) -> Firmware:
    """The firmware called ``name`` (KeyError if there is none)."""
    return _BY_NAME[name]


def flavors_of(dialect: str) -> tuple[Firmware, ...]:
    """The flavours of ``dialect``: firmware whose files it reads and that a file's marks can select."""
    return tuple(f for f in _ALL if f.flavor and f.dialect == dialect)


def documenting(code: str, dialects: Iterable[str] | None = None) -> tuple[Firmware, ...]:
    """Every firmware whose inventory has ``code`` (read in one of ``dialects``, when given)."""
    wanted = None if dialects is None else set(dialects)
    return tuple(f for f in _ALL if (wanted is None or f.dialect in wanted) and f.knows(code))
