"""Bounded work on hostile input (issue 12, items 8 and 9): a huge line is read in linear time and bounded
memory and reported, never parsed whole; a flood of findings is counted, not listed one by one; writers
(translate, --fix) refuse a file they could not read whole instead of writing part of it.

Speed is measured in bench/bench_long_line.py, not here; the memory test reads the child's peak RSS.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
from pathlib import Path

import pytest

from gclint.engine import MAX_FINDINGS, PER_LINE, Linter, Options
from gclint.syntax import source as source_mod

from .conftest import run_cli


def _findings(text: str, **options) -> list:
    return Linter(Options(**options)).check_text(text, "job.gcode").findings


# -- floods -----------------------------------------------------------------------------------------------------


def test_findings_of_one_kind_on_one_line_are_counted() -> None:
    line = "G1" + " X1" * 30_000  # 90,002 characters: parsed, 29,999 repeated words
    findings = [f for f in _findings(line + "\n", dialect="marlin") if f.code == "SX002"]
    assert len(findings) == PER_LINE, len(findings)
    assert findings[0].column == 7 and "more on this line" not in findings[0].message
    assert f"(and {29_999 - PER_LINE:,} more on this line)" in findings[-1].message


def test_counting_never_lowers_the_severity() -> None:
    # SX002: a letter repeated with the same value is a warning, with another value an error
    line = "G1" + " X1" * (PER_LINE + 1) + " X2\n"  # the error comes after PER_LINE warnings
    findings = [f for f in _findings(line, dialect="marlin") if f.code == "SX002"]
    assert len(findings) == PER_LINE and "(and 1 more on this line)" in findings[-1].message
    assert findings[-1].severity.label == "error"


def test_findings_per_file_are_capped() -> None:
    text = "G1 X1 X2\n" * (MAX_FINDINGS + 500)
    findings = [f for f in _findings(text, dialect="marlin") if f.code == "SX002"]
    assert len(findings) == MAX_FINDINGS
    assert "(and 500 more SX002 findings later in the file, not listed)" in findings[-1].message


def test_a_6_mb_line_of_repeated_words_is_small_in_every_sense(tmp_path: Path) -> None:
    job = tmp_path / "flood.gcode"
    job.write_text("G28\nG1" + " X1" * 2_000_000 + "\nG1 X1 X1\n")
    proc = run_cli("check", "--no-cache", "--format", "json", str(job))
    assert proc.returncode == 1, proc.stderr
    findings = json.loads(proc.stdout)
    assert len(findings) < 10 and len(proc.stdout) < 20_000, len(proc.stdout)
    assert any(f["line"] == 2 and f["code"] == "SX001" and "not parsed" in f["message"] for f in findings)


# -- long lines ---------------------------------------------------------------------------------------------------


def test_a_line_longer_than_the_limit_is_reported_not_held(monkeypatch) -> None:
    monkeypatch.setattr(source_mod, "LINE_LIMIT", 1000)
    monkeypatch.setattr(source_mod, "CHUNK", 256)
    text = "G28\nM792 ; SHELL C:\\x.exe ; " + "A" * 5000 + "\r\nG1 X1 X2\n"
    source = source_mod.Source.from_text(text, "job.gcode")
    source.cut_long_lines = True
    findings = Linter(Options(dialect="hyrel")).check_source(source).findings
    codes = {(f.line, f.code) for f in findings}
    assert {(2, "SC001"), (2, "SX001"), (3, "SX002")} <= codes, codes
    [sx] = [f for f in findings if f.code == "SX001"]
    assert f"{len(text.splitlines()[1]):,} bytes long" in sx.message


def test_writers_refuse_a_line_they_cannot_hold(monkeypatch) -> None:
    monkeypatch.setattr(source_mod, "LINE_LIMIT", 1000)
    source = source_mod.Source.from_text("G28\n" + "G1 X" + "1" * 5000 + "\nG28\n", "job.gcode")
    with pytest.raises(source_mod.SourceError, match=r"job.gcode: line 2 is longer than 1,000 bytes"):
        list(source.lines())


BIG = 5 * (1 << 20)


def _huge_job(tmp_path: Path) -> tuple[Path, bytes]:
    job = tmp_path / "huge.gcode"
    data = b"G28\nM792 ; SHELL C:\\x.exe ; " + b"A" * BIG + b"\nG1 X1 X2\n"
    job.write_bytes(data)
    return job, data


def test_a_huge_line_through_the_command_line(tmp_path: Path) -> None:
    job, data = _huge_job(tmp_path)
    proc = run_cli("check", "--no-cache", "--format", "json", str(job))
    assert proc.returncode == 1, proc.stderr
    found = {(f["line"], f["code"]) for f in json.loads(proc.stdout)}
    assert {(2, "SC001"), (2, "SX001"), (3, "SX002")} <= found, found
    out = tmp_path / "out.gcode"
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", str(job), "-o", str(out))
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "line 2 is longer than" in stderr and "huge.gcode" in stderr, stderr
    assert not out.exists() and not [p for p in tmp_path.iterdir() if p.name.startswith(".gclint-")]
    proc = run_cli("translate", "--from", "marlin", "--to", "marlin", str(job))
    assert proc.returncode == 2 and proc.stdout == b"", "half a translation on standard output"
    assert job.read_bytes() == data


def test_fix_never_writes_part_of_a_file(tmp_path: Path, monkeypatch) -> None:
    from gclint import fixes, runner

    monkeypatch.setattr(source_mod, "LINE_LIMIT", 1000)
    job = tmp_path / "job.gcode"
    data = b"; gclint: dialect=hyrel\nN1 G1 X1*12\n" + b"M117 " + b"A" * 5000 + b"\n"
    job.write_bytes(data)
    [result] = runner.run([str(job)], Options(), {})
    outcome = fixes.fix_file(result, runner.linter_for(Options()))
    assert (
        job.read_bytes() == data and outcome.fixed == 0
    )  # (the long line is SX001: no fix in a file that does not parse)


MEMORY_CHILD = r"""
import resource, subprocess, sys
proc = subprocess.run([sys.executable, "-m", "gclint", "check", "--no-cache", "--jobs", "1", "--format", "json",
                       sys.argv[1]], capture_output=True)
print(proc.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024)
"""


@pytest.mark.skipif(sys.platform != "linux", reason="ru_maxrss in KiB")
def test_memory_stays_bounded_on_a_huge_line(tmp_path: Path) -> None:
    job = tmp_path / "huge.gcode"
    with open(job, "wb") as fh:
        fh.write(b"G28\nG1 X1 Y")
        block = b"9" * (1 << 20)
        for _ in range(48):
            fh.write(block)
        fh.write(b"\nM30\n")
    env = {k: v for k, v in os.environ.items() if k != "GCLINT_CACHE_DIR"}
    out = subprocess.run(
        [sys.executable, "-c", MEMORY_CHILD, str(job)], capture_output=True, env=env, timeout=600, check=True
    )
    code, peak_mb = map(int, out.stdout.split())
    assert code == 1 and peak_mb < 100, (code, peak_mb)
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss > 0


def test_html_lists_a_bounded_number_of_findings(tmp_path: Path) -> None:
    from gclint.reports.html import HTML_FINDINGS

    job = tmp_path / "many.gcode"
    job.write_text("G1 X1 X2\n" * (HTML_FINDINGS + 10))
    proc = run_cli("check", "--no-cache", "--dialect", "marlin", "--format", "html", str(job))
    assert proc.returncode == 1, proc.stderr
    page = proc.stdout.decode()
    assert page.count('<tr class="f-') == HTML_FINDINGS and "10 more findings not listed" in page
