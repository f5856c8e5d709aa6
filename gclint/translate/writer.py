"""Writing the current line: replace, remove or consume a command, add lines before or after it, and
report TR findings on it (repeated findings are counted, not listed).

A mixin of ``HyrelTranslator``: the edits of one source line gather in a ``LineEdit`` (output.py), which
renders the output lines; a line with no edit is copied byte for byte.
"""

from __future__ import annotations

from gclint.rules.base import Finding, Severity
from gclint.rules.translation import TR_NAME, TR_SEVERITY
from gclint.syntax.nodes import ASSIGNMENT, GCODE, IMPLICIT, META, OWORD, TEXT, Command
from gclint.translate.findings import TR_UNTRANSLATABLE
from gclint.translate.mixin import Aspects, TranslatorMixin
from gclint.translate.output import LineEdit

ANY = frozenset(("*",))


class LineWriter(TranslatorMixin):
    """The edit operations on the line being translated (``line``, command ``index``)."""

    def _edit(self) -> LineEdit:
        edit = self.edit
        if edit is None:
            edit = self.edit = LineEdit(self.line)  # type: ignore[arg-type]
        return edit

    def replace(self, cmd: Command, text: str, note: str | None = None) -> None:
        """Write ``text`` instead of the command."""
        edit = self._edit()
        edit.replaced[self.index] = text
        edit.changed = True
        if note:
            edit.notes.append(note)

    def remove(self, cmd: Command, code: str, reason: str, *, key: object = None, aspects: Aspects = None) -> None:
        """Drop the command, with a finding."""
        self.consume(cmd)
        self.report(
            code,
            f"{_show(cmd)}: {reason}",
            key=key if key is not None else (cmd.code, reason),
            cmd=cmd,
            aspects=aspects,
        )

    def consume(self, cmd: Command, note: str | None = None) -> None:
        """Drop the command without a finding: its meaning is carried elsewhere (a tool prepared for M6,
        an S word that sets the next M3's speed) or a finding was already reported."""
        edit = self._edit()
        edit.replaced[self.index] = ""
        edit.changed = True
        if note:
            edit.notes.append(note)

    def untranslatable(self, cmd: Command, reason: str, *, key: object = None, aspects: Aspects = None) -> None:
        self.remove(cmd, TR_UNTRANSLATABLE, reason, key=key, aspects=aspects)

    def before(self, *texts: str, note: str) -> None:
        """Insert lines before the current line; ``note`` says why (``--annotate`` writes it on each)."""
        edit = self._edit()
        if self.annotate:
            texts = tuple(f"{t} ; gclint: added ({note})" for t in texts)
        edit.before.extend(texts)

    def after(self, *texts: str, note: str, first: bool = False) -> None:
        """Insert lines after the current line (``first``: before the lines already added after it)."""
        edit = self._edit()
        if self.annotate:
            texts = tuple(f"{t} ; gclint: added ({note})" for t in texts)
        if first:
            edit.after[:0] = texts
        else:
            edit.after.extend(texts)

    def report(
        self, code: str, message: str, *, key: object = None, cmd: Command | None = None, aspects: Aspects = None
    ) -> None:
        """A TR finding on the current line; repeated findings (same code and key) are counted, not listed.

        ``aspects``: what of the job the loss touches, as the meaning diff names them (trace.ASPECTS):
        a warning-level finding explains a difference ``gclint diff`` finds in one of them.  Default: any
        ("*"); ``()`` for a loss the diff does not model (acceleration, levelling...)."""
        line = self.line
        assert line is not None and self.result is not None
        edit = self._edit()
        edit.notes.append(f"{code} {message}")
        severity = TR_SEVERITY[code]
        if severity >= Severity.WARNING:
            if aspects is None:
                touched = ANY
            elif isinstance(aspects, str):
                touched = frozenset((aspects,))
            else:
                touched = frozenset(aspects)
            if touched:
                self.result.record(code, touched, line.number)
        k = (code, key if key is not None else message)
        entry = self._aggregate.get(k)
        if entry is not None:
            entry[1] += 1
            return
        finding = Finding(
            path=self.result.path,
            line=line.number,
            column=cmd.column if cmd is not None else 1,
            code=code,
            severity=severity,
            message=message,
            name=TR_NAME[code],
            source=line.raw,
        )
        self.result.findings.append(finding)
        self._aggregate[k] = [finding, 1]


def _show(cmd: Command) -> str:
    """A short name for messages: the code, or the kind of construct."""
    if cmd.kind in (GCODE, TEXT):
        return cmd.code or "?"
    if cmd.kind == IMPLICIT:
        return "motion words"
    if cmd.kind == META:
        return f"'{cmd.code}'"
    if cmd.kind in (OWORD, ASSIGNMENT):
        return "O-word" if cmd.kind == OWORD else "# parameter"
    return cmd.code or cmd.kind
