"""The engine's per-code dispatch (``Linter._run``'s ``build``): which rules a command reaches, and when."""

from __future__ import annotations

from gclint.dialects.base import Dialect
from gclint.engine import Linter, Options
from gclint.rules.base import Rule
from gclint.syntax.nodes import IMPLICIT, Command, Line


class _UnknownCodes(Rule):
    """A rule on the commands the dialect does not have, filtered by letters per code as HY008 is
    (``code[:1]``: ``trigger_letters`` takes a code)."""

    code = "ZZ901"
    name = "unknown-codes-by-letter"
    on_unknown_code = True

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        return None if code[:1] == "T" else frozenset("Q")

    def check(self, line: Line, cmd: Command) -> None:
        self.report(line, f"unknown: {cmd.kind} {cmd.code}", node=cmd)


def test_a_command_with_no_code_reaches_an_unknown_code_rule_without_letters(monkeypatch):
    """Words with no G/M/T code (``X2 Y3``) reach the rules on unknown codes when the dialect does not take
    them.  Such a command has no code to ask ``trigger_letters`` about: every such rule looks at it (the
    engine asks only for a command with a code; asking with None raised a TypeError out of the check)."""
    accepts = Dialect.accepts
    monkeypatch.setattr(Dialect, "accepts", lambda self, kind, code: kind != IMPLICIT and accepts(self, kind, code))
    linter = Linter(Options(dialect="marlin"))
    linter.rule_classes = [_UnknownCodes]
    result = linter.check_text("G1 X1 F600\nX2 Y3\nM104 S200\n")
    assert result.error is None
    assert [(f.line, f.message) for f in result.findings] == [(2, "unknown: implicit None")]
