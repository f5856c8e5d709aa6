"""The stranger review of issue 13 (translation): one test (or more) per defect it found, each failing
without its fix.  The diff's side of the same defects is in tests/test_diff_review13.py."""

from __future__ import annotations

import pytest

from gclint.config import ConfigError, parse_tool_map

from .test_translate_tables import translate


def _codes(result, code: str) -> list[str]:
    return [f.message for f in result.findings if f.code == code]


# -- (1) RepRapFirmware mixing: G1 X.. E1:2 -------------------------------------------------------------


def test_1_mixing_e_is_reported_not_dropped_silently() -> None:
    out, result = translate("reprap", "T0\nM83\nG1 X10 Y10 E1:2 F1200\nG1 X20 E3:4\n")
    assert "G1 X10 Y10 F1200" in out.splitlines() and "E1:2" not in out
    assert any("E1:2" in m and "mixing" in m for m in _codes(result, "TR005"))


# -- (2) a single-nozzle job on several heads: the head first used after an M104 --------------------------

MMU = "M104 S215\nM109 S215\nM83\nT0\nG1 X10 Y10 Z0.2 E1 F1200\nM104 S240\nT1\nG1 X20 Y20 E1\n"


def test_2_a_head_first_used_after_an_m104_waits_for_the_nozzle_heat() -> None:
    out, result = translate("marlin", MMU, tool_map="0=T0,1=T1")
    lines = out.splitlines()
    t1 = lines.index("T1")
    assert lines[t1 + 1 : t1 + 3] == ["M109 T1 S215", "M104 T1 S240"], lines
    assert lines.index("M109 T1 S215") < lines.index("G1 X20 Y20 E1")
    assert any("T1" in m and "215" in m for m in _codes(result, "TR004"))


def test_2_a_head_waited_already_gets_no_second_wait() -> None:
    out, _ = translate("marlin", MMU + "T0\nG1 X30 Y30 E1\n", tool_map="0=T0,1=T1")
    assert out.count("M109 T0") == 1  # T0 was waited at 215: only the new set-point (M104 T0 S240)
    assert "M104 T0 S240" in out


# -- (3) CNC tool change: the spindle on the mapped head; an unmapped tool still gets a head --------------

TC = "G21 G90\nT7 M6\nM3 S10000\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nT3 M6\nM3 S10000\nG1 X20\nM5\nM2\n"


@pytest.mark.parametrize("dialect", ["machinekit", "carvera"])
def test_3_spindle_runs_on_the_mapped_head(dialect: str) -> None:
    out, _ = translate(dialect, TC, tool_map="7=T3,3=T1")
    lines = out.splitlines()
    assert "M3 T3 S66.7" in lines and "M3 T1 S66.7" in lines and "M3 T0 S66.7" not in lines
    t1 = lines.index("T1")
    assert lines[t1 - 1] == "M5 T3"  # the tool change stops the spindle, on the head the tool left
    assert "M5 T1" in lines and "M5 T0" not in lines


def test_3_machinekit_spindle_stops_at_the_tool_change() -> None:
    """LinuxCNC M6: "When the tool change is complete: The spindle will be stopped" (m-code.adoc; review27 C)."""
    out, result = translate(
        "machinekit", "G21 G90\nT7 M6\nM3 S10000\nG1 X10 F100\nT3 M6\nG1 X20\nM2\n", tool_map="7=T3,3=T1"
    )
    lines = out.splitlines()
    t1 = lines.index("T1")
    assert lines[t1 - 1 : t1 + 2] == ["M5 T3", "T1", "G1 X20"] and "M3 T1" not in out
    assert any("stops the spindle" in m for m in _codes(result, "TR004"))


def test_3_carvera_spindle_stops_for_the_tool_change() -> None:
    out, _ = translate("carvera", "G21 G90\nM6 T7\nM3 S10000\nG1 X10 F100\nM6 T3\nG1 X20\nM2\n", tool_map="7=T3,3=T1")
    lines = out.splitlines()
    t1 = lines.index("T1")
    assert lines[t1 - 1] == "M5 T3" and "M3 T1" not in out


def test_3_the_spindle_setting_still_wins() -> None:
    out, _ = translate("machinekit", TC, tool_map="7=T3,3=T1", spindle="T2")
    assert "M3 T2 S66.7" in out.splitlines() and "M3 T3" not in out


def test_3_an_unmapped_tool_still_gets_a_head_before_motion() -> None:
    out, result = translate("machinekit", "G21 G90\nT7 M6\nM3 S10000\nG0 X0 Y0 Z5\nG1 X10 F100\nM2\n")
    lines = out.splitlines()
    assert "T0" in lines and lines.index("T0") < lines.index("G0 X0 Y0 Z5")
    assert any("T7" in m and "spindle head (T0)" in m for m in _codes(result, "TR007"))


# -- (10) small ones ----------------------------------------------------------------------------------------


def test_10_tool_map_with_a_tool_twice_is_refused() -> None:
    with pytest.raises(ConfigError, match="mapped twice"):
        parse_tool_map("0=T1,0=T2")


# -- (7) native flow: a header's job-wide layer height does not override the real layer heights ------------

NATIVE = (
    ";FLAVOR:Marlin\n;Layer height: 0.2\nM83\nG1 Z0.3 F600\nG1 X10 Y10 E1 F1200\nG1 X20 Y10 E1\nG1 Z0.4\n"
    "G1 X10 Y10 E1\nG1 X10 Y20 E1\nG1 Z0.5\nG1 X10 Y10 E1\nG1 X10 Y20 E1\n"
)


def test_7_native_flow_layer_heights_are_the_real_ones() -> None:
    out, _ = translate("marlin", NATIVE, flow="native")
    assert [line for line in out.splitlines() if line.startswith("M756")] == ["M756 S0.3", "M756 S0.1"]


def test_7_per_layer_height_comments_still_win() -> None:
    out, _ = translate("marlin", NATIVE.replace("G1 Z0.4\n", ";HEIGHT:0.15\nG1 Z0.4\n"), flow="native")
    assert [line for line in out.splitlines() if line.startswith("M756")] == ["M756 S0.3", "M756 S0.15"]


# -- (9) Marlin M109 S waits only while heating: never a cooling wait ---------------------------------------


def test_9_m109_s_lower_stays_a_heating_only_wait() -> None:
    out, _ = translate("marlin", "M83\nT0\nM109 S210\nG1 X1 E1 F100\nM109 S180\nG1 X2 E1\n")
    assert "M109 T0 S180" in out.splitlines() and "R" not in "".join(
        line for line in out.splitlines() if "M109" in line
    )


def test_9_m109_r_waits_both_ways_with_the_window() -> None:
    out, _ = translate("marlin", "M83\nT0\nM109 S210\nG1 X1 E1 F100\nM109 R180\nG1 X2 E1\n")
    assert "M109 T0 S180 R2" in out.splitlines()


def test_9_bare_m109_is_no_cooling_wait() -> None:
    """After M104 S0 a window (R2) would wait for the nozzle to cool to 0 +/- 2 °C: forever."""
    out, result = translate("marlin", "M83\nT0\nM109 S180\nG1 X1 E1 F100\nM104 S0\nM109\nG1 X2 E1\n")
    assert "M109 T0" in out.splitlines() and "M109 T0 R2" not in out
    assert any("without S or R" in m for m in _codes(result, "TR003"))


def test_10_rrf_tool_fans_stay_on_their_heads() -> None:
    """M563 F: a tool's own fan is its head's; "S alone -> fans of current tool" (Duet G-code dictionary, M106)."""
    src = "M563 P0 D0 H1 F0\nM563 P1 D1 H2 F2\nT0\nM83\nM106 S0.5\nG1 X1 E1 F100\nT1\nM106 S1\nG1 X2 E1\n"
    out, _ = translate("reprap", src)
    lines = out.splitlines()
    assert "M106 T0 S128" in lines and "M106 T1 S255" in lines
    assert "M107 T0" not in lines  # tool 0's own fan keeps blowing on its head (it does not follow the tool)


def test_10_rrf_m563_s_offset_is_reported() -> None:
    _, result = translate("reprap", "M563 S1\nT0\nM83\nG1 X1 E1 F100\n")
    assert any("S1" in m and "tool number" in m for m in _codes(result, "TR002"))


def test_10_m3_s0_after_m4_is_no_reversal_pause() -> None:
    """ "S0 is the same as turning it off" (Hyrel M3): no M5 and pause before it."""
    out, _ = translate("marlin", "G21\nG90\nM3 S255\nG1 X1 F100\nM4 S0\nG1 X2\nM5\n")
    assert "M0" not in out and "M4 T0 S0" in out.splitlines()


def test_10_a_huge_comment_line_keeps_its_move() -> None:
    out, result = translate("marlin", "M83\nG1 X1 Y1 E1 F100 ;" + "c" * 150_000 + "\nG1 X2 E1\n")
    assert "G1 X1 Y1 E1 F100" in out.splitlines()
    assert any("comment" in m for m in _codes(result, "TR004"))


def test_10_several_commands_are_written_one_a_line() -> None:
    # one a line, in the order LinuxCNC runs them (overview.adoc, "G-code Order of Execution": units, then the
    # coordinate system, then the distance mode), since Hyrel runs them as written
    out, _ = translate("machinekit", "G90 G21 G54\nG0 X1 Y1\n")
    lines = out.splitlines()[1:]  # (after the line that says what the output is)
    assert lines[:3] == ["G21", "G54", "G90"], lines


def test_10_translate_refuses_random_bytes(tmp_path) -> None:
    import random

    from .conftest import run_cli

    rng = random.Random(13)
    data = bytes(rng.randrange(1, 256) for _ in range(4000))  # no NUL: control characters
    path = tmp_path / "bin.gcode"
    path.write_bytes(data)
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", str(path))
    assert proc.returncode == 2 and b"not a G-code" in proc.stderr and proc.stdout == b""
    proc = run_cli("diff", "--from", "marlin", "--to", "hyrel", str(path), str(path))
    assert proc.returncode == 2 and b"not a G-code" in proc.stderr


def test_10_diff_names_an_unsupported_pair_in_words(tmp_path) -> None:
    from .conftest import run_cli

    path = tmp_path / "ok.gcode"
    path.write_text("G1 X1 E1 F100\n")
    proc = run_cli("diff", "--from", "hyrel", "--to", "marlin", str(path), str(path))
    assert proc.returncode == 2 and b"UnsupportedPair" not in proc.stderr and b"not supported" in proc.stderr


def test_3_a_spindle_started_before_any_head_stops_at_the_first_tool_change() -> None:
    out, _ = translate("machinekit", "G21 G90\nM3 S10000\nT3 M6\nG1 X10 F100\nM2\n", tool_map="3=T1")
    lines = out.splitlines()
    assert lines[lines.index("T1") - 1] == "M5 T0" and "M3 T1" not in out, lines
