"""Suppression comments in G-code, read and written in one place: ``; noqa`` / ``; noqa: HY003, SX``
on a line, ``; gclint: disable=HY003`` ... ``; gclint: enable=HY003`` for a range.  The engine reads them
(suppressing findings, never the security rules'), ``check --add-noqa`` and the language server's quick
fix write them."""

from __future__ import annotations

import re
from functools import cache, lru_cache

# "noqa" starts a comment or follows a ";" inside one ("; SAY hi ; noqa: HY029"): a word or a path that merely
# contains it ("SHELL C:\\tools\\noqa.exe") is text, not a suppression.
# After "noqa:" come codes, prefixes or rule names, separated by commas or blanks; the first word that is
# none of these ends the list ("; noqa: DL001 site macro" names DL001).
NOQA = re.compile(r"(?i)(?:^|[;(])[ \t]*+noqa\b(?:[ \t]*:[ \t]*([^;)\r\n]*))?")
DIRECTIVE = re.compile(r"(?i)\bgclint:\s*(disable|enable)\b(?:\s*=\s*([^;)\r\n]*))?")


def may_direct(comment: str) -> bool:
    """Whether a comment may hold a noqa or a gclint directive (most comments do not)."""
    return "noqa" in comment or "NOQA" in comment or "gclint" in comment.lower()


_SELECTOR = re.compile(r"[A-Za-z]{2}\d{0,3}|[A-Za-z][A-Za-z0-9]*(?:-[A-Za-z0-9]+)+")
NO_CODES = "?"  # what a "noqa:" with no code after it gives: it suppresses nothing, and is an error
# Findings a job can never silence itself (noqa, gclint: disable): the security rules.  A hostile job would
# otherwise write "; noqa: SC001" after its own "M792 ; SHELL ...".  They are suppressed only from the
# configuration or the command line (--ignore, per-file-ignores), where the suppression is visible.
INLINE_UNSUPPRESSIBLE = ("SC",)
_COMMENT_START = re.compile(r"[;(]")


MAX_SELECTORS = 200  # distinct codes kept from one noqa or disable (there are fewer rules than that)


def selectors(text: str | None) -> tuple[str, ...]:
    """The codes a ``noqa:`` or ``disable=`` names (``ALL`` for a bare ``noqa``; rule names read as their
    codes), up to the first word that is not one (a reason may follow), each once.  ``(NO_CODES,)`` when
    there is a colon and no code.  A repeated comment gives the same tuple (memory stays flat)."""
    if text is None:
        return ("ALL",)
    return _selectors(text) if len(text) <= 2048 else _read_selectors(text)


@lru_cache(maxsize=4096)
def _selectors(text: str) -> tuple[str, ...]:
    return _read_selectors(text)


def _read_selectors(text: str) -> tuple[str, ...]:
    out: dict[str, None] = {}
    for word in re.split(r"[,\s]+", text.strip()):
        if not word or not _SELECTOR.fullmatch(word):
            break
        out[_NAMES().get(word.lower(), word.upper()) if "-" in word else word.upper()] = None
        if len(out) >= MAX_SELECTORS:
            break
    return tuple(out) if out else (NO_CODES,)


@cache
def _NAMES() -> dict[str, str]:  # noqa: N802 - a constant computed once
    from gclint.rules.base import all_rules

    return {rule.name: code for code, rule in all_rules().items() if rule.name}


def noqa_insertion(text: str, codes: list[str]) -> tuple[int, int, str]:
    """How to suppress ``codes`` on a line of ``text``: (start, end, new text) as 0-based character offsets.
    The codes go first in the line's ``noqa:`` list when it has one (what follows stays as it was), else
    `` ; noqa: CODES`` ends the line (a ``;`` comment runs to the end of the line, so it is read after a
    comment already there)."""
    listed = ", ".join(codes)
    start = _COMMENT_START.search(text)
    if start is not None:
        m = NOQA.search(text, start.start())
        if m is not None and m.group(1):
            return m.start(1), m.start(1), f"{listed}, "
    stripped = text.rstrip()
    if not stripped:
        return len(text), len(text), f"; noqa: {listed}"
    return len(stripped), len(text), f" ; noqa: {listed}"


def text_code(text: str) -> str | None:
    """The code of a line whose comment is what a command says or does (M0, M1, M792 and the codes the
    translator writes as M0: ``M0 ; SAY hello``), or None.  No noqa goes on such a line, whoever writes it
    (``check --add-noqa``, the language server's quick fix): it would change what the printer says or does."""
    from gclint.syntax.parse import parse_line

    texts = _text_codes()
    return next((c.code for c in parse_line(text).commands if c.code in texts), None)


@cache
def _text_codes() -> frozenset[str]:
    from gclint.rules.security import ACTION_CODES, PAUSE_CODES

    return frozenset((*ACTION_CODES, *PAUSE_CODES))


def with_noqa(text: str, codes: list[str]) -> str:
    """``text`` with ``codes`` suppressed (``noqa_insertion`` applied)."""
    start, end, new = noqa_insertion(text, codes)
    return text[:start] + new + text[end:]
