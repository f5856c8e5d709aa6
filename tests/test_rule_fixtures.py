"""Every rule has a fixture pair: tests/fixtures/rules/<CODE>_bad.gcode must produce at least one finding
with that code, <CODE>_good.gcode none.  The rule's own documentation examples are checked the same way.

A fixture may start with "; gclint-test: key=value ..." lines to set options the file cannot set
itself: printer=ehr, loaded=T0,T1, dialect=hyrel-v4, select=..., expect=3 (exact number of findings).
"""

from __future__ import annotations

import re
import textwrap

import pytest

from gclint.config import parse_heads
from gclint.engine import Linter, Options
from gclint.rules.base import all_rules

from .conftest import FIXTURES

RULES = all_rules()
FIXTURE_DIR = FIXTURES / "rules"
_DIRECTIVE = re.compile(r"^;\s*gclint-test:\s*(.*)$", re.MULTILINE)
# Rules reported by other commands than check (translation findings) or on other files than jobs (slicer
# profiles: tests/test_profiles.py checks their examples) have no check fixtures.
NOT_CHECK_RULES = {code for code in RULES if code.startswith(("TR", "PF"))}


def options_from(text: str) -> tuple[Options, int | None]:
    opts = Options(dialect="auto")
    expect = None
    for m in _DIRECTIVE.finditer(text):
        for item in m.group(1).split():
            key, _, value = item.partition("=")
            if key == "printer":
                opts.printer = value
            elif key == "loaded":
                opts.loaded = parse_heads(value)
            elif key == "dialect":
                opts.dialect = value
            elif key == "expect":
                expect = int(value)
            elif key == "select":
                opts.select = value.split(",")
            else:
                raise AssertionError(f"unknown fixture option {key}")
    return opts, expect


def findings_for(text: str, name: str) -> list:
    opts, _ = options_from(text)
    return Linter(opts).check_text(text, name).findings


def test_every_rule_has_a_fixture_pair():
    missing = []
    for code in RULES:
        if code in NOT_CHECK_RULES:
            continue
        for kind in ("bad", "good"):
            if not (FIXTURE_DIR / f"{code}_{kind}.gcode").is_file():
                missing.append(f"{code}_{kind}.gcode")
    assert not missing, f"missing fixtures: {missing}"


def _fixture_cases():
    for path in sorted(FIXTURE_DIR.glob("*_*.gcode")):
        code, _, kind = path.stem.partition("_")
        yield pytest.param(code, kind, path, id=path.stem)


@pytest.mark.parametrize("code,kind,path", list(_fixture_cases()))
def test_fixture(code, kind, path):
    assert code in RULES, f"fixture for unknown rule {code}"
    text = path.read_text(encoding="utf-8", errors="surrogateescape")
    _, expect = options_from(text)
    found = [f for f in findings_for(text, path.name) if f.code == code]
    if kind == "bad":
        assert found, f"{path.name}: expected {code}, got none"
        if expect is not None:
            assert len(found) == expect, [f"{f.line}:{f.message}" for f in found]
    else:
        assert not found, f"{path.name}: unexpected {[(f.line, f.message) for f in found]}"


@pytest.mark.parametrize("code", [c for c in RULES if c not in NOT_CHECK_RULES])
def test_documentation_examples(code):
    rule = RULES[code]
    assert rule.summary and rule.explanation.strip(), f"{code} lacks summary or explanation"
    assert rule.example_bad.strip() and rule.example_good.strip(), f"{code} lacks examples"
    bad = textwrap.dedent(rule.example_bad)
    good = textwrap.dedent(rule.example_good)
    dialect = _example_dialect(rule)
    for text, should in ((bad, True), (good, False)):
        if not _DIRECTIVE.search(text) and "gclint: dialect=" not in text:
            text = f"; gclint-test: dialect={dialect}\n" + text
        found = [f for f in findings_for(text, f"{code}-example") if f.code == code]
        assert (
            bool(found) == should
        ), f"{code} example ({'bad' if should else 'good'}): {[(f.line, f.message) for f in found]}"


def _example_dialect(rule) -> str:
    if rule.dialects:
        return rule.dialects[0]
    if rule.families and "hyrel" in rule.families:
        return "hyrel"
    return "auto"


def test_readme_counts_the_hy_rules():
    from .conftest import ROOT

    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    count = len([code for code in RULES if code.startswith("HY")])
    assert f"({count} rules from the Hyrel pages)" in readme, f"README should say {count} HY rules"
