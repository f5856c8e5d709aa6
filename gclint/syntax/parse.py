"""Parse lines: the fast path first, the grammar for everything else, with a cache of recent lines.

``parse_line`` is a pure function of the line's text, so identical lines (about a quarter of a typical
sliced job: retractions, fan and temperature commands, comment banners) share one parse.
"""

from __future__ import annotations

from gclint.syntax.fastpath import parse_fast
from gclint.syntax.nodes import ParsedLine, Stray

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


def without_blanks(raw: str) -> str:
    """``raw`` with the spaces and tabs outside its comments removed: how a machine that ignores blanks reads a line
    (LinuxCNC: "Spaces and tabs are allowed anywhere on a line of code and do not change the meaning of the line,
    except inside comments. ... The line 'G0X +0. 12 34Y 7' is equivalent to 'G0 x+0.1234 Y7'", G-code overview,
    "Format of a line": https://linuxcnc.org/docs/html/gcode/overview.html#_format_of_a_line)."""
    out = []
    depth = 0
    for i, ch in enumerate(raw):
        if depth == 0 and ch == ";":
            out.append(raw[i:])
            break
        if ch == "(":
            depth = 1
        elif ch == ")" and depth:
            depth = 0
            out.append(ch)
            continue
        if depth or (ch != " " and ch != "\t"):
            out.append(ch)
    return "".join(out)


def read_blanks_ignored(raw: str) -> ParsedLine:
    """The parse of ``raw`` as a machine that ignores blanks reads it (``without_blanks``): the plain parse unless a
    value lost its word letter to a blank (``X 2 0`` is X20), which only a blank can do."""
    parsed = parse_line(raw)
    if not parsed.extra or not any(type(node) is Stray for node in parsed.extra):
        return parsed
    squeezed = parse_line(without_blanks(raw))
    return squeezed if squeezed.kind != "error" else parsed


def canonical_text(parsed: ParsedLine) -> str:
    """One line's text written plainly: block delete, N, each command as its code and words separated by one blank,
    then the comments (what a reader that does not ignore blanks reads the same way)."""
    parts = []
    if parsed.block_delete is not None:
        parts.append("/")
    if parsed.line_number is not None:
        parts.append(parsed.line_number.text.strip())
    for cmd in parsed.commands:
        words = [cmd.code] if cmd.code else []
        words += [w.text.replace(" ", "").replace("\t", "") for w in cmd.words]
        parts.append(" ".join(words))
    parts += [c.text for c in parsed.comments]
    return " ".join(p for p in parts if p)


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
