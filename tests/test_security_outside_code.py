"""The gate (issue 25, a third attack): names LinuxCNC hands to the shell, subroutine look-ups by base name,
definitions that may not run, RepRapFirmware codes that write files or erase the firmware, Marlin's stored macros
and LinuxCNC's user M-codes."""

from __future__ import annotations

import pytest

from gclint.engine import Linter, Options


def _found(text: str, dialect: str = "machinekit", path: str = "job.ngc") -> list[tuple[int, str, str]]:
    result = Linter(Options(dialect=dialect, select=["SC"])).check_text(text, path)
    return [(f.line, f.code, f.severity.name.lower()) for f in result.findings]


@pytest.mark.parametrize("dialect", ["machinekit", "marlin", "hyrel", "auto"])
@pytest.mark.parametrize("name", ["$(reboot)", "`id`", "${HOME}/x", "$(curl x|sh)", "a$(b)c"])
def test_a_called_name_the_shell_expands_runs_a_program(name, dialect):
    # rs274ngc_pre.cc find_ngc_file: wordexp(name, &result, 0) runs "$(...)" and "`...`"
    found = _found(f"G0 X0\no<{name}> call\nM2\n", dialect)
    assert (2, "SC001", "error") in found
    assert (2, "SC004", "warning") in found


def test_a_plain_name_is_not_a_program():
    assert [f for f in _found("o<prime> call\nM2\n") if f[1] == "SC001"] == []


def test_a_call_finds_a_subroutine_by_its_base_name():
    # interp_o_word.cc control_back_to looks up basename(o_name)
    sub = "o<x> sub\nG0 X1\no<x> endsub\n"
    assert _found(sub + "o<dir/x> call\nM2\n") == []
    assert _found("o<a/x> sub\nG0 X1\no<a/x> endsub\no<a/x> call\nM2\n") == [(4, "SC004", "warning")]


def test_a_definition_on_a_block_delete_line_may_not_run():
    text = "/o<y> sub\nG0 X1\no<y> endsub\no<y> call\nM2\n"
    assert _found(text) == [(4, "SC004", "warning")]


def test_a_definition_read_with_a_comment_line_is_no_definition():
    # LinuxCNC reads "; note\ro<z> sub" as one line: a comment
    text = "; note\ro<z> sub\nG0 X1\no<z> endsub\no<z> call\nM2\n"
    assert (5, "SC004", "warning") in _found(text)


def test_a_path_is_named_as_a_path():
    result = Linter(Options(dialect="machinekit", select=["SC004"])).check_text("o<~/evil> call\n", "job.ngc")
    assert "a path on the machine's computer" in result.findings[0].message


@pytest.mark.parametrize(
    "line",
    [
        'G29 S3 P"0:/sys/config.g"',
        'g29 s3 p"config.g"',
        'M374 P"config.g"',
        "M374 Pconfig.g",
        'M999 P"ERASE"',
        'm999 p"erase"',
        '!! M999 P"ERASE"',
    ],
)
def test_reprapfirmware_codes_that_write_files_or_erase_the_firmware(line):
    found = _found(f"G28\n{line}\n", "reprap", "job.gcode")
    assert [(n, code) for n, code, _ in found] == [(2, "SC005")]


@pytest.mark.parametrize("line", ["G29 S3", "G29 S0", "G29 P3", "G29 S3 P1", "M374", "M999", 'M999 P"x"'])
def test_ordinary_height_map_and_reset_codes_pass(line):
    assert _found(f"G28\n{line}\n", "reprap", "job.gcode") == []


@pytest.mark.parametrize(
    "line",
    ["M810 G28|M30 config.g", "m811 g28|m30 abc", "M812 G0 X1|M997 ; note", "N5 M819 G28 | M28 /sys/config.g"],
)
def test_each_command_of_a_marlin_macro_is_read(line):
    found = _found(f"G28\n{line}\n", "marlin", "job.gcode")
    assert [(n, code) for n, code, _ in found] == [(2, "SC005")]


def test_a_marlin_macro_of_plain_commands_passes():
    assert _found("M810 G28|G0 X10 Y10\nM810\n", "marlin", "job.gcode") == []


def test_linuxcnc_user_m_codes_run_programs():
    found = _found("M150 P1\nM104 P200\nM199\nM200\n", "machinekit")
    assert [(n, code) for n, code, _ in found] == [(1, "SC004"), (3, "SC004")]
    assert _found("M150 P1\n", "marlin", "job.gcode") == []  # (Marlin's M150 sets LED colours)
    # a LinuxCNC job read as another dialect: the codes that dialect does not have still run programs
    assert [(n, code) for n, code, _ in _found("G21\nM199 P1 Q2\nM2\n", "reprap")] == [(2, "SC004")]


# -- the fourth attack ----------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text,code",
    [
        ('G28\n; hi\0echo >"0:/sys/config.g" "M112"\nG1 X10\n', "SC005"),
        ("G28\nG1 X1 ; hi\0M586 P2 S1\nG1 X10\n", "SC007"),
        ('G28\n; hi\0M30 "0:/sys/config.g"\nG1 X10\n', "SC005"),
        ("G28\nM117 hi\0M586 P2 S1\nG1 X10\n", "SC007"),
    ],
)
def test_a_nul_byte_ends_a_reprapfirmware_line(text, code):
    # RepRapFirmware StringParser::Put: "if (c == 0 || c == '\n' || c == '\r') return LineFinished();"
    assert code in {c for _, c, _ in _found(text, "auto", "job.gcode")}


@pytest.mark.parametrize(
    "line",
    [
        "G1 X10 ; color #M30 X1",
        " ; comment #M30 X1",
        "M117 Printing part 1:M30 X1",
        "M117 Printing#M28 auto0.g",
        "G1 X10 Y10 ; infill " + "-" * 75 + " M28 auto0.g",
    ],
)
def test_sd_card_readers_end_commands_early(line):
    # Prusa Firmware/cmdqueue.cpp ends an SD command at "#" and after 95 characters; Marlin 1.1 at "#" and ":"
    # outside a ";" comment
    found = _found(f";FLAVOR:Marlin\nM105\nG28\n{line}\nG1 X10\n", "auto", "job.gcode")
    assert "SC005" in {code for _, code, _ in found}


def test_ordinary_slicer_comments_with_colons_and_hashes_pass():
    text = ";FLAVOR:Marlin\n;TYPE:WALL-OUTER\nM117 Layer 1: first\n; colour #FF8000\nG1 X10 ; note #1\nM105\n"
    assert _found(text, "auto", "job.gcode") == []


@pytest.mark.parametrize("line", ["o<evil> ca ll", "o100 c a l l", "o 1 0 0 c a l l", "o[100] c all"])
def test_blanks_inside_call_are_nothing_to_linuxcnc(line):
    # interp_internal.cc close_and_downcase drops blanks before read_o reads "call"
    assert [(n, code) for n, code, _ in _found(f"G21\n{line}\nM2\n")] == [(2, "SC004")]


def test_the_power_fail_script_is_read():
    found = _found('M911 S22 R23 P"echo >""0:/sys/config.g"" ""M112"""\nM911 S21 P"m586 p2 s1"\n', "reprap", "a.gcode")
    assert [(n, code) for n, code, _ in found] == [(1, "SC005"), (2, "SC007")]
    assert _found('M911 S21 R22 P"M913 X0 Y0 G91 M83 G1 Z3 E-5 F1000"\n', "reprap", "a.gcode") == []


def test_network_services_in_sys_files_other_than_start_up_ones_are_reported():
    def codes(path: str) -> list[str]:
        return [
            f.code
            for f in Linter(Options(dialect="reprap", select=["SC007"])).check_text("M586 P2 S1\n", path).findings
        ]

    assert codes("repo/sys/config.g") == []
    assert codes("repo/sys/runonce.g") == []
    assert codes("jobs/sys/part.g") == ["SC007"]


def test_more_reprapfirmware_and_marlin_codes():
    assert [c for _, c, _ in _found('G28\nM37 P"0:/gcodes/evil.g"\n', "reprap", "a.gcode")] == ["SC004"]
    assert _found("M37 S1\nM37\n", "reprap", "a.gcode") == []
    assert [c for _, c, _ in _found("M105\nM994\n", "marlin", "a.gcode")] == ["SC005"]
    found = _found("M105\nM512 P1234 S5678\nM511 P1234\n", "marlin", "a.gcode")
    assert [(n, c) for n, c, _ in found] == [(2, "SC006"), (2, "SC006"), (3, "SC006")]


# -- the fifth attack -------------------------------------------------------------------------------------------


@pytest.mark.parametrize("p", ['{"ERASE"}', "{var.e}", '{"ER"^"ASE"}'])
def test_an_expression_that_may_erase_the_firmware(p):
    # RepRapFirmware's GetQuotedString evaluates {...} before M999 compares the string with "ERASE"
    assert [c for _, c, _ in _found(f"M999 P{p}\n", "reprap", "a.gcode")] == ["SC005"]


def test_a_carvera_file_runs_its_macro_whatever_o_words_it_defines():
    # Carvera Community Firmware Player.cpp: M98 always runs /sd/gcodes/macros/<P>.cnc
    text = "G0 X0\no1234 sub\no1234 endsub\nM98 P1234\nM30\n"
    assert [(n, c) for n, c, _ in _found(text, "auto", "job.cnc")] == [(4, "SC004")]
    assert _found(text, "machinekit", "job.ngc") == []


@pytest.mark.parametrize(
    "line,found",
    [("M552 S1", True), ("M552 S2", True), ("M552 S0", False), ("M552 S-1", False), ('M586 P0 C"*"', True)],
)
def test_network_on_and_cors(line, found):
    assert bool(_found(f"{line}\n", "reprap", "a.gcode")) is found


# -- the sixth attack -------------------------------------------------------------------------------------------


@pytest.mark.parametrize("call", ["M98 P2000", "o2000 call", "M98 P2000 L1"])
def test_a_fanuc_program_number_above_the_call_defines_nothing(call):
    # interp_o_word.cc: a bare "O2000" reached in order is only logged ("Entering Fanuc-style program number");
    # the call then looks for 2000.ngc first (o-code.adoc: "the numbered subprogram must follow the M98 call")
    assert [(n, c) for n, c, _ in _found(f"O2000\nG0 X1\n{call}\nM30\n")] == [(3, "SC004")]


def test_the_mqtt_password_is_a_secret():
    found = _found('M586.4 C"dev" U"admin" K"Sup3rS3cretPassw0rd"\n', "reprap", "b.gcode")
    assert [c for _, c, _ in found] == ["SC006"]


def test_a_line_cut_into_too_many_commands_is_one_finding_in_linear_time():
    nuls = "M117 x" + "".join(f"\0M30 /a{i}" for i in range(3000))
    hashes = "G1 X1 " + "".join(f"#M30 /b{i} " for i in range(3000))
    for line in (nuls, hashes):
        # (after 12 kB of G-code: NUL bytes in a file's head make it binary, refused whole)
        found = Linter(Options(select=["SC005"])).check_text("G28\n" * 3000 + line + "\n", "job.gcode").findings
        assert any("commands after its first" in f.message for f in found), [f.message for f in found][:3]


# -- the seventh attack ---------------------------------------------------------------------------------------


def test_a_semicolon_in_a_subroutine_name_keeps_the_rest_as_written():
    # interp_internal.cc close_and_downcase copies the line from a ";" on as it is: "probe;A" is not "probe;a"
    text = 'o<"probe;A">sub\nG0 X1\no<"probe;A">endsub\no<"probe;a">call\nM2\n'
    assert [(n, c) for n, c, _ in _found(text)] == [(4, "SC004")]
    same = 'o<"probe;A">sub\nG0 X1\no<"probe;A">endsub\no<"probe;A">call\nM2\n'
    assert _found(same) == []


def test_m98_to_a_number_is_quiet_only_where_the_user_set_linuxcnc():
    text = "O2000 SUB\nG0 X1\nO2000 ENDSUB\nM98 P2000\nM2\n"
    assert [(n, c) for n, c, _ in _found(text, "auto", "job.gcode")] == [(4, "SC004")]
    assert _found(text, "machinekit", "job.ngc") == []  # (the user said LinuxCNC: it refuses the M98, runs no file)


def test_user_m_codes_in_an_ngc_file_whatever_its_content_reads_as():
    assert [(n, c) for n, c, _ in _found("G28\nM150 P255\n", "auto", "job.ngc")] == [(2, "SC004")]
    assert _found("G28\nM150 P255\n", "marlin", "job.ngc") == []  # (the user said Marlin: its LED code)


def test_an_enterprise_wifi_key_password_is_a_secret():
    line = 'M587 S"corp" X1 A"anon" U"0:/sys/user.pem" P"k.pem" Q"MyKeyPassw0rd"\n'
    result = Linter(Options(dialect="reprap", select=["SC006"])).check_text(line, "a.gcode")
    assert result.findings and all("MyKeyPassw0rd" not in (f.source or "") + f.message for f in result.findings)


# -- the eighth attack ------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "line",
    ["M552 P10.66.6.6", "M553 P255.0.0.0", "M554 P10.66.6.1", 'M588 S"*"', 'M587 S"net" P"pw"', 'M589 S"evil"'],
)
def test_network_settings_a_job_changes(line):
    # RepRapFirmware GCodes2.cpp cases 552-554 (IP address, netmask, gateway) and 587-589 (Wi-Fi networks, access
    # point): the printer joins another network or drops off its own
    assert "SC007" in [c for _, c, _ in _found(f"{line}\n", "reprap", "a.gcode")]


def test_network_settings_stay_quiet_where_they_belong():
    assert _found("M552 P10.0.0.2\nM553 P255.255.255.0\n", "reprap", "sys/config.g") == []
    # Marlin's M540 S is "abort on endstop hit", no network setting; a query changes nothing
    assert [c for _, c, _ in _found("M540 S1\nM553\n", "marlin", "a.gcode") if c == "SC007"] == []


@pytest.mark.parametrize(
    "line,code",
    [
        ('G1 X10 Y10 F3000 m30 "0:/sys/config.g"', "SC005"),  # RepRapFirmware reads its letters in either case
        ("G4 S0 m586 P2 S1", "SC007"),
        ('M117 "Printing..." M30 "0:/sys/config.g"', "SC005"),  # a quoted message ends at its closing quote
        ('NM30 "0:/sys/config.g"', "SC005"),  # a line number with no digits: what follows "N" runs
        ("nm586 P2 S1", "SC007"),
        ("N SAVE_CONFIG", "SC005"),  # Klipper: a lone "N" word, then the command
        ("N!! RUN_SHELL_COMMAND CMD=backup", "SC001"),
    ],
)
def test_commands_a_firmware_finds_where_the_grammar_reads_none(line, code):
    for dialect in ("auto", "reprap", "marlin"):
        assert code in [c for _, c, _ in _found(f"G28\n{line}\n", dialect, "job.g")], (dialect, line)


def test_an_o_word_name_is_no_lower_case_code():
    assert _found("o<m162> sub\nM67 E#500 Q1\no<m162> endsub\n", "machinekit", "m162.ngc") == []


def test_a_console_command_by_prefix_in_a_linuxcnc_reading():
    # SimpleShell matches command names by prefix (strncasecmp): "dfup[1]" runs dfu on a Carvera, though
    # LinuxCNC would read a D word; a LinuxCNC word is one letter, so "g1 x10" stays LinuxCNC's
    text = "G21 G90\no100 sub\ng0 x1\no100 endsub\no100 call\ndfup[1]\ng1 x10 f100\nM2\n"
    assert [(n, c) for n, c, _ in _found(text, "auto", "a.nc") if c == "SC003"] == [(6, "SC003")]


def test_a_subroutine_the_job_defines_below_the_call_is_information():
    # o-code.adoc: a Fanuc-style subprogram "must follow the M98 call"; LinuxCNC looks for 100.ngc first, so
    # the call is still said, as information; a subroutine the job never defines stays a warning
    below = "o1 (main)\nM98 P100\nM30\no100\nG0 X0\nM99\n"
    assert _found(below, "machinekit", "job.ngc") == [(2, "SC004", "info")]
    called = "o<later> call\nM2\no<later> sub\nG0 X1\no<later> endsub\n"
    assert _found(called, "machinekit", "job.ngc") == [(1, "SC004", "info")]
    assert _found("o<nowhere> call\nM2\n", "machinekit", "job.ngc") == [(1, "SC004", "warning")]


def test_a_comment_an_sd_card_reader_splits_is_no_user_m_code():
    # "(Illegal:  O-sub ...)": Prusa's SD reader ends a command at ":", and the view's "O-sub" is no M100-M199
    assert _found("(Illegal:  O-sub with no M02)\nG0 X1\nM2\n", "machinekit", "job.ngc") == []


@pytest.mark.parametrize(
    "line,code",
    [
        ('M118 S"hi;x" M30 "0:/sys/config.g"', "SC005"),  # (a ";" inside a quoted string starts no comment)
        ('M291 P"hi;x" S1 M552 S1', "SC007"),
        ('G10 P0 S"a(b" M586 P1 S1', "SC007"),
        ("M552 S{1}", "SC007"),  # (an expression may be 1)
    ],
)
def test_the_ninth_attack(line, code):
    assert code in [c for _, c, _ in _found(f"G28\n{line}\n", "reprap", "job.g")], line
