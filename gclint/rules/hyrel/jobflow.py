"""HY job-flow rules: the end of the job (M30), line length, M0/M792 actions, the aux ports.

Sources: the Hyrel Gcode page, "Other Commands" (M30 End of Program, M792 Execute Action), "M0 Stop
Until Resume" and "Controlling Aux Devices" (M7, M8, M670-M689), the hidden-codes page Sekret! (M673);
see docs/sources.md.
"""

from __future__ import annotations

import re

from gclint.dialects.base import Param
from gclint.machine.profiles import PROFILES
from gclint.machine.state import EVALUES
from gclint.noqa import NOQA
from gclint.rules.base import ANY_T, Rule, Severity, register
from gclint.rules.dialect import ParamTableRule
from gclint.rules.hyrel.addressing import int_value
from gclint.rules.security import ACTIONS, host_actions, shell_offsets
from gclint.syntax.build import exponents, written_out
from gclint.syntax.nodes import GCODE, Command, Line

# -- HY009 ---------------------------------------------------------------------------------------------


@register
class CodeAfterM30(Rule):
    code = "HY009"
    name = "code-after-m30"
    severity = Severity.ERROR
    summary = "Commands after M30: they are not run as part of the job"
    explanation = """
        "M30 tells the printer that this job is complete.  No gocde after an M30 will be executed as part
        of the previous job."  Whatever follows (a cool-down, a park move, M104 T0 S0, a second part)
        is not run with the job, and M30 has already reset the state it relies on (M229, M106 range,
        M660 registers, clone squads, fixture offsets; HY056).  Move those lines before M30.  Comments
        and blank lines after M30 are fine.  Reported once per M30, at the first command after it.
    """
    example_bad = """
        G1 X10 E1 F600
        M30
        M104 T0 S0
    """
    example_good = """
        G1 X10 E1 F600
        M104 T0 S0
        M30
    """
    source = "Gcode page, M30 End of Program"
    families = ("hyrel",)
    on_line_after_m30 = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.reported_for: int | None = None  # the M30 already reported

    def check_line(self, line: Line) -> None:
        st = self.state
        if st.after_m30 and line.parsed.commands and st.m30_line != self.reported_for:
            self.reported_for = st.m30_line
            cmd = line.parsed.commands[0]
            what = cmd.code or "this line"
            self.report(
                line,
                f"{what} comes after M30 (line {st.m30_line}): 'No gcode after an M30 will be executed "
                "as part of the previous job'",
                node=cmd,
            )


# -- HY010 ---------------------------------------------------------------------------------------------


@register
class MissingM30(Rule):
    code = "HY010"
    name = "missing-m30"
    severity = Severity.WARNING
    summary = "A job that moves but never ends with M30"
    explanation = """
        "M30 tells the printer that this job is complete."  It also dissolves clone squads, clears the
        fixture offsets, the M229 E-value mode, the M106 range and the M660 registers, resets the heads
        to their stored values and triggers the queued reports (M772).  A job without M30 leaves all of
        that in place for the next job and never reports its end.  Files without any move (settings
        snippets) are not reported.
    """
    example_bad = "G1 X10 E1 F600"
    example_good = """
        G1 X10 E1 F600
        M30
    """
    source = "Gcode page, M30 End of Program"
    families = ("hyrel",)

    def finish(self) -> None:
        st = self.state
        if st.m30_line is None and st.moved and st.line_number > 0:
            self.report(
                st.line_number,
                "the job has no M30 at the end: Repetrel does not see the job as complete, and "
                "its settings (M229, M106 range, M660, squads, fixture offsets) carry over",
            )


# -- HY029 ---------------------------------------------------------------------------------------------

_LIMIT = 100  # "Note that all lines will be truncated at 100 characters." (M0 Stop Until Resume)
_QUOTED = 60  # at most this many characters of what is cut are quoted (a line may be 99,000 long)


def _quoted(text: str) -> str:
    """``text`` for a message: whole when short, else its start and its length."""
    if len(text) <= _QUOTED:
        return text
    return f"{text[:_QUOTED].rstrip()}... ({len(text):,} characters)"


def _outside_comments(line: Line) -> str:
    """The text after column 100 that is not in a comment (blanks between words included)."""
    raw = line.raw
    tail = list(raw[_LIMIT:])
    for comment in line.parsed.comments:
        start = max(comment.column - 1, _LIMIT)
        end = comment.column - 1 + len(comment.text)
        if end > start:
            tail[start - _LIMIT : end - _LIMIT] = " " * (end - start)
    return "".join(tail).strip()


@register
class LineOver100Characters(Rule):
    code = "HY029"
    name = "line-over-100-characters"
    severity = Severity.WARNING
    summary = "A line longer than 100 characters: Repetrel truncates it (info when only comment text is cut)"
    explanation = """
        The M0 section says "Note that all lines will be truncated at 100 characters."  Whether "all
        lines" means the M0/M792 text or every line of the file is not clear, so gclint takes it as
        written (gclint's reading of the page): a longer line loses what follows column 100.  A warning
        when that is part of a command (a word, a parameter, a checksum) or the text of an M0/M792
        (its message or action: what the printer says or does); info when it is only comment text,
        which changes nothing the printer does (a slicer profile's banner comment, Hyrel's own among
        them).  The message says what is cut, quoting at most 60 characters of it.  As with ruff's
        E501, a line whose text up to a trailing `noqa` comment fits is not reported.
    """
    example_bad = (
        "M0 ; SAY "
        + "Please remove the part from the bed and load the next sheet, then press Play to go on."
        + " Thank you"
    )
    example_good = "M0 ; SAY Remove the part, load the next sheet, press Play"
    source = (
        "Gcode page, M0 Stop Until Resume ('all lines will be truncated at 100 characters'; gclint reads it as "
        "every line)"
    )
    families = ("hyrel",)
    on_line_longer_than = _LIMIT

    def check_line(self, line: Line) -> None:
        raw = line.raw
        if len(raw) <= _LIMIT or not raw[_LIMIT:].strip():
            return  # (only blanks after column 100: nothing is lost)
        parsed = line.parsed
        says = any(cmd.code in ("M0", "M792") for cmd in parsed.commands)  # (their comment is their text)
        if not says:
            pragma = NOQA.search(raw)
            at = pragma.start() if pragma is not None else -1
            if pragma is not None and raw[at] == ";" and len(raw[:at].rstrip()) <= _LIMIT:  # (";" runs to the end)
                return
        lost_words = []
        for cmd in parsed.commands:
            if cmd.word is not None and cmd.word.end_column > _LIMIT + 1:
                lost_words.append(cmd.word.text.strip())
            if cmd.code not in ("M0", "M792"):
                lost_words.extend(w.text.strip() for w in cmd.words if w.end_column > _LIMIT + 1)
        severity = None
        if lost_words:
            detail = f"the command loses {_quoted(' '.join(lost_words))}"
        elif (outside := _outside_comments(line)) != "":
            detail = f"'{_quoted(outside)}' is cut"
        elif says:
            detail = "the M0/M792 text (message or action) is cut"
        else:
            severity = Severity.INFO  # "the comment is cut" changes nothing the printer does
            detail = "only comment text is cut, which changes nothing the printer does"
        self.report(
            line,
            f"line is {len(raw):,} characters long; Repetrel truncates lines at {_LIMIT}: {detail}",
            column=_LIMIT + 1,
            severity=severity,
        )


# -- HY043 ---------------------------------------------------------------------------------------------

_MODEL_AUX = sorted(set().union(*(p.aux_codes for p in PROFILES.values())), key=lambda c: int(c[1:]))


@register
class AuxPortNotOnModel(Rule):
    code = "HY043"
    name = "aux-port-not-on-model"
    severity = Severity.WARNING
    summary = "An aux-port code (M671-M685) that the printer model does not have"
    explanation = """
        Several aux ports exist on some models only: M671 danger lights and M679 vacuum "(30M/ESR
        only)", M675 response LEDs "(30M/16A only)", M676 recirculation fan, M684 exhaust and M685 air
        "(16A only)", M677 buzzer "(older 30Ms only)", M678 laser cross-hair "(16A with CO2 lasers
        only)".  On another model the port is not there and the command does nothing.  Choose the
        printer with `--printer` (default 30m).
    """
    example_bad = """
        ; gclint-test: printer=30m
        M676 S100
    """
    example_good = """
        ; gclint-test: printer=30m
        M679 S100
    """
    source = "Gcode page, Controlling Aux Devices (M671-M689)"
    codes = tuple(_MODEL_AUX)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        profile = self.ctx.profile
        code = cmd.code
        if not self.ctx.on_every_model(lambda p: code not in p.aux_codes):
            return
        spec = self.ctx.dialect.spec(cmd.code)  # type: ignore[arg-type]
        what = spec.summary if spec is not None else cmd.code
        models = ", ".join(p.name for p in PROFILES.values() if cmd.code in p.aux_codes)
        self.report(
            line,
            f"{cmd.code} ({what}) is not on {profile.a} (it is on: {models}){self.ctx.model_note()}",
            node=cmd,
        )


# -- HY044 ---------------------------------------------------------------------------------------------

_DEFAULT_100 = ("M7", "M8")  # "With no parameters, it is read as M7 S100"


@register
class AuxPercentRange(ParamTableRule):
    code = "HY044"
    name = "aux-percent-range"
    severity = Severity.WARNING
    summary = "An aux-port percentage outside 0-100, or an aux command without S (no change)"
    explanation = """
        The aux ports take "Sn is the percentage (0-100)": M7 and M8 ("default is 100"), the lights,
        fans and air of M670-M689 ("0-100; no default - if no Sn, no change").  A larger value (a 0-255
        duty from another firmware) is outside what the page gives, and the pages do not say what it does
        (warning); M670-M689 without S change nothing (info).
        The ranges are data in gclint/dialects/hyrel.py (`rule="HY044"`).
    """
    example_bad = "M7 S255"
    example_good = "M7 S100"
    source = "Gcode page, Controlling Aux Devices (M7, M8, M670-M689); hidden codes, M673"
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        super().check(line, cmd)
        if cmd.params.get("S") is None and cmd.code not in _DEFAULT_100:
            self.report(
                line,
                f"{cmd.code} without a value for S changes nothing ('no default - if no Sn, no change')",
                node=cmd,
                severity=Severity.INFO,
            )

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"{cmd.code}: {problem}: S is a percentage 0-100"


# -- HY056 ---------------------------------------------------------------------------------------------

_FIXTURES = tuple(f"G{n}" for n in range(54, 60))


@register
class StateAssumedAcrossM30(Rule):
    code = "HY056"
    name = "state-assumed-across-m30"
    severity = Severity.WARNING
    summary = "Lines after M30 rely on settings that M30 reset (M106 range, M229 E1, focused head, fixture offsets)"
    explanation = """
        "M30 also dissolves any cloning setups, changes head index to 0, clears fixture offsets (G53),
        clears any M229 E-value settings, resets M106 persistent range, ... resets M660 head offsets to
        0".  In a file with more than one job (lines after M30, see HY009), the next job must set these
        again: an M106 S after M30 is read on the 0-100 range (S255 becomes "255 %"), printing without a
        new M229 E1 ignores the E amounts, printing without a T command uses head T0, and fixture
        offsets are gone.  (M660 registers: HY034; clone squads: HY048.)
    """
    example_bad = """
        M106 C255
        M106 T0 S255
        M30
        M106 T0 S128
    """
    example_good = """
        M106 C255
        M106 T0 S255
        M30
        M106 C255
        M106 T0 S128
    """
    source = "Gcode page, M30 End of Program; T_v5, M702 (an M30 decommissions any clone squads)"
    codes = ("M30", "M106", "M229", ANY_T, *_FIXTURES)
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.m30: Line | None = None
        self.assumed: dict[str, str] = {}  # kind -> what M30 reset
        self.again: dict[str, int] = {}  # kind -> first line that set it again after the M30
        self.fixture_line: int | None = None
        self.fan_warned = False

    def check(self, line: Line, cmd: Command) -> None:
        code = cmd.code
        st = self.state
        if code == "M30":
            self._settle()
            self.m30 = line
            self.assumed = {}
            if st.fan_range != 100.0:
                self.assumed["fan"] = f"M106 C{st.fan_range:g} (line {st.fan_range_line})"
            if st.flow_mode == EVALUES:
                self.assumed["evalues"] = f"M229 E1 (line {st.m229_line})"
            if st.tool not in (None, 0):
                self.assumed["tool"] = f"the focus on T{st.tool} (line {st.tool_line})"
            if st.fixture_offsets_active:
                self.assumed["fixture"] = f"the fixture offsets (line {self.fixture_line})"
            self.again = {}
            self.fan_warned = False
            return
        if code in _FIXTURES:
            self.fixture_line = line.number
            self.again.setdefault("fixture", line.number)
        elif code == "M229":
            if int_value(cmd.params.get("E")) == 1:
                self.again.setdefault("evalues", line.number)
        elif code == "M106":
            if "C" in cmd.params:
                self.again.setdefault("fan", line.number)
            elif "fan" in self.assumed and "fan" not in self.again and not self.fan_warned and "S" in cmd.params:
                self.fan_warned = True
                self.report(
                    line,
                    f"M106 S after M30 (line {self.m30.number}) is read on the default 0-100 range: M30 "  # type: ignore[union-attr]
                    f"reset {self.assumed['fan']}; repeat the M106 C",
                    node=cmd.param("S") or cmd,
                )
        elif self.m30 is not None and cmd.code and cmd.code[0] == "T":
            self.again.setdefault("tool", line.number)

    def finish(self) -> None:
        self._settle()

    def _settle(self) -> None:
        m30, self.m30 = self.m30, None
        printed = self.state.first_print_since_m30_line
        if m30 is None or printed is None:
            return
        lost = [
            what
            for kind, what in self.assumed.items()
            if kind != "fan" and (self.again.get(kind) is None or self.again[kind] > printed)
        ]
        if lost:
            self.report(
                m30,
                f"printing resumes at line {printed} after this M30, which reset {', '.join(lost)}; set "
                "them again before printing",
                node=m30.commands[0] if m30.commands else None,
            )


# -- HY059 ---------------------------------------------------------------------------------------------


@register
class M0UnknownAction(Rule):
    code = "HY059"
    name = "m0-unknown-action"
    severity = Severity.INFO
    summary = "Text after ';' on M0/M792 that is not one of the actions SAY, PIC, VID, SEND, BEEP, SHELL"
    explanation = """
        M0 and M792 take actions after a semicolon, one per segment: "M0 ; SAY Hello Wilbur ; PIC
        C:\\mr_ed.png" (SAY, PIC, VID, SEND, BEEP, SHELL).  Other text is not one of the documented
        actions: M0 shows it on the print mask ("All text following the ; will be echoed to the print
        mask"); the Gcode page does not say what M792 does with it.  A misspelt action (SPEAK, BEEEP) may be
        silently lost.  Info only.  Text that holds SHELL anywhere is not reported here: it is a security
        finding (SC001), since nothing says Repetrel will not run it.  Actions are read as the SC rules
        read them (gclint/rules/security/actions.py: any case, without invisible characters, after punctuation).
    """
    example_bad = "M792 ; SPEAK Hello Wilbur"
    example_good = "M792 ; SAY Hello Wilbur"
    source = "Gcode page, M0 Stop Until Resume and M792 Execute Action"
    codes = ("M0", "M792")
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        comment = next((c for c in line.parsed.comments if c.style == ";" and c.column > cmd.column), None)
        if comment is None:
            return
        offset = comment.column + 1  # the column of the text after the ';'
        for segment in comment.body.split(";"):
            stripped = segment.lstrip(" \t")
            column = offset + len(segment) - len(stripped)
            offset += len(segment) + 1
            if not stripped.strip():
                continue
            first = stripped.split(None, 1)[0]
            if host_actions(stripped) or shell_offsets(stripped) or first.lower().startswith(("noqa", "gclint")):
                continue
            if cmd.code == "M0":
                message = (
                    f"M0 shows '{stripped.strip()[:40]}' on the print mask; '{first}' is not an action "
                    f"({', '.join(ACTIONS)})"
                )
            else:
                message = (
                    f"M792: '{first}' is not one of the actions ({', '.join(ACTIONS)}); the Gcode page does not "
                    "say what M792 does with other text"
                )
            self.report(line, message, column=column)
            return


# -- HY066 ---------------------------------------------------------------------------------------------


@register
class CommandsRunTogether(Rule):
    code = "HY066"
    name = "commands-run-together"
    severity = Severity.WARNING
    summary = "A command written straight after the word before it (G1 Z20G1 X60): two commands on one line"
    explanation = """
        `G1 Z20G1 X60 Y40` holds two commands with no blank between them, as where a line break was
        lost.  gclint reads it as the grammar does, `G1 Z20` and then `G1 X60 Y40`; every example on the
        Hyrel pages writes one command a line, and the pages do not say how Repetrel reads a second
        command (as two moves, as a parameter of the first, or not at all).  Put each command on a
        line of its own.  (Commands separated by a blank, `G21 G90`, are not reported.)
    """
    example_bad = "G1 Z20G1 X60 Y40 F1200"
    example_good = """
        G1 Z20 F1200
        G1 X60 Y40
    """
    source = "Gcode page, the Usage and Example of every code (one command a line)"
    families = ("hyrel",)
    # a G, M or T code right after a number (what the grammar reads as a second command); the check reads
    # the line to leave out comments and parameters
    on_line_matching = re.compile(r"(?m)[0-9.][GgMmTt][0-9]")

    def check_view(self, line: Line) -> None:
        raw = line.raw
        parsed = line.parsed
        commands = parsed.commands
        ends = [c.column for c in commands[1:]] + [min((c.column for c in parsed.comments), default=len(raw) + 1)]
        for index, (previous, cmd) in enumerate(zip(commands, commands[1:], strict=False)):
            word = cmd.word
            if cmd.kind != GCODE or word is None or word.column < 2:
                continue
            before = raw[word.column - 2]
            if before.isalnum() or before == ".":
                last = previous.words[-1] if previous.words else previous.word
                start = last.column if last is not None else word.column - 1
                joined = raw[start - 1 : word.end_column - 1].strip()
                first = raw[previous.column - 1 : cmd.column - 1].strip()
                second = raw[cmd.column - 1 : ends[index + 1] - 1].strip()
                self.report(
                    line,
                    f"{cmd.code} runs into the word before it ({_quoted(joined)}): two commands on one line, as if a "
                    f"line break was lost; gclint reads '{_quoted(first)}' and then '{_quoted(second)}', and the "
                    "Hyrel pages (one command a line) do not say how Repetrel reads it: put each command on its "
                    "own line",
                    node=cmd,
                )


# -- HY067 ---------------------------------------------------------------------------------------------


@register
class ExponentNotation(Rule):
    code = "HY067"
    name = "exponent-notation"
    severity = Severity.WARNING
    summary = "A number in exponent notation (F1.875e+06): the Hyrel pages do not say how Repetrel reads it"
    explanation = """
        Some generators print large or small numbers in exponent notation: `F1.875e+06` for a feed of
        1,875,000 mm/min, `X1e-05`.  Every number on the Hyrel pages is a plain decimal, and the pages do
        not say how Repetrel reads an exponent.  gclint reads the line as G-code words are read: the
        number ends at the `e`, and `e+06` is an E word of its own, so `G1 X10 F1.875e+06` is a move at
        F1.875 with an E (which on Hyrel makes it a printing move), and an `E2` later on the line is a
        second E (SX002).  `gclint explain` reads it the same way and says so.  Whatever Repetrel makes
        of it, the line does not say one thing: write the number out (`F1875000`).  (RepRapFirmware reads
        `C7.06e-8` as one number, so the rule is Hyrel's only.)
    """
    example_bad = "G1 X10 F1.875e+06"
    example_good = "G1 X10 F1875000"
    source = "Gcode page, every Usage and Example (numbers are plain decimals); grammar.lark (the E word)"
    families = ("hyrel",)
    # a number straight before an e or E and a digit (the words are read to leave out comments and strings)
    on_line_matching = re.compile(r"(?m)[0-9.][eE][-+]?[0-9]")

    def check_view(self, line: Line) -> None:
        for cmd in line.parsed.commands:
            for word, _, number in exponents(cmd):
                self.report(line, exponent_message(number), node=word)


def exponent_message(number: str) -> str:
    """What HY067 (and ``gclint explain``) say of a number in exponent notation (``F1.875e+06``)."""
    exponent = number[max(number.rfind("e"), number.rfind("E")) :]
    return (
        f"{number} is exponent notation: gclint reads {number[: -len(exponent)]} and then an E word {exponent}, and "
        f"the Hyrel pages, whose numbers are plain decimals, do not say how Repetrel reads it; write the number "
        f"out: {written_out(number)}"
    )
