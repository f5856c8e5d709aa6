"""The stranger review of issue 14 (translation): one test (or more) per defect it found, each failing
without its fix."""

from __future__ import annotations

import pytest

from .test_translate_tables import translate


def _codes(result, code: str) -> list[str]:
    return [f.message for f in result.findings if f.code == code]


# -- (1) Machinekit velocity extrusion: feed moves outside G22 ... G23 print (docs/translation.md) -----------

VE = (
    "G21 G90\nM104 P0 S200\nM109 P0 S200\nG0 Z0.2\nM701 P0.5\nM702 P0.2\nG1 X10 Y10 F1200\nG1 X20 Y10\n"
    "G22\nG0 X30\nG1 X35\nG23\nG1 X40 Y10\nM2\n"
)


def test_1_velocity_extrusion_moves_print() -> None:
    out, result = translate("machinekit", VE)
    lines = out.splitlines()
    assert "G1 X10 Y10 F1200 E1" in lines and "G1 X20 Y10 E1" in lines and "G1 X40 Y10 E1" in lines
    assert "G1 X35" in lines and "G0 X30" in lines  # between G22 and G23: travel
    assert any("velocity extrusion" in m for m in _codes(result, "TR003"))
    assert lines.index("M109 T0 S200 R2") < lines.index("G1 X10 Y10 F1200 E1")


def test_1_velocity_extrusion_needs_a_job_without_a_moves() -> None:
    out, _ = translate("machinekit", "G21 G90\nG1 X1 Y1 Z0.2 A1 F600\nM701 P0.5\n")
    assert "M229 E1 D1" in out  # an A job: M701 does not start velocity extrusion
    out, _ = translate("machinekit", "G21 G90\nG22\nG23\nG1 X1 Y1 Z0.2 F600\n")
    assert "G1 X1 Y1 Z0.2 F600 E1" in out.splitlines() and "M229" not in out


def test_1_g22_in_a_job_with_a_moves_is_a_retract() -> None:
    out, result = translate("machinekit", "G21 G90\nG1 X1 Y1 Z0.2 A1 F600\nG22\nG1 X5 Y5\nG23\n")
    assert "G1 X5 Y5" in out.splitlines() and not any("velocity" in m for m in _codes(result, "TR003"))


# -- (2) after G28 (Marlin/RRF): the workspace and the G92 offsets of the axes not homed ------------------

WCS = "M83\nM104 S200\nM109 S200\nG28\nG55\nG1 X10 Y10 Z1 F600\nG1 X15 E1\nG28 X\nG1 X20 E1 F600\n"
G92 = "M83\nM104 S200\nM109 S200\nG28\nG1 X10 Y10 Z1 F600\nG1 X15 E1\nG92 Z5\nG1 X25 E1\nG28 X Y\nG1 X30 Z6 E1\n"


@pytest.mark.parametrize("dialect", ["marlin", "reprap"])
def test_2_g28_invokes_the_workspace_again(dialect: str) -> None:
    out, _ = translate(dialect, WCS)
    lines = out.splitlines()
    home = lines.index("G28 X0")
    assert lines[home + 1 : home + 3] == ["G55", "T0"], lines


@pytest.mark.parametrize("dialect", ["marlin", "reprap"])
def test_2_g28_sets_the_g92_offset_of_an_axis_not_homed_again(dialect: str) -> None:
    out, result = translate(dialect, G92)
    lines = out.splitlines()
    home = lines.index("G28 X0 Y0", lines.index("G92 Z5"))
    assert lines[home + 1 : home + 3] == ["T0", "G92 Z5"], lines
    assert _codes(result, "TR004")


def test_2_an_axis_the_source_homes_gets_no_offset_back() -> None:
    out, _ = translate("marlin", "G28\nG1 X1 Y1 Z1 F600\nG92 Z5\nG28\nG1 X2\n")
    assert out.count("G92 Z5") == 1  # the bare G28 homes Z in the source: its offset is gone there too


# -- (3) Marlin M0/M1 with a message the grammar cannot read: the pause stays, the message is dropped ------


def test_3_marlin_pause_with_a_colon_in_its_message_is_kept() -> None:
    out, result = translate("marlin", "M0 Remove part: 5 min\nN7 M1 S5 C:\\\\x ; note\nG1 X1 F100\n")
    lines = out.splitlines()[1:]  # (after the line that says what the output is)
    assert lines[:2] == ["M0", "N7 M0 ; note"], lines
    assert not _codes(result, "TR005")
    assert _codes(result, "TR004") and _codes(result, "TR003")  # the message; the S5 timeout


def test_3_other_unreadable_lines_are_still_dropped() -> None:
    _, result = translate("marlin", "M10: x\n")
    assert _codes(result, "TR005")


# -- (4) two source tools on one head are refused --------------------------------------------------------

TWO = "M83\nM104 T0 S220\nM104 T1 S220\nT0\nM109 S220\nG1 X1 Y1 Z0.2 E1 F600\nT1\nM109 T1 S210\nG1 X5 E1\n"


def test_4_an_explicit_many_to_one_tool_map_is_refused() -> None:
    with pytest.raises(ValueError, match="tools 0 and 1 both map to head T1"):
        translate("marlin", TWO, tool_map="0=T1,1=T1")


def test_4_a_clash_with_the_identity_default_is_refused_when_the_job_uses_both() -> None:
    with pytest.raises(ValueError, match=r"tools 0 and 1 both map to head T1 \(0=T1; tool 1 unmapped"):
        translate("marlin", TWO, tool_map="0=T1")
    out, _ = translate("marlin", "M83\nT0\nG1 X1 Y1 Z0.2 E1 F600\n", tool_map="0=T1")  # no tool 1: allowed
    assert "T1" in out.splitlines()


def test_4_the_command_line_refuses_in_one_line_and_writes_nothing(tmp_path) -> None:
    import subprocess
    import sys

    src = tmp_path / "two.gcode"
    src.write_text(TWO)
    out = tmp_path / "out.gcode"
    for mapping in ("0=T1,1=T1", "0=T1"):
        run = subprocess.run(
            [
                sys.executable,
                "-m",
                "gclint",
                "translate",
                "--from",
                "marlin",
                "--to",
                "hyrel",
                str(src),
                "-o",
                str(out),
                "--tool-map",
                mapping,
            ],
            capture_output=True,
            text=True,
            check=False,
        )
        assert run.returncode == 2 and not out.exists(), run
        assert len(run.stderr.strip().splitlines()) == 1 and "tools 0 and 1" in run.stderr


# -- (5) RepRapFirmware M109 T selects the tool: the part fan and the flow follow, as at a T change ---------

RRF_M109 = (
    "M83\nM104 T0 S200\nM104 T1 S200\nT0\nM116\nG1 Z0.2 F600\nG1 X10 Y10 E1 F1200\nM106 S255\nM221 S90\n"
    "M109 T1 S200\nG1 X20 Y10 E1\nM106 S128\n"
)


def test_5_rrf_m109_t_moves_the_part_fan_to_the_selected_tool() -> None:
    out, _ = translate("reprap", RRF_M109)
    lines = out.splitlines()
    t1 = lines.index("T1")
    move = lines.index("G1 X20 Y10 E1")
    assert t1 < lines.index("M107 T0") < move and t1 < lines.index("M106 T1 S255") < move, lines
    assert "M106 T1 S128" in lines  # the fan of the tool M109 T1 selected


def test_5_marlin_m109_t_selects_nothing() -> None:
    out, _ = translate("marlin", RRF_M109)
    assert "M106 T0 S128" in out.splitlines() and "M106 T1" not in out


# -- (6) pauses: Carvera M1 after M334 (optional stop mode on), Marlin/RRF and Carvera M25 -----------------


def test_6_carvera_m1_pauses_after_m334_only() -> None:
    out, result = translate("carvera", "G1 X1 F100\nM1\nM334\nM01 (Optional Stop)\nM333\nM1\n")
    assert [line for line in out.splitlines() if line.startswith("M0")] == [
        "M0 ; gclint: optional stop (M334) (Optional Stop)"
    ]
    dropped = [f for f in result.findings if f.code == "TR001" and "optional stop" in f.message]
    assert [f.line for f in dropped] == [2] and "2 lines like this" in dropped[0].message  # lines 2 and 6


@pytest.mark.parametrize("dialect", ["marlin", "reprap", "carvera"])
def test_6_m25_in_a_job_is_a_pause(dialect: str) -> None:
    out, _ = translate(dialect, "G1 X1 F100\nM25\nG1 X2\n")
    lines = out.splitlines()
    assert any(line.startswith("M0 ; gclint: pause") for line in lines), lines


def test_6_carvera_line_by_line_mode_is_a_warning() -> None:
    _, result = translate("carvera", "M336\nG1 X1 F100\n")
    assert any("line-by-line" in m for m in _codes(result, "TR002"))


# -- (7) --set tool-offsets=m6 writes RepRapFirmware's G10 L1 tool offsets too -----------------------------


def test_7_g10_l1_tool_offsets_are_written_as_m6() -> None:
    out, result = translate("reprap", "G10 L1 P1 X10 Y0 Z0.5\n", tool_offsets="m6")
    assert "M6 T1 O2 X-10 Y0 Z-0.5" in out.splitlines() and _codes(result, "TR003")
    out, result = translate("reprap", "G10 L1 P1 X10 Y0 Z0.5\n")
    assert "M6" not in out and any("tool-offsets=m6" in m for m in _codes(result, "TR002"))


# -- (8) Carvera M321 (laser mode) drops the tool: the spindle stops ---------------------------------------


def test_8_carvera_laser_mode_stops_the_spindle() -> None:
    out, _ = translate(
        "carvera", "G21 G90\nT1 M6\nM3 S10000\nG1 X1 Z-1 F100\nM321\nS0.5 M3\nG1 X10 S0.5\nM322\nM2\n", tool_map="1=T0"
    )
    lines = out.splitlines()
    assert lines.index("M5 T0") < lines.index("M620 T0 E1") < lines.index("G1 X10 E1"), lines
    assert lines.count("M5 T0") == 1  # not again in the footer


# -- (9) laser power: RepRapFirmware after M452, Marlin's inline power (docs/translation.md) ----------


def test_9_rrf_m452_makes_m3_s_and_move_s_laser_power() -> None:
    out, result = translate("reprap", "G21 G90\nM452\nM3 S128\nG1 X10 F600\nG1 X20 S255\nM5\n")
    lines = out.splitlines()
    assert "M3 T0 S50.2" not in lines and "M620 T0 E1" in lines
    assert lines.index("M621 P50.2") < lines.index("G1 X10 F600 E1") < lines.index("M621 P100")
    assert "G1 X20 E1" in lines and any("M452" in m for m in _codes(result, "TR003"))


def test_9_marlin_inline_laser_power_after_m3_s0() -> None:
    out, _ = translate("marlin", "G21 G90\nM3 S0\nG1 X10 S128 F600\nG1 X20\nG1 X30 S0\nM5\n")
    lines = out.splitlines()
    assert lines.index("M620 T0 E1") < lines.index("M621 P50.2") < lines.index("G1 X10 F600 E1")
    assert "G1 X20 E1" in lines and "G1 X30" in lines


def test_9_m3_without_power_is_reported() -> None:
    # (Marlin runs the first command of a line only, and a line that starts with S runs none: parser.cpp)
    out, result = translate("marlin", "G21 G90\nM3\nG1 X10 F100\nM5\n")
    assert "M3 T0" in out.splitlines() and any("M3 without S" in m for m in _codes(result, "TR003"))


# -- (10) Machinekit G20: the extruder A is an angular axis, not scaled by 25.4 ------------------------------


def test_10_machinekit_g20_leaves_the_a_axis_alone() -> None:
    out, result = translate("machinekit", "G20 G90\nG1 X1 Y1 A1 F50\nG92 A0\n")
    lines = out.splitlines()
    assert "G1 X25.4 Y25.4 E1 F1270" in lines and "G92 E0" in lines
    assert any("angular" in m for m in _codes(result, "TR003"))
    out, _ = translate("marlin", "G20 G90 M82\nG1 X1 Y1 E1 F50\n")
    assert "G1 X25.4 Y25.4 E25.4 F1270" in out.splitlines()  # Marlin's E is a length


# -- (11) RepRapFirmware M568 A (heater state): not heated on a guess ---------------------------------------


def test_11_m568_with_a_heater_state_does_not_heat_the_tool() -> None:
    out, result = translate("reprap", "M83\nM568 P1 S220 A0\nM104 T0 S200\nT0\nM116\nG1 X1 Y1 Z0.2 E1 F600\n")
    assert "T1 S220" not in out and "M109 T0 S200 R2" in out.splitlines()
    assert any("heater state" in m for m in _codes(result, "TR003"))
    out, _ = translate("reprap", "M568 P1 S220\n")
    assert "M104 T1 S220" in out.splitlines()  # no A: the active temperature, as before
