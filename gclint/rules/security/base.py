"""The base of the SC rules: what they listen to, and reading the firmwares' views of a line."""

from __future__ import annotations

from typing import ClassVar

from gclint import secrets
from gclint.rules.base import Rule, Severity
from gclint.rules.security import linuxcnc
from gclint.rules.security.common import _LEADING_CODE, _LEADING_NAME, _code, _mask_machine_password, _quote
from gclint.rules.security.views import (
    _VIEW_TRIGGER,
    DROPPED_VIEW,
    ERASED_VIEW,
    INVISIBLE_VIEW,
    SEGMENT_LIMIT,
    _views_of,
)
from gclint.syntax.nodes import Command, Comment, Line
from gclint.syntax.parse import parse_line


class _SecurityRule(Rule):
    """Listens to ``codes`` on parsed lines and, on lines with a parse error, to the code that starts the line.

    Subclasses implement ``inspect(line, code, rest, column, cmd)``: ``rest`` is the line's text after the
    code word (comments included), ``column`` the 1-based column where ``rest`` starts, ``cmd`` the parsed
    command or None.  A command's ``rest`` holds the text of every command after it on the line, so each
    code a rule listens to is inspected once per line, at its first command (a line of 30,000 "M0" is read
    once, not 30,000 times: linear time); the rules read only the first command of a line or the whole text
    after a code, so nothing is missed.

    A rule with ``active_comments`` (keys of ``linuxcnc.FILE_WRITES`` or ``linuxcnc.CODE_RUNS``) reports
    the LinuxCNC/Machinekit comments among them, in every comment and on lines the grammar refused.
    """

    active_comments: ClassVar[dict[str, str]] = {}

    on_issue = True
    # the views whose lines are read whole too (check_line): those where a firmware may drop characters
    # before the first one (SC003: "\x01rm /sd/config.txt"); not Smoothieware's own split, which keeps them
    LINE_VIEWS = frozenset({ERASED_VIEW, DROPPED_VIEW, INVISIBLE_VIEW})
    # the engine calls check_view for lines this finds (gclint/engine.py)
    on_line_matching = _VIEW_TRIGGER
    # the engine calls check_joined for lines after ones that end in a bare carriage return (LinuxCNC reads them
    # as one line)
    on_bare_cr = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._view: tuple[str, Line, int] | None = None  # (how, the line as written, offset) while reading a view
        self._line: Line | None = None  # the line (or view) whose commands are being inspected
        self._inspected: set[str] = set()  # the codes inspected on it

    def check(self, line: Line, cmd: Command) -> None:
        code = cmd.code or ""
        if line is not self._line:
            self._line = line
            self._inspected = set()
        elif code in self._inspected:
            return  # (its text is part of the text read after the first command of its code)
        self._inspected.add(code)
        word = cmd.word
        start = word.end_column if word is not None else cmd.column
        self.inspect(line, code, line.raw[start - 1 :], start, cmd)

    def check_issues(self, line: Line) -> None:
        if self.active_comments and line.parsed.kind == "error":
            # (the grammar gave up on the line, so its comments were not read: LinuxCNC may read them)
            for column, body in linuxcnc.comments_in(line.raw):
                self._active_comment(line, body, column)
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

    def check_comment(self, line: Line, comment: Comment) -> None:
        if linuxcnc.ACTIVE.match(comment.body) is not None:  # (most comments: one test in C)
            self._active_comment(line, comment.body, comment.column)

    def _active_comment(self, line: Line, body: str, column: int) -> None:
        found = linuxcnc.active_comment(body)
        if found is None or found[0] not in self.active_comments:
            return
        keyword, argument = found
        what = self.active_comments[keyword]
        if "{target}" in what and not argument:
            return  # (no file name, no text, no code: nothing is opened, written or run)
        self.report_masked(line, f"{linuxcnc.shown(keyword)} {what.format(target=_quote(argument))}", column)

    def check_view(self, line: Line) -> None:
        """Read ``line`` as each firmware that edits it first reads it (``firmware_views``), reporting on
        ``line`` with the reading named.  A line with more than SEGMENT_LIMIT different M codes after its
        first command (Smoothieware runs each) is one finding of each SC rule, for the rest: each, since
        ``per-file-ignores`` may switch some of them off."""
        views, more = _views_of(line)
        if more:
            self.report(
                line,
                f"this line holds more than {SEGMENT_LIMIT:,} commands after its first, and a firmware runs each of"
                " them (Smoothieware splits a line at each G and M, RepRapFirmware at each NUL, Prusa's SD reader at"
                f" each '#'): the security rules read the first {SEGMENT_LIMIT:,} and not the rest; split the line",
                column=1,
                severity=Severity.ERROR,
            )
        for how, view, offset in views:
            self._read_view(line, how, view, offset)

    def check_joined(self, line: Line, text: str, first: int) -> None:
        """Read lines ``first`` to ``line`` as LinuxCNC/Machinekit reads them: one line, since only a line feed
        ends a line for it (interp_read.cc ``read_text`` reads with C's ``fgets``) and the lines before
        ``line`` end in a bare carriage return; ``text`` is their text joined by those carriage returns.
        (The engine calls this: ``on_bare_cr``.)"""
        view = linuxcnc.read_as_one_line(text)
        how = f"{linuxcnc.JOINED_VIEW} (lines {first}-{line.number})"
        self._read_view(line, how, Line(line.number, view, line.ending, parse_line(view)), 0, comments=True)

    def _read_view(self, line: Line, how: str, view: Line, offset: int, comments: bool = False) -> None:
        self._view = (how, line, offset)
        try:
            parsed = view.parsed
            for cmd in parsed.commands:
                if cmd.code in self.codes:
                    self.check(view, cmd)
            for comment in parsed.comments if comments and self.active_comments else ():
                self.check_comment(view, comment)
            if parsed.issues and self.on_issue:
                self.check_issues(view)
            if how in self.LINE_VIEWS and self.on_line_starting_with and view.raw[:1] in self.on_line_starting_with:
                self.check_line(view)
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
