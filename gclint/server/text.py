"""The text of an open document as the language server protocol sees it: lines split on ``\\r\\n``,
``\\r`` and ``\\n`` only (the same line breaks as gclint's reader, and not the extra ones of Python's
``str.splitlines``), positions counted in the client's units (UTF-16 code units unless the client
chose UTF-8 or UTF-32), and incremental edits.

Pure: no protocol library is needed here.  gclint's columns are 1-based character (code point) columns;
an LSP ``character`` is 0-based and counts code units of the negotiated encoding, so a character outside
the Basic Multilingual Plane (an emoji in a comment) is one gclint column but two UTF-16 units.
"""

from __future__ import annotations

import re
from bisect import bisect_right

UTF8 = "utf-8"
UTF16 = "utf-16"
UTF32 = "utf-32"

_BREAK = re.compile(r"\r\n|\r|\n")
_SURROGATE = re.compile("[\ud800-\udfff]")


def char_to_units(line: str, index: int, encoding: str = UTF16) -> int:
    """The position ``index`` (0-based, in characters) of ``line`` in the client's units."""
    index = max(0, min(index, len(line)))
    if encoding == UTF32 or line.isascii():  # isascii() is O(1) on CPython strings
        return index
    prefix = line[:index]
    if encoding == UTF8:
        return len(prefix.encode("utf-8", "surrogatepass"))
    return len(prefix.encode("utf-16-le", "surrogatepass")) // 2


def units_to_char(line: str, units: int, encoding: str = UTF16) -> int:
    """The character index of a client position ``units`` on ``line`` (past the end: the line's length).
    A position inside a character (half of a surrogate pair) counts as the character's start."""
    if units <= 0:
        return 0
    if encoding == UTF32 or line.isascii():
        return min(units, len(line))
    if encoding == UTF8:
        data = line.encode("utf-8", "surrogatepass")
        return len(data[:units].decode("utf-8", "ignore"))
    data = line.encode("utf-16-le", "surrogatepass")
    if units * 2 >= len(data):
        return len(line)
    cut = data[: units * 2]
    if 0xD8 <= cut[-1] <= 0xDB:  # the first half of a pair: stop before it
        cut = cut[:-2]
    return len(cut.decode("utf-16-le", "surrogatepass"))


def clean_surrogates(text: str) -> str:
    """``text`` with lone surrogates (from a JSON ``\\udc80`` escape: text that was not valid Unicode)
    replaced by U+FFFD, one character for one, so that every column stays where it was."""
    if text.isascii() or _SURROGATE.search(text) is None:
        return text
    return _SURROGATE.sub("\ufffd", text)


class Snapshot:
    """One version of a document's text, with its lines indexed.  Immutable: a change makes a new one."""

    __slots__ = ("text", "version", "_starts", "_ends")

    def __init__(self, text: str, version: int | None = None) -> None:
        self.text = text
        self.version = version
        self._starts: list[int] | None = None
        self._ends: list[int] | None = None

    def _index(self) -> tuple[list[int], list[int]]:
        if self._starts is None or self._ends is None:
            starts, ends = [0], []
            for m in _BREAK.finditer(self.text):
                ends.append(m.start())
                starts.append(m.end())
            ends.append(len(self.text))
            self._starts, self._ends = starts, ends
        return self._starts, self._ends

    @property
    def line_count(self) -> int:
        return len(self._index()[0])

    def line(self, index: int) -> str:
        """Line ``index`` (0-based) without its line break; "" past the end."""
        starts, ends = self._index()
        if not 0 <= index < len(starts):
            return ""
        return self.text[starts[index] : ends[index]]

    def offset(self, line: int, units: int, encoding: str = UTF16) -> int:
        """The offset in ``text`` of a client position (clamped to the text, as the protocol asks)."""
        starts, ends = self._index()
        if line < 0:
            return 0
        if line >= len(starts):
            return len(self.text)
        return starts[line] + units_to_char(self.line(line), units, encoding)

    def position(self, offset: int, encoding: str = UTF16) -> tuple[int, int]:
        """The client position ``(line, units)`` of an offset in ``text``."""
        starts, ends = self._index()
        offset = max(0, min(offset, len(self.text)))
        line = bisect_right(starts, offset) - 1
        char = min(offset, ends[line]) - starts[line]
        return line, char_to_units(self.line(line), char, encoding)

    def edited(self, start: tuple[int, int], end: tuple[int, int], new_text: str, encoding: str = UTF16) -> str:
        """The text with the client range ``start``..``end`` replaced by ``new_text``."""
        a = self.offset(*start, encoding)
        b = self.offset(*end, encoding)
        if b < a:
            a, b = b, a
        return self.text[:a] + new_text + self.text[b:]
