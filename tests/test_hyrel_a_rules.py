"""Hyrel rules, part A: temperature (HY002, HY003, HY027, HY035, HY036, HY046, HY051), offsets (HY004,
HY005, HY025, HY034, HY038, HY055, HY061) and job flow (HY009, HY010, HY029, HY043, HY044, HY056,
HY059): the cases the fixture pairs do not pin down, and the machine state these rules read."""

from __future__ import annotations

import textwrap

import pytest

from gclint.dialects import get as get_dialect
from gclint.engine import Linter, Options
from gclint.machine.interpreter import Interpreter
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line
from tests.conftest import run_cli


def lint(text: str, dialect: str = "hyrel", printer: str = "30m", codes: tuple[str, ...] = (), **options):
    found = Linter(Options(dialect=dialect, printer=printer, **options)).check_text(textwrap.dedent(text)).findings
    return [f for f in found if not codes or f.code in codes]


def where(findings) -> list[tuple[int, str, str]]:
    return [(f.line, f.code, f.severity.label) for f in findings]


def run_state(text: str, dialect: str = "hyrel"):
    interpreter = Interpreter(get_dialect(dialect))
    for number, raw in enumerate(textwrap.dedent(text).splitlines(), 1):
        line = Line(number, raw, "\n", parse_line(raw))
        for cmd in line.commands:
            interpreter.apply(cmd, line)
    return interpreter.state


# -- machine state used by these rules -----------------------------------------------------------------


def test_state_first_move_and_prints_since_home_and_m30():
    st = run_state("""\
        G28 X0 Y0
        G0 X10 Y10
        G1 X20 E1 F600
        G28 X0 Y0
        G1 X30 E1
        M30
        G0 X0
        """)
    assert st.first_move_line == 2
    assert st.first_print_line == 3
    assert st.first_print_since_home_line == 5
    assert st.first_print_since_m30_line is None


def test_state_plain_wait_settles_w0_and_m703_needs_m702():
    st = run_state("M109 T0 S200 W0\nM190 T24 S60 W0\nM109 T0 S200\nM703 T1 S31\nM702 T0 S30\nM703 T1 S30\n")
    assert st.pending_w0 == {24: 2}
    assert st.squads == {30: {1}}


def test_state_applied_height_line_is_where_the_register_was_applied():
    st = run_state("M660 H2 Z5\nG1 Z1 H2\nG1 X1 H2\nG1 X2 H3\n")
    assert (st.applied_height_register, st.applied_height_line) == (3, 4)
    st = run_state("M660 H2 Z5\nG1 Z1 H2\nG1 X1 H2\n")
    assert (st.applied_height_register, st.applied_height_line) == (2, 2)


# -- temperature ---------------------------------------------------------------------------------------


def test_hy002_one_finding_per_line_at_the_second_group():
    found = lint("M109 T0 S240 R5 H230\n", codes=("HY002",))
    assert [(f.line, f.column) for f in found] == [(1, 17)]


def test_hy003_reads_v4_group_numbers():
    text = "M109 T100 S200\nM190 T90 S60\nM109 T0 S200\nM109 T11 S200\n"
    assert where(lint(text, dialect="hyrel-v4", codes=("HY003",))) == [
        (1, "HY003", "error"),
        (2, "HY003", "error"),
        (3, "HY003", "error"),
    ]


def test_hy027_m116_on_v4_is_one_finding():
    found = lint("M116\n", dialect="hyrel-v4")
    assert where(found) == [(1, "HY027", "error")]


def test_hy035_a_wait_without_s_is_the_pages_own_example():
    # Gcode page, M109 Example 6: "M109 R10 ... (no T# - use head with current focus) R10 (to get +/-10°C of
    # set temperature)": no earlier S in the job is needed (the head settings or the operator may have set it)
    text = """\
        M109 R10
        M109 T1 R5
        M190 R2
        """
    assert lint(text, codes=("HY035",)) == []


def test_hy035_no_limit_on_r_with_s():
    # "Rn if present, is how close the relative temperature needs to be to the set temp": no limit given
    assert lint("M109 T0 S240 R60\nM190 T24 S100 R80\nM191 S60 R55\n", codes=("HY035",)) == []
    assert where(lint("M109 T0 R60\n", codes=("HY035",))) == [(1, "HY035", "error")]


def test_hy036_reports_at_the_w0_line_once():
    text = "M109 T0 S200 W0\nG1 X1 E1 F600\nM30\n"
    assert where(lint(text, codes=("HY036",))) == [(1, "HY036", "warning")]
    assert lint("M109 T0 S200 W0\nM116\nM30\n", codes=("HY036",)) == []


# (select=HY046 alone: with HY008 enabled, T21-T26 are left to HY008 as possible v4 numbers)
@pytest.mark.parametrize("line", ["M109 T20 S50", "M190 T20 S50", "M191 T21 S30", "M109 T22 S40", "M190 T23 S40"])
def test_hy046_no_wait_fits_a_spindle_laser_or_aux(line):
    found = lint(line + "\n", select=["HY046"])
    assert len(found) == 1
    assert "use M109" not in found[0].message and "no temperature to wait for" in found[0].message


def test_hy046_names_the_wait_that_fits():
    assert "use M109" in lint("M190 T0 S60\n", select=["HY046"])[0].message
    assert "M190 (bed) or M191 (chamber)" in lint("M109 T24 S60\n", select=["HY046"])[0].message
    assert lint("M109 T0 S200\nM190 T24 S60\nM191 T25 S40\n", select=["HY046"]) == []


def test_hy051_beds_may_be_chilled():
    assert lint("M140 T24 S-10\nM190 T24 S-10\n", codes=("HY051",)) == []
    # "heated and chilled (sub-ambient) beds": no lowest set point on the page, so no DL003 either
    assert lint("M140 T24 S-60\nM141 T25 S-80\n", codes=("HY051", "DL003")) == []


def test_hy051_a_chilled_head_is_not_an_error():
    # "we have both heated and chilled (sub-ambient) heads as options": at most an info
    found = lint("M104 T0 S-20\nM109 T1 S-5 R2\nM104 T2 S4\n")
    assert where(found) == [(1, "HY051", "info"), (2, "HY051", "info")]
    assert "chilled" in found[0].message


# -- offsets -------------------------------------------------------------------------------------------


def test_hy004_needs_the_register_set_and_applied():
    assert where(lint("G1 Z5 F600 H1\nG81 T0 X1 Y1 I3 P1 Q-1 Z-2 F100\n", codes=("HY004",))) == [(2, "HY004", "error")]
    assert lint("M660 H1 Z5\nG1 Z5 F600 H1\nG81 T0 X1 Y1 I3 P1 Q-1 Z-2 F100\n", codes=("HY004",)) == []
    # "M660 Hn Zn (followed by) G1 Xn Yn Zn Fn Hn"; a G0 applies H too (the firmware's G0 and G1 both queue the
    # move through motionQ_addCommand, which takes the register from H): real Hyrel jobs write "G0 Z0 H2"
    assert lint("M660 H1 Z5\nG0 Z5 H1\nG81 T0 X1 Y1 I3 P1 Q-1 Z-2 F100\n", codes=("HY004",)) == []


@pytest.mark.parametrize("printer", ["30m", "esr", "16a", "16a-dual"])
def test_hy005_only_on_the_ehr(printer):
    assert lint("M660 H2 Z28.2\n", printer=printer, codes=("HY005",)) == []


def test_hy025_flags_are_not_values():
    # "G28 X Y" (a Marlin habit) lists the axes: homed; no value to ignore
    assert lint("G28 X Y\n", codes=("HY025",)) == []


def test_hy034_mentions_m30_and_reports_each_register_once():
    text = "M660 H2 Z5\nG1 Z1 H2\nM30\nG1 Z1 H2\nG1 Z2 H2\n"
    found = lint(text, codes=("HY034",))
    assert where(found) == [(4, "HY034", "warning")]
    assert "M30 at line 3" in found[0].message


def test_hy038_unsafe_fix_to_a_t_command():
    found = lint("M6 T1\n", codes=("HY038",))
    assert found[0].fix is not None and not found[0].fix.safe
    assert [(e.start, e.end, e.text) for e in found[0].fix.edits] == [(1, 6, "T1")]
    # v4: the T variable of M6 is a device address; v4 T12 is the tool T1
    found = lint("M6 T12\n", dialect="hyrel-v4", codes=("HY038",))
    assert found[0].fix.edits[0].text == "T1"


def test_hy055_homing_at_the_end_is_fine():
    text = "G92 X10 Y10\nG1 X10 E1 F600\nG28 X0 Y0\nM30\n"
    assert lint(text, codes=("HY055",)) == []


def test_hy055_g28_applies_a_head_offset_of_0():
    # "applies a head offset of 0 mm (as in an M6 O0)": the head selected before the G28 prints without
    # its offsets until a T command invokes them again
    text = """\
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X20 Y-30 Z0
        T1
        G28 X0 Y0
        G1 X20 Y10 E1 F1200
        """
    found = lint(text, codes=("HY055",))
    assert where(found) == [(4, "HY055", "warning")]
    assert "T1" in found[0].message and "M6 O0" in found[0].message
    # re-selected before printing: fine; a T after the printing started does not help
    assert lint(text.replace("G1 X20", "T1\n        G1 X20"), codes=("HY055",)) == []
    assert len(lint(text + "        T1\n        G1 X30 E1\n", codes=("HY055",))) == 1
    # an M6 T# ... I1 applies the offsets ("when you execute a tool change with T#")
    assert lint(text.replace("G1 X20", "M6 T1 O2 X20 Y-30 Z0 I1\n        G1 X20"), codes=("HY055",)) == []


def test_hy055_head_offset_silent_when_it_changes_nothing_or_nothing_was_selected():
    # T0 declares only zero offsets: a head offset of 0 mm is its own offset
    assert lint("M6 T0 O1 X0 Y0 Z0\nT0\nG28 X0 Y0\nG1 X1 E1 F600\n", codes=("HY055",)) == []
    # no T command at all: Default Mode, "executed with the only head loaded"
    assert lint("M6 T1 O2 X20 Y0 Z0\nG28 X0 Y0\nG1 X1 E1 F600\n", codes=("HY055",)) == []
    # the usual header: home first, then select the head
    assert lint("G28 X0 Y0\nT1\nG1 X1 E1 F600\nG28 X0 Y0\nM30\n", codes=("HY055",)) == []
    # offsets unknown (Repetrel sends them behind the scenes): reported
    assert len(lint("T1\nG28 X0 Y0\nG1 X1 E1 F600\n", codes=("HY055",))) == 1
    # v4 files: the same (T commands are tool numbers 0-9)
    assert len(lint("M6 T12 O2 X20 Y0\nT1\nG28 X0 Y0\nG1 X1 E1 F600\n", dialect="hyrel-v4", codes=("HY055",))) == 1


def test_state_head_reselected_since_g28():
    st = run_state("T1\nG28 X0 Y0\n")
    assert st.head_reselected_line is None and st.tool == 1
    st = run_state("T1\nG28 X0 Y0\nT2\nT1\n")
    assert st.head_reselected_line == 3
    st = run_state("M6 T1 O2 X20 Y-3 Z0\nM6 T2 O3 X0 Y0\n")
    assert st.declared_offsets == {1: {"X": 20, "Y": -3, "Z": 0}, 2: {"X": 0, "Y": 0}}
    assert not st.head_offsets_zero(1) and st.head_offsets_zero(2) and not st.head_offsets_zero(3)


def test_hy061_o0_without_offsets_is_fine():
    assert lint("M6 O0\nM6 T0 O0 X0 Y0\n", codes=("HY061",)) == []


# -- job flow ------------------------------------------------------------------------------------------


def test_hy009_once_per_m30_and_not_for_comments():
    text = "G1 X1 E1 F600\nM30\n; done\n\n%\nG1 X2\nG1 X3\nM30\nG1 X4\n"
    assert where(lint(text, codes=("HY009",))) == [(6, "HY009", "error"), (9, "HY009", "error")]


def test_hy010_not_for_files_without_moves():
    assert lint("M104 T0 S0\nM140 S0\n", codes=("HY010",)) == []


@pytest.mark.parametrize(
    "line,detail,severity",
    [
        ("; " + "x" * 120, "only comment text is cut", "info"),
        ("G1 X10 Y10 E1 F600 ; " + "x" * 100, "only comment text is cut", "info"),
        ("M0 ; SAY " + "x" * 100, "M0/M792 text", "warning"),
        ("G1 " + "X10.000000000 " * 7 + "Y20 E1", "loses Y20 E1", "warning"),
    ],
)
def test_hy029_says_what_is_lost(line, detail, severity):
    found = lint(line + "\n", codes=("HY029",))
    assert len(found) == 1 and found[0].column == 101 and detail in found[0].message, found
    assert found[0].severity.label == severity


def test_hy029_does_not_count_a_trailing_noqa_comment(tmp_path):
    """As ruff's E501: --add-noqa must not push a line over the limit and make a new finding."""
    text = "M109 T40 S215 ; " + "x" * 80 + "\nT0\nG1 X1 Y1 F100\nM30\n"
    assert lint(text + "G1 X1 ; " + "x" * 80 + " ; noqa: HY003\n", codes=("HY029",)) == []
    assert len(lint("G1 X1 (noqa: HY003) " + "Y2 " * 40 + "\n", codes=("HY029",))) == 1  # words after it are cut
    job = tmp_path / "an.gcode"
    job.write_text(text)
    assert run_cli("check", "--add-noqa", str(job)).returncode == 0
    assert run_cli("check", str(job)).returncode == 0, job.read_text()


def test_hy029_counts_characters_not_bytes():
    assert lint("; " + "é" * 98 + "\n", codes=("HY029",)) == []


def test_hy043_follows_the_printer():
    assert where(lint("M671 S100\n", printer="16a", codes=("HY043",))) == [(1, "HY043", "warning")]
    assert lint("M671 S100\n", printer="esr", codes=("HY043",)) == []


def test_hy044_missing_s_is_info_except_m7_m8():
    assert where(lint("M7\nM8\nM676\n", printer="16a", codes=("HY044",))) == [(3, "HY044", "info")]


def test_hy056_printing_after_m30_without_m229_and_t():
    text = """\
        M229 E1 D1
        T2
        G1 X1 E1 F600
        M30
        G1 X2 E2
        M30
        """
    found = lint(text, codes=("HY056",))
    assert where(found) == [(4, "HY056", "warning")]
    assert "M229 E1" in found[0].message and "T2" in found[0].message


def test_hy059_actions_any_case_and_directives():
    text = "M792 ; say hello ; beep\nM0 ; SAY hi ; noqa: HY029\nM792 ;SHELL C:\\x.exe\nM792 ; SAYS hi\n"
    assert where(lint(text, codes=("HY059",))) == [(4, "HY059", "info")]


# -- the Hyrel code table (DL001) ------------------------------------------------------------------------


@pytest.mark.parametrize("dialect", ["hyrel", "hyrel-v4"])
def test_dl001_knows_the_codes_the_pages_and_hyrel_files_use(dialect):
    # M92 (named by M253: "using the value set with M92 for RPM"), the M772 reports M774/M775/M776/M779
    # (hidden-codes page) and M627 (Hyrel's own slicer start code: "M627 X0 Y0 Z0 J-500 K5")
    text = "M92 S200\nM774\nM775\nM776\nM779\nM627 X0 Y0 Z0 J-500 K5\n"
    assert lint(text, dialect=dialect, codes=("DL001", "DL002")) == []
    # M777 and M778 are not named anywhere on the pages
    assert where(lint("M777\nM778\n", dialect=dialect, codes=("DL001",))) == [
        (1, "DL001", "error"),
        (2, "DL001", "error"),
    ]


# -- HY063 head-prints-without-temperature ---------------------------------------------------------------


def test_state_group_addresses_set_every_head_they_cover():
    # T_v5: T40 "ALL DEVICES", T41 "Yoke 1, all Heads", T46 "All Beds / Chambers", T47 "All non-Bed /
    # non-Chamber devices"; a clone squad's heads
    st = run_state("M104 T41 S200\n")
    assert {d: st.targets[d] for d in range(5)} == dict.fromkeys(range(5), 200) and 5 not in st.targets
    st = run_state("M104 T47 S0\nM140 T46 S60\n")
    assert st.targets[19] == 0 and st.targets[24] == st.targets[25] == 60
    st = run_state("M702 T0 S30\nM703 T2 S30\nM104 T30 S180\n")
    assert st.targets[2] == 180 and st.targets[30] == 180 and 1 not in st.targets
    # v4: T100 is all heads (v5 T47), T10 yoke 1 (v5 T41)
    st = run_state("M104 T100 S210\n", dialect="hyrel-v4")
    assert st.targets[7] == 210
    # first printing move since the tool change
    st = run_state("T1\nG1 X1 E1 F600\nG1 X2 E1\n")
    assert st.first_print_since_tool_line == 2
    assert run_state("T1\nG1 X1 E1 F600\nT2\n").first_print_since_tool_line is None


def test_hy063_a_tool_change_to_a_head_never_heated():
    text = """\
        M109 T0 S215
        T0
        G1 X10 Y10 E1 F1200
        T1
        G0 X0
        G1 X20 Y10 E1
        T1
        G1 X30 Y10 E1
        """
    found = lint(text, codes=("HY063",))
    assert where(found) == [(6, "HY063", "warning")]  # once per head, at its first printing move
    assert "T1" in found[0].message and "line 4" in found[0].message
    # heated before printing (by its address, the focused head, a group, or a squad it is in): fine
    for heat in ("M104 T1 S200", "M104 T41 S200", "M104 T40 S200", "M104 T47 S200"):
        assert lint(text.replace("T1\n", f"T1\n        {heat}\n", 1), codes=("HY063",)) == [], heat
    assert lint(text.replace("G0 X0", "M109 S200"), codes=("HY063",)) == []
    # (M702 T0 only copies T0's flow settings: "this head does not need to be in the group")
    squad = "M702 T0 S30\nM703 T0 S30\nM703 T1 S30\nM104 T30 S200\nT0\nG1 X1 E1 F600\nT1\nG1 X2 E1\n"
    assert lint(squad, codes=("HY063",)) == []
    # heated only after it printed: reported
    late = "M109 T0 S215\nT0\nG1 X1 E1 F600\nT1\nG1 X2 E1\nM104 T1 S200\nG1 X3 E1\n"
    assert where(lint(late, codes=("HY063",))) == [(5, "HY063", "warning")]


def test_hy063_silent_where_it_cannot_know():
    # the file sets no head temperature (only the footer's S0): Repetrel's settings, or unheated heads
    assert lint("T0\nG1 X1 E1 F600\nT1\nG1 X2 E1\nM104 T40 S0\nM30\n", codes=("HY063",)) == []
    # no T command: Default Mode, the head Repetrel focused
    assert lint("M104 T0 S200\nG1 X1 E1 F600\n", codes=("HY063",)) == []
    # an M104 without T before any T command heats the head focused at the start: unknown, so all count
    assert lint("M104 S200\nT0\nG1 X1 E1 F600\nT1\nG1 X2 E1\n", codes=("HY063",)) == []
    # lasers/UV pens (M620 T# E1) and spindles (M3/M4) need no heat
    uv = "M109 T0 S215\nM620 T2 E1\nT0\nG1 X1 E1 F600\nT2\nG1 X2 E1\nM620 T2 E0\n"
    assert lint(uv, codes=("HY063",)) == []
    spindle = "M109 T0 S215\nT0\nG1 X1 E1 F600\nT3\nM3 S50\nG1 X2 E1\nM5\n"
    assert lint(spindle, codes=("HY063",)) == []
    # moves that do not print (travel, no E) are not printing
    assert lint("M109 T0 S215\nT0\nG1 X1 E1 F600\nT1\nG0 X5\nG1 X6\n", codes=("HY063",)) == []


def test_hy063_v4_addressing():
    # v4: M104 T12 is yoke 1 position 2, which the T command T1 selects; T13 (position 3) is never heated
    text = "M104 T12 S200\nM104 T11 S200\nT0\nG1 X1 E1 F600\nT1\nG1 X2 E1\nT2\nG1 X3 E1\n"
    assert where(lint(text, dialect="hyrel-v4", codes=("HY063",))) == [(8, "HY063", "warning")]
