"""Which rules keep plain moves off their fast route, and what each lacks: the message of the fast-path guards.

The engine lets plain moves (``G1 X10 Y20 E.5``) skip the tree, and applies runs of them at once, only when no
rule would look at them (gclint/engine.py ``Linter._run``, ``_plain_moves``, ``_plain_arcs``;
gclint/runs.py ``rule_run_filters``; docs/architecture.md, "Plain moves" and "Runs").  The route is open when
*every* rule allows it, so asking the engine about each rule alone tells exactly which rules close it.  This
module asks the engine itself (it records what ``_run`` decides for a one-line file), then reads the rule to say
what it is missing: a guard test that finds a job read line by line names the rule and the filter, instead of
``assert 3002 < 100``.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from contextlib import contextmanager

import gclint.engine
from gclint.engine import Linter, Options
from gclint.rules.base import Rule
from gclint.syntax.source import Source

_PLAIN = frozenset("XYZEF")  # the words of a plain move (fastpath.PLAIN_MOVE)
_ARC = frozenset("XYZIJEF")  # the words of an arc of a run (fastpath.run_pattern)


@contextmanager
def _recorded(linter: Linter) -> Iterator[dict]:
    """What ``linter._run`` decides about the route: ``plain`` (None: closed; "unasked": a rule's
    ``on_line_starting_with`` holds "G"), ``runs`` (None: runs read line by line), ``arcs`` (runs take arcs)."""
    seen: dict = {"plain": "unasked", "runs": "unasked", "arcs": "unasked"}
    plain_moves, plain_arcs, run_filters = linter._plain_moves, linter._plain_arcs, gclint.engine.rule_run_filters

    def moves(*args):
        seen["plain"] = plain_moves(*args)
        return seen["plain"]

    def arcs(*args):
        seen["arcs"] = plain_arcs(*args)
        return seen["arcs"]

    def runs(*args):
        seen["runs"] = run_filters(*args)
        return seen["runs"]

    linter._plain_moves, linter._plain_arcs = moves, arcs  # type: ignore[method-assign]
    gclint.engine.rule_run_filters = runs
    try:
        yield seen
    finally:
        gclint.engine.rule_run_filters = run_filters
        del linter._plain_moves, linter._plain_arcs


def _decision(dialect: str, rules: list[type[Rule]]) -> tuple[dict, Linter, object]:
    linter = Linter(Options(dialect=dialect))
    linter.rule_classes = rules
    source = Source.from_text("G1 X1 Y1\n", "<route>")
    ctx, result = linter.prepare(source)
    with _recorded(linter) as seen:
        linter._run(source, ctx, result)
    return seen, linter, ctx


def _open(seen: dict) -> tuple[bool, bool, bool]:
    """(plain moves skip the tree, runs are applied whole, runs take arcs)."""
    plain = seen["plain"] not in (None, "unasked")
    runs = plain and seen["runs"] is not None
    return plain, runs, bool(seen["arcs"]) and seen["arcs"] != "unasked"


def lacks(rule: Rule) -> list[str]:
    """What ``rule`` (an instance) declares that keeps moves off the route, or lacks, in the words of
    CONTRIBUTING.md ("A rule that reads moves")."""
    out = []
    if rule.on_line:
        out.append("on_line = True calls check_line on every line (use on_line_matching, on_line_starting_with, ...)")
    if "G" in rule.on_line_starting_with:
        out.append('on_line_starting_with holds "G" (every move is read)')
    for code in ("G0", "G1"):
        if code not in rule.codes:
            continue
        letters = rule.trigger_letters(code)
        plain_filter = getattr(rule, "plain_filter", None)
        if letters is not None and not letters.isdisjoint(_PLAIN):
            out.append(
                f"trigger_letters({code!r}) = {''.join(sorted(letters))!r} has letters a plain move has (X Y Z E F)"
            )
        elif letters is None and plain_filter is None:
            out.append(
                f"listens to {code} with neither trigger_letters (letters a plain move never has) nor "
                "plain_filter(mode, x, y, z, e, f)"
            )
        elif letters is None and getattr(rule, "run_filter", None) is None:
            out.append(f"has plain_filter for {code} but no run_filter(text, start, end): runs are read line by line")
    for code in ("G2", "G3"):
        if code not in rule.codes:
            continue
        letters = rule.trigger_letters(code)
        if (letters is None or not letters.isdisjoint(_ARC)) and getattr(rule, "run_filter", None) is None:
            out.append(
                f"listens to {code} with no run_filter(text, start, end) (nor trigger_letters outside X Y Z I J E F): "
                "arcs are kept out of runs"
            )
    return out


def route_blockers(dialect: str, rules: Iterable[type[Rule]] | None = None, **options) -> list[str]:
    """One line per rule (of ``rules``, default: those ``Options(dialect=dialect, **options)`` selects) that
    keeps plain moves of a ``dialect`` file off their route, or runs from being applied whole, or arcs out of
    runs, where the route is open without it: ``"HY068 (MyRule) closes the plain-move route: listens to G1
    with neither trigger_letters ... nor plain_filter(...)"``."""
    if rules is None:
        rules = Linter(Options(dialect=dialect, **options)).rule_classes
    rules = list(rules)
    baseline = _open(_decision(dialect, [])[0])
    out = []
    for cls in rules:
        seen, _, ctx = _decision(dialect, [cls])
        plain, runs, arcs = _open(seen)
        if plain == baseline[0] and runs == baseline[1] and arcs == baseline[2]:
            continue
        closed = (
            "closes the plain-move route"
            if plain != baseline[0]
            else "makes runs of moves be read line by line"
            if runs != baseline[1]
            else "keeps arcs out of runs"
        )
        try:
            why = lacks(cls(ctx))  # type: ignore[arg-type]
        except Exception as exc:  # (a rule that cannot be made: the engine drops it, the route stays shut)
            why = [f"the rule cannot be made: {type(exc).__name__}: {exc}"]
        out.append(f"{cls.code} ({cls.__name__}) {closed}: {'; '.join(why) or 'see gclint/engine.py _plain_moves'}")
    return out


def slow_reading(dialect: str, found: object, *more_rules: type[Rule], **options) -> str:
    """The message of a guard that found a job read line by line (``found``: what it saw, as "3002 lines read
    one by one"): the rules that keep moves off their route, or, where none does, that the cause is elsewhere.
    ``more_rules`` are rules the test added to the linter's; ``options`` the test's (``select``)."""
    rules = [*Linter(Options(dialect=dialect, **options)).rule_classes, *more_rules]
    blockers = route_blockers(dialect, rules)
    if blockers:
        return (
            f"{dialect}: {found}: these rules keep plain moves off their fast route (CONTRIBUTING.md, "
            "'A rule that reads moves'):\n  " + "\n  ".join(blockers)
        )
    return (
        f"{dialect}: {found}, though every rule keeps the plain-move route open: a rule's run_filter wants too "
        "many lines (returns None, or every line), or the interpreter refuses the runs (Interpreter.plain_run)"
    )
