"""Snapshots of every bad fixture: its findings (every rule's, with line, column, severity, message and fix),
and for a rule with a fix, the fixture as ``gclint check --fix --unsafe-fixes`` leaves it.

tests/test_rule_fixtures.py says that a bad fixture triggers its rule; these pin *what* it reports, so that a
change of message, position, severity or fix shows in review as a change of a file under
tests/fixtures/snapshots/:

* ``<CODE>_bad.json``: the findings of tests/fixtures/rules/<CODE>_bad.gcode;
* ``<CODE>_bad.fixed.gcode``: that fixture with every fix applied (rules with ``fixable = True`` whose bad
  fixture has a finding with a fix), and ``<CODE>_bad.reverted.txt``: the fixes gclint took back, and why,
  when it took any back (a fix after which another rule reports something new is not applied).

A snapshot is compared, never written, unless ``GCLINT_UPDATE_SNAPSHOTS=1`` is set: then the missing or
different ones are written (and the test passes), e.g. after adding a rule or rewording a message::

    GCLINT_UPDATE_SNAPSHOTS=1 .venv/bin/python -m pytest -q -n0 tests/test_rule_snapshots.py -k HY068

then read the diff (``git diff tests/fixtures/snapshots``) before committing it.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest

from gclint.engine import Linter
from gclint.fixes import fix_file
from gclint.rules.base import all_rules

from .conftest import FIXTURES
from .test_rule_fixtures import options_from

RULE_FIXTURES = FIXTURES / "rules"
SNAPSHOTS = FIXTURES / "snapshots"
UPDATE = os.environ.get("GCLINT_UPDATE_SNAPSHOTS") == "1"
HOW = "GCLINT_UPDATE_SNAPSHOTS=1 .venv/bin/python -m pytest -q -n0 tests/test_rule_snapshots.py -k {}"
BAD = sorted(RULE_FIXTURES.glob("*_bad.gcode"))


def _read(path: Path) -> str:
    return path.read_text(encoding="utf-8", errors="surrogateescape")


def findings_snapshot(path: Path) -> str:
    """The findings of a fixture as the snapshot file holds them (JSON, one finding a line, ending in a newline)."""
    text = _read(path)
    opts, _ = options_from(text)
    findings = Linter(opts).check_text(text, path.name).findings
    rows = []
    for f in findings:
        row = f.to_dict()
        del row["path"]
        rows.append(json.dumps(row, ensure_ascii=False, sort_keys=True))
    return "[\n" + ",\n".join(f"  {r}" for r in rows) + ("\n" if rows else "") + "]\n"


def fixed_snapshot(path: Path, tmp: Path) -> tuple[str, str] | None:
    """The fixture after ``check --fix --unsafe-fixes`` (on a copy), and the fixes taken back, one a line (a fix
    after which another rule would report something is not applied: gclint/fixes.py); None when no finding of
    the fixture's rule offers a fix."""
    code = path.stem.split("_")[0]
    copy = tmp / path.name
    shutil.copyfile(path, copy)
    opts, _ = options_from(_read(path))
    linter = Linter(opts)
    result = linter.check_path(str(copy))
    if not any(f.code == code and f.fix is not None for f in result.findings):
        return None
    outcome = fix_file(result, linter, unsafe=True, write=True)
    assert outcome.error is None, outcome.error
    reverted = "".join(line.replace(str(copy), path.name) + "\n" for line in outcome.reverted)
    return _read(copy), reverted


def _compare(snapshot: Path, actual: str, code: str, optional: bool = False) -> None:
    """``actual`` against the snapshot file (``optional``: no file stands for the empty text)."""
    if optional and not actual:
        if UPDATE and snapshot.is_file():
            snapshot.unlink()
        assert UPDATE or not snapshot.is_file(), f"{snapshot.name}: pinned, but nothing is reverted now"
        return
    if UPDATE:
        if not snapshot.is_file() or _read(snapshot) != actual:
            snapshot.parent.mkdir(parents=True, exist_ok=True)
            snapshot.write_text(actual, encoding="utf-8", errors="surrogateescape")
        return
    assert (
        snapshot.is_file()
    ), f"no snapshot {snapshot.relative_to(FIXTURES.parent.parent)}: write it with\n  {HOW.format(code)}"
    assert actual == _read(snapshot), (
        f"{snapshot.name} differs from what gclint reports now.  If the change is meant, rewrite it with\n"
        f"  {HOW.format(code)}\nand commit the diff; else the change is a regression."
    )


@pytest.mark.parametrize("path", BAD, ids=lambda p: p.stem)
def test_findings_of_each_bad_fixture_are_pinned(path: Path) -> None:
    code = path.stem.split("_")[0]
    _compare(SNAPSHOTS / f"{path.stem}.json", findings_snapshot(path), code)


FIXABLE = [p for p in BAD if getattr(all_rules().get(p.stem.split("_")[0]), "fixable", False)]


@pytest.mark.parametrize("path", FIXABLE, ids=lambda p: p.stem)
def test_each_fixable_bad_fixture_has_its_expected_fix(path: Path, tmp_path: Path) -> None:
    code = path.stem.split("_")[0]
    got = fixed_snapshot(path, tmp_path)
    if got is None:
        pytest.skip(f"{path.name}: no {code} finding here offers a fix (the rule fixes only some cases)")
    fixed, reverted = got
    assert fixed != _read(path) or reverted, f"{path.name}: {code} offers a fix, but the fixture is unchanged"
    _compare(SNAPSHOTS / f"{path.stem}.fixed.gcode", fixed, code)
    # the fixes taken back, and why: pinned too (no file when none is)
    _compare(SNAPSHOTS / f"{path.stem}.reverted.txt", reverted, code, optional=True)


def test_no_snapshot_is_left_without_its_fixture() -> None:
    stems = {p.stem for p in BAD}
    fixable = {p.stem for p in FIXABLE}
    stale = []
    for snapshot in sorted(SNAPSHOTS.glob("*")) if SNAPSHOTS.is_dir() else []:
        stem, _, kind = snapshot.name.partition(".")
        if stem not in stems or (kind != "json" and stem not in fixable):
            stale.append(snapshot.name)
    if UPDATE:
        for name in stale:
            (SNAPSHOTS / name).unlink()
        return
    assert not stale, f"snapshots of fixtures (or fixes) that no longer exist: {stale} (delete them)"
