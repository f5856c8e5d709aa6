"""PrusaSlicer's INI files, read with positions: a flat configuration (``key = value`` lines, as the slicer
exports it and writes it at the end of a job) or a bundle of presets (``[printer:Name]`` sections, the vendor
profiles and the exported configuration bundles).

Read as PrusaSlicer reads them (boost's ``read_ini``, ``ConfigBase::load_from_ini``): ``key = value`` with
spaces around the key and the value trimmed, ``#`` and ``;`` lines are comments, a ``[name]`` line starts a
section.  A string setting's value is escaped C-style on one line (``unescape_string_cstyle`` in
libslic3r/Config.cpp: ``\\n`` a line break, ``\\r`` a carriage return, a backslash before any other character
that character); a list of strings (``start_filament_gcode``, one per extruder) is ``"..";".."``.  Each
character of a decoded value keeps the column it came from, so that a finding in a custom G-code setting points
into the file.

The input may come from anyone (a profile in a pull request): it is read as data, in bounded time and memory.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

MAX_BYTES = 16 << 20  # a vendor bundle is under 1 MB (PrusaResearch.ini, 2.5: 0.6 MB); more is not a profile
MAX_SECTIONS = 20_000


class ProfileError(Exception):
    """A file that cannot be read as a slicer profile: the message is one line."""


@dataclass(frozen=True)
class Entry:
    """One ``key = value`` line: the value as written (escaped), where it starts (1-based line and column)."""

    key: str
    value: str
    line: int
    column: int
    section: str | None = None  # the section's name (``printer:Voron_v2 0.4``), None before any section

    def decoded(self) -> Decoded:
        return unescape(self.value, self.line, self.column)


@dataclass
class Section:
    name: str | None
    line: int
    entries: dict[str, Entry] = field(default_factory=dict)


@dataclass(frozen=True)
class Decoded:
    """A setting's text as the slicer uses it, with the file position (line, column) of every character:
    ``positions[i]`` is where ``text[i]`` came from; ``positions[len(text)]`` is just past the value."""

    text: str
    positions: tuple[tuple[int, int], ...]

    def at(self, index: int) -> tuple[int, int]:
        if not self.positions:
            return (1, 1)
        return self.positions[min(max(index, 0), len(self.positions) - 1)]


_SECTION = re.compile(r"\[([^\]\r\n]*)\]\s*")


def read(text: str) -> list[Section]:
    """The sections of an INI text, in file order (the first has name None: the lines before any section).
    A key given twice in a section keeps its last value (PrusaSlicer's loader sets it twice)."""
    if len(text) > MAX_BYTES:
        raise ProfileError(f"larger than {MAX_BYTES >> 20} MB: not a slicer profile")
    sections = [Section(None, 1)]
    for number, raw in enumerate(text.splitlines(), 1):
        stripped = raw.strip()
        if not stripped or stripped[0] in "#;":
            continue
        if stripped[0] == "[":
            m = _SECTION.fullmatch(stripped)
            if m is None:
                raise ProfileError(f"line {number}: a section header with no closing ']'")
            if len(sections) >= MAX_SECTIONS:
                raise ProfileError(f"more than {MAX_SECTIONS:,} sections: not a slicer profile")
            sections.append(Section(m.group(1).strip(), number))
            continue
        key, sep, value = raw.partition("=")
        if not sep:
            continue  # (boost refuses such a line; PrusaSlicer's own writer never makes one)
        key = key.strip()  # (a value may hold "=": only the first one splits)
        column = len(raw) - len(value) + 1 + (len(value) - len(value.lstrip(" \t")))
        sections[-1].entries[key] = Entry(key, value.strip(" \t"), number, column, sections[-1].name)
    return sections


def unescape(value: str, line: int, column: int) -> Decoded:
    """A one-line string value decoded as ``unescape_string_cstyle`` decodes it, with positions."""
    out: list[str] = []
    where: list[tuple[int, int]] = []
    i = 0
    n = len(value)
    while i < n:
        c = value[i]
        at = (line, column + i)
        if c == "\\" and i + 1 < n:
            nxt = value[i + 1]
            out.append("\n" if nxt == "n" else "\r" if nxt == "r" else nxt)
            where.append(at)
            i += 2
            continue
        out.append(c)
        where.append(at)
        i += 1
    where.append((line, column + n))
    return Decoded("".join(out), tuple(where))


def unescape_list(value: str, line: int, column: int) -> list[Decoded]:
    """A list of strings (``"G1 X1\\nG1 X2";"M104 S0"``, or bare words separated by ``;``), each with
    positions, as ``unescape_strings_cstyle`` reads it."""
    items: list[Decoded] = []
    i, n = 0, len(value)
    while i < n:
        while i < n and value[i] in " \t":
            i += 1
        if i >= n:
            break
        out: list[str] = []
        where: list[tuple[int, int]] = []
        if value[i] == '"':
            i += 1
            while i < n and value[i] != '"':
                at = (line, column + i)
                if value[i] == "\\" and i + 1 < n:
                    nxt = value[i + 1]
                    out.append("\n" if nxt == "n" else "\r" if nxt == "r" else nxt)
                    i += 2
                else:
                    out.append(value[i])
                    i += 1
                where.append(at)
            where.append((line, column + i))
            i += 1  # (the closing quote)
            while i < n and value[i] != ";":
                i += 1
        else:
            while i < n and value[i] != ";":
                out.append(value[i])
                where.append((line, column + i))
                i += 1
            while out and out[-1] in " \t":
                out.pop()
                where.pop()
            where.append((line, column + i))
        i += 1  # (the ";")
        items.append(Decoded("".join(out), tuple(where)))
    return items
