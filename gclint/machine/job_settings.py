"""What a job's own slicer settings say about the machine it was sliced for.

PrusaSlicer, SuperSlicer, OrcaSlicer and BambuStudio write their settings into the job as ``; key = value``
comments (PrusaSlicer and Orca at the end of the file, BambuStudio in its head).  Read here: whether the
printer has one nozzle for several materials (``single_extruder_multi_material = 1``: an MMU or an AMS, where a
tool change is a filament change on the same nozzle and heater), how many extruders the job was sliced for
(one ``nozzle_diameter`` value each), and the bed's shape (``bed_shape`` / ``printable_area``).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

_SETTING = re.compile(r"(?m)^;[ \t]*([a-z_]+)[ \t]*=[ \t]*([^\r\n]*)$")
_WANTED = frozenset({"single_extruder_multi_material", "nozzle_diameter", "bed_shape", "printable_area"})


@dataclass(frozen=True)
class JobSettings:
    single_nozzle: bool = False  # several materials through one nozzle (its tools share one heater)
    extruders: int | None = None  # the extruders the job was sliced for
    bed: tuple[float, float, float, float] | None = None  # x0, y0, x1, y1


def read_settings(*texts: str | None) -> JobSettings:
    """The settings in ``texts`` (the job's head and tail); the first value of each key counts."""
    found: dict[str, str] = {}
    for text in texts:
        if not text or "=" not in text:
            continue
        for m in _SETTING.finditer(text):
            key = m.group(1)
            if key in _WANTED and key not in found:
                found[key] = m.group(2).strip()
    nozzles = found.get("nozzle_diameter")
    return JobSettings(
        single_nozzle=found.get("single_extruder_multi_material", "0") == "1",
        extruders=len(nozzles.split(",")) if nozzles else None,
        bed=_bed(found.get("bed_shape") or found.get("printable_area")),
    )


def _bed(value: str | None) -> tuple[float, float, float, float] | None:
    """``0x0,180x0,180x180,0x180`` -> (0, 0, 180, 180)."""
    if not value:
        return None
    points = []
    for corner in value.split(","):
        x, _, y = corner.strip().partition("x")
        try:
            points.append((float(x), float(y)))
        except ValueError:
            return None
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    return min(xs), min(ys), max(xs), max(ys)
