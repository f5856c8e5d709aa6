"""The real Hyrel jobs of the corpus (issue "Hyrel rules", done means 2).

All four public Hyrel jobs (../shared/corpus/hyrel/*.gcode, read in place) are written for v4 addressing:
`M6 T12 O2`, `M109 T12 S77`, `M703 T14 S12` with a `T1` tool change (corpus/README.md;
the T_v4 page and the Hyrel v4 firmware source, docs/sources.md).  Checked as v4 they must show no error; checked as v5 every v4 T variable must
get the HY008 warning; and `gclint check --fix --dialect hyrel` on a copy must rewrite them to v5
numbers and nothing else.  The .ini in the folder is a slicer profile, not a job.
"""

from __future__ import annotations

import json
import re
import shutil

import pytest

from gclint.engine import Linter, Options
from gclint.rules.base import Severity

from .conftest import CORPUS, needs_corpus, run_cli

pytestmark = needs_corpus

HYREL = CORPUS / "hyrel"
JOBS = sorted(p.name for p in HYREL.glob("*.gcode")) if HYREL.is_dir() else []

# Error-level findings that are real faults of these jobs when checked as v4: none.  (The v4 jobs do
# have infos: M82 without M229 E1 (HY013), comments that Repetrel truncates at 100 characters (HY029).)
V4_ERRORS: dict[str, set[tuple[int, str]]] = {name: set() for name in JOBS}

# A v4 device address as a T variable of an M-code (yoke 1 T11-T15, T16 aux, yoke 2 T21-T25, T26
# spindle, beds T90-T92, all heads T100), as the Hyrel v4 firmware source lists them (docs/sources.md).
V4_VARIABLE = re.compile(r"^\s*M\d+\b[^;]*?\bT(1[0-6]|2[0-6]|9[0-2]|100)\b")
# The certain v4 -> v5 numbers these jobs use: T12 (yoke 1, position 2) -> T1, T14 (position 4) -> T3.
V4_TO_V5 = {"T12": "T1", "T14": "T3", "S12": "S1"}


def findings(name: str, dialect: str, **options):
    return Linter(Options(dialect=dialect, **options)).check_path(str(HYREL / name)).findings


def test_the_corpus_has_the_four_v4_jobs():
    assert len(JOBS) == 4, JOBS


@pytest.mark.parametrize("name", JOBS)
def test_v4_jobs_have_no_error_as_v4(name):
    errors = {(f.line, f.code) for f in findings(name, "hyrel-v4") if f.severity == Severity.ERROR}
    assert errors == V4_ERRORS[name], [
        (f.line, f.code, f.message) for f in findings(name, "hyrel-v4") if f.severity == Severity.ERROR
    ]


@pytest.mark.parametrize("name", JOBS)
def test_v4_jobs_are_detected_as_v4(name):
    result = Linter(Options(dialect="auto")).check_path(str(HYREL / name))
    assert result.dialect == "hyrel-v4", result.dialect_reason


@pytest.mark.parametrize("name", JOBS)
def test_v4_jobs_checked_as_v5_get_hy008_on_every_v4_variable(name):
    lines = (HYREL / name).read_text(encoding="utf-8").splitlines()
    expected = {number for number, text in enumerate(lines, 1) if V4_VARIABLE.search(text)}
    assert expected, "each job addresses its head with a v4 T variable"
    found = [f for f in findings(name, "hyrel") if f.code == "HY008"]
    assert {f.line for f in found} == expected
    assert all(f.severity == Severity.WARNING and f.fix is not None for f in found)


def test_m703_alias_is_reported_with_both_numbers():
    # "M703 T14 S12": the UV pen in slot 4 answers to head 12 (v4 alias) -> v5 "M703 T3 S1"
    name = "Zmmyslony_Vector_Slicer_GCode__diagonal_1x0.5cm.gcode"
    found = [f for f in findings(name, "hyrel") if f.code == "HY008" and f.line == 45]
    edits = {(e.line, e.start): e.text for e in found[0].fix.edits}
    assert sorted((f.column, edits[(f.line, f.column)]) for f in found) == [(6, "T3"), (10, "S1")]


def test_fix_rewrites_a_copy_to_v5_numbers(tmp_path):
    name = "unidentified_idx23496765178__slot_template_v4.gcode"
    original = (HYREL / name).read_bytes()
    copy = tmp_path / "job.gcode"
    copy.write_bytes(original)
    proc = run_cli("check", "--fix", "--dialect", "hyrel", "--format", "json", str(copy))
    assert proc.returncode in (0, 1), proc.stderr
    fixed = copy.read_bytes()
    assert fixed != original
    old_lines = original.decode("utf-8").split("\n")
    new_lines = fixed.decode("utf-8").split("\n")
    assert len(old_lines) == len(new_lines)
    changed = [(a, b) for a, b in zip(old_lines, new_lines, strict=True) if a != b]
    assert changed, "nothing was rewritten"
    for before, after in changed:
        # only the v4 T variables change, each to its v5 number; everything else stays byte for byte
        words = [w for w in re.split(r"(\s+)", before)]
        expected = "".join(V4_TO_V5.get(w, w) if not before.lstrip().startswith(";") else w for w in words)
        assert after == expected, (before, after)
    assert not any(V4_VARIABLE.search(line) for line in new_lines)
    # the fixed file parses and has no v4 numbering left
    after = Linter(Options(dialect="hyrel")).check_path(str(copy)).findings
    assert not [f for f in after if f.code in ("SX001", "HY008")]
    report = json.loads(proc.stdout)
    assert not [f for f in report if f["code"] == "HY008"]


def test_fix_rewrites_the_m703_alias(tmp_path):
    name = "Zmmyslony_Vector_Slicer_GCode__radial_r_0.5cm.gcode"
    copy = tmp_path / "job.gcode"
    shutil.copyfile(HYREL / name, copy)
    run_cli("check", "--fix", "--dialect", "hyrel", str(copy))
    text = copy.read_text(encoding="utf-8")
    assert "M6 T1 O2 X120.000 Y5.000 Z56.000 \n" in text
    assert "M703 T3 S1 \n" in text
    assert "T12" not in text and "T14" not in text


@pytest.mark.parametrize("select", [None, "HY008"])
def test_fix_never_touches_a_file_that_does_not_parse(tmp_path, select):
    name = "unidentified_idx23519466326__shape1_v4.gcode"
    original = (HYREL / name).read_bytes()  # it has no final newline
    broken = original.replace(b"\nG21 ", b"\nG1 X10 Y20 )\nG21 ", 1)  # SX001: a stray ')' in the header
    assert broken != original
    copy = tmp_path / "broken.gcode"
    copy.write_bytes(broken)
    args = ["check", "--fix", "--dialect", "hyrel", "--format", "json", str(copy)]
    if select:
        args += ["--select", select]  # SX001 not even selected: HY008 itself must not offer the fix
    proc = run_cli(*args)
    assert copy.read_bytes() == broken
    report = json.loads(proc.stdout)
    hy008 = [f for f in report if f["code"] == "HY008"]
    assert hy008 and all("fix" not in f for f in hy008)
