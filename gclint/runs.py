"""Runs: the stretches of a job the engine applies at once instead of line by line.

Most of a sliced job is runs of plain moves, comment lines and empty lines (and arcs, where no rule
listens to them): ``fastpath.run_pattern`` finds them in a chunk's text, and ``Interpreter.plain_run``
applies a run with a few ``rfind`` calls.  A comment line of a run is read on its own when a directive, a
comment hook or a view hook may be about it (the run's comments are first tested together, joined by
line breaks: ``Rule.comment_hint`` and multi-line ``on_line_matching`` patterns promise that this is
safe).  Everything else, and a run the interpreter cannot apply at once, goes line by line to the
engine's loop.  tests/test_plain_moves.py checks that findings and state are the same either way.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Generator, Iterator
from operator import itemgetter

from gclint.machine.interpreter import Interpreter
from gclint.noqa import may_direct
from gclint.rules.base import MoveListener, RunFinding
from gclint.syntax.fastpath import RUN_CODE_LINE, forget_arcs, run_lines
from gclint.syntax.nodes import GCODE, Command
from gclint.syntax.source import Source, line_slices, split_lines

# (the starts of the lines of a run a rule may want, and its findings on lines it need not read: RunFinding)
RunFilter = Callable[[str, int, int], "list[int | RunFinding] | None"]
_COMMENT_LINES = re.compile(r"\n;[^\r\n]*+")  # (a literal start: searched fast)
_AGAIN = 1024  # (characters of a run first read line by line before trying again to apply it at once)
_WINDOW = 1 << 16  # (characters of a run the rules are asked about at once: their findings are held till then)
_CLEAN_LIMIT = 8192  # comment lines remembered as needing no reading (they repeat: ";WIDTH:0.45")
_QUIET_LONGEST = 1024  # (the longest comment line of a run remembered as needing no reading)
_TOGETHER = 4096  # (characters of a run's comment lines tested together before they are tested alone)
_ALONE = 4  # (comment lines that are tested alone rather than together first)


# A run shorter than this (in characters, a few lines) is read with the lines around it: applying a run costs
# more than reading several plain moves on their own (the engine's plain-move route), so a job that
# alternates a move and a G92 E0 or a commented move read 2-3x slower before this limit.
_SHORTEST_RUN = 256


class Runs:
    """How one file's runs are read.

    ``pattern``: the runs (``fastpath.run_pattern``, whose moves are never longer than ``longest``);
    ``tests``: what makes a comment line one to read on its own (each true of lines joined by line breaks
    when true of one of them, where ``together``); ``longest``: the shortest line a long-line hook wants
    (None: no such hook); ``every_comment``: every comment line is read (a hook on lines starting ";");
    ``alone``: the starts of the lines of a run to read on their own, the others being applied in bulk
    around them (None from it: read the run line by line for a while), and the findings the rules make on
    lines they need not read (``RunFinding``: ``add``, FileContext.add_on, adds them in line order);
    ``codes``: the M-code lines of runs to read on their own; see ``engine._FileRun.runs``.
    """

    def __init__(
        self,
        pattern: re.Pattern[str] | None,
        interpreter: Interpreter,
        tests: tuple[Callable[[str], object], ...],
        *,
        together: bool,
        every_comment: bool,
        longest: int | None,
        alone: RunFilter | None = None,
        codes: CodeLines | None = None,
        add: Callable[..., None],
    ) -> None:
        self.search = pattern.search if pattern is not None else None
        self.plain_run = interpreter.plain_run
        self.tests = tests
        self.together = together and not every_comment
        self.every_comment = every_comment
        self.longest = longest
        # (a comment line longer than ``longest``, after the line break before it; the pattern's moves are not)
        self.long_line = re.compile(rf"\n[^\r\n]{{{longest + 1}}}") if longest is not None else None
        self.alone = alone
        self.codes = codes
        self.add = add  # (FileContext.add_on: the rules' findings on the lines of runs, RunFinding)
        self.clean: set[str] = set()
        self.quiet: set[str] = set()  # (comment lines of runs that need no reading, each after its line break)
        self.total = 0  # lines read so far

    def lines(self, source: Source, may_apply: Callable[[], bool]) -> Iterator[tuple[int, list[tuple[str, str]]]]:
        """The lines of ``source`` to read one by one, as (number of the line before, lines); the runs in
        between are applied (while ``may_apply()``: no rule would look at their moves)."""
        search = self.search
        try:
            for block in source.blocks():
                if not isinstance(block, str):
                    yield self.total, block
                    self.total += len(block)
                    continue
                at = look = skip = 0
                while True:
                    run = search(block, look) if search is not None else None
                    start, end = run.span() if run is not None else (len(block), len(block))
                    if end - start < _SHORTEST_RUN and run is not None:
                        # (read with the lines around it: cheaper than applying it whole; and where short runs
                        # follow each other, the next ones are looked for further on, twice as far each time)
                        look = block.find("\n", end + skip - 1) + 1 or len(block) if skip else end
                        skip = skip * 2 or _SHORTEST_RUN
                        continue
                    skip = 0
                    if start > at:
                        yield from self._one_by_one(block, at, start)
                    if run is None:
                        break
                    at = look = end
                    for a, b, alone in self.parts(block, start, end):
                        if alone:
                            yield from self._one_by_one(block, a, b)
                        else:
                            yield from self._apply(block, a, b, may_apply)
        finally:
            forget_arcs()

    def _apply(
        self, block: str, a: int, b: int, may_apply: Callable[[], bool]
    ) -> Iterator[tuple[int, list[tuple[str, str]]]]:
        """Apply the run ``block[a:b]`` but for the lines to read on their own.  An M-code line that may
        change the state is read on its own before the rules are asked about the lines after it.  Where
        the rules may want any move, or the interpreter refuses to apply a stretch, some lines are read one
        by one before trying again (what they wait for, the job's first print or a rule done looking, may
        come), twice as many each time in a row: the time stays linear when it never comes."""
        # where the stretch the rules were asked about ends: the next M-code line to read on its own (then
        # code_line), or about _WINDOW characters on (their findings on it are held till then)
        window = -1
        code_line = False
        coded: list[RunFinding] = []  # the findings on the M-code lines before it (CodeLines)
        cuts: list[int] | None = None  # the rules' lines to read on their own before it, from index i
        reports: list[RunFinding] = []  # the findings on the other lines up to it, from index j
        i = j = 0
        again = _AGAIN
        while a < b:
            if not may_apply():
                cuts = None
                a = yield from self._some(block, a, b, again)
                again *= 2
                continue
            if window < a or (window == a and not code_line):
                limit = block.find("\n", a + _WINDOW, b) + 1 or b if b - a > _WINDOW else b
                window, coded = self.codes.first(block, a, limit) if self.codes is not None else (limit, [])
                code_line = window < limit
                cuts = None
            if cuts is None:
                # (a few lines, to the next M-code line read on its own: read on their own below, unasked)
                found = self.alone(block, a, window) if self.alone is not None and window - a >= _SHORTEST_RUN else ()
                if found is None:  # (any move: the lines before the first move go at once, then some)
                    move = a if block[a] == "G" else block.find("\nG", a, window) + 1 or window
                    before = self.total
                    if move == a or not self._bulk(block, a, move, may_apply):
                        a = yield from self._some(block, a, window, again)
                        again *= 2
                    else:
                        self._report(block, a, before, [r for r in coded if a <= r.at < move], 0, move)
                        a = move
                    continue
                cuts, reports = _cuts_and_reports(found, [r for r in coded if r.at >= a])
                i = j = 0
            while i < len(cuts) and cuts[i] < a:
                i += 1
            while j < len(reports) and reports[j].at < a:  # (lines read one by one since: they reported)
                j += 1
            stop = cuts[i] if i < len(cuts) else window
            if 0 < stop - a < _SHORTEST_RUN:  # (a few lines: read on their own, as a short run, and more after)
                a = yield from self._some(block, a, b, max(again, stop - a))
                again *= 2
                continue
            if stop > a:
                before = self.total
                if not self._bulk(block, a, stop, may_apply):
                    a = yield from self._some(block, a, stop, again)
                    again *= 2
                    continue
                if j < len(reports) and reports[j].at < stop:
                    j = self._report(block, a, before, reports, j, stop)
                a, again = stop, _AGAIN
            if a < b and (a < window or code_line):  # (a line to read on its own: the rules', or the M-code)
                stop = self._line(block, a, b)
                yield self.total - 1, split_lines(block[a:stop])
                a = stop

    def _report(self, block: str, a: int, total: int, reports: list[RunFinding], j: int, stop: int) -> int:
        """Add the findings ``reports[j:]`` made on lines before ``stop`` of the stretch ``block[a:stop]``,
        just applied (its first line is line ``total + 1``); return the index of the next one."""
        number, pos = total + 1, a
        add = self.add
        for k in range(j, len(reports)):
            at, rule, column, end_column, message, severity = reports[k]
            if at >= stop:
                return k
            number += block.count("\n", pos, at)
            pos = at
            end = block.find("\n", at)  # (a run's lines each end with a line break)
            raw = block[at : end - 1 if block[end - 1] == "\r" else end]
            add(rule, number, raw, column, message, severity=severity, end_column=end_column, plain=raw[0] == "G")
        return len(reports)

    def _some(
        self, block: str, a: int, limit: int, size: int
    ) -> Generator[tuple[int, list[tuple[str, str]]], None, int]:
        """Read the lines from ``a`` one by one, about ``size`` characters of them (not past ``limit``, a
        line start); return where the next line starts."""
        stop = block.find("\n", max(a, min(a + size, limit) - 1), limit) + 1
        yield from self._one_by_one(block, a, stop)
        return stop

    def _line(self, block: str, start: int, end: int) -> int:
        """Count the line at ``start`` (read on its own) and return where the next one starts."""
        self.total += 1
        return block.find("\n", start, end) + 1  # (a run's lines each end with a line break)

    def _bulk(self, block: str, a: int, b: int, may_apply: Callable[[], bool]) -> bool:
        """Apply ``block[a:b]`` at once, if the rules and the interpreter allow it."""
        if may_apply() and self.plain_run(block, a, b):
            self.total += block.count("\n", a, b)
            return True
        return False

    def _one_by_one(self, block: str, start: int, end: int) -> Iterator[tuple[int, list[tuple[str, str]]]]:
        for a, b in line_slices(block, start, end):  # (a few thousand lines at a time)
            lines = split_lines(block[a:b])
            yield self.total, lines
            self.total += len(lines)

    def needs_reading(self, comment: str) -> bool:
        """Whether a comment line is to be read on its own."""
        if self.every_comment or (self.longest is not None and len(comment) > self.longest):
            return True
        return any(test(comment) for test in self.tests)

    def any_needs_reading(self, block: str, start: int, end: int) -> bool:
        """Whether a comment line of the run ``block[start:end]`` may need reading (tested together)."""
        clean, quiet = self.clean, self.quiet
        if block[start] == ";":
            first = block[start : block.find("\n", start)]
            if first[-1:] == "\r":
                first = first[:-1]
            if first not in clean:
                if self.needs_reading(first):
                    return True
                self._remember(clean, first)
        for a, b in line_slices(block, start, end):  # (a few thousand comments at a time)
            comments = _COMMENT_LINES.findall(block, a - (a > start), b)  # (each after its line break)
            if comments:
                # (a comment line of a set that needed no reading needs none: they repeat, ";WIDTH:0.45")
                comments = [c for c in comments if c not in quiet]
                if not comments:
                    continue
                joined = "".join(comments)
                if (self.long_line is not None and self.long_line.search(joined)) or any(
                    test(joined) for test in self.tests
                ):
                    return True
                if len(quiet) + len(comments) > _CLEAN_LIMIT:
                    quiet.clear()
                quiet.update(c for c in comments if len(c) <= _QUIET_LONGEST)
        return False

    @staticmethod
    def _remember(texts: set[str], text: str) -> None:
        if len(texts) >= _CLEAN_LIMIT:
            texts.clear()
        texts.add(text)

    def parts(self, block: str, start: int, end: int) -> list[tuple[int, int, bool]]:
        """The run ``block[start:end]`` as (start, end, read one by one): cut around each comment line that
        needs reading."""
        if self.together and not self.any_needs_reading(block, start, end):
            return [(start, end, False)]
        out = []
        for comment, stop in self._to_read(block, start, end):
            if comment > start:
                out.append((start, comment, False))
            out.append((comment, stop, True))
            start = stop
        if start < end:
            out.append((start, end, False))
        return out

    def _to_read(self, block: str, start: int, end: int) -> Iterator[tuple[int, int]]:
        """(start, end) of each comment line of the run ``block[start:end]`` that needs reading, in order."""
        comment = start if block[start] == ";" else block.find("\n;", start, end) + 1 or end
        while comment < end:
            if self.together and comment:
                # stretches of comment lines tested together, halved where one may need reading (as
                # any_needs_reading tests a run's): most lines of a run that holds one secret-like setting
                # among a slicer's thousands of settings lines are never tested alone
                stretch = block.find("\n", comment + _TOGETHER, end) + 1 or end
                lines = [(m.start() + 1, m.group()) for m in _COMMENT_LINES.finditer(block, comment - 1, stretch)]
                for at in self._needing(lines):
                    yield at, block.find("\n", at, end) + 1
                comment = stretch
                continue
            stop = block.find("\n", comment, end) + 1
            text = block[comment : stop - 2 if block[stop - 2] == "\r" else stop - 1]
            if self._needs_reading_alone(text):
                yield comment, stop
            comment = block.find("\n;", stop - 1, end) + 1 or end

    def _needs_reading_alone(self, text: str) -> bool:
        if text in self.clean:
            return False
        if self.needs_reading(text):
            return True
        self._remember(self.clean, text)
        return False

    def _needing(self, lines: list[tuple[int, str]]) -> Iterator[int]:
        """The starts of the comment lines of ``lines`` (start, the line after its line break) that need
        reading: each alone where they are few, else tested together first (none of them needs reading
        when together they do not)."""
        if len(lines) <= _ALONE:
            for at, text in lines:
                if self._needs_reading_alone(text[1:]):
                    yield at
            return
        joined = "".join(text for _, text in lines)
        if (self.long_line is None or self.long_line.search(joined) is None) and not any(
            test(joined) for test in self.tests
        ):
            return
        half = len(lines) // 2
        yield from self._needing(lines[:half])
        yield from self._needing(lines[half:])


class CodeLines:
    """The M-code lines of runs to read on their own: those ``effect_of`` (the engine's) is not sure of.
    The others go with the run: ``M204 S500`` where no rule looks at accelerations changes nothing, and
    where only pure rules (``Rule.pure``) look at it (DL001 on Hyrel), their findings on it are made once
    and repeated on each such line.  Reading a line may change what the rules want of the moves after it
    (M18, M83): ``Runs`` asks the rules' filters about the lines up to it only."""

    def __init__(self, effect_of: Callable[[str], tuple[tuple, ...] | None]) -> None:
        self.effect_of = effect_of
        self.known: dict[str, tuple[tuple, ...] | None] = {}  # (the lines repeat: "M106 S255", "M204 S1000")

    def first(self, text: str, start: int, end: int) -> tuple[int, list[RunFinding]]:
        """The start of the first M-code line of ``text[start:end]`` to read on its own (``end``: none), and
        the findings on the M-code lines before it."""
        found: list[RunFinding] = []
        if text[start] != "M" and text.find("\nM", start, end) < 0:
            return end, found
        known = self.known
        for at, m in run_lines(RUN_CODE_LINE, text, start, end):
            raw = m.group()[1:]
            effect = known.get(raw, _UNKNOWN)
            if effect is _UNKNOWN:
                if len(known) >= _CLEAN_LIMIT:
                    known.clear()
                effect = known[raw] = self.effect_of(raw)
            if effect is None:
                return at, found
            for rule, column, end_column, message, severity in effect:
                found.append(RunFinding(at, rule, column, end_column, message, severity))
        return end, found


_UNKNOWN = (("",),)  # (a line's effect not known yet)


def _cuts_and_reports(
    found: list[int | RunFinding] | tuple, more: list[RunFinding]
) -> tuple[list[int], list[RunFinding]]:
    """The rules' lines to read on their own (in order), and the findings (theirs, then ``more``) on other
    lines (in line order, each line's in the order given)."""
    cuts = [x for x in found if x.__class__ is int]
    if len(cuts) == len(found) and not more:
        return sorted(set(cuts)) if len(cuts) > 1 else cuts, []
    read = set(cuts)
    reports = [x for x in (*found, *more) if x.__class__ is not int and x.at not in read]
    reports.sort(key=itemgetter(0))  # (by ``at``)
    return sorted(read), reports


def comment_tests(rules, view_patterns) -> tuple[Callable[[str], object], ...]:
    """What makes a comment line of a run one to read on its own: a directive, a rule's comment hint (a
    rule with none reads every comment), a view hook's pattern."""
    hints = dict.fromkeys(r.comment_hint or _always for r in rules if r.on_comment)  # (rules may share one)
    return (may_direct, *hints, *view_patterns)


def _always(comment: str) -> bool:  # (the comment hint of a rule that has none: it reads every comment)
    return True


def rule_run_filters(build: Callable, arcs: bool = False) -> tuple[RunFilter, ...] | None:
    """The run filters of the rules with a plain filter (``run_filter``, see docs/architecture.md) and of the
    move listeners (``wants_in_run``), and with ``arcs`` (runs take arcs: ``Linter._plain_arcs``) of the
    rules listening to G2/G3 for letters those arcs may carry, from the engine's dispatch ``build``; None
    when one of them has none (then runs are read line by line)."""
    out: list[RunFilter] = []
    for code in ("G0", "G1", *(("G2", "G3") if arcs else ())):
        always, filtered, _ = build(Command(code, GCODE, 1, {}))
        if code in ("G0", "G1"):  # (a move listener's filters are its wants_plain and wants_in_run)
            listening = [
                h
                for h in always
                if isinstance(h.__self__, MoveListener) or getattr(h.__self__, "plain_filter", None) is not None
            ]
        else:
            listening = [*always, *(h for h, letters in filtered if not letters.isdisjoint("XYZIJEF"))]
        for handler in listening:
            owner = handler.__self__
            run_filter = owner.wants_in_run if isinstance(owner, MoveListener) else getattr(owner, "run_filter", None)
            if run_filter is None:
                return None
            if run_filter not in out:
                out.append(run_filter)
    return tuple(out)


def combined(run_filters: tuple[RunFilter, ...]) -> RunFilter:
    """The lines of a run to read on their own: those one of the rules' run filters may want (None when
    one of them may want any, or fails: line by line, its rule's own filter or check fails and the rule
    is dropped)."""

    def alone(text: str, start: int, end: int) -> list[int | RunFinding] | None:
        found: list[int | RunFinding] = []
        for run_filter in run_filters:
            try:
                lines = run_filter(text, start, end)
            except Exception:
                return None
            if lines is None:
                return None
            found += lines
        return found

    return alone
