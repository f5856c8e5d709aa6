"""Carvera (Smoothieware community firmware, grbl mode) -> Hyrel v5 (docs/translation.md, Carvera -> Hyrel).

M3 S is rpm (Hyrel: percent of the spindle's maximum, configuration ``spindle-max-rpm``); an S word on a
line of its own sets the speed for the next M3; M6 T is an automatic tool change (Hyrel: focus a head
through the tool map, else a manual change: spindle off and a pause); G4 P is seconds; M7/M9 are air
(a configured aux port); M321/M322 enter and leave laser mode, where S on a move is the laser power
(0-1) and firing moves get Hyrel's E1.  ATC, probing, macros and variables cannot be translated.
"""

from __future__ import annotations

from typing import ClassVar

from gclint.syntax.nodes import Command
from gclint.translate.cnc import CncTranslator
from gclint.translate.findings import TR_APPROX, TR_DROPPED, TR_LOST, TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.findings import codes as _codes
from gclint.translate.output import fmt
from gclint.translate.words import num


class CarveraToHyrel(CncTranslator):
    MAX_RPM = 15000.0  # Carvera C1 (Carvera community docs, features/spindle-max-rpm.md)
    EXTRA_LETTERS: ClassVar[frozenset[str]] = frozenset("SABE")

    MACHINE = "the Carvera's"
    G53_ALONE = "next"  # "Must be on a line by itself OR the first G code on a line, the directly following G0/G1
    # will be executed in MCS" (Carvera community docs, gcodes.md G53)
    END_CODES: ClassVar[frozenset[str]] = frozenset({"M2"})  # "M30 End of the program, no action on the Carvera"
    HANDLERS: ClassVar[dict[str, str]] = {  # besides cnc.CNC_HANDLERS
        "M30": "m30",
        "G28": "clearance",
        "M7": "air",
        "M9": "air_off",
        "M17": "motors_on",
        "M18": "disengage",
        "M84": "disengage",
        "M600": "pause",
        "M25": "pause",
        "M1": "optional_stop",
        "M333": "optional_stop_mode",
        "M334": "optional_stop_mode",
        "M321": "laser_mode",
        "M322": "laser_mode_off",
        "M801": "vacuum",
        "M802": "vacuum_off",
        "M821": "light",
        "M822": "light_off",
    }
    DROPPED: ClassVar[dict[str, tuple[str, str]]] = {
        **_codes(
            "M105 M114 M115 M119 M27 M957 M117 M118 M118.1 M20 M21 M23 M24 M26 M503 M500 M501 M502 M504 "
            "M498 M498.1 M499 M499.1 M499.2 M493.4 M601",
            TR_DROPPED,
            "report, message or file operation",
        ),
        **_codes(
            "M331 M332 M335 M811 M812 M831 M832 M841 M842 M881 M882 M885 M886 M887 M888 M1000",
            TR_DROPPED,
            "Carvera machine feature with no effect on the toolpath",
        ),
        **_codes(
            "M336",
            TR_LOST,
            'line-by-line execution mode ("Pauses after each line", Carvera M-code table, M336): the pauses are lost',
        ),
        **_codes("M221", TR_DROPPED, "soft endstops on/off (Carvera's M221 is not a flow command)"),
        **_codes("M82 M83", TR_DROPPED, "extruder mode (no extrusion here)"),
        **_codes("M400 G29", TR_DROPPED, "wait for the move queue"),
        **_codes("G40 G80 G94", TR_DROPPED, "interpreter mode with no effect on a Hyrel job"),
        **_codes("M203 M203.1 M204 M205", TR_LOST, "feed and acceleration limits have no Hyrel counterpart"),
        **_codes("M220 M223 M325", TR_LOST, "feed, spindle or laser override"),
        **_codes("M323 M324 M321.2 M322.2", TR_LOST, "laser test mode"),
        **_codes(
            "M370 M374 M374.1 M375 M375.1 M561 M565 M670",
            TR_LOST,
            "levelling or probe settings (Hyrel's M670 is the Y-arm light)",
        ),
        **_codes("M851 M852", TR_LOST, "extended port power (map it to an aux port by hand)"),
        **_codes("M92 M206 M306 M120 M121 M665 M958 G28.1", TR_LOST, "machine configuration"),
        **_codes(
            "G30 G31 G32 G33 G38.2 G38.3 G38.4 G38.5 G92.4 G93",
            TR_UNTRANSLATABLE,
            "probing, machine-coordinate setting or inverse-time feed Hyrel has no command for",
        ),
        **_codes("M97 M98 M98.1 M99 M32", TR_UNTRANSLATABLE, "jump, subprogram or file call"),
        **_codes("M112", TR_UNTRANSLATABLE, "emergency stop: Hyrel documents no e-stop code"),
        **_codes("G10", TR_UNTRANSLATABLE, "workspace origin setting (G10 L2/L20); use Repetrel fixture offsets"),
    }

    def __init__(self, source, target, options=None) -> None:
        super().__init__(source, target, options)
        self.laser = False  # M321 laser mode
        self.laser_fire = False  # M3 in laser mode
        self.laser_power = 0.0  # percent, modal (S on moves)
        self.laser_power_written: float | None = None
        self.m1_pauses = False  # M334 turned optional stop mode on (M333 off)

    def focus_address(self) -> int | None:
        return self.opts.spindle_address()

    # -- motion -------------------------------------------------------------------------------------------

    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None:
        params = cmd.params
        drop = ""
        add: tuple[str, ...] = ()
        if "S" in params:
            drop += "S"
            self.speed_word(cmd)
        if ("A" in params or "B" in params) and "A" not in self.opts.printer.axes:
            drop += "AB"
            self.report(
                TR_UNTRANSLATABLE,
                f"rotary axis words dropped: the {self.opts.printer.name} has no A/B axis (use --printer ehr or 16a)",
                key="A",
                cmd=cmd,
                aspects=("position", "path", "moves", "feed"),
            )
        if "E" in params:
            drop += "E"
        if self.laser and self.laser_fire and not rapid and self.laser_power > 0:
            if self.laser_power_written != self.laser_power:
                self.before(f"M621 P{fmt(self.laser_power, 1)}", note="laser power")
                self.laser_power_written = self.laser_power
            add = ("E1",)  # a firing move: Hyrel lasers fire on printing moves
        return (drop, add) if drop or add else None

    def speed_word(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is None:
            return
        if self.laser:
            if s > 1:
                self.report(
                    TR_APPROX,
                    "laser power above 1 taken as percent (Carvera's laser S is 0-1)",
                    key="laser-S",
                    cmd=cmd,
                    aspects="laser",
                )
                self.laser_power = min(100.0, s)
            else:
                self.laser_power = s * 100
            return
        super().speed_word(cmd)

    def m30(self, cmd: Command) -> None:
        """ "M30 | End of the program, no action on the Carvera" (Carvera M-code table, M30): the code after it runs
        (example programs run several passes, each ending in M30).  Hyrel's M30 would end the job."""
        self.remove(cmd, TR_DROPPED, "no action on the Carvera (the code after it runs); dropped", key="M30")

    def clearance(self, cmd: Command) -> None:
        self.remove(
            cmd,
            TR_LOST,
            "Carvera's G28 goes to the clearance position; Hyrel's G28 homes and clears "
            "offsets, so it is dropped: add a safe retract",
            key="G28",
            aspects="position",
        )

    def motors_on(self, cmd: Command) -> None:
        if cmd.params:
            self.replace(cmd, "M17")

    def disengage(self, cmd: Command) -> None:
        self.hy.motors_off = True
        if cmd.params:
            self.replace(cmd, cmd.code or "M84")
            self.report(
                TR_APPROX, f"{cmd.code} with axes: Hyrel cuts every motor", key="M18", cmd=cmd, aspects="position"
            )

    def optional_stop_mode(self, cmd: Command) -> None:
        """M333 "Turn off optional stop mode", M334 "Turn on optional stop mode. See M01" (Carvera M-code table;
        the firmware's own test, corpus TEST_M01_M333_M334_OptionalStop.cnc: after M334 "The program should
        pause" at each M01).  Hyrel has no optional stop: the translator decides at each M1."""
        self.m1_pauses = cmd.code == "M334"
        state = "on: the M1 after it become pauses (M0)" if self.m1_pauses else "off: the M1 after it are dropped"
        self.remove(cmd, TR_NOTE, f"optional stop mode {state}", key=("optional-stop", cmd.code))

    def optional_stop(self, cmd: Command) -> None:
        """M1 pauses when optional stop mode is on (M334), else it does nothing (Carvera M-code table: M1, M333,
        M334)."""
        if self.m1_pauses:
            self.pause_command(cmd, "M0 ; gclint: optional stop (M334)")
            self.report(
                TR_NOTE,
                "optional stop with optional stop mode on (M334): written as Hyrel's pause M0",
                key="M1-on",
                cmd=cmd,
            )
            return
        self.remove(
            cmd,
            TR_DROPPED,
            "optional stop with optional stop mode off (no M334 before it in the job): no pause; dropped (if the "
            "operator turned the mode on at the console, the Carvera pauses here and Hyrel does not)",
            key="M1",
            aspects=(),
        )

    def pause(self, cmd: Command) -> None:
        self.pause_command(cmd, f"M0 ; gclint: pause (Carvera {cmd.code})")

    # -- spindle, tools, laser ----------------------------------------------------------------------------

    def spindle(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if self.laser:
            if s is not None:
                self.speed_word(cmd)
            self.laser_fire = True
            self.consume(cmd, "laser mode: firing follows the moves' power (E1 on firing moves)")
            return
        if cmd.code == "M4":
            self.report(
                TR_APPROX,
                "M4 is not documented on the Carvera; written as Hyrel's M4",
                key="M4",
                cmd=cmd,
                aspects="spindle",
            )
        if s is not None:
            self.rpm = s
        rpm = self.rpm
        self.spindle_on(cmd, self.rpm_percent(rpm, self.MAX_RPM) if rpm is not None else None)

    def spindle_stop(self, cmd: Command) -> None:
        if self.laser:
            self.laser_fire = False
            self.consume(cmd)
            return
        self.spindle_off(cmd)

    def tool_change(self, cmd: Command) -> None:
        self.tool_change_stops(cmd)  # (the automatic tool change stops the spindle)
        index = num(cmd.params.get("T"))
        tool = int(index) if index is not None else self.prepared
        if tool is None:
            self.remove(cmd, TR_LOST, "tool change with no tool", key="M6", aspects=("head", "spindle"))
            return
        facts = self.source.semantics
        if tool in (facts.probe_tool, facts.no_tool) or tool < 0:
            what = f"the wireless probe (T{tool})" if tool == facts.probe_tool else f"no tool (T{tool})"
            self.remove(
                cmd,
                TR_LOST,
                f"tool change to {what} has no Hyrel counterpart; dropped",
                key=("M6", tool),
                aspects=("head", "spindle"),
            )
            return
        if tool in self.opts.tool_map:
            self.select_tool(cmd, tool)
            return
        # one Hyrel spindle: a manual tool change
        address = self.spindle_head()
        lines = []
        if address in self.hy.spindles_on:
            lines.append(f"M5 T{address}")
            self.hy.spindles_on.pop(address, None)
        lines.append(f"M0 ; gclint: change to tool {tool}")
        *first, last = lines
        if first:
            self.before(*first, note="spindle off for the manual tool change")
        self.pause_command(cmd, last)
        self.report(
            TR_APPROX,
            "automatic tool change written as a manual change (spindle off, pause); map tools "
            "to Hyrel heads with --tool-map to switch heads instead",
            key="M6-manual",
            cmd=cmd,
            aspects=("head", "spindle", "pause"),
        )

    def laser_mode(self, cmd: Command) -> None:
        running = sorted(self.hy.spindles_on)
        if running:
            # M321: "The machine will drop the current tool automatically" (Carvera M-code table, M321): the spindle
            # stops with it, as at an ATC change (Semantics.tool_change_stops_spindle)
            self.before(*(f"M5 T{a}" for a in running), note="laser mode drops the tool: the spindle stops")
            self.hy.spindles_on.clear()
            self.report(
                TR_NOTE,
                "laser mode (M321) drops the current tool: the running spindle is stopped before the laser",
                key="M321-spindle",
                cmd=cmd,
            )
        self.laser = True
        self.extra_always = True  # every move: firing moves get E1 and the power
        address = self.opts.laser_address()
        self.hy.emitters_on.add(address)
        self.replace(cmd, f"M620 T{address} E1")
        self.report(
            TR_APPROX,
            f"laser mode: the laser is Hyrel device T{address} (set laser=T#); firing moves "
            "get E1 and the power M621 P",
            key="M321",
            cmd=cmd,
            aspects="laser",
        )

    def laser_mode_off(self, cmd: Command) -> None:
        self.laser = False
        self.laser_fire = False
        self.extra_always = False
        address = self.opts.laser_address()
        self.hy.emitters_on.discard(address)
        self.replace(cmd, f"M620 T{address} E0")

    # -- aux devices --------------------------------------------------------------------------------------

    def air(self, cmd: Command) -> None:
        port = self.opts.air
        self.hy.air_on = True
        text = {"M7": "M7", "M8": "M8"}.get(port, f"{port} S100")
        if text != (cmd.code or "") or cmd.params:
            self.replace(cmd, text)

    def air_off(self, cmd: Command) -> None:
        port = self.opts.air
        self.hy.air_on = False
        text = "M9" if port in ("M7", "M8") else f"{port} S0"
        if text != (cmd.code or "") or cmd.params:
            self.replace(cmd, text)

    def footer(self) -> list[str]:
        lines = super().footer()
        if self.hy.air_on and self.opts.air not in ("M7", "M8"):
            lines = [f"{self.opts.air} S0" if t == "M9" else t for t in lines]
        return lines

    def vacuum(self, cmd: Command) -> None:
        s = cmd.params.get("S") or "100"
        self.replace(cmd, f"M679 S{s}")
        self.report(TR_APPROX, "vacuum written as Hyrel's M679 (30M and ESR only)", key="M801", cmd=cmd, aspects="aux")

    def vacuum_off(self, cmd: Command) -> None:
        self.replace(cmd, "M679 S0")

    def light(self, cmd: Command) -> None:
        self.replace(cmd, "M670 S100")
        self.report(TR_NOTE, "light written as Hyrel's Y-arm light M670", key="M821", cmd=cmd)

    def light_off(self, cmd: Command) -> None:
        self.replace(cmd, "M670 S0")

    def fallback(self, cmd: Command) -> None:
        code = cmd.code or ""
        if (
            cmd.kind == "gcode"
            and code[:1] == "M"
            and code[1:4].isdigit()
            and 460 <= int(code[1:4]) <= 499
            and (len(code) == 4 or not code[4].isdigit())
        ):
            self.untranslatable(cmd, "probing, tool changer or tool-length routine of the Carvera", key="M46x-M49x")
            return
        if cmd.kind == "meta" and code == "echo":
            self.remove(cmd, TR_DROPPED, "console echo", key="echo")
            return
        super().fallback(cmd)
