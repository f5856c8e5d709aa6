"""Read what the head (and tail) of a file says about its dialect, Hyrel version and printer: the codes it
uses, the dialects' clues, habits and line marks, the kinds of line, parameters a dialect's table does not
take, how E is used, and the Hyrel addresses, declared heads, axes and model-specific codes with the number
of lines that use each.

One pass over the lines with the real parser (parses are cached by text, so the check that follows gets
these lines for free).  Plain moves (``G1 X.. Y.. E..``) are read by a regular expression, for their E word
only, and runs of them are passed over once they can tell nothing more.  A line repeated word for word is
parsed once; its counts are replayed.

What was seen is kept as a short text for the user (``M587 S"home" P"***" at line 2``), the evidence every
output and the cache show: its secrets are masked here, where it is made (``_seen``), with the masking
the findings use (gclint.secrets), so no output has to remember to.
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass, field

from gclint import secrets
from gclint.context.candidates import candidates
from gclint.dialects.base import Clue, Habit, LineMark
from gclint.firmware import all_firmware
from gclint.syntax.fastpath import PLAIN_MOVE, PLAIN_MOVE_RUN
from gclint.syntax.nodes import ASSIGNMENT, EXTENDED, GCODE, META, OWORD, TEXT, Command, Word
from gclint.syntax.parse import parse_line

_LINE_BREAK = re.compile(r"\r\n?|\n")  # as gclint.syntax.source reads lines
_LINE_LIMIT = 2000  # longer lines are not read for clues (they are reported by the check itself)
_KINDS = frozenset({EXTENDED, META, OWORD, ASSIGNMENT})  # kinds of line a dialect's language may lack
_MAX_KINDS = 64  # distinct (kind, word) pairs kept (a Klipper file may call many macros)
_AMOUNTS = 3  # printing moves with amounts read before the moves can tell nothing more
_SLICED = 2  # printing moves with amounts (and nothing native flow computes from) that make a job sliced


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
    """What the content says.  The habits' ``test`` reads ``fan_range``, ``e_values`` and ``height_registers``
    (the state of the job so far, in file order)."""

    codes: dict[str, Seen] = field(default_factory=dict)  # G/M codes -> first use
    clues: dict[str, dict[Clue, Seen]] = field(default_factory=dict)  # dialect -> clue -> first match
    flavor_clues: dict[str, dict[Clue, Seen]] = field(default_factory=dict)  # firmware -> clue -> first match
    habits: dict[str, dict[Habit, Seen]] = field(default_factory=dict)  # dialect -> habit -> first match
    marks: dict[str, dict[LineMark, Seen]] = field(default_factory=dict)  # dialect -> line mark -> first line
    kinds: dict[tuple[str, str], Seen] = field(default_factory=dict)  # (kind, WORD) of extended/meta/O-word lines
    # dialect -> (code, letter) -> (first use, what is wrong): a letter its table lacks, a value out of range
    params: dict[str, dict[tuple[str, str], tuple[Seen, str]]] = field(default_factory=dict)
    # dialect -> (code, letter) -> (first use, why): a word its firmware rejects (``Param.forbidden``)
    rejected: dict[str, dict[tuple[str, str], tuple[Seen, str]]] = field(default_factory=dict)
    # Hyrel: (code, letter, number) of each T variable (and M703/M704 S) -> first use
    addresses: dict[tuple[str, str, int], Seen] = field(default_factory=dict)
    tool_commands: dict[int, Seen] = field(default_factory=dict)  # T<n> lines
    declarations: dict[int, Seen] = field(default_factory=dict)  # M6 T<n> O.. (T as written)
    # lines that use each: ("T", code, letter, n), ("tool", n), ("axis",), ("lathe",), ("aux", code)
    counts: Counter = field(default_factory=Counter)
    waits_w0: Seen | None = None  # M109/M190/M191 W0
    m116: Seen | None = None
    rotary_axes: Seen | None = None  # an A or B word on a move, G28 or G92
    lathe: Seen | None = None  # M253/M254
    aux_codes: dict[str, Seen] = field(default_factory=dict)  # model-specific aux ports (M670-M689)
    z_homed: bool = False  # a G28 with Z so far
    m660_after_z_home: Seen | None = None  # the first M660 after a G28 Z (the EHR header)
    m660_before_z_home: Seen | None = None  # the first M660 before any
    # E: a printing move's amount (fractional, or a third whole amount other than 0 and 1) before any M229 E1
    e_amounts: Seen | None = None
    e_retract: Seen | None = None  # a G1 with a zero or negative E before any M229 E1
    e_on_g0: Seen | None = None
    e_moves: Seen | None = None  # a move with an E word (Machinekit has none: gclint.dialects Dialect.not_move_words)
    e_flags: int = 0  # printing moves (X or Y) with E1 before any M229 E1: Hyrel's marks of a printing move
    e_amount_moves: int = 0  # printing moves with an amount before any M229 E1 (counted up to _AMOUNTS)
    native_flow: Seen | None = None  # what Hyrel's native flow computes from: M756, M221 P/W/Z, or M229 E0
    whole_e: set[str] = field(default_factory=set)  # whole E amounts other than 0 and 1 seen so far
    # the state the habits read
    fan_range: bool = False  # an M106 C range was set
    e_values: bool = False  # M229 E1: the E amounts carry the flow
    height_registers: set[float] = field(default_factory=set)  # the registers M660 set
    lines_read: dict[str, tuple] = field(default_factory=dict)  # each line parsed -> the counts it adds

    @property
    def m229_e1(self) -> bool:
        return self.e_values

    @property
    def e_sliced(self) -> Seen | None:
        """The first E amount, when amounts are on two printing moves or more and nothing says native flow (no
        M229 E1, no M756 or M221 W/Z/P): a job sliced for a firmware that meters E."""
        sliced = self.e_amount_moves >= _SLICED and not self.e_values and self.native_flow is None
        return self.e_amounts if sliced else None

    def fact(self, name: str) -> Seen | None:
        """A fact of the whole reading a habit names (``e_amounts``, ``e_retract``, ``e_on_g0``)."""
        value = getattr(self, name, None)
        return value if isinstance(value, Seen) else None


_HYREL = next(c.dialect for c in candidates() if c.dialect.extras.get("resolve_variable") is not None)
# Codes whose T is an address (a T variable) on Hyrel: every code whose parameter table lists T.
_T_VARIABLE_CODES = frozenset(c for c, spec in _HYREL.codes.items() if spec.params and "T" in spec.params)
# Codes whose A and B are axes on Hyrel (Gcode page: G0/G1 note on axes; G28, G92, M203, G54-G59, M6; G38)
_AXIS_CODES = frozenset({"G0", "G1", "G2", "G3", "G28", "G92", "M203", "M6", "G38", *(f"G{n}" for n in range(54, 60))})
_MOVES = frozenset({"G0", "G1", "G2", "G3"})
_LINEAR = frozenset({"G0", "G1"})
_MODEL_AUX = frozenset(f"M{n}" for n in range(670, 690))


def _index(owners, attribute: str) -> tuple[dict[str, list], list]:
    """(code -> [(owner, item)], [(owner, item) with no code]) for the clues or habits of ``owners``."""
    by_code: dict[str, list] = {}
    general: list = []
    for name, detection in owners:
        for item in getattr(detection, attribute):
            if getattr(item, "fact", None) is not None:
                continue
            entry = (name, item)
            if item.code is not None:
                by_code.setdefault(item.code, []).append(entry)
            else:
                general.append(entry)
    return by_code, general


_DIALECTS = [(c.dialect.name, c.dialect.detection) for c in candidates() if c.flavor is None]  # (generic too)
_BY_CODE, _GENERAL = _index(_DIALECTS, "clues")
_HABITS_BY_CODE, _HABITS_GENERAL = _index(_DIALECTS, "habits")
# the marks of a firmware flavour in the content (Klipper's extended commands), read in the same pass
_FLAVOR_BY_CODE, _FLAVOR_GENERAL = _index([(f.name, f.detection) for f in all_firmware()], "clues")
_MARKS = tuple((name, mark, re.compile(mark.pattern)) for name, detection in _DIALECTS for mark in detection.line_marks)
# the general clues by the kind of command they may match (filled as kinds are met)
_GENERAL_BY_KIND: dict[str, tuple] = {}
_FLAVOR_BY_KIND: dict[str, tuple] = {}
# code -> [(dialect, its Code)] for the tables that catalogue the code's parameters, with the rules its habits
# report (a parameter a habit covers is counted once, as the habit)
_PARAM_TABLES: dict[str, list] = {}
for _c in candidates():
    if _c.flavor is not None or not _c.known:
        continue
    _habit_rules: dict[str, set[str]] = {}
    for _h in _c.dialect.detection.habits:
        if _h.code is not None:
            _habit_rules.setdefault(_h.code, set()).add(_h.rule)
    for _code, _spec in _c.dialect.codes.items():
        if _spec.params is not None:
            _PARAM_TABLES.setdefault(_code, []).append((_c.dialect.name, _spec, frozenset(_habit_rules.get(_code, ()))))


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
    """Whether plain moves can tell ``reading`` nothing more: an E word was seen and either the E values
    carry the flow (M229 E1) or an amount showed they are amounts (the E1 marks of native flow are counted
    until then)."""
    return reading.e_moves is not None and (reading.e_amount_moves >= _AMOUNTS or reading.e_values)


def _read_lines(reading: ContentReading, lines) -> None:
    plain = PLAIN_MOVE.fullmatch
    done = reading.lines_read
    counts = reading.counts
    for number, raw in lines:
        # a plain move first (most lines): it holds no line mark's required text (it is G, digits, X Y Z E F,
        # signs, points and blanks: tests/test_context.py), starts with G and is shorter than _LINE_LIMIT
        move = plain(raw)
        if move is not None:
            e = move.group(6)
            if e is not None:
                xy = move.group(3) is not None or move.group(4) is not None
                _e_word(reading, move.group(1), xy, e, number, raw)
            continue
        stripped = raw.lstrip()
        if not stripped or len(raw) > _LINE_LIMIT:
            continue
        for owner, mark, pattern in _MARKS:
            if mark.contains in raw and pattern.search(raw):
                found = reading.marks.setdefault(owner, {})
                if mark not in found:
                    found[mark] = Seen(number, secrets.mask(raw.strip())[:_SHOWN])
        if stripped[0] in ";(":
            continue
        keys = done.get(raw)
        if keys is not None:
            for key in keys:  # a line read before says nothing new but how many lines say it
                counts[key] += 1
            continue
        added: list = []
        for cmd in parse_line(raw).commands:
            _read_command(reading, cmd, number, raw, added)
        done[raw] = tuple(added)
        for key in added:
            counts[key] += 1


def _e_word(reading: ContentReading, g: str, xy: bool, e: str, number: int, raw: str) -> None:
    """What an E word on a G0/G1 says: Hyrel's E1 mark of a printing move, an amount, a retract."""
    if reading.e_moves is None:
        reading.e_moves = Seen(number, secrets.mask(raw.strip())[:_SHOWN])
    if g == "0":
        if reading.e_on_g0 is None:
            reading.e_on_g0 = Seen(number, secrets.mask(raw.strip())[:_SHOWN])
        return
    if reading.e_values:
        return
    try:
        value = float(e)
    except ValueError:
        return
    if value <= 0:
        if reading.e_retract is None:
            reading.e_retract = Seen(number, secrets.mask(raw.strip())[:_SHOWN])
        return
    if value == 1:
        if xy:
            reading.e_flags += 1
        return
    # a fractional amount, or the third whole amount other than 0 and 1 (E2, E3, E4: a Hyrel job writes E1 as
    # a flag, and a hand-written one may count a few moves)
    if "." in e.rstrip("0").rstrip(".") or len(reading.whole_e) >= 2 and e not in reading.whole_e:
        if reading.e_amounts is None:
            reading.e_amounts = Seen(number, secrets.mask(raw.strip())[:_SHOWN])
        if xy:
            reading.e_amount_moves += 1
    else:
        reading.whole_e.add(e)


def _of_kind(kind: str, entries: list) -> tuple:
    """The clues of ``entries`` a command of ``kind`` may match (in their order)."""
    return tuple((owner, clue) for owner, clue in entries if clue.kind is None or clue.kind == kind)


def _read_command(reading: ContentReading, cmd: Command, number: int, raw: str, added: list) -> None:
    code = cmd.code
    kind = cmd.kind
    seen = None
    if kind not in _GENERAL_BY_KIND:
        _GENERAL_BY_KIND[kind] = _of_kind(kind, _GENERAL)
        _FLAVOR_BY_KIND[kind] = _of_kind(kind, _FLAVOR_GENERAL)
    for owner, clue in _BY_CODE.get(code, ()) if code is not None else ():
        seen = _match(reading.clues, owner, clue, cmd, number, raw, seen)
    for owner, clue in _GENERAL_BY_KIND[kind]:
        needs = clue.contains
        if not needs or needs[0] in raw or needs[-1] in raw:
            seen = _match(reading.clues, owner, clue, cmd, number, raw, seen)
    for owner, clue in _FLAVOR_BY_CODE.get(code, ()) if code is not None else ():
        seen = _match(reading.flavor_clues, owner, clue, cmd, number, raw, seen)
    for owner, clue in _FLAVOR_BY_KIND[kind]:
        seen = _match(reading.flavor_clues, owner, clue, cmd, number, raw, seen)
    habitual = False  # another firmware's habit: its T is that firmware's (an extruder index), no address
    for owner, habit in _HABITS_BY_CODE.get(code, ()) if code is not None else ():
        try:
            hit = habit.matches(cmd, reading)
        except (TypeError, ValueError, AttributeError):  # a habit never stops the reading
            hit = False
        if hit:
            habitual = True
            found = reading.habits.setdefault(owner, {})
            if habit not in found:
                seen = found[habit] = seen or _seen(cmd, number, raw)
    if kind in _KINDS:
        key = (kind, (code or kind).upper())
        if key not in reading.kinds and len(reading.kinds) < _MAX_KINDS:
            reading.kinds[key] = seen or _seen(cmd, number, raw)
        return
    if code is None or kind not in (GCODE, TEXT):
        return
    params = cmd.params
    letter = code[0]
    if letter in "GM" and code not in reading.codes:
        reading.codes[code] = seen or _seen(cmd, number, raw)
    if letter == "T":
        tail = code[1:]
        if tail.isdigit():
            n = int(tail)
            if n not in reading.tool_commands:
                reading.tool_commands[n] = _seen(cmd, number, raw)
            added.append(("tool", n))
        return
    tables = _PARAM_TABLES.get(code) if code not in _LINEAR else None  # (lines are read for E and axes only)
    if tables is not None and params:
        _check_params(reading, cmd, code, tables, number, raw)
    if code in _T_VARIABLE_CODES and not habitual:
        _address(reading, cmd, "T", number, raw, added)
        if code in ("M703", "M704"):
            _address(reading, cmd, "S", number, raw, added)
    if code == "M6" and "O" in params:
        head = _whole(params.get("T"))
        if head is not None:
            if head not in reading.declarations:
                reading.declarations[head] = _seen(cmd, number, raw)
            added.append(("decl", head))
    elif code in ("M109", "M190", "M191") and _whole(params.get("W")) == 0:
        if reading.waits_w0 is None:
            reading.waits_w0 = _seen(cmd, number, raw)
        added.append(("W0",))
    elif code == "M229" and _whole(params.get("E")) == 1:
        reading.e_values = True
    elif (code == "M756" or code == "M221" and ("W" in params or "Z" in params or "P" in params)) or (
        code == "M229" and _whole(params.get("E")) == 0
    ):
        if reading.native_flow is None:
            reading.native_flow = _seen(cmd, number, raw)
    elif code == "M106" and "C" in params:
        reading.fan_range = True
    elif code == "M116":
        if reading.m116 is None:
            reading.m116 = _seen(cmd, number, raw)
        added.append(("M116",))
    elif code in ("M253", "M254"):
        if reading.lathe is None:
            reading.lathe = _seen(cmd, number, raw)
        added.append(("lathe",))
    elif code in _MODEL_AUX:
        if code not in reading.aux_codes:
            reading.aux_codes[code] = _seen(cmd, number, raw)
        added.append(("aux", code))
    elif code == "G28" and "Z" in params:
        reading.z_homed = True
    elif code == "M660":
        register = cmd.get("H")
        if register is not None:
            reading.height_registers.add(register)
        if reading.z_homed and reading.m660_after_z_home is None:
            reading.m660_after_z_home = _seen(cmd, number, raw)
        elif not reading.z_homed and reading.m660_before_z_home is None:
            reading.m660_before_z_home = _seen(cmd, number, raw)
    if code in _MOVES and "E" in params:
        e = params.get("E")
        if code in ("G0", "G1") and e is not None:
            _e_word(reading, code[1], "X" in params or "Y" in params, e, number, raw)
        elif reading.e_moves is None:
            reading.e_moves = _seen(cmd, number, raw)
    if code in _AXIS_CODES and ("A" in params or "B" in params):
        if reading.rotary_axes is None:
            reading.rotary_axes = _seen(cmd, number, raw)
        added.append(("axis",))


def _check_params(reading: ContentReading, cmd: Command, code: str, tables: list, number: int, raw: str) -> None:
    """Record what each catalogued table says is wrong with ``cmd``'s words (a letter the code does not take,
    a value outside its range; a word the firmware rejects apart), once per (code, letter: ``code`` is
    ``cmd``'s); a word a habit reports is the habit's."""
    for owner, spec, habit_rules in tables:
        for letter in cmd.params:
            if (code, letter) in reading.params.get(owner, ()) or (code, letter) in reading.rejected.get(owner, ()):
                continue
            param = spec.params.get(letter)
            if param is None:
                problem = f"{code} takes no {letter}"
            elif not param.constrained or param.rule in habit_rules:
                continue
            else:
                problem = param.problem(cmd.get(letter))
                if problem is None:
                    continue
            found = reading.rejected if param is not None and param.forbidden else reading.params
            found.setdefault(owner, {})[(code, letter)] = (_seen(cmd, number, raw), problem)


def _match(table: dict, owner: str, item: Clue, cmd: Command, number: int, raw: str, seen: Seen | None):
    """Record the clue ``item`` for ``owner`` when ``cmd`` matches it first."""
    found = table.get(owner)
    if found is None:
        found = table[owner] = {}
    elif item in found:
        return seen
    try:
        matched = item.matches(cmd)
    except (TypeError, ValueError, AttributeError):  # a clue never stops the reading
        matched = False
    if matched:
        seen = seen or _seen(cmd, number, raw)
        found[item] = seen
    return seen


def _address(reading: ContentReading, cmd: Command, letter: str, number: int, raw: str, added: list) -> None:
    value = _whole(cmd.params.get(letter))
    if value is None:
        return
    key = (cmd.code or "", letter, value)
    if key not in reading.addresses:
        reading.addresses[key] = _seen(cmd, number, raw)
    added.append(("T", *key))


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


__all__ = ["ContentReading", "Seen", "read_content"]
