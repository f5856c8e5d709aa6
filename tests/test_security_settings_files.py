"""Issue 25: files the printer keeps.

* M500/M502/M504 are Marlin's EEPROM settings only where the user set the dialect (command line or
  configuration): ``printf 'M106 S255\\nM502\\n' > job.nc`` was detected as Marlin and passed, and on a Carvera
  M502 deletes the config override.
* ``M30 X1`` passed: Marlin reads everything after M30 as the file name to delete (src/gcode/parser.cpp).
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from gclint.cli import main
from gclint.engine import Linter, Options


def _check(path, *options: str) -> tuple[int, set[tuple[int, str]]]:
    result = CliRunner().invoke(main, ["check", "--no-cache", "-f", "json", *options, "--", str(path)])
    return result.exit_code, {(f["line"], f["code"]) for f in json.loads(result.stdout or "[]")}


def test_a_job_detected_as_marlin_does_not_exempt_m502(tmp_path):
    job = tmp_path / "job.nc"
    job.write_text("M106 S255\nM502\n")
    code, found = _check(job)
    assert code == 1 and (2, "SC005") in found, found


@pytest.mark.parametrize(
    "head",
    [
        ";FLAVOR:Marlin\n",  # the slicer's header
        "; gclint: dialect=marlin\n",  # the job's own directive: the job does not choose how the gate reads it
        "M109 R215\n",  # content only Marlin has
    ],
)
@pytest.mark.parametrize("code", ["M500", "M502", "M504"])
def test_what_the_job_says_does_not_exempt_the_settings_codes(tmp_path, head, code):
    job = tmp_path / "job.gcode"
    job.write_text(f"{head}G28\n{code}\n")
    assert (head.count("\n") + 2, "SC005") in _check(job)[1]


def test_the_user_saying_marlin_exempts_them(tmp_path):
    job = tmp_path / "job.nc"
    job.write_text("M106 S255\nM500\nM502\nM504\n")
    assert _check(job, "--dialect", "marlin") == (0, set())
    assert _check(job, "--flavor", "prusa-buddy") == (0, set())
    (tmp_path / "gclint.toml").write_text('dialect = "marlin"\n')
    # a configuration found beside the job is not the user's word (a change can add one: gclint.trust) ...
    assert _check(job)[0] == 1
    # ... one named with --config is
    assert _check(job, "--config", str(tmp_path / "gclint.toml")) == (0, set())
    # nor is a found configuration's firmware flavour, which names the dialect too
    (tmp_path / "gclint.toml").write_text('flavor = "prusa-buddy"\n')
    assert _check(job)[0] == 1
    assert _check(job, "--config", str(tmp_path / "gclint.toml")) == (0, set())


@pytest.mark.parametrize("dialect", ["auto", "hyrel", "marlin", "reprap", "machinekit", "carvera"])
@pytest.mark.parametrize("line", ["M30 X1", "M30 P1", "M30 S0 old.gco", "N5 M30 x1*40"])
def test_words_after_m30_are_a_file_name(dialect, line):
    found = Linter(Options(dialect=dialect, select=["SC"])).check_text(f"G28\n{line}\n", "job.gcode").findings
    assert [(f.line, f.code) for f in found] == [(2, "SC005")], line


@pytest.mark.parametrize("line", ["M30", "M30 ; end of program", "M30 (done)", "N5 M30*33", "M30   "])
def test_m30_alone_ends_the_program(line):
    assert Linter(Options(select=["SC"])).check_text(f"G28\n{line}\n", "job.gcode").findings == []


def test_a_refused_allow_file_writes_counts_the_files_its_pattern_names(tmp_path, monkeypatch):
    (tmp_path / "sys").mkdir()
    (tmp_path / "jobs").mkdir()
    (tmp_path / "pyproject.toml").write_text('[tool.gclint]\nallow-file-writes = ["sys/*.g"]\n')
    (tmp_path / "sys" / "a.g").write_text("M30 x\n")
    for name in ("jobs/b.gcode", "jobs/c.gcode", "d.gcode"):
        (tmp_path / name).write_text("G28 X0 Y0\nM30\n")
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, ["check", "--no-cache", "."])
    assert "(allow-file-writes 'sys/*.g') for 1 file: refused" in result.output + (result.stderr or ""), result.output
