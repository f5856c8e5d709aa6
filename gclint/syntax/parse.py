"""Parse lines: the fast path first, the grammar for everything else, with a cache of recent lines.

``parse_line`` is a pure function of the line's text, so identical lines (about a quarter of a typical
sliced job: retractions, fan and temperature commands, comment banners) share one parse.
"""

from __future__ import annotations

from gclint.syntax.fastpath import parse_fast
from gclint.syntax.nodes import ParsedLine

_CACHE: dict[str, ParsedLine] = {}
_CACHE_LIMIT = 8192
_LARK_LINE_LIMIT = 100_000  # longer lines are refused (SX001) instead of handed to the grammar


def parse_line(raw: str) -> ParsedLine:
    """The parse of one line of text (without its line ending)."""
    parsed = _CACHE.get(raw)
    if parsed is not None:
        return parsed
    parsed = parse_fast(raw)
    if parsed is None:
        parsed = parse_slow(raw)
    if len(_CACHE) >= _CACHE_LIMIT:
        _CACHE.clear()
    _CACHE[raw] = parsed
    return parsed


def parse_slow(raw: str) -> ParsedLine:
    """The grammar's parse of ``raw`` (no fast path, no cache)."""
    if len(raw) > _LARK_LINE_LIMIT:
        from gclint.syntax.nodes import Issue, Unparsed

        return ParsedLine(
            extra=(Unparsed(raw, 1),),
            issues=(
                Issue(
                    "SX001", 1, f"line is {len(raw):,} characters long; lines over {_LARK_LINE_LIMIT:,} are not parsed"
                ),
            ),
            kind="error",
        )
    from gclint.syntax.larkparse import parse_with_lark  # imported on first use: most files never need lark

    return parse_with_lark(raw)
