"""Lasers, UV pens and spindles: M620/M621/M623 (Hyrel), M3/M4/M5, the CNC tool change M6 (LinuxCNC,
Carvera) and Hyrel's G81 peck drilling.  Which emitter is enabled and whether an M660 offset is applied
is the job's; the words' readings are the table's."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.explain.addressing import target
from gclint.explain.generic import absent, does, generic, notes, read, read_or_absent, reading
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation, fmt, number
from gclint.rules.hyrel.lasers_spindles import rpm_message
from gclint.syntax.nodes import Command

# M623 "Dn max for UV pens is 60,000 (1 minute); Dn max for other devices 1,000 (1 second)"
EMIT_MAX_MS = 1000
UV_PEN_EMIT_MAX_MS = 60000


def enable_device(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    if "T" not in cmd.params:
        exp.warn(absent(spec, "T"))
    else:
        target(job, exp, cmd, spec)
    e = cmd.param("E")
    if e is None:
        exp.note(absent(spec, "E"))
    elif e.value in ("0", "1"):
        exp.add(e.text.strip(), reading(spec, "E", e.value))
    read(exp, cmd, spec, "A")
    generic(job.dialect, exp, cmd, spec, skip="TEA")


def laser_power(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    does(exp, spec)
    p = read(exp, cmd, spec, "P")
    if read(exp, cmd, spec, "D") is None and p is not None:
        exp.note(absent(spec, "D"))
    if not job.state.laser_enabled_any:
        exp.warn("no M620 T# E1 enabled a laser before this line")
    generic(job.dialect, exp, cmd, spec, skip="PD")


def emit(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    does(exp, spec)
    read(exp, cmd, spec, "P")
    d = cmd.param("D")
    if d is not None:
        value = number(d.value)
        secs = f" ({fmt(value / 1000)} seconds)" if value is not None and value >= 1000 else ""
        exp.add(d.text.strip(), reading(spec, "D", d.value) + secs)
        if value is not None and value > EMIT_MAX_MS:
            exp.note("D above 1,000 ms is only allowed for UV pens (max 60,000); other devices stop at 1,000")
        if value is not None and value > UV_PEN_EMIT_MAX_MS:
            exp.warn("D is above the UV pen maximum of 60,000 ms")
    generic(job.dialect, exp, cmd, spec, skip="PD")


def spindle(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    direction = "clockwise" if cmd.code == "M3" else "counter-clockwise"
    exp.note(f"start the spindle {direction}")
    s = cmd.param("S")
    if job.addressed:
        target(job, exp, cmd, spec)
        if s is not None:
            exp.add(s.text.strip(), reading(spec, "S", "0" if number(s.value) == 0 else s.value))
            message = rpm_message(cmd)
            if message is not None:
                exp.warn(message)  # (as HY023 reports it)
        read_or_absent(exp, cmd, spec, "F")
        notes(exp, spec)
        generic(job.dialect, exp, cmd, spec, skip="TSF")
    else:
        if s is not None:
            exp.add(s.text.strip(), f"at {s.value} RPM")
        generic(job.dialect, exp, cmd, spec, skip="S")


def spindle_off(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    exp.note("stop the spindle")
    if job.addressed:
        target(job, exp, cmd, spec)
        generic(job.dialect, exp, cmd, spec, skip="T")
    else:
        generic(job.dialect, exp, cmd, spec)


def tool_change(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """M6 on LinuxCNC and Carvera: change to the tool T names (or the one the last T selected)."""
    t = cmd.param("T")
    prepared = job.state.prepared_tool
    facts = job.facts
    named = number(t.value) if t is not None else None
    if t is not None and named is not None and named == facts.no_tool:
        exp.add(t.text.strip(), "no tool: the spindle is emptied")
    elif t is not None and named is not None and named == facts.probe_tool:
        exp.add(t.text.strip(), f"change to the probe: T{t.value} is the machine's wireless probe, not a cutting tool")
    elif t is not None:
        exp.add(t.text.strip(), f"change to tool {t.value}")
    elif prepared is not None and prepared == job.facts.no_tool:
        exp.note(f"T{prepared} was selected: no tool, the spindle is emptied")
    elif prepared is not None:
        exp.note(f"change to the tool selected by T (T{prepared})")
    else:
        exp.note("change to the tool selected by T")
    if facts.tool_change_stops_spindle:
        exp.note("the spindle is stopped by the tool change; it runs again only at the next M3/M4")
    generic(job.dialect, exp, cmd, spec, skip="T")


def peck_drill(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    does(exp, spec)
    if "T" in cmd.params:
        target(job, exp, cmd, spec)
    x, y = cmd.param("X"), cmd.param("Y")
    if x is not None or y is not None:
        # "X100 Y75 (move to X/Y starting position X100 Y75)" (G81 Peck Drilling)
        words = " ".join(w.text.strip() for w in (x, y) if w is not None)
        exp.add(words, f"move to the X/Y starting position {words}")
    for letter in "IPQZF":
        word = cmd.param(letter)
        if word is not None:
            value = word.value or ""
            # Q and Z are distances: "Q-2 (retract upward 2mm ...)", "Z-7.5 (peck to a maximum depth of 7.5mm)"
            exp.add(word.text.strip(), reading(spec, letter, value.lstrip("-") if letter in "QZ" else value))
    notes(exp, spec)
    if job.state.applied_height_register is None:
        # "NOTE that an M660 offset must be set and applied BEFORE THIS COMMAND to allow for tool length."
        exp.warn("an M660 offset must be set and applied (G1 H#) before G81, to allow for tool length")
    generic(job.dialect, exp, cmd, spec, skip="TXYIPQZF")


def decoders(job: Job) -> dict[str, Decoder]:
    facts = job.facts
    table: dict[str, Decoder] = {}
    for effects, decoder in (
        (("emitter",), enable_device),
        (("emitter-power",), laser_power),
        (("emit",), emit),
        (("peck-drill",), peck_drill),
        (("tool-change",), tool_change),
    ):
        table.update(dict.fromkeys(facts.codes_with(*effects), decoder))
    if job.addressed or facts.working == "feeds":  # (a Marlin M3 is a laser or spindle the job may not have)
        table.update(dict.fromkeys(facts.codes_with("spindle-cw", "spindle-ccw"), spindle))
        table.update(dict.fromkeys(facts.codes_with("spindle-off"), spindle_off))
    return table
