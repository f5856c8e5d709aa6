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
PARSE_LIMIT = 100_000  # longer lines are refused (SX001) instead of parsed


def parse_line(raw: str) -> ParsedLine:
    """The parse of one line of text (without its line ending)."""
    if len(raw) > PARSE_LIMIT or type(raw) is not str:
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


def code_before_long_comment(raw: str) -> str | None:
    """The commands of a line too long to parse (over ``PARSE_LIMIT``) whose length is one trailing comment
    (``G1 X1 E1 ;cccc...`` or ``G1 X1 (cccc...)``), or None: the translator keeps such a line's command and
    drops only its comment, and the meaning diff runs the command (what a firmware does with it)."""
    cut = min((i for i in (raw.find(";"), raw.find("(")) if i >= 0), default=-1)
    if cut < 0 or cut > 1000:
        return None
    rest = raw[cut:]
    if rest[0] == "(" and not (rest.rstrip().endswith(")") and rest.count(")") == 1):
        return None  # text after the comment: not one trailing comment
    code = raw[:cut].rstrip()
    return code or None


def parse_slow(raw: str) -> ParsedLine:
    """The grammar's parse of ``raw`` (no fast path, no cache)."""
    if len(raw) > PARSE_LIMIT or type(raw) is not str:
        from gclint.syntax.nodes import Issue, Unparsed

        length = getattr(raw, "length", None)  # syntax.source.Overlong: only the line's beginning was kept
        size = f"{length:,} bytes" if length is not None else f"{len(raw):,} characters"
        return ParsedLine(
            extra=(Unparsed(raw, 1),),
            issues=(Issue("SX001", 1, f"line is {size} long; lines over {PARSE_LIMIT:,} characters are not parsed"),),
            kind="error",
        )
    from gclint.syntax.larkparse import parse_with_lark  # imported on first use: most files never need lark

    return parse_with_lark(raw)
