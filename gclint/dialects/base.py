"""What a dialect is: the codes it knows (with their parameters), its addressing, its header detection.

A dialect module builds one ``Dialect`` from tables.  Dialects that differ little from another one are
written as a delta (``base.derive(...)``), in the manner of sqlfluff's ``copy_as``.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from functools import cache
from typing import Any

from gclint.dialects.semantics import DWELL_UNKNOWN, Semantics
from gclint.secrets import mask


@dataclass(frozen=True)
class Param:
    """One parameter of a code.

    ``minimum``/``maximum`` bound the value; ``integer`` requires a whole number; ``choices`` lists the only allowed
    values; ``forbidden`` letters must not appear at all.  ``rule`` names the rule that reports a value outside these
    bounds (``DL003`` by default); ``source`` names the section of the public source the fact comes from
    (docs/sources.md).

    How ``gclint explain`` reads the word, in the words of the page's "decoded and executed by the
    printer as follows" sections: ``says`` is a phrase with ``{value}`` for the value written (for a T
    variable, the device it addresses); ``values`` gives the phrase for particular values as written
    (``{"1": "enable"}``); ``absent`` is what happens when the letter is not written.  ``meaning`` stays
    the short name that findings quote.
    """

    letter: str
    meaning: str = ""
    required: bool = False
    minimum: float | None = None
    maximum: float | None = None
    integer: bool = False
    choices: tuple[float, ...] | None = None
    rule: str = "DL003"
    source: str = ""
    forbidden: bool = False  # the letter must not appear at all (the meaning says why)
    says: str = ""
    values: Mapping[str, str] | None = None
    absent: str = ""

    @property
    def constrained(self) -> bool:
        """Whether anything about this parameter can be wrong (a bound, choices, required, forbidden)."""
        return (
            self.forbidden
            or self.required
            or self.integer
            or self.choices is not None
            or self.minimum is not None
            or self.maximum is not None
        )

    def problem(self, value: float | None) -> str | None:
        """Why ``value`` is not allowed, or None.  ``value`` is None for a letter with no number."""
        if self.forbidden:
            return f"{self.letter}: {self.meaning}"
        if value is None:
            return None
        if self.choices is not None and value not in self.choices:
            allowed = ", ".join(_fmt(c) for c in self.choices)
            return f"{self.letter}{_fmt(value)} is not one of {allowed}"
        if self.integer and value != int(value):
            return f"{self.letter}{_fmt(value)} must be a whole number"
        if self.minimum is not None and value < self.minimum:
            return f"{self.letter}{_fmt(value)} is below the minimum {_fmt(self.minimum)}"
        if self.maximum is not None and value > self.maximum:
            return f"{self.letter}{_fmt(value)} is above the maximum {_fmt(self.maximum)}"
        return None

    def reading(self, value: str | None) -> str:
        """What ``gclint explain`` says of this word written with ``value`` (as written, None for a letter
        alone): the phrase for that value, else ``says`` with the value in it."""
        if self.values is not None and value is not None and value in self.values:
            return self.values[value]
        return self.says.format(value=value)


@dataclass(frozen=True)
class Code:
    """A command code a dialect has.

    ``params`` is None when the parameters are not catalogued (any letter is accepted); otherwise it
    maps each accepted letter to its ``Param``.  ``supported`` is False for codes the dialect documents
    as not supported (Hyrel's G10/G11).  ``does`` (what the command does) and ``notes`` (what else to
    know about it) are what ``gclint explain`` says besides the words (``does`` usually before them,
    ``notes`` after).
    """

    code: str
    summary: str = ""
    params: Mapping[str, Param] | None = None
    supported: bool = True
    source: str = ""
    meanings: Mapping[str, str] | None = None  # letter -> meaning when ``params`` is not catalogued (explain)
    does: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()

    def param(self, letter: str) -> Param | None:
        return None if self.params is None else self.params.get(letter)

    def meaning(self, letter: str) -> str | None:
        """What parameter ``letter`` means, from the catalogue or the uncatalogued meanings."""
        param = self.param(letter)
        if param is not None and param.meaning:
            return param.meaning
        return self.meanings.get(letter) if self.meanings else None


def code(
    name: str,
    summary: str = "",
    *params: Param,
    source: str = "",
    supported: bool = True,
    open_params: bool = False,
    does: tuple[str, ...] = (),
    notes: tuple[str, ...] = (),
) -> Code:
    """Shorthand for a ``Code`` whose parameters are listed (``open_params`` leaves them unchecked)."""
    table = None if open_params else {p.letter: p for p in params}
    meanings = {p.letter: p.meaning for p in params} if open_params and params else None
    return Code(name, summary, table, supported, source, meanings, does, notes)


# code -> "summary", or ("summary", {"S": "meaning", ...}) (``describe``)
Descriptions = Mapping[str, str | tuple[str, Mapping[str, str]]]


def describe(codes_table: dict[str, Code], descriptions: Descriptions) -> dict[str, Code]:
    """Give codes of ``codes_table`` a summary and parameter meanings (what ``gclint explain`` prints).

    ``descriptions`` maps a code to ``"summary"`` or ``("summary", {"S": "meaning", ...})``.  Only codes
    already in the table are described (a description never adds a code), and a catalogued parameter
    table is left as it is.
    """
    out = dict(codes_table)
    for name, description in descriptions.items():
        existing = out.get(name)
        if existing is None:
            continue
        summary, meanings = (description, None) if isinstance(description, str) else description
        out[name] = replace(
            existing, summary=summary or existing.summary, meanings=dict(meanings) if meanings else existing.meanings
        )
    return out


def codes(names: Iterable[str] | str, summary: str = "") -> list[Code]:
    """Codes with no parameter catalogue, from a list or a space-separated string (``"M104 M109"``)."""
    if isinstance(names, str):
        names = names.split()
    return [Code(n, summary) for n in names]


def span(letter: str, first: int, last: int) -> str:
    """``span("M", 810, 819)`` -> ``"M810 M811 ... M819"``."""
    return " ".join(f"{letter}{i}" for i in range(first, last + 1))


try:  # CPython's own reading of a pattern, for the texts every match contains (a faster test first)
    from re import _parser as _sre_parse
except ImportError:  # pragma: no cover - another Python: every pattern is simply run
    _sre_parse = None


@cache
def _plan(pattern: str) -> tuple[re.Pattern[str], tuple[str, ...], bool, bool]:
    """How to test ``pattern`` quickly: the compiled pattern, the texts one of which every match contains
    (empty: no such test), whether that test ignores case, and whether every match lies within one line
    (no part of the pattern can match a line feed: then only the lines holding one of the texts are
    searched, ``HeadScan.found``)."""
    compiled = re.compile(pattern, re.MULTILINE)
    ignore_case = bool(compiled.flags & re.IGNORECASE)
    try:
        tree = _sre_parse.parse(pattern) if _sre_parse is not None else None
    except Exception:  # pragma: no cover - a pattern re compiled is parsed the same way
        tree = None
    if tree is None:  # pragma: no cover
        return compiled, (), ignore_case, False
    needed = _needed(list(tree), ignore_case)
    one_line = bool(needed) and not compiled.flags & re.DOTALL and _one_line(list(tree))
    return compiled, needed, ignore_case, one_line


def _needed(items: list, ignore_case: bool) -> tuple[str, ...]:
    """In a parsed sequence: the most selective required text (a run of literal characters, the longest),
    or else the texts one of which must occur (a branch whose alternatives each start with one, or each
    hold one; the run of literal characters before a branch joined to each alternative's start)."""
    p = _sre_parse
    options: list[tuple[str, ...]] = []
    run: list[str] = []
    for op, arg in [*items, (None, None)]:
        if op is p.LITERAL:
            run.append(chr(arg))
            continue
        before = "".join(run)
        if run:
            options.append((before,))
            run = []
        if op is p.SUBPATTERN:
            _group, add_flags, _del_flags, sub = arg
            if ignore_case or not add_flags & re.IGNORECASE:  # ((?i:...) in a case-sensitive pattern: no)
                options.append(_needed(list(sub), ignore_case))
        elif op is p.BRANCH:
            alternatives = [list(alternative) for alternative in arg[1]]
            leads = tuple(_lead(alternative) for alternative in alternatives)
            options.append(leads if all(leads) else ())
            if before and all(leads):  # ("\bESR|\bEngine" is read as \bE(?:SR|ngine): "ESR", "Engine")
                options.append(tuple(before + lead for lead in leads))
            inner = [_needed(alternative, ignore_case) for alternative in alternatives]
            if all(inner):
                options.append(tuple(dict.fromkeys(text for texts in inner for text in texts)))
    options = [o for o in options if o and min(map(len, o)) >= 2]
    return max(options, key=lambda o: (len(o) == 1, min(map(len, o))), default=())


_LF = 10  # (a line feed's code point)


def _one_line(items) -> bool:
    """Whether no part of a parsed sequence can match a line feed, nor an end of the text other than a
    line's end (so that searching a line alone finds what searching the whole text finds on that line).
    Conservative: a part it does not know answers False."""
    p = _sre_parse
    for op, arg in items:
        if op is p.LITERAL:
            if arg == _LF:
                return False
        elif op is p.NOT_LITERAL:
            if arg != _LF:
                return False
        elif op is p.ANY:
            continue  # (without DOTALL, which _plan rules out)
        elif op is p.IN:
            if not _set_without_line_feed(arg):
                return False
        elif op in (p.MAX_REPEAT, p.MIN_REPEAT, p.POSSESSIVE_REPEAT):
            if not _one_line(list(arg[2])):
                return False
        elif op is p.SUBPATTERN:
            _group, add_flags, del_flags, sub = arg
            if add_flags & re.DOTALL or del_flags & re.MULTILINE or not _one_line(list(sub)):
                return False
        elif op is p.ATOMIC_GROUP:
            if not _one_line(list(arg)):
                return False
        elif op is p.BRANCH:
            if not all(_one_line(list(alternative)) for alternative in arg[1]):
                return False
        elif op in (p.ASSERT, p.ASSERT_NOT):
            if not _one_line(list(arg[1])):
                return False
        elif op is p.AT:
            # ^ and $ are a line's in multi-line mode; \b, \B and \A read the text before the line too
            if arg not in (p.AT_BEGINNING, p.AT_END, p.AT_BOUNDARY, p.AT_NON_BOUNDARY, p.AT_BEGINNING_STRING):
                return False
        else:
            return False
    return True


def _set_without_line_feed(members) -> bool:
    """Whether a parsed character set (``[...]``, ``\\s``, ``\\w``) cannot match a line feed."""
    p = _sre_parse
    if members and members[0][0] is p.NEGATE:  # ([^...]: only one that names the line feed itself)
        return any(
            op is p.LITERAL and arg == _LF or op in (p.RANGE, p.RANGE_UNI_IGNORE) and arg[0] <= _LF <= arg[1]
            for op, arg in members[1:]
        )
    for op, arg in members:
        if op is p.LITERAL:
            if arg == _LF:
                return False
        elif op in (p.RANGE, p.RANGE_UNI_IGNORE):
            if arg[0] <= _LF <= arg[1]:
                return False
        elif op is p.CATEGORY:
            if arg not in (p.CATEGORY_DIGIT, p.CATEGORY_WORD, p.CATEGORY_NOT_SPACE, p.CATEGORY_NOT_LINEBREAK):
                return False
        else:
            return False
    return True


def _lead(alternative) -> str:
    """The literal characters an alternative of a branch starts with."""
    out = []
    for op, arg in alternative:
        if op is not _sre_parse.LITERAL:
            break
        out.append(chr(arg))
    return "".join(out)


class HeadScan:
    """The head of one file, asked by every dialect's ``Detection``: each pattern is tested once, and a
    pattern whose required text does not occur in the head is not run (most patterns, on most files)."""

    def __init__(self, head: str) -> None:
        self.head = head
        self._lowered: str | None = None
        self._ascii: bool | None = None
        self._seen: dict[str, str | None] = {}
        # where a required text of several patterns ("printer_model") first occurs (-1: nowhere)
        self._first: dict[tuple[str, bool], int] = {}

    @property
    def lowered(self) -> str:
        if self._lowered is None:
            self._lowered = self.head.lower()
        return self._lowered

    def matches(self, pattern: str) -> bool:
        return self.found(pattern) is not None

    def _first_at(self, needed: str, lowered: bool) -> int:
        """Where ``needed`` first occurs in the head (``lowered``: in the lowered head), -1 nowhere."""
        at = self._first.get((needed, lowered))
        if at is None:
            at = self._first[needed, lowered] = (self.lowered if lowered else self.head).find(needed)
        return at

    def _holds_text(self, needed: str, lowered: bool) -> bool:
        """Whether the head (``lowered``: the lowered head) holds ``needed``."""
        return self._first_at(needed, lowered) >= 0

    def found(self, pattern: str) -> str | None:
        """The text ``pattern`` matches first in the head (stripped, at most 80 characters, secrets masked:
        it is shown as evidence), or None."""
        if pattern in self._seen:
            return self._seen[pattern]
        compiled, needed, ignore_case, one_line = _plan(pattern)
        if needed:
            if ignore_case:
                needed = tuple(n.lower() for n in needed)
            if not any(self._holds_text(n, ignore_case) for n in needed):
                self._seen[pattern] = None
                return None
        if one_line and (not ignore_case or self._is_ascii()):
            m = self._search_lines(compiled, needed, ignore_case)
        else:
            m = compiled.search(self.head)
        found = self._seen[pattern] = None if m is None else (mask(m.group(0).strip())[:80] or m.group(0)[:80])
        return found

    def _is_ascii(self) -> bool:
        # (in ASCII text a match that ignores case holds a required text exactly as the lowered head does)
        if self._ascii is None:
            self._ascii = self.head.isascii()
        return self._ascii

    def _search_lines(self, compiled: re.Pattern[str], needed: tuple[str, ...], lowered: bool) -> re.Match | None:
        """``compiled.search(self.head)`` for a pattern whose every match lies within one line and holds one
        of ``needed`` (``_plan``): only stretches of whole lines from a line holding one are searched, in
        order (a header pattern that reads every comment line costs the head's length in a slow search, and
        a thumbnail is up to a megabyte of comment lines with none of the texts)."""
        head = self.head
        text = self.lowered if lowered else head
        nexts = {n: self._first_at(n, lowered) for n in needed}
        while True:
            at = min((i for i in nexts.values() if i >= 0), default=-1)
            if at < 0:
                return None
            start = head.rfind("\n", 0, at) + 1
            end = head.find("\n", max(at, start + _STRETCH))  # (a stretch of lines: one search, not one a line)
            if end < 0:
                end = len(head)
            m = compiled.search(head, start, end)
            if m is not None:
                return m
            for n, i in nexts.items():
                if 0 <= i < end:
                    nexts[n] = text.find(n, end)


_STRETCH = 4096  # (characters of lines searched at once from a line holding a required text)


@dataclass(frozen=True, eq=False)  # (each clue is one object: compared and hashed as itself, fast)
class Clue:
    """Content that marks a dialect: a command with ``code`` (or of command ``kind``) for which ``test``
    holds.  ``says`` is the reason shown to the user ("M6 T# O# declares a head's offsets");
    ``weight`` how strongly it marks the dialect (gclint.context weighs clues against each other).

    Codes that only this dialect's table has need no clue: gclint.context counts them from the tables.
    A clue is for what a table cannot say: a parameter only this dialect gives a code (``M109 H``), an
    address range, a kind of line (O-words, meta commands).  A use of a shared code that this dialect
    gives another meaning (Hyrel's ``M109 R`` is a tolerance, never a 215 °C target) is no clue for the
    others: it is a ``Habit``, a known mistake in this dialect's files.
    """

    says: str
    code: str | None = None
    kind: str | None = None
    test: Callable[[Any], bool] | None = None  # called with the Command
    weight: float = 3
    contains: str = ""  # one or two characters one of which the line must hold to be tried (a quick filter)

    def matches(self, cmd: Any) -> bool:
        if self.code is not None and cmd.code != self.code:
            return False
        if self.kind is not None and cmd.kind != self.kind:
            return False
        return self.test is None or bool(self.test(cmd))


def has_all(*letters: str) -> Callable[[Any], bool]:
    """Clue test: the command has every one of ``letters``."""
    return lambda cmd: all(letter in cmd.params for letter in letters)


def has_any(*letters: str) -> Callable[[Any], bool]:
    """Clue test: the command has at least one of ``letters``."""
    return lambda cmd: any(letter in cmd.params for letter in letters)


def value_at_least(letter: str, low: float, *, without: str = "") -> Callable[[Any], bool]:
    """Clue test: ``letter`` holds a number >= ``low`` (and none of the letters ``without`` is present)."""

    def test(cmd: Any) -> bool:
        value = cmd.get(letter)
        return value is not None and value >= low and not any(w in cmd.params for w in without)

    return test


@dataclass(frozen=True, eq=False)  # (each habit is one object, as a clue is)
class Habit:
    """A known mistake in this dialect's files: a habit of another firmware that a rule of this dialect
    exists to catch (a bare ``G28`` in a Hyrel job: HY025).  gclint.context counts it as a small cost for
    this dialect, never as evidence for the firmware the habit comes from: the file is this dialect's with
    a mistake in it, and ``rule`` reports it.

    A habit matches a command (``code``, ``kind``, ``test`` as a ``Clue``'s; ``test`` is called with the
    command and the state of the reading so far, whose fields are named in gclint.context.content:
    ``fan_range`` (an ``M106 C`` was seen), ``e_values`` (an ``M229 E1``), ``height_registers`` (the
    registers ``M660`` set)), or names a ``fact`` of the whole reading (``"e_amounts"``, ``"e_retract"``).
    """

    says: str
    rule: str
    code: str | None = None
    kind: str | None = None
    test: Callable[[Any, Any], bool] | None = None
    fact: str | None = None

    def matches(self, cmd: Any, state: Any) -> bool:
        if self.fact is not None:
            return False
        if self.code is not None and cmd.code != self.code:
            return False
        if self.kind is not None and cmd.kind != self.kind:
            return False
        return self.test is None or bool(self.test(cmd, state))


@dataclass(frozen=True)
class LineMark:
    """Raw lines that mark a dialect, matched before parsing (comments included): ``pattern`` is searched only
    in lines that contain ``contains``, so most lines cost one substring test.  ``weight`` is as a clue's."""

    contains: str
    pattern: str
    says: str
    weight: int = 6


@dataclass(frozen=True)
class Detection:
    """How ``--dialect auto`` recognises a file (gclint.context scores every candidate with it all):

    * ``patterns``: regular expressions over the file's head (multi-line mode), each with a weight:
      what the slicer or author wrote in comments (``;FLAVOR:Marlin``, ``generated by PrusaSlicer``);
    * ``clues``: content only this dialect has (see ``Clue``);
    * ``habits``: known mistakes in this dialect's files (see ``Habit``);
    * ``line_marks``: raw lines only this dialect has (``generic``: GRBL's ``$H``);
    * ``extensions``: file extensions typical of the dialect, used only to break a tie;
    * ``prior``: the score the dialect starts from before any evidence (Hyrel highest: it wins where the
      evidence ties; a firmware flavour below its dialect: it needs evidence).

    What a code the dialect's tables lack costs is the same for every dialect (gclint.context.score), apart
    from the codes its firmware runs without listing them (``Dialect.open_codes``).
    """

    patterns: tuple[tuple[str, int], ...] = ()
    extensions: tuple[str, ...] = ()
    extension_weight: int = 1
    clues: tuple[Clue, ...] = ()
    habits: tuple[Habit, ...] = ()
    line_marks: tuple[LineMark, ...] = ()
    prior: float = 0.0

    def header(self, scan: HeadScan) -> tuple[int, list[str]]:
        """The total weight of the header patterns found in the head, and the texts they matched."""
        total, texts = 0, []
        for pattern, weight in self.patterns:
            text = scan.found(pattern)
            if text is not None:
                total += weight
                texts.append(text)
        return total, texts

    def has_extension(self, path: str) -> bool:
        return bool(self.extensions) and path.lower().endswith(self.extensions)


_GENERIC_SEMANTICS = Semantics(dwell=DWELL_UNKNOWN)


@dataclass(frozen=True)
class Dialect:
    """A G-code dialect: the codes it has and how its files look.

    ``family`` groups dialects that share semantics (``"hyrel"``, ``"reprap"``, ``"linuxcnc"``).
    ``extended_commands`` accepts Klipper-style ``NAME KEY=VALUE`` commands; ``meta_commands`` accepts
    RepRapFirmware's ``if``/``var``/``echo``...; ``owords`` accepts LinuxCNC O-words and ``#`` parameters;
    ``words`` are command words the dialect accepts without having those (Smoothieware's console ``echo``
    on Carvera), upper case.  ``not_move_words`` are letters a move never carries in this dialect
    (Machinekit: E, its extruder is the A axis).
    ``open_codes`` is a predicate for codes the dialect accepts without listing them (user M-codes,
    macros).  ``unknown_severity`` is how serious an unknown code is on this firmware.

    ``semantics`` is what the words of a line make its machine do (gclint.dialects.semantics): every reader of
    meaning asks it, none tests the dialect's name.  ``family`` groups dialects whose rules are shared (the HY
    rules run on the ``hyrel`` family): ask ``runs_rules_of``.  ``known`` is False for ``generic``, the reading
    of a file no known dialect explains (parsing, security and dialect-free rules only).
    """

    name: str
    title: str
    family: str
    codes: Mapping[str, Code]
    aliases: tuple[str, ...] = ()
    detection: Detection = Detection()
    extended_commands: bool = False
    meta_commands: bool = False
    owords: bool = False
    words: frozenset[str] = frozenset()
    not_move_words: str = ""
    open_codes: Callable[[str], bool] | None = None
    unknown_severity: str = "warning"
    # what the firmware does with a code it does not have (explain), ``{code}`` and ``{title}`` filled in
    unknown_note: str = "{title} does not list {code}: the firmware skips it (or runs a macro of that name)"
    description: str = ""
    sources: tuple[str, ...] = ()
    extras: Mapping[str, object] = field(default_factory=dict)
    semantics: Semantics = field(default_factory=lambda: _GENERIC_SEMANTICS)
    known: bool = True
    console: bool = False  # the firmware runs a bare word as a console command (Smoothieware)
    machine_ini: bool = False  # the machine's INI file defines codes (LinuxCNC's REMAP=): they are known codes
    meta_keywords: frozenset[str] = frozenset()  # the words of its meta commands (RepRapFirmware's if, var...)
    # the firmware's own files, which configure it and may write files on purpose (RepRapFirmware's sys/ and
    # macros/): ``macro_file(path)`` any of them, ``system_file(path)`` the system files proper
    macro_file: Callable[[str], bool] | None = None
    system_file: Callable[[str], bool] | None = None
    variant_of: str | None = None  # another dialect's version (hyrel-v4 of hyrel): detection decides it after

    def runs_rules_of(
        self, families: tuple[str, ...] | None, code: str = "", names: tuple[str, ...] | None = None
    ) -> bool:
        """Whether a rule (``code``) written for ``families`` (None: every dialect) or for the dialects called
        ``names`` checks this dialect's files.  A ``generic`` file gets no HY or DL rule: nothing says which
        machine's tables apply."""
        if not self.known and code[:2] in ("HY", "DL"):
            return False
        if names is not None and self.name not in names:
            return False
        return families is None or self.family in families

    def related(self) -> tuple[str, ...]:
        """The names of the dialects whose files this one's checks read alike (its family)."""
        from gclint import dialects

        return tuple(d.name for d in dialects.all_dialects() if d.family == self.family)

    def accepts(self, kind: str, code: str | None) -> bool:
        """Whether the dialect has a command of this kind and code (see syntax.nodes for kinds)."""
        if kind in ("gcode", "text"):
            return code is not None and self.knows(code)
        if kind == "extended":
            return self.extended_commands or (code is not None and code.upper() in self.words)
        if kind == "meta":
            return self.meta_commands or (code is not None and code.upper() in self.words)
        if kind in ("oword", "assignment"):
            return self.owords
        return True

    def knows(self, code: str) -> bool:
        if code in self.codes:
            return True
        return self.open_codes is not None and self.open_codes(code)

    def spec(self, code: str) -> Code | None:
        return self.codes.get(code)

    def derive(
        self, name: str, title: str, *, add: Iterable[Code] = (), remove: Iterable[str] = (), **changes
    ) -> Dialect:
        """A new dialect that is this one plus ``add`` minus ``remove`` (codes), with other fields changed."""
        table = dict(self.codes)
        for removed in remove:
            table.pop(removed, None)
        for c in add:
            table[c.code] = c
        return replace(self, name=name, title=title, codes=table, **changes)


def table(*groups: Iterable[Code] | Code) -> dict[str, Code]:
    """Build a code table from codes and lists of codes (later entries replace earlier ones)."""
    out: dict[str, Code] = {}
    for group in groups:
        if isinstance(group, Code):
            out[group.code] = group
        else:
            for c in group:
                out[c.code] = c
    return out


def _fmt(value: float) -> str:
    return str(int(value)) if value == int(value) else f"{value:g}"
