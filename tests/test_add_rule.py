"""scripts/add_rule.py, the rule scaffold (CONTRIBUTING.md, "Adding a rule"), run into a temporary copy of the
checkout: what it writes passes the project's rule tests where it should (the rule registers, its fixtures
and its own test pass, ruff is clean) and fails them where a contributor still has work to do (the
placeholder documentation, the HY catalogue row), so that the tests, not a reviewer, catch a scaffold left
as it was.  Refusals (a malformed, taken or translation code, a taken name) are checked in process.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from .conftest import ROOT

_spec = importlib.util.spec_from_file_location("add_rule", ROOT / "scripts" / "add_rule.py")
add_rule = importlib.util.module_from_spec(_spec)  # type: ignore[arg-type]
sys.modules["add_rule"] = add_rule  # (its dataclasses look their module up)
_spec.loader.exec_module(add_rule)  # type: ignore[union-attr]

COPIED = ("gclint", "tests", "scripts", "docs", "README.md", "pyproject.toml")


@pytest.fixture(scope="module")
def checkout(tmp_path_factory) -> Path:
    """A copy of the parts of the checkout the rule tests read (no .git, no virtualenv, no caches)."""
    root = tmp_path_factory.mktemp("checkout")
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", ".pytest_cache", "snapshots-*")
    for name in COPIED:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, root / name, ignore=ignore)
        else:
            shutil.copy2(src, root / name)
    return root


def _pytest(root: Path, *args: str) -> subprocess.CompletedProcess:
    """pytest in the copy, on the copy's gclint (not the one installed from this checkout)."""
    env = {**os.environ, "PYTHONPATH": str(root), "GCLINT_UPDATE_SNAPSHOTS": ""}
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-n0", "-p", "no:cacheprovider", "--no-header", *args],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )


def test_the_scaffold_writes_a_rule_the_tests_run_and_flag_until_it_is_written(checkout: Path) -> None:
    rc = add_rule.main(
        [
            "HY990",
            "--name",
            "scaffold-check",
            "--summary",
            "A scaffolded rule",
            "--codes",
            "M104",
            "--root",
            str(checkout),
        ]
    )
    assert rc == 0
    for path in (
        "tests/fixtures/rules/HY990_bad.gcode",
        "tests/fixtures/rules/HY990_good.gcode",
        "tests/test_rule_hy990.py",
    ):
        assert (checkout / path).is_file(), path
    module = checkout / "gclint" / "rules" / "hyrel" / "temperature.py"  # (the module whose rules hear M104)
    assert 'code = "HY990"' in module.read_text(encoding="utf-8")
    assert "| HY990 | scaffold-check |" in (checkout / "docs" / "hy-rules.md").read_text(encoding="utf-8")
    lint = subprocess.run(
        [
            sys.executable,
            "-m",
            "ruff",
            "check",
            "--no-cache",
            str(module),
            str(checkout / "tests" / "test_rule_hy990.py"),
        ],
        capture_output=True,
        text=True,
    )
    if "No module named ruff" not in lint.stderr:
        assert lint.returncode == 0, lint.stdout + lint.stderr

    # what the scaffold gets right passes: the rule registers, reports its bad fixture and example, not its good
    # ones, and its own test passes; the README count agrees
    done = _pytest(
        checkout,
        "tests/test_rule_hy990.py",
        "tests/test_rule_fixtures.py",
        "-k",
        "HY990 or hy990 or every_rule_has_a_fixture_pair or count",
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-2000:]
    assert " passed" in done.stdout and "HY990" not in done.stdout.split("short test summary")[-1]

    # what is left to the contributor fails, naming the rule: placeholder documentation, message and fixture,
    # the catalogue's row, the rules reference, the missing snapshot
    todo = _pytest(
        checkout,
        "tests/test_rule_docs.py",
        "tests/test_rule_snapshots.py",
        "tests/test_reports.py::test_rules_reference_is_up_to_date",
        "-k",
        "HY990 or catalogue or rules_reference",
    )
    assert todo.returncode == 1, todo.stdout[-3000:]
    failed = [line for line in todo.stdout.splitlines() if line.startswith("FAILED")]
    for test in (
        "test_every_rule_is_documented[HY990]",
        "test_fixtures_and_messages_hold_no_placeholder[HY990]",
        "test_the_hy_catalogue_lists_every_hy_rule",
        "test_findings_of_each_bad_fixture_are_pinned[HY990_bad]",
        "test_rules_reference_is_up_to_date",
    ):
        assert any(test in line for line in failed), (test, failed)


def test_a_rule_that_listens_to_moves_gets_a_trigger_letter(tmp_path: Path) -> None:
    p = add_rule.Plan(
        code="HY991",
        name="move-check",
        summary="x",
        severity="warning",
        codes=("G1",),
        families=("hyrel",),
        family=add_rule.FAMILIES["HY"],
        module=tmp_path / "m.py",
        new_module=True,
        example_dialect="hyrel",
    )
    text = add_rule.new_module_text(p)
    assert "def trigger_letters" in text and 'frozenset("H")' in text
    compile(text, "m.py", "exec")


@pytest.mark.parametrize(
    "argv,why",
    [
        (["hy68", "--name", "a-b", "--summary", "x"], "is not a rule code"),
        (["TR050", "--name", "a-b", "--summary", "x"], "translation findings"),
        (["HY001", "--name", "a-b", "--summary", "x"], "is already used"),
        (["HY990", "--name", "m229-e1-d0", "--summary", "x"], "already used"),
        (["HY990", "--name", "Not_Kebab", "--summary", "x"], "is not a rule name"),
        (["HY990", "--name", "a-b", "--summary", "x", "--codes", "X1"], "is not a command code"),
        (["HY990", "--name", "a-b", "--summary", "x", "--family", "nosuch"], "unknown dialect family"),
    ],
)
def test_refusals_say_why_and_write_nothing(argv, why, capsys) -> None:
    before = sorted((ROOT / "tests" / "fixtures" / "rules").iterdir())
    assert add_rule.main([*argv, "--root", str(ROOT)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("add_rule.py: ") and why in err and err.count("\n") == 1, err
    assert sorted((ROOT / "tests" / "fixtures" / "rules").iterdir()) == before
