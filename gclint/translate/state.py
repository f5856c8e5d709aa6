"""What the Hyrel printer will believe after the lines written so far (the target side of a translation).

The source side is ``gclint.machine.Interpreter`` run with the source dialect (docs/translation.md,
rule X3); this is its counterpart for the output: which header lines were written, the modal G1 feed, the
focused head, what is switched on and must be switched off at the end.
"""

from __future__ import annotations

from dataclasses import dataclass, field


class HeadState:
    """What one Hyrel head has been given (None: nothing written, the head's stored value applies)."""

    __slots__ = ("target", "waited", "fan", "flow")

    def __init__(self) -> None:
        self.target: float | None = None  # set-point written (M104/M109)
        self.waited: float | None = None  # the set-point an M109 waited for
        self.fan = 0  # M106 S (0-255, range C255)
        self.flow: float | None = None  # M221 S multiplier


@dataclass(slots=True)
class HyrelSide:
    feed: float | None = None  # F of the last G1/G2/G3 written (G0 F is one-shot on Hyrel)
    m229_written: bool = False  # M229 E1 D1: E amounts carry the flow
    e_mode_written: bool | None = None  # the last M82 (True) / M83 (False) written
    fan_range_written: bool = False  # M106 C255
    focus: int | None = None  # the address of the last T command written
    started_motion: bool = False  # the header due before the first move was written
    units_seen: bool = False
    positioning_seen: bool = False
    workspace_seen: bool = False  # a G54-G59 was written (or the source selected one)
    ended: bool = False  # the source's end of program was translated (the footer is written)
    spindles_on: dict[int, str] = field(default_factory=dict)  # address -> "M3" or "M4"
    emitters_on: set[int] = field(default_factory=set)  # lasers / UV emitters (M620 E1)
    air_on: bool = False
    motors_off: bool = False  # an M18/M84 was written: Hyrel must re-home before moving
    wrote_command: bool = False  # a command reached the output (else no footer)
    temps: dict[int, tuple[str, str]] = field(default_factory=dict)  # address -> (wait code, temperature) not waited
    heads: dict[int, HeadState] = field(default_factory=dict)  # address -> what it was given
    part_fan_heads: set[int] = field(default_factory=set)  # heads that got the source's part fan
    nozzle_heads: set[int] = field(default_factory=set)  # heads given a head set-point (a single nozzle's heads)

    def head(self, address: int) -> HeadState:
        state = self.heads.get(address)
        if state is None:
            state = self.heads[address] = HeadState()
        return state
