"""Issue 24: what a dialect's word means is decided in one place, ``gclint/dialects/`` (its ``Semantics``, its tables).

No code outside that package tests a dialect's name or family: an AST scan of every module finds comparisons
(``==``, ``!=``, ``in``, ``not in``) whose operand is a dialect's name as a string (``"marlin"``, or a tuple of
them) or a ``.family`` attribute, and any other read of ``.family``.  A registry keyed by name (a dict literal)
is allowed: it is data, looked up, not a test.
"""

from __future__ import annotations

import ast
from pathlib import Path

from gclint import dialects

PACKAGE = Path(__file__).resolve().parent.parent / "gclint"
NAMES = frozenset(name for name in dialects.names()) | {d.family for d in dialects.all_dialects()}


def _is_name_literal(node: ast.AST) -> bool:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value.lower() in NAMES
    if isinstance(node, ast.Tuple | ast.List | ast.Set):
        return any(_is_name_literal(element) for element in node.elts)
    return False


def _offences(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(), str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Compare):
            operands = [node.left, *node.comparators]
            if any(_is_name_literal(o) for o in operands):
                found.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno}: compares with a dialect's name")
        if isinstance(node, ast.Attribute) and node.attr == "family":
            found.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno}: reads a dialect's family")
    return found


def test_no_dialect_name_or_family_test_outside_the_dialects_package() -> None:
    offences = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if PACKAGE / "dialects" in path.parents:
            continue
        offences += _offences(path)
    assert not offences, "\n".join(offences)


def test_the_scan_finds_what_it_looks_for(tmp_path: Path) -> None:
    sample = tmp_path / "sample.py"
    sample.write_text(
        "if d.name == 'marlin': pass\nif x in ('linuxcnc', 'smoothie'): pass\nif d.family: pass\n"
        "TABLE = {'marlin': 1}\nif mode == 'auto': pass\n"
    )
    assert len(_offences_at(sample)) == 3


def _offences_at(path: Path) -> list[str]:
    global PACKAGE
    saved, PACKAGE = PACKAGE, path.parent  # (relative paths in the messages)
    try:
        return _offences(path)
    finally:
        PACKAGE = saved
