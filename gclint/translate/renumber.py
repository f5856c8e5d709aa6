"""Hyrel v4 <-> v5: renumber T variables (and the few T commands that differ); nothing else changes.

v4 T variables are CAN device addresses, v5 has one address table (T_v4 and T_v5 pages, Hyrel v4 firmware source;
gclint/dialects/addressing.py, docs/sources.md).  Only the certain part of the map is used (V4_TO_V5_VARIABLE and its
inverse): 11-15 -> 0-4, 21-25 -> 5-9, 41 -> 21, 26 -> 20, 91/92 -> 24/25, and the wildcards 0 -> 40,
10/20 -> 41/42, 100 -> 47, 90 -> 46.  T commands (tool numbers) are 0-9 in both; v4's special tool
numbers 11-14 (laser, spindle, beds) become 21, 20, 24, 25.  A number with no certain counterpart stays
as it is and is reported (TR006); where the v4 map infers one (the aux port, v4 T16 / tool
T10 -> v5 Aux1 T22, rated "medium"; yokes 3 and 4; groups), the finding names it and says the map is
uncertain there.  Edits touch the T value only, so spacing,
comments and everything else stay byte for byte and v4 -> v5 -> v4 gives the file back.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator

from gclint.context.decide import DIRECTIVE_LINE
from gclint.dialects.addressing import (
    SQUAD_CODES,
    V4_TO_V5_COMMAND,
    V4_TO_V5_COMMAND_INFERRED,
    V4_TO_V5_VARIABLE,
    V4_TO_V5_VARIABLE_INFERRED,
    V5_TO_V4_COMMAND,
    V5_TO_V4_COMMAND_INFERRED,
    V5_TO_V4_VARIABLE,
    V5_TO_V4_VARIABLE_INFERRED,
    renumberings,
)
from gclint.dialects.base import Dialect
from gclint.rules.base import Finding
from gclint.rules.translation import TR_NAME, TR_SEVERITY
from gclint.syntax.nodes import GCODE, Command, Line, Word
from gclint.syntax.parse import parse_line
from gclint.translate.engine import TranslationResult, Translator
from gclint.translate.output import LineEdit


class Renumber(Translator):
    """hyrel-v4 -> hyrel (``to_v5``) or hyrel -> hyrel-v4."""

    def __init__(self, source: Dialect, target: Dialect, options=None, *, count: bool = True) -> None:
        super().__init__(source, target, options)
        self.to_v5 = target.extras.get("firmware") == 5
        self.variables = V4_TO_V5_VARIABLE if self.to_v5 else V5_TO_V4_VARIABLE
        self.commands = V4_TO_V5_COMMAND if self.to_v5 else V5_TO_V4_COMMAND
        self.inferred_variables = V4_TO_V5_VARIABLE_INFERRED if self.to_v5 else V5_TO_V4_VARIABLE_INFERRED
        self.inferred_commands = V4_TO_V5_COMMAND_INFERRED if self.to_v5 else V5_TO_V4_COMMAND_INFERRED
        self.annotate = bool(getattr(options, "annotate", False))
        self.count = count
        self.default_ending = "\n"
        self._reported: dict[tuple, list] = {}

    def translate_line(self, line: Line, result: TranslationResult) -> Iterable[str]:
        if line.ending and self.default_ending != line.ending:
            self.default_ending = line.ending
        commands = line.parsed.commands
        directive = DIRECTIVE_LINE.match(line.raw) if "gclint" in line.raw else None
        if directive is not None and directive.group(1) != self.target.name:
            # ("; gclint: dialect=hyrel" names v5: the renumbered job names the version it is now written for)
            if self.count:
                result.lines_changed += 1
            raw = line.raw[: directive.start(1)] + self.target.name + line.raw[directive.end(1) :]
            return (raw + (line.ending or self.default_ending),)
        if not commands:
            return (line.raw + line.ending,)
        edit: LineEdit | None = None
        for index, cmd in enumerate(commands):
            if cmd.kind != GCODE or not cmd.code:
                continue
            new = self._command(cmd, line, result)
            if new is not None:
                if edit is None:
                    edit = LineEdit(line)
                edit.replaced[index] = new
                edit.changed = True
        if edit is None:
            return (line.raw + line.ending,)
        if self.count:
            result.lines_changed += 1
        if self.annotate:
            edit.notes.append(f"{'v4 -> v5' if self.to_v5 else 'v5 -> v4'} addresses, was '{line.raw.strip()}'")
        return iter(edit.render(self.annotate, self.default_ending))

    def finish(self, result: TranslationResult) -> Iterator[str]:
        for finding, count in self._reported.values():
            if count > 1:
                finding.message += f" ({count} lines like this; the first is shown)"
        return iter(())

    # -- one command -------------------------------------------------------------------------------------

    def _command(self, cmd: Command, line: Line, result: TranslationResult) -> str | None:
        code = cmd.code or ""
        target = "v5" if self.to_v5 else "v4"
        if code in SQUAD_CODES and "S" not in cmd.params:
            self._report(
                line,
                cmd,
                result,
                f"{code} without S has no certain {target} form "
                "(v5 needs a squad or a head in S); T renumbered, the rest left as it is",
                (code, "noS"),
            )
        changes: dict = {}
        for r in renumberings(cmd, self.to_v5):
            number = r.number
            if r.new is None:
                if r.tool_command:
                    message = (
                        f"T{number} (tool number) has no certain {target} counterpart"
                        f"{self._likely('T', number, self.inferred_commands)}; left unchanged"
                    )
                    key: tuple = ("cmd", number)
                else:
                    what = "alias/squad" if r.letter == "S" else "address"
                    message = (
                        f"{code} {r.letter}{number}: this {what} has no certain {target} counterpart"
                        f"{self._likely(r.letter, number, self.inferred_variables)}; left unchanged"
                    )
                    key = (code, r.letter, number)
                self._report(line, cmd, result, message, key)
            elif r.changes:
                changes[r.node] = r.text()
        if not changes:
            return None
        return _splice(line, cmd, changes)

    def _likely(self, letter: str, number: int, inferred: dict[int, int]) -> str:
        """Where the v4 map infers a counterpart: say which, and that the map is uncertain there."""
        likely = inferred.get(number)
        if likely is None:
            return ""
        source, target = ("v4", "v5") if self.to_v5 else ("v5", "v4")
        return (
            f" (the v4 -> v5 map is uncertain here: {source} {letter}{number} is most likely {target} "
            f"{letter}{likely}, inferred, not documented (docs/sources.md, Hyrel v4 addressing); check it by hand)"
        )

    def _report(self, line: Line, cmd: Command, result: TranslationResult, message: str, key: tuple) -> None:
        entry = self._reported.get(key)
        if entry is not None:
            entry[1] += 1
            return
        finding = Finding(
            path=result.path,
            line=line.number,
            column=cmd.column,
            code="TR006",
            severity=TR_SEVERITY["TR006"],
            message=message,
            name=TR_NAME["TR006"],
            source=line.raw,
        )
        result.findings.append(finding)
        self._reported[key] = [finding, 1]


def _splice(line: Line, cmd: Command, changes: dict) -> str:
    """The command's source text with some of its words (or its code word) replaced, all else as it was."""
    nodes = [n for n in cmd.nodes()]
    start = cmd.column
    end = max(n.end_column for n in nodes) if nodes else start
    text = line.raw[start - 1 : end - 1]
    for node in sorted(changes, key=lambda n: n.column, reverse=True):
        a = node.column - start
        b = node.end_column - start
        text = text[:a] + changes[node] + text[b:]
    return text


class Chain(Translator):
    """Two translators in a row (Marlin -> v5, then v5 -> v4): the first one's output lines are parsed
    again and handed to the second, findings are kept with the source line numbers."""

    def __init__(self, first: Translator, second: Translator) -> None:
        super().__init__(first.source, second.target, first.options)
        self.first = first
        self.second = second
        self._number = 0

    def mark(self) -> str | None:
        mark = self.first.mark()
        return (
            None if mark is None else mark.replace(f"dialect={self.first.target.name}", f"dialect={self.target.name}")
        )

    def start(self, result: TranslationResult) -> Iterator[str]:
        yield from self._pipe(self.first.start(result), result)
        yield from self.second.start(result)

    def translate_line(self, line: Line, result: TranslationResult) -> Iterable[str]:
        self._number = line.number
        return self._pipe(self.first.translate_line(line, result), result)

    def finish(self, result: TranslationResult) -> Iterator[str]:
        yield from self._pipe(self.first.finish(result), result)
        yield from self.second.finish(result)

    def _pipe(self, texts, result: TranslationResult) -> Iterator[str]:
        second = self.second
        number = self._number
        for text in texts:
            for m in _LINE.finditer(text):
                raw, ending = m.group(1), m.group(2)
                if not raw and not ending:
                    continue
                yield from second.translate_line(Line(number, raw, ending, parse_line(raw)), result)


_LINE = re.compile(r"([^\r\n]*)(\r\n|\r|\n|$)")

_ = Word
