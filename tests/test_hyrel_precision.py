"""Issue 26, the Hyrel part: every finding worth a person's time, and none that states more than the pages.

Each test quotes the page (Hyrel wiki, Gcode page or T_v5 page) that the rule's fact comes from, grouped by
topic: rules that said more than the pages, misses a Hyrel operator found, what ``gclint explain`` says, and
the fixes' text (checksums, the diff).
"""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import pytest

from gclint import dialects
from gclint.engine import Linter, Options
from gclint.explain import explain_text
from gclint.rules.base import _example, all_rules
from gclint.rules.syntax import compute_checksum
from tests.conftest import CORPUS, run_cli


def lint(text: str, printer: str = "30m", codes: tuple[str, ...] = (), **options):
    found = Linter(Options(dialect="hyrel", printer=printer, **options)).check_text(textwrap.dedent(text)).findings
    return [f for f in found if not codes or f.code in codes]


def where(findings) -> list[tuple[int, str, str]]:
    return [(f.line, f.code, f.severity.label) for f in findings]


def explained(text: str) -> str:
    return "\n".join(e.render() for e in explain_text(textwrap.dedent(text), dialects.get("hyrel")))


# -- rules that stated more than the pages ---------------------------------------------------------------


def test_hy033_no_invented_limit_on_the_flow_multiplier():
    # M221: "Sn is the direct flow multiplier (to allow for undersized or oversized stock" -- no limit given.
    # A real generator's S2.5 (and any S from 0 up) is taken as written; only a negative multiplier is reported.
    assert lint("M221 T0 S2.5\nM221 T0 S10\nM221 T0 S95\nG1 X1 Y1 E1 S16 F600\n", codes=("HY033",)) == []
    found = lint("M221 T0 S-1\n", codes=("HY033",))
    assert where(found) == [(1, "HY033", "warning")]
    assert "percent" not in found[0].message and "0.025" not in found[0].message and "15.99" not in found[0].message


def test_hy023_says_only_what_the_page_says():
    # M3: "Sn - power (0-100%)"; the pages do not say Repetrel clamps a larger value
    found = lint("M3 T20 S12000\nM5 T20\n", codes=("HY023",))
    assert where(found) == [(1, "HY023", "warning")]
    assert "clamp" not in found[0].message and "power (0-100%)" in found[0].message
    from gclint.rules.hyrel.lasers_spindles import SpindlePowerOver100

    assert "clamp" not in SpindlePowerOver100.explanation


HYREL_30M_HEADER = """\
G53
G21
G91
G0 Z10
G90
G28 X0 Y0
M229 E1 D1
M190 S60
M109 T1 S215
T1
"""


def test_hy039_asks_only_for_the_axes_with_homes():
    # M18: "All axes with homes must be rehomed after an M18."  X and Y: "G28 sends the X and/or Y axes to the
    # sensor-defined physical home position".  A 30M's own Hyrel header homes X and Y only: no G28 Z0 is asked.
    job = HYREL_30M_HEADER + "G1 X10 Y10 E1 F1200\nM18\nG28 X0 Y0\nG1 X20 Y10 E1\nM30\n"
    assert lint(job, codes=("HY039",)) == []
    found = lint(HYREL_30M_HEADER + "M18\nG0 X10 Y10\n", codes=("HY039",))
    assert len(found) == 1 and "G28 X0 Y0 before" in found[0].message and "Z0" not in found[0].message
    # "Z0 ensures that the Z axis is homed": a job that homes Z shows its Z has a home, so Z is asked for too
    found = lint("G28 X0 Y0 Z0\nM18\nG28 X0 Y0\nG0 X10 Y10\n", codes=("HY039",))
    assert len(found) == 1 and "G28 Z0 before" in found[0].message


def test_hy035_accepts_the_pages_own_example_6():
    # M109 Example 6: "M109 R10 ... (no T# - use head with current focus) R10 (to get +/-10°C of set temperature)"
    assert lint("M109 R10\n", codes=("HY035",)) == []
    assert lint("M190 R10\nM191 R10\n", codes=("HY035",)) == []  # (their Example 6 too)
    # R as a Marlin target is still an error: "Sn (optional) ... if omitted, no new target temperature is set"
    assert where(lint("M109 R215\n", codes=("HY035",))) == [(1, "HY035", "error")]


# -- HY029: what the 100-character cut changes -----------------------------------------------------------


def test_hy029_comment_only_text_is_info():
    # M0: "Note that all lines will be truncated at 100 characters."  Cutting a comment changes nothing the
    # printer does: info, not a warning (the gate passes)
    found = lint(
        "; "
        + "/" * 15
        + "   BEGIN HYREL HEADER for a 30M/ESR with a Heated Head in T1/T12 - 2021.02.24   "
        + "\\" * 16
        + "\n"
    )
    assert where(found) == [(1, "HY029", "info")]
    found = lint("M104 T0 S200 ; " + "x" * 100 + "\n", codes=("HY029",))
    assert where(found) == [(1, "HY029", "info")]


def test_hy029_a_cut_command_or_parameter_is_a_warning():
    found = lint("G1 " + "X10.000000000 " * 7 + "Y20 E1 F600\n", codes=("HY029",))
    assert where(found) == [(1, "HY029", "warning")] and "loses Y20 E1 F600" in found[0].message
    found = lint("M0 ; SAY " + "x" * 100 + "\n", codes=("HY029",))
    assert where(found) == [(1, "HY029", "warning")]  # the M0 text is what the printer says


def test_hy029_quotes_at_most_a_short_part_of_a_huge_line():
    found = lint("G1 X1." + "5" * 99000 + "\n", codes=("HY029",))
    assert len(found) == 1 and len(found[0].message) < 300, len(found[0].message)
    assert "99,003 characters" in found[0].message
    found = lint("G1 X10 Y10 " + " ".join(f"E{i}" for i in range(20000)) + "\n", codes=("HY029",))
    assert len(found) == 1 and len(found[0].message) < 300, len(found[0].message)


def test_hy029_hyrels_own_prusaslicer_profile_passes_the_gate(tmp_path: Path):
    """The banner comments of Hyrel's own 30M/ESR profile are 102 and 106 characters long: a job that starts
    and ends with them passes a gate run with no flags (exit 0)."""
    profile = CORPUS / "hyrel" / "oinkotariah__printer_30M-ESR_T1_Heated.ini"
    if not profile.is_file():
        pytest.skip("corpus not found")
    settings = dict(line.split(" = ", 1) for line in profile.read_text(encoding="utf-8").splitlines() if " = " in line)

    def expand(code: str) -> str:  # (the .ini writes a line break as \n and a backslash as \\)
        text = re.sub(r"\\(.)", lambda m: {"n": "\n", "t": "\t"}.get(m.group(1), m.group(1)), code)
        text = text.replace("[bed_temperature]", "60").replace("[temperature]", "215")
        return text.replace("[layer_height]", "0.2").replace("[layer_num]", "1")

    start, end = expand(settings["start_gcode"]), expand(settings["end_gcode"])
    banners = [line for line in (start + end).splitlines() if len(line) > 100]
    assert sorted(len(line) for line in banners) == [102, 106]
    layers = "".join(
        expand(settings["before_layer_gcode"]) + f"\nG1 Z{0.2 * n:.1f} F600\nG1 X{10 * n} Y10 E{n} F1200\n"
        for n in (1, 2, 3)
    )
    job = tmp_path / "cube.gcode"
    job.write_text(start + "\nG21\nG90\nM82\nG92 E0\n" + layers + end)
    proc = run_cli("check", str(job))
    assert proc.returncode == 0, proc.stdout.decode()
    assert b"HY029 [info]" in proc.stdout and b"HY029 [warning]" not in proc.stdout
    # its "M756 S[layer_height]" at every layer, after M229 E1 D1: ignored, said once (info)
    assert proc.stdout.count(b"HY014 [info]") == 1, proc.stdout.decode()


# -- misses a Hyrel operator found -----------------------------------------------------------------------


PICK_AND_PLACE = """\
M6 T0 O1 X0 Y0 Z0
M6 T1 O2 X102.4 Y-23.5 Z0
G28 X0 Y0
T0
T1
G0 X50 Y50
G1 Z2 F600
G1 Z10
G28 X0 Y0
G0 X60 Y60
G1 Z2 F600
G1 Z10
M30
"""


def test_hy055_work_without_e_after_a_mid_job_g28():
    # G1: "a working move, during which you may be printing, milling, lasering, or doing other active work";
    # G28: "applies a head offset of 0 mm (as in an M6 O0)".  The pick-and-place head loses X102.4 Y-23.5.
    found = lint(PICK_AND_PLACE, codes=("HY055",))
    assert where(found) == [(9, "HY055", "warning")]
    assert "work resumes at line 11" in found[0].message and "T1" in found[0].message
    # selecting the head again before the work applies its offsets: "T3 (Switch to ... and invoke all flow,
    # prime, unprime, and offset parameters)"
    assert lint(PICK_AND_PLACE.replace("G0 X60 Y60\n", "T1\nG0 X60 Y60\n"), codes=("HY055",)) == []


def test_hy055_milling_after_a_mid_job_g28():
    milling = """\
        M660 H2 Z28.2
        M3 T0 S50
        G1 Z1 F300 H2
        G1 X20 Y0
        G28 X0 Y0
        G1 X30 Y0 F300
        M5 T0
        M30
        """
    found = lint(milling, codes=("HY055",))
    assert where(found) == [(5, "HY055", "warning")] and "H2" in found[0].message
    # a G28 at the end of a job, no work after it, is fine
    assert lint(milling.replace("G1 X30 Y0 F300\n", ""), codes=("HY055",)) == []


def test_h_on_g0_applies_the_register_as_on_g1():
    # G0's usage on the page has no H (G1's has: "Hn is the stored head offset to apply"), but the firmware's G0
    # and G1 both queue the move through motionQ_addCommand, which takes the register from H (Hyrel firmware
    # source, src/MotorDrivers.c): real Hyrel jobs write "G0 Z0 H2", and check, explain and HY004 agree
    assert lint("M660 H2 Z28.2\nG0 Z5 H2\nG1 Z5 F600 H2\n", codes=("HY034",)) == []
    # (real generators write "G0 Z0 H2" with no M660 in the job: on a G0 only the range is checked)
    assert lint("G0 Z5 H3\n", codes=("HY034",)) == []
    unset = lint("G1 Z5 F600 H3\n", codes=("HY034",))
    assert where(unset) == [(1, "HY034", "warning")] and "no M660 H3" in unset[0].message
    assert where(lint("G0 Z5 H70\n", codes=("HY034",))) == [(1, "HY034", "error")]
    assert lint("M660 H2 Z28.2\nG0 Z5 H2\nG81 T20 X100 Y75 I3 P3 Q-2 Z-7.5 F200\n", codes=("HY004",)) == []
    for move in ("G0 Z5 H2", "G1 Z5 F600 H2"):
        assert "invoke the offsets stored in register H2" in explained(f"M660 H2 Z28.2\n{move}")


def test_m6_offsets_without_an_o_register():
    # M6 K1 example: "(no offset registers, so ignore all offsets)"
    found = lint("M6 T1 X25 Y0 Z0.5\n")
    assert (
        where(found) == [(1, "HY061", "warning")] and "no offset registers, so ignore all offsets" in found[0].message
    )
    assert lint("M6 T1 O2 X25 Y0 Z0.5\nM6 K1\nM6 O0\n", codes=("HY061", "HY038")) == []
    assert "the offsets are ignored" in explained("M6 T1 X25 Y0 Z0.5")


@pytest.mark.parametrize("printer,expected", [("30m", 2), ("esr", 2), ("ehr", 2), ("16a", 0), ("16a-dual", 0)])
def test_bed2_only_on_the_hydra(printer, expected):
    # T_v5: "T25 || Bed2 / Chamber2"; Gcode page, Controlling Temperature: "our Hydra models have room to have
    # a second hotbed"
    found = lint("M140 T25 S60\nM190 T25 S60 R2\nM141 T25 S40\nM140 T24 S60\n", printer=printer, codes=("HY007",))
    assert len(found) == expected and all(f.severity.label == "warning" for f in found)


def test_a_head_set_to_s0_that_then_prints():
    # M109 Example 5: "S0 (to 0°C)": a set point of 0 °C
    job = textwrap.dedent("""\
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X20 Y0 Z0
        M109 T0 S215
        M109 T1 S215
        T0
        G1 X10 Y10 E1 F1200
        M104 T0 S0
        T1
        G1 X20 Y10 E1
        T0
        G1 X30 Y10 E1
        M104 T40 S0
        M30
        """)
    found = lint(job, codes=("HY063",))
    assert where(found) == [(11, "HY063", "warning")] and "set to 0 at line 7" in found[0].message
    # switched off at the end, after the printing: fine
    assert lint(job.replace("T0\nG1 X30 Y10 E1\n", ""), codes=("HY063",)) == []


def test_a_head_heated_and_waited_on_but_never_selected():
    # T_v5, Default Mode: "when printing with multiple heads, the requirement - to explicitly direct Repetrel's
    # 'focus' to a particular head"
    job = "M109 T0 S215\nM109 T1 S230\nT0\nG1 X10 Y10 E1 F1200\nM30\n"
    assert where(lint(job, codes=("HY065",))) == [(2, "HY065", "warning")]
    assert lint(job.replace("M30\n", "T1\nG1 X20 Y10 E1\nM30\n"), codes=("HY065",)) == []
    # no T command at all: Repetrel focuses "the first head it detects", which the file does not name
    assert lint("M109 T1 S230\nG1 X10 Y10 E1 F1200\nM30\n", codes=("HY065",)) == []


def test_commands_run_together_on_one_line():
    from gclint.syntax.parse import parse_line

    # the grammar reads two commands, G1 Z20 and G1 X60 Y40; the pages write one command a line
    assert [(c.code, c.params) for c in parse_line("G1 Z20G1 X60 Y40").commands] == [
        ("G1", {"Z": "20"}),
        ("G1", {"X": "60", "Y": "40"}),
    ]
    found = lint("G1 Z20G1 X60 Y40 F600\nM30\n", codes=("HY066",))
    assert where(found) == [(1, "HY066", "warning")]
    assert "Z20G1" in found[0].message and "'G1 Z20' and then 'G1 X60 Y40 F600'" in found[0].message
    assert lint("G21 G90\n; layer 2G1\nG1 X10.5 Y2 F600\n", codes=("HY066",)) == []


def test_g2_3_normal_vector_outside_g16():
    # G2.3: "If we are in G16 mode, Un, Vn, Wn define the vector normal to the work plane. If we are in G17
    # (X/Y plane) or G18 (X/Z plane) or G19 (Y/Z plane) mode, these are ignored."
    found = lint("G2.3 X10 Y0 Z5 I5 J0 K0 U0 V1 W1 E1\n", codes=("HY064",))
    assert where(found) == [(1, "HY064", "warning")] and "G17" in found[0].message
    assert lint("G16\nG2.3 X10 Y0 Z5 I5 J0 K0 U0 V1 W1 E1\n", codes=("HY064",)) == []
    assert "U V W ignored" in explained("G18\nG2.3 X10 Z5 I5 K0 U0 V1 W1")
    assert "ignored" not in explained("G16\nG2.3 X10 Z5 I5 K0 U0 V1 W1")


# -- explain -------------------------------------------------------------------------------------------------


def test_explain_m722_p_is_before_the_start():
    # T_v5, One Head Loaded: "M722 S10000 E100 P20 T0 ... P20 (20ms before start of print move sequence)"
    text = explained("M722 S10000 E100 P20 T0")
    assert "20 ms before the start of the print move" in text and "after" not in text
    # M721: "a negative number initiates this before the end of the move"
    assert "15 ms before the end of the print move" in explained("M721 S10000 E100 P-15 T0")


def test_explain_m756_ignored_under_m229_e1_d1():
    # M756: "Note: this command is ignored if you are using M229 E1 D1 to enable use of E values."
    assert "ignored" in explained("M229 E1 D1\nM756 S0.2").split("M756")[-1]
    assert "ignored" not in explained("M756 S0.2")


def test_exponent_notation_is_read_and_explained_one_way():
    """``F1.875e+06``: gclint's grammar reads F1.875 and then an E word e+06 (G-code numbers have no exponent);
    the Hyrel pages do not say how Repetrel reads it.  check and explain say the same, and name it."""
    found = lint("M229 E1 D1\nG1 X10 F1.875e+06 E2\n", codes=("HY067", "SX006", "SX002"))
    assert [f.code for f in found] == ["HY067", "SX002"]
    assert "F1.875e+06 is exponent notation" in found[0].message and "F1875000" in found[0].message
    assert "the E of F1.875e+06" in found[1].message
    text = explained("M229 E1 D1\nG1 X10 F1.875e+06 E2")
    assert "F1.875 (moving at 1.875 mm/min)" in text  # (the same reading as the rules' state)
    assert "F1.875e+06 is exponent notation" in text and "the E of F1.875e+06" in text
    # a compact line's E word is not an exponent: "G1X10E5" is X10 and E5
    assert lint("G1X10E5F600\nG1 X10E0.5\ng1x10e1\n", codes=("HY067",)) == []
    # RepRapFirmware reads "C7.06e-8" as one number: not a finding there
    reprap = Linter(Options(dialect="reprap")).check_text("M305 P0 T100000 B4725 C7.06e-8\n").findings
    assert not [f for f in reprap if f.code in ("HY067", "SX006")]


def test_hy014_and_hy037_say_what_the_pages_say():
    # M756: "ignored if you are using M229 E1 D1"; G2: "native Hyrel flow calculations (based on nozzle diameter,
    # layer thickness, and feed rate) even if your gcode has enabled the use of E values with M229 E1 D1"
    job = "M229 E1 D1\nM756 S0.2\nG1 X0 Y0 F1200\nG2 X20 Y0 I10 J0 E0.8\nM30\n"
    found = {f.code: f.message for f in lint(job, codes=("HY014", "HY037"))}
    assert "ignored" in found["HY014"]
    assert "M221/M756" not in found["HY037"] and "do not say which layer thickness" in found["HY037"]
    from gclint.rules.hyrel.arcs import ArcEAmountIgnored

    assert "comes from M221/M756" not in ArcEAmountIgnored.explanation


# -- documentation and fixes -----------------------------------------------------------------------------


def test_documentation_examples_differ_and_share_their_options():
    """A rule's documentation shows its Bad and Good examples under one set of options (those of Bad): the two
    must differ as shown, and a Good example must not need other options (HY007, HY043 showed the same line)."""
    for code, rule in all_rules().items():
        bad, bad_options = _example(rule.example_bad)
        good, good_options = _example(rule.example_good)
        assert bad != good, code
        if code.startswith("HY"):
            assert not good_options or good_options == bad_options, code


def test_unsafe_fix_recomputes_a_right_checksum(tmp_path: Path):
    """Whatever rules are selected, a fix of a checksummed line writes the checksum of the new text."""
    line = "N5 M6 T1"
    job = tmp_path / "job.gcode"
    job.write_text(f"; gclint: dialect=hyrel\n{line}*{compute_checksum(line)}\nM30\n")
    proc = run_cli("check", "--fix", "--unsafe-fixes", "--select", "HY", str(job))
    assert b"1 fixed" in proc.stdout, proc.stdout
    fixed = job.read_text().splitlines()[1]
    assert fixed == f"N5 T1*{compute_checksum('N5 T1')}"
    assert run_cli("check", str(job)).returncode == 0, run_cli("check", str(job)).stdout


def test_diff_marks_a_last_line_without_a_line_break(tmp_path: Path):
    """As diff -u and git diff do: every line of the diff ends with a line break, so a last line without one
    is marked."""
    job = tmp_path / "job.gcode"
    job.write_text("; gclint: dialect=hyrel\nM6 T1\nG1 X10 E1 F600\nM30")
    out = run_cli("check", "--diff", "--unsafe-fixes", str(job)).stdout.decode()
    assert out.endswith(" M30\n\\ No newline at end of file\n"), out
    job.write_text("; gclint: dialect=hyrel\nM6 T1")
    out = run_cli("check", "--diff", "--unsafe-fixes", str(job)).stdout.decode()
    assert out.endswith("-M6 T1\n\\ No newline at end of file\n+T1\n\\ No newline at end of file\n"), out
