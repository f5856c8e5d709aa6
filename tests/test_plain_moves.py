"""The plain-move route (engine.Linter._run): G0/G1 lines that no rule would look at skip the tree.

It must change nothing but speed: the same findings and the same machine state as the general route,
on every corpus file and on generated jobs, in every dialect.
"""

from __future__ import annotations

import dataclasses
import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

import gclint.engine
import gclint.machine.interpreter
import gclint.runs
from gclint.dialects import all_dialects
from gclint.engine import Linter, Options
from gclint.rules.base import Rule
from gclint.syntax.fastpath import PLAIN_MOVE
from gclint.syntax.source import Source
from tests.conftest import CORPUS, corpus_job, needs_corpus
from tests.plain_route import route_blockers, slow_reading
from tests.strategies import DIALECTS, any_line, numbers


@pytest.fixture(autouse=True, scope="module")
def _runs_in_small_files():
    # (the engine reads a file under 64 KiB line by line; these tests read runs in small texts)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(gclint.engine, "RUNS_IN_SMALL_FILES", True)
        yield


FOLDER_DIALECT = {"hyrel": "hyrel-v4", "linuxcnc": "machinekit"}


def _run(text_or_path: str, dialect: str, plain: bool, *, is_path: bool = False, **options):
    linter = Linter(Options(dialect=dialect, **options))
    linter.plain_moves_enabled = plain
    source = Source.open(text_or_path) if is_path else Source.from_text(text_or_path, "<t>")
    ctx, result = linter.prepare(source)
    linter._run(source, ctx, result)
    # (in the order made: past MAX_FINDINGS, which are listed and which counted depends on it)
    findings = [(f.line, f.column, f.end_column, f.code, f.severity, f.message, f.source) for f in ctx.findings]
    state = {f.name: getattr(ctx.state, f.name) for f in dataclasses.fields(ctx.state) if f.name != "position"}
    state["position"] = ctx.state.position.snapshot()
    return findings, state, result.error


def _same(text_or_path: str, dialect: str, *, is_path: bool = False, **options) -> None:
    fast = _run(text_or_path, dialect, True, is_path=is_path, **options)
    slow = _run(text_or_path, dialect, False, is_path=is_path, **options)
    assert fast == slow


def test_the_pattern_takes_only_plain_moves():
    for line in ["G1 X10 Y20 E.5", "G0 F7200 X1 Y2 Z.3", "G1 E-.8 F2100", "G1 Z.2 F720", "G1", "G0 X1.  "]:
        assert PLAIN_MOVE.fullmatch(line), line
    for line in ["G1 X10 Y20 E.5 ; c", "G1 Y1 X2", "G01 X1", "G10 X1", "g1 x1", " G1 X1", "G1 X1 H2", "G1X1"]:
        assert not PLAIN_MOVE.fullmatch(line), line
    assert PLAIN_MOVE.fullmatch("G1 X" + "9" * 31) is None  # long numbers go to the grammar (SX006)
    assert PLAIN_MOVE.fullmatch("G1 F100 X1 F200") is None  # F twice: the tree reports it (SX002)
    assert PLAIN_MOVE.fullmatch("G1 F100 X1").groups() == ("1", "100", "1", None, None, None, None)
    assert PLAIN_MOVE.fullmatch("G1 X1 F200").groups() == ("1", None, "1", None, None, None, "200")


def test_the_route_is_taken_where_no_rule_looks(monkeypatch):
    monkeypatch.setattr(gclint.runs, "_SHORTEST_RUN", 0)  # (the runs of a few lines here are applied whole)
    linter = Linter(Options(dialect="marlin"))
    source = Source.from_text("G1 X1 Y2\nM104 S200\nG1 X3 E1\n", "<t>")  # (M104: a temperature to keep)
    ctx, result = linter.prepare(source)
    calls = []
    ctx.interpreter.plain_move = lambda *a: calls.append(a)  # type: ignore[method-assign]
    ctx.interpreter.plain_run = lambda *a: calls.append(a[1:]) or False  # type: ignore[method-assign]
    linter._run(source, ctx, result)
    # each run of plain moves is offered whole, then (refused here) applied one move after the other
    assert calls == [
        (0, 9),
        ("G1", 1, "1", "2", None, None, None),
        (19, 28),
        ("G1", 3, "3", None, None, "1", None),
    ], slow_reading("marlin", f"the moves were offered as {calls}")


def test_runs_of_plain_moves_are_applied_whole(monkeypatch):
    monkeypatch.setattr(gclint.runs, "_SHORTEST_RUN", 0)  # (the runs of a few lines here are applied whole)
    linter = Linter(Options(dialect="marlin"))
    first = "G28\nG1 Z.3 F600\nG1 X1 Y1 E1\n"  # the first feed and print: one line after the other
    second = "G1 X2 E2\r\nG0 X3 F9000\nG1 Y4 E2.5\nG1 E2\n"  # applied whole
    source = Source.from_text(first + "M104 S200\n" + second + ";end\n", "<t>")
    ctx, result = linter.prepare(source)
    runs = []
    offer = ctx.interpreter.plain_run
    ctx.interpreter.plain_run = lambda *a: runs.append((*a[1:], offer(*a))) and runs[-1][-1]  # type: ignore[method-assign]
    linter._run(source, ctx, result)
    at = len(first) + 10
    assert runs == [(4, len(first), False), (at, at + len(second) + len(";end\n"), True)], (  # (comments join runs)
        slow_reading("marlin", f"runs offered and applied: {runs}")
    )
    st = ctx.state
    assert st.position.snapshot() == {"X": 3.0, "Y": 4.0, "Z": 0.3}
    assert (st.feed, st.e_position, st.motion_mode, st.first_move_line, st.first_print_line) == (
        9000.0,
        2.0,
        "G1",
        2,
        3,
    )
    assert result.lines == 9


def test_comment_lines_a_rule_may_read_are_read_one_by_one(monkeypatch):
    monkeypatch.setattr(gclint.runs, "_SHORTEST_RUN", 0)  # (the runs of a few lines here are applied whole)
    linter = Linter(Options(dialect="marlin"))
    lines = [
        "G28",
        "G1 X0 Y0 Z.2 F600",
        "G1 X1 E1",
        ";TYPE:WALL",
        "G1 X2 E2",
        "; api_key = 0123456789ABCDEF0123456789ABCDEF",
    ]
    lines += [";WIDTH:0.4", "G1 X3 E3", "G1 X4 E4 ; noqa: SC006", "G1 X5 E5", "; gclint: disable=SC006", ";x", "G1 X6"]
    source = Source.from_text("\n".join(lines) + "\n", "<t>")
    ctx, result = linter.prepare(source)
    runs, read = [], []
    offer, parse = ctx.interpreter.plain_run, ctx.read_directives
    ctx.interpreter.plain_run = lambda text, a, b: runs.append(text[a:b].count("\n")) or offer(text, a, b)  # type: ignore[method-assign]
    ctx.read_directives = lambda line: read.append(line.number) or parse(line)  # type: ignore[method-assign]
    linter._run(source, ctx, result)
    # the comments with a secret and a directive are read on their own, the others go with the moves (the
    # first four lines one by one all the same: they hold the job's first move and print)
    assert runs == [4, 2, 1, 2] and read == [4, 6, 9, 11]
    assert [f.code for f in result.findings or ctx.findings] == ["SC006"]
    assert ctx.state.position.snapshot() == {"X": 6.0, "Y": 0.0, "Z": 0.2} and ctx.state.e_position == 5.0


def test_short_runs_are_read_with_the_lines_around_them(monkeypatch):
    # (stranger review: a Hyrel job alternating one move and a G92 E0 was 1.2x slower than before runs of one
    # line were applied whole, and 3x slower than reading every line: a run costs more than a few lines)
    job = "G28\nG1 X1 Y1 Z.2 E1 F600\n" + _SLICED + "G1 X2 Y2 E.5\nG92 E0\nG1 X1\nG92 E0\n" * 300
    job += "G1 X3 Y3 E.1\n" * 3000 + "G92 E0\n" + "G1 X4 Y4 E-1\nG92 E0\n" * 20
    offered = []
    plain_run = gclint.machine.interpreter.Interpreter.plain_run
    monkeypatch.setattr(
        gclint.machine.interpreter.Interpreter,
        "plain_run",
        lambda self, text, a, b: offered.append(text[a:b].count("\n")) or plain_run(self, text, a, b),
    )
    for dialect in ("hyrel", "marlin"):
        offered.clear()
        Linter(Options(dialect=dialect)).check_text(job)
        # (the 3,000 moves, from where the rules' first look ends: the others are 1-line runs, read with the
        # lines around them, and the next runs are looked for twice as far each time)
        assert offered and min(offered) >= 1000, slow_reading(dialect, f"runs of {offered[:10]} lines offered")
        _same(job, dialect)
    # M-code lines read on their own every line or two within a run (M83, M106 T0: the interpreter's), with
    # retractions HY031 finds without reading, then a long stretch applied whole again
    dense = "".join(f"G1 X{i % 7}.5 Y{i % 5} E{'-' if i % 3 == 0 else ''}0.{i % 9 + 1}\nM83\n" for i in range(400))
    dense += "".join(f"G1 X{i}.5 Y{i % 3}\nM106 T0 S{i % 200}\nG1 E-.5\n" for i in range(300))
    job = "G28\nM83\nG1 X1 Y1 Z.2 E1 F600\n" + _SLICED + dense + "G1 X5 Y5 E.2\n" * 3000 + dense
    for dialect in ("hyrel", "marlin"):
        offered.clear()
        found = Linter(Options(dialect=dialect)).check_text(job).findings
        assert max(offered) >= 1000 and len(offered) < 50, slow_reading(
            dialect, f"{len(offered)} runs offered, the longest {max(offered, default=0)} lines"
        )
        assert dialect == "marlin" or sum(f.code == "HY031" for f in found) > 700
        _same(job, dialect)


def _how_read(dialect: str, text: str, monkeypatch, *more_rules: type[Rule]) -> tuple[list[int], int]:
    """The lines of ``text`` read one by one, and how many lines runs applied in bulk."""
    import gclint.engine

    linter = Linter(Options(dialect=dialect))
    linter.rule_classes = [*linter.rule_classes, *more_rules]
    source = Source.from_text(text, "<t>")
    ctx, result = linter.prepare(source)
    alone: list[int] = []
    bulk = [0]

    class Recorded(gclint.engine.Line):
        __slots__ = ()

        def __init__(self, number, *rest) -> None:
            if number:  # (line 0: a line of a run whose pure rules' findings the engine makes once)
                alone.append(number)
            super().__init__(number, *rest)

    monkeypatch.setattr(gclint.engine, "Line", Recorded)
    move, offer = ctx.interpreter.plain_move, ctx.interpreter.plain_run
    ctx.interpreter.plain_move = lambda mode, number, *words: alone.append(number) or move(mode, number, *words)  # type: ignore[method-assign]

    def plain_run(block: str, a: int, b: int) -> bool:
        applied = offer(block, a, b)
        bulk[0] += block.count("\n", a, b) if applied else 0
        return applied

    ctx.interpreter.plain_run = plain_run  # type: ignore[method-assign]
    linter._run(source, ctx, result)
    assert len(alone) + bulk[0] == result.lines  # (every line once)
    return sorted(alone), bulk[0]


_SLICED = "".join(f"G1 X{i} Y1 E{0.3 + i / 100:.2f}\n" for i in range(8))  # (HY060 decides: sliced)


@pytest.mark.parametrize(
    "e_mode,travel,found,expected",
    [
        # relative E: a retract and a prime (G1 with E and no X or Y), a negative or zero E while moving:
        # HY031's, found without reading the lines (RunFinding)
        ("M83", "G1 E-.8 F2100\nG0 F7200 X5 Y5\nG1 Z.2 F720\nG1 E.8 F2100\n", [1, 4], []),
        ("M83", "G1 X5 Y5 E-.1\nG1 F2100 E+0.0\nG1 Y6 X5 E0.\nG1 X7 E.05\n", [1, 2, 3], []),
        # absolute E: an amount that goes back (a retract, a wipe); the same amount again is fine
        ("M82", "G1 X5 Y5 E9000\nG1 X6 E9000\nG1 F2100 E8999\nG1 X7 Y7 E8998\nG1 E9000 F2100\n", [3, 4, 5], []),
        ("M82", "G1 Z.3 E9000\nG1 X5 E8999.5\nG1 E9001 X6\nG1 Y7 E9002\n", [2], []),
        # G0 with E (HY030), whatever the mode: read on its own
        ("M83", "G0 X5 E1\nG1 X6 Y6 E.2\n", [1], [1]),
    ],
)
def test_hyrel_runs_are_applied_around_the_moves_a_rule_wants(e_mode, travel, found, expected, monkeypatch):
    head = f"G28\n{e_mode}\nG1 X1 Y1 Z.2 E1 F600\n{_SLICED}"  # (one by one: the first print, HY060 deciding)
    moves = "".join(f"G1 X{i} Y{i} E{i * 10}\n" for i in range(2, 200))  # (E forward in either mode)
    tail = "".join(f"G1 X{i} Y{i} E{i * 10}\n" for i in range(1000, 1100))
    job = head + moves + travel + tail
    skip = (head + moves).count("\n")
    alone, bulk = _how_read("hyrel", job, monkeypatch)
    assert [n - skip for n in alone if n > skip] == expected
    assert bulk >= len(moves.splitlines()) // 2 + len(tail.splitlines()), slow_reading(
        "hyrel", f"{bulk} lines applied in runs, {len(alone)} read one by one"
    )
    findings = Linter(Options(dialect="hyrel")).check_text(job).findings
    assert [f.line - skip for f in findings if f.line > skip and f.code in ("HY030", "HY031")] == found
    _same(job, "hyrel")


def test_a_run_refused_at_first_is_applied_once_what_it_waits_for_is_read(monkeypatch):
    # (Cura: the job's first print is in a run that lasts to its end; HY060 looks at the first moves)
    job = "M82\nG92 E0\nG0 F360 X1 Y1 Z.3\n" + "".join(f"G1 X{i} Y{i} E{i}\n" for i in range(1, 3000))
    for dialect in ("marlin", "hyrel"):
        alone, bulk = _how_read(dialect, job, monkeypatch)
        assert len(alone) < 100 and bulk > 2900, slow_reading(
            dialect, f"{len(alone)} lines read one by one, {bulk} applied in runs"
        )
        _same(job, dialect)


def test_m_codes_that_change_nothing_go_with_runs(monkeypatch):
    # M204 (accelerations): no rule looks at it in Marlin and the interpreter keeps no state for it; M104
    # sets a temperature, a duplicated word is a syntax issue (SX002) and M587 is a code a view pattern is
    # about (a WiFi password): those are read on their own
    head = "G28\nG1 X0 Y0 Z.2 F600\nG1 X1 E1\n"
    moves = "".join(f"G1 X{i} Y{i} E{i + 2}\n" for i in range(300))
    codes = ["M204 S500", "M204 P1000 T500", "M104 S200", "M204 S5 S6", "M587 S1 P1234", "M221 S100", "M0204 S5"]
    job = head + moves + "".join(f"{code}\n{moves}" for code in codes)
    alone, bulk = _how_read("marlin", job, monkeypatch)
    lines = job.splitlines()
    assert [lines[n - 1] for n in alone if lines[n - 1][0] == "M"] == ["M104 S200", "M204 S5 S6", "M587 S1 P1234"]
    assert bulk > 2000, slow_reading("marlin", f"{bulk} lines applied in runs, {len(alone)} read one by one")
    _same(job, "marlin")
    findings = Linter(Options(dialect="marlin")).check_text(job).findings
    assert [(f.code, lines[f.line - 1]) for f in findings if f.code.startswith(("SX", "SC"))] == [
        ("SX002", "M204 S5 S6"),
        ("SC007", "M587 S1 P1234"),  # (the printer joins the job's Wi-Fi network)
        ("SC006", "M587 S1 P1234"),
    ]
    # in Hyrel M204 is not a code (DL001, a pure rule): its findings are made once and repeated, the
    # lines go with the runs
    alone, bulk = _how_read("hyrel", job, monkeypatch)
    assert not {"M204 S500", "M204 P1000 T500"} & {lines[n - 1] for n in alone}
    findings = Linter(Options(dialect="hyrel")).check_text(job).findings
    repeated = [n for n, t in enumerate(lines, 1) if t in ("M204 S500", "M204 P1000 T500")]
    assert set(repeated) <= {f.line for f in findings if f.code == "DL001"}
    _same(job, "hyrel")


@pytest.mark.parametrize("select", [["HY030"], ["HY031"], ["HY032"], ["HY039"], ["HY060"], ["HY031", "HY039"]])
def test_a_code_that_changes_the_state_in_a_run_is_read_before_the_moves_after_it(select):
    # (M18 in a run made the moves after it wanted, M83 and M229 change what a move's E means: the rules'
    # run filters are asked about the lines up to such a line only)
    moves = "".join(f"G1 X{i} Y{i} E{i}\n" for i in range(1, 200))
    tail = "G0 X5 Y5 E1\nG1 X1 Y1 E-1\nG1 E1\nG1 X2 Y2 E0\n" + moves
    for code in ("M18", "M84", "M83", "M82", "M229 E1 D1", "M107"):
        job = f"G28\nM82\nG1 X1 Y1 Z.2 E1 F600\n{moves}{code}\n{tail}{code}\n{tail}"
        _same(job, "hyrel", select=select)


@pytest.mark.parametrize(
    "dialect,job",
    [
        # (a feed only on G0: the interpreter refuses every stretch with an F for good, M204 in between)
        ("marlin", "M204 S500\nG0 F9000 X10 Y10\nG1 X20 Y20 E1\n" * 30000),
        # (no working feed ever: HY050 wants every move; comment lines only: the Hyrel rules want any move)
        ("hyrel", "".join(f"G1 X{i % 200}.5 Y{i % 150}.25\n" for i in range(90000))),
        ("hyrel", (";" + "x" * 99 + "\n") * 20000),
    ],
)
def test_a_run_never_applied_is_tried_a_bounded_number_of_times(dialect, job, monkeypatch):
    # (found by a stranger review: each retry searched the rest of the run again, 15 times slower)
    from gclint.machine.interpreter import Interpreter
    from gclint.runs import _WINDOW, CodeLines

    calls = {"first": 0, "plain_run": 0}
    first, plain_run = CodeLines.first, Interpreter.plain_run
    monkeypatch.setattr(CodeLines, "first", lambda *a: calls.__setitem__("first", calls["first"] + 1) or first(*a))
    monkeypatch.setattr(
        Interpreter, "plain_run", lambda *a: calls.__setitem__("plain_run", calls["plain_run"] + 1) or plain_run(*a)
    )
    Linter(Options(dialect=dialect)).check_text(job)
    windows = len(job) // _WINDOW  # (the rules are asked about 64 KB at a time)
    assert calls["first"] <= 10 + windows and calls["plain_run"] <= 60 + windows, calls  # (1 KB at a time: thousands)


def test_hyrel_long_lines_are_read_one_by_one(monkeypatch):
    # HY029 looks at lines longer than 100 characters: runs take only moves surely shorter
    long = "G1 X1.1234567" + " " * 60 + "Y2.1234567 Z3.1234567 E4.1234567 F5000.12345"  # (E and F cut)
    job = "G28\nG1 X1 Y1 Z.2 E1 F600\n" + _SLICED + "G1 X2 Y2 E2\n" * 200 + long + "\n" + "G1 X3 Y3 E3\n" * 200
    alone, bulk = _how_read("hyrel", job, monkeypatch)
    assert job.count("\n") - 200 in alone
    assert bulk >= 200, slow_reading("hyrel", f"{bulk} lines applied in runs, {len(alone)} read one by one")
    assert "HY029" in [f.code for f in Linter(Options(dialect="hyrel")).check_text(job).findings]
    _same(job, "hyrel")


def test_hyrel_runs_take_arcs_of_short_words(monkeypatch):
    # every arc rule of Hyrel has a run filter: a slicer's arcs go with the runs, but for the ones a rule
    # may want (no centre, HY017) and those longer than 100 characters (HY029) or possibly so
    arcs = "".join(f"G{2 + i % 2} X{i}.125 Y57.743 I-1.022 J-.197 E.0191\n" for i in range(300))
    no_centre = "G2 X5 Y5 I0 J-0.000 E.01\n"
    wide = "G3 X1000.12345 Y1000.12345 Z1000.12345 I-1000.12345 J-1000.12345 E1000.12345 F1000.12345\n"
    long = "G3  X1.5  Y2.5  I1  J1  E.01\n"  # (two blanks: possibly long, read on its own; not HY029's)
    longer = "G3" + "".join(f" {letter}-12345.678901" for letter in "XYZIJE") + " F12345.678901\n"
    assert len(wide) == 89 and len(longer) == 107
    job = "G28\nM83\nG1 X1 Y1 Z.2 E1 F600\n" + _SLICED + arcs + no_centre + arcs + wide + long + arcs + longer + arcs
    alone, bulk = _how_read("hyrel", job, monkeypatch)
    lines = job.splitlines()
    read = [lines[n - 1] for n in alone if lines[n - 1].startswith(("G2 ", "G3 "))]
    assert {no_centre[:-1], long[:-1], longer[:-1]} <= set(read) and wide[:-1] not in read
    # (the first ones while HY060 decides, then every 300 arcs)
    assert len(read) < 100 and bulk >= 1100, slow_reading(
        "hyrel", f"{len(read)} arcs read one by one, {bulk} lines in runs"
    )
    found = {(f.code, lines[f.line - 1]) for f in Linter(Options(dialect="hyrel")).check_text(job).findings}
    assert {("HY017", no_centre[:-1]), ("HY029", longer[:-1])} <= found
    _same(job, "hyrel")
    # under M229 E1 (HY037) or after G18 (HY052), the arcs are read
    for head, code in (("M229 E1 D1\n", "HY037"), ("G18\n", "HY052")):
        alone, bulk = _how_read("hyrel", head + job, monkeypatch)
        assert len(alone) > 1200, code
        assert code in {f.code for f in Linter(Options(dialect="hyrel")).check_text(head + job).findings}
        _same(head + job, "hyrel")


def test_back_to_back_arcs_with_no_centre_are_each_found():
    # (stranger review: the pattern took the line break the next arc starts from, so every other was missed)
    job = "G28\nG1 X1 Y1 E1 F600\n" + _SLICED + "G1 X45 Y45 E4.5\nG92 E0\n" + "G2 X5 Y5 I0 J0 E0.1\n" * 4
    lines = job.splitlines()
    found = [f.line for f in Linter(Options(dialect="hyrel")).check_text(job).findings if f.code == "HY017"]
    assert found == [n for n, t in enumerate(lines, 1) if t.startswith("G2 ")]
    _same(job, "hyrel")


def test_has_arcs_answers_for_any_stretch_in_any_order():
    import itertools

    from gclint.syntax.fastpath import has_arcs

    for text in ("G1 X1\nG2 X1 I1\nG1 X2\nG1 X3\nG3 X1 J1\n", "G2 X1 I1\nG1 X1\n", "G3 X1\n", "G1 X1\n\n;G2\nG1 X2\n"):
        starts = [0] + [i + 1 for i, c in enumerate(text) if c == "\n" and i + 1 < len(text)]
        stretches = list(itertools.combinations([*starts, len(text)], 2))
        for a, b in [*stretches, *reversed(stretches), *stretches]:  # (the next arc is remembered)
            assert has_arcs(text, a, b) == any(text.startswith(("G2", "G3"), s) for s in starts if a <= s < b)


def test_the_run_patterns():
    from gclint.syntax.fastpath import PLAIN_MOVE_RUN, run_pattern

    PLAIN_RUN, ARC_RUN = run_pattern(False), run_pattern(True)  # noqa: N806

    lines = ["G1 X10 Y20 E.5", "G0 F7200 X1 Y2 Z.3", "G1 F100 X1 F200", "G1 X1 F2", "G1 F1 X2", "G1  ", "G1 Y1 X2"]
    lines += ["G1 X1 ; c", "G1\tX1\t", "G1 X" + "9" * 31, "G0 E1 F1 F2", "G1 Z1 E1 F1", "G1 X1 S2", "g1 x1", "G01 X1"]
    for line in lines:  # the context's runs: the lines PLAIN_MOVE takes
        assert bool(PLAIN_MOVE_RUN.fullmatch(line + "\n")) == bool(PLAIN_MOVE.fullmatch(line)), line
        assert bool(PLAIN_MOVE_RUN.fullmatch(line + "\r\n")) == bool(PLAIN_MOVE.fullmatch(line)), line
        assert not PLAIN_MOVE_RUN.fullmatch(line + "\r") and not PLAIN_RUN.fullmatch(line + "\r")
    # a line with F first followed by one with F last is one run (no group carries over)
    assert PLAIN_MOVE_RUN.fullmatch("G1 F1 X1\nG1 X2 F2\n")
    # the engine's: X Y Z E F in any order, each at most once (a repeated word is SX002, read on its own)
    for line in ["G1 Y1 X2", "G1 Z.2 X1 Y1 E.5", "G0 F1 E2 Z3 Y4 X5", "G1 X1 Y2 F3 E4", "G1", ";x", ""]:
        assert PLAIN_RUN.fullmatch(line + "\n") and PLAIN_RUN.fullmatch(line + "\r\n"), line
    for line in [
        "G1 X1 X2",
        "G1 F1 X1 F2",
        "G1 E1 Y1 E2",
        "G1 Z1 Y1 X1 E1 F1 Z2",
        "G1 X1 ; c",
        "G1 X1 S2",
        "g1 x1",
        " ",
    ]:
        assert not PLAIN_RUN.fullmatch(line + "\n") and not ARC_RUN.fullmatch(line + "\n"), line
    # the E amounts of a run: every E word's text (RUN_E where the run has no comment)
    from gclint.syntax.fastpath import PLAIN_E, RUN_E

    run = "G1 X1 E.5\nG1 E-0.8 F2100\nG0 X2\r\n\nG1 F1 E+1. Y2\nG2 X1 Y1 I1 J1 E2\n"
    assert RUN_E.findall(run) == PLAIN_E.findall(run) == [".5", "-0.8", "+1.", "2"]
    assert PLAIN_E.findall(";TYPE:External E1\n" + run) == [".5", "-0.8", "+1.", "2"]
    from gclint.syntax.fastpath import run_amounts

    for text in (run, ";c\n" + run, "G1 X1\n;c E2\n" + run):  # (without comments, and with, from any line)
        for start in (0, text.index("\n") + 1):
            pattern, at = run_amounts(text, start, len(text))
            assert pattern.findall(text, at, len(text)) == PLAIN_E.findall(text, start, len(text)), (text, start)
    # arcs (where no rule looks at them): X Y Z I J E in that order, F first or last
    assert ARC_RUN.fullmatch("G2 X1 Y2 I3 J4 E5\nG3 F1 X1 Y1 I1 J1\n;c\nG1 Y1 X1\nG2 X1 Y1 I1 J1 E1 F1\n")
    assert not PLAIN_RUN.fullmatch("G2 X1 Y2 I3 J4\n")
    for line in ["G2 X1 I1 X2", "G2 X1 R1", "G2 J1 I1", "G2 X1 F1 E1", "G2 F1 X1 F2", "G2 X1 P2"]:
        assert not ARC_RUN.fullmatch(line + "\n"), line


@pytest.mark.parametrize(
    "text",
    [
        "G91\nG1 X1 Y2 E.5\nG1 X-1 F600\nG90\nG1 X5\n",
        "M83\nG1 E-1 F2400\nG0 F7200 X1 Y1\nG1 X2 Y2 E0\nM82\nG1 E5\nG1 E4\n",
        "G1 F100 X1 F200\nG1 X1 Y2 Z3 E4 F5\nM30\nG1 X2\nG0 X3 E1\n",
        "M229 E1 D1\nM6 T12 O1\nT12\nM660 H1 Z5\nG1 X1 H1\nG1 X2 Y2 E1 F600\nM18\nG1 X3\n",
        "G0 X1 E1\nG1 X2 S3\nG1 X" + "9" * 40 + "\n",
    ],
)
@pytest.mark.parametrize("dialect", DIALECTS)
def test_same_findings_and_state(text, dialect):
    _same(text, dialect)


@st.composite
def _move(draw) -> str:
    letters = draw(st.lists(st.sampled_from("FXYZEF"), max_size=6, unique=False))
    words = [f"{letter}{draw(numbers())}" for letter in letters]
    return draw(st.sampled_from(["G0", "G1"])) + "".join(" " + w for w in words)


@st.composite
def _arc(draw) -> str:
    letters = draw(st.lists(st.sampled_from("XYZIJEFR"), max_size=7, unique=False))
    words = [f"{letter}{draw(numbers())}" for letter in letters]
    return draw(st.sampled_from(["G2", "G3"])) + "".join(" " + w for w in words)


@given(
    st.lists(
        st.one_of(
            _move(),
            _move(),
            _arc(),
            st.sampled_from(
                [";TYPE:WALL", "; api_key = 0123456789ABCDEF0123456789ABCDEF", "; gclint: disable=SX002", ""]
            ),
            st.sampled_from(["G91", "G90", "M82", "M83", "M30", "G92 E0", "M18", "M84", "M229 E1 D1", "G93", "G94"]),
            any_line().filter(lambda line: "\x00" not in line),
        ),
        max_size=30,
    ),
    st.sampled_from(DIALECTS),
)
def test_same_on_generated_jobs(lines, dialect):
    _same("\n".join(lines) + "\n", dialect)


def _corpus_files() -> list:
    if not CORPUS.is_dir():
        return []
    out = []
    for folder in sorted(p for p in CORPUS.iterdir() if p.is_dir()):
        for path in sorted(folder.rglob("*")):
            if path.is_file() and path.suffix.lower() in (".gcode", ".gco", ".g", ".nc", ".ngc", ".cnc", ".tap"):
                out.append((folder.name, path))
    return out


@needs_corpus
@pytest.mark.parametrize("folder,path", _corpus_files(), ids=lambda v: getattr(v, "name", v))
def test_same_on_the_corpus(folder, path):
    dialect = FOLDER_DIALECT.get(folder, "auto")
    job = corpus_job(path)  # (a big job's head and tail; every line with GCLINT_SLOW=1)
    _same(job, dialect, is_path=True)
    if dialect != "hyrel-v4":
        _same(job, "hyrel", is_path=True)  # every Hyrel rule on, the most G1 listeners


class _LongLines(Rule):
    code = "ZZ901"
    on_line_longer_than = 1000

    def check_line(self, line):
        self.report(line, "long")


class _CommentsWithX(Rule):  # (no comment_hint: every comment is read)
    code = "ZZ902"
    on_comment = True

    def check_comment(self, line, comment):
        if "x" in comment.text:
            self.report(line, "x")


class _HintedComments(_CommentsWithX):
    code = "ZZ903"
    comment_hint = staticmethod(lambda text: "x" in text)


class _WidthLines(Rule):  # a view pattern that is not multi-line: comment lines are tested one by one
    code = "ZZ904"
    on_line_matching = re.compile("^;WIDTH")

    def check_view(self, line):
        self.report(line, "width")


class _MultiLineWidth(_WidthLines):
    code = "ZZ905"
    on_line_matching = re.compile("(?m)^;WIDTH")


@pytest.mark.parametrize("rule", [_LongLines, _CommentsWithX, _HintedComments, _WidthLines, _MultiLineWidth])
def test_rules_see_the_comment_lines_of_runs_they_ask_for(rule, monkeypatch):
    monkeypatch.setattr(gclint.runs, "_SHORTEST_RUN", 0)  # (the runs of a few lines here are applied whole)
    lines = ["G28", "G1 X0 Y0 Z.2 F600", "G1 X1 E1", "M400", ";a", "G1 X2 E2", ";" + "y" * 1000, ";WIDTH:0.4"]
    lines += ["G1 X3 E3", ";x", "G2 X1 Y1 I1 J1 E4", ";" + "z" * 999, ";WIDTH:0.5", "G1 X4 E5", ";b x"]
    runs_applied = []
    for ending in ("\n", "\r\n"):
        text = ending.join(lines) + ending
        found = {}
        for plain in (True, False):
            linter = Linter(Options(dialect="marlin"))
            linter.rule_classes = [*linter.rule_classes, rule]
            linter.plain_moves_enabled = plain
            source = Source.from_text(text, "<t>")
            ctx, result = linter.prepare(source)
            offer = ctx.interpreter.plain_run
            ctx.interpreter.plain_run = lambda *a, offer=offer: runs_applied.append(offer(*a)) or runs_applied[-1]  # type: ignore[method-assign]
            linter._run(source, ctx, result)
            found[plain] = [(f.line, f.code) for f in ctx.findings if f.code == rule.code]
        assert found[True] == found[False] and found[True], (rule, ending, found)
    assert True in runs_applied  # (the moves after M400 are applied whole, around the lines read)


class _AtX7(Rule):  # a plugin rule on G1 with a plain filter and a run filter
    code = "ZZ906"
    codes = ("G1",)

    def plain_filter(self, mode, x, y, z, e, f) -> bool:
        return x == "7"

    def run_filter(self, text: str, start: int, end: int) -> list[int] | None:
        return [m.start() for m in re.finditer(r"(?m)^G1 X7\b", text[:end]) if m.start() >= start]

    def check(self, line, cmd):
        if cmd.params.get("X") == "7":
            self.report(line, "at X7")


class _BrokenRunFilter(_AtX7):
    code = "ZZ907"

    def run_filter(self, text: str, start: int, end: int) -> list[int] | None:
        raise RuntimeError("broken")


@pytest.mark.parametrize("rule", [_AtX7, _BrokenRunFilter])
def test_a_rule_with_a_run_filter_sees_the_moves_it_wants(rule, monkeypatch):
    monkeypatch.setattr(gclint.runs, "_SHORTEST_RUN", 0)  # (9 moves between two it wants: applied whole here)
    job = "G28\nG1 X0 Y0 Z.2 F600\nG1 X1 E1\n" + "".join(f"G1 X{i % 10} Y{i} E{i + 2}\n" for i in range(300))
    found = {}
    for plain in (True, False):
        linter = Linter(Options(dialect="marlin"))
        linter.rule_classes = [*linter.rule_classes, rule]
        linter.plain_moves_enabled = plain
        result = linter.check_text(job)
        assert result.error is None
        found[plain] = [f.line for f in result.findings if f.code == rule.code]
    assert found[True] == found[False] == [4 + i for i in range(300) if i % 10 == 7]
    alone, bulk = _how_read("marlin", job, monkeypatch, rule)
    assert bulk > 200 if rule is _AtX7 else bulk == 0, slow_reading("marlin", f"{bulk} lines applied in runs", rule)


def test_a_run_of_a_million_lines_takes_no_memory_to_find():
    # (the runs repeat possessively: a backtracking repeat kept ~200 bytes per line, 239 MB on a flood of
    # 40 million empty lines, found by a stranger review)
    import tracemalloc

    from gclint.syntax.fastpath import PLAIN_MOVE_RUN, run_pattern

    for pattern, text in [
        (run_pattern(True), "G1 X1\n" + ";c\n\n" * 300_000),
        (run_pattern(False), "G1 X1\r\n" + "G1 Y1 E1\r\n" * 300_000),
        (PLAIN_MOVE_RUN, "G1 X1\n" + ";c\n" * 300_000),
    ]:
        tracemalloc.start()
        try:
            found = pattern.search(text)
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        assert found is not None and found.span() == (0, len(text))
        assert peak < 1 << 20


def test_a_comment_that_needs_reading_is_found_anywhere_in_a_long_run():
    # (runs are tested a few thousand lines at a time, line_slices: the first line of each slice counts too)
    from gclint.syntax.source import HEAD, line_slices

    lines = ["G28", "G1 X0 Y0 Z.2 F600", "G1 X1 E1", "M400"] + [";c"] * 70_000 + ["G1 X2 E2"]
    text = "\n".join(lines) + "\n"
    second_block = text.rfind("\n", 0, HEAD) + 1  # (the first block is the head's whole lines)
    cuts = [a for a, _ in line_slices(text, second_block, len(text))][1:3]
    assert cuts, "the run spans several slices"
    for cut in cuts:
        for number in range(text.count("\n", 0, cut) - 1, text.count("\n", 0, cut) + 3):
            job = list(lines)
            job[number - 1] = "; api_key = 0123456789ABCDEF0123456789ABCDEF"
            findings = Linter(Options(dialect="marlin")).check_text("\n".join(job) + "\n").findings
            assert [(f.line, f.code) for f in findings] == [(number, "SC006")], number


# -- every rule keeps plain moves on their route ---------------------------------------------------------------------

# Rules that keep part of the route shut, each with why; a new rule never goes here (CONTRIBUTING.md, "A rule that
# reads moves": declare trigger_letters, or plain_filter with run_filter).
KNOWN_SLOW = {
    ("machinekit", "DL005"): "plain_filter without run_filter: Machinekit runs of moves are read line by line",
}


@pytest.mark.parametrize("dialect", [d.name for d in all_dialects()])
def test_no_rule_keeps_plain_moves_off_their_route(dialect):
    blockers = route_blockers(dialect, select=["ALL"])  # (every rule, those off by default too)
    new = [b for b in blockers if (dialect, b[:5]) not in KNOWN_SLOW]
    assert not new, (
        "rules that keep plain moves off their fast route (CONTRIBUTING.md, 'A rule that reads moves'):\n"
        + ("\n".join(new))
    )
    assert {code for d, code in KNOWN_SLOW if d == dialect} <= {b[:5] for b in blockers}, "KNOWN_SLOW is out of date"


class _ReadsEveryMove(Rule):  # a rule on G1 that declares no filter: every move is read
    code = "ZZ908"
    codes = ("G1",)
    families = None


class _TriggersOnX(_ReadsEveryMove):  # a trigger letter a plain move has
    code = "ZZ909"

    def trigger_letters(self, code):
        return frozenset("XH")


class _PlainFilterOnly(_AtX7):  # a plain filter without a run filter
    code = "ZZ910"
    run_filter = None


@pytest.mark.parametrize(
    "rule,missing",
    [
        (_ReadsEveryMove, "listens to G1 with neither trigger_letters"),
        (_TriggersOnX, "trigger_letters('G1') = 'HX' has letters a plain move has"),
        (_PlainFilterOnly, "has plain_filter for G1 but no run_filter"),
    ],
)
def test_a_guard_names_the_rule_and_what_it_lacks(rule, missing, monkeypatch):
    """A rule that reads every move makes the guards fail with its code and the filter it lacks, not with
    ``assert 3002 < 100``."""
    [blocker] = route_blockers("marlin", [*Linter(Options(dialect="marlin")).rule_classes, rule])
    assert blocker.startswith(f"{rule.code} ({rule.__name__}) ") and missing in blocker, blocker
    job = "M82\nG92 E0\nG0 F360 X1 Y1 Z.3\n" + "".join(f"G1 X{i} Y{i} E{i}\n" for i in range(1, 3000))
    alone, bulk = _how_read("marlin", job, monkeypatch, rule)
    message = slow_reading("marlin", f"{len(alone)} lines read one by one, {bulk} applied in runs", rule)
    assert bulk < 2900 and rule.code in message and missing in message, message
