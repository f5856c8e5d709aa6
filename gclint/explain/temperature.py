"""Temperatures and waits: M104/M140/M141 (set), M109/M190/M191 (wait, with Hyrel's H C L U R window and
W0), M116.  The readings of the words are the dialect table's; the window the wait ends in is computed
here from S and the job's set points."""

from __future__ import annotations

from gclint.dialects.base import Code
from gclint.explain.addressing import target
from gclint.explain.generic import absent, does, generic, reading
from gclint.explain.job import Decoder, Job
from gclint.explain.model import DEG, Explanation, Item, fmt, number
from gclint.rules.hyrel.temperature import r_target_message
from gclint.syntax.nodes import Command

# The address of the primary bed and chamber: "T24 Bed1 / Chamber1" (T_v5 Chart of Addresses)
PRIMARY_BED = 24


def set_point(value: str | None) -> str:
    return f"to {value}{DEG}" + (" (off)" if number(value) == 0 else "")


def set_temperature(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    if job.addressed:
        target(job, exp, cmd, spec)
    elif "T" in cmd.params:
        exp.add(cmd.param("T").text.strip(), f"extruder/tool {cmd.raw('T')}")  # type: ignore[union-attr]
    s = cmd.param("S")
    if s is not None:
        exp.add(s.text.strip(), set_point(s.value))
    exp.note("set the temperature and go on without waiting")
    generic(job.dialect, exp, cmd, spec, skip="TS")


def wait_temperature(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    if job.facts.wait_r != "tolerance":
        _wait_reprap(job, exp, cmd, spec)
        return
    code = cmd.code or ""
    address = target(job, exp, cmd, spec, physical=True)
    s_word = cmd.param("S")
    s = number(s_word.value) if s_word is not None else None
    if s_word is not None:
        exp.add(s_word.text.strip(), reading(spec, "S", s_word.value) if s else f"to {s_word.value}{DEG}")
    else:
        key = (
            address.v5
            if address is not None and address.v5 is not None
            else (job.state.tool if code == "M109" else PRIMARY_BED)
        )
        known = job.state.targets.get(key) if key is not None else None
        exp.note(absent(spec, "S") + (f"; the set point stays {fmt(known)}{DEG}" if known is not None else ""))
        s = known
    low, high = _window(exp, cmd, spec, s)
    _mixed_window(exp, cmd)
    message = r_target_message(cmd)
    if message is not None:
        exp.warn(message)  # (as HY035 reports it)
    if low is not None and high is not None:
        exp.note(f"the wait ends when the temperature is anywhere between {fmt(low)}{DEG} and {fmt(high)}{DEG}")
    elif low is not None:
        exp.note(f"the wait ends once the temperature is {fmt(low)}{DEG} or more")
    elif high is not None:
        exp.note(f"the wait ends once the temperature is {fmt(high)}{DEG} or less")
    w = cmd.param("W")
    if w is not None:
        if w.value == "0":
            exp.add(w.text.strip(), reading(spec, "W", w.value))
            if job.firmware == 4:
                exp.warn("W0 and M116 exist from v5 on")
        else:
            exp.items.append(Item(w.text.strip(), "only W0 is defined", True))
    generic(job.dialect, exp, cmd, spec, skip="TSHCLURW")


def _window(exp: Explanation, cmd: Command, spec: Code | None, s: float | None) -> tuple[float | None, float | None]:
    """Add the H C L U R words; the temperatures the wait ends between (None: no bound on that side).
    H and C are absolute, L and U relative to the set point S, R both ways (M109 Wait for Temp (Head))."""
    low = high = None
    for letter in ("H", "C", "L", "U", "R"):
        word = cmd.param(letter)
        if word is None:
            continue
        exp.add(word.text.strip(), reading(spec, letter, word.value))
        value = number(word.value)
        if letter == "H":
            low = value
        elif letter == "C":
            high = value
        elif letter == "L":
            low = s - value if s is not None and value is not None else None
        elif letter == "U":
            high = s + value if s is not None and value is not None else None
        elif s is not None and value is not None:
            low, high = s - value, s + value
    return low, high


def _mixed_window(exp: Explanation, cmd: Command) -> None:
    # "Please use EITHER (H and/or C) OR (L and/or U) OR (R)"; "You can use Hn or Ln, but not both. You can
    # use Cn or Un, but not both." (M109 Wait for Temp (Head))
    groups = []
    if any(x in cmd.params for x in "HC"):
        groups.append("H/C")
    if any(x in cmd.params for x in "LU"):
        groups.append("L/U")
    if "R" in cmd.params:
        groups.append("R")
    if len(groups) > 1:
        exp.warn(
            "the Hyrel page says: use EITHER (H and/or C) OR (L and/or U) OR (R); this mixes " + " and ".join(groups)
        )
    if "H" in cmd.params and "L" in cmd.params or "C" in cmd.params and "U" in cmd.params:
        exp.warn("you can use H or L, but not both; C or U, but not both")


def _wait_reprap(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """M109/M190 as RepRap-family firmware reads them: S waits only while heating, R both ways."""
    code = cmd.code or ""
    what = "bed" if code == "M190" else "hotend"
    if "T" in cmd.params and code == "M109":
        exp.add(cmd.param("T").text.strip(), f"extruder/tool {cmd.raw('T')}")  # type: ignore[union-attr]
    s = cmd.param("S")
    r = cmd.param("R")
    if job.facts.wait_r is None:  # (its words are the dialect table's: Machinekit's remap takes P and T)
        generic(job.dialect, exp, cmd, spec)
        return
    if s is not None:
        exp.add(s.text.strip(), f"set the {what} to {s.value}{DEG} and wait only while heating up to it")
    if r is not None:
        exp.add(r.text.strip(), f"set the {what} to {r.value}{DEG} and wait while heating or cooling to it")
    if s is None and r is None:
        exp.note(f"no S or R: wait for the {what} target already set")
    generic(job.dialect, exp, cmd, spec, skip="TSR")


def wait_all(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    does(exp, spec)


def decoders(job: Job) -> dict[str, Decoder]:
    table: dict[str, Decoder] = {
        "M104": set_temperature,
        "M140": set_temperature,
        "M109": wait_temperature,
        "M190": wait_temperature,
    }
    if job.addressed:  # (a chamber is a device with an address)
        table.update({"M141": set_temperature, "M191": wait_temperature})
    table.update(dict.fromkeys(job.facts.codes_with("wait-pending"), wait_all))
    return table
