"""Arc rules (HY016-HY019, HY037, HY052): full-circle geometry in absolute and relative mode."""

from __future__ import annotations

import pytest

from gclint.engine import check_text


def codes(text: str, code: str, **options) -> list[int]:
    """Line numbers of the findings with ``code``."""
    options.setdefault("dialect", "hyrel")
    return [f.line for f in check_text(text, **options) if f.code == code]


@pytest.mark.parametrize(
    "moves, arc, full",
    [
        # absolute: the end is compared with the current position
        ("G90\nG1 X10 Y5 F600", "G2 I5 J0 S6", True),  # X/Y omitted
        ("G90\nG1 X10 Y5 F600", "G2 X10 Y5 I5 J0 S6", True),  # end = start
        ("G90\nG1 X10 Y5 F600", "G2 X10.0 Y5.000 I5 S6", True),
        ("G90\nG1 X10 Y5 F600", "G2 X10 I5 S6", True),  # Y omitted, X unchanged
        ("G90\nG1 X10 Y5 F600", "G2 X10.0005 Y5 I5 S6", True),  # within the tolerance
        ("G90\nG1 X10 Y5 F600", "G2 X20 Y5 I5 J0 S6", False),
        ("G90\nG1 X10 Y5 F600", "G3 Y6 I5 S3", False),
        # relative: X/Y are the displacement
        ("G90\nG1 X10 Y5 F600\nG91", "G2 X0 Y0 I5 S6", True),
        ("G90\nG1 X10 Y5 F600\nG91", "G2 I5 S6", True),
        ("G90\nG1 X10 Y5 F600\nG91", "G2 X10 Y5 I5 S6", False),  # would be a full circle in G90
        ("G90\nG1 X10 Y5 F600\nG91", "G3 Y-0.5 I5 S12", False),
        # relative moves before the arc are accumulated
        ("G90\nG1 X10 Y5 F600\nG91\nG1 X5 Y5\nG90", "G2 X15 Y10 I5 S6", True),
        ("G90\nG1 X10 Y5 F600\nG91\nG1 X5 Y5\nG90", "G2 X10 Y5 I5 S6", False),
        # G92 sets the position
        ("G90\nG1 X10 Y5 F600\nG92 X0 Y0", "G2 X0 Y0 I5 S6", True),
        ("G90\nG1 X10 Y5 F600\nG92 X0 Y0", "G2 X10 Y5 I5 S6", False),
        # the previous arc's end is the next arc's start
        ("G90\nG1 X0 Y0 F600\nG2 X20 Y0 I10 J0", "G2 X20 Y0 I-5 S6", True),
    ],
)
def test_segment_count_needs_a_full_circle(moves, arc, full):
    found = codes(f"{moves}\n{arc}\n", "HY016")
    assert (not found) == full, found


def test_start_unknown_is_silent():
    # no move before: the start is unknown, so the end cannot be compared
    assert codes("G2 X10 Y0 I5 J0 S6\n", "HY016") == []
    # relative mode needs no start position
    assert codes("G91\nG2 X10 Y0 I5 J0 S6\n", "HY016") == [2]


def test_segment_length_below_3_is_any_arc():
    assert codes("G1 X0 Y0 F600\nG2 X20 Y0 I10 S2.99\n", "HY016") == []
    assert codes("G1 X0 Y0 F600\nG2 X20 Y0 I10 S3\n", "HY016") == [2]


def test_segment_length_zero_is_a_warning():
    found = [f for f in check_text("G1 X0 Y0 F600\nG2 I10 S0\n", dialect="hyrel") if f.code == "HY016"]
    assert [f.severity.label for f in found] == ["warning"]


def test_arc_without_centre():
    assert codes("G1 X0 Y0 F600\nG2 X10 Y0\n", "HY017") == [2]
    assert codes("G1 X0 Y0 F600\nG2 X10 Y0 I0 J0\n", "HY017") == [2]
    assert codes("G1 X0 Y0 F600\nG2 X10 Y0 I5\n", "HY017") == []
    assert codes("G1 X0 Y0 F600\nG2 X10 Y0 J-5\n", "HY017") == []
    # the R form is reported once, as R
    assert len(codes("G1 X0 Y0 F600\nG2 X10 Y0 R5\n", "HY017")) == 1


def test_spiral_lap_parameters():
    assert codes("G2.1 I15 J20 P1.2 E1\n", "HY018") == []
    assert codes("G2.1 I15 J20 P1.2 L3 R2 E1\n", "HY018") == []
    assert codes("G2.1 I15 J20 P1.2 R2 E1\n", "HY018") == [1]  # R2 needs L
    assert codes("G3.1 I15 J20 E1\n", "HY018") == [1]  # P required
    assert codes("G3.1 X5 I15 J20 P1 E1\n", "HY018") == [1]


def test_spiral_pitch_or_laps_and_both_is_info():
    found = [f for f in check_text("G2.2 X12 I25 P4 L3 E1\n", dialect="hyrel") if f.code == "HY019"]
    assert [f.severity.label for f in found] == ["info"]


def test_arc_e_ignored_only_under_m229_e1():
    text = "G1 X0 Y0 F600\nG2 I5 E1\nM229 E1 D1\nG2 I5 E0.5\nM229 E0\nG2 I5 E1\n"
    assert codes(text, "HY037") == [4]


def test_plain_arc_plane():
    text = "G18\nG2 X10 Z5 I5 J0 F600\nG2.3 X10 Z5 I5 K0\nG17\nG2 X10 I5\nG16\nG3 I5\n"
    assert codes(text, "HY052") == [2, 7]


def test_v4_dialect_too():
    assert codes("G1 X0 Y0 F600\nG2 X20 Y0 I10 S6\n", "HY016", dialect="hyrel-v4") == [2]


def test_not_on_other_dialects():
    assert codes("G1 X0 Y0 F600\nG2 X20 Y0 R10\n", "HY017", dialect="marlin") == []
