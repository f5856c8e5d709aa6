"""Issue 14: ``gclint summary`` (and the summary in the HTML report), checked against counts made by hand."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from gclint.summary import render, summarize_path
from tests.conftest import CORPUS, needs_corpus, run_cli

HAND = """\
; gclint: dialect=hyrel
M6 T0 O1 X0 Y0 Z0
M6 T1 O2 X20 Y0 Z0
M140 S60
M109 T0 S215
M104 T1 S200
G21
G90
G28 X0 Y0
M229 E1 D1
T0
G1 Z0.3 F600
G1 X10 Y0 E1 F1200
G1 X10 Y10 E2
G1 Z0.6 F600
G1 X0 Y10 E3 F1200
T1
G1 X0 Y0 E4
G4 P2000
M30
"""


def test_a_hand_written_job(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(HAND)
    s = summarize_path(str(job))
    heads = {h.head: h for h in s.heads}
    assert heads["T0"].set_points == [215] and heads["T0"].waits == [215] and heads["T0"].printing_moves == 3
    assert heads["T1"].set_points == [200] and heads["T1"].waits == [] and heads["T1"].printing_moves == 1
    assert heads["T0"].extruded_mm == pytest.approx(3) and heads["T1"].extruded_mm == pytest.approx(1)
    assert s.devices == {"bed": [60]} and s.waited_devices == {}
    assert s.flow.startswith("native then E values")
    assert s.layers == 2 and s.z_range == (0.3, 0.6)
    assert s.x_range == (0, 10) and s.y_range == (0, 10) and s.feed_range == (1200, 1200)
    assert s.printing_mm == pytest.approx(40)
    # by hand: 40 mm at 1200 mm/min = 2 s; the Z move 0.3 -> 0.6 at 600 = 0.03 s (the first Z move starts
    # where Z is unknown: not counted); G4 P2000 = 2 s
    assert s.time_s == pytest.approx(2 + 0.03 + 2, abs=0.005)


@needs_corpus
def test_a_prusaslicer_job_against_its_own_counts() -> None:
    path = CORPUS / "marlin" / "prusaslicer-2.6.1_benchy.gcode"
    text = path.read_text(errors="replace")
    s = summarize_path(str(path))
    layers = len(re.findall(r"^;LAYER_CHANGE", text, re.M))  # the slicer's own layer marks (160)
    # (issue 28: the start purge line at Z 0.2, printed before the first mark, was counted as one more layer)
    assert s.layers == layers and s.layer_marks == "prusaslicer"
    heights = [float(z) for z in re.findall(r"^;Z:([\d.]+)", text, re.M)]
    assert s.z_range == (heights[0], heights[-1])
    used = float(re.search(r"^; filament used \[mm\] = ([\d.]+)", text, re.M).group(1))
    [head] = s.heads
    assert head.extruded_mm == pytest.approx(used, rel=0.002)  # net E: retractions taken back
    assert s.bed == (0, 0, 180, 180) and s.outside_bed  # the purge line runs at Y -2, off the bed


def test_cli_text_and_json(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(HAND)
    out = run_cli("summary", str(job)).stdout.decode()
    assert "T0: set-points 215 °C; waits for 215; 3 printing moves; 3.0 mm of filament" in out
    assert "layers: 2, Z 0.3 to 0.6 mm" in out and "estimated time: 0 min 04 s" in out
    data = json.loads(run_cli("summary", "-f", "json", str(job)).stdout)
    assert data[0]["layers"] == 2 and data[0]["read_as"].startswith("hyrel v5")
    assert run_cli("summary", str(tmp_path / "missing.gcode")).returncode == 2


def test_html_report_has_the_summary_and_counts_in_words(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(HAND.replace("M109 T0 S215", "M109 T40 S215"))
    html = run_cli("check", "-f", "html", str(job)).stdout.decode()
    assert "Job summary" in html and "layers: 2, Z 0.3 to 0.6 mm" in html
    assert "1 error<" in html and "1 errors" not in html
    assert re.search(r"1 finding in 1 file", html)


MARLIN_TWO_TOOLS = ";FLAVOR:Marlin\nM104 S215\nM109 S215\nG28\nG92 E0\nG1 X10 Y10 E1 F1500\nT1\nM109 S220\nG1 X30 Y10 E2\nM104 S0\nM84\n"
HYREL_TWO_HEADS = (
    "M6 T0 O1 X0 Y0 Z0\nM6 T1 O2 X20 Y0 Z0\nT0\nM104 S200\nG1 X10 Y10 E1 F1200\n"
    "T1\nM109 S230\nG1 X20 Y10 E1\nM104 S0\nM30\n"
)


def test_marlin_temperatures_without_t_go_to_the_active_tool(tmp_path: Path) -> None:
    # Marlin M104/M109: T is the hotend index, the active one by default (Marlin G-code reference, M104)
    job = tmp_path / "mm.gcode"
    job.write_text(MARLIN_TWO_TOOLS)
    heads = {h.head: h for h in summarize_path(str(job)).heads}
    assert heads["extruder 0"].set_points == [215] and heads["extruder 0"].waits == [215]
    assert heads["extruder 1"].set_points == [220, 0] and heads["extruder 1"].waits == [220]
    assert heads["extruder 0"].printing_moves == 1 and heads["extruder 1"].printing_moves == 1
    # an explicit T still wins over the active tool
    job.write_text(MARLIN_TWO_TOOLS.replace("M104 S0", "M104 T0 S0"))
    heads = {h.head: h for h in summarize_path(str(job)).heads}
    assert heads["extruder 0"].set_points == [215, 0] and heads["extruder 1"].set_points == [220]


def test_hyrel_temperatures_without_t_go_to_the_focused_head_and_a_first_move_counts(tmp_path: Path) -> None:
    # Hyrel Gcode page, "M109 Wait for Temp (Head)", Example 6: "(no T# - use head with current focus)"
    job = tmp_path / "sm.gcode"
    job.write_text(HYREL_TWO_HEADS)
    s = summarize_path(str(job))
    heads = {h.head: h for h in s.heads}
    assert heads["T0"].set_points == [200] and heads["T0"].waits == []
    assert heads["T1"].set_points == [230, 0] and heads["T1"].waits == [230]
    # the first printing move starts where the state does not know: it prints, and its end is known
    assert heads["T0"].printing_moves == 1 and heads["T1"].printing_moves == 1
    assert s.x_range == (10, 20) and s.y_range == (10, 10)
    assert s.printing_mm == pytest.approx(10) and s.unmeasured_moves == 1  # only its length is unknown
    out = run_cli("summary", str(job)).stdout.decode()
    assert "(and 1 move from an unknown position, not measured)" in out


def test_a_head_with_no_set_point_is_said_in_words(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(";FLAVOR:Marlin\nM104 S215\nG28\nG92 E0\nG1 X10 Y10 E1 F1500\nT1\nG1 X30 Y10 E2\n")
    out = run_cli("summary", str(job)).stdout.decode()
    assert "extruder 1: no set-point in the job; 1 printing moves" in out
    assert "none set in the job °C" not in out


def _hand_count(text: str) -> dict[int, tuple[list[float], list[float], int, float]]:
    """Per tool, by a reading independent of the machine state: set-points (M104/M109 S or R, T or the
    active tool), waits, printing moves (E advances; relative or absolute E) and net filament."""
    tool, relative, e = 0, False, None
    sets: dict[int, list[float]] = {}
    waits: dict[int, list[float]] = {}
    moves: dict[int, int] = {}
    filament: dict[int, float] = {}
    for raw in text.splitlines():
        words = raw.split(";")[0].upper().split()
        if not words:
            continue
        code, params = words[0], {w[0]: w[1:] for w in words[1:]}
        if re.fullmatch(r"T\d+", code):
            tool = int(code[1:])
        elif code in ("M82", "M83"):
            relative = code == "M83"
        elif code == "G92" and "E" in params:
            e = float(params["E"])
        elif code in ("M104", "M109") and ("S" in params or "R" in params):
            value = float(params.get("S", params.get("R")))
            target = int(params["T"]) if "T" in params else tool
            sets.setdefault(target, []).append(value)
            if code == "M109":
                waits.setdefault(target, []).append(value)
        elif code in ("G0", "G1", "G2", "G3") and "E" in params:  # Marlin: G0 extrudes as G1 does
            value = float(params["E"])
            step = value if relative else (value - e if e is not None else None)
            e = e if relative else value
            if step is not None:
                filament[tool] = filament.get(tool, 0.0) + step
                moves[tool] = moves.get(tool, 0) + (step > 0)
    return {t: (sets.get(t, []), waits.get(t, []), moves.get(t, 0), filament.get(t, 0.0)) for t in moves | sets}


@needs_corpus
@pytest.mark.parametrize(
    "name", ["prusaslicer-2.8.0-alpha4_mmu_attribute_test.gcode", "prusaslicer-2.5.0_MK3SMMU2S_full_m73.gcode"]
)
def test_multi_tool_prusaslicer_jobs_against_hand_counts(name: str) -> None:
    path = CORPUS / "marlin" / name
    hand = _hand_count(path.read_text(errors="replace"))
    assert len(hand) >= 2
    heads = {h.head: h for h in summarize_path(str(path)).heads}
    assert set(heads) == {f"extruder {t}" for t in hand}
    for tool, (sets, waits, moves, filament) in hand.items():
        head = heads[f"extruder {tool}"]
        # (the summary lists each value once, in the order the job first sets it)
        assert head.set_points == list(dict.fromkeys(sets)) and head.waits == list(dict.fromkeys(waits))
        assert head.printing_moves == moves and head.extruded_mm == pytest.approx(filament, abs=0.01)


def test_a_marlin_g0_that_extrudes_prints(tmp_path: Path) -> None:
    # Marlin: G0 is an alias of G1, E allowed, it extrudes (Marlin G-code reference, G0-G1): a slicer's purge line
    job = tmp_path / "purge.gcode"
    job.write_text(";FLAVOR:Marlin\nG28\nM83\nG0 X10 Y0 E5 F500 ; purge\nG0 X20 Y0\nG1 X30 Y0 E1\n")
    s = summarize_path(str(job))
    [head] = s.heads
    assert head.printing_moves == 2 and head.extruded_mm == pytest.approx(6)
    assert s.printing_mm == pytest.approx(20) and s.travel_mm == pytest.approx(10)


def test_a_job_that_sweeps_set_points_and_layers_stays_small(tmp_path: Path) -> None:
    """Memory: distinct set-points are listed up to MAX_VALUES, the rest counted; layers are counted."""
    from gclint.summary import MAX_VALUES, render

    job = tmp_path / "sweep.gcode"
    job.write_text("".join(f"G1 Z{i / 10:g} E1 F100\nM104 T0 S{100 + i}\nM140 T24 S{i}\n" for i in range(1, 301)))
    s = summarize_path(str(job))
    head = next(h for h in s.heads if h.head == "T0")
    assert len(head.set_points) == MAX_VALUES and head.more_set_points == 300 - MAX_VALUES
    assert len(s.devices["bed"]) == MAX_VALUES and s.more_device_set_points["bed"] == 300 - MAX_VALUES
    assert s.layers == 300 and s.z_range == (0.1, 30)
    assert f"(and {300 - MAX_VALUES:,} more settings not listed)" in render(s)


# -- issue 28: layers as the slicer counts them, a planned time --------------------------------------------------


def _job(tmp_path: Path, text: str, name: str = "job.gcode") -> str:
    job = tmp_path / name
    job.write_text(text)
    return str(job)


def test_layers_without_marks_leave_out_primes_and_parking(tmp_path: Path) -> None:
    # issue 28: a prime of the extruder alone at Z15 (the start G-code of a Prusa MINI) made "layers: 1, Z 15 to 15"
    layers = "".join(
        f"G1 Z{z} F720\nG1 X10 Y10 F6000\nG1 X30 Y10 E1 F1200\nG1 X30 Y30 E1\nG1 Z{z + 5} X100 Y100 F6000\n"
        for z in (0.2, 0.4, 0.6)
    )
    job = "G28\nM83\nG1 X0 Y-4 Z15 F4800\nG1 E2 F2400 ; prime\n" + layers + "G1 Z40 X0 Y200 F6000 ; park\nM84\n"
    s = summarize_path(_job(tmp_path, job))
    assert s.layers == 3 and s.z_range == (0.2, 0.6) and s.layer_marks == ""


def test_a_spiral_without_marks_counts_a_layer_per_turn(tmp_path: Path) -> None:
    square = [(10, 0), (10, 10), (0, 10), (0, 0)]
    text = "G28\nM83\n"
    for z in (0.2, 0.4):  # two flat bottom layers
        text += f"G1 Z{z} F720\n" + "".join(f"G1 X{x} Y{y} E0.5 F1200\n" for x, y in square)
    z = 0.4
    for _ in range(5):  # five turns rising 0.2 each
        for x, y in square:
            z += 0.05
            text += f"G1 X{x} Y{y} Z{z:.2f} E0.5\n"
    s = summarize_path(_job(tmp_path, text))
    assert s.layers == 2 + 5 and s.z_range == (0.2, 1.4)


def test_the_slicers_marks_count_the_layers_one_kind_only(tmp_path: Path) -> None:
    # PrusaSlicer's own ";LAYER_CHANGE"; a ";LAYER:n" from the user's layer G-code is not a second count.  The
    # purge line before the first mark, at the first layer's height, is no layer of its own
    layer = ";LAYER_CHANGE\n;Z:{z}\n;LAYER:{n}\nG1 Z{z} F720\nG1 X{x} Y10 E1 F1200\n"
    text = "G28\nM83\nG1 Z0.2\nG1 X60 E9 F1000 ; purge\n" + "".join(
        layer.format(z=round(0.2 * (n + 1), 1), n=n, x=10 + n) for n in range(4)
    )
    s = summarize_path(_job(tmp_path, text))
    assert (s.layers, s.layer_marks, s.z_range) == (4, "prusaslicer", (0.2, 0.8))
    # KISSlicer marks each object's part of a layer: one layer per height
    kiss = "G28\nM83\n" + "".join(
        f"; BEGIN_LAYER_OBJECT z={z}\nG1 Z{z}\nG1 X{i} Y1 E1 F600\n" for z in (0.3, 0.3, 0.6) for i in (1, 2)
    )
    s = summarize_path(_job(tmp_path, kiss, "kiss.gcode"))
    assert (s.layers, s.layer_marks) == (2, "kisslicer")


def test_the_time_of_the_layers_leaves_out_the_start_and_end_sequences(tmp_path: Path) -> None:
    text = (
        "M82\nG28\nG1 X0 Y0 Z0.2 F3000\nG4 S10\n"
        + "".join(f";LAYER:{n}\nG1 X{(n + 1) * 20} Y0 E{n + 1} F1200\n" for n in range(3))
        + "G4 S5\nG1 Z50 F600\n"
    )
    s = summarize_path(_job(tmp_path, text))
    assert s.dwell_s == 15 and s.layers_time_s is not None
    assert 10 + 5 < s.time_s - s.layers_time_s < 10 + 5 + 15  # the start's dwell, the end's and the moves around
    assert "of which the layers:" in render(s)


def test_the_jobs_own_acceleration_and_tool_change_times_count(tmp_path: Path) -> None:
    moves = ";FLAVOR:Marlin\nG28\nM83\n" + "".join(f"G1 X{100 * (i % 2)} Y{i} E1 F6000\n" for i in range(1, 21))
    fast = summarize_path(_job(tmp_path, "M204 P5000 T5000\n" + moves, "fast.gcode"))
    slow = summarize_path(_job(tmp_path, "M204 P200 T200\n" + moves, "slow.gcode"))
    assert fast.time_limits.startswith("the job's own commands") and slow.time_s > 1.3 * fast.time_s
    # the tool changes' load and unload times the slicer's settings state (PrusaSlicer's MMU: per filament)
    mmu = (
        "T0\n"
        + moves
        + "T1\n"
        + moves
        + "T0\n"
        + moves
        + "; filament_load_time = 10,12\n; filament_unload_time = 5,6\n"
    )
    s = summarize_path(_job(tmp_path, mmu, "mmu.gcode"))
    assert s.tool_change_s == pytest.approx((5 + 12) + (6 + 10))
    assert "tool changes at the slicer's load and unload times" in render(s)


def test_a_job_with_no_known_acceleration_says_its_time_is_a_lower_bound(tmp_path: Path) -> None:
    s = summarize_path(_job(tmp_path, HAND))  # Hyrel: no defaults cited, the job states none
    assert s.time_limits == "" and "no acceleration known, a lower bound" in render(s)
    assert "leaves out heating waits" in render(s)


@needs_corpus
def test_issue_28_prusaslicer_mini_cube_layers() -> None:
    out = run_cli("summary", str(CORPUS / "marlin" / "prusaslicer-2.8.1_mini_cube.gcode")).stdout.decode()
    assert "layers: 31, Z 0.2 to 6.2 mm (the slicer's layer marks)" in out
    assert "the slicer's own estimate: 3 min 41 s" in out
