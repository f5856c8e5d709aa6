"""The events the reader (``Simulator.events``) yields besides the moves (``trace.Move``): what a job makes its
machine do, in the order the machine does it.  Each carries the line it comes from."""

from __future__ import annotations

from dataclasses import dataclass

from gclint.simulate.trace import Move


@dataclass(frozen=True, slots=True)
class Dwell:
    """G4: the machine waits ``seconds`` (None: the line gives no time the dialect reads)."""

    line: int
    seconds: float | None


@dataclass(frozen=True, slots=True)
class Pause:
    """A stop for the operator (M0, a filament change...)."""

    line: int
    code: str | None


@dataclass(frozen=True, slots=True)
class Heat:
    """A set-point: ``device`` (a head's, a bed's or a chamber's name in the dialect's terms), ``kind`` (``head``,
    ``bed``, ``chamber``), the value in °C and whether the machine waits for it."""

    line: int
    device: str
    kind: str
    value: float
    wait: bool


@dataclass(frozen=True, slots=True)
class Flow:
    """Hyrel's flow mode changed: ``"native"`` (the machine meters the flow; an E marks a printing move) or
    ``"evalues"`` (M229 E1 D1: the E amounts are used)."""

    line: int
    mode: str


@dataclass(frozen=True, slots=True)
class ToolChange:
    """The working tool is another one from here on (``tool``: in the dialect's own terms, ``"T1"``)."""

    line: int
    tool: str


@dataclass(frozen=True, slots=True)
class Ignored:
    """A command written on a line that the machine does not run (Marlin runs the first command of a line)."""

    line: int
    code: str | None
    why: str


@dataclass(frozen=True, slots=True)
class ProgramEnd:
    """The end of the file; ``ended``: a program end ran (what follows it does not run)."""

    line: int
    ended: bool


Event = Move | Dwell | Pause | Heat | Flow | ToolChange | Ignored | ProgramEnd

__all__ = ["Dwell", "Event", "Flow", "Heat", "Ignored", "Move", "Pause", "ProgramEnd", "ToolChange"]
