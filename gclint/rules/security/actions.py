"""SC001, SC002: Repetrel host actions (Hyrel M0 / M1 / M792 text)."""

from __future__ import annotations

import re
import unicodedata

from gclint.rules.base import Severity, register
from gclint.rules.security import linuxcnc
from gclint.rules.security.base import _SecurityRule
from gclint.rules.security.common import _code, _excerpt, _quote
from gclint.rules.security.views import _VIEW_TRIGGER, firmware_views
from gclint.syntax.nodes import GCODE, Command, Line
from gclint.syntax.parse import parse_line

# -- Repetrel host actions (Hyrel M0 / M792) ------------------------------------------------------------

# The actions the Gcode page lists for M0 and M792: "M0 [ SAY | PIC | VID | SEND | BEEP | SHELL ]".
ACTIONS = ("SAY", "PIC", "VID", "SEND", "BEEP", "SHELL")
# The codes whose text Repetrel reads as actions (Gcode page, M0 Stop Until Resume and M792 Execute Action),
# and M1, which the Hyrel pages do not list but gclint's translator writes as M0 (translate/marlin.py,
# translate/reprap.py); what Repetrel does with text after M1 is not documented, so it is read the same way.
ACTION_CODES = ("M0", "M1", "M792")
# Codes gclint's translator writes as Hyrel's pause M0 (translate/: Marlin and RepRapFirmware M600/M601
# filament change, M25 pause, RepRapFirmware M226 and M291 S2/S3, Machinekit M226, Carvera M600 and an M6 tool
# change with no --tool-map).  Text on them becomes text after M0 when the job is translated to Hyrel.
# tests/test_security_review.py checks this list against the translators.
PAUSE_CODES = ("M6", "M25", "M226", "M291", "M600", "M601")

# Characters a program comparing text can skip (.NET's culture-aware comparison ignores U+00AD, for one), or
# that a reader does not see between two letters: control characters other than tab, Unicode's
# default-ignorable code points (soft hyphen, combining grapheme joiner, zero-width spaces and joiners,
# bidirectional marks, invisible operators, variation selectors, the BOM, tag characters, the Hangul
# fillers U+115F, U+1160, U+3164, U+FFA0...), and fillers that print as nothing or as a stretch of the line
# (Arabic tatweel U+0640, NKo lajanyalan U+07FA, the blank Braille pattern U+2800); and bytes that are not
# UTF-8 (lone surrogates: syntax/source.py), which a reader may drop or read as C1 controls (Latin-1):
# "SH\xadELL", "SH\x8aELL", a CESU-8 surrogate "SH\xed\xa0\x80ELL".
_IGNORABLE = (
    "\x00-\x08\x0a-\x1f\x7f-\x9f\udc80-\udcff\u00ad\u034f\u061c\u0640\u07fa\u115f\u1160\u17b4\u17b5\u180b-\u180f"
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


def _excerpt_name(name: str) -> str:
    """A subroutine name as a message shows it: at most 60 characters."""
    return name if len(name) <= 60 else name[:57] + "..."


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


_SHELLS_PER_LINE = 9  # SHELL actions of a line reported one by one, the rest as one finding (filecontext.PER_LINE - 1)


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
# An action or pause code anywhere in a line the grammar refused ("!! M792 ; SHELL C:\\x.exe"): what a
# reader that skips what it cannot read may run.
_CODE_ANYWHERE = re.compile(r"[Mm][ \t]*+(\d++)(?!\.)")


def _codes_anywhere(raw: str, codes: tuple[str, ...]) -> list[tuple[str, int]]:
    """The first place each of ``codes`` appears in ``raw``, as ``(code, where its text starts)``: the text
    after the first one holds the text after every later one."""
    found: dict[str, int] = {}
    for m in _CODE_ANYWHERE.finditer(raw):
        digits = m.group(1).lstrip("0")
        code = _code("M", digits) if len(digits) <= 4 else ""  # ("M000000792": leading zeros are zeros)
        if code in codes and code not in found:
            found[code] = m.end()
            if len(found) == len(codes):
                break
    return list(found.items())


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
    summary = (
        "The job makes the host computer run a program (SHELL in M0/M1/M792 text, Klipper RUN_SHELL_COMMAND,"
        " LinuxCNC (PY,...), (PYRUN,...), (PYRELOAD))"
    )
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
        Hangul fillers, bytes that are not UTF-8), and in letters that look like its own: full-width and
        mathematical forms, small capitals, Cyrillic and Greek lookalikes ("ЅНЕLL"); also in the line read
        as Windows-1252, as a Windows program may read it.  A line the grammar refuses ("!! M792 ; SHELL
        x") is searched whole for these codes.  M1 is not on the Hyrel
        pages; gclint's translator writes it as M0, so it is read the same way.  The same holds for the
        codes gclint's translator turns into Hyrel's pause M0 (M600, M601, M25, M226, M291, M6 on Carvera and
        Machinekit): text on them is text after M0 once the job is translated ("gclint translate" removes
        it, TR009, but another tool may not).  A comment that names a shell mill on a tool change is
        reported too: reword it.

        LinuxCNC and Machinekit run Python from a job's comments when their Python plugin is set up
        (interp_convert.cc convert_comment; "Executing Python statements from the interpreter" in the
        remap documentation): "(PY,code)", "(PYRUN,code)", ";py,code" and "(PYRELOAD)", in any case, after
        leading blanks.  They are reported in every dialect.
    """
    example_bad = "M792 ; SHELL C:\\program.exe"
    example_good = "M792 ; BEEP"
    source = (
        "Gcode page, M0 Stop Until Resume and M792 Execute Action"
        " (SHELL C:\\program.exe - the computer will execute the file); Klipper RUN_SHELL_COMMAND"
        " (gcode_shell_command); gclint/translate (codes written as M0); LinuxCNC"
        " src/emc/rs274ngc/interp_convert.cc convert_comment, interp_read.cc read_semicolon (;py,),"
        ' docs/src/remap/remap.adoc "Executing Python statements from the interpreter"'
    )
    codes = (*ACTION_CODES, *PAUSE_CODES, "RUN_SHELL_COMMAND", "O")
    on_comment = True  # (LinuxCNC's Python comments)
    comment_hint = staticmethod(linuxcnc.may_be_active)
    active_comments = linuxcnc.CODE_RUNS

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._reported = 0  # the last line reported (one command's text holds the next one's)

    def check_issues(self, line: Line) -> None:
        super().check_issues(line)
        if not any(c.code in self.codes for c in line.parsed.commands):
            for code, end in _codes_anywhere(line.raw, (*ACTION_CODES, *PAUSE_CODES)):
                self.inspect(line, code, line.raw[end:], end + 1, None)

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.code != "O":
            super().check(line, cmd)
            return
        # (every O-word of a line) A subroutine not defined in the job is looked for as a file, and LinuxCNC
        # hands its name to wordexp(3) with no flags first (rs274ngc_pre.cc find_ngc_file), which runs "$(...)"
        # and "`...`" through the shell: "o<$(reboot)> call" runs reboot.
        keyword, name = linuxcnc.oword(line.raw, cmd)
        if keyword == "call" and name is not None and linuxcnc.SHELL_EXPANSION.search(name):
            self.report_masked(
                line,
                f"o<{_excerpt_name(name)}> call: LinuxCNC/Machinekit pass the name of a subroutine the job does not"
                " define to the shell's word expansion to find its file, which runs the commands in $(...) and"
                " `...` and expands $VARIABLES on the machine's computer: a job file must not run programs",
                cmd.column,
            )

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
        for offset in offsets[:_SHELLS_PER_LINE]:
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
        if len(offsets) > _SHELLS_PER_LINE:  # (one finding for the rest: linear time on a line of 100,000)
            self.report_masked(
                line,
                f"{len(offsets) - _SHELLS_PER_LINE} more SHELL actions follow on this line, each making the host "
                "computer execute a program",
                column=column + offsets[_SHELLS_PER_LINE],
            )


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

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._reported: tuple[Line | None, set[int]] = (None, set())  # a line, and the columns reported on it

    def check_issues(self, line: Line) -> None:
        super().check_issues(line)
        if not any(c.code in self.codes for c in line.parsed.commands):
            for code, end in _codes_anywhere(line.raw, self.codes):
                self.inspect(line, code, line.raw[end:], end + 1, None)

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if self._reported[0] is not line:
            self._reported = (line, set())
        reported = self._reported[1]
        for keyword, argument, offset in host_actions(rest):
            if keyword in ("PIC", "VID") and column + offset not in reported:
                reported.add(column + offset)
                what = "image" if keyword == "PIC" else "video"
                target = f" {_quote(argument)}" if argument else ""
                self.report_masked(
                    line,
                    f"{code} {keyword} makes the host open the {what}{target} from its own disk",
                    column=column + offset,
                )
