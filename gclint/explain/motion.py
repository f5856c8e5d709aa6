"""Moves and modes: G0/G1 (and axis words repeating the modal motion), G4, G90/G91, M82/M83.  Where a
move goes depends on the job (absolute or relative, inches or mm, the feed set earlier, the flow mode,
the M660 registers stored); what its words mean is the dialect table's."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.dialects.semantics import computed
from gclint.explain.generic import does, generic, reading
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation, Item, fmt, number
from gclint.machine.state import EVALUES
from gclint.rules.hyrel.motion import native_e_message
from gclint.syntax.nodes import Command


def axis_text(job: Job, letter: str, value: str | None) -> str:
    unit = "in" if job.state.units == "inch" else "mm"
    if value is None:
        return f"{letter} with no value"
    if computed(value):
        return f"{letter} from {value}, a value computed when the line runs (expression, parameter or function; not evaluated here)"
    if job.state.absolute:
        return f"to {letter}{value}"
    n = number(value)
    if n is None:
        return f"by {value} {unit} in {letter}"
    return f"{'+' if n >= 0 else ''}{fmt(n)} {unit} in {letter}"


def spindle_speed(job: Job, exp: Explanation, cmd: Command) -> bool:
    """S where the dialect sets a line's S before its commands, whatever they are (LinuxCNC, "G-code Order of
    Execution": "Set spindle speed (S)"): the spindle speed, a change of speed if the spindle runs.  False when S
    means something else there (the caller reads it)."""
    word = cmd.param("S")
    if word is None or "S" not in job.facts.words_first:
        return False
    value = word.value
    what = f"{value} rpm" if number(value) is not None else f"the value {value}"
    exp.add(
        word.text.strip(),
        f"spindle speed {what}, set before the line's other commands run; a running spindle changes speed",
    )
    return True


def move(job: Job, exp: Explanation, cmd: Command, spec: Code | None, mode: str) -> None:
    """A G0 or G1 (or axis words under modal ``mode``).  ``spec`` is the mode's; what the words of a
    straight move mean is read from G0's or G1's."""
    p = cmd.params
    line = job.dialect.spec("G0" if mode == "G0" else "G1")
    if mode == "G0":
        exp.note("rapid (non-working) straight line move from the current location")
    elif line is not None and line.does:
        does(exp, line)
    else:
        exp.note("straight line move")
    for letter in "XYZAB":
        word = cmd.param(letter)
        if word is not None:
            exp.add(word.text.strip(), axis_text(job, letter, word.value))
    for letter in "AB":  # (what the table says of a move without A or B: Hyrel's "no change in A")
        param = line.param(letter) if line is not None else None
        if param is not None and param.absent and letter not in p and any(a in p for a in "XYZ"):
            exp.note(param.absent)
    e = cmd.param("E")
    if e is not None:
        if mode == "G0" and not job.facts.g0_extrudes:
            exp.items.append(
                Item(e.text.strip(), "E on a G0 does nothing: G0 never works", job.facts.e_values == "native")
            )
        elif job.facts.e_values == "native" and job.state.flow_mode != EVALUES:
            message = native_e_message(p, job.state.e_absolute, job.state.e_position) if mode == "G1" else None
            if message is not None and not any(a in p for a in "XYZAB"):
                exp.add(e.text.strip(), "no motion: native flow dispenses by move length, so nothing is dispensed")
            else:
                exp.add(e.text.strip(), reading(line, "E", e.value))
            if message is not None:
                exp.warn(message)  # (as HY031 reports it)
        elif job.state.e_absolute:
            exp.add(e.text.strip(), f"extrude until the E position is {e.value}")
        else:
            exp.add(
                e.text.strip(),
                f"extrude {e.value} mm of filament"
                if number(e.value) and (number(e.value) or 0) > 0
                else f"E by {e.value} (retract)",
            )
    f = cmd.param("F")
    rapid_ignores_f = mode == "G0" and job.facts.g0_feed == "rapid"  # (LinuxCNC: G0 at the machine's rapid rate)
    if f is not None and rapid_ignores_f:
        exp.add(f.text.strip(), f"the feed of later feed moves, {f.value} mm/min; this rapid ignores it")
    elif rapid_ignores_f:
        exp.note("at the machine's rapid rate: G0 ignores the feed rate F")
    elif f is not None:
        if mode == "G0" and job.interpreter.g0_feed_one_shot:
            exp.add(f.text.strip(), f"one-time speed of {f.value} mm/min, not persistent")
        else:
            exp.add(f.text.strip(), f"moving at {f.value} mm/min")
    elif mode == "G0" and line is not None and line.param("F") is not None and line.param("F").absent:  # type: ignore[union-attr]
        exp.note(line.param("F").absent)  # type: ignore[union-attr]
    elif job.state.feed is not None:
        exp.note(f"using the previously set F{fmt(job.state.feed)}")
    h = cmd.param("H")
    if h is not None and job.interpreter.height_registers:
        _height_register(job, exp, h.text.strip(), h.value, line)  # (on a G0 too: HY034)
    s = cmd.param("S")
    if s is not None and spindle_speed(job, exp, cmd):
        pass
    elif s is not None:
        s_param = spec.param("S") if spec is not None else None
        if mode == "G1" and s_param is not None and (s_param.says or s_param.values):
            exp.add(s.text.strip(), reading(spec, "S", s.value))
        else:
            exp.add(s.text.strip(), (spec.meaning("S") if spec is not None else None) or f"S{s.value}")
    generic(job.dialect, exp, cmd, spec, skip="XYZABEFHS")


def _height_register(job: Job, exp: Explanation, word: str, value: str | None, line: Code | None) -> None:
    """``H`` on a Hyrel move: the register an M660 stored earlier in the job, and what it holds."""
    register = number(value)
    offsets = job.state.tool_height_offsets
    whole = register is not None and register == int(register)
    stored = offsets.get(int(register)) if whole else None  # type: ignore[arg-type]
    if whole and int(register) in offsets:  # type: ignore[arg-type]
        extra = f": Z{'+' if (stored or 0) >= 0 else ''}{fmt(stored)} stored by M660" if stored is not None else ""
        exp.add(word, reading(line, "H", str(int(register))) + extra)  # type: ignore[arg-type]
    else:
        exp.add(word, reading(line, "H", value))
        exp.warn(f"no M660 H{value} stored an offset before this line")


def dwell(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """G4: the words the dialect counts time with (``Semantics.dwell``), and the pause they make, the same
    number the summary, the diff and the translator use."""
    rule = job.facts.dwell
    timed = []
    for letter in "SP":
        word = cmd.param(letter)
        if word is None:
            continue
        unit = rule.unit(letter)
        if unit is None:
            if letter == "S" and spindle_speed(job, exp, cmd):
                continue
            exp.add(word.text.strip(), f"{(spec.meaning(letter) if spec else None) or letter}: not a dwell time")
        else:
            exp.add(word.text.strip(), f"{cmd.raw(letter)} {unit}")
            timed.append(letter)
    seconds = exp.seconds = rule.seconds(cmd.params)
    if rule.refused(cmd.params):
        exp.warn(
            f'G4 without {rule.required}: the machine refuses this line and stops the program (LinuxCNC: "Dwell time '
            'missing with g4"); nothing after it runs'
        )
    elif rule.p_seconds is None and rule.s_seconds is None:
        exp.note("how long this dialect dwells is not known")
    elif seconds is None:
        exp.note("no dwell time given: no pause")
    elif len(timed) > 1:
        exp.note(f"pause for {fmt(seconds)} s in all ({rule.describe()})")
    else:
        exp.note(f"pause for {fmt(seconds)} s")


def _mode(text: str) -> Decoder:
    def decode(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        exp.note(text)

    return decode


def decoders(job: Job) -> dict[str, Decoder]:
    return {
        "G0": lambda job, exp, cmd, spec: move(job, exp, cmd, spec, "G0"),
        "G1": lambda job, exp, cmd, spec: move(job, exp, cmd, spec, "G1"),
        "G4": dwell,
        "G90": _mode("positions (X Y Z A B) are absolute from here on"),
        "G91": _mode("positions (X Y Z A B) are relative to the last position from here on"),
        "M82": _mode("E values are absolute from here on"),
        "M83": _mode("E values are relative from here on"),
    }
