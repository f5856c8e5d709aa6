"""Hostile jobs from a black-box review that passed ``gclint check`` (or its ``--fail-on error`` gate), and
translations that wrote host actions.  Each case failed before the fix.

1. Smoothieware/Carvera console lines (``rm``, ``play``, ``$H``...), M98 P<number>, M502: SC003/SC004/SC005.
2. SHELL text after M0/M1/M792 in any form (``SHELLC:``, ``SAY hi SHELL``, soft hyphen...): SC001, and
   HY059 no longer calls it "not an action".
3. ``gclint check`` reports SHELL text on codes gclint translates to M0; ``gclint translate`` never writes
   a host action (the comment is removed, TR009, or the translation is refused).
4. RepRapFirmware ``echo >file``, M929, M551, M586, Klipper SDCARD_PRINT_FILE, SAVE_CONFIG, SAVE_VARIABLE.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gclint import dialects
from gclint.engine import Linter, Options
from gclint.rules.security import PAUSE_CODES, action_shell_column, holds_action, shell_offsets
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source
from gclint.translate.engine import TranslationResult, translate_source
from gclint.translate.pairs import TO_HYREL, translator_for

from .conftest import run_cli

ALL_DIALECTS = ["auto", "hyrel", "hyrel-v4", "marlin", "reprap", "machinekit", "carvera"]


def _findings(text: str, dialect: str = "auto", path: str = "job.gcode", select=("SC", "HY059")) -> list:
    return Linter(Options(dialect=dialect, select=list(select))).check_text(text, path).findings


def _codes(text: str, dialect: str = "auto", path: str = "job.gcode") -> set[str]:
    return {f.code for f in _findings(text, dialect, path) if f.code.startswith("SC")}


# -- 1. the Smoothieware console ----------------------------------------------------------------------------


def test_the_reviewed_wipe_job_fails_the_gate(tmp_path: Path) -> None:
    job = tmp_path / "wipe.cnc"
    job.write_text("G21\nG90\nrm /sd/config.txt\nplay /sd/gcodes/evil.cnc\nM30\n")
    for extra in ([], ["-d", "carvera"]):
        done = run_cli("check", "--fail-on", "error", *extra, "--", str(job))
        out = done.stdout.decode()
        assert done.returncode == 1, out
        assert "wipe.cnc:3:1: SC003 [error]" in out and "wipe.cnc:4:1: SC003 [error]" in out


CONSOLE_LINES = [
    "rm /sd/config.txt",
    "play /sd/gcodes/evil.cnc",
    "mv /sd/config.txt /sd/x.txt",
    "upload /sd/gcodes/evil.cnc",
    "buffer rm /sd/config.txt",
    "config-set sd spindle.max_rpm 30000",
    "reset",
    "rmx /sd/config.txt",  # SimpleShell matches a command by prefix
    "save_config",  # Klipper reads it as SAVE_CONFIG; Smoothieware's shell as "save"
    "$H",
    "$X",
    "$J=X10 F100",
]


@pytest.mark.parametrize("dialect", ALL_DIALECTS)
@pytest.mark.parametrize("line", CONSOLE_LINES)
def test_console_lines_are_sc003_errors_in_every_dialect(line: str, dialect: str) -> None:
    if line.startswith("$") and dialect == "auto":
        pytest.skip("a GRBL system command makes the file generic: information (the test below)")
    found = [f for f in _findings(f"G21\n{line}\n", dialect) if f.code == "SC003"]
    assert found and found[0].severity.label == "error" and found[0].column == 1, (line, dialect)


@pytest.mark.parametrize("dialect", ["auto", "generic"])
def test_a_grbl_job_read_as_generic_passes_and_its_other_console_lines_do_not(dialect: str) -> None:
    # $H, $X, $J= are the GRBL machine's own commands (what makes the file generic): information only
    grbl = "$H\n$X\nM3 S1000\nG1 X10 F500\n$J=G91 X10 F100\nM5\nM2\n"
    found = [f for f in _findings(grbl, dialect) if f.code == "SC003"]
    assert [(f.line, f.severity.label) for f in found] == [(1, "info"), (2, "info"), (5, "info")]
    assert "GRBL system command" in found[0].message
    found = [f for f in _findings(grbl + "rm /sd/config.txt\n", dialect) if f.severity.label == "error"]
    assert [(f.line, f.code) for f in found] == [(8, "SC003")]


@pytest.mark.parametrize(
    "line,dialect",
    [
        ("echo Tool change next", "carvera"),  # prints only (CarveraController's own test programs)
        ("echo Tool change next", "auto"),
        ("  rm /sd/config.txt", "carvera"),  # SimpleShell reads the first character as it is
        ("if move.axes[0].homed", "reprap"),  # RepRapFirmware meta commands, in a job read as RRF
        ("while iterations < 3", "reprap"),
        ("var count = 1", "reprap"),
        ("set var.count = 2", "reprap"),
        ("global done = false", "reprap"),
        ('abort "probe failed"', "reprap"),
        ("g1 x10 y10 f100", "machinekit"),  # LinuxCNC reads words in any case
        ("o100 sub", "machinekit"),
        ("o<probe> call [1]", "machinekit"),
        ("#1 = 5", "machinekit"),
        ("M1000", "carvera"),
    ],
)
def test_what_a_dialect_documents_otherwise_is_not_sc003(line: str, dialect: str) -> None:
    assert "SC003" not in _codes(f"{line}\n", dialect)


@pytest.mark.parametrize("dialect", ["reprap", "machinekit"])
def test_the_exceptions_are_narrow(dialect: str) -> None:
    assert "SC003" in _codes("rm /sd/config.txt\n", dialect)
    assert "SC003" in _codes("$X\n", dialect)


def test_meta_commands_outside_reprap_are_console_lines() -> None:
    # the meta commands the Carvera's shell has a command for act there ("break": stop in the debugger); a word it
    # has none for ("if") does nothing there (issue 26: SC003 only for console commands that act)
    assert "SC003" in _codes("abort\n", "carvera")
    assert "SC003" in _codes("break\n", "marlin")
    assert "SC003" not in _codes("if x > 1\n", "carvera")


def test_console_message_says_what_the_command_does() -> None:
    [f] = [f for f in _findings("rm /sd/config.txt\n", "carvera") if f.code == "SC003"]
    assert '"rm"' in f.message and "deletes a file" in f.message


@pytest.mark.parametrize("dialect", ["auto", "hyrel", "marlin", "reprap", "carvera"])
def test_m98_macro_number_runs_a_carvera_file(dialect: str) -> None:
    found = [f for f in _findings("M98 P1234\n", dialect) if f.code == "SC004"]
    assert found and "gcodes/macros/1234.cnc" in found[0].message


def test_m98_number_is_a_linuxcnc_subprogram() -> None:
    """A subprogram of the same file when "o1 sub" defines it above the call; else LinuxCNC looks for the file
    1.ngc first (interp_o_word.cc control_back_to), a Fanuc-style "O1" above the call included: reached in order
    it is only a program number (convert_control_functions, O_)."""
    assert "SC004" in _codes("O1\nG0 X1\nM99\nM98 P1 L3\n", "machinekit")
    assert "SC004" not in _codes("o1 sub\nG0 X1\no1 endsub\nM98 P1 L3\n", "machinekit")
    assert "SC004" in _codes("M98 P1 L3\nO1\nG0 X1\nM99\n", "machinekit")


@pytest.mark.parametrize("code", ["M500", "M502", "M504"])
@pytest.mark.parametrize("dialect", ["auto", "carvera", "reprap", "machinekit"])
def test_config_override_codes(code: str, dialect: str) -> None:
    assert "SC005" in _codes(f"{code}\n", dialect)


def test_config_override_codes_are_eeprom_settings_on_marlin() -> None:
    assert _codes("M500\nM502\nM504\n", "marlin") == set()


def test_config_override_codes_on_a_detected_marlin_job_say_what_they_do_there_first() -> None:
    # a Bambu job's "M500 ; save cali data": EEPROM on its own firmware, config-override on a Carvera
    bambu = "; BambuStudio 01.08.00\n; printer_model = Bambu Lab P1S\nM104 S220\nG28\nM500 ; save cali data\n"
    (finding,) = [f for f in _findings(bambu) if f.code == "SC005"]
    assert finding.message.startswith("M500 (marlin) saves the current settings to EEPROM"), finding.message
    assert "on a Smoothieware (Carvera) controller it writes" in finding.message
    (carvera,) = [f for f in _findings("M500\n", "carvera") if f.code == "SC005"]
    assert "EEPROM" not in carvera.message and "on Smoothieware/Carvera" in carvera.message


def test_bare_m471_m472_are_carvera_probe_codes() -> None:
    assert _codes("M471\nM472\n", "carvera") == set()
    assert _codes('M472 P"0:/sys/config.g"\n', "carvera") == {"SC005"}


# -- 2. host-action text -------------------------------------------------------------------------------------

SHELL_TEXTS = [
    "SHELL C:\\evil.exe",
    "SHELLC:\\evil.exe",
    "SHELL=C:\\evil.exe",
    "SHELL,C:\\evil.exe",
    "-SHELL C:\\evil.exe",
    "SHE\u00adLL C:\\evil.exe",  # soft hyphen
    "SH\u200bELL C:\\evil.exe",  # zero-width space
    "S\u200dH\u2060E\ufeffLL C:\\evil.exe",
    "\uff33\uff28\uff25\uff2c\uff2c C:\\evil.exe",  # full-width
    "SAY hi SHELL C:\\evil.exe",
    "BEEP SHELL C:\\evil.exe",
    "shell c:\\evil.exe",
    "SAY hi ; SHELL C:\\evil.exe",
]


@pytest.mark.parametrize("text", SHELL_TEXTS)
@pytest.mark.parametrize("code", ["M0", "M1", "M792"])
def test_any_shell_text_is_sc001(code: str, text: str) -> None:
    found = _findings(f"{code} ; {text}\n", "hyrel")
    assert [f.severity.label for f in found if f.code == "SC001"] == ["error"], [(f.code, f.message) for f in found]
    assert not [f for f in found if f.code == "HY059"], "HY059 must not call SHELL text 'not an action'"


@pytest.mark.parametrize("text", SHELL_TEXTS)
def test_every_dialect_reports_shell_text(text: str) -> None:
    for dialect in ALL_DIALECTS:
        assert "SC001" in _codes(f"M792 ; {text}\n", dialect), dialect


def test_shell_offsets_point_at_the_word() -> None:
    assert shell_offsets("; SAY hi SHELL x") == [9]
    assert shell_offsets("; SHE\u00adLL x") == [2]
    assert shell_offsets("; \uff33\uff28\uff25\uff2c\uff2c x") == [2]
    assert shell_offsets("; Load the blue filament") == []


def test_hy059_and_sc001_agree() -> None:
    found = _findings("M792 ; SPEAK hello\n", "hyrel")
    [hy] = [f for f in found if f.code == "HY059"]
    assert "does nothing" not in hy.message and "does not say" in hy.message
    for text in ("SHELLC:\\x.exe", "SHE\u00adLL x", "-PIC x.png", "PIC=x.png"):
        assert not [f for f in _findings(f"M792 ; {text}\n", "hyrel") if f.code == "HY059"], text


def test_pic_and_vid_are_read_the_same_way() -> None:
    for text in ("PIC=C:\\x.png", "-PIC C:\\x.png", "P\u00adIC C:\\x.png", "vid x.mp4"):
        assert _codes(f"M0 ; {text}\n", "hyrel") == {"SC002"}, text


# -- 3. translation ------------------------------------------------------------------------------------------


def test_check_reports_shell_on_codes_translated_to_m0(tmp_path: Path) -> None:
    job = tmp_path / "j.gcode"
    job.write_text(";FLAVOR:Marlin\nG28\nG1 X1 Y1 E1 F1000\nM600 ; SHELL C:\\evil.exe\n")
    done = run_cli("check", "--fail-on", "error", "--", str(job))
    assert done.returncode == 1 and "j.gcode:4:8: SC001 [error]" in done.stdout.decode()
    for code in PAUSE_CODES:
        assert "SC001" in _codes(f"{code} ; SHELL C:\\evil.exe\n", "marlin"), code


def _translate(text: str, source: str, target: str = "hyrel") -> tuple[str, TranslationResult]:
    result = TranslationResult("job", source, target)
    translator = translator_for(dialects.get(source), dialects.get(target))
    out = "".join(translate_source(Source.from_text(text, "job"), translator, result))
    return out, result


def test_pause_codes_match_the_translators() -> None:
    """Every code a translator writes as M0 with text from the source is in PAUSE_CODES (or is M0/M1)."""
    missing = []
    for name, factory in TO_HYREL.items():
        probe = factory(dialects.get(name), dialects.get("hyrel"))
        for code in sorted(probe.handlers):
            if not code.startswith("M"):
                continue
            out, result = _translate(f"G21\nG90\nT0\n{code} S3 P1 T1 ; marker\nG1 X1\n", name)
            kept = [line for line in out.splitlines() if line.startswith(("M0", "M792")) and "marker" in line]
            if kept and code not in (*PAUSE_CODES, "M0", "M1"):
                missing.append((name, code, kept))
    assert not missing


def test_translate_removes_shell_from_pauses(tmp_path: Path) -> None:
    job = tmp_path / "j.gcode"
    job.write_text(";FLAVOR:Marlin\nG28\nG1 X1 Y1 E1 F1000\nM600 ; SHELL C:\\evil.exe\nM1 ; SHELL C:\\x.exe\n")
    done = run_cli("translate", "--from", "marlin", "--to", "hyrel", str(job))
    out = done.stdout.decode()
    assert done.returncode == 0 and "SHELL" not in out and "M0 ; gclint: filament change" in out
    assert "TR009" in done.stderr.decode()


@pytest.mark.parametrize("text", SHELL_TEXTS)
@pytest.mark.parametrize("code", ["M0", "M1", "M600", "M226"])
def test_translated_pauses_never_carry_shell(code: str, text: str) -> None:
    for source in TO_HYREL:
        out, result = _translate(f"G21\nG90\nG28\n{code} ; {text}\nG1 X1\n", source)
        assert not result.refused
        assert not [f for f in _findings(out, "hyrel") if f.code == "SC001"], (source, out)


@pytest.mark.parametrize(
    "pair", [("hyrel", "hyrel"), ("hyrel-v4", "hyrel"), ("hyrel", "hyrel-v4"), ("marlin", "marlin")]
)
def test_translate_refuses_to_write_a_host_action(tmp_path: Path, pair: tuple[str, str]) -> None:
    job = tmp_path / "h.gcode"
    job.write_text("G28\nM0 ; SHELL C:\\evil.exe\nM792 ; SAY done\n")
    out = tmp_path / "out.gcode"
    for target in (["-o", str(out)], []):
        done = run_cli("translate", "--from", pair[0], "--to", pair[1], str(job), *target)
        assert done.returncode == 1
        assert done.stdout == b"" and not out.exists()
        assert "not translated" in done.stderr.decode() and "TR009" in done.stderr.decode()
    done = run_cli("translate", "--from", pair[0], "--to", pair[1], "--unsupported", "ignore", str(job))
    assert done.returncode == 1 and done.stdout == b""


HOSTILE = [
    *(f"M0 ; {t}" for t in SHELL_TEXTS),
    *(f"{c} ; SHELL C:\\x.exe" for c in ("M1", *PAUSE_CODES)),
    'M291 P"Change" S2 ; SHELL x',
    "M6 T3 (SHELL x)",
    "M0 SHELL C:\\x.exe",
    "M0 (SHELL x)",
    "M792 ; SHELL x",
    "M0 ; PIC C:\\x.png",
    "M0 ; VID x.mp4",
    "M600 ; PIC=x.png",
    *CONSOLE_LINES,
    "M1000 rm /sd/config.txt",
    'M98 P"0:/macros/x.g"',
    "M98 P1234",
    "M98.1 L2 {gcodes/x.cnc}",
    "M32 x.gco",
    "M23 x.gco",
    "M30 old.gco",
    "M28 /sys/config.g",
    'M471 S"/sys/a.g" T"/sys/b.g"',
    'M472 P"0:/sys/config.g"',
    'M559 P"x"',
    'M560 P"x"',
    'echo >"0:/sys/config.g" "M112"',
    'echo >>"0:/sys/config.g" "M112"',
    'M929 P"0:/sys/homeall.g" S1',
    'M551 P"pw123"',
    "M586 P2 S1",
    "M500",
    "M502",
    "M504",
    "SAVE_CONFIG",
    "SDCARD_PRINT_FILE FILENAME=x.gcode",
    "SAVE_VARIABLE VARIABLE=a VALUE=1",
    "RUN_SHELL_COMMAND CMD=x",
    'M587 S"net" P"pass123"',
]


@pytest.mark.parametrize("source", sorted(TO_HYREL))
def test_translate_output_is_free_of_sc_findings(source: str) -> None:
    """Translated to Hyrel, no hostile line keeps an SC finding (comments are copied byte for byte, so a
    secret in a comment stays: SC006 on comment lines is not a host action and not asserted here)."""
    problems = []
    for line in HOSTILE:
        out, result = _translate(f"G21\nG90\nG28 X0 Y0\nG1 X1 Y1 F1000\n{line}\nG1 X2 Y2\n", source)
        if result.refused:
            problems.append((line, "refused: a translator kept a host action"))
            continue
        for dialect in ("hyrel", "auto"):
            found = [f for f in _findings(out, dialect, "out.gcode") if f.code.startswith("SC")]
            if found:
                problems.append((line, dialect, [(f.code, f.message) for f in found]))
    assert not problems


def test_the_guard_reads_lines_as_sc001_does() -> None:
    def column(raw: str) -> int | None:
        return action_shell_column(Line(1, raw, "\n", parse_line(raw)))

    assert column("M0 ; SHELL x") == 6
    assert column("M0 SHELL C:\\x.exe") == 4  # the grammar refuses the line
    assert column("N10 M792 ; say hi shell x") == 19
    assert column("M0 ; SAY hi") is None
    assert column("G1 X1 ; SHELL x") is None
    assert column("M104 S200 ; SHELL x") is None
    assert holds_action("-PIC x") and holds_action("SHELLC:x") and not holds_action("Load filament")


# -- 4. file-changing and program-running commands ------------------------------------------------------------

FILE_COMMANDS = [
    ('echo >"0:/sys/config.g" "M112"', "SC005"),
    ('echo >>"0:/sys/homeall.g" "M112"', "SC005"),
    ('echo >>>"0:/sys/homeall.g" "M112"', "SC005"),
    ('  echo >{var.file} "M112"', "SC005"),
    ('M929 P"0:/sys/homeall.g" S1', "SC005"),
    ('M929 P"homez.g" S3', "SC005"),
    ('M472 P"0:/sys/config.g"', "SC005"),
    ("SAVE_CONFIG", "SC005"),
    ("SAVE_VARIABLE VARIABLE=a VALUE=1", "SC005"),
    ('M551 P"secret-pass"', "SC006"),
    ("M586 P2 S1", "SC007"),
    ("M586 P1 S1", "SC007"),
    ("M586 P0 S1", "SC007"),
    ("SDCARD_PRINT_FILE FILENAME=other.gcode", "SC004"),
]


@pytest.mark.parametrize("dialect", ALL_DIALECTS)
@pytest.mark.parametrize("line,code", FILE_COMMANDS)
def test_file_and_network_commands(line: str, code: str, dialect: str) -> None:
    assert code in _codes(f"G28\n{line}\n", dialect), (line, dialect)


@pytest.mark.parametrize(
    "line",
    [
        'echo "done"',
        "echo {move.axes[0].homed}",
        'M929 P"eventlog.txt" S1',
        "M929 S1",
        'M929 P"0:/sys/homeall.g" S0',
        "M586 P2 S0",
        'M551 P""',
    ],
)
def test_harmless_forms(line: str) -> None:
    assert _codes(f"{line}\n", "reprap") == set()


def test_network_setup_in_the_configuration_is_not_reported() -> None:
    assert _codes("M586 P0 S1\nM586 P1 S1\n", "reprap", "printer/sys/config.g") == set()
    assert _codes("M586 P2 S1\n", "reprap", "gcodes/job.g") == {"SC007"}
    assert _codes("M586 P2 S1\n", "marlin", "printer/sys/config.g") == {"SC007"}
    # only a .g file right in sys/ is a system file: a job placed there (or deeper) is a job
    assert _codes("M586 P2 S1\n", "reprap", "jobs/sys/print.gcode") == {"SC007"}
    assert _codes("M586 P2 S1\n", "reprap", "sys/jobs/print.g") == {"SC007"}
    # (a change can add any file to a sys/ folder: only the files RepRapFirmware runs at start-up are exempt)
    assert _codes("M586 P2 S1\n", "reprap", "printer/SYS/network.g") == {"SC007"}
    assert _codes("M586 P2 S1\n", "reprap", "printer/SYS/runonce.g") == set()


def test_the_machine_password_never_reaches_a_report() -> None:
    [f] = [f for f in _findings('M551 P"secret-pass"\n', "reprap") if f.code == "SC006"]
    assert "secret-pass" not in f.message and "secret-pass" not in (f.source or "")
    assert f.column == len('M551 P"') + 1


def test_klipper_commands_are_read_in_any_case() -> None:
    assert "SC005" in _codes("save_config\n", "marlin")
    assert "SC004" in _codes("sdcard_print_file filename=x.gcode\n", "marlin")
