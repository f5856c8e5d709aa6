"""Which dialect (and firmware flavour) explains a file best: a score per candidate reading.

Each candidate (gclint.context.candidates) starts from its prior (``Detection.prior``: Hyrel highest, the first
target wins where the evidence ties) and every piece of evidence moves some candidates' scores.  The scale is
roughly a log-likelihood: a few points is a preference, eight is "nearly impossible".

* A G/M code a candidate's tables lack while another candidate's have it costs it ``UNLISTED``, the same for
  every dialect: whether a firmware skips such a code or stops on it, its own files rarely hold another
  firmware's codes.  A code no known table has costs every known candidate ``NOBODY``; against ``generic``,
  only ``UNLISTED_NOBODY`` those whose firmware runs codes it does not list (``Dialect.open_codes``:
  RepRapFirmware's macro files, LinuxCNC's user M-codes): it tells no known dialect from another.
* A code only one dialect has counts for it (``UNIQUE``: the others' costs say the rest).
* A kind of line a candidate's language lacks (an O-word in a Marlin file, a meta command in a Hyrel job, a
  Klipper command in a RepRapFirmware one): ``MISFIT``.
* A dialect's clues (gclint.dialects ``Clue``: ``M6 T# O#``, ``M109 H``...) and line marks add their weight
  to it; a flavour's clues to that flavour.
* A dialect's habits (gclint.dialects.habits: a bare ``G28`` or ``M106 S255`` in a Hyrel job) are no evidence
  for the firmware the habit comes from: each costs its dialect's reading ``HABIT``, less for each further one,
  and all of them together at most ``HABITS_AT_MOST``, less than Hyrel's lead as the prior (a test holds it):
  habits alone never take a file from Hyrel, and they never give a reason for another reading.
* How the job uses E, against the readings whose firmware reads E the other way (``E_USE``): E1 marks on every
  printing move and no amount (Hyrel's native flow) where E is an amount; amounts on every printing move with
  nothing native flow computes from (no ``M229 E1``, ``M756``, ``M221 W``) where E is native flow's mark.
* *Soft* costs, which tell known dialects apart but never make a file ``generic``: the habits, how E is used,
  a parameter a catalogued table does not take or a value out of its range (``PARAM``).  The k-th soft cost
  of a reading counts 1/k: one author's habits come together.
* A word a dialect's firmware rejects (``Param.forbidden``: Hyrel's arcs take no R or K) is a misfit as a code
  it lacks is (``UNLISTED``): that reading cannot run the file.
* E words on the moves of a machine with no extruder (``NO_EXTRUDER``) or whose moves have no E (Machinekit:
  ``MISFIT``).
* The slicer header, ``SLIC3R_GCODE_FLAVOR`` (``HEADER_SCALE``) and the extension (``EXTENSION_POINTS``) are
  weak evidence.
* ``generic`` has a fixed score (its prior).  It wins only when it beats every known reading's *fit* (the score
  with the soft costs forgiven): when each has a large misfit.  A mark of a machine no known dialect describes
  (GRBL's ``$H``, a GRBL sender or CAM named in a comment, Mach3's torch-height codes) is one for every known
  reading (``FOREIGN``, ``LineMark.weight``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint.context.candidates import Candidate, candidates, having
from gclint.context.content import ContentReading, Seen
from gclint.context.header import ENV_WEIGHT, extension, found, slicer_flavor, tells
from gclint.context.model import CONTENT, EXTENSION, HEADER
from gclint.dialects.base import HeadScan
from gclint.syntax.nodes import ASSIGNMENT, EXTENDED, META, OWORD

MISFIT = 8.0  # a kind of line a language lacks; an E word on a machine whose moves have none
UNLISTED = 3.0  # a code the candidate lacks and another has: the same for every dialect
NOBODY = 4.0  # a code no known table has
INI_POINTS = 4.0  # a LinuxCNC machine's INI beside the job defines codes (REMAP=): the job is that machine's
# A code no firmware has that the candidate's firmware runs though it does not list it (a RepRapFirmware macro
# file sys/M<n>.g, a LinuxCNC user M-code): the machine's own (MillenniumOS's M4000 macros)
UNLISTED_NOBODY = 0.3  # (what it costs that reading's fit against generic: the ranking counts NOBODY)
LOOSELY = 3.0  # a code only a historic inventory lists (the 2015 RepRap page lists every firmware's numbers)
UNIQUE = 1.0  # a code only one dialect has (the others' misfits say the rest)
SHARED = 0.5
PARAM = 0.5
# a habit, and all of a reading's habits together: "a little", below Hyrel's lead as the prior (1.0 over
# Marlin's 0.5: gclint.dialects Detection.prior), so habits alone never take a file from Hyrel
HABIT = 0.25
HABITS_AT_MOST = 0.4
E_USE = 4.5  # E words used the way another firmware reads them, on every printing move: more than a header
E_MARKS_LINES = 3  # printing moves with E1 (or with amounts) before they count as the job's way of using E
NO_EXTRUDER = 4.0
HEADER_SCALE = 0.3  # a ";FLAVOR:Marlin" line (10) is worth 3 points: less than a code only one dialect has
EXTENSION_POINTS = 2.0
FOREIGN = 7.0  # a comment naming a GRBL sender or CAM, Mach3's torch-height codes: against every known dialect
CLOSE = 5.0  # a lead smaller than this over another dialect is a weak decision

_KIND_TEXT = {
    EXTENDED: "a Klipper-style extended command",
    META: "a RepRapFirmware meta command",
    OWORD: "an O-word",
    ASSIGNMENT: "a # parameter assignment",
}


@dataclass
class Item:
    """One piece of evidence: what it is (shown to the user), where, of which kind (``content``, ``header``,
    ``extension``), and how it moves each candidate's score (by candidate key).  ``soft``: a known mistake or
    an odd use (a habit, a parameter, how E is used), which tells known dialects apart but does not make a
    file ``generic``: a Hyrel job with five Marlin habits is a Hyrel job with five findings.  ``habit``: a
    habit of another firmware (capped, and never a reason for another reading)."""

    text: str
    line: int
    source: str
    deltas: dict[str, float]
    soft: bool = False
    habit: bool = False
    # what a reading's *fit* against ``generic`` gets back: a code no known table has that its firmware runs
    # anyway (a macro) says nothing about which known dialect, only that this one can run the file
    relief: dict[str, float] = field(default_factory=dict)


@dataclass
class Ranking:
    """Every candidate's score and the evidence behind it."""

    pool: tuple[Candidate, ...]
    items: list[Item] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.by_key: dict[str, Candidate] = {c.key: c for c in self.pool}

    def score(self, key: str, sources: tuple[str, ...] | None = None, prior: bool = True) -> float:
        """``key``'s score, counting the evidence of ``sources`` (None: all).  Its soft costs count less and
        less, the largest first (the k-th counts 1/k): one author's habits come together, and each further
        one says less about which firmware the file is for."""
        total = self.by_key[key].prior if prior else 0.0
        soft: list[float] = []
        habits: list[float] = []
        for item in self.items:
            if sources is not None and item.source not in sources:
                continue
            value = item.deltas.get(key)
            if not value:
                continue
            if item.soft and value < 0:
                (habits if item.habit else soft).append(value)
            else:
                total += value
        total += _diminishing(soft)
        return total + max(-HABITS_AT_MOST, _diminishing(habits))

    def scores(self, sources: tuple[str, ...] | None = None) -> dict[str, float]:
        return {c.key: self.score(c.key, sources) for c in self.pool}

    def best(self, scores: dict[str, float], dialect: str | None = None, other: bool = False) -> str | None:
        """The key with the highest score (of ``dialect``'s candidates, or with ``other`` of the others);
        among equals the first in the candidates' order."""
        keys = [c.key for c in self.pool if dialect is None or (c.dialect.name == dialect) != other]
        return max(keys, key=lambda k: scores[k]) if keys else None

    def best_of(self, scores: dict[str, float], dialect: str) -> str:
        """``best`` of a dialect that has candidates (a KeyError for one that has none)."""
        key = self.best(scores, dialect)
        if key is None:
            raise KeyError(dialect)
        return key

    def reasons(
        self,
        winner: str,
        loser: str | None,
        count: int = 3,
        sources: tuple[str, ...] | None = None,
        field: tuple[str, ...] = (),
    ) -> tuple[str, ...]:
        """The evidence that puts ``winner`` above ``loser`` most, strongest first (earliest among equals, the
        file's tail last); what puts it above every reading of ``field`` (the other dialects') comes first."""
        ranked = []
        for item in self.items:
            if item.habit or sources is not None and item.source not in sources:
                continue  # (a habit is no evidence for the firmware it comes from)
            mine = item.deltas.get(winner, 0.0)
            lead = mine - (item.deltas.get(loser, 0.0) if loser else 0.0)
            if lead > 0:
                above_all = min((mine - item.deltas.get(k, 0.0) for k in field), default=0.0)
                ranked.append((-max(above_all, 0.0), -lead, item.line or 1 << 40, item.text))
        ranked.sort()
        return tuple(dict.fromkeys(r[-1] for r in ranked))[:count]

    def against(self, key: str, count: int = 2) -> tuple[str, ...]:
        """What costs ``key`` most (its misfits), worst first."""
        ranked = sorted(
            ((i.deltas[key], i.line or 1 << 40, i.text) for i in self.items if i.deltas.get(key, 0.0) < 0),
        )
        return tuple(dict.fromkeys(text for _, _, text in ranked))[:count]


def _diminishing(costs: list[float]) -> float:
    """The sum of ``costs`` with the k-th largest counting 1/k."""
    return sum(value / k for k, value in enumerate(sorted(costs), 1))


def rank(
    reading: ContentReading,
    scan: HeadScan,
    tail: HeadScan | None,
    path: str,
    env_flavor: str | None,
    pool: tuple[Candidate, ...] | None = None,
    machine_codes: tuple[str, ...] = (),
) -> Ranking:
    """Score every candidate of ``pool`` (default: all) on the file's content, header and name (and the codes the
    machine's INI beside the job defines: ``machine_codes``)."""
    ranking = Ranking(pool if pool is not None else candidates())
    known = tuple(c for c in ranking.pool if c.known)
    add = ranking.items.append
    if machine_codes:
        # a LinuxCNC machine's INI beside the job that defines codes (REMAP=): the job is that machine's, and
        # the codes are its own (LinuxCNC docs/src/config/ini-config.adoc, [RS274NGC] REMAP)
        readers = {c.key: INI_POINTS for c in known if c.dialect.machine_ini}
        add(Item(f"the machine's INI beside the job defines {', '.join(machine_codes[:3])}", 0, CONTENT, readers))
    _codes(reading, known, add, frozenset(machine_codes))
    _clues(reading, ranking.pool, add)
    _kinds(reading, known, add)
    _e_words(reading, known, add)
    _header(scan, tail, env_flavor, ranking.pool, known, add)
    for c in known:
        if tells(c.dialect.detection, path) and c.flavor is None:
            points = EXTENSION_POINTS * c.dialect.detection.extension_weight
            add(
                Item(
                    f"the extension {extension(path)}",
                    0,
                    EXTENSION,
                    {k.key: points for k in known if k.dialect is c.dialect},
                )
            )
    return ranking


def _owners(keys: list[str]) -> str:
    return ", ".join(keys)


def _codes(reading: ContentReading, known: tuple[Candidate, ...], add, machine: frozenset[str] = frozenset()) -> None:
    for code, seen in reading.codes.items():
        has = having(code)
        deltas: dict[str, float] = {}
        relief: dict[str, float] = {}
        for c in known:
            if code in machine and c.dialect.machine_ini:
                continue  # (the machine's own code: its INI defines it)
            if c.has(code):
                if not c.supported(code):
                    continue  # (a code the table lists as unsupported: the dialect's habit, when it is one)
                bonus = UNIQUE if len(has) == 1 else SHARED if len(has) == 2 else 0.0
                if bonus:
                    deltas[c.key] = bonus
                continue
            if c.lists_loosely(code):
                cost = LOOSELY
            elif has:
                cost = UNLISTED
            else:
                cost = NOBODY
                if c.runs_unlisted(code):
                    relief[c.key] = NOBODY - UNLISTED_NOBODY
            deltas[c.key] = -cost
        if not deltas:
            continue
        owners = [c.dialect.name for c in known if c.flavor is None and c.has(code)]
        # a flavour whose dialect's own table lacks the code has it too (FABlin's M728, which Hyrel also has:
        # not "only hyrel has M728" as the reason a file is FABlin's)
        flavors = [c.flavor.name for c in known if c.flavor is not None and c.has(code) and code not in c.dialect.codes]
        mixed = bool(owners and flavors)
        owners += flavors
        if not owners:
            text = f"{seen}: no known dialect has {code}"
        elif len(owners) == 1:
            text = f"{seen}: only {owners[0]} has {code}"
        elif mixed:
            text = f"{seen}: only {', '.join(owners[:-1])} and {owners[-1]} have {code}"
        else:
            missing = [c.dialect.name for c in known if c.flavor is None and c.dialect.name not in has]
            text = f"{seen}: {code} is not a {' or '.join(missing)} code" if missing else f"{seen}: {code}"
        add(Item(text, seen.line, CONTENT, deltas, relief=relief))


def _clues(reading: ContentReading, pool: tuple[Candidate, ...], add) -> None:
    for name, found_clues in reading.clues.items():
        members = [c.key for c in pool if c.dialect.name == name]
        if not members:
            continue
        for clue, seen in found_clues.items():
            add(Item(f"{seen}: {clue.says}", seen.line, CONTENT, {k: float(clue.weight) for k in members}))
    for fw, found_clues in reading.flavor_clues.items():
        members = [c.key for c in pool if c.flavor is not None and c.flavor.name == fw]
        if not members:
            continue
        for clue, seen in found_clues.items():
            add(Item(f"{seen}: {clue.says}", seen.line, CONTENT, {k: float(clue.weight) for k in members}))
    for dialect in {c.dialect.name: c.dialect for c in pool}.values():
        members = [c.key for c in pool if c.dialect is dialect]
        habits = dict(reading.habits.get(dialect.name, {}))
        for habit in dialect.detection.habits:
            if habit.fact is not None and (fact := reading.fact(habit.fact)) is not None:
                habits[habit] = fact
        by_rule: dict[str, tuple] = {}  # (one rule, one finding's worth: the first habit it reports)
        for habit, seen in sorted(habits.items(), key=lambda hs: hs[1].line or 1 << 40):
            by_rule.setdefault(habit.rule, (habit, seen))
        for habit, seen in by_rule.values():
            text = f"{seen}: {habit.says} ({habit.rule} reports it on {dialect.name})"
            add(Item(text, seen.line, CONTENT, {k: -HABIT for k in members}, soft=True, habit=True))
        for seen, problem in reading.rejected.get(dialect.name, {}).values():
            # a word the firmware rejects: the file cannot run there, as with a code it lacks
            cost = UNLISTED
            add(Item(f"{seen}: {problem} on {dialect.name}", seen.line, CONTENT, {k: -cost for k in members}))
        for seen, problem in reading.params.get(dialect.name, {}).values():
            add(
                Item(
                    f"{seen}: {problem} on {dialect.name}", seen.line, CONTENT, {k: -PARAM for k in members}, soft=True
                )
            )
        for mark, seen in reading.marks.get(dialect.name, {}).items():
            if dialect.known:
                add(Item(f"{seen}: {mark.says}", seen.line, CONTENT, {k: float(mark.weight) for k in members}))
            else:  # a mark of a machine no known dialect describes: against every known one
                deltas = {c.key: -float(mark.weight) for c in pool if c.known}
                add(Item(f"{seen}: {mark.says}", seen.line, CONTENT, deltas))


def _kinds(reading: ContentReading, known: tuple[Candidate, ...], add) -> None:
    first: dict[str, dict[str, Seen]] = {}  # kind -> candidate key -> the first line of it the candidate lacks
    for (kind, word), seen in reading.kinds.items():
        for c in known:
            if not c.accepts(kind, word):
                first.setdefault(kind, {}).setdefault(c.key, seen)
    for kind, lacking in first.items():
        seen = min(lacking.values(), key=lambda s: s.line or 1 << 40)
        text = f"{seen}: {_KIND_TEXT.get(kind, kind)} (not in {_owners(sorted({k.split('/')[0] for k in lacking}))})"
        add(Item(text, seen.line, CONTENT, {k: -MISFIT for k in lacking}))


def _e_words(reading: ContentReading, known: tuple[Candidate, ...], add) -> None:
    moves = reading.e_moves
    if moves is None:
        return
    by_key = {c.key: c for c in known}
    no_e = {c.key: -MISFIT for c in known if "E" in c.dialect.not_move_words}
    if no_e:
        add(
            Item(
                f"{moves}: an E word on a move (not a word of {_owners(sorted({k.split('/')[0] for k in no_e}))} moves)",
                moves.line,
                CONTENT,
                no_e,
            )
        )
    no_extruder = {c.key: -NO_EXTRUDER for c in known if c.dialect.semantics.extruder is None and c.key not in no_e}
    if no_extruder:
        add(Item(f"{moves}: an E word on a move (a machine with no extruder)", moves.line, CONTENT, no_extruder))
    amount = {c.key for c in known if c.dialect.semantics.extruder == "E" and c.key not in no_e}
    native = {k for k in amount if by_key[k].dialect.semantics.e_values == "native"}
    if reading.e_flags >= E_MARKS_LINES and reading.e_amounts is None and not reading.e_values:
        # Hyrel native flow: "E will trigger a working or printing move" whatever its value (Hyrel wiki, Gcode
        # page, "G1 Working Move"); where E is an amount, E1 on every move feeds nothing after the first
        # (absolute E) or the same length whatever the move's (relative)
        text = f"E1 on {reading.e_flags} printing moves and no E amount (native flow's marks of a printing move)"
        add(Item(text, 0, CONTENT, {k: -E_USE for k in amount - native}, soft=True))
    if (sliced := reading.e_sliced) is not None and native:
        # "In native mode ... the value of Extrusion rate E will be ignored" (G1 Working Move): amounts on every
        # printing move and nothing native flow computes from (M756 layer heights, M221 widths) were sliced for
        # a firmware that meters E; Hyrel's own slicer header enables the amounts ("M229 E1 D1")
        text = f"{sliced}: E amounts on every printing move with neither M229 E1 nor native-flow settings"
        add(Item(text, sliced.line, CONTENT, {k: -E_USE for k in native}, soft=True))


def _header(scan: HeadScan, tail: HeadScan | None, env_flavor: str | None, pool, known, add) -> None:
    for c in pool:
        if c.flavor is None:
            hits = found(c.dialect.detection, scan, tail)
            if not hits:
                continue
            weight = max(w for w, _ in hits)  # (one slicer's lines say one thing: ";FLAVOR:", its markers)
            text = "; ".join(t for _, t in hits[:2])
            if c.known:
                members = {k.key: weight * HEADER_SCALE for k in pool if k.dialect is c.dialect}
            else:  # the header names a machine no known dialect describes: against every known one, once
                members = {k.key: -FOREIGN for k in known}
            add(Item(text, 0, HEADER, members))
        else:
            hits = found(c.flavor.detection, scan, tail)
            if hits:
                weight = max(w for w, _ in hits)
                text = "; ".join(t for _, t in hits[:2])
                add(Item(text, 0, HEADER, {c.key: weight * HEADER_SCALE}))
    if env_flavor:
        mapped = slicer_flavor(env_flavor)
        members = {k.key: ENV_WEIGHT * HEADER_SCALE for k in pool if k.dialect.name == mapped}
        if members:
            add(Item(f"SLIC3R_GCODE_FLAVOR={env_flavor.strip()}", 0, HEADER, members))


__all__ = ["CLOSE", "Item", "Ranking", "rank"]
