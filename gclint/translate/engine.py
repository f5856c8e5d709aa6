"""The translation engine.  A ``Translator`` for a dialect pair turns each source line into zero or more
output lines; the identity translator (same dialect on both sides) keeps every line as it is.  Which
translator serves which pair is pairs.py's business (``translator_for``); this module knows none of them,
so the translators can import it without a cycle."""

from __future__ import annotations

import re
from array import array
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field

from gclint.dialects.base import Dialect
from gclint.rules.base import Finding
from gclint.syntax.fastpath import PLAIN_MOVE
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source


class UnsupportedPair(Exception):
    """No translator exists for this pair of dialects (yet)."""


@dataclass
class TranslationResult:
    """Findings (TR codes) and counts gathered while translating one file.

    ``occurrences`` keeps every line a warning-level finding was made on (findings repeat; the list of
    findings shows the first), by (code, aspects): the aspects of the job the loss touches, as the meaning
    diff names them (gclint/simulate/trace.py ASPECTS; "*" for any).  ``gclint diff`` explains its
    differences with them."""

    path: str
    source_dialect: str
    target_dialect: str
    findings: list[Finding] = field(default_factory=list)
    lines_in: int = 0
    lines_changed: int = 0
    occurrences: dict[tuple[str, frozenset[str]], array] = field(default_factory=dict)
    refused: bool = False  # the output would run a program on the host (HostActionGuard): write nothing

    def record(self, code: str, aspects: frozenset[str], line: int) -> None:
        lines = self.occurrences.get((code, aspects))
        if lines is None:
            lines = self.occurrences[(code, aspects)] = array("l")
        if not lines or lines[-1] != line:
            lines.append(line)


class Translator:
    """Identity translator; subclasses override ``translate_line`` (and ``header``/``footer``)."""

    def __init__(self, source: Dialect, target: Dialect, options=None) -> None:
        self.source = source
        self.target = target
        self.options = options

    def read_job(self, source: Source) -> None:
        """Before the first line: what the job's own settings say (its slicer's ``; key = value`` lines)."""

    def start(self, result: TranslationResult) -> Iterator[str]:
        return iter(())

    def mark(self) -> str | None:
        """The first line of the output, or None: what it is written in, said so that whoever reads it next (gclint
        check, the pre-commit hook) reads it as that, not as the firmware its kept comments name
        (``;FLAVOR:Marlin``).  Only a translation from another dialect says it (a v4 <-> v5 renumbering keeps
        the job's own lines, and a round trip gives back the job byte for byte)."""
        return None

    def translate_line(self, line: Line, result: TranslationResult) -> Iterable[str]:
        yield line.render()

    def finish(self, result: TranslationResult) -> Iterator[str]:
        return iter(())

    def plain_route(self) -> PlainMove | None:
        """A function that takes a plain move (``syntax.fastpath.PLAIN_MOVE``: a G0/G1 with only X Y Z E F
        numbers) without its tree and says whether it leaves the line unchanged (True; it has then
        applied it to its state), or None when every line must go through ``translate_line``.  The
        identity keeps every line."""
        return _keep if type(self).translate_line is Translator.translate_line else None


# (is G1, line number, X, Y, Z, E, F as source texts or None, line ending) -> the line is kept unchanged
PlainMove = Callable[[bool, int, "str | None", "str | None", "str | None", "str | None", "str | None", str], bool]


def _keep(g1: bool, number: int, x, y, z, e, f, ending: str) -> bool:
    return True


def translate_source(source: Source, translator: Translator, result: TranslationResult) -> Iterator[str]:
    """Yield the translated text of ``source`` (line endings included), one piece per chunk of source
    lines, so that writers encode and write a few large strings instead of one per line.

    Every piece passes ``HostActionGuard``: a written line that Repetrel would run as a program (SHELL in
    the text of M0/M1/M792) is an error finding, and the writers (translate/cli.py) then write nothing."""
    guard = HostActionGuard(result)
    for text in _translate(source, translator, result):
        guard.check(text)
        yield text


def _translate(source: Source, translator: Translator, result: TranslationResult) -> Iterator[str]:
    translator.read_job(source)
    yield from translator.start(result)
    mark = translator.mark()
    number = 0
    translate = translator.translate_line
    plain = translator.plain_route()  # plain moves the translator keeps as they are skip the tree
    plain_match = PLAIN_MOVE.fullmatch
    for chunk in source.chunks():
        parts: list[str] = []
        extend = parts.extend
        for raw, ending in chunk:
            number += 1
            if mark is not None:  # (with the first line's ending: a CRLF job stays CRLF)
                extend((mark, ending or "\n"))
                mark = None
            if plain is not None and raw[:1] == "G" and len(raw) <= 100:  # longer lines: Translator._fit
                m = plain_match(raw)
                if m is not None:
                    digit, f_first, x, y, z, e, f = m.groups()
                    if plain(digit == "1", number, x, y, z, e, f if f is not None else f_first, ending):
                        extend((raw, ending))
                        continue
            extend(translate(Line(number, raw, ending, parse_line(raw)), result))
        if parts:
            yield "".join(parts)
    result.lines_in = number
    yield from translator.finish(result)


# An M0, M1 or M792 anywhere in a piece of output: only those lines are parsed again by the guard.
_ACTION_CODE = re.compile(r"[Mm][ \t]*+(?:0*+(?:1|792)|0++)(?![\d.])")
_LINE_BREAK = re.compile(r"\r\n?|\n")  # the line endings gclint reads (syntax/source.py)
# ... or a character some firmware edits the line with before reading it (a backspace, a Unicode space or
# lookalike letter: security.firmware_views), which can make an M0/M792 of a line that shows none
_UNUSUAL = re.compile(r"[^\t\n\r\x20-\x7e]")


def _may_act(text: str) -> bool:
    return _ACTION_CODE.search(text) is not None or _UNUSUAL.search(text) is not None


class HostActionGuard:
    """Checks what a translation writes: no line may carry a Repetrel host action that runs a program
    (SHELL in the text of M0/M1/M792, as SC001 reads it).  The translators remove such text from the
    pauses they write (TR009); the guard catches what they keep as it is, a Hyrel source's own
    ``M0 ; SHELL ...`` (the identity and the v4/v5 renumbering copy lines), and anything a translator
    might get wrong.  A line it finds is a TR009 error finding: ``translate`` then writes nothing."""

    def __init__(self, result: TranslationResult) -> None:
        self.result = result
        self.lines = 0  # output lines before the current piece

    def check(self, text: str) -> None:
        if not _may_act(text):
            self.lines += text.count("\n") + text.count("\r") - text.count("\r\n")
            return
        from gclint.rules.security import action_shell_column

        pieces = _LINE_BREAK.split(text)
        for index, raw in enumerate(pieces):
            if _may_act(raw):
                column = action_shell_column(Line(self.lines + index + 1, raw, "", parse_line(raw)))
                if column is not None:
                    self.refuse(self.lines + index + 1, column)
        self.lines += len(pieces) - 1

    def refuse(self, number: int, column: int) -> None:
        from gclint.rules.base import Severity
        from gclint.rules.translation import TR_NAME

        self.result.refused = True
        if any(f.code == "TR009" and f.severity == Severity.ERROR for f in self.result.findings):
            return  # one is enough: nothing is written
        self.result.findings.append(
            Finding(
                self.result.path,
                number,
                column,
                "TR009",
                Severity.ERROR,
                f"output line {number} would make Repetrel run a program (SHELL after M0/M1/M792, see SC001):"
                " the translation is refused and nothing is written",
                name=TR_NAME["TR009"],
            )
        )
