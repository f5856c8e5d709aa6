"""Fans and UV LEDs: M106 and M107.  On Hyrel, S is a share of the range M106 C set earlier in the job
(default 0-100); elsewhere a 0-255 value (or, on RepRapFirmware, a 0-1 fraction)."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.explain.addressing import target
from gclint.explain.generic import absent, does, generic, read, reading
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation, fmt, number
from gclint.syntax.nodes import Command


def fan(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    if job.facts.fan_scale != "range":
        _fan_reprap(job, exp, cmd, spec)
        return
    c_word = cmd.param("C")
    c = number(c_word.value) if c_word is not None else None
    # "M106 C255 ... ** (on all tools) ** (no speed) ** C255 (of range 0-255)" (M106 Set Cooling / Etc.)
    c_alone = c_word is not None and not any(x in cmd.params for x in "SP")
    if c_alone and "T" not in cmd.params:
        exp.note("on all tools")
    else:
        target(job, exp, cmd, spec)
    fan_range = c if c is not None and c > 0 else job.state.fan_range
    s = cmd.param("S")
    if s is not None:
        value = number(s.value)
        if value is not None and fan_range:
            share = value / fan_range * 100
            exp.add(
                s.text.strip(),
                f"{reading(spec, 'S', s.value)} of range 0-{fmt(fan_range)}: {fmt(round(share, 1))}% duty",
            )
            if value > fan_range:
                exp.warn(f"S{s.value} is above the range 0-{fmt(fan_range)} (M106 C sets the range)")
        else:
            exp.add(s.text.strip(), reading(spec, "S", s.value))
    elif c_word is not None and "P" not in cmd.params:
        exp.note(absent(spec, "S"))
    if c_word is not None:
        read(exp, cmd, spec, "C")
    elif s is not None:
        src = f"set by M106 C at line {job.state.fan_range_line}" if job.state.fan_range_line else "default 0-100"
        exp.note(f"range 0-{fmt(job.state.fan_range)} ({src})")
    read(exp, cmd, spec, "P")
    generic(job.dialect, exp, cmd, spec, skip="TSCP")


def _fan_reprap(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    if spec is not None and spec.params is not None:  # (the table catalogues its words: Machinekit's P and T)
        generic(job.dialect, exp, cmd, spec)
        return
    p = cmd.param("P")
    if p is not None:
        exp.add(p.text.strip(), f"fan number {p.value}")
    s = cmd.param("S")
    if s is not None:
        value = number(s.value)
        if value is not None and value <= 1 and "." in (s.value or "") and job.facts.fan_scale == "255-or-fraction":
            exp.add(s.text.strip(), f"fan speed {fmt(value * 100)}% (RepRapFirmware reads 0-1 as a fraction)")
        elif value is not None:
            exp.add(s.text.strip(), f"fan speed {s.value} of 255: {fmt(round(value / 255 * 100, 1))}%")
    else:
        exp.note("no S: full speed")
    generic(job.dialect, exp, cmd, spec, skip="PS")


def fan_off(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    if job.addressed:
        target(job, exp, cmd, spec)
        does(exp, spec)
    else:
        exp.note("fan off")
        generic(job.dialect, exp, cmd, spec)


def decoders(job: Job) -> dict[str, Decoder]:
    return {"M106": fan, "M107": fan_off}
