"""What the slicer wrote about a job besides the moves: its settings (``; key = value``, the config block at the top
or the end of the file) and its own time estimate.

Where each slicer writes them (as the slicers' own output shows: the test corpus's marlin folder):

* PrusaSlicer, SuperSlicer, OrcaSlicer and BambuStudio: every setting as ``; key = value`` (a list of values per
  mode or extruder, comma-separated: the first is the normal mode's); the estimate as
  ``; estimated printing time (normal mode) = 1h 2m 3s`` (PrusaSlicer, near the end; OrcaSlicer and BambuStudio
  for some printers, in the header), or BambuStudio's ``; model printing time: 1h 57m 37s; total estimated time:
  2h 4m 35s`` (the total is the whole file's: the model's time leaves out the start sequence).
* Cura: ``;TIME:3485`` (seconds; Griffin headers ``;PRINT.TIME:480``); Cura legacy ``;Print time: 37 minutes``
  (the FABtotum fork) or ``;Print time:     0:42`` (hours:minutes).
* ideaMaker: ``;Print Time: 811`` (seconds).  Simplify3D: ``;   Build time: 1 hour 50 minutes``.  KISSlicer:
  ``; Estimated Build Time:   35.09 minutes``.
"""

from __future__ import annotations

import re

_SETTING = re.compile(r"(?m)^;[ \t]*([a-z][a-z0-9_]*)[ \t]*=[ \t]*(.*?)[ \t]*\r?$")
# Cura's settings the user changed: a JSON text cut into ";SETTING_3 " lines at the end of the job, each profile an
# INI text whose line breaks are written "\\n"
_CURA_LINE = re.compile(r"(?m)^;SETTING_3 (.*?)\r?$")
_CURA_SETTING = re.compile(r"(?:^|\\\\n)([a-z][a-z0-9_]*) = ([^\\\n\"]*)")


def slicer_settings(*texts: str | None) -> dict[str, str]:
    """The ``; key = value`` settings found in ``texts`` (the file's head and tail), then Cura's ``;SETTING_3``
    ones; the first found wins."""
    found: dict[str, str] = {}
    for text in texts:
        if not text:
            continue
        for m in _SETTING.finditer(text):
            found.setdefault(m.group(1), m.group(2))
    for text in texts:
        if text and ";SETTING_3 " in text:
            joined = "".join(m.group(1) for m in _CURA_LINE.finditer(text))
            for m in _CURA_SETTING.finditer(joined):
                found.setdefault(m.group(1), m.group(2).strip())
    return found


def _hms(text: str) -> float | None:
    parts = re.findall(r"(\d+(?:\.\d+)?)\s*([dhms])", text)
    if not parts:
        return None
    scale = {"d": 86400, "h": 3600, "m": 60, "s": 1}
    return sum(float(n) * scale[u] for n, u in parts)


def _minutes(text: str) -> float:
    return float(text) * 60


def _hours_minutes(hours: str, minutes: str) -> float:
    return float(hours) * 3600 + float(minutes) * 60


# (pattern, how its groups become seconds, the slicer's words for it); the first that matches is the estimate
_ESTIMATES: tuple[tuple[re.Pattern[str], object, str], ...] = (
    (
        re.compile(r"(?m)^; estimated printing time \(normal mode\) = ([\dhmsd ]+?)\s*$"),
        _hms,
        "estimated printing time",
    ),
    (re.compile(r"(?m)^; .*total estimated time: ([\dhmsd ]+?)\s*$"), _hms, "total estimated time"),
    (re.compile(r"(?m)^;TIME:(\d+(?:\.\d+)?)\s*$"), float, ";TIME"),
    (re.compile(r"(?m)^;PRINT\.TIME:(\d+(?:\.\d+)?)\s*$"), float, ";PRINT.TIME"),
    (re.compile(r"(?m)^;Print Time: (\d+(?:\.\d+)?)\s*$"), float, "Print Time"),
    (re.compile(r"(?m)^;\s*Print time: (\d+(?:\.\d+)?) minutes?\s*$"), _minutes, "Print time"),
    (re.compile(r"(?m)^;\s*Print time:\s+(\d+):(\d\d)\s*$"), _hours_minutes, "Print time"),
    (re.compile(r"(?m)^;\s+Build time: (\d+) hours? (\d+) minutes?\s*$"), _hours_minutes, "Build time"),
    (re.compile(r"(?m)^; Estimated Build Time:\s+(\d+(?:\.\d+)?) minutes\s*$"), _minutes, "Estimated Build Time"),
)


def slicer_estimate(*texts: str | None) -> tuple[float, str] | None:
    """The slicer's own estimate of the print time in ``texts`` (the file's head and tail), in seconds, with the
    words it is written with; None when the job states none."""
    for pattern, convert, words in _ESTIMATES:
        for text in texts:
            if not text:
                continue
            m = pattern.search(text)
            if m is not None:
                seconds = convert(*m.groups())  # type: ignore[operator]
                if seconds is not None:
                    return float(seconds), words
    return None
