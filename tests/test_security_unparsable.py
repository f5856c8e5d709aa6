"""Issue 25: on a line the grammar refuses, only the code at its start was read, so ``; gclint: disable=SX``
then ``!! M792 ; SHELL C:\\x.exe`` passed.  The whole line is now searched for M0, M1, M792 and the pause codes
(what a reader that skips what it cannot read runs), and what follows each is read.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from gclint.cli import main
from gclint.engine import Linter, Options


def _codes(text: str, dialect: str = "auto") -> set[tuple[int, str]]:
    found = Linter(Options(dialect=dialect, select=["SC"])).check_text(text, "job.gcode").findings
    return {(f.line, f.code) for f in found}


def test_the_reproducer_fails_the_gate(tmp_path):
    job = tmp_path / "job.gcode"
    job.write_text("; gclint: disable=SX\n!! M792 ; SHELL C:\\x.exe\n")
    result = CliRunner().invoke(main, ["check", "--no-cache", "-f", "json", "--", str(job)])
    assert result.exit_code == 1, result.output
    [finding] = json.loads(result.stdout)
    assert (finding["line"], finding["column"], finding["code"]) == (2, 11, "SC001"), finding


@pytest.mark.parametrize("dialect", ["auto", "hyrel", "marlin", "reprap", "machinekit", "carvera"])
@pytest.mark.parametrize(
    "line, code",
    [
        ("!! M792 ; SHELL C:\\x.exe", "SC001"),
        ("G1 X1 Y ?? M0 SHELL C:\\x.exe", "SC001"),
        ("{{ m1 ; shell x.exe", "SC001"),
        ("!! M600 ; SHELL x.exe", "SC001"),  # a pause code: the translator writes it as M0
        ("!! G4 M6 T1 ; SHELL x.exe", "SC001"),
        ("!! M0 ; PIC C:\\x.png", "SC002"),
        ("!! M792 ; VID C:\\x.mp4", "SC002"),
        ("!! M0000000000792 ; SHELL x.exe", "SC001"),  # leading zeros
    ],
)
def test_an_action_anywhere_in_a_refused_line(dialect, line, code):
    assert (2, code) in _codes(f"G28\n{line}\nM84\n", dialect), line


@pytest.mark.parametrize("line", ["!! M104 S200 ; SHELL x", "!! M07 ; SHELL x", "!! M7920 ; SHELL x"])
def test_other_codes_in_a_refused_line_are_not_actions(line):
    assert (2, "SC001") not in _codes(f"G28\n{line}\nM84\n"), line


def test_each_action_is_reported_once():
    found = Linter(Options(select=["SC"])).check_text("M0 ?? M792 ; PIC C:\\x.png ; SHELL y\n", "job.gcode").findings
    assert sorted(f.code for f in found) == ["SC001", "SC002"], [(f.code, f.message) for f in found]
