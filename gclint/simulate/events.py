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
class Layer:
    """A slicer's mark that a layer begins (``;LAYER_CHANGE``, ``;LAYER:3``, ``; CHANGE_LAYER``...: ``LAYER_MARKS``):
    ``marks`` names the kind of mark (a job counts its layers with one kind), ``z`` is the height the mark itself
    states (None when it states none)."""

    line: int
    marks: str
    z: float | None


@dataclass(frozen=True, slots=True)
class Limits:
    """The job sets its machine's motion limits (Marlin M201, M203, M204, M205; RepRapFirmware M566; Klipper
    SET_VELOCITY_LIMIT), already in mm and seconds whatever the firmware's units: ``values`` maps a name of
    ``LIMIT_NAMES`` to its new value."""

    line: int
    values: dict[str, float]


@dataclass(frozen=True, slots=True)
class Ignored:
    """A command written on a line that the machine does not run (Marlin runs the first command of a line)."""

    line: int
    code: str | None
    why: str


@dataclass(frozen=True, slots=True)
class Stop:
    """A line the machine refuses (an interpreter error): the program stops there, and nothing after it runs."""

    line: int
    code: str | None
    why: str


@dataclass(frozen=True, slots=True)
class ProgramEnd:
    """The end of the file; ``ended``: a program end ran (what follows it does not run)."""

    line: int
    ended: bool


Event = Move | Dwell | Pause | Heat | Flow | ToolChange | Layer | Limits | Ignored | Stop | ProgramEnd

# The motion limits a ``Limits`` event may set (units: mm, s): the largest acceleration of each axis (M201), the
# largest speed of each axis (M203) and of the head (Klipper's VELOCITY), the acceleration of printing, travel and retraction moves (M204 P, T, R;
# Klipper's ACCEL for all three), the jerk of each axis (the speed change a junction may make without slowing
# down: M205 X Y Z E, M566), the junction deviation (M205 J), Klipper's square corner velocity, and the lowest
# feeds of printing and travel moves (M205 S, T).
LIMIT_NAMES = frozenset(
    {
        *(f"max_accel_{a}" for a in "xyze"),
        *(f"max_feed_{a}" for a in "xyze"),
        *(f"jerk_{a}" for a in "xyze"),
        "max_feed",
        "accel_print",
        "accel_travel",
        "accel_retract",
        "junction_deviation",
        "square_corner_velocity",
        "min_feed_print",
        "min_feed_travel",
    }
)

# The layer marks slicers write, each on a comment line of its own, by kind: what the slicers' output (the test
# corpus's marlin folder) shows each writing.  PrusaSlicer, SuperSlicer and OrcaSlicer ";LAYER_CHANGE" (then ";Z:0.2");
# BambuStudio "; CHANGE_LAYER" (then "; Z_HEIGHT: 0.2"); Cura, ideaMaker, Cura legacy and Slic3r profiles
# ";LAYER:0" (Cura's raft layers are negative); Simplify3D "; layer 1, Z = 0.200"; KISSlicer
# "; BEGIN_LAYER_OBJECT z=1.00" and "; BEGIN_LAYER_RAFT z=0.50" (the group gives the height where the mark has
# one).
LAYER_MARKS: tuple[tuple[str, str], ...] = (
    ("prusaslicer", r";LAYER_CHANGE\s*"),
    ("bambu", r";\s?CHANGE_LAYER\s*"),
    ("cura", r";LAYER:-?\d+\s*"),
    ("simplify3d", r"; layer \d+, Z ?= ?(-?[\d.]+)\s*"),
    ("kisslicer", r"; BEGIN_LAYER_(?:OBJECT|RAFT) z=(-?[\d.]+).*"),
)

__all__ = [
    "LAYER_MARKS",
    "LIMIT_NAMES",
    "Dwell",
    "Event",
    "Flow",
    "Heat",
    "Ignored",
    "Layer",
    "Limits",
    "Move",
    "Pause",
    "ProgramEnd",
    "ToolChange",
]
