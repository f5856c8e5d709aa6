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
        # M721: "milliseconds relative to the end of the move ...; a negative number initiates this before
        # the end of the move"; M722: "relative to the start of the move"
        v = p.value or ""
        edge = "end" if cmd.code == "M721" else "start"
        exp.add(
            p.text.strip(),
            f"{v.lstrip('-')} ms {'before' if v.startswith('-') else 'after'} the {edge} of the print move",
        )
    target(job, exp, cmd, spec)
    i = cmd.param("I")
    if i is not None and i.value == "1":
        exp.add(i.text.strip(), reading(spec, "I", i.value))
    else:
        exp.note(absent(spec, "I"))
    generic(job.dialect, exp, cmd, spec, skip="SEPTI")


def decoders(job: Job) -> dict[str, Decoder]:
    facts = job.facts
    return {
        **dict.fromkeys(facts.codes_with("flow-mode"), use_e_values),
        **dict.fromkeys(facts.codes_with("unprime", "prime"), prime),
    }
