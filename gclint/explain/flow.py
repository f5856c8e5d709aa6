"""Material flow on Hyrel: M229 (E values or native flow, and how the steps reach the head) and the
prime/unprime settings M721/M722."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.explain.addressing import target
from gclint.explain.generic import absent, generic, read, reading
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation
from gclint.syntax.nodes import Command


def _choice(exp: Explanation, cmd: Command, spec: Code | None, letter: str, otherwise: str) -> None:
    """A word whose values the table lists (``Param.values``); ``otherwise`` for any other value."""
    word = cmd.param(letter)
    if word is not None:
        values = spec.params[letter].values or {}  # type: ignore[union-attr,index]
        exp.add(word.text.strip(), values.get(word.value or "", otherwise))


def use_e_values(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    _choice(exp, cmd, spec, "E", "E must be 0 or 1")
    _choice(exp, cmd, spec, "D", "D must be 0 to 3")
    read(exp, cmd, spec, "S")
    e, d = cmd.params.get("E", ""), cmd.params.get("D", "")
    # "Note: E1 D0 is an illegal combination."; "M229 E1 D1 ... Above is the default way to enable E values."
    if e == "1" and d == "0":
        exp.warn("E1 D0 is an illegal combination (use M229 E1 D1)")
    elif e == "1" and "D" not in cmd.params:
        exp.note("M229 E1 D1 is the default way to enable E values")
    generic(job.dialect, exp, cmd, spec, skip="EDS")


def prime(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    for letter in "SE":
        word = cmd.param(letter)
        if word is not None:
            exp.add(word.text.strip(), reading(spec, letter, word.value or ""))
    p = cmd.param("P")
    if p is not None:
        v = p.value or ""
        if cmd.code == "M721":
            # "Pn is the number of milliseconds relative to the end of the move to begin the unprime (retract)
            # action; a negative number initiates this before the end of the move"
            exp.add(
                p.text.strip(),
                f"{v.lstrip('-')} ms {'before' if v.startswith('-') else 'after'} the end of the print move",
            )
        elif not v.startswith("-"):
            # M722 "Pn is the number of milliseconds to dwell relative to the start of the move to allow for the
            # prime (advance) action"; T_v5, One Head Loaded: "P20 (20ms before start of print move sequence)"
            exp.add(p.text.strip(), f"{v.lstrip('+')} ms before the start of the print move sequence")
        else:
            exp.add(
                p.text.strip(),
                f"{v} ms relative to the start of the print move: the pages decode a prime P only as a time "
                "before the start ('P20 (20ms before start of print move sequence)')",
            )
    target(job, exp, cmd, spec)
    i = cmd.param("I")
    if i is not None and i.value == "1":
        exp.add(i.text.strip(), reading(spec, "I", i.value))
    else:
        exp.note(absent(spec, "I"))
    generic(job.dialect, exp, cmd, spec, skip="SEPTI")


def layer_height(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """M756: the layer height of native flow, "ignored if you are using M229 E1 D1 to enable use of E
    values" (M756 Set Height for Flow)."""
    generic(job.dialect, exp, cmd, spec)
    state = job.state
    if state.e_values():
        exp.warn(
            f"ignored: E values are enabled (M229 E1 on line {state.m229_line}); 'this command is ignored if you "
            "are using M229 E1 D1 to enable use of E values'"
        )


def decoders(job: Job) -> dict[str, Decoder]:
    facts = job.facts
    return {
        **dict.fromkeys(facts.codes_with("flow-mode"), use_e_values),
        **dict.fromkeys(facts.codes_with("unprime", "prime"), prime),
        **dict.fromkeys(facts.codes_with("layer-height"), layer_height),
    }
