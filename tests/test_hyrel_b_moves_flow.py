"""G0/G1 and flow rules (HY001, HY011-HY015, HY030-HY033, HY039, HY042, HY050, HY053, HY060).

The G0/G1 rules share one listener declared to the engine (``MoveChecks``, a ``MoveListener``); these
tests also check that any subset of them selected alone still works.
"""

from __future__ import annotations

import itertools

import pytest

from gclint.engine import Linter, Options, check_text
from gclint.rules.hyrel.motion import MoveChecks

MOVE_RULES = ("HY030", "HY031", "HY032", "HY033", "HY039", "HY042", "HY050", "HY053", "HY060")

# One line (or more) that triggers each G0/G1 rule, on a 30M.
TRIGGERS = """\
G0 X5 Y5 E1
G1 X10 Y10 E1
G1 X20 Y10 E-1 F600
G1 X20 Y20 E1 S-2
G91
G1 X1 Y1 E1
G90
G1 X1 Y1 A5 E1
G93
G1 X1 Y2 F10
G1 X2 Y2 F20
G1 X3 Y2 F30
G1 X4 Y2 F40
G1 X5 Y2 F50
G1 X1 Y1 E0.52
G1 X1 Y2 E0.31
G1 X1 Y3 E0.44
M18
G0 X1 Y1
"""


def lines(text: str, code: str, **options) -> list[int]:
    options.setdefault("dialect", "hyrel")
    return [f.line for f in check_text(text, **options) if f.code == code]


def test_all_move_rules_fire_together():
    result = check_text(TRIGGERS, dialect="hyrel", printer="30m")  # (a 30m has no A axis: HY042)
    assert {f.code for f in result} >= set(MOVE_RULES)


@pytest.mark.parametrize("subset", [s for n in (1, 2) for s in itertools.combinations(MOVE_RULES, n)])
def test_any_subset_alone(subset):
    every = check_text(TRIGGERS, dialect="hyrel", printer="30m")
    alone = Linter(Options(dialect="hyrel", printer="30m", select=list(subset))).check_text(TRIGGERS).findings
    expected = sorted((f.line, f.code, f.message) for f in every if f.code in subset)
    assert sorted((f.line, f.code, f.message) for f in alone) == expected


def test_one_listener_for_g0_g1():
    linter = Linter(Options(dialect="hyrel"))
    from gclint.dialects import get
    from gclint.engine import FileContext
    from gclint.machine.profiles import get_profile

    ctx = FileContext("x", get("hyrel"), get_profile("30m"), linter.options)
    rules = [cls(ctx) for cls in linter.rule_classes]
    members = [r for r in rules if r.code in MOVE_RULES]
    assert not [r.code for r in members if "G0" in r.codes or "G1" in r.codes]  # no rule listens for the others
    (checks,) = ctx.move_listeners
    assert isinstance(checks, MoveChecks) and checks.members == members
    assert ctx.move_listener(MoveChecks) is checks  # one per file
    assert all(getattr(r, "moves", None) is checks for r in members)


def test_the_engine_calls_the_listener_itself(monkeypatch):
    # (no rule's check stands in for it: one call of MoveChecks.move per G0/G1 line read, from the engine)
    calls = []
    move = MoveChecks.move

    def counted(self, line, cmd):
        calls.append((line.number, cmd.code))
        move(self, line, cmd)

    monkeypatch.setattr(MoveChecks, "move", counted)
    findings = check_text("G0 X1 Y1 E1\nG1 X2 Y2 A1 F600\nM104 S200\n", dialect="hyrel", printer="30m")
    assert calls == [(1, "G0"), (2, "G1")]
    assert {f.code for f in findings} >= {"HY030", "HY042"}


# -- G0/G1 rules --------------------------------------------------------------------------------------------


def test_hy031_native_only():
    text = "G1 X1 Y1 E1 F600\nG1 X2 Y1 E-0.5\nG1 E-1\nM229 E1 D1\nG1 X3 Y1 E-0.5\nG1 E-1\n"
    assert lines(text, "HY031") == [2, 3]


def test_hy031_native_e1_convention_with_m82():
    text = "M82\nG92 E0\nG1 X1 Y1 E1 F600\nG1 X2 Y1 E1\nG1 X3 Y1 E1\n"
    assert lines(text, "HY031") == []


def test_hy032_once_per_g91_stretch_and_not_for_retracts():
    text = "G91\nG1 E-1 F300\nG1 Z5\nG1 X1 E1\nG1 X1 E1\nG90\nG1 X1 E1\nG91\nG1 X1 E1\n"
    assert lines(text, "HY032") == [4, 9]


def test_hy039_once_per_m18_and_cleared_by_homing():
    text = "M18\nG0 X1\nG1 X2 F600\nG28 X0 Y0\nG0 X1\nM84\nG1 X3\n"
    assert lines(text, "HY039") == [2, 7]


def test_hy039_bare_g28_homes_nothing():
    assert lines("M18\nG28\nG0 X1\n", "HY039") == [3]


def test_hy042_by_printer():
    text = "G1 X1 A5 F600\nG0 B2\n"
    assert lines(text, "HY042", printer="30m") == [1, 2]
    assert lines(text, "HY042", printer="esr") == [1, 2]
    assert lines(text, "HY042", printer="ehr") == []
    assert lines(text, "HY042", printer="16a") == []


def test_hy042_where_the_pages_give_a_code_a_and_b():
    # M203 "An is the new speed in the A axis for G0 moves", G54-G59 "An is the offset in mm in the A
    # axis", M6 "An is the offset in the A axis"
    text = "M203 X3000 A500\nG54 X30 B-2\nG59 A1\nM6 T1 O2 X20 A3\nM6 T0 O1 X0 Y0 Z0\nM203 Y2000\n"
    assert lines(text, "HY042", printer="30m") == [1, 2, 3, 4]
    message = next(f.message for f in check_text(text, dialect="hyrel", printer="esr") if f.code == "HY042")
    assert "ESR" in message
    assert lines(text, "HY042", printer="ehr") == []


def test_hy050_once_and_only_without_a_working_feed():
    assert lines("G0 X1 F3000\nG1 X2 E1\nG1 X3 E1\n", "HY050") == [2]
    assert lines("G1 X2 E1 F600\nG0 X1 F3000\nG1 X3 E1\n", "HY050") == []
    assert lines("G0 X1 F3000\nG2 I5 E1\n", "HY050") == [2]


def test_hy053_g53_and_g93():
    assert lines("G53\nG0 X0\n", "HY053") == []
    assert lines("G53 G0 X0\nG0 G53 Z0\nG53 X1\n", "HY053") == [1, 2, 3]
    # G94 after G93 confirms inverse time
    assert lines("G93\nG1 X1 F10\nG94\n", "HY053") == [1]
    # a constant F on every move is a native job, not inverse time
    constant = "G93\n" + "".join(f"G1 X{i} F300 E1\n" for i in range(8))
    assert lines(constant, "HY053") == []


def test_hy060_once_and_not_with_m229_anywhere():
    sliced = "".join(f"G1 X{i} Y1 E{0.3 + i / 100:.2f} F600\n" for i in range(8))
    assert lines(sliced, "HY060") == [1]
    assert lines(sliced + "M229 E1 D1\n", "HY060") == []
    assert lines("G1 X1 E1 F600\n" * 10, "HY060") == []


def test_hy060_stops_looking_after_look_at_moves_whatever_their_amounts():
    # (a job that cycles through a few amounts: the rule looks at LOOK_AT moves with E, then stops)
    from gclint.rules.hyrel.flow import SlicerEWithoutM229

    head = "".join(f"G1 X{i} Y1 E{0.3 + i % 3 / 100:.2f} F600\n" for i in range(SlicerEWithoutM229.LOOK_AT))
    later = "".join(f"G1 X{i} Y2 E{0.5 + i / 100:.2f}\n" for i in range(8))
    assert lines(head + later, "HY060") == []
    assert lines(head[: head.index("\n") + 1] + later, "HY060") == [1]


def test_hy030_g0_with_e():
    assert lines("G0 X1 E1\nG1 X2 E1 F600\n", "HY030") == [1]


def test_hy033_g1_s_and_m221_negative_only():
    # the page gives the multiplier no limit (HY033): only a negative one is reported
    assert lines("G1 X1 E1 S16 F600\nG1 X2 E1 S-1.2\nM221 S95\nM221 S-1\nM221 S2.5\n", "HY033") == [2, 4]


# -- flow codes -------------------------------------------------------------------------------------------


def test_hy001_only_the_combination_the_page_calls_illegal():
    # "Note: E1 D0 is an illegal combination"; the page says nothing of an omitted D, and the firmware, given E1
    # with no routing, sends the steps as D3 does (src/MCode.c M_Code_M229: "force canbus E steps")
    assert lines("M229 E1 D0\n", "HY001") == [1]
    assert lines("M229 E1\n", "HY001") == []
    assert lines("M229 E0 D2\nM229 E0 D0\nM229 E1\n", "HY001") == []


def test_hy011_range_on_the_same_line_and_persisting():
    assert lines("M106 C255 T0 S200\nM106 T0 S255\n", "HY011") == []
    assert lines("M106 C255\nM30\nM106 T0 S255\n", "HY011") == [3]  # M30 resets the range


def test_hy012_info_for_undocumented_range():
    result = [f for f in check_text("M106 C50\n", dialect="hyrel") if f.code == "HY012"]
    assert [f.severity.label for f in result] == ["info"]


def test_hy013_hy014_follow_m229():
    assert lines("M83\nM229 E1 D1\nM83\nM229 E0\nM82\n", "HY013") == [1, 5]
    assert lines("M756 S0.2\nM229 E1 D1\nM756 S0.2\nM30\nM756 S0.2\n", "HY014") == [3]


def test_hy015_hints():
    def message(line):
        return [f.message for f in check_text(line + "\n", dialect="hyrel") if f.code == "HY015"][0]

    assert "M721" in message("G10")
    assert "M722" in message("G11")
    assert "M104" in message("G10 P0 S210 R150")
    assert "M6" in message("G10 L2 P1 X0")


def test_a_failing_member_does_not_crash_the_file(monkeypatch):
    from gclint.rules.hyrel.motion import TravelMarkedPrinting

    def broken(self, line, cmd):
        raise RuntimeError("boom")

    monkeypatch.setattr(TravelMarkedPrinting, "move", broken)
    result = Linter(Options(dialect="hyrel")).check_text("G1 X1 Y1 E-1 F600\nM620 E1\nM30\nM18\nG0 X1 E1\n")
    assert result.error is not None and "internal error in rule HY031" in result.error  # the member, by name
    assert any(f.code == "HY020" for f in result.findings)  # the other rules went on
    assert {"HY030", "HY039"} <= {f.code for f in result.findings}  # and the listener's other members too


def test_a_failing_listener_goes_with_its_members(monkeypatch):
    # (its own code failed, not a member's: no member to blame alone, so all go, named once by the first)
    def broken(self, line, cmd):
        raise RuntimeError("boom")

    monkeypatch.setattr(MoveChecks, "move", broken)
    result = Linter(Options(dialect="hyrel")).check_text("G0 X1 Y1 E1\nM620 E1\nG0 X2 E1\nM30\n")
    assert result.error is not None and result.error.count("internal error") == 1
    assert "internal error in rule HY030" in result.error and "at line 1" in result.error
    codes = {f.code for f in result.findings}
    assert "HY020" in codes and "HY030" not in codes


@pytest.mark.parametrize("e", ["0", "-0", ".0", "0.000", "+0", "-.5", "-1", "0."])
def test_hy031_relative_zero_or_negative_prints(e):
    assert lines(f"M83\nG1 X1 Y1 E{e} F600\n", "HY031") == [2]


@pytest.mark.parametrize("e", [".5", "0.01", "10", "+1", "1.", "00.1"])
def test_hy031_relative_positive_is_fine(e):
    assert lines(f"M83\nG1 X1 Y1 E{e} F600\n", "HY031") == []


def test_hy031_absolute_repeat_and_reset():
    # the same E as the last good move is fine while the E position equals it, not after G92 E moved it
    text = "M82\nG92 E0\nG1 X1 Y1 E2 F600\nG1 X2 Y1 E2\nG92 E5\nG1 X3 Y1 E2\n"
    assert lines(text, "HY031") == [6]
