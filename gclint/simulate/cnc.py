"""Machinekit FDM (LinuxCNC) and Carvera (Smoothieware community firmware), as the source of a translation.

Machinekit (the Machinekit-FDM README "Machinekit Flavor GCode" and remap.ini; the LinuxCNC G-code docs): the
extruder is the A axis and follows G90/G91; E is not a word of the language; G0 ignores F (the F still
sets the feed of later moves); ``M104 P<index> S<temp>`` (the README) or ``M104 P<temp> T<index>`` (the
final remap), M106/M109 alike; ``M221 P`` is a factor; ``T`` prepares a tool and ``M6`` changes to it;
the G28 remap (g28.ngc) rapids X, then Y, then Z to 0 and resets A; M2 and M30 end the program.

Carvera (the Carvera community docs' M-code and G-code tables): M3 S is rpm, an S word alone sets the
speed; M5 stops; ``M6 T<n>`` changes tools (T0 is the probe, T-1 none); M7/M9 air; M321/M322 enter and
leave laser mode, where M3 fires and S on a move is the power (0-1); G28 goes to the clearance position;
"M2 end program, stop spindle and air"; "M30 End of the program, no action on the Carvera"; G0's F is
one-shot.  No extrusion.
"""

from __future__ import annotations

import math

from gclint.simulate.devices import DeviceModel
from gclint.simulate.heat import LayerHeights, ToolHeat
from gclint.simulate.machine import number
from gclint.simulate.trace import AUX_PORTS, EndState, Look, Move
from gclint.syntax.nodes import Command


def _length(move: Move) -> float | None:
    """The length of a move's path (mm): an arc's turn and its linear axis, or the straight line."""
    a, b = move.start, move.end
    if move.arc is not None:
        plane, _, radius, _, _, turn = move.arc
        linear = {17: 2, 18: 1, 19: 0}.get(plane, 2)
        rise = (b[linear] - a[linear]) if a[linear] is not None and b[linear] is not None else 0.0
        return float(math.hypot(radius * turn, rise))
    if any(a[i] is None or b[i] is None for i in range(3)):
        return None
    return math.dist(a[:3], b[:3])


class CncSimulator(DeviceModel):
    """What LinuxCNC and Carvera share: workspaces, G53, spindle, tool change, coolant, end of program."""

    def __init__(self, dialect, mapping=None, *, cnc: bool = True) -> None:
        super().__init__(dialect, mapping, cnc=cnc)
        self.tool: int | None = None  # the tool in the spindle
        self.prepared: int | None = None
        self.rpm: float | None = None
        self.spindle: str | None = None  # "M3" / "M4"
        self.aux: dict[str, float] = {}
        self._g53_line = -1
        self._g53_next = False
        self.inverse_time = False
        self.inverse_line = 0

    def table(self):
        h = {
            "G0": self.g0,
            "G1": self.g1,
            "G2": self.arc,
            "G3": self.arc,
            "G17": self.set_plane,
            "G18": self.set_plane,
            "G19": self.set_plane,
            "G20": self.units,
            "G21": self.units,
            "G53": self.g53,
            "G90": self.positioning,
            "G91": self.positioning,
            "G92": self.set_position,
            "G92.1": self.clear_offsets,
            "M2": self.m2,
            "M3": self.spindle_on,
            "M4": self.spindle_on,
            "M5": self.spindle_off,
            "M6": self.tool_change,
            "G4": self.g4,
            "G93": self.feed_mode,
            "G94": self.feed_mode,
        }
        for n in range(54, 60):
            h[f"G{n}"] = self.workspace
        return h

    def implicit(self, cmd: Command, n: int) -> Move | None:
        if "S" in cmd.params:
            self.speed(number(cmd.params.get("S")))
        return super().implicit(cmd, n)

    def speed(self, rpm: float | None) -> None:
        if rpm is not None:
            self.rpm = rpm
            self.dirty()

    def line_words(self, commands: tuple, n: int) -> None:
        """The S words of a line where the dialect sets the spindle speed before the line's commands (LinuxCNC: "Set
        spindle speed (S)", G-code Order of Execution): ``G4 P1 S5000`` changes the speed (not a dwell word there)."""
        super().line_words(commands, n)
        if "S" not in self.facts.words_first:
            return
        for cmd in commands:
            if "S" in cmd.params and (cmd.code != "G4" or self.facts.dwell.unit("S") is None):
                self.speed(number(cmd.params["S"]))

    G53_NEXT_LINE = False  # Carvera: a G53 alone on its line puts the next G0/G1 in machine coordinates

    def g53(self, cmd: Command, n: int) -> Move | None:
        """G53: the move on this line is in machine coordinates (LinuxCNC: "Non-modal; requires G0/G1 active";
        Carvera: "the directly following G0/G1 will be executed in MCS"; Carvera community docs, gcodes.md G53).  Its
        words may be on G53 itself ("G53 Z-2", "G0 G53 Z-2": the motion mode applies)."""
        self._g53_line = n
        self._g53_next = self.G53_NEXT_LINE
        if any(a in cmd.params for a in "XYZAB") and self.motion_mode in ("G0", "G1"):
            return self.motion(self.motion_mode, cmd.params, n)
        return None

    def feed_mode(self, cmd: Command, n: int) -> None:
        """G93 inverse time: "1/min in G93 inverse-time" (LinuxCNC G-code docs, G93; Carvera community docs,
        gcodes/inverse-time-feed-g93-g94.md): F on a feed move is the inverse of the minutes it takes, so its feed is F
        times its length; G94 units per minute."""
        self.inverse_time = cmd.code == "G93"
        self.inverse_line = n

    def inverse(self, params: dict, move: Move | None, saved: float | None) -> Move | None:
        """A feed move in inverse time: its own F (not modal) over its length."""
        self.feed = saved
        if move is not None:
            f = number(params.get("F"))
            length = _length(move)
            move.feed = None if f is None or length is None else f * length
            move.feed_mode = self.inverse_line
        return move

    def arc(self, cmd: Command, n: int) -> Move | None:
        if not self.inverse_time:
            return super().arc(cmd, n)
        saved = self.feed
        return self.inverse(cmd.params, super().arc(cmd, n), saved)

    def motion(self, mode: str, params: dict, n: int) -> Move | None:
        if self.inverse_time and mode != "G0":
            saved = self.feed
            return self.inverse(params, self._motion(mode, params, n), saved)
        return self._motion(mode, params, n)

    def _motion(self, mode: str, params: dict, n: int) -> Move | None:
        if "S" in params:
            self.speed(number(params.get("S")))
        if self._g53_line != n and not (self._g53_next and mode in ("G0", "G1")):
            return super().motion(mode, params, n)
        self._g53_next = False
        saved, shift = self.wcs, list(self.shift)
        self.wcs, self.shift = "G53", [0.0] * 5
        self.dirty()
        try:
            move = super().motion(mode, params, n)
        finally:
            self.wcs, self.shift = saved, shift
            self.dirty()
        return move

    def clear_offsets(self, cmd: Command, n: int) -> None:
        self.clear_shift()

    def tool_command(self, cmd: Command, n: int) -> None:
        text = (cmd.code or "T")[1:]
        if text.lstrip("-").isdigit() and len(text) <= 6:
            self.prepared = int(text)  # T prepares, M6 changes

    def tool_change(self, cmd: Command, n: int) -> None:
        value = number(cmd.params.get("T"))
        tool = int(value) if value is not None else self.prepared
        if tool is None:
            if self.facts.tool_change_stops_spindle:
                self.spindle = None
                self.dirty()
            return
        # the dialect's "no tool" number empties the spindle (LinuxCNC: "T0 gets special handling: no tool")
        self.tool = None if tool == self.facts.no_tool else tool
        if self.facts.tool_change_stops_spindle:  # (LinuxCNC M6: "The spindle will be stopped"; the Carvera's ATC)
            self.spindle = None
        self.dirty()

    def tool_label(self, tool: int | None) -> str:
        return "no tool" if tool is None else f"tool {tool}"

    def tool_name(self) -> str:
        return self.named(self.tool)

    def spindle_percent(self) -> float | None:
        top = self.mapping.spindle_max_rpm
        if self.rpm is None or top is None:
            return None
        return round(max(0.0, min(100.0, self.rpm / top * 100)), 1)

    def spindle_on(self, cmd: Command, n: int) -> None:
        self.speed(number(cmd.params.get("S")))
        if self.rpm is not None and self.rpm == 0:
            self.spindle = None
        else:
            self.spindle = cmd.code
        self.dirty()

    def spindle_off(self, cmd: Command, n: int) -> None:
        self.spindle = None
        self.dirty()

    def spindle_direction(self) -> str | None:
        return self.spindle

    def m2(self, cmd: Command, n: int) -> None:
        self.end_program(cmd, n)

    def spindle_look(self) -> tuple | None:
        """(direction, percent); with no maximum known, (direction, None, rpm): compared relatively (compare.py)."""
        if not self.spindle:
            return None
        pct = self.spindle_percent()
        return (self.spindle, pct) if pct is not None or self.rpm is None else (self.spindle, None, self.rpm)

    def build_look(self) -> Look:
        return Look(
            head=self.working_head(), spindle=self.spindle_look(), aux=tuple(sorted(self.aux.items())), wcs=self.wcs
        )

    def working_head(self) -> int | str | None:
        return self.mapping.spindle_address()

    def spindle_head(self) -> int | str | None:
        """The head the source's spindle is on in Hyrel terms: the ``spindle`` setting, else the working head
        (a mapped tool is a spindle head; translate/spindle.py)."""
        if self.mapping.spindle is not None:
            return self.mapping.spindle
        head = self.working_head()
        return head if isinstance(head, int) else self.mapping.spindle_address()

    def end_state(self) -> EndState:
        spindles = {self.spindle_head(): self.spindle} if self.spindle else {}
        # the job ends at its end of program or with its file (the translation's footer ends it with M30)
        end = EndState(ended=True, spindles=spindles, aux=dict(self.aux))
        return end if self.pure else self.finish_end(end)


class MachinekitSimulator(CncSimulator):
    """Machinekit FDM.  Velocity extrusion (Machinekit-FDM remap.ini, M700-M702; docs/translation.md: VE mode if
    M700/M701/M702 or G22/G23 without A-moves; g22.ngc/g23.ngc in the corpus: with VE, G22 disables the extruder and G23
    enables it): from its start every feed move (G1/G2/G3 moving X, Y or Z) outside G22 ... G23 extrudes at a
    rate the machine computes from the line width (M701 P) and height (M702 P), Hyrel's native flow; once a
    move has an A word the extruder is an axis again.  Without VE, G22/G23 retract and recover."""

    def __init__(self, dialect, mapping=None, *, cnc: bool = True) -> None:
        super().__init__(dialect, mapping, cnc=cnc)
        self.heat = ToolHeat(self.mapping)
        self.heat.tool = None
        self.ve = False  # velocity extrusion
        self.ve_travel = False  # between G22 and G23 in VE
        self.a_moves = False  # a move had an A word: the extruder is the A axis
        self.bead: tuple[float | None, float | None] = (None, None)  # VE line width (M701), height (M702)
        self.layers = LayerHeights() if self.mapping.flow == "native" else None

    def m2(self, cmd: Command, n: int) -> None:
        # LinuxCNC's M2/M30 end the program with the spindle stopped and the coolant off
        self.spindle = None
        self.aux.clear()
        self.dirty()
        self.end_program(cmd, n)

    def table(self):
        h = super().table()
        h.update(
            {
                "G28": self.g28,
                **({"G30": self.predefined} if self.facts.g30 == "predefined" else {}),
                "M30": self.m2,
                "M104": self.m104,
                "M109": self.m109,
                "M140": self.bed,
                "M141": self.bed,
                "M190": self.bed,
                "M191": self.bed,
                "M106": self.m106,
                "M107": self.m107,
                "M221": self.m221,
                "M7": self.coolant_on,
                "M8": self.coolant_on,
                "M9": self.coolant_off,
                "G22": self.g22,
                "G23": self.g22,
                "M700": self.ve_line,
                "M701": self.ve_line,
                "M702": self.ve_line,
                # M0 "program pause" (LinuxCNC); M226 a pause of the FDM remap (Machinekit-FDM
                # remap.ini, M226; docs/translation.md: M0); M1 is an optional stop, off unless the operator enables
                # it: not counted
                "M0": self.pause,
                "M226": self.pause,
            }
        )
        return h

    def plain_moves(self) -> bool:
        return False  # E is not a word here; plain moves go through motion() with their words checked

    def motion(self, mode: str, params: dict, n: int) -> Move | None:
        if "E" in params:
            self.note_once("E", "E is not a word of Machinekit/LinuxCNC (the extruder is the A axis): ignored")
            params = {k: v for k, v in params.items() if k != "E"}
        if "A" in params:
            self.a_moves = True
            if self.ve:
                self.ve = False
                self.dirty()
            self.e_only = not any(a in params for a in self.axes)
        return super().motion(mode, params, n)

    def arc(self, cmd: Command, n: int) -> Move | None:
        if "A" in cmd.params:
            self.a_moves = True
            if self.ve:
                self.ve = False
                self.dirty()
        return super().arc(cmd, n)

    def velocity_extrusion(self) -> bool:
        """VE starts (M700-M702, or G22/G23 before any A move); whether it is on."""
        if not self.ve and not self.a_moves:
            self.ve = True
            self.dirty()
        return self.ve

    def g22(self, cmd: Command, n: int) -> None:
        if self.velocity_extrusion():
            self.ve_travel = cmd.code == "G22"
        elif self.mapping.retract == "explicit":
            (self.unprime if cmd.code == "G22" else self.prime)(self.working_head())

    def ve_line(self, cmd: Command, n: int) -> None:
        """M700 P cross-section (mm²), M701 P line width, M702 P line height (mm): VE's bead."""
        self.velocity_extrusion()
        p = number(cmd.params.get("P"))
        width, height = self.bead
        if cmd.code == "M701":
            width = p
        elif cmd.code == "M702":
            height = p
        else:
            width = p / height if p is not None and height else None
        self.bead = (width, height)
        self.dirty()

    def retraction(self, delta: float) -> None:
        if self.mapping.retract == "explicit":
            (self.unprime if delta < 0 else self.prime)(self.working_head())

    def sync(self, start, arc, delta, feed, rapid, native=False):
        moved = self.machine() != start or arc is not None
        if self.ve and not self.ve_travel and not rapid and moved and self.cnc:
            native = True  # a feed move in VE extrudes (Hyrel: native flow)
        move = super().sync(start, arc, delta, feed, rapid, native=native)
        layers = self.layers
        printing = layers is not None and move is not None and move.e is not None and not self.ve
        if printing and layers.printing(self.logical(2), self.line):  # type: ignore[union-attr]
            self.dirty()
            move.look = self.look()
        return move

    def predefined(self, cmd: Command, n: int) -> Move | None:
        """LinuxCNC's G28/G30: "a rapid move to the position specified by axes including any offsets, then ... a
        rapid move to the absolute position of the values in parameters 5161-5166 [G30: 5181-5186] for all axes
        specified"; no axis: every axis goes there (g-code.adoc, "G28, G28.1", "G30, G30.1").  The stored
        position is not in the file: those axes are somewhere this reading does not know."""
        params = cmd.params
        listed = [a for a in self.axes if a in params]
        via = self.motion("G0", {a: params[a] for a in listed}, n) if listed else None
        start = self.machine()
        self.forget("".join(listed) or self.axes)
        self.sync(start, None, None, None, True)
        return via

    def g28(self, cmd: Command, n: int) -> Move | None:
        if self.facts.home == "predefined":
            return self.predefined(cmd, n)
        params = cmd.params
        listed = [a for a in "XYZ" if a in params]
        bare = not any(a in params for a in "XYZA")
        for axis in listed or (["X", "Y", "Z"] if bare else []):
            if self.absolute:
                i = "XYZ".index(axis)
                self.pos[i] = self.shift[i]  # program 0
                self.anchor[i] = n
                self.set_frame(i, self.frame_label(i))
        if bare or "A" in params:
            self.e_pos = 0.0
        return None

    def tool_change(self, cmd: Command, n: int) -> None:
        super().tool_change(cmd, n)
        self.heat.tool = self.tool
        self.dirty()

    def _flavour(self, cmd: Command) -> tuple[float | None, int | None]:
        """(value, index): the README's ``P<index> S<value>`` or the remap's ``P<value> T<index>``."""
        params = cmd.params
        if "S" in params:
            index = number(params.get("P"))
            return number(params.get("S")), int(index) if index is not None else None
        index = number(params.get("T"))
        return number(params.get("P")), int(index) if index is not None else None

    def m104(self, cmd: Command, n: int) -> None:
        value, index = self._flavour(cmd)
        if value is not None:
            self.heat.set_temp(index, value, wait=False)
            self.dirty()

    def m109(self, cmd: Command, n: int) -> None:
        value, index = self._flavour(cmd)
        if value is not None:
            self.heat.set_temp(index, value, wait=True, both_ways=True)  # waits on "temp in range" (1.3)
            self.dirty()

    def bed(self, cmd: Command, n: int) -> None:
        value = number(cmd.params.get("S", cmd.params.get("P")))
        if value is None:
            return
        chamber = cmd.code in ("M141", "M191")
        self.heat.set_bed(self.mapping.chamber if chamber else self.mapping.bed, value, cmd.code in ("M190", "M191"))
        self.dirty()

    def m106(self, cmd: Command, n: int) -> None:
        value, index = self._flavour(cmd)
        if value is None:
            return
        self.heat.set_fan(index or 0, value / 255)
        self.dirty()

    def m107(self, cmd: Command, n: int) -> None:
        index = number(cmd.params.get("T", cmd.params.get("P")))
        self.heat.set_fan(int(index) if index is not None else 0, 0.0)
        self.dirty()

    def m221(self, cmd: Command, n: int) -> None:
        factor = number(cmd.params.get("P"))
        if factor is not None:
            self.heat.set_flow(None, factor)
            self.dirty()

    def coolant_on(self, cmd: Command, n: int) -> None:
        self.aux[AUX_PORTS[cmd.code]] = 100.0  # type: ignore[index]
        self.dirty()

    def coolant_off(self, cmd: Command, n: int) -> None:
        self.aux.clear()
        self.dirty()

    def working_head(self) -> int | str | None:
        return self.mapping.head(self.heat.tool if self.heat.tool is not None else 0)

    def layer_look(self) -> tuple | None:
        """Native flow: VE's bead (width, height), or the layer heights of a job translated to native flow."""
        if self.ve:
            width, height = self.bead
            return (width, (height,) if height else ())
        if self.layers is not None:
            return (None, self.layers.heights)
        return None

    def build_look(self) -> Look:
        heat = self.heat
        saved = heat.tool
        if heat.tool is None:
            heat.tool = 0
        temp, flow = heat.working(infer=not self.pure)
        heat.tool = saved
        return Look(
            layer=self.layer_look(),
            head=self.working_head(),
            temp=temp,
            fan=round(heat.fans.get(0, 0.0), 3),
            flow=round(flow, 4),
            beds=heat.bed_look(),
            spindle=self.spindle_look(),
            aux=heat.aux_fans() + tuple(sorted(self.aux.items())),
            wcs=self.wcs,
        )

    def end_state(self) -> EndState:
        state = super().end_state()
        heat = self.heat
        saved = heat.tool
        if heat.tool is None:
            heat.tool = 0
        state.heaters = heat.end_heaters()
        state.fans = heat.end_fans()
        if self.pure:
            heat.tool = saved
        return state


class CarveraSimulator(CncSimulator):
    G53_NEXT_LINE = True

    def __init__(self, dialect, mapping=None, *, cnc: bool = True) -> None:
        super().__init__(dialect, mapping, cnc=cnc)
        self.laser_mode = False
        self.stops = False  # optional stop mode (M334): M1 pauses
        self.firing = False  # M3 in laser mode
        self.power = 0.0  # percent

    def table(self):
        h = super().table()
        h.update(
            {
                "G28": self.g28,
                "M7": self.air_on,
                "M9": self.air_off,
                "M321": self.m321,
                "M322": self.m322,
                "M801": self.vacuum,
                "M802": self.vacuum_off,
                "M821": self.light,
                "M822": self.light_off,
                # M600 "Pause (use this to add pauses)" (Carvera M-code table); M25 pauses the file being
                # played (Smoothieware source, M25); M1 is an optional stop, a pause in optional
                # stop mode
                "M600": self.pause,
                "M25": self.pause,
                "M1": self.optional_stop,
                "M333": self.stop_mode,
                "M334": self.stop_mode,
            }
        )
        return h

    def optional_stop(self, cmd: Command, n: int) -> None:
        if self.stops:
            self.pause(cmd, n)

    def stop_mode(self, cmd: Command, n: int) -> None:
        # "M333 Turn off optional stop mode", "M334 Turn on optional stop mode. See M01" (Carvera M-code table;
        # its M1 row names them the other way round: the rows of the codes themselves are followed here)
        self.stops = cmd.code == "M334"

    def plain_moves(self) -> bool:
        return not self.laser_mode and super().plain_moves()

    def g28(self, cmd: Command, n: int) -> None:
        self.forget("XYZ")  # "G28 means goto clearance position on the Carvera": a place this file does not say

    def speed(self, rpm: float | None) -> None:
        if rpm is None:
            return
        if self.laser_mode:
            self.power = min(100.0, rpm) if rpm > 1 else rpm * 100
        else:
            self.rpm = rpm
        self.dirty()

    def spindle_on(self, cmd: Command, n: int) -> None:
        if self.laser_mode:
            self.speed(number(cmd.params.get("S")))
            self.firing = True
            self.dirty()
            return
        super().spindle_on(cmd, n)

    def spindle_off(self, cmd: Command, n: int) -> None:
        if self.laser_mode:
            self.firing = False
            self.dirty()
            return
        super().spindle_off(cmd, n)

    def tool_change(self, cmd: Command, n: int) -> None:
        super().tool_change(cmd, n)  # (the spindle stops for it: Semantics.tool_change_stops_spindle)

    def working_head(self) -> int | str | None:
        tool = self.tool
        if tool is not None and tool in self.mapping.tool_map:
            return self.mapping.head(tool)
        return self.mapping.spindle_address()

    def sync(self, start, arc, delta, feed, rapid, native=False):
        fires = self.laser_mode and self.firing and not rapid and self.power > 0
        return super().sync(start, arc, delta, feed, rapid, native=fires)

    def m2(self, cmd: Command, n: int) -> None:
        self.spindle = None  # "end program, stop spindle and air"
        self.aux.pop(AUX_PORTS.get(self.mapping.air, self.mapping.air), None)
        self.dirty()
        self.end_program(cmd, n)

    def m321(self, cmd: Command, n: int) -> None:
        self.laser_mode = True
        self.dirty()

    def m322(self, cmd: Command, n: int) -> None:
        self.laser_mode = False
        self.firing = False
        self.dirty()

    def air_on(self, cmd: Command, n: int) -> None:
        self.aux[AUX_PORTS.get(self.mapping.air, self.mapping.air)] = 100.0
        self.dirty()

    def air_off(self, cmd: Command, n: int) -> None:
        self.aux.pop(AUX_PORTS.get(self.mapping.air, self.mapping.air), None)
        self.dirty()

    def vacuum(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        self.aux["vacuum"] = 100.0 if s is None else s
        self.dirty()

    def vacuum_off(self, cmd: Command, n: int) -> None:
        self.aux.pop("vacuum", None)
        self.dirty()

    def light(self, cmd: Command, n: int) -> None:
        self.aux["light"] = 100.0
        self.dirty()

    def light_off(self, cmd: Command, n: int) -> None:
        self.aux.pop("light", None)
        self.dirty()

    def build_look(self) -> Look:
        look = super().build_look()
        if self.laser_mode:
            return Look(head=look.head, spindle=look.spindle, aux=look.aux, wcs=look.wcs, laser=round(self.power, 1))
        return look

    def end_state(self) -> EndState:
        state = super().end_state()
        if self.laser_mode:
            state.emitters = frozenset({self.mapping.laser_address()})
        return state
