"""Noise on real jobs, fixed where it starts (issue 26): each case is a line real slicers, hosts or machines
write, which gclint used to misread.

* OctoPrint's @ commands are host commands, not G-code words (``@BEDLEVELVISUALIZER`` was seven SX002 "E is
  repeated"); the ones that act on the print are reported (DL007).
* Klipper's manual probe (``TESTZ Z=-.2``, ``accept``) is not a Smoothieware console command (SC003).
* A configuration the user names (``--config``) may let RepRapFirmware system macros write files
  (``allow-file-writes``, SC005); one found beside the files may not.
* A LinuxCNC/Machinekit job's REMAP codes, from the machine's INI beside it, and its M100-M199 user M-codes
  are known codes (DL001).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from gclint.engine import Linter, Options
from gclint.machine import linuxcnc_ini
from gclint.runner import options_for
from gclint.syntax.nodes import HOST, IMPLICIT
from gclint.syntax.parse import parse_line, parse_slow
from tests.conftest import CORPUS, needs_corpus, run_cli


def codes(text: str, **options) -> list[tuple[int, str, str]]:
    result = Linter(Options(**options)).check_text(text, "job.gcode")
    return [(f.line, f.code, f.severity.label) for f in result.findings]


# -- OctoPrint @ commands ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "line,name,args",
    [
        ("@BEDLEVELVISUALIZER", "@BEDLEVELVISUALIZER", None),
        ("@pause", "@pause", None),
        ("  @custom_command with some parameters ; note", "@custom_command", " with some parameters "),
    ],
)
def test_an_at_line_is_one_host_command(line, name, args):
    for parsed in (parse_line(line), parse_slow(line)):
        [cmd] = parsed.commands
        assert (cmd.kind, cmd.code, cmd.params) == (HOST, name, {})
        assert (cmd.args.text if cmd.args is not None else None) == args
        assert not parsed.issues


@pytest.mark.parametrize("line", ["@5 ^90", "G1 @5 ^90", "G1 @.5"])
def test_linuxcnc_polar_words_stay_words(line):
    """LinuxCNC's @ (polar radius) and ^ (angle) are words: an @ followed by a number, or after a command."""
    [cmd] = parse_line(line).commands
    assert cmd.kind != HOST and cmd.params.get("@") is not None
    assert parse_line("@5 ^90").commands[0].kind == IMPLICIT


def test_bed_level_visualizer_is_no_repeated_word():
    """Artillery's start G-code (PrusaSlicer's bundled profile): "@BEDLEVELVISUALIZER" then G29."""
    job = "; gclint: dialect=marlin\nG28\n@BEDLEVELVISUALIZER\nG29 ; ABL\nM420 S1 Z3\n"
    assert codes(job) == []


def test_octoprint_commands_that_act_are_reported():
    """OctoPrint's documented @ commands (docs.octoprint.org, Features, "@ Commands"): @pause and @resume as info,
    @cancel and @abort as a warning (the rest of the job never runs); names as written (@PAUSE is none)."""
    job = "; gclint: dialect=marlin\nG28\n@pause\n@resume\n@cancel\n@abort\n@PAUSE\n@BEDLEVELVISUALIZER\n"
    assert codes(job) == [
        (3, "DL007", "info"),
        (4, "DL007", "info"),
        (5, "DL007", "warning"),
        (6, "DL007", "warning"),
    ]


def test_host_commands_in_every_dialect_are_never_unknown_codes():
    for dialect in ("hyrel", "marlin", "reprap", "machinekit", "carvera"):
        found = codes("@BEDLEVELVISUALIZER\n", dialect=dialect)
        assert not [c for c in found if c[1] in ("DL001", "SX001", "SX002")], (dialect, found)


def test_explain_says_what_a_host_command_is():
    proc = run_cli("explain", "-d", "marlin", "-e", "@pause", "-e", "@BEDLEVELVISUALIZER")
    out = proc.stdout.decode()
    assert "OctoPrint @ command: OctoPrint runs it and never sends it to the printer" in out
    assert "OctoPrint pauses the print" in out


# -- Klipper's manual probe ---------------------------------------------------------------------------------


def test_klipper_manual_probe_script_is_no_console_command():
    """Klipper's PROBE_CALIBRATE / manual probe asks for TESTZ and ACCEPT (Klipper reads commands in any case):
    Smoothieware's console has neither, so SC003 has nothing to say (it reports only console commands that act)."""
    job = "G28\nPROBE_CALIBRATE\nTESTZ Z=-.2\nTESTZ Z=+.05\naccept\nACCEPT\nSAVE_CONFIG\n"
    found = codes(job)
    assert not [c for c in found if c[1] == "SC003"], found
    assert (7, "SC005", "error") in found  # (SAVE_CONFIG still writes the printer's config)


# -- RepRapFirmware system macros: allow-file-writes ------------------------------------------------------------

MACRO = 'echo >"0:/sys/dwc-settings.json" "{}"\nM28 /sys/x.g\nM29\n'


def _rrf(tmp_path: Path, config_name: str) -> Path:
    (tmp_path / "sys").mkdir()
    (tmp_path / "sys" / "save-settings.g").write_text(MACRO)
    (tmp_path / "macros").mkdir()
    (tmp_path / "macros" / "other.g").write_text(MACRO)
    (tmp_path / config_name).write_text('[tool.gclint]\nallow-file-writes = ["sys/*.g"]\n')
    return tmp_path


def test_allow_file_writes_in_a_named_configuration(tmp_path):
    _rrf(tmp_path, "ci.toml")
    proc = run_cli("check", "--config", "ci.toml", "sys", "macros", cwd=tmp_path)
    out = proc.stdout.decode()
    assert "sys/save-settings.g" not in out  # allowed
    assert "macros/other.g:1:1: SC005" in out  # (only the files it names)
    assert "ci.toml switches off security rule SC005 (allow-file-writes 'sys/*.g') for 1 file" in out


def test_allow_file_writes_found_beside_the_files_is_refused(tmp_path):
    _rrf(tmp_path, "gclint.toml")
    proc = run_cli("check", "sys", cwd=tmp_path)
    out = proc.stdout.decode()
    assert proc.returncode == 1
    assert "sys/save-settings.g:1:1: SC005" in out
    assert "gclint.toml asks to switch off security rule SC005 (allow-file-writes 'sys/*.g') for 1 file: refused" in out


def test_allow_file_writes_patterns_are_checked(tmp_path):
    (tmp_path / "ci.toml").write_text('[tool.gclint]\nallow-file-writes = "sys/*.g"\n')
    (tmp_path / "a.g").write_text("G1 X1\n")
    proc = run_cli("check", "--config", "ci.toml", "a.g", cwd=tmp_path)
    assert proc.returncode == 2 and "'allow-file-writes' must be a list of path patterns" in proc.stderr.decode()


# -- LinuxCNC: the machine's INI beside the job ----------------------------------------------------------------


def _machine(tmp_path: Path, ini: str, job_folder: str = ".") -> Path:
    (tmp_path / "machine.ini").write_text(ini)
    folder = tmp_path / job_folder
    folder.mkdir(exist_ok=True)
    job = folder / "part.ngc"
    job.write_text("#1 = 100\nG21 G90\nM206 P#1\nM150 P1 Q2\nG1 X10 F100\nM2\n")
    return job


REMAP_INI = (
    "[EMC]\nMACHINE = fdm\n[RS274NGC]\nSUBROUTINE_PATH = subroutines\nREMAP=M206 modalgroup=10 argspec=P ngc=fan\n"
)


@pytest.mark.parametrize("where", [".", "subroutines"])
def test_remap_codes_of_the_ini_beside_or_above_the_job_are_known(tmp_path, where):
    linuxcnc_ini.clear()
    job = _machine(tmp_path, REMAP_INI, where)
    options = options_for(str(job), Options(), {}, None)
    assert options.machine_codes == ("M206",)
    result = Linter(options).check_path(str(job))
    assert result.dialect == "machinekit"
    assert not [f for f in result.findings if f.code == "DL001"], result.findings  # (M150: a user M-code)


def test_without_the_ini_the_remap_code_is_unknown(tmp_path):
    linuxcnc_ini.clear()
    job = _machine(tmp_path, "[EMC]\nMACHINE = fdm\n; no [RS274NGC], no REMAP\nREMAP=M206 ngc=fan\n")
    options = options_for(str(job), Options(), {}, None)
    assert options.machine_codes == ()
    assert [f.code for f in Linter(options).check_path(str(job)).findings if f.code == "DL001"] == ["DL001"]


def test_the_ini_is_read_safely(tmp_path):
    """Bounded (a huge file is not read), never through a link, and only for DL001: it reaches no SC rule."""
    linuxcnc_ini.clear()
    big = tmp_path / "big"
    big.mkdir()
    (big / "huge.ini").write_text(REMAP_INI + "; " + "x" * (linuxcnc_ini.MAX_BYTES + 10) + "\n")
    assert linuxcnc_ini.machine_codes(str(big / "job.ngc")) == ((), ())
    linked = tmp_path / "linked"
    linked.mkdir()
    (tmp_path / "elsewhere.ini").write_text(REMAP_INI)
    os.symlink(tmp_path / "elsewhere.ini", linked / "machine.ini")
    assert linuxcnc_ini.machine_codes(str(linked / "job.ngc")) == ((), ())
    codes_ini = tmp_path / "codes"
    codes_ini.mkdir()
    (codes_ini / "m.ini").write_text("[RS274NGC]\nREMAP=M30 ngc=x\nREMAP=M28 ngc=y\n")
    job = codes_ini / "job.ngc"
    job.write_text("G21\nM28 /home/cnc/x.ngc\nM2\n")
    linuxcnc_ini.clear()
    options = options_for(str(job), Options(), {}, None)
    assert "M28" in options.machine_codes
    assert "SC005" in [f.code for f in Linter(options).check_path(str(job)).findings]


@needs_corpus
def test_corpus_remap_jobs():
    """The Machinekit BeBoPr-Bridge configuration remaps M206 (fan control) in lineardelta.ini, beside its
    velocity-extruding test and above its subroutines' test."""
    linuxcnc_ini.clear()
    base = CORPUS / "machinekit/machinekit-cnc/configs/ARM/BeagleBone/BeBoPr-Bridge"
    for job in (base / "subroutines/fan_and_wait_on_temp_test.ngc", base / "velocity-extruding/test_lincurve.ngc"):
        options = options_for(str(job), Options(), {}, None)
        assert "M206" in options.machine_codes
        assert not [f for f in Linter(options).check_path(str(job)).findings if f.code == "DL001"]


# -- Carvera laser mode --------------------------------------------------------------------------------------


def test_carvera_laser_mode_variants_are_known_codes():
    """Makera's firmware (Laser.cpp) runs M321.2 and M322.2: laser mode on and off without the tool drop
    and the Z offset change that M321 and M322 make; CarveraController's board test uses both."""
    assert codes("; gclint: dialect=carvera\nM321.2\nG1 X10 F600 S0.5\nM322.2\nM30\n") == []
    assert codes("; gclint: dialect=carvera\nM321.3\nM30\n") == [(2, "DL001", "warning")]


# -- a dialect only assumed ----------------------------------------------------------------------------------


def test_findings_of_an_assumed_dialect_are_information_that_says_so(tmp_path):
    """A file nothing sets apart for Hyrel (a host's 3-line test: a bare G28, moves, no M30) is checked as
    Hyrel, the default, but its HY/DL findings are information naming the assumption: the gate does not fail
    a Marlin test file on what is true only of a Hyrel job.  A file with Hyrel evidence keeps its warnings."""
    result = Linter(Options()).check_text("G28\nG0 Z10 S0\nG1 X10 Y10 F600\n", "quicktest.gcode")
    assert result.context.assumed and result.context.label().startswith("hyrel v5 (assumed)")
    dialect = [f for f in result.findings if f.code.startswith(("HY", "DL"))]
    assert {f.code for f in dialect} >= {"HY025", "HY010", "DL002"}
    assert all(f.severity.label == "info" and "dialect assumed" in f.message for f in dialect)
    job = tmp_path / "quicktest.gcode"
    job.write_text("G28\nG0 Z10 S0\nG1 X10 Y10 F600\n")
    assert run_cli("check", "--no-cache", str(job)).returncode == 0
    hyrel = Linter(Options()).check_text("M6 T0 O1 X0 Y0 Z0\nG28\nT0\nG1 X10 Y10 E1 F600\n", "job.gcode")
    assert not hyrel.context.assumed
    assert [(f.code, f.severity.label) for f in hyrel.findings if f.code == "HY025"] == [("HY025", "warning")]
    told = Linter(Options(dialect="hyrel")).check_text("G28\nG1 X10 Y10 F600\n", "job.gcode")
    assert ("HY025", "warning") in [(f.code, f.severity.label) for f in told.findings]


def test_an_octoprint_smart_plug_address_is_no_stray_value():
    # jneilliii's OctoPrint plugins (Wemo, TP-Link) read "M81 192.168.1.84": the host switches that plug off
    assert codes("; gclint: dialect=marlin\nM81 192.168.1.84\n") == []
    assert codes("; gclint: dialect=marlin\nG1 X1 0.200 F600\n") == [(2, "SX007", "warning")]


# -- LinuxCNC programs and subroutine libraries --------------------------------------------------------------


def _sc004(path) -> list[str]:
    return [f.message for f in Linter(Options()).check_path(str(path)).findings if f.code == "SC004"]


def test_m98_in_a_linuxcnc_program_is_read_as_linuxcnc_reads_it(tmp_path):
    """A ".ngc" program whose content reads as LinuxCNC: M98 P1 calls its Fanuc-style subprogram O1 (o-code.adoc,
    "Fanuc-Style Numbered Programs"), not a Carvera's gcodes/macros/1.cnc; LinuxCNC looks for 1.ngc first."""
    job = tmp_path / "test.ngc"
    job.write_text("o1 (main)\n#1 = 2\nM98 P100\nM30\n\no100\nG53 G0 X0 Y0 Z0\nM99\n")
    found = _sc004(job)
    assert found and all("gcodes/macros" not in m and '"100.ngc"' in m for m in found), found
    (tmp_path / "100.ngc").write_text("o100 sub\no100 endsub\nM2\n")
    assert _sc004(job) == found  # (a file beside the job is not the one the machine runs: still said)
    carvera = tmp_path / "job.cnc"
    carvera.write_text("G0 X0\nM98 P100\nM30\n")
    assert any("gcodes/macros/100.cnc" in m for m in _sc004(carvera))


def test_a_library_subroutine_calling_its_sibling_files_is_still_reported(tmp_path):
    # (the ninth attack: a harmless or empty lib/move.ngc beside the job says nothing of the move.ngc the
    # controller runs from its SUBROUTINE_PATH)
    lib = tmp_path / "ngcgui_lib"
    (lib / "utilitysubs").mkdir(parents=True)
    (lib / "utilitysubs" / "move.ngc").write_text("o<move> sub\nG0 X#1\no<move> endsub\n")
    job = lib / "arc1.ngc"
    job.write_text("o<arc1> sub\n#<x> = 1\no<move> call [#<x>]\no<arc1> endsub\n")
    assert len(_sc004(job)) == 1
