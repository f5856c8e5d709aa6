"""The fast path: parse the commonest line shapes with a few regular expressions.

Real jobs are millions of lines of ``G1 X.. Y.. E..``; the lark parser reads about 30k lines/s, this
path several times that.  It only accepts shapes whose parse it can reproduce exactly and returns None
for anything else, which then goes to the grammar.  ``tests/test_fastpath.py`` checks on generated lines
and on every corpus line that both give the same tree.

Three tiers, cheapest first:

1. blank lines and lines holding only a ``;`` or ``(...)`` comment;
2. the canonical shape: upper-case words separated by whitespace, one G/M/T command (optionally after an
   ``N`` line number), a trailing ``;`` comment.  Parameter words are not built until a rule asks for
   them (``Command.words``).  A free-text code with no text (``M30``, ``M117``) is read here too (a job's
   last line is often ``M30``: reading it no longer loads lark);
3. any sequence of letter-and-number words, upper or lower case, with or without spaces
   (``G0X0Y0S12000M3``, ``g1 x 10``), grouped into commands by ``build.assemble``.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from functools import cache
from operator import itemgetter

from gclint.syntax.build import TEXT_CODES, TextCommand, assemble
from gclint.syntax.nodes import (
    FAST_NUMBER,
    FAST_WORD,
    GCODE,
    NUMBER,
    Command,
    Comment,
    ParsedLine,
    Word,
    normalize_code,
)

# Numbers as nodes.FAST_NUMBER reads them; the canonical pattern also uses possessive quantifiers: it never
# needs to backtrack, and that makes it about 25% faster.
_NUM = FAST_NUMBER
_NUM_P = r"[-+]?+(?:[0-9]{1,30}+(?:\.[0-9]{0,30}+)?+|\.[0-9]{1,30}+)"
_CANON = re.compile(rf"[ \t]*+[A-Z]{_NUM_P}(?:[ \t]++[A-Z]{_NUM_P})*+[ \t]*+")
_GENERAL = re.compile(rf"[ \t]*(?:[A-Za-z][ \t]*{_NUM}[ \t]*)+")
_WORD = FAST_WORD
# A G0/G1 with only plain X Y Z E F words in the order slicers write them (F first or last, not both), no
# comment: the route for lines that need no tree (Linter._run, translate_source).  Same number syntax as
# _CANON.  Groups: 1 the digit of G0/G1, 2 F (first), 3-6 X Y Z E, 7 F (last).
# Runs of blanks are bounded too, so that a plain move is at most a few hundred characters: a longer line
# (or the beginning of a huge one, syntax.source.Overlong) always goes to the parser, which reports it.
_SEP = r"[ \t]{1,64}+"
PLAIN_MOVE = re.compile(
    rf"G([01])(?:{_SEP}F({_NUM_P}))?+(?:{_SEP}X({_NUM_P}))?+(?:{_SEP}Y({_NUM_P}))?+(?:{_SEP}Z({_NUM_P}))?+"
    rf"(?:{_SEP}E({_NUM_P}))?+(?(2)|(?:{_SEP}F({_NUM_P}))?+)[ \t]{{0,64}}+"
)
# Runs of lines the engine may read in bulk (Linter._run, Interpreter.plain_run): from a line start, one
# or more whole lines ended by LF or CR LF, each a G0/G1 with X Y Z E F words (each at most once, in any
# order), a ";" comment of printable ASCII, an empty line or, with arcs, a G2/G3 with X Y Z I J E words in
# that order and F first or last.  Numbers and blanks as in PLAIN_MOVE; no groups (in a repeated group, a group
# keeps its value from the line before).


def _any_order(letters: str, sep: str = _SEP, num: str = _NUM_P) -> str:
    """Words of ``letters``, each at most once, in any order (a tree of the orders: no backtracking)."""

    @cache
    def after(used: str) -> str:
        rest = [letter for letter in letters if letter not in used]
        if not rest:
            return ""
        return f"(?:{sep}(?:" + "|".join(f"{x}{num}{after(used + x)}" for x in rest) + "))?+"

    return after("")


def _in_order(letters: str, sep: str = _SEP, num: str = _NUM_P) -> str:
    return "".join(rf"(?:{sep}{letter}{num})?+" for letter in letters)


_RUN_COMMENT = r";[\t\x20-\x7e]*+"
_PLAIN_WORDS = _in_order("XYZE")
# Runs of exactly the moves PLAIN_MOVE takes, and comments (what gclint.context reads nothing from)
PLAIN_MOVE_RUN = re.compile(
    rf"(?m)^(?:(?:G[01](?:{_SEP}F{_NUM_P}{_PLAIN_WORDS}|{_PLAIN_WORDS}(?:{_SEP}F{_NUM_P})?+)[ \t]{{0,64}}+"
    rf"|{_RUN_COMMENT})\r?\n)++"
)
# The longest line of a run: "G0", seven words of at most 64 blanks, a letter and a 62-character number,
# and 64 trailing blanks.
RUN_LINE_LONGEST = 2 + 7 * (64 + 1 + 62) + 64
# Where lines longer than some length are read one by one (a rule looks at long lines: HY029's 100), runs
# take moves of short words: blanks of 1-2 characters, numbers of at most 15 (6 digits, a point and 7).
_SHORT_SEP = r"[ \t]{1,2}+"
_SHORT_NUM = r"[-+]?+(?:[0-9]{1,6}+(?:\.[0-9]{0,7}+)?+|\.[0-9]{1,7}+)"


# Arcs there: one blank before each word, numbers of at most 11 characters (4 digits, a point and 5)
_ARC_NUM = r"[-+]?+(?:[0-9]{1,4}+(?:\.[0-9]{0,5}+)?+|\.[0-9]{1,5}+)"
_ARC_LINE = 2 + 7 * (1 + 1 + 11) + 2  # ("G2", the words, 2 trailing blanks)


def _short_line(words: int) -> int:
    return 2 + words * (2 + 1 + 15) + 2  # ("G1", the words, 2 trailing blanks)


@cache
def run_pattern(arcs: bool, longest: int | None = None) -> re.Pattern[str] | None:
    """The runs of plain moves, M-codes of plain words (no E: the engine reads the ones a rule or the
    interpreter would look at on their own, gclint.runs.CodeLines) and comments, with arcs or without
    (compiled on first use: it is large); with ``longest``, of lines at most that long but for comments
    (None: no move is surely short enough)."""
    sep, num, trail = _SEP, _NUM_P, r"[ \t]{0,64}+"
    move = "G[01]" + _any_order("XYZEF")
    code = rf"M[0-9]{{1,4}}+(?:{sep}[A-DF-Z]{num}){{0,6}}+"  # (at most RUN_LINE_LONGEST long)
    arc_sep, arc_num = sep, num
    if longest is not None and longest < RUN_LINE_LONGEST:
        if _short_line(5) > longest:
            return None
        sep, num, trail = _SHORT_SEP, _SHORT_NUM, r"[ \t]{0,2}+"
        arc_sep, arc_num = r"[ \t]", _ARC_NUM  # (7 words of a slicer's arc fitting: 95 characters at most)
        arcs = arcs and longest >= _ARC_LINE
        move = "G[01]" + _any_order("XYZEF", sep, num)
        code = rf"M[0-9]{{1,4}}+(?:{sep}[A-DF-Z]{num}){{0,4}}+"  # (shorter than 5 words)
    if arcs:
        xyzije = _in_order("XYZIJE", arc_sep, arc_num)
        arc = rf"G[23](?:{arc_sep}F{arc_num}{xyzije}|{xyzije}(?:{arc_sep}F{arc_num})?+)"
        move = f"(?:{move}|{arc})"
    return re.compile(rf"(?m)^(?:(?:{move}{trail}|{code}{trail}|{_RUN_COMMENT}|)\r?\n)++")


RUN_CODE_LINE = re.compile(r"\nM[^\r\n]*+")  # (the M-code lines of a run, after their line break)


PLAIN_NUMBER = re.compile(_NUM_P)  # (the number after a letter of a plain move)
PLAIN_E = re.compile(rf"(?m)^G[0-3][^E\r\n]*+E({_NUM_P})")  # (the E amounts of the moves of a run)
_RUN_E_LINE = re.compile(rf"\nG[0-3][^E\r\n]*+E({_NUM_P})")  # (the same, each after its line break: faster)
RUN_E = re.compile(r"E([-+.0-9]++)")  # (the same in a run without comments: every E is a word; found faster)


_ARC_START = re.compile(r"\nG[23]")  # (an arc line, from the line break before it)
_next_arc: list = [None, 0, -1]  # (the text asked about last, from where, the start of its next arc line: -1 none)


def has_arcs(text: str, start: int, end: int) -> bool:
    """Whether the run ``text[start:end]`` (from a line start) has an arc.  The next arc of the text asked
    about last is remembered: the runs of a chunk are asked about in order, and most chunks have none."""
    cached, since, at = _next_arc
    if cached is not text or start < since or 0 <= at < start:
        if start == 0 and text.startswith(("G2", "G3")):
            at = 0
        else:
            m = _ARC_START.search(text, start - 1 if start else 0)
            at = -1 if m is None else m.start() + 1
        _next_arc[:] = text, start, at
    return 0 <= at < end


def forget_arcs() -> None:
    """Let go of the text ``has_arcs`` asked about last (gclint.runs, when a file is done: a chunk of it)."""
    _next_arc[:] = None, 0, -1


def run_amounts(text: str, start: int, end: int) -> tuple[re.Pattern[str], int]:
    """How to find the E amounts of the moves and arcs of the run ``text[start:end]`` (group 1 of each match,
    in order): the pattern, and where to search from (up to ``end``)."""
    if text.find(";", start, end) < 0:
        return RUN_E, start
    if start and text[start - 1] == "\n":
        return _RUN_E_LINE, start - 1
    return PLAIN_E, start


# Lines of a run, each pattern written from the line break before the line (a literal start: searched fast;
# run_lines gives the line starts): a G1 with E before any X or Y word (G1 E-0.8 F2100, G1 F2100 E0.8: every
# G1 with E and no X or Y is one); a G0 with E; an arc, an arc with E.
RUN_G1_E_FIRST = re.compile(rf"\nG1(?:{_SEP}[FZ]{_NUM_P})*+{_SEP}E")
RUN_G0_E = re.compile(r"\nG0[^E\r\n]*+E")
RUN_ARC = re.compile(r"\nG[23][^\r\n]*+")  # (an arc of a run: its words are X Y Z I J E F; see has_arcs)
RUN_ARC_E = re.compile(r"\nG[23][^E\r\n]*+E")
# A negative or zero E amount, wherever it is (a comment too: the caller looks at the line)
E_NOT_FORWARD = re.compile(r"E(?:-|\+?+(?=[0.])0*+\.?+0*+(?![0-9]))")


def run_lines(pattern: re.Pattern[str], text: str, start: int, end: int) -> Iterator[tuple[int, re.Match[str]]]:
    """(line start, match) for each line of ``text[start:end]`` (whole lines, from a line start) that
    ``pattern``, written from the line break before a line, finds."""
    if start and text[start - 1] == "\n":
        pos = start - 1
    else:  # (the first line of the text, or of a chunk: no line break before it)
        pos = text.find("\n", start, end)
        if pos < 0:
            pos = end
        m = pattern.match("\n" + text[start : pos + 1])
        if m is not None:
            yield start, m
    for m in pattern.finditer(text, pos, end):
        yield m.start() + 1, m


def run_line_starts(pattern: re.Pattern[str], text: str, start: int, end: int) -> list[int]:
    """The starts of the lines of ``text[start:end]`` that ``pattern`` finds (as ``run_lines``)."""
    if start and text[start - 1] == "\n":
        return [m.start() + 1 for m in pattern.finditer(text, start - 1, end)]
    return [at for at, _ in run_lines(pattern, text, start, end)]


_LINENO_VALUE = re.compile(r"[0-9]+(?:\.[0-9]+)?")
_LETTER_AND_VALUE = itemgetter(0, slice(1, None))  # "X10.5" -> ("X", "10.5"), in C

_BLANK = ParsedLine(kind="blank")
_CODES: dict[str, str] = {}


def _code(token: str) -> str:
    code = _CODES.get(token)
    if code is None:
        if len(_CODES) > 50000:
            _CODES.clear()
        code = _CODES[token] = normalize_code(token[0], token[1:])
    return code


def parse_fast(raw: str) -> ParsedLine | None:
    """Parse ``raw`` if it has one of the fast shapes, else return None."""
    if not raw:
        return _BLANK
    if raw[0] == ";":
        return ParsedLine(comments=(Comment(raw, 1, ";"),), kind="comment")
    semi = raw.find(";")
    body = raw if semi < 0 else raw[:semi]
    # Tier 2 first: the canonical shape is most lines of a job (and excludes blanks, "(", "0x").
    if _CANON.fullmatch(body):
        parsed = _canonical(raw, body, (Comment(raw[semi:], semi + 1, ";"),) if semi >= 0 else ())
        if parsed is not None:
            return parsed
    # Tier 1: blank and comment-only lines.
    stripped = body.strip(" \t")
    if not stripped:
        if semi < 0:
            return _BLANK
        return ParsedLine(comments=(Comment(raw[semi:], semi + 1, ";"),), kind="comment")
    if stripped[0] == "(":
        close = stripped.find(")")
        if close == len(stripped) - 1 and semi < 0:
            column = raw.find("(") + 1
            return ParsedLine(comments=(Comment(stripped, column, "("),), kind="comment")
        return None
    if "0x" in body:
        return None  # maybe a hex value (M708 A0x0b), which only the grammar reads
    comments = (Comment(raw[semi:], semi + 1, ";"),) if semi >= 0 else ()
    # Tier 3: any run of letter-and-number words.
    if _GENERAL.fullmatch(body):
        return _general(raw, body, comments)
    return None


def _canonical(raw: str, body: str, comments: tuple[Comment, ...]) -> ParsedLine | None:
    tokens = body.split()
    first = tokens[0]
    letter = first[0]
    line_number = None
    if letter == "N":
        if not _LINENO_VALUE.fullmatch(first[1:]) or len(tokens) == 1:
            return None
        n_start = raw.find(first)
        line_number = Word("N", first[1:], NUMBER, first, n_start + 1)
        tokens = tokens[1:]
        start = raw.find(tokens[0], n_start + len(first))
        first = tokens[0]
        letter = first[0]
    else:
        start = 0 if raw[0] == letter else raw.find(first)
    if letter != "G" and letter != "M" and letter != "T":
        return None
    code = _CODES.get(first) or _code(first)
    if code in TEXT_CODES:
        if len(tokens) == 1 and first[1:].isdigit():
            # a free-text code alone (M30, M117): no text, as the grammar's text_command reads it
            word = Word(letter, first[1:], NUMBER, first, start + 1)
            return assemble([TextCommand(word, None), *comments], None, line_number)
        return None
    count = len(tokens) - 1
    params = dict(map(_LETTER_AND_VALUE, tokens[1:])) if count else {}
    # Several commands on the line, or a repeated letter: the general tier groups and reports those.
    if len(params) != count or "G" in params or "M" in params or (letter == "T" and "T" in params):
        return None
    command = Command(code, GCODE, start + 1, params, None, None, None, raw, (start, len(body)))
    return ParsedLine((command,), comments, line_number, None, None, (), (), "code")


def _general(raw: str, body: str, comments: tuple[Comment, ...]) -> ParsedLine | None:
    pieces: list = []
    for m in _WORD.finditer(body):
        text = m.group(0)
        value = m.group(2)
        pieces.append(Word(m.group(1).upper(), value, NUMBER, text, m.start() + 1))
    line_number = None
    if pieces and pieces[0].letter == "N" and _LINENO_VALUE.fullmatch(pieces[0].value):
        line_number = pieces.pop(0)
    if pieces and pieces[0].letter == "O":
        return None  # an O-word statement (LinuxCNC), see grammar.lark
    for piece in pieces:
        if piece.letter in "GM" and normalize_code(piece.letter, piece.value) in TEXT_CODES:
            return None
    pieces.extend(comments)
    return assemble(pieces, None, line_number)
