"""Issue 11, fix safety (ruff's principle): a safe fix never changes what a valid line means, a fix that
brings a new finding is taken back, a file that changed since it was checked is not fixed, and --fix
and --diff say what they did."""

from __future__ import annotations

import json
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

import tests.strategies  # noqa: F401  (the hypothesis profiles)
from gclint.engine import Linter, Options
from gclint.fixes import fix_file
from gclint.machine.profiles import PROFILES
from gclint.rules.base import Edit, Finding, Fix, Severity
from tests.conftest import run_cli

# -- generated valid v5 jobs: fixing changes nothing ----------------------------------------------------

_TEMP = st.integers(0, 260).map(str)


@st.composite
def valid_v5_job(draw) -> tuple[str, str]:
    """A job every line of which is valid Hyrel v5 on ``printer`` (addresses from the T_v5 chart)."""
    printer = draw(st.sampled_from(sorted(PROFILES)))
    positions = PROFILES[printer].positions
    heads = draw(st.lists(st.sampled_from(positions), min_size=1, max_size=3, unique=True))
    lines = [f"M6 T{h} O{h + 1} X{draw(st.integers(0, 40))} Y0 Z0" for h in heads]
    lines += ["G21", "G90", "G28 X0 Y0"]
    head = st.sampled_from(heads)
    pieces = st.one_of(
        head.map(lambda h: f"T{h}"),
        st.tuples(head, _TEMP).map(lambda t: f"M104 T{t[0]} S{t[1]}"),
        st.tuples(head, _TEMP).map(lambda t: f"M109 T{t[0]} S{t[1]}"),
        st.tuples(head, _TEMP).map(lambda t: f"M109 T{t[0]} S{t[1]} W0\nM116"),
        st.tuples(head, _TEMP, st.integers(1, 10)).map(lambda t: f"M109 T{t[0]} S{t[1]} R{t[2]}"),
        st.tuples(st.sampled_from(["M140 T24", "M140 T25", "M141 T24", "M141 T25", "M190 T24"]), _TEMP).map(
            lambda t: f"{t[0]} S{t[1]}"
        ),
        st.just("M620 T21 E1\nM621 T21 P50\nM620 T21 E0"),
        st.just("M3 T20 S50\nG4 P1000\nM5 T20"),
        st.tuples(head, st.integers(0, 100)).map(lambda t: f"M106 T{t[0]} S{t[1]}"),
        head.map(lambda h: f"M107 T{h}"),
        st.tuples(st.integers(0, 200), st.integers(0, 200)).map(lambda p: f"G1 X{p[0]} Y{p[1]} E1 F1200"),
        st.sampled_from(["M104 T40 S0", "M140 T46 S0", "M107 T47", "M620 T47 E0"]),
    )
    lines += draw(st.lists(pieces, min_size=1, max_size=25))
    lines.append("M30")
    return printer, "\n".join(lines) + "\n"


@given(valid_v5_job(), st.booleans(), st.booleans())
def test_fix_changes_nothing_in_a_valid_v5_job(tmp_path_factory, job, explicit_dialect, explicit_printer):
    printer, text = job
    path = tmp_path_factory.mktemp("fix") / "job.gcode"
    path.write_text(text)
    options = Options(dialect="hyrel" if explicit_dialect else "auto", printer=printer if explicit_printer else None)
    linter = Linter(options)
    result = linter.check_path(str(path))
    assert result.dialect == "hyrel", result.dialect_reason
    assert not [f for f in result.findings if f.code == "HY008"], [f.message for f in result.findings]
    outcome = fix_file(result, linter, unsafe=False)
    assert outcome.error is None and outcome.fixed == 0
    assert path.read_text() == text


# -- a fix that brings a new finding is taken back ------------------------------------------------------


def _with_fix(result, line: int, start: int, end: int, text: str, code: str = "XX001") -> None:
    result.findings.append(
        Finding(
            result.path,
            line,
            start,
            code,
            Severity.WARNING,
            "made up",
            fix=Fix("test", (Edit(line, start, end, text),)),
        )
    )


def test_a_fix_that_brings_a_new_finding_is_reverted(tmp_path: Path) -> None:
    path = tmp_path / "job.gcode"
    text = "; gclint: dialect=marlin\nG1 X1 Y1 F600\nG1 X2 Y2\nN3 G1 X3*12\n"
    path.write_text(text)
    linter = Linter(Options())
    result = linter.check_path(str(path))
    # one fix that would duplicate a word (SX002), one fix that is good (the checksum)
    _with_fix(result, 2, 8, 10, "X1 X9")
    outcome = fix_file(result, linter, unsafe=True)  # (the checksum fix is unsafe)
    assert outcome.fixed == 1 and len(outcome.reverted) == 1
    assert "XX001 fix not applied" in outcome.reverted[0] and "SX002 would report" in outcome.reverted[0]
    assert path.read_text() == text.replace("*12", "*96")


def test_a_file_changed_since_it_was_checked_is_not_fixed(tmp_path: Path) -> None:
    path = tmp_path / "job.gcode"
    path.write_text("; gclint: dialect=marlin\nN1 G1 X1 Y1*12\n")
    linter = Linter(Options())
    result = linter.check_path(str(path))
    assert result.findings and result.findings[0].fix is not None
    path.write_text("; gclint: dialect=marlin\nN1 G1 X1 Y*12\n")  # "Y1" cut to "Y": same size, new bytes
    outcome = fix_file(result, linter, unsafe=True)
    assert outcome.fixed == 0 and "changed since it was checked" in (outcome.error or "")
    assert path.read_text() == "; gclint: dialect=marlin\nN1 G1 X1 Y*12\n"


def test_no_fix_in_a_file_that_does_not_parse(tmp_path: Path) -> None:
    path = tmp_path / "job.gcode"
    text = "; gclint: dialect=hyrel\nM6 T12 O2\nM109 T12 S200\nG1 X10 Y20 )\n"
    path.write_text(text)
    proc = run_cli("check", "--fix", str(path))
    assert path.read_text() == text and proc.returncode == 1


# -- what --fix and --diff say -------------------------------------------------------------------------

V4_IN_V5 = "; gclint: dialect=hyrel\nM6 T12 O2 X0 Y0 Z0\nM109 T12 S200\nT1\nG1 X10 Y10 E1 F1200\nM30\n"


def test_fix_says_how_many_were_fixed_and_how_many_remain(tmp_path: Path) -> None:
    path = tmp_path / "job.gcode"
    path.write_text(V4_IN_V5.replace("M30\n", "T4\nM30\n"))
    proc = run_cli("check", "--fix", str(path))
    out = proc.stdout.decode()
    # (T4, a fifth slot, makes the job an EHR's (issue 24): no head is loaded there, HY006)
    assert "Found 6 findings (2 fixed, 3 more ended by those fixes, 1 remaining: 1 warning in 1 file)." in out, out
    assert path.read_text().startswith("; gclint: dialect=hyrel\nM6 T1 O2 X0 Y0 Z0\nM109 T1 S200\n")
    path.write_text(V4_IN_V5)
    proc = run_cli("check", "--fix", str(path))
    assert (
        proc.returncode == 0
        and "Found 5 findings (2 fixed, 3 more ended by those fixes, 0 remaining)." in proc.stdout.decode()
    )


def test_diff_shows_the_fixes_and_writes_nothing(tmp_path: Path) -> None:
    path = tmp_path / "job.gcode"
    path.write_text(V4_IN_V5)
    proc = run_cli("check", "--diff", str(path))
    assert proc.returncode == 1 and path.read_text() == V4_IN_V5
    out = proc.stdout.decode()
    assert out.startswith(f"--- {path}\n+++ {path} (fixed)\n@@ -1,6 +1,6 @@\n")
    assert "-M6 T12 O2 X0 Y0 Z0\n+M6 T1 O2 X0 Y0 Z0\n-M109 T12 S200\n+M109 T1 S200\n" in out
    assert "Would fix 2 findings (0 remaining, 3 more would end with them)." in proc.stderr.decode()
    clean = tmp_path / "clean.gcode"
    clean.write_text("; gclint: dialect=marlin\nG1 X1 F100\n")
    proc = run_cli("check", "--diff", str(clean))
    assert proc.returncode == 0 and proc.stdout == b""


def test_a_read_only_job_is_reported_and_left_as_it_is(tmp_path: Path) -> None:
    """Issue 25: --fix renamed a fixed copy over a read-only job (the folder allowed it): now it says so and
    leaves the file, its mode and its findings as they are; --add-noqa too."""
    job = tmp_path / "a.gcode"
    text = "; gclint: dialect=hyrel\nM109 T12 S200\nG1 X1 F600\nM30\n"  # HY008, a safe fix
    job.write_text(text)
    job.chmod(0o444)
    inode = job.stat().st_ino
    for how in ("--fix", "--add-noqa"):
        proc = run_cli("check", "--no-cache", how, str(job))
        assert job.read_text() == text and job.stat().st_ino == inode and job.stat().st_mode & 0o777 == 0o444
        assert b"read-only: not rewritten" in proc.stderr, (how, proc.stderr)
    assert run_cli("check", "--no-cache", "--fix", str(job)).returncode == 1  # the finding is still there


def test_fixable_counts_only_the_fixes_that_fix_applies(tmp_path: Path) -> None:
    # Renumbering v4 T11/T12 (yoke 1 heads when heated, a laser and a spindle as T commands) would leave
    # heads heated that no T command selects (HY065): --fix takes those fixes back, so none is "fixable".
    path = tmp_path / "job.gcode"
    text = "; gclint: dialect=hyrel\nM109 T11 S215\nM109 T12 S215\nT11\nG1 X10 Y10 E1 F1200\nT12\nG1 X20 E1\nM30\n"
    path.write_text(text)
    proc = run_cli("check", "--no-cache", str(path))
    out = proc.stdout.decode()
    assert "HY008 [warning] M109 T11" in out and "[*]" not in out and "fixable with" not in out, out
    proc = run_cli("check", "--no-cache", "-f", "json", str(path))
    fixes = [f["fix"] for f in json.loads(proc.stdout) if f["code"] == "HY008"]
    assert fixes and all(fix["applicability"] == "unsafe" for fix in fixes)
    path.write_text(V4_IN_V5)  # (here the renumbering is kept: still fixable)
    assert "[*] 2 fixable with --fix." in run_cli("check", "--no-cache", str(path)).stdout.decode()


def test_fix_counts_the_findings_a_fix_ends_elsewhere(tmp_path: Path) -> None:
    # M6 T12 and M109 T12 renumbered to T1: HY065, HY006 and HY063 end with them
    path = tmp_path / "job.gcode"
    path.write_text(V4_IN_V5)
    before = run_cli("check", "--no-cache", str(path)).stdout.decode()
    assert "Found 5 findings (5 warnings)" in before, before
    proc = run_cli("check", "--diff", str(path))
    assert "Would fix 2 findings (0 remaining, 3 more would end with them)." in proc.stderr.decode()
    proc = run_cli("check", "--fix", str(path))
    assert "Found 5 findings (2 fixed, 3 more ended by those fixes, 0 remaining)." in proc.stdout.decode()
