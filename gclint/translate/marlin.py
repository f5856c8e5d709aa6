"""Marlin and RepRapFirmware -> Hyrel v5 (research/dialects.md section 2.1).

The traps (dialects.md 1.7): M109/M190/M191 R is a target that also waits while cooling (Hyrel: a
tolerance window); M106 S is 0-255 (RepRapFirmware also 0-1) and P is a fan index (Hyrel: duty during
extrusion); M221 is a percentage (Hyrel: a multiplier); M203 is mm/s caps (Hyrel: G0 speeds in mm/min);
G10/G11 retract (Hyrel: unsupported); G28 homes every axis (Hyrel: only those listed); G90/G91 also set
the E mode on Marlin; M30 deletes a file.
"""

from __future__ import annotations

from typing import ClassVar

from gclint.syntax.nodes import Command
from gclint.translate.base import HyrelTranslator
from gclint.translate.findings import TR_APPROX, TR_DROPPED, TR_LOST, TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.findings import codes as _codes
from gclint.translate.output import fmt, rewrite
from gclint.translate.words import num

# Codes with no Hyrel counterpart (research/dialects.md 2.1 and 1.8).  TR001: no effect on the job.
_NO_EFFECT = {
    **_codes("M73 M73.2", TR_DROPPED, "print progress display"),
    **_codes("M117 M118", TR_DROPPED, "display or host message"),
    **_codes(
        "M105 M114 M115 M119 M27 M31 M155 M154 M503 M122 M123 M43 M100 M111 M113 M430 M876",
        TR_DROPPED,
        "host report or diagnostic",
    ),
    **_codes("M400", TR_DROPPED, "wait for the move queue (Hyrel runs commands in order)"),
    **_codes("M486 M555", TR_DROPPED, "object labels and print area for the host"),
    **_codes("M75 M76 M77 M78", TR_DROPPED, "print job timer and statistics"),
    **_codes("M108 M110", TR_DROPPED, "host protocol"),
    **_codes("M20 M21 M22 M23 M24 M25 M26 M28 M29 M32 M33 M34 M524 M928", TR_DROPPED, "SD card operation"),
    **_codes(
        "M500 M501 M502 M504 M510 M511 M512 M575 M993 M994 M995 M997 M999",
        TR_DROPPED,
        "settings storage or firmware maintenance",
    ),
    **_codes("M862.1 M862.2 M862.3 M862.4 M862.5 M862.6 M16", TR_DROPPED, "printer, nozzle or firmware check"),
    **_codes("M150 M250 M256 M355 M7219 M960", TR_DROPPED, "lights or display"),
    **_codes("M80 M81 M85 M86 M87", TR_DROPPED, "power supply or idle timeout"),
    **_codes("M120 M121 M540 M302 M412 M413 M591 M603 M217 M145 M149", TR_DROPPED, "firmware safety or preset setting"),
    **_codes("M301 M303 M304 M305 M307 M308 M143 M142", TR_DROPPED, "heater configuration"),
    **_codes(
        "M92 M350 M351 M569 M906 M907 M908 M909 M910 M911 M912 M913 M914 M915 M916 M917 M919",
        TR_DROPPED,
        "stepper driver configuration (Repetrel configures the Hyrel machine)",
    ),
    **_codes(
        "M260 M261 M42 M281 M282 M672 M860 M861 M862 M863 M864 M865 M866 M867 M868 M869 M871",
        TR_DROPPED,
        "pin, bus or sensor configuration",
    ),
    **_codes("M710", TR_DROPPED, "controller fan (the number is Hyrel's RTD enable)"),
    **_codes(
        "M971 M991 M1002 M975 M981 M982 M983 M1003 M1006 M1007 M973 M970 M970.3 M974 M976 M977 M972 M980.3"
        " M963 M964 M969 M1002 M708 M709",
        TR_DROPPED,
        "vendor-specific (Bambu, Prusa) notification or calibration",
    ),
    **_codes("G81 G162 G392", TR_DROPPED, "vendor-specific report or check"),
}

# TR002: the source firmware did something here that Hyrel cannot do from G-code.
_LOST = {
    **_codes(
        "M201 M201.2 M204 M205 M566",
        TR_LOST,
        "acceleration and jerk limits have no Hyrel G-code (M204 and M205 "
        "mean no-ramp speed and homing speed in Hyrel firmware)",
    ),
    **_codes("M900 M572 M593 M592", TR_LOST, "pressure/linear advance and input shaping have no Hyrel counterpart"),
    **_codes(
        "G29 G29.1 G29.2 G30 G31 G32 G33 G34 G35 G80 G26 G425 G39 G380 G383 M420 M421 M422 M423 M425 M851 M48 "
        "M290 M401 M402 G76 M192",
        TR_LOST,
        "bed levelling and probing calibration; Hyrel has none in G-code",
    ),
    **_codes(
        "M207 M208 M209",
        TR_LOST,
        "firmware retraction settings (Hyrel heads carry their own unprime/prime settings, M721/M722)",
    ),
    **_codes("M206 M428 M218", TR_LOST, "home and hotend offsets (Repetrel declares head offsets with M6)"),
    **_codes("M163 M164 M165 M166 M567", TR_LOST, "colour mixing"),
    **_codes("M605", TR_LOST, "duplication mode (Hyrel clone squads need M702/M703 set up by hand)"),
    **_codes("M701 M702", TR_LOST, "filament load/unload (the numbers are Hyrel head reporting and clone squads)"),
    **_codes("M10 M11 M380 M381 M126 M127 M128 M129 M240", TR_LOST, "auxiliary output (valve, solenoid, camera)"),
    **_codes("M665 M666 M951", TR_LOST, "kinematics configuration"),
    **_codes("M404 M405 M406 M407", TR_LOST, "filament width sensor"),
    **_codes("M280", TR_LOST, "servo position"),
    **_codes("G12 G27 G60 M125", TR_LOST, "nozzle cleaning or parking moves"),
    **_codes("M410", TR_LOST, "quick stop"),
    **_codes("M193", TR_LOST, "laser cooler temperature"),
    **_codes("M403", TR_LOST, "MMU filament type"),
}

_UNTRANSLATABLE = {
    **_codes(
        "G5 G6 G42 G61 G150 G38.2 G38.3 G38.4 G38.5",
        TR_UNTRANSLATABLE,
        "a move or probing move Hyrel has no command for (the toolpath changes)",
    ),
    **_codes("M808", TR_UNTRANSLATABLE, "repeat markers (a loop over part of the job)"),
    **_codes("M112", TR_UNTRANSLATABLE, "emergency stop: Hyrel documents no e-stop code"),
    # Bambu's AMS filament change: the numbers are Hyrel's laser and UV codes (M620-M623).
    **_codes(
        "M620 M620.1 M620.3 M620.10 M620.11 M621 M622 M622.1 M623 M624 M625",
        TR_UNTRANSLATABLE,
        "vendor filament-change sequence (the number is a Hyrel laser/UV code)",
    ),
}

_HOST_NO_EFFECT = frozenset(
    {
        "EXCLUDE_OBJECT_DEFINE",
        "EXCLUDE_OBJECT_START",
        "EXCLUDE_OBJECT_END",
        "EXCLUDE_OBJECT",
        "SET_PRINT_STATS_INFO",
        "RESPOND",
        "SET_DISPLAY_TEXT",
        "UPDATE_DELAYED_GCODE",
        "SAVE_VARIABLE",
        "M117",
    }
)
_HOST_LOST = frozenset(
    {
        "SET_VELOCITY_LIMIT",
        "SET_PRESSURE_ADVANCE",
        "SET_RETRACTION",
        "SET_GCODE_OFFSET",
        "SET_INPUT_SHAPER",
        "SET_FAN_SPEED",
        "SET_LED",
        "SET_HEATER_TEMPERATURE",
        "TEMPERATURE_WAIT",
        "SET_TEMPERATURE_FAN_TARGET",
        "BED_MESH_PROFILE",
        "BED_MESH_CLEAR",
        "BED_MESH_CALIBRATE",
        "SET_KINEMATIC_POSITION",
        "SET_EXTRUDER_ROTATION_DISTANCE",
    }
)


class MarlinToHyrel(HyrelTranslator):
    """Marlin 2.x and Marlin-flavour slicer output -> Hyrel v5."""

    HANDLERS: ClassVar[dict[str, str]] = {  # besides HyrelTranslator.HANDLERS
        "G4": "dwell",
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
        "M601": "filament_change",
        "M30": "m30",
        "M2": "m2",
    }
    DROPPED: ClassVar[dict[str, tuple[str, str]]] = {**_NO_EFFECT, **_LOST, **_UNTRANSLATABLE}
    FAN_MAX = 255.0
    RRF = False
    E_MODE_FOLLOWS_POSITIONING: str | None = "Marlin's G90/G91 also set the E mode"
    EXTRA_LETTERS: ClassVar[frozenset[str]] = frozenset("SABUVWCHK")

    def __init__(self, source, target, options=None) -> None:
        super().__init__(source, target, options)
        self.wcs = "G54"

    # -- motion ---------------------------------------------------------------------------------------

    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None:
        params = cmd.params
        drop = ""
        if "S" in params:
            drop += "S"
            self.report(
                TR_APPROX,
                "S (laser power) on a move dropped: Hyrel's G1 S is a flow multiplier and G2 S a segment size",
                key="move-S",
                cmd=cmd,
            )
        if ("A" in params or "B" in params) and "A" not in self.opts.printer.axes:
            drop += "AB"
            self.report(
                TR_UNTRANSLATABLE,
                f"A/B axis words dropped: the {self.opts.printer.name} has no A/B axes",
                key="AB",
                cmd=cmd,
            )
        for letter in "UVWCHK" if cmd.code in ("G0", "G1") else "UVWCH":
            if letter in params:
                drop += letter
        if drop:
            return drop, ()
        return None

    def dwell(self, cmd: Command) -> None:
        params = cmd.params
        if "S" in params and "P" in params:
            self.replace(cmd, rewrite(cmd, drop="P"))
            self.report(
                TR_NOTE, "G4 with S and P: Marlin uses S alone, Hyrel would add them; P dropped", key="G4SP", cmd=cmd
            )

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
        self.hy.motors_off = False
        params = cmd.params
        axes = [a for a in "XYZ" if a in params]
        if "A" in params and "A" in self.opts.printer.axes:
            axes.append("A")
        if "B" in params and "B" in self.opts.printer.axes:
            axes.append("B")
        if not axes:
            home_z = self.opts.homes_z()
            axes = ["X", "Y", "Z"] if home_z else ["X", "Y"]
            if not home_z:
                self.report(
                    TR_APPROX,
                    "G28 homes every axis in the source; Hyrel homes only the listed axes and Z "
                    "is not homed here (G28 X0 Y0; set home-z=true for Z0)",
                    key="G28",
                    cmd=cmd,
                )
        others = [letter for letter in params if letter not in "XYZAB"]
        if others:
            self.report(TR_NOTE, f"G28 {' '.join(others)} dropped (homing options)", key="G28-options", cmd=cmd)
        text = "G28 " + " ".join(f"{a}0" for a in axes)
        if " ".join([cmd.code or "", *(f"{w.letter}{w.value}" for w in cmd.words)]) != text:
            self.replace(cmd, text)
        self.refocus()

    def machine_coordinates(self, cmd: Command) -> None:
        line = self.line
        assert line is not None
        rest = line.commands[self.index + 1 :]
        if any(c.code in ("G0", "G1", "G2", "G3") for c in rest):
            # G53 applies to the rest of the line in the source; Hyrel's G53 is modal "clear offsets"
            self.remove(
                cmd,
                TR_APPROX,
                "G53 prefix: written as G53 before the move and the workspace re-invoked "
                "after it (Hyrel's G53 is modal; G92 and head offsets still apply)",
                key="G53",
            )
            self.before("G53")
            self.after(self.wcs)
        elif self.RRF:
            self.remove(cmd, TR_DROPPED, "G53 alone does nothing in RepRapFirmware", key="G53-alone")

    def workspace(self, cmd: Command) -> None:
        self.wcs = cmd.code or "G54"
        super().workspace(cmd)

    def workspace_extra(self, cmd: Command) -> None:
        self.untranslatable(cmd, "Hyrel has no G59.1-G59.3 workspaces")

    def clear_g92(self, cmd: Command) -> None:
        self.replace(cmd, "G93")
        self.report(TR_NOTE, "G92.1 (reset workspace offsets) written as G93 (clear G92 offsets)", key="G92.1", cmd=cmd)

    def g10(self, cmd: Command) -> None:
        self.firmware_retract(cmd, "M721", "firmware retract", "fw-retract")

    def g11(self, cmd: Command) -> None:
        self.firmware_retract(cmd, "M722", "firmware recover", "fw-retract")

    def pause(self, cmd: Command) -> None:
        if cmd.params or cmd.code != "M0":
            self.replace(cmd, "M0")
            if cmd.params:
                self.report(TR_NOTE, "pause timeout dropped: Hyrel's M0 waits for Resume", key="M0-timeout", cmd=cmd)

    def filament_change(self, cmd: Command) -> None:
        self.replace(cmd, "M0 ; filament change")
        self.report(
            TR_APPROX, f"{cmd.code} (filament change) written as a pause: no park, unload or load", key="M600", cmd=cmd
        )

    def m30(self, cmd: Command) -> None:
        self.untranslatable(cmd, "M30 deletes a file on the SD card here; Hyrel's M30 ends the job")

    def m2(self, cmd: Command) -> None:
        self.remove(cmd, TR_LOST, "M2 has no meaning in Marlin", key="M2")

    def m6(self, cmd: Command) -> None:
        self.remove(cmd, TR_LOST, "M6 is not a tool change here; Hyrel's M6 declares head offsets", key="M6")

    def m226(self, cmd: Command) -> None:
        self.remove(cmd, TR_LOST, "wait for a pin state has no Hyrel counterpart", key="M226")

    def extended(self, cmd: Command) -> None:
        """Klipper-style host commands found in Marlin-flavour files (Orca, Bambu, Klipper start macros)."""
        name = (cmd.code or "").upper()
        if name in _HOST_NO_EFFECT:
            self.remove(cmd, TR_DROPPED, "host command with no effect on the job", key=name)
        elif name in _HOST_LOST:
            self.remove(cmd, TR_LOST, "host (Klipper) setting has no Hyrel counterpart", key=name)
        else:
            self.untranslatable(cmd, "host macro (Klipper): its content is not known here", key=name)

    def beep(self, cmd: Command) -> None:
        # the action is the text after ';' (M792), so it gets a line of its own
        self.before("M792 ; BEEP")
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
            )
            return
        if not any(a in params for a in "XYZ"):
            self.remove(cmd, TR_LOST, "disabling only the extruder motor has no Hyrel counterpart", key="M84-E")
            return
        self.hy.motors_off = True
        self.replace(cmd, cmd.code or "M84")
        self.report(
            TR_APPROX, f"{cmd.code} with axes: Hyrel cuts every motor (re-home before moving)", key="M84-axes", cmd=cmd
        )

    # -- spindle and laser --------------------------------------------------------------------------------

    def spindle(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is None:
            self.spindle_on(cmd, None)
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
        )

    def spindle_stop(self, cmd: Command) -> None:
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
                self.untranslatable(cmd, "material preset temperature (I) is not known to the translator")
            elif "R" in params:
                self.remove(cmd, TR_APPROX, "standby temperature has no Hyrel counterpart", key="standby")
            else:
                self.remove(
                    cmd,
                    TR_DROPPED,
                    "M104 without S sets nothing here (Hyrel would switch the heater off)",
                    key="M104-noS",
                )
            return
        if "R" in params and self.RRF:
            self.report(TR_APPROX, "standby temperature (R) has no Hyrel counterpart", key="standby", cmd=cmd)
        self.temperature(cmd, "M104", self.head(self._tool_index(cmd)), temp)

    def _autotemp_note(self, cmd: Command) -> None:
        if "B" in cmd.params or "F" in cmd.params:
            self.report(TR_NOTE, "autotemp (B/F) dropped", key="autotemp", cmd=cmd)

    def m109(self, cmd: Command) -> None:
        params = cmd.params
        self._autotemp_note(cmd)
        index = self._tool_index(cmd)
        address = self.head(index)
        if "S" in params:
            self.temperature(cmd, "M109", address, params["S"])
        elif "R" in params:
            self.temperature(cmd, "M109", address, params["R"], window=True)
            self.report(
                TR_NOTE,
                "R (wait heating or cooling to this target) written as S with Hyrel's tolerance "
                f"window R{fmt(self.opts.temp_window)}",
                key="wait-R",
                cmd=cmd,
            )
        else:
            self.temperature(cmd, "M109", address, None, window=True)
        if self.RRF and index is not None and address is not None and address != self.hy.focus:
            # RepRapFirmware's M109 T also selects the tool
            self.after(f"T{address}", note="RepRapFirmware's M109 T selects the tool")
            self.hy.focus = address

    def _slot(self, cmd: Command, default: int) -> int | None:
        """RepRapFirmware's bed/chamber slot P: P0 the first (T24), P1 the second (T25)."""
        slot = self._tool_index(cmd, "P") if self.RRF else None
        if slot is None or slot == 0:
            return default
        if slot == 1 and default == 24:
            return 25
        self.report("TR007", f"heater slot P{slot} has no Hyrel address", key=("slot", slot), cmd=cmd)
        return None

    def _heater(self, cmd: Command, code: str, default: int) -> None:
        params = cmd.params
        address = self._slot(cmd, default)
        wait = code in ("M190", "M191")
        if code == "M190" and "T" in params and not self.RRF:
            self.report(TR_APPROX, "M190 T (annealing cool-down time) dropped", key="M190-T", cmd=cmd)
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

    def m106(self, cmd: Command) -> None:
        params = cmd.params
        if "T" in params and not self.RRF:
            self.report(TR_NOTE, "M106 T (secondary fan speed) dropped", key="M106-T", cmd=cmd)
        index = self._tool_index(cmd, "P")
        address = self.head(index if index is not None else 0, "fan")
        self.fan(cmd, address, self._fan_value(cmd))

    def m107(self, cmd: Command) -> None:
        index = self._tool_index(cmd, "P")
        self.fan_off(cmd, self.head(index if index is not None else 0, "fan"))

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
            )
            return
        factor = 1.0 if self.RRF else 60.0
        words = []
        for letter in "XYZ":
            v = num(cmd.params.get(letter))
            if v is not None:
                words.append(f"{letter}{fmt(v * factor, 1)}")
        if not words:
            self.remove(cmd, TR_LOST, "maximum feed rate for the extruder has no Hyrel counterpart", key="M203")
            return
        self.replace(cmd, "M203 " + " ".join(words))
        self.report(
            TR_APPROX,
            "maximum feed rates written as Hyrel's G0 speeds (mm/min): Hyrel does not cap G1",
            key="M203-convert",
            cmd=cmd,
        )

    def m220(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is None or s == 100:
            self.remove(cmd, TR_DROPPED, "feed rate factor at 100 % (or backup/restore) changes nothing", key="M220")
        else:
            self.remove(cmd, TR_LOST, "feed rate factor has no Hyrel counterpart", key="M220-S")

    def m221(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is None:
            self.remove(cmd, TR_DROPPED, "M221 without S sets nothing", key="M221-noS")
            return
        index = self._tool_index(cmd, "D" if self.RRF else "T")
        address = self.head(index)
        if address is None:
            self.consume(cmd)
            return
        # percent -> multiplier (Hyrel M221 S: "direct flow multiplier, 1.0")
        self.replace(cmd, f"M221 T{address} S{fmt(s / 100, 4)}")


class RepRapToHyrel(MarlinToHyrel):
    """RepRapFirmware 3 (Duet) -> Hyrel v5: like Marlin, plus tool temperatures and offsets in G10, fan values
    0-1, meta commands and macros (untranslatable), M116."""

    HANDLERS: ClassVar[dict[str, str]] = {
        "M116": "m116",
        "M568": "m568",
        "M98": "macro",
        "M99": "macro_return",
        "M291": "message_box",
        "M226": "rrf_m226",
        "M0": "rrf_stop",
        "M1": "rrf_stop",
        "M2": "end_program",
    }
    DROPPED: ClassVar[dict[str, tuple[str, str]]] = {
        **MarlinToHyrel.DROPPED,
        **_codes(
            "M550 M551 M552 M553 M554 M555 M556 M557 M558 M559 M560 M561 M562 M563 M564 M570 M571 M573 M574 "
            "M575 M576 M577 M578 M579 M580 M581 M582 M584 M585 M586 M587 M588 M589 M594 M595 M596 M597 M598 "
            "M599 M650 M651 M667 M669 M671 M673 M674 M675 M905 M918 M929 M950 M951 M952 M953 M954 M955 M956 "
            "M957 M998 M409 M409.1 M408 M36 M36.1 M37 M38 M39 M101 M102 M103 M144 M470 M471 M472 M500.1 "
            "M569.1 M569.2 M569.3 M569.4 M569.5 M569.6 M569.7 M569.8 M569.9 M586.4 M292 M450 M451 M452 M453 "
            "M201.1 M260.1 M260.2 M261.1 M261.2 M374 M375 M376 M505 M86",
            TR_DROPPED,
            "RepRapFirmware configuration or report (Repetrel configures the Hyrel machine)",
        ),
        **_codes("G22 G23", TR_LOST, "RepRapFirmware G22/G23 (tool change support) has no Hyrel counterpart"),
        **_codes("G68 G69", TR_UNTRANSLATABLE, "coordinate rotation changes the toolpath"),
        **_codes("G93", TR_UNTRANSLATABLE, "inverse-time feed (every F would need converting per move)"),
        **_codes("G94", TR_DROPPED, "units-per-minute feed mode (Hyrel's only mode)"),
    }
    FAN_MAX = 255.0
    RRF = True
    E_MODE_FOLLOWS_POSITIONING = None  # RepRapFirmware: G90/G91 leave the E mode alone
    CHECK_EXPRESSIONS = True
    END_CODES = frozenset({"M2"})
    MOVE_OVERRIDE_IGNORES_PLAIN = True  # move() below adds cases for H, S and R words only

    def move(self, cmd: Command) -> None:
        params = cmd.params
        homing = "H" in params and num(params.get("H")) not in (None, 0)
        if homing or (cmd.code == "G1" and num(params.get("S")) in (1, 2)):
            self.untranslatable(
                cmd,
                "homing or endstop-sensing move (G1 H/S) is machine-specific; Hyrel's G1 H "
                "applies a tool-height register",
                key="G1-H",
            )
            return
        if "R" in params and num(params.get("R")) not in (None, 0):
            self.untranslatable(
                cmd, "move to a saved restore point (G0/G1 R) depends on the firmware's memory", key="G1-R"
            )
            return
        super().move(cmd)

    def fallback(self, cmd: Command) -> None:
        code = cmd.code
        if (
            cmd.kind == "gcode"
            and code
            and code[0] in "GM"
            and code not in self.DROPPED
            and code not in self.source.codes
        ):
            # RepRapFirmware runs the macro file sys/<code>.g for a code it does not know
            self.untranslatable(
                cmd, "RepRapFirmware runs a macro file for this code; its content is unknown here", key=code
            )
            return
        super().fallback(cmd)

    def dwell(self, cmd: Command) -> None:
        """G4 S and P: RepRapFirmware's units are Hyrel's (S seconds, P milliseconds)."""

    def _fan_value(self, cmd: Command) -> float | None:
        s = num(cmd.params.get("S"))
        if s is not None and s <= 1.0:
            return s * 255  # RepRapFirmware: S 0.0-1.0 is a fraction, above 1 a 0-255 value
        return s

    def m106(self, cmd: Command) -> None:
        params = cmd.params
        if "S" not in params and any(letter in params for letter in "CLXBHTRAF"):
            self.remove(
                cmd,
                TR_DROPPED,
                "fan configuration (RepRapFirmware M106 with configuration parameters)",
                key="M106-config",
            )
            return
        super().m106(cmd)

    def g10(self, cmd: Command) -> None:
        params = cmd.params
        if "L" in params:
            level = num(params.get("L"))
            if level in (2, 20):
                self.untranslatable(
                    cmd, "G10 L2/L20 sets workspace origins; not translated (use Repetrel fixture offsets and G54)"
                )
            else:
                self.remove(cmd, TR_LOST, "tool offsets: Repetrel declares head offsets itself (M6)", key="G10-offset")
            return
        if "P" not in params:
            self.firmware_retract(cmd, "M721", "firmware retract", "fw-retract")
            return
        index = self._tool_index(cmd, "P")
        if any(a in params for a in "XYZ"):
            if self.opts.tool_offsets == "m6":
                self._offsets_as_m6(cmd, index)
                if "S" not in params:
                    return
            else:
                self.report(
                    TR_LOST,
                    "tool offsets in G10 dropped: Repetrel declares head offsets itself (M6; set "
                    "tool-offsets=m6 to write them)",
                    key="G10-offset",
                    cmd=cmd,
                )
        if "S" in params:
            if "R" in params:
                self.report(TR_APPROX, "standby temperature (R) has no Hyrel counterpart", key="standby", cmd=cmd)
            self.temperature(cmd, "M104", self.head(index), params["S"])
        elif "R" in params:
            self.remove(cmd, TR_APPROX, "standby temperature (R) has no Hyrel counterpart", key="standby")
        else:
            self.consume(cmd)

    def _offsets_as_m6(self, cmd: Command, index: int | None) -> None:
        """RepRapFirmware subtracts a tool's offset from the position; Hyrel's M6 declares the head's offset
        (register O = position + 1, the v4 convention): written with the opposite sign, to verify."""
        address = self.head(index)
        if address is None:
            return
        words = [f"M6 T{address} O{address + 1}"]
        for letter in "XYZ":
            value = num(cmd.params.get(letter))
            if value is not None:
                words.append(f"{letter}{fmt(-value)}")
        text = " ".join(words)
        if "S" in cmd.params:
            self.before(text, note="tool offsets")
        else:
            self.replace(cmd, text)
        self.report(
            TR_APPROX,
            "tool offsets written as M6 (sign reversed, register O = head + 1): verify on the "
            "machine; Repetrel also sends head offsets at job start",
            key="G10-m6",
            cmd=cmd,
        )

    def m568(self, cmd: Command) -> None:
        params = cmd.params
        index = self._tool_index(cmd, "P")
        if "S" in params:
            if "R" in params:
                self.report(TR_APPROX, "standby temperature (R) has no Hyrel counterpart", key="standby", cmd=cmd)
            self.temperature(cmd, "M104", self.head(index), params["S"])
        else:
            self.remove(
                cmd, TR_APPROX, "tool settings without an active temperature have no Hyrel counterpart", key="M568"
            )

    def m116(self, cmd: Command) -> None:
        """Wait for every temperature set without waiting: written as explicit waits with a tolerance."""
        window = num(cmd.params.get("S"))
        window_text = fmt(window) if window is not None else fmt(self.opts.temp_window)
        waits = [f"{code} T{address} S{temp} R{window_text}" for address, (code, temp) in sorted(self.hy.temps.items())]
        self.hy.temps.clear()
        if not waits:
            self.remove(cmd, TR_NOTE, "M116 with no temperature set since the last wait; dropped", key="M116-none")
            return
        *first, last = waits
        if first:
            self.before(*first, note="RepRapFirmware M116")
        self.replace(cmd, last)
        self.report(TR_NOTE, "M116 written as explicit waits for the temperatures set before it", key="M116", cmd=cmd)

    def macro(self, cmd: Command) -> None:
        self.untranslatable(cmd, "macro call: the macro's content is not translated")

    def macro_return(self, cmd: Command) -> None:
        self.remove(cmd, TR_DROPPED, "return from a macro", key="M99")

    def message_box(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is not None and s >= 2:
            self.replace(cmd, "M0 ; message")
            self.report(
                TR_APPROX,
                "blocking message box written as a pause (the message text is not shown)",
                key="M291",
                cmd=cmd,
            )
        else:
            self.remove(cmd, TR_DROPPED, "message box", key="M291")

    def rrf_m226(self, cmd: Command) -> None:
        self.replace(cmd, "M0")
        self.report(
            TR_APPROX, "M226 (pause at this point) written as Hyrel's M0 (wait for Resume)", key="M226", cmd=cmd
        )

    def rrf_stop(self, cmd: Command) -> None:
        self.replace(cmd, "M0")
        self.report(
            TR_APPROX,
            f"RepRapFirmware {cmd.code} stops (and may switch heaters and motors off); written as Hyrel's pause M0",
            key="M0-rrf",
            cmd=cmd,
        )

    def extended(self, cmd: Command) -> None:
        self.untranslatable(cmd, "extended command cannot be translated", key=cmd.code)
