"""T addressing: the T variable of an M-code (v5 and v4 numbers, the head with focus), T command lines,
clone squads (M702-M704).  What a number addresses is gclint.dialects.addressing's; which heads are
loaded, which has focus and which squads exist is the job's (``MachineState``)."""

from __future__ import annotations

from gclint.dialects.addressing import GROUP, HEAD, VIRTUAL, Address, resolve_v5, yoke_label
from gclint.dialects.base import Code
from gclint.explain.generic import generic, notes, read
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation, number
from gclint.syntax.nodes import Command, Line

TARGET_HEAD = "target head: {value}"


def address_text(job: Job, address: Address) -> str:
    if job.firmware == 4:
        # v4 labels read "yoke 1, position 1 (v4 T11)"; add the v5 number the rest of gclint speaks
        text = address.label
        if address.v5 is not None and text.endswith(")"):
            text = f"{text[:-1]} = v5 T{address.v5})"
        if address.kind == HEAD:
            text = "head at " + text
    elif address.kind == HEAD and address.v5 is not None:
        text = f"head T{address.v5} ({yoke_label(address.v5)})"
    else:
        text = address.label
    if not address.certain:
        text += "; this v4 correspondence is inferred, not documented"
    return text


def focus_default(job: Job) -> str:
    # "M109 R10 ... (no T# - use head with current focus)" (M109 Wait for Temp (Head), example 6)
    focus = job.state.tool
    return "no T: use the head with current focus" + (f" (T{focus})" if focus is not None else "")


def target(
    job: Job,
    exp: Explanation,
    cmd: Command,
    spec: Code | None,
    role: str | None = None,
    physical: bool = False,
    declares: bool = False,
) -> Address | None:
    """Decode the T variable of an M-code, as the table reads it (``Param.says``, "target head" unless it
    says otherwise; ``role`` where the reading depends on another word); without T, the table's ``absent``
    or the head with focus.  ``physical``: the code fails on a virtual or group address.  ``declares``:
    the command itself declares the head loaded (Repetrel's ``M6 T# O...``), so it takes effect on it."""
    word = cmd.param("T")
    param = spec.param("T") if spec is not None else None
    if word is None:
        exp.note(param.absent if param is not None and param.absent else focus_default(job))
        return None
    reading = role or (param.says if param is not None and param.says else TARGET_HEAD)
    address = job.interpreter.address(cmd)
    if address is None:
        exp.add(word.text.strip(), reading.format(value=f"{word.value!r} is not a device number"))
        return None
    text = address_text(job, address)
    if reading == TARGET_HEAD and text.startswith("head "):
        exp.add(word.text.strip(), f"target {text}")
    else:
        exp.add(word.text.strip(), reading.format(value=text))
    if address.kind == "reserved":
        exp.warn(f"no device has the address T{address.number}")
    if physical and address.kind in (VIRTUAL, GROUP):
        # "this will FAIL (non-fatally) if you address a virtual group address" (M109 Wait for Temp (Head))
        exp.warn(f"{cmd.code} will FAIL (non-fatally) on a virtual or group address: use a physical address")
    if (
        address.kind == HEAD
        and address.position is not None
        and not (declares and job.state.loaded_heads is None)
        and job.state.head_loaded(address.position) is False
    ):
        exp.warn(f"no head is loaded at T{address.position} (per the job header or --loaded)")
    return address


def targeted(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    """A code whose only word that needs the job is T (M221, M723, M728, M701, M783)."""
    target(job, exp, cmd, spec)
    generic(job.dialect, exp, cmd, spec, skip="T")


# -- T command lines ----------------------------------------------------------------------------------


def tool(job: Job, cmd: Command, line: Line) -> Explanation:
    """A ``T<n>`` line: on Hyrel a change of focus (T Tool Change; T_v5 Chart of Addresses), elsewhere a tool."""
    code = cmd.code or ""
    digits = code[1:]
    if len(digits.lstrip("-")) > 6:  # no printer has a million tools: do not parse 5000 digits
        return Explanation(line.number, line.raw, code[:12] + "...", "a T number too large for any tool or head")
    n = int(digits)
    if not job.addressed:
        exp = Explanation(line.number, line.raw, code, f"select tool {n}")
        if n < 0:
            exp = Explanation(line.number, line.raw, code, "deselect the current tool")
        if job.facts.tool_select == "prepare":
            exp.note("prepares the tool; M6 changes to it")
            if n == job.facts.no_tool:
                exp.note(f"T{n} is no tool: the M6 that follows empties the spindle")
        else:
            exp.note(f"extruder/tool {n} becomes active (its offsets and temperature apply)")
        return exp
    address = job.interpreter.tool_command_address(cmd)
    if address is None:
        return Explanation(line.number, line.raw, code, "tool change")
    if address.kind == HEAD:
        # "T executes a tool change, invoking the parameters specified in the M6" (T Tool Change)
        exp = Explanation(
            line.number,
            line.raw,
            code,
            f"switch to head T{address.v5}: {yoke_label(address.v5)}, and invoke all its flow, prime, "  # type: ignore[arg-type]
            "unprime and offset parameters",
        )
        if job.firmware == 4 and address.v5 != address.number:
            exp.note(f"v4 tool number {address.number}")
        if job.state.head_loaded(address.v5) is False:  # type: ignore[arg-type]
            # T_v5: "we compare that with which tool positions on the yoke actually have heads"
            exp.warn(
                f"no head is loaded at T{address.v5}: Repetrel warns when T commands do not match the loaded heads"
            )
        return exp
    if address.kind == VIRTUAL:
        exp = Explanation(line.number, line.raw, code, f"switch to {address.label}: the squad's heads act together")
        members = job.state.squads.get(address.v5)  # type: ignore[arg-type]
        if members:
            exp.note("heads in the squad: " + ", ".join(f"T{h}" for h in sorted(members)))
        elif members is None:
            exp.warn(f"no M702 established squad T{address.v5} before this line")
        return exp
    if address.kind == "reserved":
        exp = Explanation(line.number, line.raw, code, f"{address.label}")
        exp.warn("no device answers to this tool number")
        return exp
    return Explanation(line.number, line.raw, code, f"switch focus to {address_text(job, address)}")


# -- clone squads (T_v5 M702-M704; v4: aliases, Hydra4/src/MCode.c M702-M704) --------------------------


def _squad(cmd: Command) -> int | None:
    """S as a clone squad (T30-T39), or None when it names a head (or nothing)."""
    value = number(cmd.raw("S"))
    squad = int(value) if value is not None and value == int(value) else None
    return squad if squad is not None and resolve_v5(squad).kind == VIRTUAL else None


def establish_squad(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    target(job, exp, cmd, spec)
    read(exp, cmd, spec, "S")
    notes(exp, spec)
    generic(job.dialect, exp, cmd, spec, skip="TS")


def join_squad(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    if job.firmware == 4:
        target(job, exp, cmd, spec)
        read(exp, cmd, spec, "S")
        generic(job.dialect, exp, cmd, spec, skip="TS")
        return
    squad = _squad(cmd)
    s = cmd.param("S")
    # T_v5 M703: "T# is the target head to add to the squad, S# is the clone squad number ... OR T# is the
    # head which will duplicate commands sent to S#, S# is the head which T# will duplicate"
    if squad is not None:
        target(job, exp, cmd, spec, "head to add to the squad: {value}")
        exp.add(s.text.strip(), f"clone squad T{squad} to join")  # type: ignore[union-attr]
        if squad not in job.state.squads:
            exp.warn(f"no M702 established squad T{squad} before this line")
    else:
        target(job, exp, cmd, spec, "head on which to imitate the actions of head S: {value}")
        if s is not None:
            exp.add(s.text.strip(), f"head T{s.value}, which T will imitate")
    generic(job.dialect, exp, cmd, spec, skip="TS")


def leave_squad(job: Job, exp: Explanation, cmd: Command, spec: Code | None) -> None:
    target(job, exp, cmd, spec)
    s = cmd.param("S")
    if s is not None:
        squad = _squad(cmd)
        # T_v5 M704: "S# is the clone squad number ... OR S# is the head (which T# will stop duplicating)"
        if job.firmware == 4:
            read(exp, cmd, spec, "S")
        elif squad is not None:
            exp.add(s.text.strip(), f"from clone squad T{squad}")
        else:
            exp.add(s.text.strip(), f"stop imitating head T{s.value}")
    generic(job.dialect, exp, cmd, spec, skip="TS")


def decoders(job: Job) -> dict[str, Decoder]:
    if not job.addressed:  # (the codes below address a device by its T)
        return {}
    return {
        "M702": establish_squad,
        "M703": join_squad,
        "M704": leave_squad,
        **dict.fromkeys(("M221", "M723", "M728", "M701", "M783"), targeted),
    }
