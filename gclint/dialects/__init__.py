"""The dialect registry: look dialects up by name or alias, and detect a file's dialect.

Adding a dialect is adding one module that builds a ``Dialect`` and listing it in ``_ALL``.
"""

from __future__ import annotations

import re

from gclint.dialects.base import Code, Dialect, HeadScan, Param
from gclint.dialects.carvera import CARVERA
from gclint.dialects.hyrel import HYREL_V4, HYREL_V5
from gclint.dialects.machinekit import MACHINEKIT
from gclint.dialects.marlin import MARLIN
from gclint.dialects.reprap import REPRAP

__all__ = ["Code", "Dialect", "Param", "all_dialects", "detect", "get", "names", "UnknownDialect", "DEFAULT"]

_ALL: tuple[Dialect, ...] = (HYREL_V5, HYREL_V4, MARLIN, REPRAP, MACHINEKIT, CARVERA)
_BY_NAME: dict[str, Dialect] = {}
for _d in _ALL:
    _BY_NAME[_d.name] = _d
    for _alias in _d.aliases:
        _BY_NAME[_alias] = _d

DEFAULT = HYREL_V5
_DIRECTIVE = re.compile(r"(?im)^[^\n]*[;(]\s*gclint:\s*dialect\s*=\s*([\w.-]+)")


class UnknownDialect(ValueError):
    pass


def all_dialects() -> tuple[Dialect, ...]:
    return _ALL


def names() -> list[str]:
    """The dialect names accepted on the command line (aliases included)."""
    return sorted(_BY_NAME)


def get(name: str) -> Dialect:
    """The dialect called ``name`` (case-insensitive; aliases such as ``rrf`` and ``hyrel-v5`` work)."""
    dialect = _BY_NAME.get(name.strip().lower())
    if dialect is None:
        known = ", ".join(d.name for d in _ALL)
        raise UnknownDialect(f"unknown dialect {name!r} (known: {known}, auto)")
    return dialect


def detect(head: str, path: str = "", env_flavor: str | None = None) -> tuple[Dialect, str]:
    """Guess the dialect of a file from its first lines; returns the dialect and why.

    Order: a ``; gclint: dialect=NAME`` directive, then a slicer flavour from the environment
    (``SLIC3R_GCODE_FLAVOR``), then the best-scoring header patterns, else ``hyrel``.
    """
    scan = HeadScan(head)
    m = _DIRECTIVE.search(head) if "gclint" in scan.lowered else None
    if m:
        try:
            return get(m.group(1)), f"'gclint: dialect={m.group(1)}' directive"
        except UnknownDialect:
            pass
    if env_flavor:
        flavor = env_flavor.strip().lower()
        mapped = _SLICER_FLAVORS.get(flavor)
        if mapped:
            return get(mapped), f"slicer flavour {env_flavor!r}"
    best, best_score = DEFAULT, 0
    for dialect in _ALL:
        score = dialect.detection.score(scan, path)
        if score > best_score:
            best, best_score = dialect, score
    if best_score == 0:
        return DEFAULT, "no dialect marks found; default"
    return best, "file header"


# PrusaSlicer/SuperSlicer/OrcaSlicer gcode_flavor values (SLIC3R_GCODE_FLAVOR, "; gcode_flavor = ...").
_SLICER_FLAVORS = {
    "marlin": "marlin",
    "marlin2": "marlin",
    "marlinlegacy": "marlin",
    "reprap": "marlin",  # "RepRap/Sprinter": Marlin-like
    "repetier": "marlin",
    "teacup": "marlin",
    "makerware": "marlin",
    "sailfish": "marlin",
    "klipper": "marlin",
    "smoothie": "marlin",
    "sprinter": "marlin",
    "no-extrusion": "marlin",
    "mach3": "marlin",
    "reprapfirmware": "reprap",
    "machinekit": "machinekit",
    "hyrel": "hyrel",
}


def slicer_flavor(name: str) -> Dialect | None:
    """The dialect for a slicer's gcode_flavor value, or None."""
    mapped = _SLICER_FLAVORS.get(name.strip().lower())
    return get(mapped) if mapped else None
