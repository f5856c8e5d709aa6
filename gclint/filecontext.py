"""``FileContext``: the per-file world a rule sees (``self.ctx``): the dialect, the printer, the options,
the machine state and interpreter, and the findings with their bounds and suppressions.  The engine makes
one per file; ``gclint.rules.base`` names it only as a type."""

from __future__ import annotations

from array import array
from bisect import bisect_left, bisect_right
from collections.abc import Callable, Iterator
from typing import TypeVar

from gclint.context import Context
from gclint.dialects.base import Dialect
from gclint.machine.interpreter import Interpreter
from gclint.machine.profiles import PrinterProfile, get_profile
from gclint.machine.state import MachineState
from gclint.noqa import DIRECTIVE, INLINE_UNSUPPRESSIBLE, NOQA, may_direct, selectors
from gclint.options import Options
from gclint.rules.base import Finding, Fix, MoveListener, Rule, Severity, matches
from gclint.secrets import mask_quoted
from gclint.syntax.nodes import Line

# Findings stay bounded whatever the input (a 3 MB line of "X1" once gave a million findings and 1.1 GB):
# at most PER_LINE findings of one code are listed for one line and the rest are counted on the last one
# listed ("(and N more on this line)"; a few distinct findings on one line, such as one per head left on
# at M30, stay visible), at most MAX_FINDINGS are kept per file (later ones are counted on the last kept
# finding of their code), and a finding keeps at most SOURCE_LIMIT characters of its line for the reports.
PER_LINE = 10
MAX_FINDINGS = 20_000
SOURCE_LIMIT = 2048

_Listener = TypeVar("_Listener", bound=MoveListener)
_MAX_MERGED_EDITS = 64  # fixes merged into one finding (the rest is fixed by running --fix again)
_REMEMBERED_LINE = 1024  # comment lines longer than this are not remembered as "no directive"


class FileContext:
    """The per-file world a rule sees: dialect, printer, options, machine state, and the findings."""

    def __init__(
        self, path: str, dialect: Dialect, profile: PrinterProfile, options: Options, context: Context | None = None
    ) -> None:
        self.path = path
        self.dialect = dialect
        self.profile = profile
        self.options = options
        # what the file was read as; rules that rest on an assumed printer model say so (``model_note``)
        self.context = context if context is not None else Context(dialect.name, printer=profile.name)
        self.state = MachineState(loaded_heads=options.loaded)
        self.interpreter = Interpreter(dialect, self.state)
        self.findings: list[Finding] = []
        self._current: Line | None = None
        self.enabled_codes: frozenset[str] = frozenset()
        self.shared: dict[str, object] = {}  # objects several rules of this file share (by name)
        # the file's G0/G1 listeners (``move_listener``): the engine calls them for moves, in place of rules
        self.move_listeners: list[MoveListener] = []
        self.noqa = NoqaLines()  # line -> the codes its noqa names
        self.noqa_used: set[tuple[int, str]] = set()  # (line, selector) that suppressed a finding
        self.directives = Directives()  # (line, "disable" or "enable", codes), in line order
        self._directives_by_code: dict[str, list] = {}  # code (or ALL) -> [positions, disables, read, verdicts]
        self._plain_comments: set[str] = set()  # lines whose comments hold no noqa or gclint directive
        # code -> [its latest finding, that finding's own message, more on its line, more later in the file,
        #          findings of the code listed on that line]
        self._latest: dict[str, list] = {}

    def release(self) -> None:
        """Let go of what the file's rules share once they are done (calling their ``release``, if any): those
        objects hold the rules, which hold this context, a reference cycle that would keep the file's
        findings until the garbage collector's next full pass (the next file would be read with them still
        in memory); and of what only the rules' run needed (the comment lines remembered as plain, the latest
        finding of each code)."""
        for shared in self.shared.values():
            release = getattr(shared, "release", None)
            if release is not None:
                release()
        self.shared.clear()
        for listener in self.move_listeners:
            listener.release()
        self.move_listeners = []
        self._plain_comments.clear()
        self._latest.clear()

    def move_listener(self, kind: type[_Listener]) -> _Listener:
        """The file's G0/G1 listener of class ``kind``, made on first ask: the rules that ask for it share it,
        and the engine calls it for the file's moves (``rules.base.MoveListener``)."""
        for listener in self.move_listeners:
            if type(listener) is kind and isinstance(listener, kind):  # (isinstance: for the type checker)
                return listener
        made = kind(self)
        self.move_listeners.append(made)
        return made

    def enabled(self, code: str) -> bool:
        """Whether the rule ``code`` is selected for this run."""
        return code in self.enabled_codes

    def severity_of(self, code: str, default: Severity) -> Severity:
        """The level of a finding: the configuration's ``severity`` table (the longest matching code or
        prefix) overrides the rule's."""
        overrides = self.options.severity
        if overrides:
            for length in (5, 4, 3, 2):
                level = overrides.get(code[:length])
                if level is not None:
                    return Severity.parse(level)
        return default

    def model_note(self) -> str:
        """What a finding that rests on the printer model adds when nobody said which model it is."""
        return self.context.model_note()

    def on_every_model(self, test: Callable[[PrinterProfile], bool]) -> bool:
        """Whether ``test`` holds for every model the job fits (only the model itself when it was given or
        assumed by default): a finding that rests on the model is not made on a guess between models."""
        names = self.context.printer_candidates or (self.profile.name,)
        return all(test(get_profile(name)) for name in names)

    def add(
        self,
        rule: Rule | type[Rule],
        line: Line | int,
        column: int,
        message: str,
        *,
        fix: Fix | None = None,
        severity: Severity | None = None,
        end_column: int | None = None,
    ) -> None:
        if isinstance(line, Line):
            self.add_on(rule, line.number, line.raw, column, message, fix=fix, severity=severity, end_column=end_column)
        else:
            self.add_on(rule, line, None, column, message, fix=fix, severity=severity, end_column=end_column)

    def add_on(
        self,
        rule: Rule | type[Rule],
        number: int,
        raw: str | None,
        column: int,
        message: str,
        *,
        fix: Fix | None = None,
        severity: Severity | None = None,
        end_column: int | None = None,
        plain: bool = False,
    ) -> None:
        """``add`` for line ``number`` whose text is ``raw`` (None: not known); ``plain``: the line is of plain
        number words and the message quotes only them (nothing to mask: a finding on a line of a run)."""
        code = rule.code
        if (self.noqa.lines or self.directives.lines) and self.suppresses(code, number):
            return  # (not kept, so not counted against the bounds below)
        if severity is None:
            severity = rule.severity
        if self.options.severity:
            severity = self.severity_of(code, severity)
        latest = self._latest.get(code)
        same_line = latest is not None and latest[0].line == number
        if latest is not None and ((same_line and latest[4] >= PER_LINE) or len(self.findings) >= MAX_FINDINGS):
            self._count(latest, number, severity, fix)
            return
        if raw is not None:  # once, for every output and the cache: a rule may quote a secret word
            if not plain:
                message = mask_quoted(message, raw)
            if len(raw) > SOURCE_LIMIT:
                raw = raw[:SOURCE_LIMIT] + "..."
        # (path, line, column, code, severity, message, name, fix, end_column, source: positional, the hot path)
        finding = Finding(self.path, number, max(1, column), code, severity, message, rule.name, fix, end_column, raw)
        self.findings.append(finding)
        self._latest[code] = [finding, message, 0, 0, latest[4] + 1 if same_line else 1]  # type: ignore[index]

    def made_by(self, call: Callable[[], object]) -> list[tuple]:
        """The findings ``call`` makes, as (rule, column, message, fix, severity, end_column), not added."""
        made: list[tuple] = []

        def record(rule, line, column, message, *, fix=None, severity=None, end_column=None) -> None:
            made.append((rule, column, message, fix, severity, end_column))

        self.add = record  # type: ignore[method-assign]
        try:
            call()
        finally:
            del self.add
        return made

    @staticmethod
    def _count(latest: list, number: int, severity: Severity, fix: Fix | None) -> None:
        """Count a finding into the latest one of its code: "(and N more on this line)"."""
        kept: Finding = latest[0]
        if kept.line == number:
            latest[2] += 1
            if fix is not None and kept.fix is not None and len(kept.fix.edits) < _MAX_MERGED_EDITS:
                kept.fix = Fix(kept.fix.message, kept.fix.edits + fix.edits, kept.fix.safe and fix.safe)
        else:
            latest[3] += 1
        if severity > kept.severity:
            kept.severity = severity  # counting never lowers the worst severity (the exit code)
        message = latest[1]
        if latest[2]:
            message += f" (and {latest[2]:,} more on this line)"
        if latest[3]:
            message += f" (and {latest[3]:,} more {kept.code} findings later in the file, not listed)"
        kept.message = message

    # -- suppression ------------------------------------------------------------------------------------

    def read_directives(self, line: Line) -> None:
        raw = line.raw
        if raw in self._plain_comments:
            return
        found = False
        for comment in line.parsed.comments:
            body = comment.body
            if may_direct(body):
                found = True
                m = NOQA.search(body)
                if m:
                    self.noqa.add(line.number, selectors(m.group(1)))
                for d in DIRECTIVE.finditer(body):
                    self.directives.add(line.number, d.group(1).lower() == "disable", selectors(d.group(2)))
        if not found and len(raw) <= _REMEMBERED_LINE:
            # comment lines repeat (";TYPE:Perimeter"): remember the ones with no directive
            if len(self._plain_comments) >= 8192:
                self._plain_comments.clear()
            self._plain_comments.add(raw)

    def suppressed(self, finding: Finding) -> bool:
        return self.suppresses(finding.code, finding.line)

    def may_suppress(self) -> bool:
        """Whether the job has a noqa or a ``gclint: disable`` comment (else ``suppressed`` is always False)."""
        return bool(self.noqa.lines or self.directives.lines)

    def suppresses(self, code: str, number: int) -> bool:
        """Whether a finding of ``code`` on line ``number`` is suppressed by the job's comments (a noqa on
        the line, or the last ``gclint: disable``/``enable`` naming the code at or above it).  ``add`` asks
        as findings come, so that suppressed findings take no place under MAX_FINDINGS: 20,000 findings
        silenced by noqa must not make the next, unsilenced one a mere count on a suppressed one."""
        if code.startswith(INLINE_UNSUPPRESSIBLE):
            return False
        codes = self.noqa.get(number)
        if codes:
            used = [c for c in codes if c == "ALL" or code.startswith(c)]
            if used:
                self.noqa_used.update((number, c) for c in used)
                return True
        directives = self.directives
        if not directives:
            return False
        # the last disable/enable naming the code at or above the line decides: positions in the list of
        # directives, from an index of those naming ALL (shared by every code) and one per code of the
        # others, each extended as directives are read (time does not grow with directives x findings)
        before = bisect_right(directives.lines, number)
        if before == 0:
            return False
        best, disabling = -1, False
        for positions, flags in (self._all_index(), self._directive_index(code)):
            at = bisect_left(positions, before)
            if at > 0 and positions[at - 1] > best:
                best, disabling = positions[at - 1], bool(flags[at - 1])
        return disabling

    def _all_index(self) -> tuple[array, bytearray]:
        return self._extend("ALL", lambda codes: "ALL" in codes)

    def _directive_index(self, code: str) -> tuple[array, bytearray]:
        return self._extend(code, lambda codes: "ALL" not in codes and matches(code, codes))

    def _extend(self, key: str, applies: Callable[[tuple[str, ...]], bool]) -> tuple[array, bytearray]:
        """The positions of the directives ``applies`` to (and whether each disables), as far as read."""
        index = self._directives_by_code.get(key)
        if index is None:
            index = self._directives_by_code[key] = [array("q"), bytearray(), 0, {}]
        positions, flags, scanned, verdicts = index
        directives = self.directives
        if scanned < len(directives):
            sets, ids, disable = directives.sets, directives.ids, directives.disable
            for at in range(scanned, len(directives)):
                which = ids[at]
                verdict = verdicts.get(which)
                if verdict is None:
                    verdict = verdicts[which] = applies(sets[which])
                if verdict:
                    positions.append(at)
                    flags.append(disable[at])
            index[2] = len(directives)
        return positions, flags


class _Interned:
    """Distinct lists of codes, each kept once and named by its number (a job repeats the same few)."""

    def __init__(self) -> None:
        self.sets: list[tuple[str, ...]] = []
        self._ids: dict[tuple[str, ...], int] = {}

    def intern(self, codes: tuple[str, ...]) -> int:
        found = self._ids.get(codes)
        if found is None:
            found = self._ids[codes] = len(self.sets)
            self.sets.append(codes)
        return found


class NoqaLines(_Interned):
    """The ``noqa`` comments of a file: line number -> the codes named, as two arrays (the line numbers in
    order, and the number of the line's list of codes): 12 bytes a line, whatever the number of lines
    (a dict of tuples was ~100).  Reads like a read-only dict."""

    def __init__(self) -> None:
        super().__init__()
        self.lines = array("q")
        self.ids = array("l")

    def add(self, line: int, codes: tuple[str, ...]) -> None:
        lines = self.lines
        if lines and line <= lines[-1]:  # another comment on the same line (or, never in practice, out of order)
            at = bisect_left(lines, line)
            if at < len(lines) and lines[at] == line:
                self.ids[at] = self.intern(self.sets[self.ids[at]] + codes)
                return
            lines.insert(at, line)
            self.ids.insert(at, self.intern(codes))
            return
        lines.append(line)
        self.ids.append(self.intern(codes))

    def get(self, line: int, default: tuple[str, ...] | None = None) -> tuple[str, ...] | None:
        lines = self.lines
        at = bisect_left(lines, line)
        if at < len(lines) and lines[at] == line:
            return self.sets[self.ids[at]]
        return default

    def __getitem__(self, line: int) -> tuple[str, ...]:
        found = self.get(line)
        if found is None:
            raise KeyError(line)
        return found

    def __contains__(self, line: object) -> bool:
        return isinstance(line, int) and self.get(line) is not None

    def __len__(self) -> int:
        return len(self.lines)

    def __iter__(self) -> Iterator[int]:
        return iter(self.lines)

    def items(self) -> Iterator[tuple[int, tuple[str, ...]]]:
        """(line, codes) in line order."""
        sets = self.sets
        for line, which in zip(self.lines, self.ids, strict=True):
            yield line, sets[which]


class Directives(_Interned):
    """The ``gclint: disable`` / ``enable`` comments of a file, in line order, as arrays (line number,
    disable or not, the number of the list of codes).  Iterates as (line, "disable" or "enable", codes)."""

    def __init__(self) -> None:
        super().__init__()
        self.lines = array("q")
        self.disable = bytearray()
        self.ids = array("l")

    def add(self, line: int, disable: bool, codes: tuple[str, ...]) -> None:
        self.lines.append(line)
        self.disable.append(disable)
        self.ids.append(self.intern(codes))

    def __len__(self) -> int:
        return len(self.lines)

    def __iter__(self) -> Iterator[tuple[int, str, tuple[str, ...]]]:
        sets = self.sets
        for line, disable, which in zip(self.lines, self.disable, self.ids, strict=True):
            yield line, "disable" if disable else "enable", sets[which]
