"""What the Hyrel printer will believe after the lines written so far (the target side of a translation).

The source side is ``gclint.machine.Interpreter`` run with the source dialect (research/dialects.md 2.0
X3); this is its counterpart for the output: which header lines were written, the modal G1 feed, the
focused head, what is switched on and must be switched off at the end.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class HyrelSide:
    feed: float | None = None  # F of the last G1/G2/G3 written (G0 F is one-shot on Hyrel)
    m229_written: bool = False  # M229 E1 D1: E amounts carry the flow
    e_mode_written: bool | None = None  # the last M82 (True) / M83 (False) written
    fan_range_written: bool = False  # M106 C255
    focus: int | None = None  # the address of the last T command written
    started_motion: bool = False  # the header due before the first move was written
    units_seen: bool = False
    positioning_seen: bool = False
    ended: bool = False  # the source's end of program was translated (the footer is written)
    spindles_on: dict[int, str] = field(default_factory=dict)  # address -> "M3" or "M4"
    emitters_on: set[int] = field(default_factory=set)  # lasers / UV emitters (M620 E1)
    air_on: bool = False
    motors_off: bool = False  # an M18/M84 was written: Hyrel must re-home before moving
    wrote_command: bool = False  # a command reached the output (else no footer)
    temps: dict[int, tuple[str, str]] = field(default_factory=dict)  # address -> (wait code, temperature) not waited
