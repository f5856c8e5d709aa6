"""The command line, run for real in a subprocess: exit codes, formats, stdin, folders, bad input."""

from __future__ import annotations

import json

from .conftest import ROOT, run_cli

EXAMPLE = ROOT / "examples" / "hyrel_job.gcode"


def test_version_and_help():
    assert run_cli("--version").returncode == 0
    proc = run_cli("--help")
    assert proc.returncode == 0 and b"check" in proc.stdout and b"translate" in proc.stdout


def test_check_example_finds_problems_and_exits_1():
    proc = run_cli("check", str(EXAMPLE))
    out = proc.stdout.decode()
    assert proc.returncode == 1, proc.stderr
    assert f"{EXAMPLE}:" in out and "Found" in out


def test_clean_file_exits_0(tmp_path):
    job = tmp_path / "ok.gcode"
    job.write_text("; gclint: dialect=marlin\nG21\nG90\nG1 X1 Y1 F1200\n")
    proc = run_cli("check", str(job))
    assert proc.returncode == 0, proc.stdout
    assert b"All checks passed" in proc.stdout


def test_exit_zero_and_select_ignore(tmp_path):
    job = tmp_path / "bad.gcode"
    job.write_text("G1 X1 X2\n")
    marlin = ("--dialect", "marlin")  # (with nothing to tell, the file would be read as hyrel: no M30, no F)
    assert run_cli("check", str(job), *marlin).returncode == 1
    assert run_cli("check", str(job), *marlin, "--exit-zero").returncode == 0
    assert run_cli("check", str(job), *marlin, "--ignore", "SX002").returncode == 0
    assert run_cli("check", str(job), *marlin, "--select", "DL").returncode == 0
    assert run_cli("check", str(job), *marlin, "--select", "SX00").returncode == 1


def test_json_format_fields(tmp_path):
    job = tmp_path / "bad.gcode"
    job.write_text("N1 G1 X1*12\n")
    proc = run_cli("check", str(job), "--format", "json")
    data = json.loads(proc.stdout)
    assert proc.returncode == 1
    finding = next(f for f in data if f["code"] == "SX004")
    assert finding["path"] == str(job) and finding["line"] == 1 and finding["column"] == 9
    assert finding["severity"] == "error" and "checksum" in finding["message"]
    assert finding["fix"]["edits"][0]["content"].startswith("*")
    ruff_spelling = run_cli("check", str(job), "--output-format", "json")  # ruff's name for the option
    assert json.loads(ruff_spelling.stdout) == data


def test_stdin():
    proc = run_cli("check", "-", "--dialect", "marlin", input=b"G1 X1 X2\n")
    assert proc.returncode == 1
    assert proc.stdout.decode().startswith("-:1:7: SX002")
    proc = run_cli("check", "-", "--stdin-filename", "job.gcode", input=b"G1 X1 X2\n")
    assert proc.stdout.decode().startswith("job.gcode:1:")


def test_folder_walk(tmp_path):
    (tmp_path / "a.gcode").write_text("G1 X1 X2\n")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "b.NC").write_text("G1 X1 X2\n")
    (tmp_path / "notes.txt").write_text("G1 X1 X2\n")
    proc = run_cli("check", str(tmp_path), "--format", "json", "--jobs", "2")
    paths = sorted({f["path"] for f in json.loads(proc.stdout)})
    assert paths == [str(tmp_path / "a.gcode"), str(tmp_path / "sub" / "b.NC")]


def test_bad_input_exit_2_one_line(tmp_path):
    cases = {
        "missing": (str(tmp_path / "nope.gcode"), "no such file"),
        "empty folder": (str(tmp_path), "no G-code files"),
    }
    for name, (path, text) in cases.items():
        proc = run_cli("check", path)
        err = proc.stderr.decode()
        assert proc.returncode == 2, name
        assert text in err and path in err and err.count("\n") == 1, (name, err)
        assert "Traceback" not in err


def test_not_gcode_is_refused(tmp_path):
    script = tmp_path / "run.gcode"
    script.write_text("#!/bin/sh\necho hi\n")
    proc = run_cli("check", str(script))
    assert proc.returncode == 2 and b"not G-code" in proc.stderr


def test_usage_errors_exit_2():
    assert run_cli("check", str(EXAMPLE), "--dialect", "nonsense").returncode == 2
    assert run_cli("check", str(EXAMPLE), "--printer", "ultimaker").returncode == 2
    assert run_cli("check", str(EXAMPLE), "--format", "yaml").returncode == 2
    assert run_cli("check", str(EXAMPLE), "--loaded", "T99").returncode == 2


def test_non_utf8_output_does_not_crash(tmp_path):
    job = tmp_path / "latin1.gcode"
    job.write_bytes(b"G1 X1 X2 ; caf\xe9\n")
    proc = run_cli("check", str(job))
    assert proc.returncode == 1 and b"Traceback" not in proc.stderr
    assert b"SX002" in proc.stdout


def test_dialects_and_rules_commands():
    proc = run_cli("dialects")
    names = [line.split()[0] for line in proc.stdout.decode().splitlines()]
    assert names == ["hyrel", "hyrel-v4", "marlin", "reprap", "machinekit", "carvera", "generic", "auto"]
    rules = json.loads(run_cli("rules", "--format", "json").stdout)
    assert {"SX001", "DL001"} <= {r["code"] for r in rules}
    doc = run_cli("rules", "SX004").stdout.decode()
    assert "checksum" in doc and "Bad:" in doc and "Good:" in doc


def test_translate_identity_stdin_stdout():
    data = b"G1 X1\r\nG1 X2 ; c\rG1 X3"
    proc = run_cli("translate", "--from", "marlin", "--to", "marlin", "-", input=data)
    assert proc.returncode == 0 and proc.stdout == data


def test_translate_to_dev_full_exits_2(tmp_path):
    job = tmp_path / "a.gcode"
    job.write_text("G1 X1\n" * 1000)
    proc = run_cli("translate", "--from", "marlin", "--to", "marlin", str(job), "-o", "/dev/full")
    assert proc.returncode == 2 and b"/dev/full" in proc.stderr and b"Traceback" not in proc.stderr


def test_config_file(tmp_path):
    (tmp_path / "gclint.toml").write_text('dialect = "marlin"\nignore = ["SX002"]\n')
    job = tmp_path / "a.gcode"
    job.write_text("G1 X1 X2\n")
    assert run_cli("check", str(job)).returncode == 0
    (tmp_path / "gclint.toml").write_text("nonsense = 1\n")
    proc = run_cli("check", str(job))
    assert proc.returncode == 2 and b"unknown option 'nonsense'" in proc.stderr


def test_noqa_and_disable_ranges(tmp_path):
    job = tmp_path / "a.gcode"
    job.write_text(
        "G1 X1 X2 ; noqa: SX002\n"
        "G1 X1 X2 (noqa: SX002)\n"
        "; gclint: disable=SX002\n"
        "G1 X1 X2\n"
        "; gclint: enable=SX002\n"
        "G1 X1 X2\n"
    )
    data = json.loads(run_cli("check", str(job), "--dialect", "marlin", "--format", "json").stdout)
    assert [(f["line"], f["code"]) for f in data] == [(6, "SX002")]


def test_fix_applies_safe_fixes_only(tmp_path):
    job = tmp_path / "a.gcode"
    job.write_text("N1 G1 X1*12\n")
    # a checksum fix is unsafe (a wrong checksum may be a damaged line): --fix leaves it
    proc = run_cli("check", str(job), "--fix", "--dialect", "marlin")
    assert proc.returncode == 1 and job.read_text() == "N1 G1 X1*12\n", proc.stdout
    proc = run_cli("check", str(job), "--fix", "--unsafe-fixes", "--dialect", "marlin")
    assert proc.returncode == 0, proc.stdout
    assert job.read_text() == "N1 G1 X1*96\n"  # XOR of the bytes of "N1 G1 X1"
    assert run_cli("check", str(job), "--dialect", "marlin").returncode == 0


def test_closed_standard_input_is_one_error_line():
    import subprocess
    import sys

    for args in (("check", "-"), ("check", "--fix", "-"), ("explain", "-"), ("summary", "-")):
        proc = subprocess.run([sys.executable, "-m", "gclint", *args], stdin=subprocess.DEVNULL, capture_output=True)
        assert proc.returncode in (0, 2), args  # (an empty input is fine)
        closed = subprocess.run(
            [
                sys.executable,
                "-c",
                "import os, sys, runpy; os.close(0); sys.stdin = None; sys.argv = ['gclint', *sys.argv[1:]];"
                " runpy.run_module('gclint', run_name='__main__')",
                *args,
            ],
            capture_output=True,
        )
        assert closed.returncode == 2 and b"standard input is closed" in closed.stderr, (args, closed.stderr)
        assert b"Traceback" not in closed.stderr and b"internal error" not in closed.stderr
