"""The summary reads Hyrel addresses as ``check`` (the HY rules) and ``explain`` do: one reading of a T variable
(gclint/dialects/addressing.py).  Inputs from a Hyrel operator's review."""

from __future__ import annotations

from pathlib import Path

from gclint.engine import Linter, Options
from gclint.summary import JobSummary, render, summarize_path
from gclint.syntax.source import Source

V5 = "; gclint: dialect=hyrel\n"


def _summary(tmp_path: Path, text: str, first: str = V5) -> JobSummary:
    job = tmp_path / "job.gcode"
    job.write_text(first + text)
    return summarize_path(str(job))


def _codes(tmp_path: Path, text: str) -> list[str]:
    job = tmp_path / "check.gcode"
    job.write_text(V5 + text)
    source = Source.open(str(job))
    return [f.code for f in Linter(Options()).check_source(source).findings]


def _heads(summary: JobSummary) -> dict[str, tuple[list[float], list[float], int]]:
    return {h.head: (h.set_points, h.waits, h.printing_moves) for h in summary.heads}


SQUAD = (
    "M6 T0 O1 X0 Y0\nM6 T1 O2 X30 Y0\nM702 T0 S30\nM703 T0 S30\nM703 T1 S30\nM104 T30 S215\nM109 T30 S215\n"
    "M140 S60\nM190 T46 S60\nT30\nG1 X10 Y10 F600\nG1 X20 E1\nG1 X30 E1\nM30\n"
)


def test_a_clone_squad_sets_and_prints_with_its_heads_and_its_wait_fails(tmp_path: Path) -> None:
    summary = _summary(tmp_path, SQUAD)
    # one row per head: the squad's set-point and printing go to its members; the wait on T30 fails (HY003)
    assert _heads(summary) == {"T0": ([215.0], [], 2), "T1": ([215.0], [], 2)}
    # M190 T46 (all beds) sets the bed and does not wait (HY003)
    assert summary.devices == {"bed": [60.0]}
    assert summary.waited_devices == {}
    text = render(summary)
    assert "waits for" not in text and "T30" not in text


def test_a_squad_without_members_is_one_row(tmp_path: Path) -> None:
    text = "M702 T0 S31\nM104 T31 S210\nM109 T31 S210\nT31\nG1 X10 Y10 F600\nG1 X20 E1\nM30\n"
    summary = _summary(tmp_path, text)
    assert _heads(summary) == {"T31": ([210.0], [], 1)}


def test_check_reports_the_waits_the_summary_does_not_count(tmp_path: Path) -> None:
    assert _codes(tmp_path, SQUAD).count("HY003") == 2


W0 = (
    "M6 T0 O1 X0 Y0\nM109 T0 S240 W0\nM190 T24 S60 W0\nM116\nT0\nG0 X0 Y25 Z1 F3000\nG1 X10 E1 F600\n"
    "G2 X20 Y25 I5 J0 E1\nG2.1 I25 J0 P4 L3 E1\nG2.2 X12 I25 P4 E1\nM30\n"
)


def test_w0_waits_at_m116(tmp_path: Path) -> None:
    summary = _summary(tmp_path, W0)
    assert _heads(summary)["T0"][:2] == ([240.0], [240.0])
    assert summary.waited_devices == {"bed": [60.0]}


def test_w0_without_m116_does_not_wait(tmp_path: Path) -> None:
    summary = _summary(tmp_path, W0.replace("M116\n", ""))
    assert _heads(summary)["T0"][:2] == ([240.0], [])
    assert summary.waited_devices == {}


def test_spirals_are_printing_moves_not_measured(tmp_path: Path) -> None:
    summary = _summary(tmp_path, W0)
    assert _heads(summary)["T0"][2] == 4  # G1, G2, G2.1, G2.2
    assert summary.unmeasured_spirals == 2
    assert summary.unmeasured_moves == 3  # and the first G0, from an unknown position
    # (the G1 prints from X0: where a printing move starts is in the extent; G2.1 ends where it starts)
    assert summary.x_range == (0.0, 20.0) and summary.y_range == (25.0, 25.0)
    assert "2 spirals (G2.1/G2.2: the path is not modelled)" in render(summary)
    ended = _summary(tmp_path, W0.replace("G2.2 X12", "G2.2 X40"))
    assert ended.x_range == (0.0, 40.0)  # G2.2 ends at its X


def test_an_all_devices_set_point_goes_to_the_heads_and_beds_it_covers(tmp_path: Path) -> None:
    end = "M6 T0 O1 X0 Y0\nM6 T1 O2 X30 Y0\nM109 T0 S215\nM140 S60\nT0\nG1 X10 Y10 F600\nG1 X20 E1\n"
    summary = _summary(tmp_path, end + "M104 T40 S0\nM140 T46 S0\nM30\n")
    assert _heads(summary) == {"T0": ([215.0, 0.0], [215.0], 1), "T1": ([0.0], [], 0)}
    assert summary.devices == {"bed": [60.0, 0.0]}
    # v4: T variables 11 and 12 are yoke 1's first heads, T100 all heads (v4 T0 is all devices)
    v4_end = end.replace("T0 O1", "T11 O1").replace("T1 O2", "T12 O2").replace("M109 T0", "M109 T11")
    v4 = _summary(tmp_path, v4_end + "M104 T100 S0\nM30\n", "; gclint: dialect=hyrel-v4\n")
    assert _heads(v4) == {"T0": ([215.0, 0.0], [215.0], 1), "T1": ([0.0], [], 0)}


def test_a_bed_command_on_a_head_address_is_the_head_as_hy046_reads_it(tmp_path: Path) -> None:
    text = "M6 T0 O1 X0 Y0\nM190 T0 S60\nM140 T1 S60\nM109 T0 S215\nT0\nG1 X10 Y10 F600\nG1 X20 E1\nG1 X30 E1\nM30\n"
    summary = _summary(tmp_path, text)
    assert summary.devices == {}
    assert _heads(summary) == {"T0": ([60.0, 215.0], [60.0, 215.0], 2), "T1": ([60.0], [], 0)}
    assert _codes(tmp_path, text).count("HY046") == 2


def test_the_second_bed_is_its_own_row(tmp_path: Path) -> None:
    summary = _summary(tmp_path, "M140 S60\nM190 T25 S70\nM30\n")
    assert summary.devices == {"bed": [60.0], "bed 2 (T25)": [70.0]}
    assert summary.waited_devices == {"bed 2 (T25)": [70.0]}


def test_the_extent_holds_where_printing_moves_start(tmp_path: Path) -> None:
    summary = _summary(tmp_path, "; gclint: dialect=marlin\nG28\nG1 X10 Y10 Z0.2 F1200\nG1 X40 Y10 E2\nM30\n")
    assert summary.x_range == (10.0, 40.0) and summary.y_range == (10.0, 10.0)
