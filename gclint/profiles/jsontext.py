"""A JSON document read with the position of every string value (OrcaSlicer's and Bambu Studio's printer
profiles, Cura's machine definitions).  Python's ``json`` gives the values but not where they are; a finding in
``machine_start_gcode`` must point at its line in the file.

A small reader of the JSON grammar (RFC 8259), bounded: a profile may come from anyone.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass

from gclint.profiles.ini import Decoded, ProfileError

MAX_DEPTH = 64
MAX_BYTES = 16 << 20
_ESCAPES = {'"': '"', "\\": "\\", "/": "/", "b": "\b", "f": "\f", "n": "\n", "r": "\r", "t": "\t"}
_WS = " \t\r\n"


@dataclass(frozen=True)
class Text:
    """A JSON string value: its text, and where each of its characters is in the file."""

    decoded: Decoded

    @property
    def value(self) -> str:
        return self.decoded.text


def load(text: str) -> object:
    """The document: dicts, lists, numbers, None, bools, and strings as ``Text`` (with positions)."""
    if len(text) > MAX_BYTES:
        raise ProfileError(f"larger than {MAX_BYTES >> 20} MB: not a slicer profile")
    reader = _Reader(text)
    reader.blank()
    value = reader.value(0)
    reader.blank()
    if reader.i != len(text):
        raise ProfileError(f"line {reader.line_col(reader.i)[0]}: text after the JSON document")
    return value


def plain(value: object) -> object:
    """``value`` with every ``Text`` turned into its string (as ``json.loads`` gives it)."""
    if isinstance(value, Text):
        return value.value
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    return value


class _Reader:
    def __init__(self, text: str) -> None:
        self.text = text
        self.i = 0
        self.starts = [0] + [i + 1 for i, c in enumerate(text) if c == "\n"]

    def line_col(self, index: int) -> tuple[int, int]:
        line = bisect.bisect_right(self.starts, index)
        return line, index - self.starts[line - 1] + 1

    def fail(self, what: str) -> ProfileError:
        line, col = self.line_col(self.i)
        return ProfileError(f"line {line}, column {col}: {what}: not valid JSON")

    def blank(self) -> None:
        text, i = self.text, self.i
        while i < len(text) and text[i] in _WS:
            i += 1
        self.i = i

    def value(self, depth: int) -> object:
        if depth > MAX_DEPTH:
            raise self.fail("nested too deeply")
        if self.i >= len(self.text):
            raise self.fail("the document ends too early")
        c = self.text[self.i]
        if c == "{":
            return self.obj(depth)
        if c == "[":
            return self.array(depth)
        if c == '"':
            return self.string()
        for word, meaning in (("true", True), ("false", False), ("null", None)):
            if self.text.startswith(word, self.i):
                self.i += len(word)
                return meaning
        return self.number()

    def obj(self, depth: int) -> dict:
        self.i += 1
        out: dict = {}
        self.blank()
        if self.text.startswith("}", self.i):
            self.i += 1
            return out
        while True:
            self.blank()
            if not self.text.startswith('"', self.i):
                raise self.fail("expected a key")
            key = self.string().value
            self.blank()
            if not self.text.startswith(":", self.i):
                raise self.fail("expected ':'")
            self.i += 1
            self.blank()
            out[key] = self.value(depth + 1)
            self.blank()
            if self.text.startswith(",", self.i):
                self.i += 1
                continue
            if self.text.startswith("}", self.i):
                self.i += 1
                return out
            raise self.fail("expected ',' or '}'")

    def array(self, depth: int) -> list:
        self.i += 1
        out: list = []
        self.blank()
        if self.text.startswith("]", self.i):
            self.i += 1
            return out
        while True:
            self.blank()
            out.append(self.value(depth + 1))
            self.blank()
            if self.text.startswith(",", self.i):
                self.i += 1
                continue
            if self.text.startswith("]", self.i):
                self.i += 1
                return out
            raise self.fail("expected ',' or ']'")

    def string(self) -> Text:
        text = self.text
        i = self.i + 1
        chars: list[str] = []
        where: list[int] = []
        while True:
            if i >= len(text):
                raise self.fail("a string with no closing quote")
            c = text[i]
            if c == '"':
                break
            if c == "\\":
                nxt = text[i + 1 : i + 2]
                if nxt == "u":
                    digits = text[i + 2 : i + 6]
                    try:
                        chars.append(chr(int(digits, 16)))
                    except ValueError:
                        raise self.fail("a bad \\u escape") from None
                    where.append(i)
                    i += 6
                    continue
                if nxt not in _ESCAPES:
                    raise self.fail("a bad escape")
                chars.append(_ESCAPES[nxt])
                where.append(i)
                i += 2
                continue
            if c == "\n":
                raise self.fail("a line break inside a string")
            chars.append(c)
            where.append(i)
            i += 1
        where.append(i)
        self.i = i + 1
        positions = tuple(self.line_col(at) for at in where)
        return Text(Decoded("".join(chars), positions))

    def number(self) -> float:
        start = self.i
        text = self.text
        while self.i < len(text) and text[self.i] in "+-0123456789.eE":
            self.i += 1
        try:
            return float(text[start : self.i])
        except ValueError:
            raise self.fail("expected a value") from None
