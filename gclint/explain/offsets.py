"""Position and offsets: G28 (home), G92 (set the position), and Hyrel's M6 (declare head offsets) and
M660 (tool-height registers, applied by H on a move)."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.explain.addressing import target
from gclint.explain.generic import absent, does, generic, notes, read, reading
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation, number
from gclint.rules.hyrel.offsets import home_value_message, m6_message
from gclint.syntax.nodes import Command


def _signed(value: str) -> str:
    """A value with its sign written out: ``+20``, ``-30`` ("X20 (X+20)", "Z28.2 (+28.2 to Z position)")."""
    return value if value.startswith(("-", "+")) else "+" + value


def home(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    listed = [a for a in "XYZAB" if a in cmd.params]
    home_form = job.facts.home
    if home_form == "listed":
        does(exp, spec)
        for axis in "XYZAB":
            if read(exp, cmd, spec, axis) is None:
                exp.note(absent(spec, axis))
            elif job.addressed and (message := home_value_message(cmd, axis)) is not None:
                exp.warn(message)  # (as HY025 reports it)
        if not listed:
            # "Any axis not homed will have its position remain unchanged" (G28 Send X, Y to Physical Home)
            exp.warn("no axis listed: Hyrel homes only the axes named (G28 X0 Y0)")
        notes(exp, spec)
    elif home_form == "all-if-none":
        if listed:
            for axis in listed:
                exp.add(cmd.param(axis).text.strip(), f"home {axis}")  # type: ignore[union-attr]
        else:
            exp.note("no axis listed: home all axes")
    else:
        exp.note(
            {
                "predefined": "go through the listed axes' point (in the current distance mode, offsets "
                "included), then to the stored G28 position (parameters 5161-5169; machine zero if none stored)",
                "zero-listed": "rapid to zero on the listed axes (all when none is listed)",
            }.get(home_form, "go to the clearance (G28) position")
        )
        generic(job.dialect, exp, cmd, spec)


def set_position(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    exp.note("replace the current position values (no motion)")
    for word in cmd.words:
        if word.letter in "XYZABE":
            exp.add(
                word.text.strip(),
                f"present {word.letter} position is {word.value if word.value is not None else 0}",
            )
        else:
            generic(
                job.dialect,
                exp,
                Command(cmd.code, cmd.kind, cmd.column, {word.letter: word.value}, words=(word,)),
                spec,
            )


def declare_offsets(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    # "M6 T# O..." is the header line that declares the head: it is loaded from this line on
    target(job, exp, cmd, spec, declares="O" in cmd.params)
    message = m6_message(cmd.params)
    if message is not None:
        exp.warn(message)  # (as HY038 reports it)
    if read(exp, cmd, spec, "O") is None and any(axis in cmd.params for axis in "XYZAB"):
        exp.warn(absent(spec, "O"))  # M6 K1: "(no offset registers, so ignore all offsets)"
    for axis in "XYZAB":
        word = cmd.param(axis)
        if word is not None:
            exp.add(word.text.strip(), f"{axis}{_signed(word.value or '0')}")
    read(exp, cmd, spec, "D")
    if read(exp, cmd, spec, "I") is None and "T" in cmd.params:
        exp.note(absent(spec, "I"))
    read(exp, cmd, spec, "K")
    notes(exp, spec)
    generic(job.dialect, exp, cmd, spec, skip="TOXYZABDIK")


def height_offset(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    h = read(exp, cmd, spec, "H")
    z = cmd.param("Z")
    if z is not None:
        sign = "+" if (number(z.value) or 0) >= 0 and not (z.value or "").startswith("+") else ""
        exp.add(z.text.strip(), reading(spec, "Z", f"{sign}{z.value}"))
    # "M660 Hn Zn (followed by) G1 ... Hn"; "NOTE: You MUST have a G28 Z0 in your header to run this M660 on
    # the EHR." (M660 Assign Tool Height Offset)
    exp.note(f"applied only when a G1 carries H{h.value if h is not None else 'n'}; the EHR needs G28 Z0 in the header")
    generic(job.dialect, exp, cmd, spec, skip="HZ")


def decoders(job: Job) -> dict[str, Decoder]:
    facts = job.facts
    table: dict[str, Decoder] = dict.fromkeys(facts.codes_with("home", "home-reset-offsets"), home)
    table["G92"] = set_position
    table.update(dict.fromkeys(facts.codes_with("declare-head-offsets"), declare_offsets))
    table.update(dict.fromkeys(facts.codes_with("height-offset"), height_offset))
    return table
