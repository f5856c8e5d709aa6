"""Parse lines: the fast path first, the grammar for everything else, with a cache of recent lines.

``parse_line`` is a pure function of the line's text, so identical lines (about a quarter of a typical
sliced job: retractions, fan and temperature commands, comment banners) share one parse.
"""

from __future__ import annotations

from gclint.syntax.fastpath import parse_fast
from gclint.syntax.nodes import ParsedLine

_CACHE: dict[str, ParsedLine] = {}
_CACHE_LIMIT = 8192
_CACHED_LENGTH = 1024  # longer lines are not remembered (8192 long lines would hold gigabytes)
_LARK_LINE_LIMIT = 100_000  # longer lines are refused (SX001) instead of parsed


def parse_line(raw: str) -> ParsedLine:
    """The parse of one line of text (without its line ending)."""
    if len(raw) > _LARK_LINE_LIMIT or type(raw) is not str:
        # "not parsed": a very long line, or only the beginning of one (syntax.source.Overlong); neither
        # path reads it, so time and memory stay bounded
        return parse_slow(raw)
    parsed = _CACHE.get(raw)
    if parsed is not None:
        return parsed
    parsed = parse_fast(raw)
    if parsed is None:
        parsed = parse_slow(raw)
    if len(raw) <= _CACHED_LENGTH:
        if len(_CACHE) >= _CACHE_LIMIT:
            _CACHE.clear()
        _CACHE[raw] = parsed
    return parsed


def parse_slow(raw: str) -> ParsedLine:
    """The grammar's parse of ``raw`` (no fast path, no cache)."""
    if len(raw) > _LARK_LINE_LIMIT or type(raw) is not str:
        from gclint.syntax.nodes import Issue, Unparsed

        length = getattr(raw, "length", None)  # syntax.source.Overlong: only the line's beginning was kept
        size = f"{length:,} bytes" if length is not None else f"{len(raw):,} characters"
        return ParsedLine(
            extra=(Unparsed(raw, 1),),
            issues=(
                Issue("SX001", 1, f"line is {size} long; lines over {_LARK_LINE_LIMIT:,} characters are not parsed"),
            ),
            kind="error",
        )
    from gclint.syntax.larkparse import parse_with_lark  # imported on first use: most files never need lark

    return parse_with_lark(raw)
