"""The grammar's parse tables ship with the package (gclint/grammar.tables, ``python -m
gclint.syntax.larkparse``): they must be those of the current grammar, and parse as the grammar does."""

from __future__ import annotations

import lark
import pytest
from hypothesis import given, settings

from gclint.syntax import larkparse
from tests.strategies import any_line

LINES = [
    "G1 X1 Y2 ; move",
    "M117 Hello (world)",
    "EXCLUDE_OBJECT_DEFINE NAME=part_1 CENTER=1,2",
    'M587 S"net" P"pass"',
    "o100 sub",
    "#1 = [2 * 3]",
    "G1 X{var.x} Y[#1]",
    "if move.axes[0].homed",
    "N10 G1 X1*87",
    "G1 X1 (unclosed",
    "M84 X Y E",
    "%",
    "/G1 X1",
    "",
]


def _outcome(parser: lark.Lark, line: str) -> str:
    try:
        return parser.parse(line).pretty()
    except lark.exceptions.UnexpectedInput as exc:
        return f"{type(exc).__name__} at {exc.column}"


@pytest.fixture(scope="module")
def built() -> lark.Lark:
    return lark.Lark(larkparse.GRAMMAR_PATH.read_text(encoding="utf-8"), **larkparse._OPTIONS)


def test_the_tables_are_those_of_the_grammar():
    grammar = larkparse.GRAMMAR_PATH.read_text(encoding="utf-8")
    first = larkparse.TABLES_PATH.read_bytes().split(b"\n", 1)[0] + b"\n"
    if f"lark {lark.__version__}," not in first.decode():
        pytest.skip(f"the tables were made by another lark ({first.decode().strip()}): the grammar is built")
    assert first == larkparse.tables_key(grammar), "grammar changed: run python -m gclint.syntax.larkparse"


def test_the_tables_are_used():
    larkparse.parser.cache_clear()
    try:
        parser = larkparse.parser()
    finally:
        larkparse.parser.cache_clear()
    # (a built parser keeps the grammar's source text; one loaded from tables does not)
    if larkparse.TABLES_PATH.read_bytes().startswith(
        larkparse.tables_key(larkparse.GRAMMAR_PATH.read_text(encoding="utf-8"))
    ):
        assert not hasattr(parser, "source_grammar")


def test_the_tables_parse_as_the_grammar(built):
    loaded = larkparse.parser()
    for line in LINES:
        assert _outcome(loaded, line) == _outcome(built, line), line


@settings(max_examples=300)
@given(any_line())
def test_the_tables_parse_generated_lines_as_the_grammar(built, line):
    assert _outcome(larkparse.parser(), line) == _outcome(built, line)
