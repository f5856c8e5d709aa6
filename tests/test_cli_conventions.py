"""Issue 14: the conventions a ruff user expects, through the real command line (statistics, severity in
the text output, a closed pipe, --fix - for editors, --show-fixes, fixable rules marked)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from tests.conftest import ROOT, run_cli

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


def test_unknown_rule_selectors_are_errors_with_a_hint(tmp_path: Path) -> None:
    job = tmp_path / "a.gcode"
    job.write_text(MARLIN)
    proc = run_cli("check", "--select", "HY999", str(job))
    assert proc.returncode == 2 and b"unknown rule code, prefix or name 'HY999' (did you mean" in proc.stderr
    proc = run_cli("check", "--ignore", "duplicate-wrod", str(job))
    assert proc.returncode == 2 and b"did you mean duplicate-word?" in proc.stderr
    # a rule's name works as its code
    assert run_cli("check", "--select", "duplicate-word", "--exit-zero", str(job)).returncode == 0
    (tmp_path / "gclint.toml").write_text('select = ["NOPE"]\n')
    proc = run_cli("check", str(job))
    assert proc.returncode == 2 and b"gclint.toml: 'select': unknown rule code, prefix or name 'NOPE'" in proc.stderr


def test_per_file_ignores_are_relative_to_the_configuration_and_globs_are_rufs(tmp_path: Path) -> None:
    (tmp_path / "calibration" / "deep").mkdir(parents=True)
    for name in ("calibration/a.gcode", "calibration/deep/b.gcode"):
        (tmp_path / name).write_text(MARLIN)
    (tmp_path / "gclint.toml").write_text('per-file-ignores = { "calibration/*.gcode" = ["SX002", "DL001"] }\n')
    elsewhere = tmp_path / "calibration" / "deep"  # run from another folder: patterns stay the config's
    out = json.loads(run_cli("check", "-f", "json", str(tmp_path / "calibration"), cwd=elsewhere).stdout)
    by_file = {Path(f["path"]).name for f in out}
    assert by_file == {"b.gcode"}  # "*" does not cross "/": deep/b.gcode keeps its findings
    (tmp_path / "gclint.toml").write_text('per-file-ignores = { "calibration/**/*.gcode" = ["SX002", "DL001"] }\n')
    out = json.loads(run_cli("check", "-f", "json", str(tmp_path / "calibration"), cwd=elsewhere).stdout)
    assert out == []


def test_exclude_gitignore_and_files_that_are_not_gcode(tmp_path: Path) -> None:
    import subprocess as sp

    sp.run(["git", "init", "-q", str(tmp_path)], check=True)
    for folder in ("jobs", "archive", "build"):
        (tmp_path / folder).mkdir()
    job = "; gclint: dialect=marlin\nG1 X1 X2 F600\n"
    for name in ("jobs/a.gcode", "archive/old.gcode", "build/b.gcode", "jobs/x.tmp.gcode"):
        (tmp_path / name).write_text(job)
    (tmp_path / ".gitignore").write_text("build/\n*.tmp.gcode\n")
    (tmp_path / "jobs" / "Foo.g").write_text("grammar Foo;\nrule: A ;\n")  # an ANTLR grammar
    (tmp_path / "jobs" / "data.nc").write_bytes(b"CDF\x01\x00\x00\x00\x00")  # NetCDF
    (tmp_path / "jobs" / "test.tap").write_text("TAP version 13\n1..2\nok 1 - a\nok 2 - b\n")
    (tmp_path / "gclint.toml").write_text('extend-exclude = ["archive/**"]\n')
    config = ("--config", "gclint.toml")  # (found beside the files, it could not exclude them: issue 25)
    proc = run_cli("check", "-f", "json", *config, ".", cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr  # files that are not G-code are never passed
    found = {(Path(f["path"]).as_posix(), f["code"]) for f in json.loads(proc.stdout)}
    assert {path for path, code in found if not code.startswith("SC")} == {"jobs/a.gcode"}
    # (the security rules read them as a firmware would: "grammar Foo;" is no console command a Carvera has, so
    # nothing is found in them, and they fail the gate as files that are not G-code)
    assert not {(path, code) for path, code in found if path in ("jobs/Foo.g", "jobs/test.tap")}
    err = proc.stderr.decode()
    assert "Foo.g: an ANTLR grammar" in err and "data.nc: NetCDF data" in err and "test.tap: Test Anything" in err
    others = ("--extend-exclude", "jobs/Foo.g,jobs/data.nc,jobs/test.tap")
    assert run_cli("check", "-f", "json", *config, *others, ".", cwd=tmp_path).returncode == 1
    # named on the command line: what is not G-code is an error, an excluded file is checked ...
    assert run_cli("check", "jobs/Foo.g", cwd=tmp_path).returncode == 2
    assert run_cli("check", *config, "archive/old.gcode", cwd=tmp_path).returncode == 1
    # ... unless --force-exclude (pre-commit passes every staged file by name)
    proc = run_cli("check", "--force-exclude", *config, "archive/old.gcode", "build/b.gcode", cwd=tmp_path)
    assert proc.returncode == 0 and b"no files left to check" in proc.stderr
    # .gitignore respected by default, not with --no-respect-gitignore; --exclude replaces the list
    args = ("check", "-f", "json", *config, *others, "--no-respect-gitignore", ".")
    out = json.loads(run_cli(*args, cwd=tmp_path).stdout)
    assert {Path(f["path"]).as_posix() for f in out} == {"jobs/a.gcode", "build/b.gcode", "jobs/x.tmp.gcode"}
    # (the configuration's extend-exclude still applies, as in ruff)
    out = json.loads(
        run_cli("check", "-f", "json", *config, "--exclude", "jobs", "--no-respect-gitignore", ".", cwd=tmp_path).stdout
    )
    assert {Path(f["path"]).as_posix() for f in out} == {"build/b.gcode"}


def test_noqa_unknown_codes_unused_noqa_and_add_noqa(tmp_path: Path) -> None:
    job = tmp_path / "a.gcode"
    job.write_text("; gclint: dialect=marlin\nG1 X1 F100 ; noqa: HY999\n")
    proc = run_cli("check", str(job))
    assert proc.returncode == 2 and b"a.gcode:2: a noqa or disable names an unknown rule code" in proc.stderr
    assert b"did you mean" in proc.stderr
    job.write_text("; gclint: dialect=marlin\nG1 X1 F100 ; noqa: SX002\nG1 X1 X2 ; noqa: SX002\n")
    assert run_cli("check", str(job)).returncode == 0  # unused noqa is opt-in (ruff's RUF100)
    out = run_cli("check", "--extend-select", "SX008", str(job)).stdout.decode()
    assert f"{job}:2:1: SX008 [warning] unused noqa: SX002" in out and ":3:1: SX008" not in out
    # --add-noqa: an archive keeps its findings as they are; security findings stay
    job.write_text("; gclint: dialect=marlin\nG1 X1 X2 F100 ; note\nM9999\nM792 ; SHELL x.exe\n")
    # (M792 is FABlin's too, its XY/AB switch: alone it makes the job FABlin's; Prusa Buddy lacks it, so the line
    # keeps a DL001 beside its SC001)
    proc = run_cli("check", "--add-noqa", "--flavor", "prusa-buddy", str(job))
    # (the comment after M792 is its text on Hyrel: the line goes between disable and enable lines)
    assert job.read_text() == (
        "; gclint: dialect=marlin\nG1 X1 X2 F100 ; note ; noqa: SX002\nM9999 ; noqa: DL001\n"
        "; gclint: disable=DL001\nM792 ; SHELL x.exe\n; gclint: enable=DL001\n"
    )
    assert b"Added a noqa comment to 3 lines." in proc.stdout
    # the security finding cannot be marked by the job: said, with the line and why, and the exit says it
    assert proc.returncode == 1
    assert b":4: SC001 not marked: a job cannot silence its own security findings" in proc.stderr
    assert b"1 finding is still reported (" in proc.stdout and b":5 SC001)" in proc.stdout
    left = json.loads(run_cli("check", "-f", "json", str(job)).stdout)
    assert [f["code"] for f in left] == ["SC001"]


def test_clean_removes_nested_projects_and_all(tmp_path: Path) -> None:
    env = {"XDG_CACHE_HOME": str(tmp_path / "xdg")}
    project = tmp_path / "p"
    (project / "sub").mkdir(parents=True)
    (project / "a.gcode").write_text("G1 X1 X2\n")
    (project / "sub" / "b.gcode").write_text("G1 X1 X2\n")
    (project / "sub" / "gclint.toml").write_text('ignore = ["HY"]\n')  # a project of its own

    def entries() -> int:
        return len(list((tmp_path / "xdg").rglob("*.json")))

    run_cli("check", ".", cwd=project, env=env)
    assert entries() == 2
    proc = run_cli("clean", cwd=project, env=env)
    assert proc.returncode == 0 and entries() == 0, proc.stdout
    run_cli("check", ".", cwd=project, env=env)
    assert b"removed 2 cached results" in run_cli("clean", "--all", cwd=tmp_path, env=env).stdout
    assert entries() == 0


def test_suppression_lists_are_read_once_and_bounded() -> None:
    from gclint.engine import Linter, Options
    from gclint.noqa import MAX_SELECTORS, selectors

    assert selectors(",".join(["HY001"] * 16000)) == ("HY001",)  # each code once
    assert len(selectors(" ".join(f"HY{n:03d}" for n in range(1000)))) == MAX_SELECTORS
    assert selectors("HY001, HY002") is selectors("HY001, HY002")  # a repeated comment: one tuple
    # disable/enable regions: the last directive at or above a line decides, per code
    text = (
        "; gclint: dialect=hyrel\n; gclint: disable=HY003\nM109 T40 S200\n; gclint: enable=HY003\n"
        "M109 T40 S200\n; gclint: disable=HY\nM109 T40 S200\n; gclint: enable=HY003\nM109 T40 S200\nM30\n"
    )
    lines = [f.line for f in Linter(Options()).check_text(text, "j.gcode").findings if f.code == "HY003"]
    assert lines == [5, 9]


def test_a_nested_configuration_keeps_the_security_levels_raised_above_it(tmp_path: Path) -> None:
    (tmp_path / "gclint.toml").write_text('severity = { SC004 = "error" }\n')
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    job = jobs / "a.gcode"
    job.write_text('; gclint: dialect=reprap\nM98 P"x.g"\n')
    assert run_cli("check", "--no-cache", "--fail-on", "error", str(job)).returncode == 1
    # the nearest configuration applies alone, but one added in a sub-folder (a change can add one) does not
    # drop what the project raised for security: SC004 stays an error
    (jobs / ".gclint.toml").write_text('dialect = "reprap"\n')
    assert run_cli("check", "--no-cache", "--fail-on", "error", str(job)).returncode == 1
    (jobs / ".gclint.toml").write_text('severity = { SC004 = "warning" }\n')
    assert run_cli("check", "--no-cache", "--fail-on", "error", str(job)).returncode == 1
    # a configuration named with --config is the user's word
    proc = run_cli("check", "--no-cache", "--fail-on", "error", "--config", str(jobs / ".gclint.toml"), str(job))
    assert proc.returncode == 0, proc.stdout.decode()


def test_add_noqa_leaves_the_text_of_pauses_and_actions_alone(tmp_path: Path) -> None:
    """On Hyrel the comment after M0/M792 is what the printer says or does: a noqa there would change it."""
    job = tmp_path / "a.gcode"
    job.write_text("G28 X0 Y0\nM792 ; FOO bar\nM0 T40 ; SAY hello\nM109 T40 S200\nM30\n")
    proc = run_cli("check", "--add-noqa", str(job))
    assert job.read_text() == (
        "G28 X0 Y0\n; gclint: disable=HY059\nM792 ; FOO bar\n; gclint: enable=HY059\n"
        "; gclint: disable=DL002\nM0 T40 ; SAY hello\n; gclint: enable=DL002\nM109 T40 S200 ; noqa: HY003\nM30\n"
    )
    assert b"Added a noqa comment to 3 lines." in proc.stdout
    assert (
        proc.stderr.count(b"marked by '; gclint: disable=' and 'enable=' lines around it: its comment is the text of")
        == 2
    )
    assert proc.returncode == 0 and run_cli("check", "--no-cache", str(job)).returncode == 0  # the file passes


def test_add_noqa_leaves_the_readme_example_passing(tmp_path: Path) -> None:
    """Issue 28: after --add-noqa the README's own example still exited 1 (HY006 on an M6 line, whose comment
    is the text M6 carries)."""
    job = tmp_path / "hyrel_job.gcode"
    job.write_bytes((ROOT / "examples" / "hyrel_job.gcode").read_bytes())
    assert run_cli("check", "--no-cache", str(job)).returncode == 1
    proc = run_cli("check", "--add-noqa", str(job))
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert b"Added a noqa comment to 5 lines." in proc.stdout
    after = run_cli("check", "--no-cache", str(job))
    assert after.returncode == 0 and b"All checks passed." in after.stdout


def test_notes_about_how_files_were_read_are_one_line_per_run(tmp_path: Path) -> None:
    """Issue 28: a folder run printed one "weak evidence" note per file (20 lines, then a count); now one
    summary line per run names the first few, and -v gives each file's reasons."""
    for n in range(6):
        (tmp_path / f"prog{n}.ngc").write_text("G0 X0\nM2\n")  # machinekit, on weak evidence
    for n in range(4):
        (tmp_path / f"plain{n}.gcode").write_text("G1 X1 Y1 F600\nM30\n")  # nothing says the dialect
    proc = run_cli("check", "--no-cache", "--jobs", "1", str(tmp_path))
    notes = [line for line in proc.stderr.decode().splitlines() if line.startswith("gclint: note:")]
    assert len(notes) == 2, notes
    assert "6 files were read on weak evidence (machinekit 6: " in notes[0] and "and 3 more); -v gives" in notes[0]
    assert "nothing in 4 files tells the dialect" in notes[1]
    verbose = run_cli("check", "--no-cache", "--jobs", "1", "-v", str(tmp_path)).stderr.decode()
    assert verbose.count("checked as machinekit") == 6 and verbose.count("checked as hyrel") == 4
    assert run_cli("check", "--no-cache", "-q", str(tmp_path)).stderr == b""


def test_fail_on_is_the_same_in_every_entry_point(tmp_path: Path) -> None:
    """Issue 28: `check --fail-on never` was refused while postprocess and the Action took it, and the
    Action failed on errors only while check (and so the pre-commit hook) failed on warnings."""
    import re

    from gclint.cli.app import DEFAULT_FAIL_ON, FAIL_ON_LEVELS

    assert DEFAULT_FAIL_ON == "warning" and FAIL_ON_LEVELS == ("error", "warning", "info", "never")
    action = (ROOT / "action.yml").read_text(encoding="utf-8")
    default = re.search(r"\n  fail-on:\n    description: [^\n]*\n    default: (\w+)\n", action)
    assert default and default.group(1) == DEFAULT_FAIL_ON
    assert "error|warning|info|never)" in action  # the values the action takes before passing them to check
    hooks = (ROOT / ".pre-commit-hooks.yaml").read_text(encoding="utf-8").splitlines()
    entries = [line for line in hooks if line.startswith(("  entry:", "  args:"))]
    assert entries and all("--fail-on" not in line for line in entries)  # the hooks run check's default
    assert all(line.startswith("  entry: gclint check ") for line in entries if "entry" in line)
    job = tmp_path / "a.gcode"
    job.write_text("; gclint: dialect=marlin\nG28\nM9999\nG1 X1 Y1 F100\n")  # DL001, a warning
    for command in (["check", "--no-cache"], ["postprocess", "--no-report"]):
        assert run_cli(*command, str(job)).returncode == 1, command  # the default: warning
        for level, code in (("error", 0), ("warning", 1), ("info", 1), ("never", 0)):
            assert run_cli(*command, "--fail-on", level, str(job)).returncode == code, (command, level)
    job.write_text("; gclint: dialect=marlin\nG28\nG1 X1 X2 Y1 F100\n")  # SX002, an error
    assert run_cli("check", "--no-cache", "--fail-on", "never", str(job)).returncode == 0
