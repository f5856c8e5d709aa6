"""Path patterns, matched in time bounded by the name's length times the pattern's, whatever they hold.

Two readings share one matcher:

* ruff's globs (``exclude``, ``extend-exclude``, ``per-file-ignores``), relative to the folder of the
  configuration file that names them: ``*`` and ``?`` stay within one folder, ``**`` as a whole part of
  the path crosses folders, ``[...]`` is a character class; a pattern with no ``/`` also matches a file's
  name alone (``*.nc``, ``calibration.gcode``);
* ``.gitignore`` lines (``gclint.gitignore``), which are git's wildmatch with the same pieces.

A pattern is cut at ``/`` into parts, and a path into folders.  Within a part, ``*`` is matched the way
git's and most shells' simple matchers do it: on a mismatch, go back to the last ``*`` only and let it take
one more character, which is correct when there is one kind of star and never backtracks further.  The
same is done one level up with ``**`` parts over the path's folders.  A regular expression built from
such a pattern (what ``pathspec`` and the former ``compile_glob`` made) backtracks exponentially:
``*a*a*a*a*a*a*a*a*a*a*a*ac`` against a 40-character ``aaaa....gcode`` took minutes.

``**`` inside a part (``a**b``) is read as ``*``, as git does.  A pattern ending in ``/**`` matches what
is inside the folder, not the folder itself.  A backslash takes the next character as it is.  Patterns
are checked when the configuration is read (``check``): a reversed range ``[z-a]``, an unclosed ``[`` or
an unknown ``[:class:]`` is one error line.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from functools import lru_cache


class GlobError(ValueError):
    """A pattern that cannot be read; the message says what is wrong with it (one line)."""


# The POSIX classes git's wildmatch knows, as tests on one character.
_POSIX = {
    "alnum": str.isalnum,
    "alpha": str.isalpha,
    "blank": lambda c: c in " \t",
    "cntrl": lambda c: ord(c) < 32 or ord(c) == 127,
    "digit": lambda c: "0" <= c <= "9",
    "graph": lambda c: c.isprintable() and not c.isspace(),
    "lower": str.islower,
    "print": str.isprintable,
    "punct": lambda c: c.isprintable() and not c.isalnum() and not c.isspace(),
    "space": str.isspace,
    "upper": str.isupper,
    "xdigit": lambda c: c in "0123456789abcdefABCDEF",
}


@dataclass(frozen=True)
class _Class:
    """``[...]``: single characters, ranges and POSIX classes, perhaps negated."""

    chars: frozenset[str]
    ranges: tuple[tuple[str, str], ...]
    classes: tuple[str, ...]
    negated: bool

    def __call__(self, c: str) -> bool:
        hit = c in self.chars or any(lo <= c <= hi for lo, hi in self.ranges)
        hit = hit or any(_POSIX[name](c) for name in self.classes)
        return hit != self.negated


_STAR = object()  # a token: any run of characters within a part
_ANY = object()  # a token: one character (a literal character is a token too, as a one-character str)


def _read_class(text: str, i: int) -> tuple[_Class, int]:
    """The class starting at ``text[i] == "["``, and the index after its ``]``."""
    j = i + 1
    negated = j < len(text) and text[j] in "!^"
    if negated:
        j += 1
    chars: set[str] = set()
    ranges: list[tuple[str, str]] = []
    classes: list[str] = []
    first = True
    while True:
        if j >= len(text):
            raise GlobError("'[' is not closed by ']'")
        c = text[j]
        if c == "]" and not first:
            return _Class(frozenset(chars), tuple(ranges), tuple(classes), negated), j + 1
        first = False
        if c == "[" and text.startswith("[:", j):
            end = text.find(":]", j + 2)
            if end < 0:
                raise GlobError("'[:' is not closed by ':]'")
            name = text[j + 2 : end]
            if name not in _POSIX:
                raise GlobError(f"unknown character class [:{name}:] (known: {', '.join(sorted(_POSIX))})")
            classes.append(name)
            j = end + 2
            continue
        if c == "\\":
            j += 1
            if j >= len(text):
                raise GlobError("'[' is not closed by ']'")
            c = text[j]
        if j + 2 < len(text) and text[j + 1] == "-" and text[j + 2] != "]":
            k = j + 2
            hi = text[k]
            if hi == "\\":
                k += 1
                if k >= len(text):
                    raise GlobError("'[' is not closed by ']'")
                hi = text[k]
            if hi < c:
                raise GlobError(f"the range {c}-{hi} is reversed (write {hi}-{c})")
            ranges.append((c, hi))
            j = k + 1
            continue
        chars.add(c)
        j += 1


class Part:
    """One part of a pattern (between ``/``): literal characters, ``?``, classes and ``*``."""

    __slots__ = ("tokens", "literal", "suffix", "prefix", "segments", "lead", "tail", "least")

    def __init__(self, text: str) -> None:
        tokens: list = []
        i = 0
        while i < len(text):
            c = text[i]
            if c == "*":
                while i < len(text) and text[i] == "*":  # "**" within a part is "*"
                    i += 1
                tokens.append(_STAR)
                continue
            if c == "?":
                tokens.append(_ANY)
            elif c == "[":
                cls, i = _read_class(text, i)
                tokens.append(cls)
                continue
            elif c == "\\":
                i += 1
                if i >= len(text):
                    raise GlobError("it ends with a lone backslash")
                tokens.append(text[i])
            else:
                tokens.append(c)
            i += 1
        self.tokens = tuple(tokens)
        # the usual shapes, answered without the general loop: "name", "*.gcode", "name*"
        self.literal = "".join(tokens) if not _special(tokens) else None
        rest = tokens[1:]
        self.suffix = "".join(rest) if tokens and tokens[0] is _STAR and not _special(rest) else None
        head = tokens[:-1]
        self.prefix = "".join(head) if tokens and tokens[-1] is _STAR and not _special(head) else None
        # what any name it matches starts and ends with, and its least length: most names are refused on these
        # before the general loop (a .gitignore of 3,000 "*a*a*...*ac1" lines against long names took a minute)
        special = [i for i, t in enumerate(tokens) if not isinstance(t, str)]
        self.lead = "".join(tokens[: special[0]]) if special else ""
        self.tail = "".join(tokens[special[-1] + 1 :]) if special else ""
        self.least = sum(1 for t in tokens if t is not _STAR)
        # literals and "*" only: the literal pieces between stars, found in order (leftmost is right for "*")
        self.segments = None
        if special and all(t is _STAR or isinstance(t, str) for t in tokens):
            pieces: list[str] = [""]
            for t in tokens:
                if t is _STAR:
                    pieces.append("")
                else:
                    pieces[-1] += t
            self.segments = tuple(pieces)

    def match(self, name: str) -> bool:
        if self.literal is not None:
            return name == self.literal
        if self.suffix is not None:
            return name.endswith(self.suffix)
        if self.prefix is not None:
            return name.startswith(self.prefix)
        if len(name) < self.least or not name.startswith(self.lead) or not name.endswith(self.tail):
            return False
        if self.segments is not None:
            return _match_segments(self.segments, name)
        return _match_tokens(self.tokens, name)


def _match_segments(segments: tuple[str, ...], name: str) -> bool:
    """Whether ``name`` matches literal ``segments`` joined by ``*``: the first at the start, the last at the
    end, the others found in order, each as early as it can be (a later choice never helps)."""
    first, last = segments[0], segments[-1]
    if len(name) < len(first) + len(last) or not name.startswith(first) or not name.endswith(last):
        return False
    at, end = len(first), len(name) - len(last)
    for piece in segments[1:-1]:
        found = name.find(piece, at, end)
        if found < 0:
            return False
        at = found + len(piece)
    return True


def _special(tokens) -> bool:
    return any(not isinstance(t, str) for t in tokens)


def _one(token, c: str) -> bool:
    if token.__class__ is str:
        return token == c
    return token is _ANY or token(c)


def _match_tokens(tokens: tuple, name: str) -> bool:
    """Whether ``name`` matches ``tokens``: on a mismatch, only the last ``*`` takes one more character
    (at most len(name) x len(tokens) steps)."""
    t = p = 0
    star = -1
    mark = 0
    n, m = len(name), len(tokens)
    while t < n:
        if p < m and tokens[p] is _STAR:
            star, mark = p, t
            p += 1
        elif p < m and _one(tokens[p], name[t]):
            t += 1
            p += 1
        elif star >= 0:
            mark += 1
            t = mark
            p = star + 1
        else:
            return False
    while p < m and tokens[p] is _STAR:
        p += 1
    return p == m


_FOLDERS = object()  # a "**" part: any number of folders
_ONE = object()  # any one part (what a trailing "/**" needs before it: something inside the folder)


class Glob:
    """A compiled ``/``-separated pattern; ``match`` takes a ``/``-separated relative path."""

    __slots__ = ("parts", "text")

    def __init__(self, text: str) -> None:
        self.text = text
        parts: list = []
        pieces = text.split("/")
        for index, piece in enumerate(pieces):
            if len(piece) >= 2 and piece.strip("*") == "":  # "**" (git reads "***" as "**" too)
                if parts and parts[-1] is _FOLDERS:
                    continue  # "**/**" is "**"
                if index == len(pieces) - 1:
                    parts.append(_ONE)  # "a/**" is what is inside a, not a itself
                parts.append(_FOLDERS)
            else:
                parts.append(Part(piece))
        self.parts = tuple(parts)

    def match(self, path: str) -> bool:
        return _match_parts(self.parts, path.split("/"))


def _part_match(part, name: str) -> bool:
    return True if part is _ONE else part.match(name)


def _match_parts(parts: tuple, names: list[str]) -> bool:
    """The parts before the first ``**`` and after the last one are matched at the ends of the path; in
    between, the last ``**`` takes one more folder on a mismatch (as ``*`` within a part)."""
    stars = [i for i, p in enumerate(parts) if p is _FOLDERS]
    if not stars:
        return len(parts) == len(names) and all(_part_match(p, n) for p, n in zip(parts, names, strict=True))
    first, last = stars[0], stars[-1]
    head, tail = parts[:first], parts[last + 1 :]
    if len(head) + len(tail) > len(names):
        return False
    if not all(_part_match(p, n) for p, n in zip(head, names, strict=False)):
        return False
    if tail and not all(_part_match(p, n) for p, n in zip(tail, names[len(names) - len(tail) :], strict=True)):
        return False
    middle = parts[first : last + 1]
    rest = names[len(head) : len(names) - len(tail)]
    t = p = 0
    star = -1
    mark = 0
    n, m = len(rest), len(middle)
    while t < n:
        if p < m and middle[p] is _FOLDERS:
            star, mark = p, t
            p += 1
        elif p < m and _part_match(middle[p], rest[t]):
            t += 1
            p += 1
        elif star >= 0:
            mark += 1
            t = mark
            p = star + 1
        else:
            return False
    while p < m and middle[p] is _FOLDERS:
        p += 1
    return p == m


@lru_cache(maxsize=1024)
def compile_glob(pattern: str) -> Glob:
    """The compiled ``pattern`` (raises ``GlobError`` for one that cannot be read)."""
    return Glob(pattern)


def check(pattern: str) -> None:
    """Raise ``GlobError`` when ``pattern`` cannot be read (what the configuration checks on loading)."""
    compile_glob(_normal(pattern))


def _normal(pattern: str) -> str:
    pattern = pattern.strip()
    if pattern.startswith("./"):
        pattern = pattern[2:]
    return pattern.rstrip("/")


def matches(pattern: str, path: str) -> bool:
    """Whether ``path`` (``/``-separated, relative) matches ``pattern``; a pattern with no ``/`` also
    matches the last part of the path."""
    pattern = _normal(pattern)
    glob = compile_glob(pattern)
    if "/" not in pattern:  # one part (or "**"): the whole path matches only when the name does
        return glob.match(path.rpartition("/")[2])
    return glob.match(path)


def relative(path: str, base: str) -> str:
    """``path`` relative to the folder ``base``, with ``/`` separators (``..`` parts when outside)."""
    absolute, folder = os.path.abspath(path), os.path.abspath(base)
    prefix = folder.rstrip(os.sep) + os.sep
    if absolute.startswith(prefix):  # the usual case, without relpath's walk over every folder
        rel = absolute[len(prefix) :]
    elif absolute == folder:
        rel = "."
    else:
        try:
            rel = os.path.relpath(absolute, folder)
        except ValueError:  # another drive (Windows)
            rel = absolute
    return rel.replace(os.sep, "/")
