"""The decision over a ``Ranking`` (gclint.context.score): which reading wins, where the decision came from
(content, the slicer header, the extension, nothing), how sure it is, why, and what it overruled.

The best known reading wins unless none explains the file: ``generic``'s fixed score beats every known reading's
fit (its score with the soft costs forgiven), which takes a large misfit each (GRBL's ``$H``, a code no known
dialect has, a GRBL or Mach3 mark), never a pile of habits.  The decision is weak when the best reading of
another dialect comes within ``CLOSE`` (or ``generic`` does).  A firmware flavour is read when it beats its
dialect's own reading and no other flavour ties it.
"""

from __future__ import annotations

from dataclasses import dataclass

from gclint.context.model import CONTENT, DEFAULT, EXTENSION, HEADER, NONE, STRONG, WEAK
from gclint.context.score import CLOSE, Ranking


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
            v + i.relief.get(key, 0.0)
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
    winner, rival, margin, lead = _pick(ranking)
    dialect = ranking.by_key[winner].dialect.name
    own = ranking.best_of(scores, dialect)  # (the best reading of the winner's dialect: a flavour, perhaps)
    reasons: tuple[str, ...]
    if not any(any(v for v in i.deltas.values()) for i in ranking.items if not i.habit):  # (habits tell nothing)
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
        if lead <= 0 and ranking.by_key[winner].known:
            # only its prior sets the winner above the rest: nothing in the file is for it (a bare G28 and a few
            # moves that every firmware runs); its dialect's findings are the default reading's (Context.assumed)
            strength = NONE
        # the other dialects' best readings: what sets the winner above all of them is said first
        field = tuple(
            ranking.best_of(scores, c.dialect.name)
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
    chosen = ranking.by_key[own]
    if chosen.flavor is not None:
        plain = next((c.key for c in ranking.pool if c.dialect.name == dialect and c.flavor is None), None)
        tied = [
            c.key for c in ranking.pool if c.dialect.name == dialect and c.key != own and scores[c.key] == scores[own]
        ]
        if not tied:
            flavor = chosen.flavor.name
            # the slicer's settings first (they name the printer), then the content
            flavor_reasons = ranking.reasons(own, plain, 2, (HEADER,))
            flavor_reasons = (flavor_reasons + ranking.reasons(own, plain, 2, (CONTENT,)))[:2]
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
                best_header = (value, name, item.text)
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


__all__ = ["Decision", "decide"]
