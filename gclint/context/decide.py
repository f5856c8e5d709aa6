"""Weigh the evidence: which dialect a file is, which Hyrel firmware version, which printer model.

The order of strength (DESIGN.md, "Dialect names"):

1. what the user said: ``--dialect``/``--printer``, the configuration, a ``; gclint: dialect=`` line;
2. content only one dialect has: clues (``M6 T# O#``, ``M109 H``, ``M109 T40``, O-words, meta commands...),
   uses a dialect would never write (Hyrel's ``M109 R215``), and codes that some dialects' tables have
   and others' do not;
3. the slicer header (``;FLAVOR:``, ``; gcode_flavor =``, ``SLIC3R_GCODE_FLAVOR``), which loses to clear
   content (and the context says so);
4. the file extension, only to break a tie (``.gcode`` says nothing: every firmware uses it);
5. nothing: ``hyrel``, the first target.

Dialects that read each other's files are weighed as a group first (content tells a Hyrel job from a
RepRap-family one from a CNC program clearly), then within the group (Marlin or RepRapFirmware; Machinekit
or Carvera), where the slicer header and the extension know better than the code tables.

Hyrel v4 or v5 comes from the addresses the file uses (each number votes for the numbering in which it
fits its commands), ``M116`` and ``W0`` (v5 only).  The model comes from what the job says about the
machine: declared heads (``M6 T# O#``), a second yoke, A/B axes, the lathe, model-specific aux ports.

The flavour of a Marlin-flavour file (the firmware it was written for: Prusa Buddy, Prusa MK3, Bambu,
Klipper; gclint.firmware) comes from the slicer's settings, in the head or at the end of the file
(``; printer_model = MK4S``, ``M862.3 P "MK4S"``, ``; gcode_flavor = klipper``), and from commands only that
firmware has (Klipper's ``NAME KEY=VALUE``).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from functools import cache

from gclint import dialects, firmware
from gclint.context.content import ContentReading, candidates, read_content
from gclint.context.model import (
    CONFIGURATION,
    CONTENT,
    DEFAULT,
    DIRECTIVE,
    EXPLICIT,
    EXTENSION,
    HEADER,
    NONE,
    OPTION,
    STRONG,
    WEAK,
    Context,
)
from gclint.dialects.addressing import HEAD, RESERVED, fits, resolve_v4_command, resolve_v4_variable, resolve_v5
from gclint.dialects.base import HeadScan
from gclint.machine.profiles import PROFILES

_DIRECTIVE = re.compile(r"(?im)^[^\n]*[;(]\s*gclint:\s*dialect\s*=\s*([^\s;)]+)")

# PrusaSlicer/SuperSlicer/OrcaSlicer gcode_flavor values (SLIC3R_GCODE_FLAVOR, "; gcode_flavor = ...").
SLICER_FLAVORS = {
    "marlin": "marlin",
    "marlin2": "marlin",
    "marlinlegacy": "marlin",
    "reprap": "marlin",  # "RepRap/Sprinter": Marlin-like
    "repetier": "marlin",
    "teacup": "marlin",
    "makerware": "marlin",
    "sailfish": "marlin",
    "klipper": "marlin",
    "smoothie": "marlin",
    "sprinter": "marlin",
    "no-extrusion": "marlin",
    "mach3": "marlin",
    "reprapfirmware": "reprap",
    "machinekit": "machinekit",
    "hyrel": "hyrel",
}
_ENV_WEIGHT = 10
_DECIDES = 3  # content decides against the slicer header from this lead on (one clue, two codes...)
_STRONG = 4  # ... and is strong from here, when it leads the runner-up by _LEAD and nothing disagrees
_LEAD = 3
_LEANS = 2  # less content than this (one weak clue) is as good as none: the extension or the default decide
MODEL_ORDER = ("30m", "esr", "ehr", "16a", "16a-dual")  # the simplest model that fits the job wins

_GROUP_OF_FAMILY = {"hyrel": "hyrel", "reprap": "reprap", "linuxcnc": "cnc", "smoothie": "cnc"}
_GROUP_LABEL = {"hyrel": "Hyrel's", "reprap": "Marlin/RepRap-like", "cnc": "a CNC program's"}
_GENERIC = (".gcode", ".gco")  # every firmware's files: they tell Marlin from RepRapFirmware at most

Evidence = list[tuple[int, int, str]]  # (weight, line, text)


def infer(
    head: str,
    path: str = "",
    *,
    dialect: str = "auto",
    dialect_origin: str = OPTION,
    printer: str | None = None,
    printer_origin: str = OPTION,
    flavor: str | None = None,
    flavor_origin: str = OPTION,
    env_flavor: str | None = None,
    complete: bool = True,
    tail: str | None = None,
) -> Context:
    """The context of the file whose beginning is ``head`` (``complete``: the whole file; ``tail``: the
    end of a longer file, whole lines; the flavour reads it too).

    ``dialect`` is a dialect name or ``auto``; ``printer`` a model name or None (infer it); ``flavor`` the
    firmware the user declared (``klipper``; None: read it from the file), which also says the dialect when
    nobody else does.  The ``*_origin`` arguments say where an explicit value came from (``option`` or
    ``configuration``).
    """
    declared = _declared(flavor)
    told = (f"--flavor {flavor}" if flavor_origin == OPTION else f"flavor = {flavor} in the configuration",)
    scan = HeadScan(head)
    reading: ContentReading | None = None

    def content() -> ContentReading:
        nonlocal reading
        if reading is None:
            reading = read_content(head, complete, tail)
        return reading

    directive, unknown = _directive(scan)
    notes = (f"'; gclint: dialect={unknown}' names no dialect: ignored",) if unknown else ()
    if dialect != "auto":  # the user's word beats the file's: a job does not choose how the gate reads it
        name, origin, reasons, strength, conflict = dialects.get(dialect).name, dialect_origin, (), EXPLICIT, ""
        if directive is not None and directive != name:
            told_by = "--dialect" if dialect_origin == OPTION else "dialect in the configuration"
            conflict = f"its '; gclint: dialect={directive}' line is ignored: {told_by} says {name}"
    elif directive is not None:
        name, origin, reasons, strength, conflict = directive, DIRECTIVE, (), EXPLICIT, ""
    elif declared is not None:  # the firmware's files are its dialect's
        name, origin, reasons, strength, conflict = declared.dialect, flavor_origin, told, EXPLICIT, ""
    else:
        name, origin, reasons, strength, conflict = _weigh(
            scan, content(), path, env_flavor, HeadScan(tail) if tail else None
        )
    if notes:  # a directive that names nothing is shown, as weak evidence is
        conflict = "; ".join((*notes, conflict)) if conflict else notes[0]
    if declared is not None and declared.dialect != name:
        ignored = f"{told[0]} is a firmware for {declared.dialect} files, and this one is read as {name}: ignored"
        conflict = f"{conflict}; {ignored}" if conflict else ignored
    if dialects.get(name).family != "hyrel":
        if declared is not None and declared.dialect == name:
            found, flavor_reasons = declared.name, told
        else:
            found, flavor_reasons = _flavor(scan, HeadScan(tail) if tail else None, content, name)
        return Context(name, origin, strength, reasons, conflict, flavor=found, flavor_reasons=flavor_reasons)

    firmware, firmware_origin, firmware_reasons, evidence = _version(content(), name, origin)
    name = "hyrel-v4" if firmware == 4 else "hyrel"
    model, model_origin, model_reasons, fitting = _model(content(), firmware, printer, printer_origin)
    return Context(
        name,
        origin,
        strength,
        reasons,
        conflict,
        firmware=firmware,
        firmware_origin=firmware_origin,
        firmware_reasons=firmware_reasons,
        version_evidence=evidence,
        printer=model,
        printer_origin=model_origin,
        printer_reasons=model_reasons,
        printer_candidates=fitting,
    )


def _declared(flavor: str | None) -> firmware.Firmware | None:
    return firmware.get(flavor) if flavor is not None else None


_FAR = 1 << 20  # how far to read when the head is mostly comments (a slicer's thumbnail images)


def infer_source(source, path: str | None = None, **options) -> Context:
    """The context of a ``gclint.syntax.source.Source`` (not consumed): its head, read on past comment
    blocks such as thumbnails, and the tail of a regular file (slicers' end code, Hyrel's footer)."""
    head = source.head_text()
    limit = len(head)
    while not source.head_is_whole and limit < _FAR and _mostly_comments(head):
        limit = min(_FAR, limit * 4)  # past the comment block, in steps (thumbnails are 10 KB to 1 MB)
        head = source.head_text(limit)
    return infer(
        head,
        source.display if path is None else path,
        complete=source.head_is_whole,
        tail=source.tail_text(),
        **options,
    )


def _mostly_comments(text: str) -> bool:
    comments = sum(len(line) for line in text.splitlines() if line.lstrip()[:1] in (";", "("))
    return comments > 0.75 * len(text)


def _directive(scan: HeadScan) -> tuple[str | None, str | None]:
    """(the dialect a ``; gclint: dialect=NAME`` line names, the name when it names none)."""
    if "gclint" not in scan.lowered:
        return None, None
    m = _DIRECTIVE.search(scan.head)
    if m is None:
        return None, None
    try:
        return dialects.get(m.group(1)).name, None
    except dialects.UnknownDialect:
        return None, m.group(1)[:40]


# -- the dialect ---------------------------------------------------------------------------------------


class _Points:
    """Content points per group of dialects, and per dialect within its group."""

    def __init__(self, reading: ContentReading) -> None:
        table = {d.name: d for d in candidates()}
        self.names = list(table)
        self.group_of = {n: _GROUP_OF_FAMILY.get(table[n].family, n) for n in self.names}
        self.groups = list(dict.fromkeys(self.group_of.values()))
        self.group: dict[str, Evidence] = {g: [] for g in self.groups}
        self.member: dict[str, Evidence] = {n: [] for n in self.names}
        counted: set[tuple[str, str]] = set()
        for name, found in reading.clues.items():
            for clue, seen in found.items():
                text = f"{seen}: {clue.says}"
                if clue.against:  # a mark for every other dialect that has the code
                    gainers = {self.group_of[m] for m in self.names if m != name and _has(table[m], clue.code)}
                else:
                    gainers = {self.group_of[name]}
                    self.member[name].append((clue.weight, seen.line, text))
                for g in gainers:
                    if (g, clue.says) not in counted:
                        counted.add((g, clue.says))
                        self.group[g].append((clue.weight, seen.line, text))
        if reading.e_amounts is not None:
            # "Hyrel ignores E amounts unless M229 E1 D1" (DESIGN.md key facts; Gcode page, M229): a job
            # metering E before any M229 E1 was written for a firmware that uses E amounts
            self.group["reprap"].append(
                (2, reading.e_amounts.line, f"{reading.e_amounts}: E amounts with no M229 E1 (Hyrel ignores them)")
            )
        for code, seen in reading.codes.items():
            knowers = [m for m in self.names if _has(table[m], code)]
            groups = list(dict.fromkeys(self.group_of[m] for m in knowers))
            if groups and len(groups) < len(self.groups):  # a code some groups have and others do not
                weight = 2 if len(groups) == 1 else 1
                for g in groups:
                    self.group[g].append((weight, seen.line, f"{seen}: {_who_has(code, groups, self.groups)}"))
            for g in groups:  # ... and within a group
                members = [m for m in self.names if self.group_of[m] == g]
                missing = [m for m in members if m not in knowers]
                if missing:
                    for m in members:
                        if m in knowers:
                            self.member[m].append(
                                (1, seen.line, f"{seen}: {code} is not a {' or '.join(missing)} code")
                            )

        self.reading, self.table = reading, table

    def misfit(self, name: str) -> str | None:
        """What in the content ``name`` would never have: a code its table lacks and another dialect's has,
        or a word its moves do not carry (Machinekit's E); None when it fits."""
        dialect = self.table[name]
        for code, seen in self.reading.codes.items():
            if not (dialect.knows(code) or _has(dialect, code)) and any(
                _has(other, code) for other in self.table.values()
            ):
                return f"{seen}: {code} is not a {name} code"
        moves = self.reading.e_moves
        if moves is not None and "E" in dialect.not_move_words:
            return f"{moves}: E is not a word of {name} moves"
        return None

    @staticmethod
    def score(evidence: Evidence) -> int:
        return sum(weight for weight, _, _ in evidence)


def _has(dialect: dialects.Dialect, code: str | None) -> bool:
    """Whether ``dialect`` has ``code``: in its table, or in the inventory of a firmware whose files it
    reads (Bambu's M620 is a Marlin-flavour code, not only Hyrel's)."""
    return code in dialect.codes or code in _flavor_codes(dialect.name)


@cache
def _flavor_codes(name: str) -> frozenset[str]:
    return frozenset().union(*(f.codes for f in firmware.flavors_of(name) if f.marks_dialect))


def _who_has(code: str, having: list[str], groups: list[str]) -> str:
    label = {"hyrel": "Hyrel", "reprap": "Marlin/RepRap", "cnc": "CNC (Machinekit/LinuxCNC, Carvera)"}
    if len(having) == 1:
        return f"only {label.get(having[0], having[0])} dialects have {code}"
    missing = [label.get(g, g) for g in groups if g not in having]
    return f"{code} is not a {' or '.join(missing)} code"


def _weigh(
    scan: HeadScan, reading: ContentReading, path: str, env_flavor: str | None, tail: HeadScan | None = None
) -> tuple[str, str, tuple[str, ...], str, str]:
    """(dialect, origin, reasons, strength, conflict) when nobody said which dialect."""
    points = _Points(reading)
    names, groups, group_of = points.names, points.groups, points.group_of
    header, header_texts = _header_scores(scan, env_flavor, tail)
    header_best = max(names, key=lambda n: header[n]) if any(header.values()) else None
    header_group = group_of[header_best] if header_best is not None else None

    scores = {g: points.score(points.group[g]) for g in groups}
    best = max(scores.values())
    top = [g for g in groups if scores[g] == best]
    lead = best - max((scores[g] for g in groups if g not in top), default=0) if len(top) == 1 else 0
    conflict = ""
    if header_group is not None and (header_group in top or lead < _DECIDES):
        # the slicer header decides among what the content leaves open (content wins only when clear)
        group, origin = header_group, HEADER
        reasons = tuple(header_texts[header_best][:2])  # type: ignore[index]
        agree = best > 0 and header_group in top
        if agree:
            reasons += _top_reasons(points.group[group], 2)
        elif lead > 0:
            conflict = f"the content leans to {_GROUP_LABEL[top[0]]} ({_top_reasons(points.group[top[0]], 1)[0]}), less than the slicer header"
        strength = STRONG if (agree and best >= _DECIDES) or (header[header_best] >= 8 and not lead) else WEAK  # type: ignore[index]
    elif best >= _LEANS and len(top) == 1:
        # content that leans one way beats the extension and the default: the extension only breaks ties
        group, origin = top[0], CONTENT
        reasons = _top_reasons(points.group[group])
        if header_group is not None:
            conflict = (
                f"the slicer says {header_best} ({header_texts[header_best][0]}), but the content is "  # type: ignore[index]
                f"{_GROUP_LABEL[group]}: content wins"
            )
        strength = STRONG if best >= _STRONG and lead >= _LEAD and not conflict else WEAK
    else:
        pool = top if best >= _LEANS else groups  # a tie: the extension may break it, among the tied only
        named = [
            n
            for n in names
            if group_of[n] in pool
            and dialects.get(n).detection.has_extension(path)
            and not path.lower().endswith(_GENERIC)
        ]
        # content that rules a dialect out rules out its extension too (a Hyrel job saved as .nc)
        misfits = {n: points.misfit(n) for n in named}
        by_extension = [n for n in named if misfits[n] is None]
        if named and not by_extension:
            conflict = "; ".join(
                f"the extension {_extension(path)} is {n}'s, but {misfits[n]}: not read as {n}" for n in named
            )
        if len(by_extension) == 1:
            group, origin = group_of[by_extension[0]], EXTENSION
            reasons = (f"the extension {_extension(path)}",) + _top_reasons(points.group[group], 2)
        elif best >= _LEANS:
            group, origin = ("hyrel" if "hyrel" in top else top[0]), CONTENT
            reasons = _top_reasons(points.group[group])
        else:
            return "hyrel", DEFAULT, (), NONE, conflict
        strength = WEAK
    return _member(points, group, header, header_texts, path, origin, reasons, strength, conflict)


def _member(
    points: _Points,
    group: str,
    header: dict[str, int],
    header_texts: dict[str, list[str]],
    path: str,
    origin: str,
    reasons: tuple[str, ...],
    strength: str,
    conflict: str,
) -> tuple[str, str, tuple[str, ...], str, str]:
    """Choose the dialect within ``group``: the slicer header, else a clear lead in clues only one member
    has, else the extension, else codes only one member's table has, else the first member."""
    members = [n for n in points.names if points.group_of[n] == group]
    if len(members) == 1:
        return members[0], origin, reasons, strength, conflict
    clues = {m: sum(w for w, _, text in points.member[m] if " is not a " not in text) for m in members}
    leader = max(members, key=lambda m: clues[m])
    clear_lead = all(clues[leader] - clues[m] >= 3 for m in members if m != leader)
    named = [m for m in members if header[m] > 0]
    if named and not (clear_lead and leader not in named):
        choice = max(named, key=lambda m: header[m])
        extra = (f"the slicer header ({header_texts[choice][0]}) names {choice}",) if origin != HEADER else ()
        return choice, origin, _unique(reasons[:2] + extra + reasons[2:]), strength, conflict
    if clear_lead:
        return leader, origin, _unique(reasons + _top_reasons(points.member[leader], 1)), strength, conflict
    own = {m: points.score(points.member[m]) for m in members}
    best = max(own.values())
    tied = [m for m in members if own[m] >= best - 1]  # the tables are not exact: a point is a tie
    by_extension = [m for m in tied if dialects.get(m).detection.has_extension(path)]
    if len(by_extension) == 1:  # (the group's evidence stands: the extension only names the member)
        return by_extension[0], origin, _unique(reasons + (f"the extension {_extension(path)}",)), strength, conflict
    top = max(members, key=lambda m: own[m])
    return top, origin, _unique(reasons + _top_reasons(points.member[top], 1)), WEAK, conflict


def _unique(texts: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(dict.fromkeys(texts))


def _top_reasons(evidence: Evidence, count: int = 3) -> tuple[str, ...]:
    """The strongest pieces of evidence, earliest first among equals (the file's tail last)."""
    ranked = sorted(evidence, key=lambda e: (-e[0], e[1] or 1 << 40))
    return _unique(tuple(text for _, _, text in ranked))[:count]


def scores(
    head: str, path: str = "", env_flavor: str | None = None, complete: bool = True, tail: str | None = None
) -> dict[str, dict]:
    """Every group's and dialect's content points and the header's (for ``gclint check -v`` and tests)."""
    points = _Points(read_content(head, complete, tail))
    header, texts = _header_scores(HeadScan(head), env_flavor)
    groups = {
        g: {"content": points.score(points.group[g]), "evidence": _top_reasons(points.group[g], 5)}
        for g in points.groups
    }
    members = {
        n: {"own": points.score(points.member[n]), "header": header[n], "header_texts": texts[n]} for n in points.names
    }
    return {"groups": groups, "dialects": members}


def _header_scores(
    scan: HeadScan, env_flavor: str | None, tail: HeadScan | None = None
) -> tuple[dict[str, int], dict[str, list[str]]]:
    """The slicer's word on the dialect: header patterns in the head, or in the settings slicers write at
    the end of the file (PrusaSlicer's ``; gcode_flavor = marlin2``), and SLIC3R_GCODE_FLAVOR."""
    scores: dict[str, int] = {}
    texts: dict[str, list[str]] = {}
    for dialect in candidates():
        score, found = dialect.detection.header(scan)
        if not score and tail is not None:
            score, found = dialect.detection.header(tail)
            found = [text + _AT_END for text in found]
        scores[dialect.name], texts[dialect.name] = score, found
    if env_flavor:
        mapped = SLICER_FLAVORS.get(env_flavor.strip().lower())
        if mapped is not None:
            scores[mapped] += _ENV_WEIGHT
            texts[mapped].insert(0, f"SLIC3R_GCODE_FLAVOR={env_flavor.strip()}")
    return scores, texts


def _extension(path: str) -> str:
    dot = path.rfind(".")
    return path[dot:] if dot > path.replace("\\", "/").rfind("/") else ""


def slicer_flavor(name: str) -> str | None:
    """The dialect name for a slicer's gcode_flavor value, or None."""
    return SLICER_FLAVORS.get(name.strip().lower())


# -- the flavour -------------------------------------------------------------------------------------------

_FLAVOR_DECIDES = 4  # one printer_model line (8) decides; BambuStudio's name alone (2) does not
_AT_END = " (in the settings at the end of the file)"


def _flavor(
    scan: HeadScan, tail: HeadScan | None, content: Callable[[], ContentReading], dialect: str
) -> tuple[str | None, tuple[str, ...]]:
    """The firmware the file was written for, among the flavours of ``dialect``, and why: the one whose
    marks weigh most (a tie decides nothing)."""
    flavors = firmware.flavors_of(dialect)
    if not flavors:
        return None, ()
    scored: list[tuple[int, str, Evidence]] = []
    for fw in flavors:
        evidence: Evidence = []
        for pattern, weight in fw.detection.patterns:
            text = scan.found(pattern)
            if text is None and tail is not None and (text := tail.found(pattern)) is not None:
                text += _AT_END
            if text is not None:
                evidence.append((weight, 0, text))
        for clue, seen in content().flavor_clues.get(fw.name, {}).items():
            evidence.append((clue.weight, seen.line, f"{seen}: {clue.says}"))
        score = sum(weight for weight, _, _ in evidence)
        if score:
            scored.append((score, fw.name, evidence))
    scored.sort(key=lambda s: -s[0])
    if not scored or scored[0][0] < _FLAVOR_DECIDES or (len(scored) > 1 and scored[1][0] == scored[0][0]):
        return None, ()
    return scored[0][1], _top_reasons(scored[0][2], 2)


# -- Hyrel v4 or v5 --------------------------------------------------------------------------------------


def _version(reading: ContentReading, name: str, origin: str) -> tuple[int, str, tuple[str, ...], int | None]:
    """(firmware, origin, reasons, what the addresses say) for a Hyrel file.

    Each distinct number votes once: for v4 when some command it is used with fits it in v4 numbering
    and none in v5, for v5 the other way round (one wrong head number on three commands is one vote).
    """
    uses: dict[int, list[tuple[bool, bool, str]]] = {}  # number -> (fits v4, fits v5, what)
    for (code, letter, number), seen in reading.addresses.items():
        if letter == "S":  # M703/M704 S: v4 an alias (a device), v5 a squad 30-39 or a head
            old, new = resolve_v4_variable(number).kind == HEAD, 30 <= number <= 39 or _v5_head(number)
        else:
            old, new = fits(code, resolve_v4_variable(number)), _v5_fits(code, number)
        uses.setdefault(number, []).append(
            (old, new, f"{seen}: T{number} {'is a v4 device address' if old else 'fits v5'}")
        )
    for number, seen in reading.tool_commands.items():
        old = resolve_v4_command(number).kind != RESERVED
        new = resolve_v5(number).kind != RESERVED and (number > 19 or _v5_head(number))
        uses.setdefault(number + 1000, []).append(
            (old, new, f"{seen}: {'a v4 tool number' if old else 'a v5 address'}")
        )
    v4: list[tuple[int, str]] = []
    v5: list[tuple[int, str]] = []
    for number_uses in uses.values():
        only_v4 = [what for old, new, what in number_uses if old and not new]
        only_v5 = [what for old, new, what in number_uses if new and not old]
        if only_v4 and not only_v5:
            v4.append((0, only_v4[0]))
        elif only_v5 and not only_v4:
            v5.append((0, only_v5[0]))
    for seen, what in ((reading.m116, "M116 exists from v5"), (reading.waits_w0, "W0 exists from v5")):
        if seen is not None:  # "[v5+]" on the Gcode page: worth two addresses each
            v5.extend([(0, f"{seen}: {what}")] * 2)
    evidence = 4 if len(v4) > len(v5) else 5 if len(v5) > len(v4) else None
    reasons_of = {4: v4, 5: v5}
    if name == "hyrel-v4" or (name == "hyrel" and origin in (OPTION, CONFIGURATION, DIRECTIVE)):
        firmware = 4 if name == "hyrel-v4" else 5
        return firmware, origin, (), evidence
    firmware = evidence or 5
    reasons = tuple(dict.fromkeys(text for _, text in reasons_of[firmware]))[:3]
    against = reasons_of[9 - firmware]
    if against:
        reasons += (f"{len(against)} address{'es' if len(against) != 1 else ''} read as v{9 - firmware}",)
    return firmware, CONTENT if evidence else DEFAULT, reasons, evidence


def _v5_head(number: int) -> bool:
    # T10-T19 are heads of a third and fourth yoke, which no model gclint knows has (T_v5 chart)
    return 0 <= number <= 9


def _v5_fits(code: str, number: int) -> bool:
    address = resolve_v5(number)
    if address.kind == HEAD and not _v5_head(number):
        return False
    return fits(code, address)


# -- the printer model -----------------------------------------------------------------------------------


def _model(
    reading: ContentReading, firmware: int, printer: str | None, printer_origin: str
) -> tuple[str, str, tuple[str, ...], tuple[str, ...]]:
    """(model, origin, reasons, every model the job fits) for a Hyrel file."""
    if printer is not None:
        return printer, printer_origin, (), (printer,)
    needs: list[tuple[str, object]] = []  # (what the job says, test on a profile)
    resolve = resolve_v4_variable if firmware == 4 else resolve_v5
    positions = {
        address.position: seen
        for number, seen in reading.declarations.items()
        if (address := resolve(number)).position is not None
    }
    if positions:
        top = max(positions)
        needs.append((f"{positions[top]}: declares a head at T{top}", lambda p, top=top: top in p.positions))
    # a second yoke: its group address (v5 T42, v4 T20), or a head on it (T5-T9) addressed by the job
    yoke2_group = 20 if firmware == 4 else 42
    resolve_command = resolve_v4_command if firmware == 4 else resolve_v5
    yoke2 = [seen for (_code, letter, n), seen in reading.addresses.items() if letter == "T" and n == yoke2_group]
    yoke2 += [
        seen
        for (_code, letter, n), seen in reading.addresses.items()
        if letter == "T" and 5 <= (resolve(n).position if resolve(n).position is not None else -1) <= 9
    ]
    yoke2 += [seen for n, seen in reading.tool_commands.items() if 5 <= (resolve_command(n).position or -1) <= 9]
    if yoke2:
        first = min(yoke2, key=lambda s: s.line or 1 << 40)
        needs.append((f"{first}: addresses a head on a second yoke", lambda p: p.max_position >= 9))
    if reading.rotary_axes is not None:
        needs.append((f"{reading.rotary_axes}: uses an A/B axis", lambda p: "A" in p.axes))
    if reading.lathe is not None:
        needs.append((f"{reading.lathe}: runs the lathe", lambda p: p.lathe))
    for code, seen in reading.aux_codes.items():
        needs.append((f"{seen}: {code} exists on some models only", lambda p, code=code: code in p.aux_codes))
    if not needs:
        return MODEL_ORDER[0], DEFAULT, (), (MODEL_ORDER[0],)
    profiles = [PROFILES[n] for n in MODEL_ORDER]
    met = {p.name: sum(1 for _, test in needs if test(p)) for p in profiles}  # type: ignore[operator]
    most = max(met.values())
    fitting = tuple(p.name for p in profiles if met[p.name] == most)
    best = PROFILES[fitting[0]]
    unmet = [what for what, test in needs if not test(best)]  # type: ignore[operator]
    reasons = tuple(what for what, test in needs if test(best))[:2]  # type: ignore[operator]
    if unmet:  # no model fits everything the job says: the default, and why
        return MODEL_ORDER[0], DEFAULT, (f"no model fits everything: {unmet[0]}",), (MODEL_ORDER[0],)
    if len(fitting) == len(MODEL_ORDER):  # every model fits: the job tells nothing about the model
        return MODEL_ORDER[0], DEFAULT, (), (MODEL_ORDER[0],)
    return best.name, CONTENT, reasons, fitting


__all__ = ["infer", "infer_source", "slicer_flavor", "scores", "SLICER_FLAVORS"]
