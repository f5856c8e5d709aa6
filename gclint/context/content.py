"""Read what the head of a file says about its dialect: the codes it uses, the dialects' clues, and the
Hyrel addresses, declared heads, axes and model-specific codes (for the firmware version and model).

One pass over the head's lines with the real parser (parses are cached by text, so the check that
follows gets these lines for free).  Plain moves (``G1 X.. Y.. E..``) carry no clue and are skipped.

What was seen is kept as a short text for the user (``M587 S"home" P"***" at line 2``), the evidence every
output and the cache show: its secrets are masked here, where it is made (``_seen``), with the masking
the findings use (gclint.secrets), so no output has to remember to.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from gclint import secrets
from gclint.dialects import Dialect, get, known_dialects
from gclint.dialects.base import Clue
from gclint.firmware import all_firmware
from gclint.syntax.fastpath import PLAIN_MOVE, PLAIN_MOVE_RUN
from gclint.syntax.nodes import GCODE, TEXT, Command, Word
from gclint.syntax.parse import parse_line

_LINE_BREAK = re.compile(r"\r\n?|\n")  # as gclint.syntax.source reads lines
_LINE_LIMIT = 2000  # longer lines are not read for clues (they are reported by the check itself)


@dataclass(frozen=True)
class Seen:
    """Where something was first seen: the line number (0: in the file's tail, line unknown) and the
    command's text."""

    line: int
    text: str

    def __str__(self) -> str:
        return f"{self.text} at line {self.line}" if self.line else f"{self.text} near the end of the file"


@dataclass
class ContentReading:
    """What the head's content says."""

    codes: dict[str, Seen] = field(default_factory=dict)  # G/M codes -> first use
    clues: dict[str, dict[Clue, Seen]] = field(default_factory=dict)  # candidate -> clue -> first match
    flavor_clues: dict[str, dict[Clue, Seen]] = field(default_factory=dict)  # firmware -> clue -> first match
    # Hyrel: (code, letter, number) of each T variable (and M703/M704 S) -> first use
    addresses: dict[tuple[str, str, int], Seen] = field(default_factory=dict)
    tool_commands: dict[int, Seen] = field(default_factory=dict)  # T<n> lines
    declarations: dict[int, Seen] = field(default_factory=dict)  # M6 T<n> O.. (T as written)
    waits_w0: Seen | None = None  # M109/M190/M191 W0
    m116: Seen | None = None
    rotary_axes: Seen | None = None  # an A or B word on a move, G28 or G92
    lathe: Seen | None = None  # M253/M254
    aux_codes: dict[str, Seen] = field(default_factory=dict)  # model-specific aux ports (M670-M689)
    e_amounts: Seen | None = None  # a working move with a fractional E before any M229 E1
    e_moves: Seen | None = None  # a move with an E word (Machinekit has none: gclint.dialects Dialect.move_letters)
    m229_e1: bool = False
    whole_e: set[str] = field(default_factory=set)  # whole E amounts other than 0 and 1 seen so far
    lines_read: set[str] = field(default_factory=set)  # the lines parsed (a repeated line is read once)


def candidates() -> tuple[Dialect, ...]:
    """The dialects ``auto`` chooses between (Hyrel v4 and v5 are one candidate; the version is decided
    from the addresses afterwards)."""
    return tuple(d for d in known_dialects() if d.variant_of is None)


_HYREL = get("hyrel")
# Hyrel codes whose T is an address (a T variable): every code whose parameter table lists T.
_T_VARIABLE_CODES = frozenset(c for c, spec in _HYREL.codes.items() if spec.params and "T" in spec.params)
# Codes whose A and B are axes on Hyrel (Gcode page: G0/G1 note on axes; G28, G92, M203, G54-G59, M6; G38)
_AXIS_CODES = frozenset({"G0", "G1", "G2", "G3", "G28", "G92", "M203", "M6", "G38", *(f"G{n}" for n in range(54, 60))})
_MOVES = frozenset({"G0", "G1", "G2", "G3"})
_MODEL_AUX = frozenset(f"M{n}" for n in range(670, 690))


def _clue_index(owners) -> tuple[dict[str, list[tuple[str, Clue]]], list[tuple[str, Clue]]]:
    by_code: dict[str, list[tuple[str, Clue]]] = {}
    general: list[tuple[str, Clue]] = []
    for owner in owners:
        for clue in owner.detection.clues:
            entry = (owner.name, clue)
            if clue.code is not None:
                by_code.setdefault(clue.code, []).append(entry)
            else:
                general.append(entry)
    return by_code, general


_BY_CODE, _GENERAL = _clue_index(candidates())
# the marks of a firmware flavour in the content (Klipper's extended commands), read in the same pass
_FLAVOR_BY_CODE, _FLAVOR_GENERAL = _clue_index(all_firmware())
# the general clues by the kind of command they may match (filled as kinds are met)
_GENERAL_BY_KIND: dict[str, tuple[tuple[str, Clue], ...]] = {}
_FLAVOR_BY_KIND: dict[str, tuple[tuple[str, Clue], ...]] = {}


def read_content(head: str, complete: bool, tail: str | None = None) -> ContentReading:
    """Read ``head`` (the beginning of a file; ``complete`` when it is the whole file) and ``tail`` (its
    end, whole lines; slicers put their end code there)."""
    reading = ContentReading()
    if not complete:  # cut short: the last line may be half a line
        whole = head[:-2] if head.endswith("\r\n") else head[:-1] if head.endswith(("\r", "\n")) else head
        head = whole[: max(whole.rfind("\n"), whole.rfind("\r")) + 1]
    _read_text(reading, head, True)
    if tail:
        _read_text(reading, tail, False)
    return reading


def _read_text(reading: ContentReading, text: str, numbered: bool) -> None:
    """Read the lines of ``text``; runs of plain moves and comments (fastpath.PLAIN_MOVE_RUN) are passed
    over whole once the moves have said what they can (``_moves_read``), and always when they hold only
    comments."""
    number = 0

    def read(start: int, end: int) -> None:
        nonlocal number
        lines = _LINE_BREAK.split(text[start:end])  # the line breaks the check reads (a form feed is none)
        if not lines[-1]:
            lines.pop()
        _read_lines(reading, enumerate(lines, number + 1) if numbered else ((0, raw) for raw in lines))
        number += len(lines)

    at = 0
    while at < len(text):
        run = PLAIN_MOVE_RUN.search(text, at)
        stop = run.start() if run is not None else len(text)
        if stop > at:
            read(at, stop)
        if run is None:
            return
        if _moves_read(reading) or (text[stop] != "G" and text.find("\nG", stop, run.end()) < 0):
            number += text.count("\n", stop, run.end())  # (nothing to read: moves said all, or comments only)
        else:
            read(stop, run.end())
        at = run.end()


def _moves_read(reading: ContentReading) -> bool:
    """Whether plain moves can tell ``reading`` nothing more (see ``_read_lines``)."""
    return reading.e_moves is not None and (reading.e_amounts is not None or reading.m229_e1)


def _read_lines(reading: ContentReading, lines) -> None:
    plain = PLAIN_MOVE.fullmatch
    done = reading.lines_read
    for number, raw in lines:
        stripped = raw.lstrip()
        if not stripped or stripped[0] in ";(" or len(raw) > _LINE_LIMIT:
            continue
        move = plain(raw)
        if move is not None:
            if reading.e_moves is None and move.group(6) is not None:
                reading.e_moves = Seen(number, secrets.mask(raw.strip())[:_SHOWN])
            if reading.e_amounts is None and not reading.m229_e1 and move.group(1) == "1":
                e = move.group(6)
                # a fractional amount, or the third whole amount other than 0 and 1 (E2, E3, E4: a Hyrel job
                # writes E1 as a flag, and a hand-written one may count a few moves)
                if e is not None and abs(float(e)) not in (0.0, 1.0):
                    if "." in e.rstrip("0").rstrip(".") or len(reading.whole_e) >= 2 and e not in reading.whole_e:
                        reading.e_amounts = Seen(number, secrets.mask(raw.strip())[:_SHOWN])
                    else:
                        reading.whole_e.add(e)
            continue
        if raw in done:
            continue  # a line read before says nothing new (only where each clue is first seen is kept)
        done.add(raw)
        for cmd in parse_line(raw).commands:
            _read_command(reading, cmd, number, raw)


def _of_kind(kind: str, entries: list[tuple[str, Clue]]) -> tuple[tuple[str, Clue], ...]:
    """The clues of ``entries`` a command of ``kind`` may match (in their order)."""
    return tuple((owner, clue) for owner, clue in entries if clue.kind is None or clue.kind == kind)


def _read_command(reading: ContentReading, cmd: Command, number: int, raw: str) -> None:
    code = cmd.code
    seen = None
    if reading.clues:  # (the first command tries every clue: each candidate's entry is made in that order)
        kind = cmd.kind
        if kind not in _GENERAL_BY_KIND:
            _GENERAL_BY_KIND[kind] = _of_kind(kind, _GENERAL)
            _FLAVOR_BY_KIND[kind] = _of_kind(kind, _FLAVOR_GENERAL)
        general, flavor = _GENERAL_BY_KIND[kind], _FLAVOR_BY_KIND[kind]
    else:
        general, flavor = _GENERAL, _FLAVOR_GENERAL
    for candidate, clue in _BY_CODE.get(code, ()) if code is not None else ():  # type: ignore[arg-type]
        seen = _match(reading, candidate, clue, cmd, number, raw, seen)
    for candidate, clue in general:
        seen = _match(reading, candidate, clue, cmd, number, raw, seen)
    for firmware, clue in _FLAVOR_BY_CODE.get(code, ()) if code is not None else ():  # type: ignore[arg-type]
        seen = _match(reading, firmware, clue, cmd, number, raw, seen, reading.flavor_clues)
    for firmware, clue in flavor:
        seen = _match(reading, firmware, clue, cmd, number, raw, seen, reading.flavor_clues)
    if code is None or cmd.kind not in (GCODE, TEXT):
        return
    params = cmd.params
    letter = code[0]
    if letter in "GM" and code not in reading.codes:
        reading.codes[code] = seen or _seen(cmd, number, raw)
    if letter == "T":
        tail = code[1:]
        if tail.isdigit() and int(tail) not in reading.tool_commands:
            reading.tool_commands[int(tail)] = _seen(cmd, number, raw)
        return
    if code in _T_VARIABLE_CODES:
        _address(reading, cmd, "T", number, raw)
        if code in ("M703", "M704"):
            _address(reading, cmd, "S", number, raw)
    if code == "M6" and "O" in params:
        head = _whole(params.get("T"))
        if head is not None and head not in reading.declarations:
            reading.declarations[head] = _seen(cmd, number, raw)
    elif code in ("M109", "M190", "M191") and _whole(params.get("W")) == 0 and reading.waits_w0 is None:
        reading.waits_w0 = _seen(cmd, number, raw)
    elif code == "M229" and _whole(params.get("E")) == 1:
        reading.m229_e1 = True
    elif code == "M116" and reading.m116 is None:
        reading.m116 = _seen(cmd, number, raw)
    elif code in ("M253", "M254") and reading.lathe is None:
        reading.lathe = _seen(cmd, number, raw)
    elif code in _MODEL_AUX and code not in reading.aux_codes:
        reading.aux_codes[code] = _seen(cmd, number, raw)
    if code in _MOVES and "E" in params and reading.e_moves is None:
        reading.e_moves = _seen(cmd, number, raw)
    if code in _AXIS_CODES and reading.rotary_axes is None and ("A" in params or "B" in params):
        reading.rotary_axes = _seen(cmd, number, raw)


def _match(
    reading: ContentReading,
    candidate: str,
    clue: Clue,
    cmd: Command,
    number: int,
    raw: str,
    seen: Seen | None,
    into: dict[str, dict[Clue, Seen]] | None = None,
) -> Seen | None:
    table = reading.clues if into is None else into
    found = table.get(candidate)
    if found is None:
        found = table[candidate] = {}
    elif clue in found:
        return seen
    try:
        matched = clue.matches(cmd)
    except (TypeError, ValueError, AttributeError):  # a clue never stops the reading
        matched = False
    if matched:
        seen = seen or _seen(cmd, number, raw)
        found[clue] = seen
    return seen


def _address(reading: ContentReading, cmd: Command, letter: str, number: int, raw: str) -> None:
    value = _whole(cmd.params.get(letter))
    if value is None:
        return
    key = (cmd.code or "", letter, value)
    if key not in reading.addresses:
        reading.addresses[key] = _seen(cmd, number, raw)


def _whole(text: str | None) -> int | None:
    if text is None or not 0 < len(text) <= 6:
        return None
    try:
        value = float(text)
    except ValueError:
        return None
    return int(value) if value == int(value) else None


_SHOWN = 40  # characters of a command shown as evidence


def _seen(cmd: Command, number: int, raw: str) -> Seen:
    """``cmd`` (on line ``raw``) as evidence: its code and first words, secrets masked.

    The words are rendered from the parse (``M109 T0 S215``), so a secret is masked on the line first and
    each word that touches it is shown from the masked line: ``M551 Phunter2`` parses as ``P``, ``H``,
    ``U``... and would otherwise show the password's letters.  Masked before it is cut short (a cut
    ``P"pass`` would no longer look like a password)."""
    spans = secrets.find(raw)
    masked = secrets.mask(raw) if spans else raw
    parts = []
    for letter, value in list(cmd.params.items())[:4]:
        word = cmd.param(letter) if spans else None
        if word is not None and _touches(word, spans):
            parts.append(masked[word.column - 1 : word.end_column - 1].replace(" ", "").replace("\t", ""))
        else:
            parts.append(f"{letter}{value if value is not None else ''}")
    params = " ".join(parts)
    text = f"{cmd.code} {params}".strip() if cmd.kind in (GCODE, TEXT) else (cmd.code or cmd.kind)
    return Seen(number, secrets.mask(text)[:_SHOWN])


def _touches(word: Word, spans: list[secrets.Secret]) -> bool:
    start, end = word.column - 1, word.end_column - 1
    return any(s.start < end and start < s.end for s in spans)
