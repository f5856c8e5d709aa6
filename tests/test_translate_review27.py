"""The translation reviewer's findings (review 27: A-F) and the explain/translate/diff items of the stranger review
of issue 24 (1.4, 1.5, 1.6, 1.9, sections 2 and 3), each as it must read now.  Facts from the LinuxCNC documentation
(https://linuxcnc.org/docs/html/gcode/overview.html, g-code.html, m-code.html) and the Carvera M-code table."""

from __future__ import annotations

import pytest

from gclint import dialects
from gclint.explain import explain_text
from gclint.syntax.parse import parse_line
from gclint.translate.words import has_expression

from .conftest import run_cli
from .test_diff import translate_and_diff
from .test_translate_tables import translate


def explained(text: str, dialect: str) -> str:
    return "\n".join(e.render() for e in explain_text(text, dialects.get(dialect)))


def codes_on(result, line: int) -> list[str]:
    return sorted(f.code for f in result.findings if f.line == line)


# -- A: an expression that starts with a function name is a computed value ----------------------------------------


@pytest.mark.parametrize(
    "line",
    [
        "G0 XSIN[30] Y1",
        "G0 X ABS[-4]",
        "G0 X EXISTS[#<_foo>]",
        "G0 X ATAN[1]/[2]",
        "G0 X-ROUND[2.5]",
        "G0 Y FIX[2.8]",
        "G0 Y FUP[2.8]",
        "G0 Y SQRT[4]",
        "G0 Y LN[4]",
        "G0 Y EXP[1]",
        "G0 Y ACOS[0]",
        "G0 Y ASIN[1]",
        "G0 Y COS[0]",
        "G0 Y TAN[45]",
        "G1 X cos[0] F100",
    ],
)
def test_a_function_value_is_untranslatable_and_explained_as_computed(line: str) -> None:
    out, result = translate("machinekit", f"G21 G90\nG0 X0 Y0 Z1\n{line}\nM2\n")
    assert line not in out
    assert "TR005" in codes_on(result, 3)
    text = explained(line, "machinekit")
    assert "a value computed when the line runs" in text and "(to X" not in text.replace(" (to X0", "")


def test_what_counts_as_a_computed_value() -> None:
    assert has_expression(parse_line("G0 X EXISTS[#<_foo>]").commands[0])
    assert not has_expression(parse_line('M118 S"a #1 b"').commands[0])
    assert not has_expression(parse_line("G1 X-2.5 Y.5").commands[0])


# -- B: LinuxCNC ignores blanks anywhere on a line ------------------------------------------------------------------

CUT6 = "G21 G90 G54\nM3 S6000\nG0 X0 Y0 Z1\nG1 Z-1 F100\nG1 X 2 0 Y 5\nG1 X1 0 0\nG0X +0. 12 34Y 7\nG0 Z5\nM2\n"


def test_blanks_inside_numbers_read_as_linuxcnc_reads_them() -> None:
    out, result = translate("machinekit", CUT6, spindle_max_rpm="10000")
    lines = out.splitlines()
    assert "G1 X20 Y5" in lines and "G1 X100" in lines and "G0 X+0.1234 Y7" in lines
    assert not any(" 2 0" in text or "X1 0 0" in text for text in lines)
    assert "TR004" in codes_on(result, 5)
    # the diff reads the source as LinuxCNC does: the translation agrees, the source's text kept does not
    text, _, diff = translate_and_diff("machinekit", CUT6, spindle_max_rpm="10000")
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    from gclint.simulate import Explanations, Mapping, diff_sources
    from gclint.syntax.source import Source

    kept = text.replace("G1 X20 Y5", "G1 X 2 0 Y 5")
    again = diff_sources(
        Source.from_text(CUT6, "s"),
        Source.from_text(kept, "o"),
        dialects.get("machinekit"),
        dialects.get("hyrel"),
        Mapping(),
        Explanations(),
    )
    assert again.unexplained()
    assert "X20 (to X20)" in explained("G1 X 2 0 Y 5 F100", "machinekit")


def test_blanks_are_not_squeezed_where_they_do_not_change_the_reading() -> None:
    out, result = translate("machinekit", "G21 G90\nG1 X 5 Y 2 F100\nM2\n")
    assert "G1 X 5 Y 2 F100" in out.splitlines() or "G1 X 5 Y 2" in out
    assert not any("blanks" in f.message for f in result.findings)


# -- C: LinuxCNC's M6 stops the spindle -------------------------------------------------------------------------------

TOOLS = "G21 G90 G54\nT1 M6\nM3 S6000\nG0 X0 Y0 Z1\nG1 Z-1 F100\nG1 X10\nT2 M6\nG1 X20\nG0 Z5\nM2\n"


@pytest.mark.parametrize("tools", ["", "1=T1,2=T2", "1=T1"])
def test_m6_stops_the_spindle_and_nothing_restarts_it(tools: str) -> None:
    settings = {"spindle_max_rpm": "15000", **({"tool_map": tools} if tools else {})}
    text, result, diff = translate_and_diff("machinekit", TOOLS, **settings)
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    lines = text.splitlines()
    after = lines[lines.index("G1 X10") + 1 : lines.index("G1 X20")]
    assert any(t.startswith("M5 T") for t in after) and not any(t.startswith(("M3", "M4")) for t in after), after
    message = " ".join(f.message for f in result.findings if f.line == 7)
    assert "stops the spindle" in message and "runs on" not in message
    # a translation that restarts it differs from the source
    from gclint.simulate import Mapping, diff_sources
    from gclint.simulate.translation import explanations_from
    from gclint.syntax.source import Source

    wrong = text.replace("G1 X20", "M3 T2 S40\nG1 X20")
    again = diff_sources(
        Source.from_text(TOOLS, "s"),
        Source.from_text(wrong, "o"),
        dialects.get("machinekit"),
        dialects.get("hyrel"),
        Mapping(spindle_max_rpm=15000.0),
        explanations_from(result),
    )
    assert any(d.aspect == "spindle" for d in again.unexplained())


# -- D: LinuxCNC sets the feed (step 3) before the units (step 12) ------------------------------------------------------

UNITS = "G21 G90 G54\nG0 X0 Y0 Z1\nS1000 M3\nG20 G1 X1 F10\nG1 Y1\nG21 G1 X50 F250\nG1 Y50\nM2\n"


def test_f_on_a_line_with_g20_or_g21_is_read_in_the_units_before_it() -> None:
    """overview.adoc "G-code Order of Execution": "Set feed rate (F)" before "Set length units (G20, G21)";
    interp_convert.cc convert_length_units keeps the feed's speed ("settings->feed_rate = GET_EXTERNAL_FEED_RATE()")."""
    text, result, diff = translate_and_diff("machinekit", UNITS, spindle_max_rpm="15000")
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    lines = text.splitlines()
    assert "G1 X25.4 F10" in lines  # 10 mm/min: G21 was in force when F was read
    assert "G1 Y25.4" in lines  # the same 10 mm/min
    assert "G1 X50 F6350" in lines  # 250 in/min: G20 was in force
    assert "G1 Y50" in lines
    from gclint.simulate import Mapping, diff_sources
    from gclint.simulate.translation import explanations_from
    from gclint.syntax.source import Source

    wrong = text.replace("G1 X25.4 F10", "G1 X25.4 F254")
    again = diff_sources(
        Source.from_text(UNITS, "s"),
        Source.from_text(wrong, "o"),
        dialects.get("machinekit"),
        dialects.get("hyrel"),
        Mapping(spindle_max_rpm=15000.0),
        explanations_from(result),
    )
    assert any(d.aspect == "feed" for d in again.unexplained())


def test_marlin_reads_f_in_the_units_of_its_own_line() -> None:
    out, _ = translate("marlin", "G21\nG20\nG1 X1 F10\n")
    assert "G1 X25.4 F254" in out.splitlines()


# -- E: Marlin G20 with absolute E ------------------------------------------------------------------------------------

M8 = "M104 S200\nM109 S200\nG92 E0\nG1 X10 Y10 Z0.3 F1200\nG1 X20 E8\nG20\nG1 X2 E8\nG1 X3 E8.5\nG21\nG1 X80 E216.9\n"


def test_absolute_e_under_g20_is_compared_in_the_same_units() -> None:
    text, _, diff = translate_and_diff("marlin", M8)
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    lines = text.splitlines()
    assert "G1 X50.8 E203.2" in lines  # E8 in inches is 203.2 mm, from the E position 8 mm
    assert "G1 X76.2 E215.9" in lines
    assert "G1 X80 E216.9" in lines  # back in mm: 1 mm more


# -- F: Machinekit G91 and a move on one line: the E mode before the move ---------------------------------------------


@pytest.mark.parametrize("line", ["G91 G1 X10 A0.5", "G1 X10 A0.5 G91"])
def test_relative_e_is_written_before_the_move_of_its_line(line: str) -> None:
    source = f"G21 G90\nM104 P0 S210\nM109 P0 S210\nG92 A0\nG1 Z0.3 F1200\nG1 X10 Y10 A1.5 F1800\n{line}\nG90\nG1 X30 A3\nM2\n"
    text, _, diff = translate_and_diff("machinekit", source)
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    lines = text.splitlines()
    g91 = lines.index("G91")
    assert lines[g91 + 1 : g91 + 3] == ["M83", "G1 X10 E0.5"], lines


# -- review24 1.4: LinuxCNC G4 P1 S5000 changes the spindle speed -------------------------------------------------------

L8 = "G21 G90\nT1 M6\nG0 X0 Y0 Z5\nM3 S10000\nG1 Z-1 F100\nG1 X10\nG4 P1 S5000\nG1 X20\nG1 X30\nM5\nM2\n"


def test_s_on_a_dwell_line_is_a_spindle_speed_change() -> None:
    text, result, diff = translate_and_diff("machinekit", L8, spindle_max_rpm="15000")
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    lines = text.splitlines()
    assert lines[lines.index("G4 S1") - 1] == "M3 T1 S33.3", lines
    from gclint.simulate import Mapping, diff_sources
    from gclint.simulate.translation import explanations_from
    from gclint.syntax.source import Source

    kept = text.replace("M3 T1 S33.3\n", "")
    again = diff_sources(
        Source.from_text(L8, "s"),
        Source.from_text(kept, "o"),
        dialects.get("machinekit"),
        dialects.get("hyrel"),
        Mapping(spindle_max_rpm=15000.0),
        explanations_from(result),
    )
    assert any(d.aspect == "spindle" for d in again.unexplained())
    text = explained("G4 P1 S5000", "machinekit")
    assert "spindle speed 5000 rpm" in text and "pause for 1 s" in text


# -- review24 1.9: LinuxCNC refuses G4 without P ------------------------------------------------------------------------

G4S = "G21 G90\nG0 X0 Y0\nG4 S3\nG1 X10 F100\nG4 P1 S2\nM2\n"


def test_g4_without_p_is_an_error_in_translate_and_explain() -> None:
    out, result = translate("machinekit", G4S)
    assert "TR005" in codes_on(result, 3) and "G4 S3" not in out.splitlines() and "G4" in out
    text = explained("G4 S3", "machinekit")
    assert "refuses this line and stops the program" in text
    assert "G4 P1 S2" not in out  # (the good one is translated: S is the spindle speed)


def test_check_reports_g4_without_p(tmp_path) -> None:
    job = tmp_path / "j.ngc"
    job.write_text(G4S)
    proc = run_cli("check", "--dialect", "machinekit", str(job))
    assert b"j.ngc:3:1: DL004" in proc.stdout and b"G4 needs P" in proc.stdout
    assert b":5:" not in proc.stdout
    summary = run_cli("summary", "--dialect", "machinekit", str(job))
    assert b"stops at line 3" in summary.stdout


# -- review24 1.5: explain reads LinuxCNC lines as the translator does ------------------------------------------------

ARCS = "G21 G17 G90\nG90.1\nT1 M6\nG0 X50 Y50 Z5\nS10000 M3\nG1 Z-1 F100 S3000\nG2 X70 Y50 I60 J50 F300\nG91.1\nG2 X50 Y50 I-10 J0\nM2\n"


def test_explain_reads_arc_centre_modes_and_spindle_words() -> None:
    text = explained(ARCS, "machinekit")
    assert "a machinekit command" not in text
    assert "I, J and K are the centre's absolute coordinates" in text
    assert "I60 (centre at X60, absolute under G90.1)" in text and "J50 (centre at Y50, absolute under G90.1)" in text
    assert "I-10 (centre -10 from the start in X, an offset under G91.1)" in text
    assert "modal G0" not in text and "S10000 (spindle speed 10000 rpm" in text
    assert "S3000 (spindle speed 3000 rpm" in text
    out, _ = translate("machinekit", ARCS)
    assert "G2 X70 Y50 I10 J0 F300" in out.splitlines()  # the translator reads the same centre


# -- review24 1.6: Carvera M6 T0 (wireless probe) and M6 T-1 (no tool) ------------------------------------------------


def test_carvera_probe_and_no_tool_in_explain_and_diff() -> None:
    source = "G21 G90\nM6 T1\nM3 S10000\nG1 X10 F300\nM5\nM6 T0\nG4 P1.5\nM6 T-1\nM2\n"
    text = explained(source, "carvera")
    assert "T0 (change to the probe: T0 is the machine's wireless probe" in text
    assert "T-1 (no tool: the spindle is emptied)" in text
    assert "change to tool 0" not in text and "change to tool -1" not in text
    out, result, diff = translate_and_diff("carvera", source, spindle_max_rpm="15000")
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    assert {"TR002"} <= set(codes_on(result, 6)) and {"TR002"} <= set(codes_on(result, 8))


# -- review24 sections 2 and 3: explain says what check says ----------------------------------------------------------


def test_explain_m6_and_m109_r_as_check_reports_them() -> None:
    text = explained("M6", "hyrel")
    assert "all future T# or M6 commands" not in text and "does nothing on Hyrel" in text
    assert "M6 T1 looks like a tool change" in explained("M6 T1", "hyrel")
    assert "looks like a tool change" not in explained("M6 T1 O2 X0 Y0 Z0", "hyrel")
    assert "warning: M109 R215 is a Marlin-style target" in explained("M109 R215", "hyrel")
    assert "warning" not in explained("M109 T0 S215 R5", "hyrel")


def test_one_reading_of_a_native_flow_e_only_move() -> None:
    text = explained("M229 E0 D0\nT0\nG1 X10 Y10 E1 F1200\nG1 E-0.5 F1800\n", "hyrel")
    assert "while extruding" not in text.split("E-0.5 (")[1]
    assert "nothing is dispensed" in text and "G1 with only E does nothing in native flow" in text
    from gclint.dialects.habits import HYREL_HABITS

    says = [habit.says for habit in HYREL_HABITS if habit.rule == "HY031"]
    assert says and all("E-only G1 does nothing" in text for text in says)


def test_linuxcnc_rapids_ignore_f_in_explain() -> None:
    text = explained("G1 X1 F300\nG0 X5\nG0 X6 F50\n", "machinekit")
    assert "previously set F" not in text.split("X5 (to X5)")[1]
    assert "G0 ignores the feed rate F" in text and "this rapid ignores it" in text


def test_summary_of_a_milling_job_counts_cutting_not_printing(tmp_path) -> None:
    job = tmp_path / "mill.ngc"
    job.write_text("G21 G90\nT1 M6\nG0 X0 Y0 Z5\nM3 S10000\nG1 Z-1 F100\nG1 X10\nG0 Z5\nM5\nM2\n")
    out = run_cli("summary", "--dialect", "machinekit", str(job)).stdout.decode()
    assert "flow:" not in out and "printing" not in out
    assert "0.02 m at feed (cutting)" in out, out


# -- the second translation review ------------------------------------------------------------------------------


def test_absolute_arc_centres_in_inches_are_written_in_mm():
    # LinuxCNC G90.1: I and J are the centre's coordinates, in the line's units (G20: inches)
    text = "G20 G90 G54 G17\nG0 X1 Y1 Z0\nG90.1\nG1 X1 Y1 F10\nG2 X2 Y1 I1.5 J1\nG91.1\nG2 X3 Y1 I0.5 J0\nM2\n"
    out, _ = translate("machinekit", text)
    arcs = [line for line in out.splitlines() if line.startswith("G2 ")]
    assert arcs == ["G2 X50.8 Y25.4 I12.7 J0", "G2 X76.2 Y25.4 I12.7 J0"]


def test_clearing_g92_offsets_gives_the_position_back():
    # LinuxCNC G92.1 turns the G92 offsets off: the arc starts from Y10 again, not from the shifted Y0
    text = "G21 G90\nG0 X10 Y10 Z5\nG92 X0 Y0\nG1 X5 F200\nG92.1\nG1 X20\nG2 X30 Y10 R10\nM2\n"
    out, _ = translate("machinekit", text)
    assert "G2 X30 Y10 I5 J-8.6603" in out.splitlines()


def test_m3_before_any_spindle_speed_is_a_warning():
    _, result = translate("machinekit", "G21 G90\nG0 X0 Y0 Z5\nM3\nG1 X10 F100\nS5000\nG1 X20\nM2\n")
    assert any(f.code == "TR003" and "no spindle speed set yet" in f.message for f in result.findings)
    _, result = translate("machinekit", "G21\nS1000 M3\nG1 X1 F100\nM2\n")
    assert not any("no spindle speed set yet" in f.message for f in result.findings)


def test_words_with_no_command_are_never_dropped_in_silence():
    # (Prusa XL's "P0 S1 L2 D0" parks the tool: its S is no spindle speed)
    _, result = translate("marlin", "G21\nM83\nG1 X10 E1 F1000\nP0 S1 L2 D0\nG1 X20\n")
    assert [(f.line, f.code) for f in result.findings if f.code == "TR002"] == [(4, "TR002")]


@pytest.mark.parametrize(
    "line,words",
    [("M3 S10000", "not RPM"), ("G28 X10", "ignores the value")],
)
def test_explain_warns_where_check_does(line, words):
    # (HY023 and HY025: the one message, in check and in explain)
    text = "\n".join(e.render() for e in explain_text(line, dialects.get("hyrel")))
    assert f"warning: {line.split()[0]}" in text and words in text
