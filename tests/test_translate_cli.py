"""``gclint translate`` on the command line (the contracts of README.md and docs/translation.md): stdin/stdout, -o, --in-place,
--unsupported, --annotate, --tool-map, --printer, --flow, --set; ``gclint rules TR00n``."""

from __future__ import annotations

import os
import stat

from .conftest import run_cli

JOB = b"; job\nM104 S200\nM140 S60\nG28\nG1 X10 Y10 E0.5 F1200\nM204 P1500\nM107\n"
MARK = "; gclint: dialect=hyrel (written by gclint translate from marlin)"


def test_stdin_to_stdout_with_findings_on_stderr():
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "-", input=JOB)
    assert proc.returncode == 0
    out = proc.stdout.decode().splitlines()
    # the first line says what the output is, so that the gate reads it as Hyrel (issue 27)
    assert out[:4] == [MARK, "; job", "M104 T0 S200", "M140 T24 S60"]
    assert out[-1] == "M30"
    err = proc.stderr.decode()
    assert "-:4:1: TR003 " in err and ":6:1: TR002 M204" in err


def test_output_file(tmp_path):
    job = tmp_path / "job.gcode"
    job.write_bytes(JOB)
    out = tmp_path / "out.gcode"
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", str(job), "-o", str(out))
    assert proc.returncode == 0
    assert out.read_bytes().startswith(MARK.encode() + b"\n; job\nM104 T0 S200\n")
    assert job.read_bytes() == JOB


def test_in_place_replaces_the_file_and_keeps_its_mode(tmp_path):
    job = tmp_path / "job.gcode"
    job.write_bytes(JOB)
    os.chmod(job, 0o640)
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--in-place", str(job))
    assert proc.returncode == 0
    assert job.read_bytes().startswith(MARK.encode() + b"\n; job\nM104 T0 S200\n")
    assert stat.S_IMODE(job.stat().st_mode) == 0o640
    assert [p.name for p in tmp_path.iterdir()] == ["job.gcode"]  # no temporary file left


def test_unsupported_error_writes_nothing_and_exits_1(tmp_path):
    job = tmp_path / "job.gcode"
    job.write_bytes(JOB)
    out = tmp_path / "out.gcode"
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--unsupported", "error", str(job), "-o", str(out))
    assert proc.returncode == 1
    assert not out.exists()
    assert b"not translated" in proc.stderr
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--unsupported", "error", "-", input=JOB)
    assert proc.returncode == 1 and proc.stdout == b""


def test_unsupported_error_in_place_leaves_the_file(tmp_path):
    job = tmp_path / "job.gcode"
    job.write_bytes(JOB)
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--unsupported", "error", "--in-place", str(job))
    assert proc.returncode == 1
    assert job.read_bytes() == JOB


def test_unsupported_error_accepts_info_level_losses():
    data = b"M117 hello\nG1 X1 Y1 E0.2 F600\nG1 E-0.5\n"  # TR001 and TR004 only
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--unsupported", "error", "-", input=data)
    assert proc.returncode == 0, proc.stderr
    assert b"G1 X1 Y1 E0.2 F600" in proc.stdout


def test_unsupported_ignore_is_quiet():
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--unsupported", "ignore", "-", input=JOB)
    assert proc.returncode == 0 and proc.stderr == b""


def test_annotate():
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--annotate", "-", input=JOB)
    out = proc.stdout.decode().splitlines()
    assert out[2] == "M104 T0 S200 ; gclint: was 'M104 S200'"
    assert any(line.startswith("; gclint: dropped 'M204 P1500' (TR002") for line in out)
    assert "; job" in out


def test_tool_map_and_printer():
    data = b"T1\nM104 T1 S200\nG1 X1 F600\n"
    proc = run_cli(
        "translate", "--from", "marlin", "--to", "hyrel", "--tool-map", "1=T4", "--printer", "ehr", "-", input=data
    )
    assert proc.returncode == 0
    assert proc.stdout.decode().splitlines()[:3] == [MARK, "T4", "M104 T4 S200"]
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--tool-map", "1=T4", "-", input=data)
    assert b"TR007" in proc.stderr  # a 30M has no T4


def test_flow_and_settings():
    data = b"G1 X1 Y1 E0.5 F600\nG10\n"
    proc = run_cli(
        "translate",
        "--from",
        "marlin",
        "--to",
        "hyrel",
        "--flow",
        "native",
        "--set",
        "retract=explicit",
        "-",
        input=data,
    )
    assert proc.returncode == 0
    assert proc.stdout.decode().splitlines() == [MARK, "G21", "G90", "T0", "G1 X1 Y1 E1 F600", "M721 T0 I1", "M30"]


def test_bad_setting_is_a_usage_error():
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--set", "colour=blue", "-", input=JOB)
    assert proc.returncode == 2 and b"colour" in proc.stderr
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--set", "retract", "-", input=JOB)
    assert proc.returncode == 2


def test_unsupported_pair_exits_2():
    proc = run_cli("translate", "--from", "hyrel", "--to", "marlin", "-", input=b"G1 X1\n")
    assert proc.returncode == 2 and b"not supported" in proc.stderr


def test_v4_to_v5_on_the_command_line():
    proc = run_cli("translate", "--from", "hyrel-v4", "--to", "hyrel", "-", input=b"M104 T12 S200\r\nT1\r\n")
    assert proc.stdout == b"M104 T1 S200\r\nT1\r\n"


def test_identity_is_byte_for_byte():
    data = b"G1 X1  Y2\r\n;c\r\nM204 P1\r\nM109 R200"  # no final newline
    proc = run_cli("translate", "--from", "marlin", "--to", "marlin", "-", input=data)
    assert proc.stdout == data and proc.returncode == 0


def test_rules_show_tr_documentation():
    proc = run_cli("rules", "TR001")
    text = proc.stdout.decode()
    assert proc.returncode == 0 and text.startswith("TR001 dropped (info)")
    assert "Example" in text and "gclint translate" in text
    proc = run_cli("rules")
    assert all(f"TR00{n}" in proc.stdout.decode() for n in range(1, 9))


def test_check_never_reports_tr_codes():
    proc = run_cli("check", "--dialect", "marlin", "--format", "json", "-", input=JOB)
    assert b'"TR0' not in proc.stdout


def test_tool_map_to_a_bed_is_refused():
    """issue 13 item 6: a tool maps to a head (T0-T19) only; T24 is a bed: one line, exit 2."""
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", "--tool-map", "0=T24", "-", input=JOB)
    assert proc.returncode == 2 and proc.stdout == b""
    err = proc.stderr.decode().strip()
    assert len(err.splitlines()) == 1 and "T24 is Bed1" in err and "T0-T19" in err


def test_check_reports_e_words_in_machinekit_jobs():
    """issue 13 item 8: ``check --dialect machinekit`` on a job written with E (DL005)."""
    proc = run_cli("check", "--dialect", "machinekit", "--select", "DL005", "-", input=b"G1 X1 Y1 E0.5 F600\n")
    assert proc.returncode == 1 and b"DL005" in proc.stdout
