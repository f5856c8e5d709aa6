"""``gclint diff`` after a stranger's review: pauses, dwells and Hyrel's one-shot G1 S flow are compared;
a finding explains only what it is about; a finding on the line of the last agreeing move still counts;
Marlin's one part fan is compared as one fan at the end."""

from __future__ import annotations

import pytest

from gclint import dialects
from gclint.simulate import Mapping, diff_sources
from gclint.simulate.translation import explanations_from
from gclint.syntax.source import Source

from .test_diff import diff_texts, translate_and_diff

JOB = "G28\nM83\nM104 S200\nM109 S200\nM106 S128\nG1 Z0.2 X10 F600\nG1 X20 E1\nG4 S10\nG1 X30 E1\nG1 X40 E1\n"


def _edited(old: str, new: str) -> str:
    text, _, diff = translate_and_diff("marlin", JOB)
    assert not diff.differences
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize(
    ("old", "new", "aspect"),
    [
        ("G4 S10\n", "", "dwell"),
        ("G4 S10\n", "G4 S100\n", "dwell"),
        ("G4 S10\n", "G4 S5 P5000\n", None),  # Hyrel adds S and P: 10 s, the same dwell
        ("G1 X30 E1\n", "M0\nG1 X30 E1\n", "pause"),
        ("G1 X30 E1\n", "G1 X30 E1 S3\n", "flow"),  # "Sn is a one-time ... flow rate multiplier"
        ("G1 X40 E1\n", "G1 X40 E1\nG4 P500\n", "dwell"),  # after the last working move
        ("G1 X40 E1\n", "G1 X40 E1\nM0\n", "pause"),
    ],
)
def test_edited_pauses_dwells_and_flow_are_differences(old: str, new: str, aspect: str | None) -> None:
    diff = diff_texts("marlin", JOB, _edited(old, new))
    assert [d.aspect for d in diff.differences] == ([aspect] if aspect else [])


@pytest.mark.parametrize(
    ("dialect", "source", "output"),
    [
        ("marlin", "G1 X1 F100\nG4 P1500\nG1 X2\n", "G1 X1 F100\nG4 S1.5\nG1 X2\n"),  # Marlin P: ms
        ("marlin", "G1 X1 F100\nG4 S2 P500\nG1 X2\n", "G1 X1 F100\nG4 S2\nG1 X2\n"),  # Marlin: S wins
        ("machinekit", "G1 X1 F100\nG4 P2\nG1 X2\n", "G1 X1 F100\nG4 S2\nG1 X2\n"),  # LinuxCNC P: seconds
        ("carvera", "G1 X1 F100\nG4 P2\nG1 X2\n", "G1 X1 F100\nG4 S2\nG1 X2\n"),  # grbl mode P: seconds
        ("marlin", "G1 X1 F100\nM600\nG1 X2\n", "G1 X1 F100\nM0\nG1 X2\n"),
        ("reprap", "G1 X1 F100\nM226\nG1 X2\n", "G1 X1 F100\nM0\nG1 X2\n"),
        ("machinekit", "G1 X1 F100\nM1\nG1 X2\n", "G1 X1 F100\nG1 X2\n"),  # an optional stop
    ],
)
def test_dwells_and_pauses_in_each_dialect(dialect: str, source: str, output: str) -> None:
    if dialect in ("machinekit", "carvera"):  # CNC jobs: every feed move is a working move
        src, out = "G21 G90\n" + source, "G21 G90\n" + output
    else:
        src = "M83\n" + source.replace("X1 F100", "X1 E1 F100").replace("X2\n", "X2 E1\n")
        out = "M83\n" + output.replace("X1 F100", "X1 E1 F100").replace("X2\n", "X2 E1\n")
    timing = {"dwell", "pause"}
    diff = diff_texts(dialect, src, out)
    assert not [d for d in diff.differences if d.aspect in timing], diff.differences
    bare = "".join(line for line in out.splitlines(keepends=True) if not line.startswith(("G4", "M0")))
    if bare != out:  # and one missing is seen
        assert {d.aspect for d in diff_texts(dialect, src, bare).differences} & timing


def test_finding_on_the_line_of_the_last_agreeing_move_explains() -> None:
    """C: the M3 after the move on line 3 runs after it; its TR003 (assumed 15000 rpm) explains a speed that
    differs.  (With no spindle-max-rpm the speeds are compared relatively, so the translation has none.)"""
    source = "G21 G90 G54\nG0 X0 Y0 Z1\nG1 Z-1 F100 M3 S12000 M7\nG1 X10\nG1 X20 M5 M9\nM2\n"
    text, result, diff = translate_and_diff("carvera", source)
    assert not diff.unexplained(), [(d.aspect, d.source, d.output) for d in diff.unexplained()]
    slower = diff_sources(
        Source.from_text(source, "source"),
        Source.from_text(text.replace("M3 T0 S80", "M3 T0 S60"), "output"),
        dialects.get("carvera"),
        dialects.get("hyrel"),
        Mapping(spindle_max_rpm=15000),
        explanations_from(result),
    )
    assert [(d.aspect, d.explained_by) for d in slower.differences] == [("spindle", ("TR003", 3))]


# -- D: Marlin's one part fan ---------------------------------------------------------------------------------

SHARED_FAN = (
    "M83\nM104 T0 S210\nM104 T1 S220\nM109 T0 S210\nM109 T1 S220\nG1 Z0.2 F600\nG1 X10 Y10 E1 F1200\nM106 S255\n"
    "T1\nG1 X0 Y0 F3000\n"
)


def test_the_part_fan_is_one_fan_at_the_end() -> None:
    """D: the part fan is at 100 % on both sides; the translator left it on the head that last printed."""
    text, _, diff = translate_and_diff("marlin", SHARED_FAN)
    assert not diff.differences, [(d.aspect, d.source, d.output) for d in diff.differences]
    slower = diff_texts("marlin", SHARED_FAN, text.replace("M106 T0 S255", "M106 T0 S25"))
    assert [(d.aspect, d.source, d.output) for d in slower.differences] == [
        ("end", "fans: part fan 100 %", "fans: part fan 9.8 %")
    ]
    both = diff_texts("marlin", SHARED_FAN, text.replace("M106 T0 S255", "M106 T0 S255\nM106 T1 S25"))
    assert [d.aspect for d in both.differences] == ["end"]  # two heads' fans at two speeds are not one fan


# -- B: a finding explains only what it is about ----------------------------------------------------------------


def _diff_with(dialect: str, source: str, output: str, findings: list[tuple[str, tuple[str, ...], list[int]]]):
    from gclint import dialects
    from gclint.simulate import Explanations, Mapping, diff_sources
    from gclint.syntax.source import Source

    return diff_sources(
        Source.from_text(source, "source"),
        Source.from_text(output, "output"),
        dialects.get(dialect),
        dialects.get("hyrel"),
        Mapping(),
        Explanations([(code, frozenset(aspects), lines) for code, aspects, lines in findings]),
    )


BAMBU = "M83\nM104 S200\nM109 S200\nG1 Z0.2 X10 F600 E1\nG1 X20 E1\nM106 S255\nT9\nG1 X30 E1\nG1 X40 E1\n"


def test_a_finding_about_a_tool_with_no_head_explains_only_that_tool() -> None:
    """B: TR007 (tool 9 has no head) with the aspect ``tool:9`` explains the head and the end state of tool 9,
    not an edited fan or set-point."""
    text, result, _ = translate_and_diff("marlin", BAMBU)
    tr007 = [("TR007", ("tool:9",), [7])]
    diff = _diff_with("marlin", BAMBU, text, tr007)
    assert diff.differences and not diff.unexplained(), [(d.aspect, d.source) for d in diff.unexplained()]
    edited = text.replace("M106 T0 S255", "M106 T0 S25").replace("M109 T0 S200", "M109 T0 S200\nM104 T0 S190")
    diff = _diff_with("marlin", BAMBU, edited, tr007)
    unexplained = {(d.aspect, d.source.split(":")[0]) for d in diff.unexplained()}
    assert ("fan", "100 %") in unexplained
    assert ("end", "fans") in unexplained
    assert ("end", "heaters") in unexplained


def test_a_finding_about_another_fan_does_not_explain_the_part_fan() -> None:
    """B: a dropped ``M106 P3`` (an aux fan) explains a difference in fan 3, not one in a head's fan."""
    source = "M83\nM104 S200\nM109 S200\nM106 P3 S255\nM106 S255\nG1 Z0.2 X10 F600 E1\nM106 P3 S0\nG1 X20 E1\n"
    output = "M83\nM104 T0 S200\nM109 T0 S200\nM106 C255\nM106 T0 S128\nT0\nG1 Z0.2 X10 F600 E1\nG1 X20 E1\n"
    for aspects in (("aux",), ("fan:3",)):
        diff = _diff_with("reprap", source, output, [("TR002", aspects, [4, 7])])
        found = {d.aspect: d for d in diff.differences}
        assert found["aux"].source == "fan 3 100 %" and found["aux"].explained_by == ("TR002", 4)
        assert found["fan"].explained_by is None
        assert found["end"].explained_by is None  # part fan 100 % -> 50.2 %


# -- A, as time allowed: inverse-time feed, head and tool offsets -------------------------------------------


@pytest.mark.parametrize("dialect", ["machinekit", "carvera"])
def test_inverse_time_feed_is_converted(dialect: str) -> None:
    """G93: "1/min in G93 inverse-time": ``G1 X10 F2`` from X0 takes half a minute, 20 mm/min."""
    source = "G21 G90\nG0 X0 Y0 Z0\nG1 X5 F100\nG93\nG1 X15 F2\nG94\nG1 X20 F100\n"
    good = diff_texts(dialect, source, "G21\nG90\nG0 X0 Y0 Z0\nG1 X5 F100\nG1 X15 F20\nG1 X20 F100\n")
    assert not [d for d in good.differences if d.aspect == "feed"], good.differences
    bad = diff_texts(dialect, source, "G21\nG90\nG0 X0 Y0 Z0\nG1 X5 F100\nG1 X15 F2\nG1 X20 F100\n")
    assert [(d.aspect, d.source, d.output) for d in bad.differences if d.aspect == "feed"] == [("feed", "F20", "F2")]
    _, _, translated = translate_and_diff(dialect, source)
    assert not translated.unexplained()  # the translator reports the G93 it cannot carry


@pytest.mark.parametrize(
    ("old", "new", "change"),
    [
        ("T0\n", "M6 T0 O1 Z5\nT0\n", "Z5.2"),  # "M6 T# O1 X20 Y-30 Z40 ... Z40 (Z+40)", invoked by T#
        ("G1 Z0.2 X10 F600\n", "M660 H1 Z2\nG1 Z0.2 X10 F600 H1\n", "Z2.2"),  # "Z28.2 (+28.2 to Z position)"
        ("G1 Z0.2 X10 F600\n", "M660 H1 Z2\nG1 Z0.2 X10 F600 H1\nG28 Z0\nG1 Z0.2\n", None),  # G28 clears H
    ],
)
def test_hyrel_head_offsets_move_the_head(old: str, new: str, change: str | None) -> None:
    diff = diff_texts("marlin", JOB, _edited(old, new))
    assert [(d.aspect, d.output) for d in diff.differences if d.aspect == "position"] == (
        [("position", change)] if change else []
    )


def test_reprap_tool_offsets_are_seen() -> None:
    """RRF ``G10 L1 P1 X10``: tool 1's offset, applied by T1; the translator drops it (a warning)."""
    source = "G28\nM83\nG10 L1 P1 X10\nM104 S200\nM109 S200\nT1\nM104 S200\nM109 S200\nG1 Z0.2 X10 F600\nG1 X20 E1\n"
    _, _, diff = translate_and_diff("reprap", source)
    assert [d.aspect for d in diff.differences] == ["position"]
    assert "tool 1 offset" in diff.differences[0].source
    assert diff.differences[0].explained_by is not None and not diff.unexplained()
    plain = source.replace("G10 L1 P1 X10\n", "G10 L1 P1 X0\n")
    assert not translate_and_diff("reprap", plain)[2].differences


def test_carvera_optional_stop_pauses_in_optional_stop_mode() -> None:
    """Carvera M1 pauses after "M334 Turn on optional stop mode", not before it or after M333."""
    source = "G21 G90\nG0 X0 Y0 Z0\nG1 X5 F100\nM1\nG1 X6\nM334\nM1\nG1 X7\nM333\nM1\nG1 X8\n"
    output = "G21\nG90\nG54\nG0 X0 Y0 Z0\nG1 X5 F100\nG1 X6\nM0\nG1 X7\nG1 X8\n"
    assert not [d for d in diff_texts("carvera", source, output).differences if d.aspect == "pause"]
    moved = output.replace("M0\nG1 X7\n", "G1 X7\nM0\n")
    assert [d.source_line for d in diff_texts("carvera", source, moved).differences if d.aspect == "pause"] == [
        8
    ]  # then at 11: one entry, 2 moves
    _, _, diff = translate_and_diff("carvera", source)
    assert not diff.differences


def test_a_difference_about_several_fans_needs_a_finding_for_each() -> None:
    """B: ``fan 2, fan 3 -> none`` is explained by findings about fan 2 and fan 3, not by one of them."""
    source = "M83\nM104 S200\nM109 S200\nM106 P2 S100\nM106 P3 S180\nG1 Z0.2 X10 F600 E1\n"
    output = "M229 E1 D1\nM83\nM104 T0 S200\nM109 T0 S200\nT0\nG1 Z0.2 X10 F600 E1\nM30\n"
    both = _diff_with("marlin", source, output, [("TR002", ("fan:2",), [4]), ("TR002", ("fan:3",), [5])])
    assert [(d.aspect, d.explained_by) for d in both.differences] == [("aux", ("TR002", 4)), ("end", ("TR002", 4))]
    one = _diff_with("marlin", source, output, [("TR002", ("fan:2",), [4])])
    assert [(d.aspect, d.explained_by) for d in one.differences] == [("aux", None), ("end", None)]
