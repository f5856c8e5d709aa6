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

# Smoothieware's split gives one view per M code of a line: at most this many different ones are read for
# one text, and a line with more is one finding (``_SecurityRule.check_view``), so that a line of 30,000 commands costs
# linear time and says so instead of passing unread.
SEGMENT_LIMIT = 1_000

# C0 control characters other than tab, and DEL (the line breaks end the line before a rule sees it).
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f]")
# ... and those with the bytes that are not UTF-8, which reach the rules as lone surrogates (syntax/source.py
# decodes with surrogateescape): what a reader may drop.
_DROPPABLE = re.compile("[\x00-\x08\x0b-\x1f\x7f\udc80-\udcff]")
# A line some firmware reads differently from gclint: a character other than printable ASCII and tab, or
# an M code after the first two characters of its code (Smoothieware splits the line there; no SC rule
# listens to a G code).
# (Multi-line and within a line, for the engine's runs of comment lines: rules.base.Rule.on_line_matching.)
# Also a line where an SD-card reader ends a command early (``_sd_card_commands``): a "#" before a letter, a ":"
# before a letter outside a ";" comment, or more than SD_COMMAND_SIZE characters after a first one that is not ";".
_VIEW_TRIGGER = re.compile(
    "(?m)[^\t\n\r\x20-\x7e]|^[^;(\n\r]{2}[^;(\n\r]*?[Mm][ \t]*+[0-9]|^[ \t]*+[Nn](?![ \t]*+[0-9])"
    '|[Mm][ \t]*+0*+11[78][^"\n\r;]*?"|"[^"\n\r]*?[;(]|[Mm][ \t]*+81[0-9][^;\n\r]*?\\|'
    "|#[ \t]*+[A-Za-z]|^[^;\n\r]*?:[ \t]*+[A-Za-z]|^[^;\n\r][^\n\r]{95}|[Mm][ \t]*+0*+911[^;\n\r]*?[Pp]"
)
# Smoothieware's GcodeDispatch: comments start at the first ";" or "(", and the rest is cut before each "G"
# and "M" from its third character on ("find_first_of("GM", 2)"); M117 and M1000 take the rest of the line.
_SMOOTHIE_COMMENT = re.compile("[;(]")
_SMOOTHIE_SPLIT = re.compile("[GM]")
_SMOOTHIE_CODE = re.compile("M[ \t]*+[0-9]")  # (the segments the SC rules listen to: M codes)
_SMOOTHIE_WHOLE = re.compile("M0*+(?:117|1000)(?![0-9])")
_KLIPPER_COMMENT = ";"
# Marlin's G-code macros: "M810 G28|M30 file" stores the commands separated by "|" and "M810" runs them
# (https://github.com/MarlinFirmware/Marlin/blob/bugfix-2.1.x/Marlin/src/gcode/feature/macro/M810-M819.cpp:
# "Set Macro 0 to the given commands, separated by the pipe character"); the text before ";" is the macro.
_MARLIN_MACRO = re.compile(r"[ \t]*+(?:[Nn][ \t]*+\d++[ \t]*+)?[Mm][ \t]*+81[0-9](?![0-9.])")

MARLIN_VIEW = "read as Marlin reads backspaces (src/gcode/queue.cpp process_stream_char)"
TRIMMED_VIEW = "read trimmed as Klipper trims it (Python's str.strip() drops these spaces and controls)"
KLIPPER_VIEW = 'read as Klipper reads it (klippy/gcode.py: str.strip(), the text before ";", str.upper())'
SMOOTHIE_VIEW = "read as Smoothieware (Carvera) splits the line at each G and M (GcodeDispatch)"
MACRO_VIEW = "read as the commands a Marlin M810-M819 macro stores (separated by |)"
NUL_VIEW = "read as RepRapFirmware reads a NUL byte: the end of a line (StringParser::Put)"
SD_SPLIT_VIEW = (
    'read as Prusa and Marlin 1.1 firmware read a job from the SD card: "#" (and, outside a ";" comment, ":") ends'
    " a command"
)
SD_CUT_VIEW = "read as Prusa firmware reads a job from the SD card: a command ends after 95 characters"

# Prusa firmware (Firmware/cmdqueue.cpp, reading from the SD card) ends a command at "#", and after
# SD_COMMAND_SIZE characters (MAX_CMD_SIZE 96, less one), dropping the character that ended it; it skips only
# lines that start with ";", and does not track a ";" comment within a line.  Marlin 1.1 (Marlin_main.cpp
# get_sdcard_commands) ends a command at "#" or ":" outside a ";" comment.
SD_COMMAND_SIZE = 95
POWER_FAIL_VIEW = "read as the commands RepRapFirmware runs when the power fails (the M911 P script)"
# RepRapFirmware's M911 P"..." stores commands that it runs when the supply voltage drops during a print
# (src/GCodes/GCodes2.cpp case 911, powerFailScript; a quote inside is written "").
_POWER_FAIL = re.compile(
    r"""(?i)[ \t]*+(?:N[ \t]*+\d++[ \t]*+)?M[ \t]*+0*+911(?![0-9.])[^;"]*?P[ \t]*+"((?:[^"\r\n]|"")*+)"?"""
)
_SD_SPLIT = re.compile("#")
_SD_SPLIT_OUTSIDE_COMMENT = re.compile("[#:]")
# What other firmwares do with control characters is not in gclint's sources: the two readings a firmware
# may have are both read (and say so).
ERASED_VIEW = "read with each backspace or DEL erasing the character before it, comments included (a firmware may)"
DROPPED_VIEW = "read without its control characters and undecodable bytes (a firmware may drop them)"
UPPER_VIEW = "read as RepRapFirmware reads its command letters, in either case (StringParser: toupper)"
NUMBERLESS_VIEW = (
    'read as a line number with no digits: RepRapFirmware and Klipper run what follows "N" (klippy/gcode.py: a '
    'lone "N" word; StringParser skips what is not a digit)'
)
STRING_VIEW = 'read as RepRapFirmware reads a quoted string: a ";" or "(" inside it starts no comment'
_QUOTED = re.compile('(?<=[A-Za-z])[ \t]*+"(?:[^"\n\r]|"")*+"')  # (a parameter's string: S"...", not o<"name">)
QUOTED_VIEW = 'read as RepRapFirmware reads a quoted message: M117/M118 "..." ends at its closing quote'
_LOWER_CODE = re.compile("(?<![<A-Za-z_])[gm](?=[ \t]*+[0-9])")  # (not in an O-word name: "o<m162>")
_NUMBERLESS = re.compile("[ \t]*+[Nn](?![ \t]*+[0-9])[^A-Za-z\n\r]*+")
_QUOTED_MESSAGE = re.compile('[ \t]*+(?:[Nn][ \t]*+[0-9]++[ \t]*+)?[Mm][ \t]*+0*+11[78][^"\n\r;]*?"(?:[^"\n\r]|"")*+"')
INVISIBLE_VIEW = "read without its invisible format characters (a BOM or zero-width space a firmware may skip)"
WINDOWS_1252_VIEW = "read as Windows-1252 (Repetrel is a Windows program; gclint reads the file as UTF-8)"

# Windows-1252 as Windows decodes it: Python's cp1252 codec leaves 0x81, 0x8D, 0x8F, 0x90 and 0x9D undefined,
# and Windows' table (C_1252.NLS) maps them to the C1 controls U+0081... (shown in
# https://mail.python.org/pipermail/python-ideas/2018-January/048702.html; the WHATWG Encoding Standard's
# index-windows-1252, https://encoding.spec.whatwg.org/index-windows-1252.txt, maps them the same way).
_WINDOWS_1252 = {
    byte: bytes([byte]).decode("cp1252", "replace").replace("\ufffd", chr(byte)) for byte in range(0x80, 0x100)
}


# Windows-1252 keeps ASCII as it is, so the line keeps its commands and comments: its reading differs only
# in the text of a command ("M792 ; SH\u02edLL"), so it is read for lines with an M code.
_M_CODE = re.compile("[Mm][ \t]*+[0-9]")


def _as_windows_1252(raw: str) -> str:
    """``raw`` (UTF-8, undecodable bytes as lone surrogates) as a program reading the bytes as Windows-1252
    reads it: a UTF-8 character becomes two to four characters ("\u02ed" is "\xcb\xad": Ë and a soft
    hyphen, so SH\u02edLL shows SHELL), and an undecodable byte its own character (0xAD the soft hyphen)."""
    return raw.encode("utf-8", "surrogateescape").decode("latin-1").translate(_WINDOWS_1252)


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


def _smoothie_segments(text: str) -> tuple[list[tuple[str, int]], bool]:
    """The M commands after the first command that Smoothieware runs for ``text``, with their offsets (the
    first of each text, at most SEGMENT_LIMIT different ones), and whether there are more."""
    cut = _SMOOTHIE_COMMENT.search(text)
    end = cut.start() if cut is not None else len(text)
    out: list[tuple[str, int]] = []
    seen: set[str] = set()
    if _SMOOTHIE_WHOLE.match(text, 0, end):  # (M117, M1000: the rest of the line is their text)
        return out, False
    m = _SMOOTHIE_SPLIT.search(text, 2, end)
    while m is not None:
        begin = m.start()
        m = None if _SMOOTHIE_WHOLE.match(text, begin, end) else _SMOOTHIE_SPLIT.search(text, begin + 2, end)
        after = m.start() if m is not None else end
        if _SMOOTHIE_CODE.match(text, begin, after) and text[begin:after] not in seen:
            if len(out) == SEGMENT_LIMIT:
                return out, True
            seen.add(text[begin:after])
            out.append((text[begin:after], begin))
    return out, False


def firmware_views(raw: str) -> list[tuple[str, str, int]]:
    """The texts firmwares may read for the line ``raw`` other than ``raw`` itself: ``(how, text, offset)``,
    ``offset`` being where ``text`` starts in ``raw`` (0 where the characters do not line up).  (``_views``
    also says whether Smoothieware's split was cut at SEGMENT_LIMIT commands.)

    * Marlin: backspaces erase the character before them (``_marlin_reads``), with and without
      PAREN_COMMENTS.
    * Another reader: each backspace or DEL erasing the character before it; the line without its control
      characters and undecodable bytes; the line without its invisible format characters.
    * A line with spaces or controls at its ends that Python's ``str.strip()`` removes (U+00A0, U+3000,
      U+2000-U+200A, U+0085, \\x1c-\\x1f...): trimmed, as Klipper does before anything else.
    * Klipper: trimmed, cut at ``;`` and upper-cased with Python's ``str.upper()`` (U+017F to S, U+0131
      to I, U+FB01 to FI...), where the command part holds a character that is not ASCII.
    * Windows-1252, where the line is not ASCII (``_as_windows_1252``).
    * Marlin's macros: each command "M810 G28|M30 file" stores (``_MARLIN_MACRO``).
    * RepRapFirmware: each NUL ends a line; Prusa and Marlin 1.1 reading from the SD card: "#", ":" outside a
      comment and the 95th character end a command (``_sd_card_commands``); the commands of its power-fail
      script (M911 P"...").
    * RepRapFirmware: command letters in either case ("G1 X1 m30 ..."); a ";" or "(" inside a parameter's quoted
      string starts no comment; a quoted M117/M118 message ends at its closing quote (what follows is another
      command); a line number with no digits ("NM30", Klipper's "N SAVE_CONFIG"): what follows the N.
    * Smoothieware: each G or M after the first command of the line, of ``raw`` and of the views above
      (but Klipper's, which does not split).
    """
    return _views(raw)[0]


def _views(raw: str) -> tuple[list[tuple[str, str, int]], bool]:
    views: list[tuple[str, str, int]] = []
    seen = {raw}
    raw = raw[:VIEW_LIMIT]
    more = False

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
    if _DROPPABLE.search(raw) is not None:
        add(DROPPED_VIEW, _DROPPABLE.sub("", raw), 0)
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
    if not raw.isascii() and _M_CODE.search(raw) is not None:
        add(WINDOWS_1252_VIEW, _as_windows_1252(raw), 0)
    if "\x00" in raw:  # (RepRapFirmware: each NUL ends a line, and what follows is the next one)
        at, taken = raw.find("\x00"), 0
        while at >= 0:
            if taken == SEGMENT_LIMIT:  # (as Smoothieware's split: the rest is one finding, check_view)
                more = True
                break
            nxt = raw.find("\x00", at + 1)
            piece = raw[at + 1 : nxt if nxt >= 0 else len(raw)]
            if piece.strip(" \t"):  # (a run of NULs, a sparse file's, holds no command)
                add(NUL_VIEW, piece, at + 1)
                taken += 1
            at = nxt
    comment = _SMOOTHIE_COMMENT.search(raw)
    end = comment.start() if comment is not None else len(raw)
    if _LOWER_CODE.search(raw, 2, end) is not None:  # ("G1 X1 m30 ...": RepRapFirmware's next command)
        add(UPPER_VIEW, raw[:2] + _LOWER_CODE.sub(lambda m: m.group(0).upper(), raw[2:end]) + raw[end:], 0)
    numberless = _NUMBERLESS.match(raw)
    if numberless is not None and numberless.end() < len(raw):
        add(NUMBERLESS_VIEW, raw[numberless.end() :], numberless.end())
    if '"' in raw:  # ('M118 S"hi;x" M30 ...': the commands after a string that holds ";" or "(")
        strings = _QUOTED.sub(lambda m: m.group(0).replace(";", "_").replace("(", "_"), raw)
        if strings != raw:
            add(STRING_VIEW, strings, 0)
    quoted = _QUOTED_MESSAGE.match(raw)
    if quoted is not None:
        add(QUOTED_VIEW, raw[quoted.end() :], quoted.end())
    script = _POWER_FAIL.match(raw)
    if script is not None:
        add(POWER_FAIL_VIEW, script.group(1).replace('""', '"'), 0)
    macro = _MARLIN_MACRO.match(raw)
    if macro is not None and "|" in raw:
        for piece in raw[macro.end() :].split(";", 1)[0].split("|"):
            add(MACRO_VIEW, piece.strip(" \t"), 0)
    for how, text, offset in [(None, raw, 0), *views]:
        if how == KLIPPER_VIEW:
            continue
        segments, cut = _smoothie_segments(text)
        more = more or cut
        for segment, start in segments:
            label = SMOOTHIE_VIEW if how is None else f"{how}, then as Smoothieware splits it at each G and M"
            add(label, segment, offset + start if how is None or offset else 0)
    if raw[:1] != ";":  # (Prusa and Marlin 1.1 read the SD card without Smoothieware's split: after it)
        commands = _sd_card_commands(raw)
        if len(commands) > 3 * SEGMENT_LIMIT:  # (a line cut into more pieces than this is one finding)
            commands, more = commands[: 3 * SEGMENT_LIMIT], True
        for text, start in commands:
            add(SD_CUT_VIEW if start < 0 else SD_SPLIT_VIEW, text, max(start, 0))
    return views, more


def _sd_card_commands(raw: str) -> list[tuple[str, int]]:
    """The commands after the first that an SD-card reader of Prusa or Marlin 1.1 firmware makes of ``raw`` (a
    line that does not start with ";"), with their offsets: those after each "#", and each ":" before the first
    ";"; and, for a line longer than SD_COMMAND_SIZE, each SD_COMMAND_SIZE characters after the first ones, as
    the character that ended the command before is kept or dropped (offset -1: they do not line up)."""
    out: list[tuple[str, int]] = []
    comment = raw.find(";")
    cuts = [m.start() for m in _SD_SPLIT.finditer(raw)]
    cuts += [m.start() for m in _SD_SPLIT_OUTSIDE_COMMENT.finditer(raw, 0, comment if comment >= 0 else len(raw))]
    cuts = sorted(set(cuts))
    for index, at in enumerate(cuts):
        end = cuts[index + 1] if index + 1 < len(cuts) else len(raw)
        out.append((raw[at + 1 : end], at + 1))
    if len(raw) > SD_COMMAND_SIZE:
        for step in (SD_COMMAND_SIZE, SD_COMMAND_SIZE + 1):
            for start in range(step, len(raw), step):
                out.append((raw[start : start + SD_COMMAND_SIZE], -1))
    return out


_local = threading.local()


def _views_of(line: Line) -> tuple[list[tuple[str, Line, int]], bool]:
    """``firmware_views`` of ``line``, parsed, and whether Smoothieware's split was cut (SEGMENT_LIMIT);
    computed once for all the SC rules that read the line."""
    cached = getattr(_local, "views", None)
    if cached is not None and cached[0] is line:
        return cached[1]
    texts, more = _views(line.raw)
    views = [(how, Line(line.number, text, line.ending, parse_line(text)), offset) for how, text, offset in texts]
    _local.views = (line, (views, more))
    return views, more
