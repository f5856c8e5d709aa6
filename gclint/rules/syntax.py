"""SX: syntax and structure.  The parser finds the problems (syntax/build.py, larkparse.py); these rules
name them, document them and check what needs more than one line (N numbers, checksums)."""

from __future__ import annotations

from gclint import secrets
from gclint.rules.base import Edit, Rule, Severity, register
from gclint.syntax.nodes import Line


class _IssueRule(Rule):
    """Reports the parser's issues that carry this rule's code."""

    on_issue = True

    def check_issues(self, line: Line) -> None:
        for issue in line.issues:
            if issue.code == self.code:
                severity = Severity.parse(issue.severity) if issue.severity else None
                self.report(line, issue.message, column=issue.column, severity=severity)


@register
class ParseError(_IssueRule):
    code = "SX001"
    name = "parse-error"
    severity = Severity.ERROR
    summary = "The line is not valid G-code in any dialect gclint knows"
    explanation = """
        The grammar (gclint/grammar.lark) could not read the line: an unexpected character, a bracket
        that is never closed, a G or M word without a number, a checksum in the middle of the line.
        Firmware reacts to such lines in different ways: some skip them, some stop the job, some read
        part of the line and silently ignore the rest.
    """
    example_bad = "G1 X10 Y20 )"
    example_good = "G1 X10 Y20"
    source = "grammar.lark"


@register
class DuplicateWord(_IssueRule):
    code = "SX002"
    name = "duplicate-word"
    severity = Severity.ERROR
    summary = "The same parameter letter appears twice in one command"
    explanation = """
        "G1 X10 X20" is ambiguous: firmware keeps either the first or the last value, and LinuxCNC
        refuses the line ("Multiple X words on one line").  Write each letter once.  A letter repeated
        with the same value ("G0 X0 Y0 X0") is only a warning: every firmware gets the same value.
    """
    example_bad = "G1 X10 Y5 X20"
    example_good = "G1 X20 Y5"
    source = 'LinuxCNC source, src/emc/rs274ngc/interp_read.cc ("Multiple X words on one line")'

    def check_issues(self, line: Line) -> None:
        """As the parser says, except from a password on: an unquoted password is read as words ("M551
        Ppassword": p, a, s, s...), and naming the repeated letters would spell it out."""
        starts: list[int] | None = None
        for issue in line.issues:
            if issue.code != self.code:
                continue
            message = issue.message
            if starts is None:
                starts = [s.start + 1 for s in secrets.find(line.raw)] if secrets.may_hold(line.raw) else []
            if starts:
                cmd = max((c for c in line.commands if c.column <= issue.column), key=lambda c: c.column, default=None)
                first = cmd.column if cmd is not None else 1
                if any(first <= start <= issue.column for start in starts):
                    message = f"a letter is repeated in {cmd.code if cmd is not None and cmd.code else 'this block'}"
                    message += " after a password (the letter is not named: it may be one of the password's)"
            severity = Severity.parse(issue.severity) if issue.severity else None
            self.report(line, message, column=issue.column, severity=severity)


@register
class LineNumberSequence(Rule):
    code = "SX003"
    name = "line-number-sequence"
    severity = Severity.WARNING
    summary = "On checksummed lines, an N line number that is not the previous one plus one"
    explanation = """
        Under the RepRap host protocol (lines with a *checksum) each N must be the previous one plus one,
        or the firmware asks for a resend ("Line Number is not Last Line Number+1").  M110 sets the next
        number.  On lines without a checksum N is a label: LinuxCNC says line numbers "may be repeated or
        used out of order, although normal practice is to avoid such usage" (G-code overview, "Optional
        Line Number"), and a printer reading a file from its card does not count them, so their order is
        not reported.
    """
    example_bad = "N10 G1 X1 F600*0\nN12 G1 X2*81"
    example_good = "N10 G1 X1 F600*0\nN11 G1 X1*81"
    source = (
        'Marlin source, Marlin/src/gcode/queue.cpp (STR_ERR_LINE_NO: "Line Number is not Last Line Number+1"); '
        "LinuxCNC G-code overview, Optional Line Number"
    )
    on_numbered = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.last: float | None = None

    def check_line(self, line: Line) -> None:
        word = line.parsed.line_number
        if word is None:
            return
        value = word.number
        if value is None:
            return
        commands = line.parsed.commands
        if commands and commands[0].code == "M110":  # "N<n> M110 N<m>": the next line is N<m+1>
            reset = commands[0].get("N")
            self.last = reset if reset is not None else value
            return
        last = self.last
        self.last = value
        if last is None:
            return
        if line.parsed.checksum is not None and value != last + 1:
            self.report(line, f"N{_n(value)} follows N{_n(last)}: checksummed lines must count up by one", node=word)


@register
class ChecksumMismatch(Rule):
    code = "SX004"
    name = "checksum-mismatch"
    severity = Severity.ERROR
    summary = "The *checksum does not match the line"
    explanation = """
        Under the RepRap host protocol the number after "*" is the XOR of every byte before it.  A
        wrong checksum makes the firmware reject the line and ask for a resend; in a file it means the
        line was edited after the checksums were written.
    """
    example_bad = "N8 G1 X3.0 Y3.0*30"
    example_good = "N8 G1 X3.0 Y3.0*33"
    source = "Marlin queue.cpp, RepRap G-code page (checksums)"
    on_numbered = True
    fixable = True
    fix_applicability = "unsafe"

    def check_line(self, line: Line) -> None:
        checksum = line.parsed.checksum
        if checksum is None:
            return
        expected = compute_checksum(line.raw[: checksum.column - 1])
        actual = checksum.value
        if actual is None:
            return  # reported by SX001
        if actual != expected:
            from gclint.rules.base import Fix

            # Unsafe: a wrong checksum is how a host finds a line damaged in transfer; recomputing it would
            # bless the damage.  Only the user knows the line's words are what they meant.
            start = checksum.column
            fix = Fix(
                f"set the checksum to {expected}",
                (Edit(line.number, start, checksum.end_column, f"*{expected}"),),
                safe=False,
            )
            self.report(line, f"checksum is {actual}, the line's bytes give {expected}", node=checksum, fix=fix)


def compute_checksum(text: str) -> int:
    """XOR of the bytes of ``text`` (the part of a line before ``*``)."""
    value = 0
    for byte in text.encode("utf-8", "surrogateescape"):
        value ^= byte
    return value


def with_checksum(line: Line, edits: list[Edit]) -> list[Edit]:
    """``edits`` (of one line, before its ``*`` checksum) and, when the line's checksum was right, the edit
    that recomputes it over the edited text: a fix must not turn a good line into a damaged one (SX004).
    A wrong checksum is left as it is (SX004 reports it; recomputing it would bless the damage)."""
    checksum = line.parsed.checksum
    if checksum is None or not edits:
        return edits
    text = line.raw[: checksum.column - 1]
    if checksum.value != compute_checksum(text) or any(e.end > checksum.column for e in edits):
        return edits
    for e in sorted(edits, key=lambda e: e.start, reverse=True):
        text = text[: e.start - 1] + e.text + text[e.end - 1 :]
    return [*edits, Edit(line.number, checksum.column, checksum.end_column, f"*{compute_checksum(text)}")]


@register
class UnclosedComment(_IssueRule):
    code = "SX005"
    name = "unclosed-comment"
    severity = Severity.ERROR
    summary = "A comment opened with '(' is not closed on the same line"
    explanation = """
        Parenthesised comments end at ")" on the same line.  LinuxCNC refuses an unclosed comment;
        printers that accept "(" comments may swallow the rest of the line, or the next one.
    """
    example_bad = "G0 X10 (move to the clamp"
    example_good = "G0 X10 (move to the clamp)"
    source = "LinuxCNC rs274ngc errors: Unclosed comment found"


@register
class InvalidNumber(_IssueRule):
    code = "SX006"
    name = "invalid-number"
    severity = Severity.ERROR
    summary = "A word's value is not a number"
    explanation = """
        G-code numbers are an optional sign, digits and at most one decimal point.  "X1.2.3", "X--1"
        or "X-" are read differently by every firmware (often as 0 or as the first valid prefix), so
        the move goes somewhere nobody intended.
    """
    example_bad = "G1 X1.2.3 Y4"
    example_good = "G1 X1.23 Y4"
    source = "RepRap G-code page (fields)"


@register
class StrayValue(_IssueRule):
    code = "SX007"
    name = "stray-value"
    severity = Severity.WARNING
    summary = "A number with no word letter (firmware ignores it)"
    explanation = """
        "G1 0.200 F10000" has a number that belongs to no letter: firmware skips it, so whatever it
        was meant to be (usually a Z height whose "Z" got lost) does not happen.
    """
    example_bad = "G1 0.200 F10000"
    example_good = "G1 Z0.200 F10000"
    source = "RepRap G-code page (fields)"

    def check_issues(self, line: Line) -> None:
        # (one finding a line, at its first stray value: a firmware's own "U0.00 0.00 0.00 ..." is one mistake)
        strays = [issue for issue in line.issues if issue.code == self.code]
        if strays:
            more = f" (and {len(strays) - 1} more on this line)" if len(strays) > 1 else ""
            self.report(line, strays[0].message + more, column=strays[0].column)


@register
class UnusedNoqa(Rule):
    code = "SX008"
    name = "unused-noqa"
    severity = Severity.WARNING
    default_enabled = False  # opt in, as ruff's RUF100: --extend-select SX008
    summary = "A noqa comment that suppresses nothing (the finding it was for is gone)"
    explanation = """
        A `; noqa: HY003` stays in a job after the mistake it silenced was fixed, or names a rule that
        does not report that line; then it silences the next real finding there without anyone deciding
        so.  The rule reports each code of a `noqa` comment that suppressed nothing on its line (a bare
        `noqa` that suppressed nothing too).  Security findings (SC) are never silenced by a job, so a
        `noqa: SC...` is always unused.  Off by default: select it with `--extend-select SX008`, as ruff's
        RUF100.  A `noqa` or `gclint: disable` that names a code no rule has is an error (exit 2).
    """
    example_bad = "; gclint-test: select=SX008\nG1 X10 Y10 F1200 ; noqa: SX002"
    example_good = "; gclint-test: select=SX002,SX008\nG1 X10 X20 F1200 ; noqa: SX002"
    source = "gclint's suppression comments (README, Rules); ruff RUF100"
    codes = ()  # reported by the engine once every finding of the file is known


def _n(value: float) -> str:
    return str(int(value)) if value == int(value) else str(value)
