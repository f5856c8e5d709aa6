"""The machine's modal state while a job runs, as the target firmware understands it.

Rules read this state; they never scan back through lines.  ``Interpreter`` (interpreter.py) updates it
command by command, with the semantics of the file's dialect.  Heads are v5 position numbers (0-19)
whatever the dialect; other devices keep their v5 address (20 spindle, 21 laser, 24/25 beds...).
"""

from __future__ import annotations

from dataclasses import dataclass, field

NATIVE = "native"  # Hyrel native flow: E marks printing moves only
EVALUES = "evalues"  # Hyrel M229 E1: E amounts drive the flow


@dataclass(slots=True)
class Position:
    """The last commanded position.  Axes are None until known.

    Absolute moves store the value's source text and convert it only when read (most jobs never ask):
    ``values`` maps an axis to its text, a number, or None (unknown).  Other letters a move carries may
    sit in ``values`` too; only X Y Z A B are ever read.
    """

    values: dict = field(default_factory=dict)

    def set_raw(self, axis: str, text: str | None) -> None:
        self.values[axis] = text

    def set(self, axis: str, value: float | None) -> None:
        self.values[axis] = value

    def get(self, axis: str) -> float | None:
        value = self.values.get(axis)
        if type(value) is str:
            try:
                value = float(value)
            except ValueError:
                value = None
            self.values[axis] = value
        return value

    def add(self, axis: str, delta: float) -> None:
        current = self.get(axis)
        self.values[axis] = None if current is None else current + delta

    def forget(self, axis: str) -> None:
        self.values.pop(axis, None)

    def snapshot(self) -> dict[str, float | None]:
        return {axis: self.get(axis) for axis in "XYZAB" if axis in self.values}


@dataclass(slots=True)
class MachineState:
    """Modal state.  Line numbers (``*_line``) say where a setting was made, for messages."""

    # positioning and units
    units: str = "mm"  # G21 / G20
    absolute: bool = True  # G90 / G91 (X Y Z A B)
    arc_absolute: bool = False  # G90.1 / G91.1: arc centres I J K absolute, or offsets from the start (LinuxCNC)
    e_absolute: bool = True  # M82 / M83 (and G90/G91 on Marlin)
    plane: int = 17  # G16 (Hyrel "any"), G17, G18, G19
    motion_mode: str | None = None  # modal G0/G1/G2/G3 for lines with axis words only (LinuxCNC)
    position: Position = field(default_factory=Position)
    e_position: float | None = 0.0
    feed: float | None = None  # modal F of working moves
    working_feed_set: bool = False  # an F was given on G1/G2/G3 (Hyrel: G0 F is one-shot)

    # flow (Hyrel M229, M221, M756)
    flow_mode: str = NATIVE
    m229_line: int | None = None
    layer_height: float | None = None

    # heads and tools
    tool: int | None = None  # focused head/device (v5 address)
    tool_line: int | None = None
    prepared_tool: int | None = None  # the tool a CNC T selected for the next M6 (LinuxCNC, Carvera)
    declared_heads: dict[int, int] = field(default_factory=dict)  # position -> line of its M6 T# O...
    # position -> axis -> offset its M6 T# O... lines declare (None: not a plain number)
    declared_offsets: dict[int, dict[str, float | None]] = field(default_factory=dict)
    # The first line since the last Hyrel G28 (which "applies a head offset of 0 mm (as in an M6 O0)")
    # or M30 that applied a head's offsets again: a T command ("invoke all flow, prime, unprime, and
    # offset parameters") or an M6 T# ... I1.  None when there is none (also before the first G28).
    head_reselected_line: int | None = None
    loaded_heads: frozenset[int] | None = None  # from --loaded or configuration; None = unknown
    squads: dict[int, set[int]] = field(default_factory=dict)  # squad (30-39) -> heads
    squads_dissolved_line: int | None = None  # last M30 that dissolved squads

    # fans (Hyrel M106 C range persists until M30)
    fan_range: float = 100.0
    fan_range_line: int | None = None

    # tool-height offsets (Hyrel M660 H.. Z.. then G1 H..)
    tool_height_offsets: dict[int, float | None] = field(default_factory=dict)
    applied_height_register: int | None = None
    applied_height_line: int | None = None  # where the applied register was first applied (repeats keep it)

    # homing and motors
    homed_axes: set[str] = field(default_factory=set)
    # axes the job has homed anywhere (a G28 that lists Z shows the machine's Z has a home: "Z0 ensures that
    # the Z axis is homed"); X and Y have homes on every Hyrel ("G28 sends the X and/or Y axes to the
    # sensor-defined physical home position")
    axes_with_homes: set[str] = field(default_factory=lambda: {"X", "Y"})
    z_homed_line: int | None = None
    motors_off_line: int | None = None  # last M18/M84 while some axis is not homed again since
    axes_to_rehome: set[str] = field(default_factory=set)  # axes with homes M18/M84 left unhomed (G28 takes them off)
    fixture_offsets_active: bool = False
    g92_offsets_active: bool = False
    # what G92 shifted each axis by (program position = machine position - shift; None: not known), so that
    # clearing the offsets (LinuxCNC's G92.1/G92.2, Marlin's G92.1, Hyrel's G93) gives the position back
    g92_shift: dict[str, float | None] = field(default_factory=dict)

    # temperatures
    targets: dict[int, float] = field(default_factory=dict)  # device -> last set temperature
    pending_w0: dict[int, int] = field(default_factory=dict)  # device -> line of M109/M190/M191 W0 awaiting M116

    # lasers, UV pens, spindles
    emitters_enabled: dict[int, int] = field(default_factory=dict)  # device -> line of M620 T# E1
    laser_enabled_any: bool = False  # an M620 E1 has been seen (M621 applies to it)
    spindles: dict[int, tuple[str, int]] = field(default_factory=dict)  # device -> ("cw"|"ccw", line)

    # job progress
    moved: bool = False  # any motion command so far
    printed: bool = False  # any printing (working, extruding) move so far
    first_print_line: int | None = None
    first_move_line: int | None = None  # first G0/G1/G2/G3 (or spiral) move; homing does not count
    first_print_since_home_line: int | None = None  # first printing move after the last Hyrel G28
    # First working move after the last Hyrel G28 that works without E: a G1 or arc moving an axis while a
    # spindle turns or before the job has printed (milling, pick and place: G1 "is a working move, during
    # which you may be printing, milling, lasering, or doing other active work"), or a G81 peck drilling.
    first_work_since_home_line: int | None = None
    first_print_since_m30_line: int | None = None  # first printing move after the last M30
    first_print_since_tool_line: int | None = None  # first printing move since the last T command (or M30)
    after_m30: bool = False
    m30_line: int | None = None
    line_number: int = 0  # the line being processed

    def e_values(self) -> bool:
        """True when Hyrel uses the E amounts (M229 E1 active)."""
        return self.flow_mode == EVALUES

    def head_offsets_zero(self, position: int) -> bool:
        """True when the job's M6 T# O... lines give head ``position`` only zero offsets (so a head
        offset of 0 mm changes nothing for it); False when they give another value or none at all."""
        offsets = self.declared_offsets.get(position)
        return offsets is not None and bool(offsets) and all(value == 0 for value in offsets.values())

    def head_loaded(self, position: int) -> bool | None:
        """Whether a head sits at ``position``; None when no one knows."""
        if self.loaded_heads is not None:
            return position in self.loaded_heads
        if self.declared_heads:
            return position in self.declared_heads
        return None
