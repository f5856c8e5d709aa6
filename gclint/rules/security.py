"""SC: security.  Commands that make the host or the printer run programs or touch files, and secrets left
in the job.

A G-code job is data that comes from elsewhere (a slicer, a colleague, a download, a print farm queue) and
is run by software with access to the machine and, on Hyrel printers, to the Windows PC running Repetrel.
These rules apply to every dialect: a hostile job can claim any flavour in its header, so the check does not
trust the dialect.  Messages and ``Finding.source`` go through ``gclint.secrets.mask``.

Lines the grammar cannot parse (``M0 SHELL C:\\x.exe`` without a ``;``, ``M1000 rm -rf /sd``) are still
read: each rule also looks at the start of lines with a parse error.  Each rule also reads a line as the
firmwares that edit it before parsing read it (``firmware_views``: Marlin's backspaces, Klipper's
``strip()`` and ``upper()``, Smoothieware running every M code of a line), reporting on the line as written.

Where a firmware documents a line as something harmless the rule says so, but the finding stays unless the
dialect the job is read as documents it otherwise (the SC003 and SC005 explanations list those cases).
"""

from __future__ import annotations

import re
import threading
import unicodedata

from gclint import secrets
from gclint.rules.base import Rule, Severity, register
from gclint.syntax.nodes import ASSIGNMENT, GCODE, IMPLICIT, META, OWORD, Command, Comment, Line
from gclint.syntax.parse import parse_line

# "M792", "N10 M0", "/M98", "m0792": the code at the start of a line the grammar could not parse.
_LEADING_CODE = re.compile(
    r"[ \t]*+(?:/[ \t]*+)?(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?([Mm])[ \t]*+(\d{1,8}+(?:\.\d{1,4}+)?)(?![\d.])"
)
# "RUN_SHELL_COMMAND", "N5 save_config": a Klipper command name at the start of a line the grammar refused.
_LEADING_NAME = re.compile(r"[ \t]*+(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?([A-Za-z_][A-Za-z0-9_]*+)")
_NUMBER = re.compile(r"[-+]?\d+(?:\.\d*)?")


def _code(letter: str, number: str) -> str:
    whole, _, frac = number.partition(".")
    frac = frac.rstrip("0")
    return letter.upper() + (whole.lstrip("0") or "0") + ("." + frac if frac else "")


_PAREN_COMMENT = re.compile(r"\([^)\r\n]*+(?:\)|$)")


def _strip_comment(text: str) -> str:
    """``text`` without its comments (``;`` to the end, ``(...)``): the argument of a command."""
    cut = text.find(";")
    if cut >= 0:
        text = text[:cut]
    if "(" in text:
        text = _PAREN_COMMENT.sub("", text)
    return text.strip(" \t")


def _starts_line(line: Line, cmd: Command | None) -> bool:
    """Marlin and RepRapFirmware run the first command of a line; "(note about M30 ...)" is prose.  (The
    other commands of the line are read in Smoothieware's view of it: ``firmware_views``.)"""
    return cmd is None or line.parsed.commands[0] is cmd


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
_VIEW_TRIGGER = re.compile("[^\t\x20-\x7e]|^[^;(]{2}[^;(]*?M[ \t]*+[0-9]")
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


class _SecurityRule(Rule):
    """Listens to ``codes`` on parsed lines and, on lines with a parse error, to the code that starts the line.

    Subclasses implement ``inspect(line, code, rest, column, cmd)``: ``rest`` is the line's text after the
    code word (comments included), ``column`` the 1-based column where ``rest`` starts, ``cmd`` the parsed
    command or None.
    """

    on_issue = True
    # the engine calls check_view for lines this finds (gclint/engine.py)
    on_line_matching = _VIEW_TRIGGER

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._view: tuple[str, Line, int] | None = None  # (how, the line as written, offset) while reading a view

    def check(self, line: Line, cmd: Command) -> None:
        word = cmd.word
        start = word.end_column if word is not None else cmd.column
        self.inspect(line, cmd.code or "", line.raw[start - 1 :], start, cmd)

    def check_issues(self, line: Line) -> None:
        if line.parsed.commands and any(c.code in self.codes for c in line.parsed.commands):
            return  # already seen by check()
        m = _LEADING_CODE.match(line.raw)
        if m is not None:
            code = _code(m.group(1), m.group(2))
        else:  # a Klipper command ("RUN_SHELL_COMMAND\u00a0CMD=x"): Klipper reads names in any case
            m = _LEADING_NAME.match(line.raw)
            if m is None:
                return
            code = m.group(1).upper()
        if code in self.codes:
            self.inspect(line, code, line.raw[m.end() :], m.end() + 1, None)

    def check_view(self, line: Line) -> None:
        """Read ``line`` as each firmware that edits it first reads it (``firmware_views``), reporting on
        ``line`` with the reading named."""
        for how, view, offset in _views_of(line):
            self._view = (how, line, offset)
            try:
                parsed = view.parsed
                for cmd in parsed.commands:
                    if cmd.code in self.codes:
                        self.check(view, cmd)
                if parsed.issues and self.on_issue:
                    self.check_issues(view)
                # (no check_line: SC003's console lines are Smoothieware's, which reads its lines as they are)
            finally:
                self._view = None

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        raise NotImplementedError

    def report_masked(self, line: Line, message: str, column: int, severity: Severity | None = None) -> None:
        """Report with the message and the source line masked (no secret reaches any output).  While a
        firmware's view of a line is read, the finding goes on the line as written, naming the view, unless
        the line already has it."""
        if self._view is not None:
            how, line, offset = self._view
            if any(
                f.line == line.number and f.code == self.code and f.message.endswith(secrets.mask(message))
                for f in self._findings_on(line.number)
            ):
                return
            message = f"{how}: {message}"
            column = offset + column if offset else 1
        self.report(line, secrets.mask(message), column=column, severity=severity)
        finding = self.ctx.findings[-1]
        if finding.line == line.number and finding.source is not None:
            # (the line, or its beginning for a very long one)
            finding.source = _mask_machine_password(secrets.mask(finding.source))

    def _findings_on(self, number: int) -> list:
        """The findings already made on line ``number`` (they are made in line order)."""
        out = []
        for finding in reversed(self.ctx.findings):
            if finding.line != number:
                break
            out.append(finding)
        return out


# -- Repetrel host actions (Hyrel M0 / M792) ------------------------------------------------------------

# The actions the Gcode page lists for M0 and M792: "M0 [ SAY | PIC | VID | SEND | BEEP | SHELL ]".
ACTIONS = ("SAY", "PIC", "VID", "SEND", "BEEP", "SHELL")
# The codes whose text Repetrel reads as actions (Gcode page, M0 Stop Until Resume and M792 Execute Action),
# and M1, which the Hyrel pages do not list but gclint's translator writes as M0 (translate/marlin.py,
# translate/reprap.py); what Repetrel does with text after M1 is not documented, so it is read the same way.
ACTION_CODES = ("M0", "M1", "M792")
# Codes gclint's translator writes as Hyrel's pause M0 (translate/: Marlin and RepRapFirmware M600/M601
# filament change, RepRapFirmware M226 and M291 S2/S3, Machinekit M226, Carvera M600 and an M6 tool change
# with no --tool-map).  Text on them becomes text after M0 when the job is translated to Hyrel.
# tests/test_security_review.py checks this list against the translators.
PAUSE_CODES = ("M6", "M226", "M291", "M600", "M601")

# Characters a program comparing text can skip (.NET's culture-aware comparison ignores U+00AD, for one), or
# that a reader does not see between two letters: control characters other than tab, Unicode's
# default-ignorable code points (soft hyphen, combining grapheme joiner, zero-width spaces and joiners,
# bidirectional marks, invisible operators, variation selectors, the BOM, tag characters, the Hangul
# fillers U+115F, U+1160, U+3164, U+FFA0...), and fillers that print as nothing or as a stretch of the line
# (Arabic tatweel U+0640, NKo lajanyalan U+07FA, the blank Braille pattern U+2800).
_IGNORABLE = (
    "\x00-\x08\x0a-\x1f\x7f-\x9f\u00ad\u034f\u061c\u0640\u07fa\u115f\u1160\u17b4\u17b5\u180b-\u180f"
    "\u200b-\u200f\u202a-\u202e\u2060-\u206f\u2800\u3164\ufe00-\ufe0f\ufeff\uffa0\ufff0-\ufff8"
    "\U0001bca0-\U0001bca3\U0001d159\U0001d173-\U0001d17a\U000e0000-\U000e0fff"
)
_GAP = f"[{_IGNORABLE}]*+"
_IGNORABLE_RUN = re.compile(f"[{_IGNORABLE}]++")
# "SHELL" in any case, with ignorable characters between its letters
_SHELL = re.compile("(?i)" + _GAP.join("SHELL"))
_ACTION_SPLIT = re.compile(r"[;()]")
# the first word of a segment: letters (and ignorable characters between them) after anything else
_FIRST_WORD = re.compile(f"[^A-Za-z]*?((?:[A-Za-z]{_GAP})+)")


def _visible(text: str) -> str:
    """``text`` without ignorable characters."""
    return _IGNORABLE_RUN.sub("", text)


# After NFKD and case folding, "shell" with anything but printable ASCII between its letters: a cheap test
# (in C) that lets the exact, character by character reading below run only where it can find something.
_FOLDED_HINT = re.compile("[^\x20-\x7e]*+".join("shell"))

# Letters of other scripts that look like S, H, E and L and that NFKD does not fold (it folds the full-width,
# mathematical, circled and modifier forms): Cyrillic, Greek, Latin small capitals and letters with a
# stroke or hook, Cherokee, Lisu, Coptic (after Unicode's confusables.txt).  A reader sees SHELL; whether
# Repetrel compares them as SHELL is not documented, so they are read as SHELL.
_CONFUSABLE = str.maketrans(
    {
        **dict.fromkeys("\u0405\u0455\ua731\u13da\ua4e2\u054f\u0282\u023f\u10bd", "s"),
        **dict.fromkeys("\u041d\u043d\u0397\u029c\u04bb\u13bb\ua4e7\u2c8e\u0127\u0126\u0266\u04a2\u04a3", "h"),
        **dict.fromkeys("\u0415\u0435\u0395\u1d07\u13ac\ua4f0\u2c88\u04bd\u0247\u0246", "e"),
        **dict.fromkeys(
            "\u029f\u13de\ua4e1\u2cd0\u04c0\u04cf\u0399\u0406\u01c0\u0142\u0141\u019a\u026b\u026d\u2113", "l"
        ),
    }
)


def _fold(text: str) -> str:
    """``text`` as the letters it shows: confusable letters mapped, then NFKD and case folding."""
    return unicodedata.normalize("NFKD", text.translate(_CONFUSABLE)).translate(_CONFUSABLE).casefold()


def _folded_shell(text: str) -> int | None:
    """Where SHELL starts in ``text`` once compatibility forms are folded (full-width ＳＨＥＬＬ, letters
    with combining marks), letters of other scripts that look like its letters mapped (Cyrillic ЅНЕLL,
    small capitals ꜱʜᴇʟʟ: ``_CONFUSABLE``) and ignorable characters dropped, or None.  Only for text with
    non-ASCII characters (the regular expression has already looked at the rest)."""
    if _FOLDED_HINT.search(_fold(text)) is None:
        return None
    folded: list[str] = []
    where: list[int] = []
    for index, char in enumerate(text):
        for part in _fold(char):
            if unicodedata.category(part) in ("Mn", "Me", "Cf", "Cc") or _IGNORABLE_RUN.match(part):
                continue
            folded.append(part)
            where.append(index)
    found = "".join(folded).find("shell")
    return where[found] if found >= 0 else None


def shell_offsets(text: str) -> list[int]:
    """Where each SHELL starts in ``text``: any case, anywhere (``SHELLC:\\\\x``, ``SAY hi SHELL x``,
    ``-SHELL``), with invisible characters (U+00AD, U+200B...) or compatibility forms in between."""
    found = [m.start() for m in _SHELL.finditer(text)]
    if not found and not text.isascii():
        offset = _folded_shell(text)
        if offset is not None:
            found.append(offset)
    return found


def host_actions(rest: str) -> list[tuple[str, str, int]]:
    """The Repetrel actions in the text after ``M0``/``M792``: ``(KEYWORD, argument, offset)``.

    The Hyrel page writes them after ``;``, one per segment: ``M0 ; SAY Hello Wilbur ; PIC C:\\\\mr_ed.png``.
    A segment is an action when its first word is one of SAY, PIC, VID, SEND, BEEP, SHELL in any case,
    read without invisible characters and after any punctuation (``-PIC``, ``PIC=C:\\\\x.png``); a first
    word that starts with SHELL (``SHELLC:\\\\x.exe``) is SHELL.  ``offset`` is where the keyword starts in
    ``rest``.  (SHELL anywhere in the text is SC001's business: ``shell_offsets``.)
    """
    out = []
    pos = 0
    for segment in _ACTION_SPLIT.split(rest):
        m = _FIRST_WORD.match(segment)
        if m is not None:
            word = _visible(m.group(1)).upper()
            keyword = "SHELL" if word.startswith("SHELL") else word
            if keyword in ACTIONS:
                # the argument: what follows the keyword's letters ("SHELLC:\\x" -> "C:\\x")
                letters = 0
                cut = m.start(1)
                while cut < len(segment) and letters < len(keyword):
                    if segment[cut].isalpha():
                        letters += 1
                    cut += 1
                argument = _visible(segment[cut:]).strip(" \t=,:")
                out.append((keyword, argument, pos + m.start(1)))
        pos += len(segment) + 1
    return out


def holds_action(text: str) -> bool:
    """Whether Repetrel could read ``text`` (after M0/M1/M792) as an action: an action keyword starting a
    segment, or SHELL anywhere."""
    return bool(host_actions(text)) or bool(shell_offsets(text))


def _shell_argument(rest: str, offset: int) -> str:
    """The text after the SHELL at ``offset``, to the end of its segment."""
    tail = rest[offset:]
    m = _SHELL.match(tail)
    after = tail[m.end() :] if m is not None else tail[5:]
    return _visible(_ACTION_SPLIT.split(after, 1)[0]).strip(" \t=,:")


# "M0", "N10 M792", "/m1": an action code starting a line (for lines the grammar refused).
_ACTION_LINE = re.compile(
    r"[ \t]*+(?:/[ \t]*+)?(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?[Mm][ \t]*+(?:0*+(?:1|792)|0++)(?![\d.])"
)


def action_shell_column(line: Line) -> int | None:
    """The column of the first SHELL in the text of an M0/M1/M792 on ``line`` (Repetrel would run it as a
    program), in the line as written or as a firmware may read it (``firmware_views``: a leading U+00A0
    trimmed, backspaces applied...), or None.  The translator's guard (translate/engine.py) checks every line
    it writes with it."""
    column = _action_shell_column(line)
    if column is not None or _VIEW_TRIGGER.search(line.raw) is None:
        return column
    for _, text, offset in firmware_views(line.raw):
        column = _action_shell_column(Line(line.number, text, line.ending, parse_line(text)))
        if column is not None:
            return offset + column if offset else 1
    return None


def _action_shell_column(line: Line) -> int | None:
    raw = line.raw
    for cmd in line.parsed.commands:
        if cmd.code in ACTION_CODES and cmd.kind == GCODE:
            word = cmd.word
            start = word.end_column if word is not None else cmd.column
            offsets = shell_offsets(raw[start - 1 :])
            if offsets:
                return start + offsets[0]
    if not line.parsed.commands or line.parsed.issues:
        m = _ACTION_LINE.match(raw)
        if m is not None:
            offsets = shell_offsets(raw[m.end() :])
            if offsets:
                return m.end() + 1 + offsets[0]
    return None


@register
class HostRunsProgram(_SecurityRule):
    code = "SC001"
    name = "host-runs-program"
    severity = Severity.ERROR
    summary = "The job makes the host computer run a program (SHELL in M0/M1/M792 text, Klipper RUN_SHELL_COMMAND)"
    explanation = """
        Repetrel's M0 and M792 take actions after the command; "SHELL C:\\program.exe" makes the PC that
        drives the printer execute that file, with the rights of the user running Repetrel.  Klipper's
        gcode_shell_command extension does the same on the printer's host with RUN_SHELL_COMMAND.  A
        G-code job is data: it must not start programs.  Anyone who can hand you a job file (a download,
        a shared folder, a print farm queue) could otherwise run anything on that computer.  Remove the
        action; if a program really must run around a job, start it from the host, not from the file.

        The Hyrel pages show the form "M0 ; SHELL C:\\program.exe" but do not say how strictly Repetrel
        reads it, so any SHELL in the text of M0, M1 or M792 is reported: in any case, anywhere in the
        text ("SAY hi SHELL x", "SHELLC:\\x.exe", "-SHELL", "SHELL=x"), with invisible characters or
        fillers inside the word (soft hyphen, zero-width space, Arabic tatweel, the blank Braille pattern,
        Hangul fillers), and in letters that look like its own: full-width and mathematical forms, small
        capitals, Cyrillic and Greek lookalikes ("ЅНЕLL").  M1 is not on the Hyrel
        pages; gclint's translator writes it as M0, so it is read the same way.  The same holds for the
        codes gclint's translator turns into Hyrel's pause M0 (M600, M601, M226, M291, M6 on Carvera and
        Machinekit): text on them is text after M0 once the job is translated ("gclint translate" removes
        it, TR009, but another tool may not).  A comment that names a shell mill on a tool change is
        reported too: reword it.
    """
    example_bad = "M792 ; SHELL C:\\program.exe"
    example_good = "M792 ; BEEP"
    source = (
        "Gcode page, M0 Stop Until Resume and M792 Execute Action"
        " (SHELL C:\\program.exe - the computer will execute the file); Klipper RUN_SHELL_COMMAND"
        " (gcode_shell_command); gclint/translate (codes written as M0)"
    )
    codes = (*ACTION_CODES, *PAUSE_CODES, "RUN_SHELL_COMMAND")

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._reported = 0  # the last line reported (one command's text holds the next one's)

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if code == "RUN_SHELL_COMMAND":
            where = cmd.column if cmd is not None else 1
            self.report_masked(
                line, f"RUN_SHELL_COMMAND runs a shell command on the printer's host{_excerpt(rest)}", where
            )
            return
        if line.number == self._reported:
            return
        offsets = shell_offsets(rest)
        if not offsets:
            return
        self._reported = line.number
        for offset in offsets:
            argument = _shell_argument(rest, offset)
            target = f" {_quote(argument)}" if argument else ""
            if code in ("M0", "M792"):
                message = f"{code} SHELL makes the host computer execute{target}: a job file must not run programs"
            elif code == "M1":
                message = (
                    f"SHELL in M1 text{target}: gclint writes M1 as Hyrel's M0, whose SHELL action makes the host "
                    "computer execute a program (the Hyrel pages do not say what Repetrel does with M1 text)"
                )
            else:
                message = (
                    f"SHELL in {code} text{target}: {code} becomes Hyrel's pause M0 when this job is translated, "
                    "and SHELL after M0 makes the host computer execute a program"
                )
            self.report_masked(line, message, column=column + offset)


@register
class HostOpensFile(_SecurityRule):
    code = "SC002"
    name = "host-opens-file"
    severity = Severity.WARNING
    summary = "The job makes the host open a file named in the job (M0/M792 PIC or VID)"
    explanation = """
        "M792 ; PIC C:\\sample.jpg" and "VID C:\\sample.mp4" make Repetrel open and show a file from the
        host computer's disk, chosen by whoever wrote the job.  That is usually harmless (a picture of
        the next step), but it reads files outside the job, and a crafted media file is a classic way into
        a viewer.  Check that the path is one you expect; a job from someone else should not name files
        on your computer.  The keyword is read in any case, without invisible characters and after
        punctuation ("-PIC", "PIC=C:\\x.png").
    """
    example_bad = "M0 ; PIC C:\\mr_ed.png"
    example_good = "M0 ; SAY Load the blue filament"
    source = "Gcode page, M0 Stop Until Resume and M792 Execute Action (PIC, VID)"
    codes = ("M0", "M792")

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        for keyword, argument, offset in host_actions(rest):
            if keyword in ("PIC", "VID"):
                what = "image" if keyword == "PIC" else "video"
                target = f" {_quote(argument)}" if argument else ""
                self.report_masked(
                    line,
                    f"{code} {keyword} makes the host open the {what}{target} from its own disk",
                    column=column + offset,
                )


# -- the Smoothieware console (Carvera) ------------------------------------------------------------------

# Smoothieware's console: a line whose first character is a lower-case letter or "$" goes to SimpleShell
# (and to the player's own commands); G-code starts with an upper-case letter.  Carvera Community Firmware,
# src/modules/utils/simpleshell/SimpleShell.cpp (on_console_line_received: "ignore anything that is not
# lowercase or a $"; commands_table, matched by prefix with strncasecmp) and src/modules/utils/player/
# Player.cpp (on_main_loop feeds every line of a played file to ON_CONSOLE_LINE_RECEIVED; play, buffer,
# upload, download, goto, abort, suspend, resume); research/firmware_codes.md section 8.
CONSOLE_START = frozenset("abcdefghijklmnopqrstuvwxyz$")
# What the shell runs for a first word (exact matches first, then SimpleShell's table in its order: a word
# runs the first entry it starts with).
_CONSOLE_EXACT = {
    "config-get": "reads a configuration value",
    "config-set": "changes the configuration on the SD card",
    "config-load": "loads a configuration",
    "config-get-all": "reads the configuration",
    "config-restore": "restores a saved configuration",
    "config-default": "restores the default configuration",
    "play": "plays another file",
    "progress": "reports progress",
    "abort": "aborts the running file",
    "suspend": "suspends the running file",
    "resume": "resumes the running file",
    "buffer": "queues a console command to run",
    "upload": "writes a file to the SD card",
    "download": "sends a file from the SD card",
    "goto": "jumps to a line of the running file",
    "laser": "drives the laser module",
}
_CONSOLE_TABLE = (
    ("ls", "lists files"),
    ("cd", "changes folder"),
    ("pwd", "prints the folder"),
    ("cat", "prints a file"),
    ("echo", "prints its text"),
    ("rm", "deletes a file"),
    ("mv", "moves or renames a file"),
    ("mkdir", "creates a folder"),
    ("reset", "restarts the controller"),
    ("dfu", "starts a firmware update"),
    ("break", "stops the controller in its debugger"),
    ("help", "prints help"),
    ("ftype", "reports the file type"),
    ("version", "prints the version"),
    ("mem", "prints memory use"),
    ("get", "reads machine state"),
    ("set_temp", "sets a temperature"),
    ("switch", "switches an output"),
    ("net", "reports the network"),
    ("ap", "configures the WiFi access point"),
    ("wlan", "configures the WiFi network"),
    ("diagnose", "runs diagnostics"),
    ("sleep", "puts the machine to sleep"),
    ("power", "switches power"),
    ("load", "loads a configuration override"),
    ("save", "writes a configuration override file"),
    ("remount", "remounts the SD card"),
    ("calc_thermistor", "computes thermistor values"),
    ("thermistors", "lists thermistors"),
    ("md5sum", "hashes a file"),
    ("time", "sets the clock"),
    ("test", "runs a hardware test"),
    ("model", "sets the machine model"),
    ("check_5th", "tests the 5th axis"),
    ("check_4th", "tests the 4th axis"),
    ("check_led", "tests the lights"),
    ("fset", "sets a factory value"),
    ("enable_4th_hd", "enables the 4th axis"),
    ("disable_4th_hd", "disables the 4th axis"),
)
# RepRapFirmware's meta commands: lower-case words that RepRapFirmware itself runs (research/
# firmware_codes.md section 6; StringParser.cpp ProcessConditionalGCode).
_RRF_META = frozenset(
    ("if", "elif", "else", "while", "break", "continue", "abort", "var", "global", "set", "echo", "skip")
)
_FIRST_TOKEN = re.compile(r"[^ \t;(]*")


def console_command(token: str) -> str | None:
    """What Smoothieware's console does with a line starting with ``token``, or None when the community
    firmware's tables have no command for it (modules and other versions add their own)."""
    low = token.lower()
    if low in _CONSOLE_EXACT:
        return _CONSOLE_EXACT[low]
    if low.startswith("$"):
        return "runs a grbl command (home, unlock, jog, switch...)"
    for name, what in _CONSOLE_TABLE:
        if low.startswith(name):
            return what
    return None


@register
class ShellPassThrough(_SecurityRule):
    code = "SC003"
    name = "shell-pass-through"
    severity = Severity.ERROR
    summary = "A line Smoothieware/Carvera runs as a console command (a lower-case first word, $, M1000)"
    explanation = """
        The Carvera (Smoothieware) plays a file by handing every line to its console, and the console
        (SimpleShell and the player) runs any line that starts with a lower-case letter or "$" as a
        command: "rm /sd/config.txt" deletes the configuration, "mv" moves files, "play" runs another
        file, "upload" writes one, "config-set" changes settings, "buffer" queues a console command,
        "reset" and "dfu" restart the controller, "$X" unlocks an alarm.  "M1000 <command>" hands the
        lower-cased command to the same shell.  A job has no business running console commands; one line
        can erase the machine's configuration or other jobs.  Do file and configuration work from the
        controller's console, not from G-code.

        Such a line is never G-code on the Carvera, so it is reported in every dialect (a job that runs
        on a Carvera can claim any flavour), with these exceptions, where the dialect documents the line
        as something else: RepRapFirmware's meta commands ("if", "while", "var", "set", "abort",
        "break"...) in a job read as RepRapFirmware, and lower-case G-code words, "n" line numbers, O-words
        and parameter assignments in a job read as Machinekit/LinuxCNC (which reads words in any case).
        "echo" is not
        reported: both firmwares only print its text (RepRapFirmware's "echo >file" writes a file:
        SC005).  Note that "break" and "abort" do something else on a Carvera (stop in the debugger, abort
        the job), and that Klipper reads its commands in any case, so write them in upper case.  Lines
        that start with a space or tab are not sent to the shell (SimpleShell reads the first character
        as it is).
    """
    example_bad = "rm /sd/config.txt"
    example_good = "M1000"
    source = (
        "Carvera M-code table (seeds/carvera-mcodes.md): M1000 pass-through to the simpleshell;"
        " research/firmware_codes.md section 8 (console commands); Carvera Community Firmware"
        " SimpleShell.cpp and Player.cpp (every played line goes to the console)"
    )
    codes = ("M1000",)
    on_line_starting_with = CONSOLE_START

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        argument = _strip_comment(rest)
        if argument:
            self.report_masked(
                line,
                f"M1000 passes {_quote(argument)} to the controller's shell: a job must not run console commands",
                column,
            )

    def check_line(self, line: Line) -> None:
        raw = line.raw
        token = _FIRST_TOKEN.match(raw).group(0)  # type: ignore[union-attr]
        if token == "echo" or self._documented_otherwise(line, token):
            return
        what = console_command(token)
        does = f": it {what}" if what else " (the community firmware's tables have no such command; others may)"
        self.report_masked(
            line,
            f"Smoothieware (Carvera) runs this line as the console command {_quote(token, 40)}{does};"
            " a job must not run console commands",
            1,
        )

    def _documented_otherwise(self, line: Line, token: str) -> bool:
        parsed = line.parsed
        commands = parsed.commands
        if parsed.issues:
            return False
        dialect = self.ctx.dialect
        if dialect.name == "reprap":
            return bool(commands) and commands[0].kind == META and token in _RRF_META
        if dialect.family == "linuxcnc":
            if token[:1] == "$" and not token[1:2].isdigit():
                return False  # ("$1" is LinuxCNC's spindle word)
            if not commands:
                return parsed.line_number is not None  # "n100 (a comment)"
            return commands[0].kind in (GCODE, IMPLICIT, OWORD, ASSIGNMENT)
        return False


# -- files on the printer ---------------------------------------------------------------------------------


def _file_argument(code: str, rest: str, cmd: Command | None) -> str | None:
    """The file a command names, or None when it names none (``M98 P100`` calls subprogram 100)."""
    argument = _strip_comment(rest)
    if not argument:
        return None
    if code == "M98":
        if cmd is not None and cmd.words:
            p = cmd.raw("P")
            if p is None:
                return None
            if p.startswith('"'):
                return p.strip('"')
            if _NUMBER.fullmatch(p):
                return None  # subprogram or macro number (Fanuc, Carvera macros/####.cnc)
        if argument[:1] in "Pp":
            value = argument[1:].strip(" \t")
            if not value or _NUMBER.fullmatch(value.split()[0]) or value.startswith("["):
                return None
            return value.strip('"')
        return argument if not _NUMBER.fullmatch(argument) else None
    if code == "M98.1" and "{" in argument:
        return argument[argument.find("{") + 1 :].rstrip("} \t")  # M98.1 L2 {gcodes/test.cnc}
    if "!" in argument:  # Marlin M32 P !/models/part.gco#
        return argument[argument.find("!") + 1 :].split("#", 1)[0]
    return argument.strip('"')


_MACRO_NUMBER = re.compile(r"[Pp][ \t]*+(\d{1,9}+)(?:\.0*+)?(?![\d.])")


def _macro_number(rest: str, cmd: Command | None) -> int | None:
    """The number of ``M98 P1234`` (a Carvera macro file, a LinuxCNC/Fanuc subprogram), or None."""
    if cmd is not None and cmd.words:
        p = cmd.raw("P")
        return int(float(p)) if p is not None and _NUMBER.fullmatch(p) and float(p) >= 0 else None
    m = _MACRO_NUMBER.match(_strip_comment(rest))
    return int(m.group(1)) if m is not None else None


def _reprap_configuration(path: str) -> bool:
    """Whether ``path`` is a RepRapFirmware system or macro file: ``.g``, or under ``sys/`` or ``macros/``."""
    parts = path.replace("\\", "/").lower().split("/")
    return parts[-1].endswith(".g") or "sys" in parts[:-1] or "macros" in parts[:-1]


def _reprap_system_file(path: str) -> bool:
    """Whether ``path`` is a RepRapFirmware system file: a ``.g`` file right in a ``sys/`` folder (config.g
    and the files it runs); a job (``.gcode``) placed there, or deeper, is not."""
    parts = path.replace("\\", "/").lower().split("/")
    return len(parts) >= 2 and parts[-2] == "sys" and parts[-1].endswith(".g")


@register
class RunsFile(_SecurityRule):
    code = "SC004"
    name = "runs-file"
    severity = Severity.WARNING
    summary = (
        "The job runs or selects another file on the printer (M98 with a path or a macro number, M98.1, M32, M23,"
        " Klipper SDCARD_PRINT_FILE)"
    )
    explanation = """
        M98 P"file" (RepRapFirmware macros), M98 P1234 (Carvera: the file gcodes/macros/1234.cnc), M98.1
        {path} (Carvera), M32 (select and start a file), M23 (select a file for M24) and Klipper's
        SDCARD_PRINT_FILE FILENAME=... (load a file and start it) make the firmware run a file that is not
        in this job.  What runs is whatever that file holds on the machine at print time, which this check
        cannot see; on a shared or networked printer it may have been changed.  Prefer self-contained jobs;
        when a macro is intended, silence this code for those files with per-file-ignores in the
        configuration.  A job cannot silence SC findings itself: "; noqa: SC004" and "; gclint:
        disable=SC" are ignored for the security rules.

        M98 P with a number is a subprogram of the same file in LinuxCNC (Fanuc style,
        research/firmware_codes.md section 7), so it is not reported in a job read as
        Machinekit/LinuxCNC; elsewhere it is, since a Carvera runs gcodes/macros/<number>.cnc for it.

        RepRapFirmware's own configuration is macros calling macros: the firmware runs homeall.g for G28,
        tpre0.g for T0, M<n>.g for a code it does not have, and these files call each other with M98
        (research/firmware_codes.md section 6).  So M98 in a RepRapFirmware system or macro file (a `.g`
        file, or a file in a `sys/` or `macros/` folder, checked as RepRapFirmware) is not reported: it
        runs another part of the same configuration.  A job that calls a macro still is.
    """
    example_bad = 'M98 P"0:/macros/prime.g"'
    example_good = """
        ; gclint-test: dialect=machinekit
        M98 P100 L2
    """
    source = (
        "RepRap G-code page (M23, M32, M98); Carvera M-code table (M98 P####: gcodes/macros/####.cnc, M98.1, M32,"
        " M23); Klipper docs/G-Codes.md [virtual_sdcard] (SDCARD_PRINT_FILE: load a file and start SD print)"
    )
    codes = ("M98", "M98.1", "M32", "M23", "SDCARD_PRINT_FILE")

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.configuration = ctx.dialect.name == "reprap" and _reprap_configuration(ctx.path)

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if not _starts_line(line, cmd) or (code == "M98" and self.configuration):
            return
        if code == "SDCARD_PRINT_FILE":
            name = cmd.params.get("FILENAME") if cmd is not None else None
            target = f" {_quote(name.strip(chr(34)))}" if name else ""
            where = cmd.column if cmd is not None else 1
            self.report_masked(
                line,
                f"SDCARD_PRINT_FILE loads and starts the file{target} on a Klipper printer: code outside this job",
                where,
            )
            return
        name = _file_argument(code, rest, cmd)
        if name is None:
            if code == "M98" and self.ctx.dialect.family != "linuxcnc":
                number = _macro_number(rest, cmd)
                if number is not None:
                    self.report_masked(
                        line,
                        f"M98 P{number} runs the file gcodes/macros/{number}.cnc on a Carvera: code outside this job",
                        column,
                    )
            return
        verb = {"M23": "selects", "M32": "selects and starts"}.get(code, "runs")
        self.report_masked(line, f"{code} {verb} the file {_quote(name)} on the printer: code outside this job", column)


# RepRapFirmware 3.4 and later: "echo >file ...", ">>file" (StringParser.cpp ProcessEchoCommand: '>' opens the
# file for writing, '>>' for appending; any text starting with '>' is read as a redirect).
_ECHO_REDIRECT = re.compile(
    r"""[ \t]*+(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?echo[ \t]*+(>{1,3}+)[ \t]*+("(?:[^"\r\n]|"")*+"?|\{[^}\r\n]*+\}?|[^ \t;]*+)"""
)
_LOG_FILE = re.compile(r"(?i)\.(?:txt|log)$")
# Codes whose file effect belongs to one firmware (research/firmware_codes.md): Smoothieware keeps settings
# in a config-override file (section 8: M500 save overrides, M502 delete override file, M504 save to a
# named file; seeds/carvera-mcodes.md M502 "deletes config-override"), RepRapFirmware writes
# config-override.g (section 6: M500-M503 config-override); Marlin keeps them in EEPROM (sections 1 and 5:
# save / load / defaults / report / validate settings), so a job read as Marlin is not reported.
_CONFIG_OVERRIDE = {
    "M500": "writes the machine's settings into its config-override file (Smoothieware/Carvera config-override,"
    " RepRapFirmware config-override.g)",
    "M502": "deletes the config-override file on Smoothieware/Carvera (the machine falls back to config.txt)",
    "M504": "writes the machine's settings into a named config-override file on Smoothieware/Carvera",
}


# Codes that replace the printer's firmware (research/firmware_codes.md: section 1 Prusa Buddy M997 firmware
# update; section 5 Marlin M997 firmware update, M936 OTA update; section 6 RepRapFirmware M997 firmware update).
_FIRMWARE_UPDATE = {
    "M997": "starts a firmware update (Marlin, Prusa Buddy, RepRapFirmware): a job must not replace the printer's"
    " firmware",
    "M936": "starts an over-the-air firmware update (Marlin)",
}


@register
class ChangesPrinterFiles(_SecurityRule):
    code = "SC005"
    name = "changes-printer-files"
    severity = Severity.ERROR
    summary = (
        "The job deletes, writes or renames files on the printer, or replaces its firmware (M30 <file>, M28, M471,"
        " M472, M559, M560, echo >file, M928/M929 into a non-log file, M500/M502/M504, M505, M997, M936, Klipper"
        " SAVE_CONFIG and SAVE_VARIABLE)"
    )
    explanation = """
        In Marlin and RepRapFirmware "M30 file" deletes that file from the SD card, M28 writes the
        following lines into a file instead of running them (M28 /sys/config.g replaces the printer's
        configuration), M471 renames or moves a file, M472 deletes one and M559/M560 upload configuration
        or web files.  RepRapFirmware 3.4 and later write the text of "echo >"file" ..." into a file
        (">>" appends), so "echo >"0:/sys/config.g" "M112"" replaces the configuration; "M929 P"file" S1"
        logs into a file, which in a .g file puts log lines into a macro the printer runs (log files
        ending in .txt or .log are not reported).  On Smoothieware (Carvera) M500 writes the
        config-override file, M502 deletes it and M504 writes a named one (RepRapFirmware's M500 writes
        config-override.g); in a job read as Marlin they are the EEPROM settings and not reported.
        Klipper's SAVE_CONFIG overwrites the printer's config file and restarts the host, and SAVE_VARIABLE
        writes a variable to disk.  Marlin's M928 logs the commands that follow into a named file on the SD
        card (a .txt or .log file is not reported, as for M929); RepRapFirmware's M505 makes another folder
        the system folder, so the printer reads its config.g from there; M997 (Marlin, Prusa, RepRapFirmware)
        and M936 (Marlin) update the firmware.

        A job that changes the printer's files outlives the print: it can break the next job, the
        machine's limits or its safety settings.  Plain "M30" (end of program) is fine, as are a bare M471
        or M472 (on the Carvera they pair the wireless probe and switch its laser on).  In a job read as
        Hyrel, M30 is "End of Program" and takes no file, but the finding stays: the dialect is read from
        the job itself, and a job that names a file after M30 deletes it wherever Marlin or RepRapFirmware
        runs it.  The same holds for RepRapFirmware system and macro files: a macro package that writes
        its own files is reported, and a configuration repository silences this code for those files
        with per-file-ignores.

        Smoothieware (Carvera) runs every G and M code of a line, so "G0 X0 M502" is reported (on the
        M502) in every dialect; the dialect's own exemptions still hold.
    """
    example_bad = "M30 /sys/config.g"
    example_good = "M30"
    source = (
        "RepRap G-code page (M28, M30, M471, M559, M560); research/firmware_codes.md sections 6 (M472 delete, M929"
        " logging, M500-M503 config-override) and 8 (M500, M502 delete override file, M504); RepRapFirmware"
        " StringParser.cpp ProcessEchoCommand (echo >file, >>file); Klipper docs/G-Codes.md [configfile]"
        " SAVE_CONFIG and [save_variables] SAVE_VARIABLE; research/firmware_codes.md sections 2 and 5 (M928 SD"
        " logging into a file), 6 (M505 set system folder), 1, 5 and 6 (M997 firmware update), 5 (M936 OTA"
        " update), 8 (several G/M words on one line are split at each G/M)"
    )
    codes = (
        "M30",
        "M28",
        "M471",
        "M472",
        "M559",
        "M560",
        "M929",
        "M500",
        "M502",
        "M504",
        "echo",
        "SAVE_CONFIG",
        "SAVE_VARIABLE",
        "M928",
        "M505",
        "M997",
        "M936",
    )

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if not _starts_line(line, cmd):
            return
        if code == "echo":
            self._echo(line, cmd.column if cmd is not None else 1)
            return
        if code in ("SAVE_CONFIG", "SAVE_VARIABLE"):
            where = cmd.column if cmd is not None else 1
            what = (
                "overwrites the printer's config file and restarts Klipper"
                if code == "SAVE_CONFIG"
                else "writes a variable to the printer's [save_variables] file"
            )
            self.report_masked(line, f"{code} {what}", where)
            return
        if code in _FIRMWARE_UPDATE:
            self.report_masked(line, f"{code} {_FIRMWARE_UPDATE[code]}{_excerpt(rest)}", column)
            return
        if code in _CONFIG_OVERRIDE:
            if self.ctx.dialect.name != "marlin":
                self.report_masked(line, f"{code} {_CONFIG_OVERRIDE[code]}", column)
            return
        argument = re.sub(r"\*\d+\s*$", "", _strip_comment(rest))  # (a "*99" checksum is no file name)
        if code in ("M30", "M28"):
            if not argument.strip():
                return
            if code == "M30" and cmd is not None and cmd.words and not any(w.kind == "string" for w in cmd.words):
                return  # "M30 P1": parameter words, no file name
            action = "deletes" if code == "M30" else "writes the following lines into"
            where = "on the printer"
            if code == "M30" and self.ctx.dialect.family == "hyrel":
                # the dialect is read from the job, which an attacker writes: the gate does not rest on it
                where = "on a Marlin or RepRapFirmware printer (on Hyrel, M30 ends the program and takes no file)"
            self.report_masked(line, f"{code} {action} the file {_quote(argument.strip(chr(34)))} {where}", column)
            return
        if code == "M929":
            self._logging(line, argument, column, cmd)
            return
        if code == "M928":
            name = argument.strip().strip('"')
            if name and not (_LOG_FILE.search(name) and "{" not in name):  # (as M929: a .txt/.log file is a log)
                self.report_masked(
                    line,
                    f"M928 starts logging the commands that follow into the file {_quote(name)}"
                    " on the printer's SD card (Marlin, Prusa MK3)",
                    column,
                )
            return
        if code == "M505":
            self.report_masked(
                line,
                f"M505 moves RepRapFirmware's system folder{_excerpt(argument)}: the printer then reads config.g and"
                " its other system files from there",
                column,
            )
            return
        if code in ("M471", "M472") and not argument.strip():
            return  # Carvera: pair the wireless probe, switch its laser on
        action = {
            "M471": "renames or moves a file",
            "M472": "deletes a file",
            "M559": "uploads a configuration file",
            "M560": "uploads a web file",
        }[code]
        self.report_masked(line, f"{code} {action} on the printer{_excerpt(argument)}", column)

    def check_issues(self, line: Line) -> None:
        super().check_issues(line)
        if any(c.code == "echo" for c in line.parsed.commands):
            return  # already seen by check()
        if "echo" in line.raw:
            self._echo(line, 1)

    def _echo(self, line: Line, column: int) -> None:
        m = _ECHO_REDIRECT.match(line.raw)
        if m is None:
            return
        mode = "appends its text to" if len(m.group(1)) > 1 else "writes its text into"
        target = f" {_quote(m.group(2).strip(chr(34)))}" if m.group(2).strip('"') else ""
        self.report_masked(
            line, f"echo {m.group(1)} {mode} the file{target} on a RepRapFirmware printer (3.4 and later)", column
        )

    def _logging(self, line: Line, argument: str, column: int, cmd: Command | None) -> None:
        if cmd is not None and cmd.words:
            target, level = cmd.raw("P"), cmd.raw("S")
        else:
            m_p = re.search(r"""(?i)P[ \t]*+("[^"]*+"?|\S+)""", argument)
            m_s = re.search(r"(?i)S[ \t]*+(\S+)", argument)
            target, level = (m_p.group(1) if m_p else None), (m_s.group(1) if m_s else None)
        if target is None or (level is not None and _NUMBER.fullmatch(level) and float(level) == 0):
            return  # the default log file (eventlog.txt), or logging stopped
        name = target.strip('"')
        if _LOG_FILE.search(name) and "{" not in name:
            return
        self.report_masked(
            line,
            f"M929 logs into the file {_quote(name)}: log lines written into a file the printer runs (a .g macro)"
            " become G-code",
            column,
        )


# -- secrets ------------------------------------------------------------------------------------------------


@register
class LeakedSecret(_SecurityRule):
    code = "SC006"
    name = "leaked-secret"
    severity = Severity.ERROR
    summary = "A password, API key or token is left in the job (slicer settings, URLs, WiFi setup)"
    explanation = """
        Slicers append their settings to the job as comments, and some have written the print host's
        credentials there ("; printhost_apikey = ...", "; printhost_password = ..."; OctoPrint's File
        Check warns about the same leak).  URLs with "user:password@", bearer tokens, API keys,
        RepRapFirmware's M587 WiFi password and its M551 machine password (the password of the web
        interface, FTP and Telnet) end up in start G-code the same way.  A job file is copied to
        print farms, shared folders and git: whoever gets it gets the secret.  Remove it, clear the field
        in the slicer's printer settings, and revoke the key.  gclint masks the value in every report.
    """
    example_bad = "; printhost_apikey = 0123456789ABCDEF0123456789ABCDEF"
    example_good = "; printhost_apikey = "
    source = (
        "research/anchors.md: OctoPrint File Check, leaked_api_key; research/firmware_codes.md section 6"
        " (M551 password, M587 Wi-Fi networks)"
    )
    codes = ("M117", "M118", "M551", "M587", "M589")
    on_comment = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._clean: set[str] = set()  # comment texts with no secret

    def check_comment(self, line: Line, comment: Comment) -> None:
        text = comment.text
        if text in self._clean:  # comments repeat (";TYPE:Perimeter", ";WIDTH:0.45")
            return
        found = secrets.find(text)
        if not found and len(text) <= 1024:  # (long texts are not remembered: memory stays bounded)
            if len(self._clean) >= 8192:
                self._clean.clear()
            self._clean.add(text)
        for s in found:
            self.report_masked(
                line, f"{s.kind} left in a comment: anyone who gets this job can read it", comment.column + s.start
            )

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if cmd is None:
            return  # parse errors are read whole in check_issues
        if code == "M551":
            self._machine_password(line)
            return
        end = min((c.column for c in line.parsed.comments), default=len(line.raw) + 1)
        start = cmd.column
        for s in secrets.find(line.raw[start - 1 : end - 1]):
            self.report_masked(line, f"{s.kind} in {code}: anyone who gets this job can read it", start + s.start)

    def check_issues(self, line: Line) -> None:
        if line.parsed.kind != "error":
            return
        # The grammar gave up on the line, so its comments were not read: look at the whole text.
        for s in secrets.find(line.raw):
            self.report_masked(line, f"{s.kind} left in the job: anyone who gets this job can read it", s.start + 1)
        self._machine_password(line)

    def _machine_password(self, line: Line) -> None:
        for start, _ in _machine_passwords(line.raw):
            self.report_masked(
                line,
                "machine password in M551 (RepRapFirmware's password for the web interface, FTP and Telnet): anyone"
                " who gets this job can read it",
                start + 1,
            )


# RepRapFirmware M551 P"password" (research/firmware_codes.md section 6: M551 password); an old-style
# unquoted value runs to the end of the command.
_M551 = re.compile(
    r"""(?i)(?<![A-Za-z0-9])M0{0,4}+551(?![\d.])[^;\r\n]{0,300}?(?<![A-Za-z0-9'])P[ \t]{0,4}+("((?:[^"\r\n]|""){0,256}+)"|[^\s;"]{1,256}+)"""
)


def _machine_passwords(text: str) -> list[tuple[int, int]]:
    """The spans of M551 password values in ``text`` (empty values are no secret)."""
    if "551" not in text:
        return []
    out = []
    for m in _M551.finditer(text):
        if m.group(2) is not None:
            if m.group(2):
                out.append((m.start(2), m.end(2)))
        else:
            out.append((m.start(1), m.end(1)))
    return out


def _mask_machine_password(text: str) -> str:
    """``text`` with each M551 password replaced by ``*`` (secrets.mask does not know M551)."""
    spans = _machine_passwords(text)
    for start, end in reversed(spans):
        text = text[:start] + "*" * (end - start) + text[end:]
    return text


# -- network services ----------------------------------------------------------------------------------------

# RepRapFirmware src/Networking/NetworkDefs.h: HttpProtocol = 0, FtpProtocol = 1, TelnetProtocol = 2,
# MulticastDiscoveryProtocol = 3, MqttProtocol = 4 (M586 P); S1 enables, S0 disables
# (research/firmware_codes.md section 6: M586 network protocols).
_PROTOCOLS = {
    0: "HTTP (the web interface: files, configuration, any G-code)",
    1: "FTP (read and write access to the SD card)",
    2: "Telnet (a G-code console)",
    3: "multicast discovery",
    4: "MQTT",
}


@register
class OpensNetworkService(_SecurityRule):
    code = "SC007"
    name = "opens-network-service"
    severity = Severity.ERROR
    summary = "The job switches on a network service of the printer (RepRapFirmware M586: HTTP, FTP, Telnet)"
    explanation = """
        RepRapFirmware's "M586 P<protocol> S1" switches on a network service: P0 the web interface (HTTP),
        P1 FTP, P2 Telnet.  FTP reads and writes every file on the SD card and Telnet is a G-code console,
        both protected only by the M551 password (if one is set).  A job that turns them on leaves the
        machine open to anyone on its network after the print.  The network belongs in the printer's
        configuration: M586 in a `.g` file right in a RepRapFirmware `sys/` folder (config.g and the files
        it runs, checked as RepRapFirmware) is not reported; a job placed in such a folder is.  Switching a service off (S0) is not reported.
    """
    example_bad = "M586 P2 S1"
    example_good = "M586 P2 S0"
    source = (
        "research/firmware_codes.md section 6 (M586 network protocols); RepRapFirmware src/Networking/NetworkDefs.h"
        " (protocol numbers: 0 HTTP, 1 FTP, 2 Telnet)"
    )
    codes = ("M586",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.configuration = ctx.dialect.name == "reprap" and _reprap_system_file(ctx.path)

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if self.configuration or not _starts_line(line, cmd):
            return
        if cmd is not None and cmd.words:
            protocol, state = cmd.raw("P"), cmd.raw("S")
        else:
            argument = _strip_comment(rest)
            m_p = re.search(r"(?i)P[ \t]*+(\S+)", argument)
            m_s = re.search(r"(?i)S[ \t]*+(\S+)", argument)
            protocol, state = (m_p.group(1) if m_p else None), (m_s.group(1) if m_s else None)
        if state is None or (_NUMBER.fullmatch(state) and float(state) == 0):
            return
        number = int(float(protocol)) if protocol is not None and _NUMBER.fullmatch(protocol) else None
        what = _PROTOCOLS.get(number, f"network protocol P{protocol}") if number is not None else "a network service"
        self.report_masked(
            line,
            f"M586 switches on {what}: anyone on the printer's network can reach the machine through it after this job",
            column,
        )


def _quote(text: str, limit: int = 80) -> str:
    return '"' + (text[:limit] + "..." if len(text) > limit else text) + '"'


def _excerpt(text: str, limit: int = 60) -> str:
    text = _strip_comment(text)
    if not text:
        return ""
    return f" ({text[:limit]}{'...' if len(text) > limit else ''})"
