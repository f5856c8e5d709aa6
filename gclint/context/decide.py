"""Weigh the evidence: which dialect a file is, which Hyrel firmware version, which printer model.

The order of strength (DESIGN.md, "Dialect names"):

1. what the user said: ``--dialect``/``--printer``, the configuration, a ``; gclint: dialect=`` line;
2. content only one dialect has: clues (``M6 T# O#``, ``M109 H``, ``M109 T40``, O-words, meta commands,
   ``M109 R215``...) and codes that some dialects' tables have and others' do not;
3. the slicer header (``;FLAVOR:``, ``; gcode_flavor =``, ``SLIC3R_GCODE_FLAVOR``), which loses to clear
   content (and the context says so);
4. the file extension, only to break a tie (``.gcode`` says nothing: every firmware uses it);
5. nothing: ``hyrel``, the first target.

Hyrel v4 or v5 comes from the addresses the file uses (a number that fits a command in one numbering
and not in the other), ``M116`` and ``W0`` (v5 only).  The model comes from what the job says about the
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
from gclint.context.content import ContentReading, Seen, candidates, read_content
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
from gclint.dialects.addressing import HEAD, fits, resolve_v4_command, resolve_v4_variable, resolve_v5
from gclint.dialects.base import HeadScan
from gclint.machine.profiles import PROFILES, PrinterProfile

_DIRECTIVE = re.compile(r"(?im)^[^\n]*[;(]\s*gclint:\s*dialect\s*=\s*([\w.-]+)")

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
_DECIDES = 3  # content decides from this score on (a clue, or two codes only one group has)
_STRONG = 4  # ... and is strong from here, when it leads the runner-up by _LEAD
_LEAD = 3
_LEANS = 2  # below _DECIDES, content still beats the default from here (weakly): a bare G28, one odd code
MODEL_ORDER = ("30m", "esr", "ehr", "16a", "16a-dual")  # the simplest model that fits the job wins


def infer(
    head: str,
    path: str = "",
    *,
    dialect: str = "auto",
    dialect_origin: str = OPTION,
    printer: str | None = None,
    printer_origin: str = OPTION,
    env_flavor: str | None = None,
    complete: bool = True,
    tail: str = "",
) -> Context:
    """The context of the file whose beginning is ``head`` (``complete``: the whole file) and whose end
    is ``tail`` (when it is not in the head; only the flavour reads it).

    ``dialect`` is a dialect name or ``auto``; ``printer`` a model name or None (infer it).  The
    ``*_origin`` arguments say where an explicit value came from (``option`` or ``configuration``).
    """
    scan = HeadScan(head)
    reading: ContentReading | None = None

    def content() -> ContentReading:
        nonlocal reading
        if reading is None:
            reading = read_content(head, complete)
        return reading

    directive = _directive(scan)
    if directive is not None:
        name, origin, reasons, strength, conflict = directive, DIRECTIVE, (), EXPLICIT, ""
    elif dialect != "auto":
        name, origin, reasons, strength, conflict = dialects.get(dialect).name, dialect_origin, (), EXPLICIT, ""
    else:
        name, origin, reasons, strength, conflict = _weigh(scan, content(), path, env_flavor)
    if dialects.get(name).family != "hyrel":
        flavor, flavor_reasons = _flavor(scan, HeadScan(tail) if tail else None, content, name)
        return Context(name, origin, strength, reasons, conflict, flavor=flavor, flavor_reasons=flavor_reasons)

    firmware, firmware_origin, firmware_reasons, evidence = _version(content(), name, origin)
    name = "hyrel-v4" if firmware == 4 else "hyrel"
    model, model_origin, model_reasons = _model(content(), firmware, printer, printer_origin)
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
    )


def _directive(scan: HeadScan) -> str | None:
    if "gclint" not in scan.lowered:
        return None
    m = _DIRECTIVE.search(scan.head)
    if m is None:
        return None
    try:
        return dialects.get(m.group(1)).name
    except dialects.UnknownDialect:
        return None


# -- the dialect ---------------------------------------------------------------------------------------


# Dialects that read each other's files are weighed as a group first (the content tells Hyrel from a
# RepRap-family printer from a CNC controller clearly), then within the group, where the slicer header
# knows better than the content (Marlin and RepRapFirmware share most codes).
_GROUP_OF_FAMILY = {"hyrel": "hyrel", "reprap": "reprap", "linuxcnc": "cnc", "smoothie": "cnc"}
_GENERIC = (".gcode", ".gco")  # every firmware's files: they tell Marlin from RepRapFirmware at most

Evidence = list[tuple[int, int, str]]  # (weight, line, text)


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
                having = [m for m in members if m in knowers]
                if len(having) < len(members):
                    for m in having:
                        self.member[m].append((1, seen.line, f"{seen}: only {m} has {code}"))

    def score(self, evidence: Evidence) -> int:
        return sum(weight for weight, _, _ in evidence)


def _has(dialect: dialects.Dialect, code: str | None) -> bool:
    """Whether ``dialect`` has ``code``: in its table, or in the inventory of a firmware whose files it
    reads (Bambu's M620 is a Marlin-flavour code, not only Hyrel's)."""
    return code in dialect.codes or code in _flavor_codes(dialect.name)


@cache
def _flavor_codes(name: str) -> frozenset[str]:
    return frozenset().union(*(f.codes for f in firmware.flavors_of(name)))


def _who_has(code: str, having: list[str], groups: list[str]) -> str:
    label = {"hyrel": "Hyrel", "reprap": "Marlin/RepRap", "cnc": "CNC (Machinekit/LinuxCNC, Carvera)"}
    if len(having) == 1:
        return f"only {label.get(having[0], having[0])} dialects have {code}"
    missing = [label.get(g, g) for g in groups if g not in having]
    return f"{code} is not a {' or '.join(missing)} code"


def _weigh(
    scan: HeadScan, reading: ContentReading, path: str, env_flavor: str | None
) -> tuple[str, str, tuple[str, ...], str, str]:
    """(dialect, origin, reasons, strength, conflict) when nobody said which dialect."""
    points = _Points(reading)
    names, groups, group_of = points.names, points.groups, points.group_of
    header, header_texts = _header_scores(scan, env_flavor)
    header_best = max(names, key=lambda n: header[n]) if any(header.values()) else None
    header_group = group_of[header_best] if header_best is not None else None

    scores = {g: points.score(points.group[g]) for g in groups}
    ranked = sorted(groups, key=lambda g: -scores[g])
    best, runner_up = scores[ranked[0]], scores[ranked[1]]
    top = [g for g in groups if scores[g] == best]
    conflict = ""
    if best >= _DECIDES and len(top) == 1:
        group, origin = top[0], CONTENT
        reasons = _top_reasons(points.group[group])
        if header_group is not None and header_group != group:
            conflict = (
                f"the slicer header says {header_best} ({header_texts[header_best][0]}), but the content is "  # type: ignore[index]
                f"{_GROUP_LABEL[group]}: content wins"
            )
        clear = best >= _STRONG and best - runner_up >= _LEAD
        strength = STRONG if (clear or header_group == group) and not conflict else WEAK
    elif header_group is not None and (best < _DECIDES or header_group in top):
        group, origin = header_group, HEADER
        reasons = tuple(header_texts[header_best][:2])  # type: ignore[index]
        agree = best >= _DECIDES
        if agree:
            reasons += _top_reasons(points.group[group], 2)
        strength = STRONG if agree or header[header_best] >= 8 else WEAK  # type: ignore[index]
    else:
        # no content decides (one point is a single code in a table, not a decision): the extension breaks
        # the tie, and .gcode/.gco, which every firmware uses, say nothing here
        by_extension = [
            n for n in names if dialects.get(n).detection.has_extension(path) and not path.lower().endswith(_GENERIC)
        ]
        if len(by_extension) == 1:
            group, origin = group_of[by_extension[0]], EXTENSION
            reasons = (f"the extension {_extension(path)}",) + _top_reasons(points.group[group], 2)
        elif best >= _LEANS:
            group, origin = ("hyrel" if "hyrel" in top else top[0]), CONTENT
            reasons = _top_reasons(points.group[group])
        else:
            return "hyrel", DEFAULT, (), NONE, ""
        strength = WEAK
    return _member(points, group, header, header_texts, path, origin, reasons, strength, conflict)


_GROUP_LABEL = {"hyrel": "Hyrel's", "reprap": "Marlin/RepRap-like", "cnc": "a CNC program's"}


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
    clues = {m: sum(w for w, _, text in points.member[m] if " only " not in text) for m in members}
    leader = max(members, key=lambda m: clues[m])
    clear_lead = all(clues[leader] - clues[m] >= 3 for m in members if m != leader)
    named = [m for m in members if header[m] > 0]
    if named and not (clear_lead and leader not in named):
        choice = max(named, key=lambda m: header[m])
        extra = (f"the slicer header ({header_texts[choice][0]}) names {choice}",) if origin != HEADER else ()
        return choice, origin, _unique(reasons[:2] + extra + reasons[2:]), strength, conflict
    if clear_lead:
        return leader, origin, _unique(reasons + _top_reasons(points.member[leader], 1)), strength, conflict
    by_extension = [m for m in members if dialects.get(m).detection.has_extension(path)]
    if len(by_extension) == 1:  # (the group's evidence stands: the extension only names the member)
        return by_extension[0], origin, _unique(reasons + (f"the extension {_extension(path)}",)), strength, conflict
    own = {m: points.score(points.member[m]) for m in members}
    top = max(members, key=lambda m: own[m])
    return top, origin, _unique(reasons + _top_reasons(points.member[top], 1)), WEAK, conflict


def _unique(texts: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(dict.fromkeys(texts))


def _top_reasons(evidence: Evidence, count: int = 3) -> tuple[str, ...]:
    """The strongest pieces of evidence, earliest first among equals."""
    return tuple(text for _, _, text in sorted(evidence, key=lambda e: (-e[0], e[1]))[:count])


def scores(head: str, path: str = "", env_flavor: str | None = None, complete: bool = True) -> dict[str, dict]:
    """Every group's and dialect's content points and the header's (for ``gclint check -v`` and tests)."""
    points = _Points(read_content(head, complete))
    header, texts = _header_scores(HeadScan(head), env_flavor)
    groups = {
        g: {"content": points.score(points.group[g]), "evidence": _top_reasons(points.group[g], 5)}
        for g in points.groups
    }
    members = {
        n: {"own": points.score(points.member[n]), "header": header[n], "header_texts": texts[n]} for n in points.names
    }
    return {"groups": groups, "dialects": members}


def _header_scores(scan: HeadScan, env_flavor: str | None) -> tuple[dict[str, int], dict[str, list[str]]]:
    scores: dict[str, int] = {}
    texts: dict[str, list[str]] = {}
    for dialect in candidates():
        score, found = dialect.detection.header(scan)
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
    """(firmware, origin, reasons, what the addresses say) for a Hyrel file."""
    v4: list[tuple[int, str]] = []
    v5: list[tuple[int, str]] = []
    for (code, letter, number), seen in reading.addresses.items():
        if letter == "S":  # M703/M704 S: v4 an alias (a device), v5 a squad 30-39 or a head
            old, new = resolve_v4_variable(number).kind == HEAD, 30 <= number <= 39 or _v5_head(number)
        else:
            old, new = fits(code, resolve_v4_variable(number)), _v5_fits(code, number)
        if old and not new:
            v4.append((seen.line, f"{seen}: T{number} is a v4 device address"))
        elif new and not old:
            v5.append((seen.line, f"{seen}: T{number} is a v5 address"))
    for number, seen in reading.tool_commands.items():
        old, new = resolve_v4_command(number).kind != "reserved", resolve_v5(number).kind != "reserved"
        if old and not new:
            v4.append((seen.line, f"{seen}: a v4 tool number"))
        elif new and not old and number > 9:
            v5.append((seen.line, f"{seen}: a v5 address"))
    for seen, what in ((reading.m116, "M116 exists from v5"), (reading.waits_w0, "W0 exists from v5")):
        if seen is not None:  # "[v5+]" on the Gcode page: worth two addresses each
            v5.extend([(seen.line, f"{seen}: {what}")] * 2)
    evidence = 4 if len(v4) > len(v5) else 5 if len(v5) > len(v4) else None
    reasons_of = {4: v4, 5: v5}
    if name == "hyrel-v4" or (name == "hyrel" and origin in (OPTION, CONFIGURATION, DIRECTIVE)):
        firmware = 4 if name == "hyrel-v4" else 5
        return firmware, origin, (), evidence
    firmware = evidence or 5
    reasons = tuple(dict.fromkeys(text for _, text in sorted(reasons_of[firmware])))[:3]
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
) -> tuple[str, str, tuple[str, ...]]:
    if printer is not None:
        return printer, printer_origin, ()
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
    yoke2 = 20 if firmware == 4 else 42
    for (_code, letter, number), seen in reading.addresses.items():
        if letter == "T" and number == yoke2:
            needs.append((f"{seen}: addresses a second yoke", lambda p: p.max_position >= 9))
            break
    if reading.rotary_axes is not None:
        needs.append((f"{reading.rotary_axes}: moves an A/B axis", lambda p: "A" in p.axes))
    if reading.lathe is not None:
        needs.append((f"{reading.lathe}: runs the lathe", lambda p: p.lathe))
    for code, seen in reading.aux_codes.items():
        needs.append((f"{seen}: {code} exists on some models only", lambda p, code=code: code in p.aux_codes))
    if not needs:
        return MODEL_ORDER[0], DEFAULT, ()
    profiles: list[PrinterProfile] = [PROFILES[n] for n in MODEL_ORDER]
    best = max(profiles, key=lambda p: sum(1 for _, test in needs if test(p)))  # type: ignore[operator]
    met = [what for what, test in needs if test(best)]  # type: ignore[operator]
    unmet = [what for what, test in needs if not test(best)]  # type: ignore[operator]
    reasons = tuple(met[:2])
    if unmet:
        reasons += (f"no model fits everything: {unmet[0]}",)
    return best.name, CONTENT, reasons


__all__ = ["infer", "slicer_flavor", "SLICER_FLAVORS", "Seen", "NONE", "WEAK", "STRONG"]
