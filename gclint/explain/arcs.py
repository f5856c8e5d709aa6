"""Hyrel arcs and spirals: G2/G3, the G2.1/G2.2 spirals (and G3.x), the G2.3 arcs in 3-space.  The words'
readings are the table's; what depends on a number (S: a segment length below 3, a segment count from 3)
or on the job (relative or absolute ends, the arc plane) is read here."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.explain.generic import absent, does, generic, notes, read, read_or_absent
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation, fmt, number
from gclint.explain.motion import axis_text
from gclint.syntax.nodes import Command

# The arc planes of G2.x/G3.x (G16 Arc Plane: Any ... G19 Arc Plane: YZ; G2.3: "If we are in G16 mode, Un,
# Vn, Wn define the vector normal to the work plane")
PLANES = {16: "any plane (U V W give the normal vector)", 17: "X/Y plane", 18: "X/Z plane", 19: "Y/Z plane"}


def arc(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    does(exp, spec)
    for letter in "XYZ":
        word = cmd.param(letter)
        if word is not None:
            exp.add(word.text.strip(), axis_text(job, letter, word.value))
    read(exp, cmd, spec, "I")
    read(exp, cmd, spec, "J")
    segments(exp, cmd, spec)
    read(exp, cmd, spec, "E")
    read_or_absent(exp, cmd, spec, "F")
    notes(exp, spec)
    generic(job.dialect, exp, cmd, spec, skip="XYZIJSEF")


def segments(exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """S: "S values less than 3.0 dictate the length in mm of each segment ...; S values of 3.0 or more
    dictate how many total segments comprise this element - only allowed on complete circles" (G2)."""
    word = cmd.param("S")
    if word is None:
        exp.note(absent(spec, "S"))
        return
    value = number(word.value)
    if value is None:
        exp.add(word.text.strip(), "segment length or count")
    elif value < 3:
        exp.add(word.text.strip(), f"segments {word.value} mm long")
    else:
        exp.add(word.text.strip(), f"made up of {fmt(value)} segments (only allowed on complete 360° circles)")


def spiral(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    laps_around_start = (cmd.code or "").endswith(".1")  # G2.1/G3.1: no X/Y, an R direction flag
    does(exp, spec)
    for letter in "XYZ":
        word = cmd.param(letter)
        if word is not None:
            exp.add(word.text.strip(), (spec.meaning(letter) if spec is not None else None) or letter)
    read(exp, cmd, spec, "I")
    read(exp, cmd, spec, "J")
    read_or_absent(exp, cmd, spec, "L")
    read(exp, cmd, spec, "P")
    read(exp, cmd, spec, "E")
    segments(exp, cmd, spec)
    if laps_around_start:
        r = cmd.param("R")
        if r is not None:
            values = spec.params["R"].values or {}  # type: ignore[union-attr,index]
            exp.add(r.text.strip(), values.get(r.value or "", "unknown spiral direction flag"))
        else:
            exp.note(absent(spec, "R"))
    read_or_absent(exp, cmd, spec, "F")
    generic(job.dialect, exp, cmd, spec, skip="XYZIJLPESRF")


def arc3(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    does(exp, spec)
    plane = job.state.plane
    exp.note(f"arc plane: {PLANES.get(plane, 'X/Y plane')}")
    normal = "".join(letter for letter in "UVW" if letter in cmd.params)
    if normal and plane != 16:
        # G2.3: "If we are in G17 (X/Y plane) or G18 (X/Z plane) or G19 (Y/Z plane) mode, these are ignored."
        exp.warn(f"{' '.join(normal)} ignored: the normal vector applies only in G16 mode (here G{plane})")
    segments(exp, cmd, spec)
    generic(job.dialect, exp, cmd, spec, skip="S")


def centre_mode(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """G90.1 / G91.1 (LinuxCNC, "G90.1, G91.1 Arc Distance Mode": https://linuxcnc.org/docs/html/gcode/g-code.html#gcode:g90.1-g91.1)."""
    if job.facts.effect(cmd.code) == "arc-absolute":
        exp.note("arc centres from here on: I, J and K are the centre's absolute coordinates")
    else:
        exp.note("arc centres from here on: I, J and K are offsets from the arc's start point")
    generic(job.dialect, exp, cmd, spec)


def centre_arc(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """G2/G3 where the dialect switches the arc-centre mode (``Semantics.arc_centre_modes``): I J K read in the mode
    in force, P as the dialect counts turns, S as the spindle speed where it is one."""
    from gclint.explain.motion import spindle_speed

    does(exp, spec)
    for letter in "XYZ":
        word = cmd.param(letter)
        if word is not None:
            exp.add(word.text.strip(), axis_text(job, letter, word.value))
    absolute = job.state.arc_absolute
    for letter, axis in (("I", "X"), ("J", "Y"), ("K", "Z")):
        word = cmd.param(letter)
        if word is None:
            continue
        if absolute:
            exp.add(word.text.strip(), f"centre at {axis}{word.value}, absolute under G90.1")
        else:
            exp.add(word.text.strip(), f"centre {word.value} from the start in {axis}, an offset under G91.1")
    r = cmd.param("R")
    if r is not None:
        exp.add(r.text.strip(), f"radius {r.value}")
    p = cmd.param("P")
    if p is not None:
        turns = "turns (P1 is the arc itself)" if job.facts.arc_turns == "turns" else "extra full circles"
        exp.add(p.text.strip(), f"{p.value} {turns}")
    f = cmd.param("F")
    if f is not None:
        exp.add(f.text.strip(), f"moving at {f.value} mm/min")
    spindle_speed(job, exp, cmd)
    generic(job.dialect, exp, cmd, spec, skip="XYZIJKRPFS")


def decoders(job: Job) -> dict[str, Decoder]:
    """The arcs whose words the dialect's table catalogues (Hyrel's G2/G3 S, the spirals, the 3-space arcs):
    others are read from the table alone."""
    table: dict[str, Decoder] = {}
    if job.facts.arc_centre_modes:
        table.update(dict.fromkeys(job.facts.codes_with("arc-absolute", "arc-relative"), centre_mode))
        table.update(dict.fromkeys(job.facts.codes_with("arc"), centre_arc))
        return table
    for code in job.facts.codes_with("arc", "spiral-in-place"):
        spec = job.dialect.spec(code)
        if spec is None or spec.params is None:
            continue
        if "L" in spec.params or (job.facts.effect(code) == "spiral-in-place"):
            table[code] = spiral
        elif "U" in spec.params:
            table[code] = arc3
        else:
            table[code] = arc
    return table
