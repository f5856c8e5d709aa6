"""What the slicer and the file's name say: header patterns (in the head, or in the settings slicers write at
the end of the file), ``SLIC3R_GCODE_FLAVOR``, and the extension.  Weak evidence: gclint.context.score
weighs it below content (a ``;FLAVOR:Marlin`` kept from the source does not outweigh a translated job's
``M229 E1 D1``)."""

from __future__ import annotations

from gclint.dialects.base import Detection, HeadScan

# PrusaSlicer/SuperSlicer/OrcaSlicer gcode_flavor values (SLIC3R_GCODE_FLAVOR, "; gcode_flavor = ...").
SLICER_FLAVORS = {
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
ENV_WEIGHT = 10  # SLIC3R_GCODE_FLAVOR weighs as a ";FLAVOR:" line: the slicer's own word
AT_END = " (in the settings at the end of the file)"
GENERIC_EXTENSIONS = (".gcode", ".gco")  # every firmware's files: they say nothing of the dialect


def slicer_flavor(name: str) -> str | None:
    """The dialect name for a slicer's gcode_flavor value, or None."""
    return SLICER_FLAVORS.get(name.strip().lower())


def found(detection: Detection, scan: HeadScan, tail: HeadScan | None) -> list[tuple[int, str]]:
    """(weight, text) of each of ``detection``'s patterns found in the head, else in the tail."""
    out = []
    for pattern, weight in detection.patterns:
        text = scan.found(pattern)
        if text is None and tail is not None and (text := tail.found(pattern)) is not None:
            text += AT_END
        if text is not None:
            out.append((weight, text))
    return out


def extension(path: str) -> str:
    """``path``'s extension (``.ngc``), or ``""``."""
    dot = path.rfind(".")
    return path[dot:] if dot > path.replace("\\", "/").rfind("/") else ""


def tells(detection: Detection, path: str) -> bool:
    """Whether ``path``'s extension is one of ``detection``'s and says something (``.gcode`` does not)."""
    return detection.has_extension(path) and not path.lower().endswith(GENERIC_EXTENSIONS)


__all__ = ["SLICER_FLAVORS", "ENV_WEIGHT", "AT_END", "slicer_flavor", "found", "extension", "tells"]
