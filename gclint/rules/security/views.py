"""The line as each firmware reads it: the texts a firmware may read for a line that gclint parses as written."""

from __future__ import annotations

import re
import threading

from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line
from gclint.textsafe import FORMAT_CHARACTERS

# -- the line as each firmware reads it ----------------------------------------------------------------------
#
# gclint parses the line as it is written; firmwares edit it first.  ``firmware_views`` gives the other texts a
# firmware may read for a line, and every SC rule also reads each of them (``_SecurityRule.check_view``,
# called by the engine for lines ``on_line_matching`` finds), reporting on the line itself with the view named.

# Views are read for the first 100,000 characters of a line (the grammar parses no longer line either:
# syntax/parse.py), so that a long line costs linear time and bounded memory.
VIEW_LIMIT = 100_000

# C0 control characters other than tab, and DEL (the line breaks end the line before a rule sees it).
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f]")
# A line some firmware reads differently from gclint: a character other than printable ASCII and tab, or
# an M code after the first two characters of its code (Smoothieware splits the line there; no SC rule
# listens to a G code).
# (Multi-line and within a line, for the engine's runs of comment lines: rules.base.Rule.on_line_matching.)
_VIEW_TRIGGER = re.compile("(?m)[^\t\n\r\x20-\x7e]|^[^;(\n\r]{2}[^;(\n\r]*?M[ \t]*+[0-9]")
# Smoothieware's GcodeDispatch: comments start at the first ";" or "(", and the rest is cut before each "G"
# and "M" from its third character on ("find_first_of("GM", 2)"); M117 and M1000 take the rest of the line.
_SMOOTHIE_COMMENT = re.compile("[;(]")
_SMOOTHIE_SPLIT = re.compile("[GM]")
_SMOOTHIE_CODE = re.compile("M[ \t]*+[0-9]")  # (the segments the SC rules listen to: M codes)
_SMOOTHIE_WHOLE = re.compile("M0*+(?:117|1000)(?![0-9])")
_KLIPPER_COMMENT = ";"

MARLIN_VIEW = "read as Marlin reads backspaces (src/gcode/queue.cpp process_stream_char)"
TRIMMED_VIEW = "read trimmed as Klipper trims it (Python's str.strip() drops these spaces and controls)"
KLIPPER_VIEW = 'read as Klipper reads it (klippy/gcode.py: str.strip(), the text before ";", str.upper())'
SMOOTHIE_VIEW = "read as Smoothieware (Carvera) splits the line at each G and M (GcodeDispatch)"
# What other firmwares do with control characters is not in gclint's sources: the two readings a firmware
# may have are both read (and say so).
ERASED_VIEW = "read with each backspace or DEL erasing the character before it, comments included (a firmware may)"
DROPPED_VIEW = "read without its control characters (a firmware may drop them)"
INVISIBLE_VIEW = "read without its invisible format characters (a BOM or zero-width space a firmware may skip)"


def _marlin_reads(raw: str, parens: bool) -> str:
    """The command Marlin 2 queues for ``raw`` (src/gcode/queue.cpp ``process_stream_char``): the text
    before ``;`` (and outside ``(...)`` when built with PAREN_COMMENTS), a backslash taking the next
    character as it is, and a backspace erasing the character queued before it."""
    out: list[str] = []
    escaped = in_paren = False
    for char in raw:
        if in_paren:
            if char == ")":
                in_paren = False
            continue
        if escaped:
            escaped = False
        elif char == "\\":
            escaped = True
            continue
        elif char == ";":
            break
        elif parens and char == "(":
            in_paren = True
            continue
        if char == "\x08":
            if out:
                out.pop()
        else:
            out.append(char)
    return "".join(out)


def _smoothie_segments(text: str) -> list[tuple[str, int]]:
    """The M commands after the first command that Smoothieware runs for ``text``, with their offsets."""
    cut = _SMOOTHIE_COMMENT.search(text)
    end = cut.start() if cut is not None else len(text)
    starts = []
    start = 0
    while not _SMOOTHIE_WHOLE.match(text, start, end):  # (M117, M1000: the rest of the line is their text)
        m = _SMOOTHIE_SPLIT.search(text, start + 2, end)
        if m is None:
            break
        start = m.start()
        starts.append(start)
    starts.append(end)
    return [
        (text[begin:after], begin)
        for begin, after in zip(starts, starts[1:], strict=False)
        if _SMOOTHIE_CODE.match(text, begin, after)
    ]


def firmware_views(raw: str) -> list[tuple[str, str, int]]:
    """The texts firmwares may read for the line ``raw`` other than ``raw`` itself: ``(how, text, offset)``,
    ``offset`` being where ``text`` starts in ``raw`` (0 where the characters do not line up).

    * Marlin: backspaces erase the character before them (``_marlin_reads``), with and without
      PAREN_COMMENTS.
    * A line with spaces or controls at its ends that Python's ``str.strip()`` removes (U+00A0, U+3000,
      U+2000-U+200A, U+0085, \\x1c-\\x1f...): trimmed, as Klipper does before anything else.
    * Klipper: trimmed, cut at ``;`` and upper-cased with Python's ``str.upper()`` (U+017F to S, U+0131
      to I, U+FB01 to FI...), where the command part holds a character that is not ASCII.
    * Smoothieware: each G or M after the first command of the line, of ``raw`` and of the views above
      (but Klipper's, which does not split).
    """
    views: list[tuple[str, str, int]] = []
    seen = {raw}
    raw = raw[:VIEW_LIMIT]

    def add(how: str, text: str, offset: int) -> None:
        if text not in seen and text.strip(" \t"):
            seen.add(text)
            views.append((how, text, offset))

    if "\x08" in raw:
        add(MARLIN_VIEW, _marlin_reads(raw, False), 0)
        add(MARLIN_VIEW + " with PAREN_COMMENTS", _marlin_reads(raw, True), 0)
    if _CONTROL.search(raw) is not None:
        erased: list[str] = []
        for char in raw:
            if char in "\x08\x7f":
                if erased:
                    erased.pop()
            else:
                erased.append(char)
        add(ERASED_VIEW, _CONTROL.sub("", "".join(erased)), 0)
        add(DROPPED_VIEW, _CONTROL.sub("", raw), 0)
    if FORMAT_CHARACTERS.search(raw) is not None:  # (a BOM mid-file, where files were joined with cat)
        add(INVISIBLE_VIEW, FORMAT_CHARACTERS.sub("", _CONTROL.sub("", raw)), 0)
    trimmed = raw.strip()
    if trimmed != raw.strip(" \t"):
        lead = len(raw) - len(raw.lstrip())
        add(TRIMMED_VIEW, trimmed, lead)
    cut = trimmed.find(_KLIPPER_COMMENT)
    command = trimmed if cut < 0 else trimmed[:cut]
    if not command.isascii():
        add(KLIPPER_VIEW, command.upper(), len(raw) - len(raw.lstrip()))
    for how, text, offset in [(None, raw, 0), *views]:
        if how == KLIPPER_VIEW:
            continue
        for segment, start in _smoothie_segments(text):
            label = SMOOTHIE_VIEW if how is None else f"{how}, then as Smoothieware splits it at each G and M"
            add(label, segment, offset + start if how is None or offset else 0)
    return views


_local = threading.local()


def _views_of(line: Line) -> list[tuple[str, Line, int]]:
    """``firmware_views`` of ``line``, parsed; computed once for all the SC rules that read the line."""
    cached = getattr(_local, "views", None)
    if cached is not None and cached[0] is line:
        return cached[1]
    views = [
        (how, Line(line.number, text, line.ending, parse_line(text)), offset)
        for how, text, offset in firmware_views(line.raw)
    ]
    _local.views = (line, views)
    return views
