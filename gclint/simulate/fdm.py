"""Marlin and RepRapFirmware, as the source of a translation (the Marlin G-code reference,
https://marlinfw.org/meta/gcode/; the Duet G-code dictionary, https://docs.duet3d.com/User_manual/Reference/Gcodes;
the RepRap wiki G-code page of 2015, https://reprap.org/wiki/G-code).

What differs from Hyrel and matters for the diff: G0 is G1 (it extrudes, and shares G1's F); Marlin's
G90/G91 also set the E mode; M106 S is 0-255 (RepRapFirmware: 0-1 too); M221 is a percentage; G28 with
no axis homes all axes; M220 scales every feed; M3 S is a PWM value 0-255 on Marlin (O too), rpm on
RepRapFirmware; RepRapFirmware's M0, M1 and M2 end the job, M116 waits for every set-point, G10 P S and
M568 set a tool's temperature, M109 T selects the tool.
"""

from __future__ import annotations

from gclint.machine.job_settings import read_settings
from gclint.simulate.devices import DeviceModel
from gclint.simulate.events import Limits
from gclint.simulate.heat import LayerHeights, ToolHeat
from gclint.simulate.machine import number
from gclint.simulate.trace import AUX_PORTS, EndState, Look, Move
from gclint.syntax.nodes import Command


def _index(text: str | None) -> int | None:
    value = number(text)
    if value is None or value < 0 or value != int(value):
        return None
    return int(value)


class MarlinSimulator(DeviceModel):
    RRF = False

    def __init__(self, dialect, mapping=None, *, cnc: bool = False) -> None:
        super().__init__(dialect, mapping, cnc=cnc)
        self.heat = ToolHeat(self.mapping)
        # native flow asked for: the layer heights Hyrel is to compute the flow of the printing moves with
        self.layers = LayerHeights() if self.mapping.flow == "native" else None
        self.feed_factor = 1.0  # M220
        self.spindle: tuple | None = None
        # M3/M4 until M5: an S on a move is the laser power (Marlin G-code reference, G0-G1)
        self.cutter: str | None = None
        self.coolant: dict[str, bool] = {}
        self._g53_line = -1
        self._g53_alone = False

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
            "G28": self.home,
            "G53": self.g53,
            "G90": self.positioning,
            "G91": self.positioning,
            "G92": self.set_position,
            "G92.1": self.clear_offsets,
            "M82": self.e_mode,
            "M83": self.e_mode,
            "M104": self.m104,
            "M109": self.m109,
            "M140": self.bed,
            "M190": self.bed,
            "M141": self.bed,
            "M191": self.bed,
            "M106": self.m106,
            "M107": self.m107,
            "M220": self.m220,
            "M221": self.m221,
            "M3": self.spindle_on,
            "M4": self.spindle_on,
            "M5": self.spindle_off,
            "M7": self.coolant_on,
            "M8": self.coolant_on,
            "M9": self.coolant_off,
            "G4": self.g4,
            # firmware retraction: "G10 - Retract", "G11 - Recover" (Marlin; RepRapFirmware's G10 without P or L)
            "G10": self.firmware_retract,
            "G11": self.firmware_retract,
            # waits for the operator or an event: M0/M1 "wait for user", M25 "pause file print", M226 "wait
            # for pin state" (Marlin G-code reference), M600 filament change (Marlin G-code reference, M600)
            "M0": self.pause,
            "M1": self.pause,
            "M25": self.pause,
            "M226": self.pause,
            "M600": self.pause,
            # motion limits (only ``events`` reads them: the summary's print time)
            "M201": self.limits,
            "M203": self.limits,
            "M204": self.limits,
            "M205": self.limits,
            "SET_VELOCITY_LIMIT": self.limits,
        }
        for n in range(54, 60):
            h[f"G{n}"] = self.workspace
        return h

    def plain_moves(self) -> bool:
        return self.feed_factor == 1.0 and super().plain_moves()

    def fast_plain(self) -> bool:
        # (``motion`` below does for a plain line what the shared one does while ``plain_now``: no G53 before it,
        # no M220 factor; a plain line has no S for a cutter)
        return self.g0_feed == "modal" and self.g0_extrudes and self.extruder == "E"

    def plain_now(self) -> bool:
        return self.feed_factor == 1.0 and not self._g53_alone

    def tool_name(self) -> str:
        return self.named(self.heat.tool)

    def read_job(self, source) -> None:
        # "single_extruder_multi_material = 1": one nozzle and heater for every tool, from the start (the job's
        # slicer settings; PrusaSlicer and Orca write them at the end of the file, Bambu at its start)
        if read_settings(source.head_text(), source.tail_text()).single_nozzle:
            self.heat.shared = self.heat.one_nozzle = True

    # -- motion ---------------------------------------------------------------------------------------

    def motion(self, mode: str, params: dict, n: int) -> Move | None:
        self.e_only = "E" in params and not ("X" in params or "Y" in params or "Z" in params)
        if self._g53_line == n:
            self._g53_alone = False
            return self.machine_move(mode, params, n)
        if self._g53_alone:  # the G53 before was alone on its line: the native workspace is active
            self._g53_alone = False
            self.wcs = None
            self.dirty()
        if self.cutter is not None and "S" in params and not self.RRF:
            # Marlin: "S = laser power" on G0/G1/G2/G3 (Marlin G-code reference, G0-G1), in the M3/M4 unit
            self.set_power(self.cutter, self.spindle_percent({"S": params["S"]}))
        move = super().motion(mode, params, n)
        if move is not None and self.feed_factor != 1.0 and move.feed is not None:
            move.feed *= self.feed_factor
        return move

    def sync(self, start, arc, delta, feed, rapid, native=False):
        move = super().sync(start, arc, delta, feed, rapid, native=native)
        layers = self.layers
        if (
            layers is not None
            and move is not None
            and move.e is not None
            and layers.printing(self.logical(2), self.line)
        ):
            self.dirty()
            move.look = self.look()
        return move

    def retraction(self, delta: float) -> None:
        if self.mapping.retract == "explicit":
            (self.unprime if delta < 0 else self.prime)(self.heat.head())

    def firmware_retract(self, cmd: Command, n: int) -> None:
        if self.mapping.retract == "explicit":
            (self.unprime if cmd.code == "G10" else self.prime)(self.heat.head())

    def g53(self, cmd: Command, n: int) -> None:
        # G53: "Machine coordinates for the move it prefixes; alone on a line activates native workspace"
        # (Marlin G-code reference, G53); "Non-modal, rest of line only" (Duet G-code dictionary, G53).  Whether a
        # move follows on the line is not known here: a move on this line uses machine coordinates, and the
        # native workspace is active from here in Marlin.
        self._g53_line = n
        self._g53_alone = not self.RRF  # until a move on this line shows it was a prefix

    def machine_move(self, mode: str, params: dict, n: int) -> Move | None:
        saved, self.wcs = self.wcs, "G53"
        shift = list(self.shift)
        self.shift = [0.0] * 5
        self.dirty()
        try:
            move = super().motion(mode, params, n)
        finally:
            self.shift = shift
            self.wcs = saved
            self.dirty()
        return move

    def clear_offsets(self, cmd: Command, n: int) -> None:
        self.clear_shift()

    def workspace(self, cmd: Command, n: int) -> None:
        self._g53_alone = False
        super().workspace(cmd, n)

    def home(self, cmd: Command, n: int) -> None:
        listed = "".join(a for a in "XYZ" if a in cmd.params)
        self.home_axes(listed or "XYZ")

    # The motion limits, in mm and seconds (``events.LIMIT_NAMES``), from each code's words as the firmware reads them
    # (Marlin G-code reference: M201 "max acceleration, units/s²", M203 "max feedrate, units/s", M204 "P printing,
    # R retract, T travel; S legacy: printing and travel", M205 "X Y Z E jerk, units/s; J junction deviation, mm;
    # S minimum feedrate, T minimum travel feedrate"; Klipper's SET_VELOCITY_LIMIT VELOCITY ACCEL
    # SQUARE_CORNER_VELOCITY, mm/s and mm/s², Klipper G-Codes reference).  A code's words -> names.
    LIMIT_WORDS: dict[str, dict[str, tuple[str, ...]]] = {
        "M201": {"X": ("max_accel_x",), "Y": ("max_accel_y",), "Z": ("max_accel_z",), "E": ("max_accel_e",)},
        "M203": {"X": ("max_feed_x",), "Y": ("max_feed_y",), "Z": ("max_feed_z",), "E": ("max_feed_e",)},
        "M204": {
            "S": ("accel_print", "accel_travel"),
            "P": ("accel_print",),
            "R": ("accel_retract",),
            "T": ("accel_travel",),
        },
        "M205": {
            "X": ("jerk_x",),
            "Y": ("jerk_y",),
            "Z": ("jerk_z",),
            "E": ("jerk_e",),
            "J": ("junction_deviation",),
            "S": ("min_feed_print",),
            "T": ("min_feed_travel",),
        },
        "SET_VELOCITY_LIMIT": {
            "VELOCITY": ("max_feed",),
            "ACCEL": ("accel_print", "accel_travel"),
            "SQUARE_CORNER_VELOCITY": ("square_corner_velocity",),
        },
    }
    PER_MINUTE: frozenset[str] = frozenset()  # the codes whose speeds the firmware reads in units/min

    def limits(self, cmd: Command, n: int) -> None:
        """A code that sets motion limits: a ``Limits`` event (``events`` only; nothing here depends on them)."""
        if not self.listening:
            return
        words = self.LIMIT_WORDS.get(cmd.code or "")
        if not words:
            return
        per_minute = cmd.code in self.PER_MINUTE
        values: dict[str, float] = {}
        for letter, names in words.items():
            value = number(cmd.params.get(letter))
            if value is None or value < 0:
                continue
            if names[0] != "junction_deviation" and per_minute:
                value /= 60
            if not names[0].startswith("square"):  # (lengths in the job's units; Klipper speaks mm)
                value *= self.scale
            for name in names:
                values[name] = value
        if values:
            self.emit(Limits(n, values))

    def m220(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        if s is not None:
            self.feed_factor = s / 100

    # -- tools and heat -------------------------------------------------------------------------------

    def tool_command(self, cmd: Command, n: int) -> None:
        text = (cmd.code or "T")[1:]
        if text == "-1":
            self.heat.tool = None
        elif text.isdigit() and len(text) <= 2:
            self.heat.tool = int(text)
        else:
            return  # vendor pseudo-tools (T1000...) and queries: no tool change
        self.dirty()

    def m104(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        if s is None:
            return
        self.heat.set_temp(_index(cmd.params.get("T")), s, wait=False)
        self.dirty()

    def m109(self, cmd: Command, n: int) -> None:
        params = cmd.params
        value = number(params.get("S")) if "S" in params else number(params.get("R"))
        tool = _index(params.get("T"))
        if self.RRF and tool is not None:
            self.heat.tool = tool  # RepRapFirmware: M109 T also selects the tool
        self.heat.set_temp(tool, value, wait=True, both_ways="S" not in params and "R" in params)
        self.dirty()

    def _slot(self, cmd: Command) -> int:
        chamber = cmd.code in ("M141", "M191")
        default = self.mapping.chamber if chamber else self.mapping.bed
        slot = _index(cmd.params.get("P")) if self.RRF else None
        if slot == 1 and default == 24:
            return 25
        return default

    def bed(self, cmd: Command, n: int) -> None:
        params = cmd.params
        wait = cmd.code in ("M190", "M191")
        value = number(params.get("S")) if "S" in params else (number(params.get("R")) if wait else None)
        if value is None and not wait:
            return
        self.heat.set_bed(self._slot(cmd), value, wait)
        self.dirty()

    def fan_value(self, cmd: Command) -> float | None:
        if "S" not in cmd.params:
            return 1.0  # Marlin: M106 without S is full speed
        s = number(cmd.params.get("S"))
        return None if s is None else s / 255

    def fans_of(self, cmd: Command) -> tuple[int, ...]:
        """The fans an M106/M107 drives: P, else fan 0 (the part fan)."""
        return (_index(cmd.params.get("P")) or 0,)

    def m106(self, cmd: Command, n: int) -> None:
        value = self.fan_value(cmd)
        if value is None:
            return
        for fan in self.fans_of(cmd):
            self.heat.set_fan(fan, value)
        self.dirty()

    def m107(self, cmd: Command, n: int) -> None:
        for fan in self.fans_of(cmd):
            self.heat.set_fan(fan, 0.0)
        self.dirty()

    def m221(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        if s is None:
            return
        self.heat.set_flow(_index(cmd.params.get("D" if self.RRF else "T")), s / 100)
        self.dirty()

    # -- spindle and coolant --------------------------------------------------------------------------

    def spindle_percent(self, params: dict) -> float | None:
        s = number(params.get("S"))
        if s is None and "O" in params:  # Marlin: O is the power as PWM 0-255
            o = number(params.get("O"))
            return None if o is None else max(0.0, min(100.0, o / 255 * 100))
        if s is None:
            return None
        return max(0.0, min(100.0, s / 255 * 100))  # Marlin's default cutter unit: PWM 0-255

    def spindle_on(self, cmd: Command, n: int) -> None:
        self.cutter = cmd.code
        self.set_power(cmd.code, self.spindle_percent(cmd.params), self.spindle_rpm(cmd.params))

    def spindle_rpm(self, params: dict) -> float | None:
        """The speed in rpm where the percent is not known (RepRapFirmware with no spindle-max-rpm)."""
        return None

    def set_power(self, code: str | None, pct: float | None, rpm: float | None = None) -> None:
        if (pct is not None and pct == 0) or (pct is None and rpm is not None and rpm <= 0):
            self.spindle = None
        elif pct is None and rpm is not None:
            self.spindle = (code, None, rpm)  # rpm with no known maximum: compared relatively (compare.py)
        else:
            self.spindle = (code, None if pct is None else round(pct, 1))
        self.dirty()

    def spindle_off(self, cmd: Command, n: int) -> None:
        self.spindle = None
        self.cutter = None
        self.dirty()

    def cutting(self) -> bool:
        return self.spindle is not None

    def spindle_direction(self) -> str | None:
        return self.spindle[0] if self.spindle else None

    def coolant_on(self, cmd: Command, n: int) -> None:
        self.coolant[cmd.code] = True  # type: ignore[index]
        self.dirty()

    def coolant_off(self, cmd: Command, n: int) -> None:
        self.coolant.clear()
        self.dirty()

    # -- Hyrel terms --------------------------------------------------------------------------------------

    def build_look(self) -> Look:
        heat = self.heat
        temp, flow = heat.working(infer=not self.pure)
        aux = heat.aux_fans() + tuple((AUX_PORTS[code], 100.0) for code in sorted(self.coolant))
        own = heat.own_fan(heat.tool)
        return Look(
            layer=(None, self.layers.heights) if self.layers is not None and self.cutter is None else None,
            head=heat.head(),
            temp=temp,
            fan=round(own if own is not None else heat.fans.get(0, 0.0) if heat.owner(0) is None else 0.0, 3),
            flow=round(flow, 4),
            beds=heat.bed_look(),
            spindle=self.spindle,
            aux=aux,
            wcs=self.wcs,
        )

    def end_state(self) -> EndState:
        heat = self.heat
        spindles = {self.mapping.spindle_address(): self.spindle[0]} if self.spindle else {}
        end = EndState(
            ended=True,  # a print ends with its file (RepRapFirmware's M0/M1/M2 end it before)
            heaters=heat.end_heaters(),
            fans=heat.end_fans(),
            spindles=spindles,
            aux={AUX_PORTS[code]: 100.0 for code in self.coolant},
        )
        return end if self.pure else self.finish_end(end)


class RepRapSimulator(MarlinSimulator):
    RRF = True

    def __init__(self, dialect, mapping=None, *, cnc: bool = False) -> None:
        super().__init__(dialect, mapping, cnc=cnc)
        self.tool_offsets: dict[int, dict[str, float]] = {}  # G10 L1 P<tool> X Y Z

    def table(self):
        h = super().table()
        h.update(
            {
                "G10": self.g10,
                "M568": self.m568,
                "M116": self.m116,
                "M563": self.m563,
                "M0": self.end_program,
                "M1": self.end_program,
                "M2": self.end_program,
                "M566": self.limits,
            }
        )
        return h

    # RepRapFirmware reads M203 and M566 speeds in mm/min; M566 sets the jerk, M205 the same in mm/s; M204 has
    # P and T only (RepRapFirmware G-code reference, M201-M205, M566)
    LIMIT_WORDS = {
        **MarlinSimulator.LIMIT_WORDS,
        "M204": {"P": ("accel_print",), "T": ("accel_travel",)},
        "M205": {"X": ("jerk_x",), "Y": ("jerk_y",), "Z": ("jerk_z",), "E": ("jerk_e",)},
        "M566": {"X": ("jerk_x",), "Y": ("jerk_y",), "Z": ("jerk_z",), "E": ("jerk_e",)},
    }
    PER_MINUTE = frozenset({"M203", "M566"})

    def home(self, cmd: Command, n: int) -> None:
        listed = "".join(a for a in "XYZ" if a in cmd.params)
        self.home_axes(listed or "XYZ")

    def g10(self, cmd: Command, n: int) -> None:
        params = cmd.params
        if not params:
            self.firmware_retract(cmd, n)  # "G10: Retract" (firmware retraction: no parameters)
            return
        if "P" in params and "L" not in params and "S" in params:
            s = number(params.get("S"))
            if s is not None:
                self.heat.set_temp(_index(params.get("P")), s, wait=False)
                self.dirty()
        tool = _index(params.get("P"))
        if tool is not None and number(params.get("L")) in (None, 1):
            # "G10 P3 X17.8 Y-19.3 Z0.0 ... sets the offset for tool ... 3" (RepRap wiki G-code page 2015, G10;
            # Duet G-code dictionary, G10: G10 L1/L2/L20 P X Y Z... tool offset or WCS origin); T applies the G10
            # offsets (Duet G-code dictionary, T).  Which way an offset moves the head is not in the sources: an
            # axis set while the tool has an offset is in the frame "tool N offset", not at a number.
            offsets = dict(self.tool_offsets.get(tool, {}))
            for letter in "XYZ":
                value = number(params.get(letter))
                if value is not None:
                    offsets[letter] = value
            self.tool_offsets[tool] = offsets

    def frame_label(self, i: int = 0) -> str | None:
        label = super().frame_label(i)
        if self.wcs == "G53" or not self.tool_offsets or i > 2:
            return label  # G53: "ignores WCS and tool offsets" (Duet G-code dictionary, G53)
        tool = self.heat.tool
        if tool is None or not self.tool_offsets.get(tool, {}).get("XYZ"[i]):
            return label
        return f"{label} + tool {tool} offset" if label else f"tool {tool} offset"

    def m568(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        if s is not None:
            self.heat.set_temp(_index(cmd.params.get("P")), s, wait=False)
            self.dirty()

    def m563(self, cmd: Command, n: int) -> None:
        """Define a tool: its own fans (F: Duet G-code dictionary, M563); M106 without P drives "fans of current
        tool" (M106)."""
        tool = _index(cmd.params.get("P"))
        text = cmd.params.get("F")
        if tool is None or text is None:
            return
        fans = tuple(f for f in (_index(part) for part in text.split(":")) if f is not None)
        self.heat.tool_fans[tool] = fans
        self.dirty()

    def fans_of(self, cmd: Command) -> tuple[int, ...]:
        fan = _index(cmd.params.get("P"))
        if fan is not None:
            return (fan,)
        declared = self.heat.tool_fans.get(self.heat.tool) if self.heat.tool is not None else None
        return declared or (0,)  # "S alone -> fans of current tool"

    def m116(self, cmd: Command, n: int) -> None:
        self.heat.wait_all()
        self.dirty()

    def fan_value(self, cmd: Command) -> float | None:
        params = cmd.params
        if "S" not in params:
            if any(letter in params for letter in "CLXBHTRAF"):
                return None  # fan configuration, no speed
            return 1.0
        s = number(params.get("S"))
        if s is None:
            return None
        return s if s <= 1.0 else s / 255  # RepRapFirmware: 0-1, or 0-255 above 1

    def spindle_percent(self, params: dict) -> float | None:
        s = number(params.get("S"))
        if s is None or s <= 0:
            return s
        top = self.mapping.spindle_max_rpm
        if top is None:
            return None  # rpm with no known maximum: compared relatively (spindle_rpm)
        return max(0.0, min(100.0, s / top * 100))

    def spindle_rpm(self, params: dict) -> float | None:
        if self.mapping.spindle_max_rpm is not None:
            return None
        return number(params.get("S"))
