"""Marlin -> Hyrel v5 (docs/translation.md, Marlin and RepRapFirmware -> Hyrel; RepRapFirmware builds on it in
reprap.py).

The traps (docs/translation.md): M109/M190/M191 R is a target that also waits while cooling (Hyrel: a
tolerance window); M106 S is 0-255 (RepRapFirmware also 0-1) and P is a fan index (Hyrel: duty during
extrusion); M221 is a percentage (Hyrel: a multiplier); M203 is mm/s caps (Hyrel: G0 speeds in mm/min);
G10/G11 retract (Hyrel: unsupported); G28 homes every axis (Hyrel: only those listed); G90/G91 also set
the E mode on Marlin; M30 deletes a file.
"""

from __future__ import annotations

import re
from typing import ClassVar

import gclint.translate.marlin_codes as codes
from gclint.syntax.nodes import Command
from gclint.translate.base import HyrelTranslator
from gclint.translate.findings import TR_APPROX, TR_DROPPED, TR_LOST, TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.output import fmt
from gclint.translate.words import num

# Klipper host settings whose loss the meaning diff can see (the others: acceleration, shaping...)
_HOST_ASPECTS: dict[str, tuple[str, ...]] = {
    "SET_FAN_SPEED": ("aux", "fan"),
    "SET_HEATER_TEMPERATURE": ("temp", "beds"),
    "TEMPERATURE_WAIT": ("temp", "beds"),
    "SET_GCODE_OFFSET": ("position",),
    "SET_KINEMATIC_POSITION": ("position",),
    "SET_EXTRUDER_ROTATION_DISTANCE": ("e",),
}


class MarlinToHyrel(HyrelTranslator):
    """Marlin 2.x and Marlin-flavour slicer output -> Hyrel v5."""

    # "M0, M1 | wait for user | P ms, S s, rest of line = text" (Marlin G-code reference, M0-M1):
    # the code (after an N number), its S/P timeout words, then the message
    TEXT_PAUSE: ClassVar[re.Pattern[str] | None] = re.compile(
        r"[ \t]*(?:[Nn][ \t]*\d+[ \t]*)?[Mm][ \t]*0*[01](?![\d.])(?:[ \t]*[SsPp][ \t]*[-+]?(?:\d+\.?\d*|\.\d+)(?![\w.]))*"
    )

    HANDLERS: ClassVar[dict[str, str]] = {  # besides HyrelTranslator.HANDLERS
        "G10": "g10",
        "G11": "g11",
        "G28": "home",
        "G53": "machine_coordinates",
        "G59.1": "workspace_extra",
        "G59.2": "workspace_extra",
        "G59.3": "workspace_extra",
        "M0": "pause",
        "M1": "pause",
        "M3": "spindle",
        "M4": "spindle",
        "M5": "spindle_stop",
        "M6": "m6",
        "M7": "keep",
        "M8": "keep",
        "M9": "keep",
        "M17": "motors_on",
        "M18": "disengage",
        "M84": "disengage",
        "M82": "e_mode",
        "M83": "e_mode",
        "M104": "m104",
        "M106": "m106",
        "M107": "m107",
        "M109": "m109",
        "M140": "m140",
        "M141": "m141",
        "M190": "m190",
        "M191": "m191",
        "M200": "m200",
        "M203": "m203",
        "M220": "m220",
        "M221": "m221",
        "M226": "m226",
        "M300": "beep",
        "M600": "filament_change",
        "M25": "print_pause",
        "M601": "filament_change",
        "M30": "m30",
        "M2": "m2",
    }
    DROPPED: ClassVar[dict[str, tuple[str, str]]] = {**codes.NO_EFFECT, **codes.LOST, **codes.UNTRANSLATABLE}
    FAN_MAX = 255.0
    RRF = False
    E_MODE_FOLLOWS_POSITIONING: str | None = "Marlin's G90/G91 also set the E mode"
    EXTRA_LETTERS: ClassVar[frozenset[str]] = frozenset("SABUVWCHK")
    G53_ALONE = "keep"  # Marlin: G53 "alone on a line activates native workspace" (modal, as Hyrel's)

    # -- motion ---------------------------------------------------------------------------------------

    def __init__(self, source, target, options=None) -> None:
        super().__init__(source, target, options)
        self.laser = False  # S on moves and M3/M4 S are laser power (Marlin: inline power; RRF: M452)
        self.laser_fire = False  # M3/M4 in laser mode (M5 stops it)
        self.cutter_on = False  # the source's M3/M4 (even at S0) until M5
        self.laser_power: float | None = None  # percent, modal
        self.laser_power_written: float | None = None

    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None:
        params = cmd.params
        drop = ""
        add: tuple[str, ...] = ()
        if "S" in params and not self.laser and not self.RRF:
            # Marlin: S is the laser power on G0/G1/G2/G3 (Marlin G-code reference G0-G1, LASER_FEATURE): the machine
            # is a laser
            self.enter_laser(cmd, "a move with S (Marlin's inline laser power)")
        if self.laser:
            if "S" in params:
                drop += "S"
                s = num(params.get("S"))
                if s is not None:
                    self.laser_power = self.laser_percent(cmd, s)
            add = self.laser_move(cmd, rapid)
        elif "S" in params:
            drop += "S"
            self.report(
                TR_APPROX,
                "S (laser power) on a move dropped: Hyrel's G1 S is a flow multiplier and G2 S a segment size",
                key="move-S",
                cmd=cmd,
                aspects=("laser", "spindle", "moves"),  # the moves it cut do not cut
            )
        if ("A" in params or "B" in params) and "A" not in self.opts.printer.axes:
            drop += "AB"
            self.report(
                TR_UNTRANSLATABLE,
                f"A/B axis words dropped: the {self.opts.printer.name} has no A/B axes",
                key="AB",
                cmd=cmd,
                aspects=("position", "path", "moves", "feed"),
            )
        for letter in "UVWCHK" if cmd.code in ("G0", "G1") else "UVWCH":
            if letter in params:
                drop += letter
        if drop or add:
            return drop, add
        return None

    # -- laser (docs/translation.md: M3/M4 laser -> M620 T<laser> E1 (once) + M621 P<pct>; moves with power get
    # E1; G1 ... S<p> (Marlin laser power) -> M621 P<%> before the move, S stripped, %=S/255*100 (PWM)) ------

    def enter_laser(self, cmd: Command, why: str) -> None:
        """From here S is laser power: a spindle started before (the same cutter) stops, the laser is enabled."""
        self.laser = True
        self.extra_always = True  # every move: firing moves get E1 and the power
        address = self.opts.laser_address()
        running = sorted(self.hy.spindles_on)
        if running:
            self.before(*(f"M5 T{a}" for a in running), note="the cutter is a laser: no spindle")
            self.hy.spindles_on.clear()
        self.laser_fire = self.cutter_on  # switched on with M3/M4 before (Marlin: M3 S0, then power on the moves)
        if address not in self.hy.emitters_on:
            self.before(f"M620 T{address} E1", note="laser enabled")
            self.hy.emitters_on.add(address)
        self.report(
            TR_APPROX,
            f"laser mode ({why}): the laser is Hyrel device T{address} (set laser=T#); M3/M4 S and the S on moves "
            "are its power, written as M621 P (percent of 255); firing moves get E1",
            key="laser-mode",
            cmd=cmd,
            aspects=("laser", "spindle", "e"),  # the cutter is a laser, its cuts Hyrel printing moves (E1)
        )

    def leave_laser(self, cmd: Command) -> None:
        address = self.opts.laser_address()
        self.laser = self.laser_fire = False
        self.extra_always = False
        if address in self.hy.emitters_on:
            self.hy.emitters_on.discard(address)
            self.replace(cmd, f"M620 T{address} E0")
        else:
            self.consume(cmd)

    def laser_percent(self, cmd: Command, s: float) -> float:
        """Marlin's cutter power unit is PWM 0-255 by default; RepRapFirmware's laser S is 0-255 (Marlin G-code
        reference M3; Duet G-code dictionary M3)."""
        return min(100.0, max(0.0, s / 255 * 100))

    def laser_move(self, cmd: Command, rapid: bool) -> tuple[str, ...]:
        """A move in laser mode: the power before it when it changes, E1 when it fires."""
        power = self.laser_power
        if not self.laser_fire or power is None or power <= 0:
            return ()
        if rapid:
            self.report(
                TR_APPROX,
                "a G0 while the laser is on: written as a travel move (whether the source fires on G0 depends on "
                "its firmware's configuration)",
                key="laser-G0",
                cmd=cmd,
                aspects="laser",
            )
            return ()
        if self.laser_power_written != power:
            self.before(f"M621 P{fmt(power, 1)}", note="laser power")
            self.laser_power_written = power
        return ("E1",)

    def laser_spindle(self, cmd: Command, s: float | None) -> None:
        """M3/M4 in laser mode: firing on (the moves with power get E1), the power if given."""
        self.laser_fire = True
        if s is not None:
            self.laser_power = self.laser_percent(cmd, s)
        elif self.laser_power is None:
            self.report(
                TR_APPROX,
                f"{cmd.code} without a power and none set before: the laser does not fire until a power is given",
                key="laser-no-power",
                cmd=cmd,
                aspects="laser",
            )
        self.consume(cmd)

    def e_mode(self, cmd: Command) -> None:
        absolute = cmd.code == "M82"
        if not self.evalues:
            self.remove(cmd, TR_NOTE, "E mode dropped: in native flow Hyrel does not use E amounts", key="e-mode")
            return
        if not self.hy.m229_written:
            self.hy.m229_written = True
            self.before("M229 E1 D1", note="header: the E values carry the flow")
        self.hy.e_mode_written = absolute

    def home(self, cmd: Command) -> None:
        if not self.hy.started_motion:
            self.before_motion(focus=False)
        motors_were_off = self.hy.motors_off
        self.hy.motors_off = False
        params = cmd.params
        axes = [a for a in "XYZ" if a in params]
        if motors_were_off and axes and len(axes) < 3:
            # "All axes with homes must be rehomed after an M18" (Hyrel Gcode page, M18)
            missing = [a for a in "XYZ" if a not in axes]
            axes = [a for a in "XYZ" if a in axes or a in missing]
            self.report(
                TR_APPROX,
                f"G28 after M18/M84 homes {' '.join(missing)} too: Hyrel must re-home every axis after the "
                "motors were disengaged",
                key="G28-rehome",
                cmd=cmd,
                aspects="position:" + "".join(missing),
            )
        if "A" in params and "A" in self.opts.printer.axes:
            axes.append("A")
        if "B" in params and "B" in self.opts.printer.axes:
            axes.append("B")
        if not axes:
            home_z = self.opts.homes_z() or motors_were_off  # (every axis after M18/M84)
            axes = ["X", "Y", "Z"] if home_z else ["X", "Y"]
            if not home_z:
                self.report(
                    TR_APPROX,
                    "G28 homes every axis in the source; Hyrel homes only the listed axes and Z "
                    "is not homed here (G28 X0 Y0; set home-z=true for Z0)",
                    key="G28",
                    cmd=cmd,
                    aspects="position:Z",  # X and Y are homed as in the source
                )
        others = [letter for letter in params if letter not in "XYZAB"]
        if others:
            self.report(TR_NOTE, f"G28 {' '.join(others)} dropped (homing options)", key="G28-options", cmd=cmd)
        text = "G28 " + " ".join(f"{a}0" for a in axes)
        if " ".join([cmd.code or "", *(f"{w.letter}{w.value}" for w in cmd.words)]) != text:
            self.replace(cmd, text)
        # the source homes the listed axes, every one when none is listed (Marlin G-code reference, G28)
        self.restore_offsets(cmd, [a for a in "XYZ" if a in params] or ["X", "Y", "Z"])

    def workspace_extra(self, cmd: Command) -> None:
        self.untranslatable(cmd, "Hyrel has no G59.1-G59.3 workspaces", aspects=("wcs", "position", "offsets"))

    def clear_g92(self, cmd: Command) -> None:
        self.g92_axes.clear()
        self.replace(cmd, "G93")
        self.report(TR_NOTE, "G92.1 (reset workspace offsets) written as G93 (clear G92 offsets)", key="G92.1", cmd=cmd)

    def g10(self, cmd: Command) -> None:
        self.firmware_retract(cmd, "M721", "firmware retract", "fw-retract")

    def g11(self, cmd: Command) -> None:
        self.firmware_retract(cmd, "M722", "firmware recover", "fw-retract")

    def pause(self, cmd: Command) -> None:
        self.pause_command(cmd, "M0")
        params = cmd.params
        if num(params.get("S")) is not None or num(params.get("P")) is not None:
            self.report(
                TR_APPROX,
                "pause timeout dropped: Marlin goes on after S seconds / P ms, Hyrel's M0 waits for Resume",
                key="M0-timeout",
                cmd=cmd,
                aspects=("pause", "dwell"),
            )
        elif params:
            self.report(TR_NOTE, "pause message dropped (it is not a comment on Hyrel)", key="M0-message", cmd=cmd)

    def print_pause(self, cmd: Command) -> None:
        """M25 "pause file print" (Marlin G-code reference, M24 and M25: start or resume /
        pause the SD print; Duet G-code dictionary, M25): inside the job it pauses the print until it is resumed."""
        self.pause_command(cmd, "M0 ; gclint: pause (M25)")
        self.report(
            TR_APPROX,
            "M25 (pause the file print until it is resumed) written as Hyrel's pause M0; what the firmware does "
            "on pause (a park move, heaters) is not made",
            key="M25",
            cmd=cmd,
            aspects="pause",
        )

    def filament_change(self, cmd: Command) -> None:
        self.pause_command(cmd, "M0 ; gclint: filament change")
        self.report(
            TR_APPROX,
            f"{cmd.code} (filament change) written as a pause: no park, unload or load",
            key="M600",
            cmd=cmd,
            aspects="pause",
        )

    def m30(self, cmd: Command) -> None:
        """M30 "Delete a file on the SD card" ("M30 filename.gco": RepRap G-code page, M30); Hyrel's M30 ends the
        job, which the translation writes at the end anyway."""
        name = cmd.args.text.strip() if cmd.args is not None else ""
        if not name:
            self.remove(
                cmd, TR_DROPPED, "M30 deletes the SD card file it names, and this one names none", key="M30", aspects=()
            )
            return
        self.remove(
            cmd,
            TR_LOST,
            "M30 deletes a file on the SD card here (Hyrel's M30 ends the job): the deletion is not made",
            key="M30-file",
            aspects=(),
        )

    def m2(self, cmd: Command) -> None:
        self.remove(cmd, TR_LOST, "M2 has no meaning in Marlin", key="M2", aspects=())

    def m6(self, cmd: Command) -> None:
        self.remove(
            cmd, TR_LOST, "M6 is not a tool change here; Hyrel's M6 declares head offsets", key="M6", aspects=()
        )

    def m226(self, cmd: Command) -> None:
        self.remove(cmd, TR_LOST, "wait for a pin state has no Hyrel counterpart", key="M226", aspects=())

    def extended(self, cmd: Command) -> None:
        """Klipper-style host commands found in Marlin-flavour files (Orca, Bambu, Klipper start macros)."""
        name = (cmd.code or "").upper()
        if name in codes.HOST_NO_EFFECT:
            self.remove(cmd, TR_DROPPED, "host command with no effect on the job", key=name)
        elif name in codes.HOST_LOST:
            self.remove(
                cmd,
                TR_LOST,
                "host (Klipper) setting has no Hyrel counterpart",
                key=name,
                aspects=_HOST_ASPECTS.get(name, ()),
            )
        else:
            self.untranslatable(cmd, "host macro (Klipper): its content is not known here", key=name)

    def beep(self, cmd: Command) -> None:
        # the action is the text after ';' (M792), so it gets a line of its own
        self.before("M792 ; BEEP", note="M300 tone")
        self.consume(cmd)
        self.report(
            TR_NOTE, "tone written as Hyrel's BEEP action: frequency and duration are lost", key="M300", cmd=cmd
        )

    def motors_on(self, cmd: Command) -> None:
        if cmd.params:
            self.replace(cmd, "M17")
            self.report(TR_NOTE, "M17 axes dropped: Hyrel engages every motor", key="M17", cmd=cmd)

    def disengage(self, cmd: Command) -> None:
        params = cmd.params
        if not params:
            self.hy.motors_off = True
            return
        if "S" in params and not any(a in params for a in "XYZ"):
            self.remove(
                cmd,
                TR_LOST,
                "motor idle timeout has no Hyrel counterpart (M18/M84 with a value would cut the motors at once)",
                key="M84-S",
                aspects=(),
            )
            return
        if not any(a in params for a in "XYZ"):
            self.remove(
                cmd, TR_LOST, "disabling only the extruder motor has no Hyrel counterpart", key="M84-E", aspects=()
            )
            return
        self.hy.motors_off = True
        self.replace(cmd, cmd.code or "M84")
        self.report(
            TR_APPROX,
            f"{cmd.code} with axes: Hyrel cuts every motor (re-home before moving)",
            key="M84-axes",
            cmd=cmd,
            aspects="position",
        )

    # -- spindle and laser --------------------------------------------------------------------------------

    def spindle(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is None:
            s = num(cmd.params.get("O"))  # Marlin: "O" is the power as PWM 0-255
        self.cutter_on = True
        if self.laser:
            self.laser_spindle(cmd, s)
            return
        if s is None:
            self.spindle_on(cmd, None)
            self.report(
                TR_APPROX,
                f"{cmd.code} without S: the power the source runs it at (an earlier S, the firmware's default) is not "
                "known; written without S",
                key="M3-no-S",
                cmd=cmd,
                aspects="spindle:speed",
            )
            return
        if self.RRF:
            self.spindle_on(cmd, self.rpm_percent(s))
            return
        pct = min(100.0, max(0.0, s / 255 * 100))
        self.spindle_on(cmd, fmt(pct, 1))
        self.report(
            TR_APPROX,
            "spindle/laser power taken as PWM 0-255 (Marlin's default cutter unit) and written as percent",
            key="M3-pwm",
            cmd=cmd,
            aspects="spindle:speed",
        )

    def spindle_stop(self, cmd: Command) -> None:
        self.cutter_on = False
        if self.laser:
            # "M5 -> M5 T<spindle> (or M621 P0 for laser)" (docs/translation.md)
            self.laser_fire = False
            if self.laser_power_written:
                self.replace(cmd, "M621 P0")
                self.laser_power_written = 0.0
            else:
                self.consume(cmd)
            return
        self.spindle_off(cmd)

    # -- temperatures ---------------------------------------------------------------------------------------

    def _tool_index(self, cmd: Command, letter: str = "T") -> int | None:
        value = num(cmd.params.get(letter))
        if value is None or value != int(value) or value < 0:
            return None
        return int(value)

    def m104(self, cmd: Command) -> None:
        params = cmd.params
        self._autotemp_note(cmd)
        temp = params.get("S")
        if temp is None:
            if "I" in params:
                self.untranslatable(
                    cmd, "material preset temperature (I) is not known to the translator", aspects="temp"
                )
            elif "R" in params:
                self.remove(
                    cmd, TR_APPROX, "standby temperature has no Hyrel counterpart", key="standby", aspects="temp"
                )
            else:
                self.remove(
                    cmd,
                    TR_DROPPED,
                    "M104 without S sets nothing here (Hyrel would switch the heater off)",
                    key="M104-noS",
                )
            return
        if "R" in params and self.RRF:
            self.report(
                TR_APPROX, "standby temperature (R) has no Hyrel counterpart", key="standby", cmd=cmd, aspects="temp"
            )
        index = self._tool_index(cmd)
        self.temperature(cmd, "M104", self.head(index), temp, tool=index)

    def _autotemp_note(self, cmd: Command) -> None:
        if "B" in cmd.params or "F" in cmd.params:
            self.report(TR_NOTE, "autotemp (B/F) dropped", key="autotemp", cmd=cmd)

    def m109(self, cmd: Command) -> None:
        params = cmd.params
        self._autotemp_note(cmd)
        index = self._tool_index(cmd)
        address = self.head(index)
        if "S" in params:
            self.temperature(cmd, "M109", address, params["S"], tool=index)
        elif "R" in params:
            self.temperature(cmd, "M109", address, params["R"], window=True, tool=index)
            self.report(
                TR_NOTE,
                "R (wait heating or cooling to this target) written as S with Hyrel's tolerance "
                f"window R{fmt(self.opts.temp_window)}",
                key="wait-R",
                cmd=cmd,
            )
        else:
            # no S or R: the Marlin reference gives M109 only with them (S waits while heating, R both
            # ways).  Hyrel's M109 with no window waits while heating only ("no H/C/L/U/R -> waits until
            # T >= S-1 °C"): a window would wait for cooling too, forever after an M104 S0
            self.temperature(cmd, "M109", address, None, tool=index)
            self.report(
                TR_APPROX,
                "M109 without S or R: written as Hyrel's wait for the set-point while heating (the sources "
                "give M109 only with S, a wait while heating, or R, a wait heating or cooling)",
                key="M109-bare",
                cmd=cmd,
                aspects="temp",
            )
        if self.RRF and index is not None and address is not None:
            # "RRF M109 T selects the tool" (Duet G-code dictionary, M109): a tool change, with what the
            # tool prints with (set-point, part fan, flow) carried to its head before its first working move
            if address != self.hy.focus:
                self.after(f"T{address}", note="RepRapFirmware's M109 T selects the tool")
                old, self.hy.focus = self.hy.focus, address
                self.spindle_to_head(old, address)
            if index != self.state.tool:
                self.sync_due = True
            self.state.tool = index  # the source interpreter does not select it: the translator's view

    def _slot(self, cmd: Command, default: int) -> int | None:
        """RepRapFirmware's bed/chamber slot P: P0 the first (T24), P1 the second (T25)."""
        slot = self._tool_index(cmd, "P") if self.RRF else None
        if slot is None or slot == 0:
            return default
        if slot == 1 and default == 24:
            return 25
        self.report("TR007", f"heater slot P{slot} has no Hyrel address", key=("slot", slot), cmd=cmd, aspects="beds")
        return None

    def _heater(self, cmd: Command, code: str, default: int) -> None:
        params = cmd.params
        address = self._slot(cmd, default)
        wait = code in ("M190", "M191")
        if code == "M190" and "T" in params and not self.RRF:
            self.report(TR_APPROX, "M190 T (annealing cool-down time) dropped", key="M190-T", cmd=cmd, aspects="beds")
        if "S" in params:
            self.temperature(cmd, code, address, params["S"])
        elif "R" in params and wait:
            self.temperature(cmd, code, address, params["R"], window=True)
            self.report(
                TR_NOTE,
                "R (wait heating or cooling to this target) written as S with Hyrel's tolerance "
                f"window R{fmt(self.opts.temp_window)}",
                key="wait-R",
                cmd=cmd,
            )
        elif wait:
            self.temperature(cmd, code, address, None, window=True)
        else:
            self.remove(cmd, TR_DROPPED, f"{code} without S sets nothing", key=f"{code}-noS")

    def m140(self, cmd: Command) -> None:
        self._heater(cmd, "M140", self.opts.bed)

    def m141(self, cmd: Command) -> None:
        self._heater(cmd, "M141", self.opts.chamber)

    def m190(self, cmd: Command) -> None:
        self._heater(cmd, "M190", self.opts.bed)

    def m191(self, cmd: Command) -> None:
        self._heater(cmd, "M191", self.opts.chamber)

    # -- fans and flow ------------------------------------------------------------------------------------

    def _fan_value(self, cmd: Command) -> float | None:
        return num(cmd.params.get("S"))

    def part_fan_note(self) -> None:
        """Marlin's M106/M107 without P drive "the one part fan whichever extruder is active"; on a printer
        built with a fan per extruder they drive the active extruder's own fan instead.  How many fans the
        printer has is firmware configuration, not in the file: the one-fan reading is kept, with a note."""
        self.report(
            TR_NOTE,
            "M106/M107 without P while a tool other than T0 is active: taken as the one part fan, moved to the head "
            "that prints; on a Marlin printer with a fan per extruder it is that extruder's own fan (the fan "
            "count is firmware configuration, not in the file)",
            key="fan-count",
        )

    def m106(self, cmd: Command) -> None:
        params = cmd.params
        if "T" in params and not self.RRF:
            self.report(TR_NOTE, "M106 T (secondary fan speed) dropped", key="M106-T", cmd=cmd)
        index = self._tool_index(cmd, "P")
        if index is None and self.current_tool() != 0:
            self.part_fan_note()
        address = self.head(index if index is not None else 0, "fan")
        self.fan(cmd, address, self._fan_value(cmd), index=index)

    def m107(self, cmd: Command) -> None:
        index = self._tool_index(cmd, "P")
        if index is None and self.current_tool() != 0:
            self.part_fan_note()
        self.fan_off(cmd, self.head(index if index is not None else 0, "fan"), index=index)

    def m200(self, cmd: Command) -> None:
        d = num(cmd.params.get("D"))
        if d and self.evalues:
            self.remove(
                cmd,
                TR_APPROX,
                "volumetric E (M200 D): Hyrel takes E as given; set the heads' P in pulses per microlitre",
                key="M200",
            )
        else:
            self.remove(cmd, TR_DROPPED, "filament diameter setting", key="M200")

    def m203(self, cmd: Command) -> None:
        if self.opts.max_feed != "convert":
            self.remove(
                cmd,
                TR_LOST,
                "maximum feed rates (mm/s) are not Hyrel's M203 (G0 speeds in mm/min); "
                "dropped (set max-feed=convert to write them as G0 speeds)",
                key="M203",
                aspects=(),
            )
            return
        factor = 1.0 if self.RRF else 60.0
        words = []
        for letter in "XYZ":
            v = num(cmd.params.get(letter))
            if v is not None:
                words.append(f"{letter}{fmt(v * factor, 1)}")
        if not words:
            self.remove(
                cmd, TR_LOST, "maximum feed rate for the extruder has no Hyrel counterpart", key="M203", aspects=()
            )
            return
        self.replace(cmd, "M203 " + " ".join(words))
        self.report(
            TR_APPROX,
            "maximum feed rates written as Hyrel's G0 speeds (mm/min): Hyrel does not cap G1",
            key="M203-convert",
            cmd=cmd,
            aspects=(),
        )

    def m220(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is None or s == 100:
            self.remove(cmd, TR_DROPPED, "feed rate factor at 100 % (or backup/restore) changes nothing", key="M220")
        else:
            self.remove(cmd, TR_LOST, "feed rate factor has no Hyrel counterpart", key="M220-S", aspects="feed")

    def m221(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is None:
            self.remove(cmd, TR_DROPPED, "M221 without S sets nothing", key="M221-noS")
            return
        index = self._tool_index(cmd, "D" if self.RRF else "T")
        # percent -> multiplier (Hyrel M221 S: "direct flow multiplier, 1.0")
        self.flow(cmd, self.head(index), s / 100, tool=index)
