"""Which dialect (and firmware flavour) explains a file best: a score per candidate reading.

Each candidate (gclint.context.candidates) starts from its prior (Hyrel highest: the first target wins
where the evidence ties) and every piece of evidence moves some candidates' scores.  The scale is roughly
a log-likelihood: a few points is a preference, eight is "nearly impossible".

* A G/M code a candidate's tables lack while another candidate's have it: nearly impossible under it
  (``MISFIT``), less where the firmware runs codes it does not list (RepRapFirmware's macro files, LinuxCNC's
  user M-codes: ``UNLISTED``).  A code no known table has costs every known candidate (``NOBODY``).
* A code only one dialect has is strong evidence for it (``UNIQUE``), one two dialects share a little.
* A kind of line a candidate's language lacks (an O-word in a Marlin file, a meta command in a Hyrel job, a
  Klipper command in a RepRapFirmware one): ``MISFIT``.
* A dialect's clues (gclint.dialects ``Clue``: ``M6 T# O#``, ``M109 H``...) add their weight to it; a
  flavour's clues to that flavour.
* A dialect's habits (gclint.dialects.habits: a bare ``G28`` in a Hyrel job) cost it a little (``Habit.cost``; the k-th of a file counts 1/k)
  and are no evidence for the firmware the habit comes from: its rule reports the line.
* A parameter a dialect's catalogued table does not take, or a value outside its range: ``PARAM``.
* E words: constant E1 marks on printing moves and no amount are Hyrel's native flow, implausible under a
  firmware whose E is an amount (``E_MARKS``); an E on a move of a machine with no extruder (``NO_EXTRUDER``)
  or whose moves have no E (Machinekit: ``MISFIT``).
* The slicer header, ``SLIC3R_GCODE_FLAVOR`` and the extension are weak evidence (``HEADER_SCALE``,
  ``EXTENSION``).
* ``generic`` has a fixed score (its prior); a mark of a machine no known dialect describes (GRBL's ``$H``, a
  GRBL sender or CAM named in a comment, Mach3's torch-height codes) is a large misfit for every known one.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint.context.candidates import Candidate, candidates, having
from gclint.context.content import ContentReading
from gclint.context.header import ENV_WEIGHT, extension, found, slicer_flavor, tells
from gclint.context.model import CONTENT, DEFAULT, EXTENSION, HEADER, NONE, STRONG, WEAK
from gclint.dialects.base import HeadScan
from gclint.syntax.nodes import ASSIGNMENT, EXTENDED, META, OWORD

MISFIT = 8.0  # a kind of line a language lacks; an E word on a machine whose moves have none
NOBODY = 4.0  # a code no known table has (at most what the dialect's ``Detection.unlisted`` says)
# A code the firmware runs though it does not list it (a RepRapFirmware macro file sys/M<n>.g, a LinuxCNC user
# M-code): where no firmware has the number it is the machine's own (MillenniumOS's M4000 macros), where another
# firmware has it the file more likely comes from that firmware
UNLISTED = 4.0
UNLISTED_NOBODY = 0.3
LOOSELY = 3.0  # a code only a historic inventory lists (the 2015 RepRap page lists every firmware's numbers)
UNIQUE = 1.0  # a code only one dialect has (the others' misfits say the rest)
SHARED = 0.5
PARAM = 0.5
E_MARKS = 3.0
E_MARKS_LINES = 3  # printing moves with E1 (or with amounts) before they count as the job's way of using E
NO_EXTRUDER = 4.0
HEADER_SCALE = 0.3  # a ";FLAVOR:Marlin" line (10) is worth 3 points: less than one code a dialect lacks
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
    file ``generic``: a Hyrel job with five Marlin habits is a Hyrel job with five findings."""

    text: str
    line: int
    source: str
    deltas: dict[str, float]
    soft: bool = False


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
        soft = []
        for item in self.items:
            if sources is not None and item.source not in sources:
                continue
            value = item.deltas.get(key)
            if not value:
                continue
            if item.soft and value < 0:
                soft.append(value)
            else:
                total += value
        soft.sort()
        return total + sum(value / k for k, value in enumerate(soft, 1))

    def scores(self, sources: tuple[str, ...] | None = None) -> dict[str, float]:
        return {c.key: self.score(c.key, sources) for c in self.pool}

    def best(self, scores: dict[str, float], dialect: str | None = None, other: bool = False) -> str | None:
        """The key with the highest score (of ``dialect``'s candidates, or with ``other`` of the others);
        among equals the first in the candidates' order."""
        keys = [c.key for c in self.pool if dialect is None or (c.dialect.name == dialect) != other]
        return max(keys, key=lambda k: scores[k]) if keys else None

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
            if sources is not None and item.source not in sources:
                continue
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


def rank(
    reading: ContentReading,
    scan: HeadScan,
    tail: HeadScan | None,
    path: str,
    env_flavor: str | None,
    pool: tuple[Candidate, ...] | None = None,
) -> Ranking:
    """Score every candidate of ``pool`` (default: all) on the file's content, header and name."""
    ranking = Ranking(pool if pool is not None else candidates())
    known = tuple(c for c in ranking.pool if c.known)
    add = ranking.items.append
    _codes(reading, known, add)
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


def _codes(reading: ContentReading, known: tuple[Candidate, ...], add) -> None:
    for code, seen in reading.codes.items():
        has = having(code)
        deltas: dict[str, float] = {}
        for c in known:
            if c.has(code):
                if not c.supported(code):
                    continue  # (a code the table lists as unsupported: the dialect's habit, when it is one)
                bonus = UNIQUE if len(has) == 1 else SHARED if len(has) == 2 else 0.0
                if bonus:
                    deltas[c.key] = bonus
                continue
            unlisted = c.dialect.detection.unlisted
            if has:
                cost = UNLISTED if c.runs_unlisted(code) else LOOSELY if c.lists_loosely(code) else unlisted
            else:
                cost = (
                    UNLISTED_NOBODY
                    if c.runs_unlisted(code)
                    else LOOSELY
                    if c.lists_loosely(code)
                    else min(NOBODY, unlisted)
                )
            deltas[c.key] = -cost
        if not deltas:
            continue
        owners = [c.dialect.name for c in known if c.flavor is None and c.has(code)]
        owners = owners or [c.flavor.name for c in known if c.flavor is not None and c.has(code)]  # type: ignore[union-attr]
        if not owners:
            text = f"{seen}: no known dialect has {code}"
        elif len(owners) == 1:
            text = f"{seen}: only {owners[0]} has {code}"
        else:
            missing = [c.dialect.name for c in known if c.flavor is None and c.dialect.name not in has]
            text = f"{seen}: {code} is not a {' or '.join(missing)} code" if missing else f"{seen}: {code}"
        add(Item(text, seen.line, CONTENT, deltas))


def _clues(reading: ContentReading, pool: tuple[Candidate, ...], add) -> None:
    for dialect, found_clues in reading.clues.items():
        members = [c.key for c in pool if c.dialect.name == dialect]
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
            if habit.fact is not None and (seen := reading.fact(habit.fact)) is not None:
                habits[habit] = seen
        by_rule: dict[str, tuple] = {}  # (one rule, one finding's worth: the costliest habit it reports)
        for habit, seen in habits.items():
            if habit.rule not in by_rule or habit.cost > by_rule[habit.rule][0].cost:
                by_rule[habit.rule] = (habit, seen)
        for habit, seen in by_rule.values():
            text = f"{seen}: {habit.says} ({habit.rule} reports it)"
            add(Item(text, seen.line, CONTENT, {k: -habit.cost for k in members}, soft=True))
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
    first: dict[str, dict[str, object]] = {}  # kind -> candidate key -> the first line of it the candidate lacks
    for (kind, word), seen in reading.kinds.items():
        for c in known:
            if not c.accepts(kind, word):
                first.setdefault(kind, {}).setdefault(c.key, seen)
    for kind, lacking in first.items():
        seen = min(lacking.values(), key=lambda s: s.line or 1 << 40)  # type: ignore[attr-defined]
        text = f"{seen}: {_KIND_TEXT.get(kind, kind)} (not in {_owners(sorted({k.split('/')[0] for k in lacking}))})"
        add(Item(text, seen.line, CONTENT, {k: -MISFIT for k in lacking}))  # type: ignore[attr-defined]


def _e_words(reading: ContentReading, known: tuple[Candidate, ...], add) -> None:
    moves = reading.e_moves
    if moves is None:
        return
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
    if reading.e_flags >= E_MARKS_LINES and reading.e_amounts is None and not reading.e_values:
        # Hyrel native flow: "E will trigger a working or printing move" whatever its value (Hyrel wiki, Gcode
        # page, "G1 Working Move"); where E is an amount, E1 on every move feeds nothing after the first
        # (absolute E) or the same length whatever the move's (relative)
        deltas = {
            c.key: -E_MARKS
            for c in known
            if c.dialect.semantics.extruder == "E" and c.dialect.semantics.e_values == "amount" and c.key not in no_e
        }
        if deltas:
            text = f"E1 on {reading.e_flags} printing moves and no E amount (native flow's marks of a printing move)"
            add(Item(text, 0, CONTENT, deltas, soft=True))


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
            add(Item(f"the header: {text}", 0, HEADER, members))
        else:
            hits = found(c.flavor.detection, scan, tail)
            if hits:
                weight = max(w for w, _ in hits)
                text = "; ".join(t for _, t in hits[:2])
                add(Item(f"the header: {text}", 0, HEADER, {c.key: weight * HEADER_SCALE}))
    if env_flavor:
        mapped = slicer_flavor(env_flavor)
        members = {k.key: ENV_WEIGHT * HEADER_SCALE for k in pool if k.dialect.name == mapped}
        if members:
            add(Item(f"SLIC3R_GCODE_FLAVOR={env_flavor.strip()}", 0, HEADER, members))


# -- the decision ------------------------------------------------------------------------------------------


@dataclass
class Decision:
    dialect: str
    flavor: str | None
    origin: str
    strength: str
    reasons: tuple[str, ...]
    conflict: str
    flavor_reasons: tuple[str, ...]
    candidates: tuple[tuple[str, float], ...]
    candidate_reasons: tuple[str, ...]


def _pick(ranking: Ranking, sources: tuple[str, ...] | None = None) -> tuple[str, str | None, float, float]:
    """(winner, rival, margin, lead) counting only the evidence of ``sources`` (None: all): the best known
    reading, unless none explains the file, when ``generic`` wins: its fixed score beats every known reading's
    fit (the score with its soft costs forgiven: a large misfit each, not a pile of habits).  The rival is the
    best known reading of another dialect; ``lead`` what the evidence (priors aside) puts between them."""
    pool = ranking.pool
    scores = ranking.scores(sources)
    known = [c.key for c in pool if c.known]
    generic = next((c.key for c in pool if not c.known), None)

    def fit(key: str) -> float:
        prior = ranking.by_key[key].prior
        return prior + sum(
            v
            for i in ranking.items
            if (sources is None or i.source in sources) and ((v := i.deltas.get(key, 0.0)) > 0 or not i.soft)
        )

    best_known = max(known, key=lambda k: scores[k]) if known else None  # (the first among equals: Hyrel)
    best_fit = max((fit(k) for k in known), default=float("-inf"))
    if best_known is None or (generic is not None and scores[generic] > best_fit):
        rival = best_known
        margin = scores[generic] - best_fit  # type: ignore[index]
        lead = -(best_fit - ranking.by_key[rival].prior) if rival is not None else 1.0
        return generic, rival, margin, lead  # type: ignore[return-value]
    dialect = ranking.by_key[best_known].dialect.name
    others = [k for k in known if ranking.by_key[k].dialect.name != dialect]
    rival = max(others, key=lambda k: scores[k]) if others else None
    margin = scores[best_known] - scores[rival] if rival is not None else float("inf")
    if generic is not None:
        margin = min(margin, fit(best_known) - scores[generic])
    lead = (
        ranking.score(best_known, sources, prior=False) - ranking.score(rival, sources, prior=False)
        if rival is not None
        else 1.0
    )
    return best_known, rival, margin, lead


def decide(ranking: Ranking) -> Decision:
    """The best reading of ``ranking``: its dialect and flavour, where the decision came from, how sure it is,
    why, and what disagreed."""
    scores = ranking.scores()
    winner, rival, margin, _ = _pick(ranking)
    dialect = ranking.by_key[winner].dialect.name
    own = ranking.best(scores, dialect)  # (the best reading of the winner's dialect: a flavour, perhaps)
    if not any(any(v for v in i.deltas.values()) for i in ranking.items):
        origin, strength, reasons = DEFAULT, NONE, ()
    else:
        by_content, _, _, content_lead = _pick(ranking, (CONTENT,))
        by_header = _pick(ranking, (CONTENT, HEADER))[0]
        if ranking.by_key[by_content].dialect.name == dialect and content_lead > 0:
            origin = CONTENT
        elif ranking.by_key[by_header].dialect.name == dialect and any(
            i.source == HEADER and i.deltas.get(winner, 0) > 0 for i in ranking.items
        ):
            origin = HEADER
        elif any(i.source == EXTENSION and i.deltas.get(winner, 0) > 0 for i in ranking.items):
            origin = EXTENSION
        else:
            origin = CONTENT
        strength = STRONG if margin >= CLOSE else WEAK
        # the other dialects' best readings: what sets the winner above all of them is said first
        field = tuple(
            ranking.best(scores, c.dialect.name)  # type: ignore[misc]
            for c in ranking.pool
            if c.known and c.flavor is None and c.dialect.name != dialect
        )
        if origin == EXTENSION:
            reasons = ranking.reasons(winner, rival, 3, (EXTENSION,)) + ranking.reasons(
                winner, rival, 2, (CONTENT,), field
            )
        else:
            reasons = ranking.reasons(winner, rival, 3, (CONTENT,) if origin == CONTENT else (HEADER, CONTENT), field)
        if not reasons and rival is not None:
            # the runner-up explains the file as well (the prior decided): say what rules the others out, the
            # default (the highest prior) first
            rival_dialect = ranking.by_key[rival].dialect.name
            others = sorted(
                (k for k in field if ranking.by_key[k].dialect.name != rival_dialect),
                key=lambda k: -ranking.by_key[k].prior,
            )
            for other in others:
                reasons = tuple(dict.fromkeys(reasons + ranking.reasons(winner, other, 1)))
                if len(reasons) == 2:
                    break
            reasons += (f"{rival_dialect} explains it as well",)
    conflict = _conflicts(ranking, scores, winner, dialect, origin)

    flavor = None
    flavor_reasons: tuple[str, ...] = ()
    chosen = ranking.by_key[own]  # type: ignore[index]
    if chosen.flavor is not None:
        plain = next((c.key for c in ranking.pool if c.dialect.name == dialect and c.flavor is None), None)
        tied = [
            c.key for c in ranking.pool if c.dialect.name == dialect and c.key != own and scores[c.key] == scores[own]
        ]
        if not tied:
            flavor = chosen.flavor.name
            # the slicer's settings first (they name the printer), then the content
            flavor_reasons = ranking.reasons(own, plain, 2, (HEADER,))  # type: ignore[arg-type]
            flavor_reasons = (flavor_reasons + ranking.reasons(own, plain, 2, (CONTENT,)))[:2]  # type: ignore[arg-type]
    ordered = sorted(scores.items(), key=lambda kv: -kv[1])
    shown = tuple((key, round(value, 2)) for key, value in ordered)
    why = []
    for key, _ in ordered[:4]:
        against = ranking.against(key, 1)
        if against:
            why.append(f"{key}: {against[0]}")
    return Decision(dialect, flavor, origin, strength, reasons, conflict, flavor_reasons, shown, tuple(why))


def _conflicts(ranking: Ranking, scores: dict[str, float], winner: str, dialect: str, origin: str) -> str:
    """What the header or the extension said that the decision overrules."""
    out = []
    header_items = [i for i in ranking.items if i.source == HEADER]
    best_header: tuple[float, str, str] | None = None
    for item in header_items:
        for key, value in item.deltas.items():
            name = ranking.by_key[key].dialect.name
            if (
                value > 0
                and name != dialect
                and ranking.by_key[key].known
                and (best_header is None or value > best_header[0])
            ):
                best_header = (value, name, item.text.removeprefix("the header: "))
    if best_header is not None and not any(i.deltas.get(winner, 0) > 0 for i in header_items):
        _, name, text = best_header
        out.append(f"the slicer says {name} ({text}), but the content is {dialect}'s: content wins")
    if origin == HEADER:
        content = ranking.scores((CONTENT,))
        leader = ranking.best(content)
        if leader is not None and ranking.by_key[leader].dialect.name != dialect:
            lean = ranking.reasons(leader, winner, 1, (CONTENT,))
            if lean:
                out.append(
                    f"the content leans to {ranking.by_key[leader].dialect.name} ({lean[0]}), less than the slicer header"
                )
    for item in ranking.items:
        if item.source != EXTENSION or item.deltas.get(winner, 0) > 0:
            continue
        name = ranking.by_key[next(iter(item.deltas))].dialect.name
        key = next(iter(item.deltas))
        misfit = ranking.against(key, 1)
        ext = item.text.removeprefix("the extension ")
        if misfit:
            out.append(f"the extension {ext} is {name}'s, but {misfit[0]}: not read as {name}")
        else:
            out.append(f"the extension {ext} is {name}'s, but the content is {dialect}'s: not read as {name}")
    return "; ".join(out)


__all__ = ["Item", "Ranking", "Decision", "rank", "decide"]
