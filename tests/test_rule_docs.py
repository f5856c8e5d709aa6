"""Every rule is documented: its summary, explanation, examples and source are written (no placeholder left
by scripts/add_rule.py), its messages say something, and the HY catalogue (docs/hy-rules.md) lists it.

docs/rules.md is generated from the same fields (tests/test_reports.py checks it is up to date); the
examples are checked as fixtures by tests/test_rule_fixtures.py.
"""

from __future__ import annotations

import re

import pytest

from gclint.rules.base import all_rules

from .conftest import FIXTURES, ROOT
from .test_rule_fixtures import NOT_CHECK_RULES, findings_for

RULES = all_rules()
PLACEHOLDER = re.compile(r"\bTODO\b")
FIELDS = ("summary", "explanation", "example_bad", "example_good", "source")


@pytest.mark.parametrize("code", sorted(RULES))
def test_every_rule_is_documented(code: str) -> None:
    rule = RULES[code]
    for field in FIELDS:
        value = getattr(rule, field, "") or ""
        assert value.strip(), f"{code}: {field} is empty (CONTRIBUTING.md, 'Adding a rule')"
        assert not PLACEHOLDER.search(value), f"{code}: {field} still holds a placeholder: {value.strip()[:120]!r}"
    assert len(rule.explanation.split()) >= 8, f"{code}: the explanation says too little to act on"
    assert re.fullmatch(r"[a-z][a-z0-9]*(-[a-z0-9]+)*", rule.name), f"{code}: name {rule.name!r} is not kebab-case"


def test_rule_names_are_unique() -> None:
    names: dict[str, str] = {}
    for code, rule in sorted(RULES.items()):
        assert rule.name not in names, f"{code} and {names[rule.name]} are both named {rule.name!r}"
        names[rule.name] = code


@pytest.mark.parametrize("code", sorted(c for c in RULES if c not in NOT_CHECK_RULES))
def test_fixtures_and_messages_hold_no_placeholder(code: str) -> None:
    for kind in ("bad", "good"):
        path = FIXTURES / "rules" / f"{code}_{kind}.gcode"
        if path.is_file():
            text = path.read_text(encoding="utf-8", errors="surrogateescape")
            assert not PLACEHOLDER.search(text), f"{path.name}: a placeholder is left (write the real case)"
    path = FIXTURES / "rules" / f"{code}_bad.gcode"
    if path.is_file():
        text = path.read_text(encoding="utf-8", errors="surrogateescape")
        for f in findings_for(text, path.name):
            if f.code == code:
                assert not PLACEHOLDER.search(f.message), f"{code}: its message is a placeholder: {f.message!r}"


def test_the_hy_catalogue_lists_every_hy_rule() -> None:
    table = (ROOT / "docs" / "hy-rules.md").read_text(encoding="utf-8")
    rows = {m.group(1): m.group(0) for m in re.finditer(r"^\| (HY\d{3}) \|.*$", table, re.MULTILINE)}
    codes = sorted(c for c in RULES if c.startswith("HY"))
    assert [c for c in codes if c not in rows] == [], "docs/hy-rules.md lacks these HY rules"
    assert [c for c in rows if c not in RULES] == [], "docs/hy-rules.md lists rules that do not exist"
    for code in codes:
        assert f"| {RULES[code].name} |" in rows[code], f"docs/hy-rules.md: {code} is not named {RULES[code].name}"
        assert not PLACEHOLDER.search(rows[code]), f"docs/hy-rules.md: {code}'s row still holds a placeholder"
