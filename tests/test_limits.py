"""Limits and failures inside a run: a rule that raises, an internal error, one bad file among many with
``--jobs N``.  Nothing stops the other rules or the other files; each problem is one line naming the rule
(when there is one) and the file, and the exit code is 2 because the check is incomplete.

(Peak memory on a 5-million-line job is measured by bench/bench_memory.py, not here.)
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gclint import runner
from gclint.engine import Linter, Options
from gclint.machine.interpreter import Interpreter
from gclint.rules.base import Rule, Severity

from .conftest import run_cli


class _Explodes(Rule):
    """Raises on the second G1 (after reporting the first), to show what is kept and what goes on."""

    code = "XX901"
    name = "explodes"
    severity = Severity.WARNING
    summary = "test rule"
    codes = ("G1",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.seen = 0

    def check(self, line, cmd) -> None:
        self.seen += 1
        if self.seen == 1:
            self.report(line, "first G1", node=cmd)
            return
        raise ValueError("bug in a rule\nwith a second line")


class _ExplodesAtEnd(_Explodes):
    code = "XX902"
    name = "explodes-at-end"
    codes = ()

    def finish(self) -> None:
        raise KeyError("finish")


class _ExplodesAtStart(_Explodes):
    code = "XX903"
    name = "explodes-at-start"

    def __init__(self, ctx) -> None:
        raise RuntimeError("constructor")


JOB = "G28\nG1 X1 (unclosed\nG1 X2\nG1 X3 (unclosed\nM104 S200 S210\n"


def _linter(*extra: type[Rule]) -> Linter:
    linter = Linter(Options(dialect="marlin", select=["SX"]))
    linter.rule_classes = list(linter.rule_classes) + list(extra)
    return linter


def test_a_rule_that_raises_is_named_and_dropped_and_the_others_go_on() -> None:
    result = _linter(_Explodes).check_text(JOB, "job.gcode")
    assert result.error is not None and "\n" not in result.error
    assert result.error.startswith("job.gcode: internal error in rule XX901 (explodes)")
    assert "at line 3" in result.error and "ValueError: bug in a rule" in result.error
    codes = [(f.line, f.code) for f in result.findings]
    # Its finding before the crash is kept; the SX rules ran on every line, before and after the crash.
    assert codes == [(2, "XX901"), (2, "SX005"), (4, "SX005"), (5, "SX002")], codes
    assert result.lines == 5


def test_failures_in_finish_and_in_the_constructor() -> None:
    result = _linter(_ExplodesAtEnd, _ExplodesAtStart).check_text(JOB, "job.gcode")
    assert "XX902 (explodes-at-end)" in result.error and "KeyError" in result.error
    assert "XX903 (explodes-at-start)" in result.error and "RuntimeError: constructor" in result.error
    assert "\n" not in result.error
    assert {f.code for f in result.findings} == {"SX005", "SX002"}


def test_the_same_linter_checks_the_next_file_with_the_rule_again() -> None:
    linter = _linter(_Explodes)
    first = linter.check_text(JOB, "one.gcode")
    second = linter.check_text("G1 X1\n", "two.gcode")
    assert first.error and second.error is None
    assert [f.code for f in second.findings] == ["XX901"]


def test_an_internal_error_outside_the_rules_names_the_file(monkeypatch, tmp_path) -> None:
    def broken(self, cmd, line):  # the interpreter's handler for M104
        raise AssertionError("interpreter bug")

    monkeypatch.setattr(Interpreter, "_set_temp", broken)
    job = tmp_path / "limits.gcode"
    job.write_text("G28\nM104 S200\n")
    result = runner.check_one(str(job), Options(dialect="marlin"))
    assert result.error is not None and "internal error" in result.error and "AssertionError" in result.error
    assert "\n" not in result.error and result.path.endswith("limits.gcode")


@pytest.mark.parametrize("dialect", ["hyrel", "marlin", "linuxcnc"])
def test_a_file_is_freed_when_its_check_is_done(monkeypatch, dialect) -> None:
    # The file's context, rules, state and findings go as soon as the result is out, without a pass of the
    # garbage collector (reference cycles between them once kept each file's findings while the next file
    # was read: +4 MB of peak memory on the Marlin folder under --dialect hyrel).
    import gc
    import weakref

    made = []
    prepare = Linter.prepare
    monkeypatch.setattr(Linter, "prepare", lambda self, source: made.append(prepare(self, source)) or made[-1])
    job = (
        "M83\nG1 X1 Y1 Z.2 E1 F600\nG1 E-1\nG0 X5 E1\nM104 S200\nT1\nG2 X9 Y9 I1 J1\n; gclint: disable=SC006\nG1 X2 ; noqa: SC006\n"
        * 50
    )
    linter = Linter(Options(dialect=dialect, select=["ALL"]))
    gc.collect()
    gc.disable()
    try:
        result = linter.check_text(job, "job.gcode")
        assert result.findings and result.error is None
        ((ctx, _),) = made
        made.clear()
        freed = [weakref.ref(ctx), weakref.ref(ctx.interpreter)]  # (the state has slots, no weak reference)
        del ctx
        assert [ref() is None for ref in freed] == [True, True]
    finally:
        gc.enable()


def _folder(tmp_path: Path) -> Path:
    folder = tmp_path / "jobs"
    folder.mkdir()
    for i in range(6):
        (folder / f"ok{i}.gcode").write_text(f"G28\nG1 X{i} (unclosed\n")
    (folder / "binary.gcode").write_bytes(bytes(range(256)) * 16)
    (folder / "dangling.gcode").symlink_to(folder / "gone.gcode")
    (folder / "script.gcode").write_text("#!/bin/sh\necho not G-code\n")
    (folder / "empty.gcode").write_bytes(b"")
    return folder


@pytest.mark.parametrize("jobs", ["1", "2", "4"])
def test_one_bad_file_does_not_stop_the_others(tmp_path: Path, jobs: str) -> None:
    folder = _folder(tmp_path)
    proc = run_cli("check", "--jobs", jobs, "--format", "json", str(folder))
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "Traceback" not in stderr, stderr
    lines = sorted(line for line in stderr.splitlines() if line.strip())
    assert len(lines) == 3, lines
    assert "binary.gcode" in lines[0] and "dangling.gcode" in lines[1] and "script.gcode" in lines[2]
    findings = json.loads(proc.stdout)
    checked = sorted({Path(f["path"]).name for f in findings})
    assert checked == [f"ok{i}.gcode" for i in range(6)], checked


def test_parallel_and_serial_runs_give_the_same_report(tmp_path: Path) -> None:
    folder = _folder(tmp_path)
    serial = run_cli("check", "--jobs", "1", "--format", "json", str(folder))
    parallel = run_cli("check", "--jobs", "3", "--format", "json", str(folder))
    assert serial.stdout == parallel.stdout
    assert sorted(serial.stderr.splitlines()) == sorted(parallel.stderr.splitlines())
