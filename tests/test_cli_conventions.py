"""Issue 14: the conventions a ruff user expects, through the real command line (statistics, severity in
the text output, a closed pipe, --fix - for editors, --show-fixes, fixable rules marked)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from tests.conftest import run_cli

V4_IN_V5 = "; gclint: dialect=hyrel\nM6 T12 O2 X0 Y0 Z0\nM109 T12 S200\nT1\nG1 X10 Y10 E1 F1200\nM30\n"
MARLIN = "; gclint: dialect=marlin\nG1 X1 X2 F600\nG1 X1 X3\nM9999\n"


def test_text_output_shows_the_severity(tmp_path: Path) -> None:
    job = tmp_path / "a.gcode"
    job.write_text(MARLIN)
    out = run_cli("check", str(job)).stdout.decode()
    assert f"{job}:2:7: SX002 [error] X appears more than once in G1" in out
    grouped = run_cli("check", "-f", "grouped", str(job)).stdout.decode()
    assert "SX002 [error] X appears" in grouped


def test_statistics_alone_prints_the_table_and_json_with_format_json(tmp_path: Path) -> None:
    job = tmp_path / "a.gcode"
    job.write_text(MARLIN)
    proc = run_cli("check", "--statistics", str(job))
    out = proc.stdout.decode()
    assert proc.returncode == 1
    assert "SX002" in out and "X appears more than once" not in out  # the table, not the findings
    assert out.splitlines()[0].split()[:2] == ["2", "SX002"]
    rows = json.loads(run_cli("check", "--statistics", "-f", "json", str(job)).stdout)
    assert rows[0] == {
        "code": "SX002",
        "name": "duplicate-word",
        "severity": "error",
        "count": 2,
        "fixable": 0,
        "first": f"{job}:2",
    }


def test_a_closed_pipe_is_quiet_and_keeps_the_exit_code(tmp_path: Path) -> None:
    job = tmp_path / "many.gcode"
    job.write_text("; gclint: dialect=marlin\n" + "G1 X1 X2\n" * 20000)
    for extra, code in (((), 1), (("--exit-zero",), 0)):
        proc = subprocess.Popen(
            [sys.executable, "-m", "gclint", "check", "--no-cache", *extra, str(job)],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        assert proc.stdout is not None and proc.stderr is not None
        proc.stdout.readline()
        proc.stdout.close()  # as "| head -1" does
        err = proc.stderr.read().decode()
        assert proc.wait(timeout=120) == code, err
        assert "Traceback" not in err and "Broken pipe" not in err and "cannot write" not in err


def test_fix_stdin_to_stdout(tmp_path: Path) -> None:
    proc = run_cli("check", "--fix", "-", input=V4_IN_V5.encode())
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.decode() == V4_IN_V5.replace("T12", "T1")
    assert "2 fixed, 0 remaining" in proc.stderr.decode()
    left = run_cli("check", "--fix", "-", input=MARLIN.encode())
    assert left.returncode == 1 and left.stdout.decode() == MARLIN  # nothing to fix: the text unchanged
    assert "SX002 [error]" in left.stderr.decode()


def test_show_fixes_lists_what_was_fixed(tmp_path: Path) -> None:
    job = tmp_path / "a.gcode"
    job.write_text(V4_IN_V5)
    out = run_cli("check", "--fix", "--show-fixes", str(job)).stdout.decode()
    assert f"Fixed in {job}:\n  2 x HY008 (v4-addressing-in-v5)\n" in out


def test_rules_marks_the_fixable_ones() -> None:
    lines = run_cli("rules").stdout.decode().splitlines()
    marked = {line.split()[0] for line in lines if line.split()[1:2] == ["[*]"]}
    assert {"HY008", "SX004", "HY038"} <= marked and "HY003" not in marked


def test_fail_on_and_per_rule_severity(tmp_path: Path) -> None:
    job = tmp_path / "a.gcode"
    job.write_text("; gclint: dialect=marlin\nG1 X1 F600\nM9999\n")  # DL001 [warning]
    assert run_cli("check", str(job)).returncode == 1
    assert run_cli("check", "--fail-on", "error", str(job)).returncode == 0
    assert run_cli("check", "--fail-on", "info", str(job)).returncode == 1
    (tmp_path / "gclint.toml").write_text('severity = { DL001 = "error" }\n')
    proc = run_cli("check", "--fail-on", "error", str(job))
    assert proc.returncode == 1 and "DL001 [error]" in proc.stdout.decode()
    (tmp_path / "gclint.toml").write_text('severity = { DL = "info" }\n')
    proc = run_cli("check", str(job))
    assert proc.returncode == 0 and "DL001 [info]" in proc.stdout.decode()
    (tmp_path / "gclint.toml").write_text('severity = { DL001 = "fatal" }\n')
    proc = run_cli("check", str(job))
    assert proc.returncode == 2 and b"unknown severity 'fatal'" in proc.stderr
