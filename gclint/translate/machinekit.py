"""Machinekit FDM (LinuxCNC with the FDM remaps) -> Hyrel v5 (docs/translation.md, Machinekit -> Hyrel).

Two flavours of the temperature and fan codes, told apart per command: the first README's
``M104 P<index> S<temp>`` (S present: P is an index) and the final remap's ``M104 P<temp> T<index>``
(no S: P is the value).  The extruder is the A axis (A follows G90/G91), G22/G23 retract, G4 P is
seconds, M2 ends the program.  O-words, # parameters, [expressions], HAL I/O (M62-M68) and user
M-codes (M100-M199) cannot be translated.
"""

from __future__ import annotations

from typing import ClassVar

from gclint.syntax.nodes import Command
from gclint.translate.cnc import CncTranslator
from gclint.translate.findings import TR_APPROX, TR_DROPPED, TR_LOST, TR_NOTE, TR_UNTRANSLATABLE, dropped_aspects
from gclint.translate.findings import codes as _codes
from gclint.translate.output import fmt
from gclint.translate.words import INCH, num


class MachinekitToHyrel(CncTranslator):
    EXTRUDER = "A"
    TURNS_COUNT_THE_ARC = True
    E_MODE_FOLLOWS_POSITIONING: str | None = "the extruder (A) follows G90/G91 in Machinekit"
    FAN_MAX = 255.0
    EXTRA_LETTERS: ClassVar[frozenset[str]] = frozenset("FEBCUVWSP")
    # The extruder A is an angular axis ("[AXIS_3] # Extruders ... TYPE = ANGULAR", ANGULAR_UNITS = degree:
    # corpus machinekit/taz_cramps/TAZ_5_CRAMPS.ini); G20 scales lengths only (docs/translation.md rule X10: X Y Z
    # I J K R F (and linear E) multiplied by 25.4), so A amounts are not converted under G20 (reported: a configuration
    # with a linear A would scale them)
    E_LINEAR = False

    HANDLERS: ClassVar[dict[str, str]] = {  # besides cnc.CNC_HANDLERS
        "G22": "retract",
        "G23": "unretract",
        "G28": "mk_home",
        "G30": "g30",
        "M7": "keep",
        "M8": "keep",
        "M9": "keep",
        "M104": "m104",
        "M109": "m109",
        "M140": "m140",
        "M141": "m141",
        "M190": "m190",
        "M191": "m191",
        "M106": "m106",
        "M107": "m107",
        "M221": "m221",
        "M226": "m226",
        "M300": "beep",
        "M700": "m700",
        "M701": "m701",
        "M702": "m702",
        "G5.2": "nurbs_start",
        "G5.3": "nurbs_end",
    }
    DROPPED: ClassVar[dict[str, tuple[str, str]]] = {
        **_codes("M1", TR_DROPPED, "optional stop (off unless the operator enables it)"),
        **_codes("M400", TR_DROPPED, "wait for the move queue"),
        **_codes("M420", TR_DROPPED, "RGBW light"),
        **_codes(
            "G40 G61 G61.1 G64 G80 G94 G17.1 G18.1 G19.1 G97 G98 G99 M48 M49 M50 M51 M52 M53",
            TR_DROPPED,
            "interpreter mode with no effect on a Hyrel job",
        ),
        **_codes("M200", TR_DROPPED, "filament diameter (velocity extrusion)"),
        **_codes("M207", TR_LOST, "retraction settings (Hyrel heads carry their own unprime/prime settings)"),
        **_codes("M280", TR_LOST, "servo position"),
        **_codes("M710", TR_LOST, "manual filament jog"),
        **_codes("M600 M601 M306", TR_LOST, "Z calibration or probing remap"),
        **_codes("G29 G29.1 G29.2 G30.1 G28.1", TR_LOST, "probing and bed calibration"),
        **_codes(
            "G43 G43.1 G43.2 G49",
            TR_LOST,
            "tool length offsets (Hyrel: M660 registers applied with H on G1; set them up by hand)",
        ),
        **_codes("G92.2 G92.3", TR_LOST, "suspend/restore G92 offsets"),
        **_codes("M19 M70 M71 M72 M73 M60 M61", TR_LOST, "spindle orientation, modal state save/restore, pallet"),
        **_codes("G41 G41.1 G42 G42.1", TR_UNTRANSLATABLE, "cutter radius compensation"),
        **_codes(
            "G5 G5.1 G5.2 G5.3 G7 G8 G33 G33.1 G38.2 G38.3 G38.4 G38.5 G52 G70 G71 G71.1 G71.2 G72 G72.1 G72.2 "
            "G73 G74 G76 G81 G82 G83 G84 G85 G86 G87 G88 G89 G93 G95 G96",
            TR_UNTRANSLATABLE,
            "canned cycle, spline, threading, probing or feed mode Hyrel has no command for",
        ),
        **_codes("M62 M63 M64 M65 M66 M67 M68", TR_UNTRANSLATABLE, "HAL digital/analog I/O"),
        **_codes("M98 M99", TR_UNTRANSLATABLE, "subprogram call"),
        **_codes("G59.1 G59.2 G59.3", TR_UNTRANSLATABLE, "Hyrel has no G59.1-G59.3 workspaces"),
        **_codes("G10", TR_LOST, "tool table or coordinate system setting (G10 L..)"),
    }

    def __init__(self, source, target, options=None) -> None:
        super().__init__(source, target, options)
        self.nurbs = False  # inside a G5.2 ... G5.3 block
        # velocity extrusion (Machinekit-FDM remap.ini, M700-M702 and G22/G23; docs/translation.md, Machinekit ->
        # Hyrel: VE mode if M700/M701/M702 or G22/G23 without A moves, and in VE mode G22/G23 delimit non-printing
        # stretches, the moves between G22 and G23 being travel): the feed moves outside G22 ... G23 print, with no
        # A word
        self.ve = False
        self.ve_travel = False  # between a G22 and its G23
        self.a_moves = False  # a move carried an A word (the extruder is an axis: no VE)

    def e_absolute(self) -> bool:
        return self.state.absolute  # A follows G90/G91

    def e_delta(self, cmd: Command) -> float | None:
        value = num(cmd.params.get("A"))
        if value is None:
            return None
        if not self.state.absolute:
            return value
        current = self.state.position.get("A")
        if current is None:
            return value
        return value - current

    MOVE_OVERRIDE_IGNORES_PLAIN = True  # move() below only adds polar words (@, ^) and NURBS blocks

    def move(self, cmd: Command) -> None:
        if self.nurbs:
            self.untranslatable(cmd, "a NURBS control point (G5.2 block) cannot be translated", key="nurbs")
            return
        if "@" in cmd.params or "^" in cmd.params:
            self.untranslatable(cmd, "polar coordinates (@ radius, ^ angle) cannot be translated", key="polar")
            return
        if "A" in cmd.params:
            self.extruder_axis(cmd)
        self.feed_required(cmd)
        super().move(cmd)

    def arc(self, cmd: Command) -> None:
        if "A" in cmd.params:
            self.extruder_axis(cmd)
        self.feed_required(cmd)
        super().arc(cmd)

    def feed_required(self, cmd: Command) -> None:
        """G1, G2 and G3: "It is an error if: No feed rate has been set" (LinuxCNC g-code.adoc, G1 and G2/G3):
        the interpreter stops there; Hyrel would move at a feed the job never gave."""
        code = cmd.code if cmd.code is not None else self.state.motion_mode
        if code in ("G1", "G2", "G3") and "F" not in cmd.params and self.state.feed is None:
            self.report(
                TR_UNTRANSLATABLE,
                f'{code} before any feed rate: LinuxCNC stops the program here ("No feed rate has been set"); '
                "give the move an F",
                key="no-feed",
                cmd=cmd,
            )

    def scaled_e(self, text: str | None) -> str:
        if self.inch:
            self.report(
                TR_APPROX,
                "G20 (inches): the extruder A is not converted, as an angular axis (TAZ_5_CRAMPS.ini: A TYPE = "
                "ANGULAR, degree); a machine configured with a linear A would scale it by 25.4",
                key="A-inch",
                aspects="e",
            )
        return text or "0"

    def extruder_axis(self, cmd: Command) -> None:
        """A move with an A word: the extruder is an axis, no velocity extrusion from here."""
        if self.ve and not self.a_moves:
            self.report(
                TR_APPROX,
                "an A (extruder axis) move in a velocity-extrusion job: from here only moves with A extrude "
                "(the sources do not say how Machinekit mixes the two)",
                key="VE-A",
                cmd=cmd,
                aspects="e",
            )
        self.a_moves = True

    def velocity_extrusion(self, cmd: Command) -> None:
        """VE mode starts (docs/translation.md, Machinekit -> Hyrel): from now on the feed moves outside G22 ... G23
        print."""
        if self.ve or self.a_moves:
            return  # the extruder is the A axis (docs/translation.md: VE "without A-moves")
        self.ve = True
        self.extra_always = True  # move_extra adds the E1 of printing moves
        self.report(
            TR_APPROX,
            "velocity extrusion (M700-M702, G22/G23): Machinekit extrudes on every feed move outside G22 ... G23; "
            "written as Hyrel native flow (E1 on those moves, the flow computed by Hyrel from the width M221 W "
            "and the layer height M756), not Machinekit's velocity-proportional rate",
            key="VE",
            cmd=cmd,
            aspects="e",
        )

    def ve_print(self, cmd: Command, rapid: bool) -> bool:
        """A move that prints in VE mode: a feed move (G1/G2/G3) that moves X, Y or Z, outside G22 ... G23,
        with no A word of its own."""
        if not self.ve or self.ve_travel or rapid or self.a_moves:
            return False
        if not any(a in cmd.params for a in "XYZ"):
            return False
        if self.sync_due:
            self.sync_working_head()
        if self.evalues and self.hy.m229_written:
            # E1 is a marker only in native flow (Gcode page, M229: "E0 (native flow calculation)")
            self.before("M229 E0 D0", note="velocity extrusion: Hyrel's native flow")
            self.hy.m229_written = False
        return True

    def nurbs_start(self, cmd: Command) -> None:
        self.nurbs = True
        self.untranslatable(cmd, "NURBS block (G5.2 ... G5.3): Hyrel has no spline moves", key="nurbs")

    def nurbs_end(self, cmd: Command) -> None:
        self.nurbs = False
        self.remove(cmd, TR_DROPPED, "end of a NURBS block", key="nurbs-end")

    def implicit_move(self, cmd: Command) -> None:
        if self.nurbs and any(a in cmd.params for a in "XYZP"):
            self.untranslatable(cmd, "a NURBS control point (G5.2 block) cannot be translated", key="nurbs")
            return
        super().implicit_move(cmd)

    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None:
        params = cmd.params
        drop = ""
        if "S" in params:
            drop += "S"  # the spindle speed, modal (for the next M3, or now if it runs)
            self.speed_word(cmd)
        if "P" in params and cmd.code in ("G0", "G1"):
            drop += "P"  # no P on a LinuxCNC G0/G1
        if rapid and "F" in params:
            drop += "F"  # LinuxCNC's G0 ignores F (the F still sets the feed of later G1s)
        if "E" in params:
            drop += "E"
            self.report(
                TR_UNTRANSLATABLE,
                "E is not a word of Machinekit/LinuxCNC (the extruder is the A axis): the E word is dropped and "
                "the move does not extrude (was the job written for another firmware?)",
                key="E-word",
                cmd=cmd,
                aspects="e",
            )
        axes = self.opts.printer.axes
        lost = [letter for letter in "BCUVW" if letter in params and letter not in axes]
        if lost:
            self.report(
                TR_UNTRANSLATABLE,
                f"axis words {' '.join(lost)} dropped: the {self.opts.printer.name} has no such axes "
                "(A is the extruder here)",
                key=("axes", *lost),
                cmd=cmd,
                aspects=("position", "path", "moves", "feed"),
            )
        for letter in "BCUVW":
            if letter in params and letter not in axes:
                drop += letter
        add: tuple[str, ...] = ("E1",) if self.ve_print(cmd, rapid) else ()
        return (drop, add) if drop or add else None

    def extruding_rapid(self, cmd: Command) -> None:
        self.report(
            TR_APPROX,
            "a rapid (G0) that moves the extruder (A): Hyrel's G0 cannot extrude, so it is written as a G1 at the "
            "modal feed",
            key="G0-A",
            cmd=cmd,
            aspects=("moves", "feed", "position", "path", "e"),
        )

    def retract(self, cmd: Command) -> None:
        self.velocity_extrusion(cmd)
        if self.ve:
            self.ve_travel = True
        self.firmware_retract(cmd, "M721", f"{cmd.code} retraction", "G22")

    def unretract(self, cmd: Command) -> None:
        self.velocity_extrusion(cmd)
        if self.ve:
            self.ve_travel = False
        self.firmware_retract(cmd, "M722", f"{cmd.code} retraction", "G22")

    def mk_home(self, cmd: Command) -> None:
        """G28: LinuxCNC's goes through a point to a stored position; Machinekit FDM's remap (g28.ngc) does not
        home: it rapids the listed axes (all if none) to 0 and resets A.  The job's firmware says which
        (gclint.dialects.semantics ``home``; the Machinekit FDM flavour)."""
        if self.source.semantics.home == "predefined":
            self.predefined(cmd)
            return
        if not self.hy.started_motion:
            self.before_motion()
        params = cmd.params
        axes = [a for a in "XYZ" if a in params] or (["X", "Y", "Z"] if "A" not in params else [])
        # g28.ngc: "G0 X0", then "G0 Y0", then "G0 Z0" (one axis at a time), then "G92 A0"
        lines = [f"G0 {a}0" for a in axes]
        if "A" in params or not any(a in params for a in "XYZ"):
            lines.append("G92 E0")
        self.replace(cmd, lines[0])
        if len(lines) > 1:
            self.after(*lines[1:], note="Machinekit's G28, one axis at a time")
        self.report(
            TR_NOTE,
            "Machinekit's G28 (g28.ngc) does not home: it moves X, then Y, then Z to 0 and resets the "
            "extruder; written as the same G0 moves and G92 E0",
            key="G28",
            cmd=cmd,
        )

    def g30(self, cmd: Command) -> None:
        """G30: LinuxCNC's second stored position; Machinekit FDM's remap probes (g30.ngc)."""
        if self.source.semantics.g30 == "predefined":
            self.predefined(cmd)
        else:
            self.remove(cmd, TR_LOST, "probing and bed calibration", key="G30", aspects=dropped_aspects("G30", TR_LOST))

    def predefined(self, cmd: Command) -> None:
        """LinuxCNC's G28 and G30: "a rapid move to the position specified by axes including any offsets, then
        ... a rapid move to the absolute position of the values in parameters 5161-5166 [G30: 5181-5186] for
        all axes specified"; with no axis, every axis goes there; "If no positions are stored with G28.1 then
        all axes will go to the machine origin" (g-code.adoc, "G28, G28.1", "G30, G30.1").  The stored position
        is not in the file: the point is written as a rapid, then Hyrel's G28 homes those axes (the machine
        origin, where a machine with nothing stored goes), and the job's workspace and head are set again."""
        params = cmd.params
        st = self.state
        listed = [a for a in "XYZ" if a in params]
        for axis in listed:
            if num(params[axis]) is None:
                self.untranslatable(cmd, f"{cmd.code} {axis} is not a number", key=(cmd.code, "value"))
                return
        if not self.hy.started_motion:
            self.before_motion(focus=False)  # (the T follows the G28: restore_offsets)
        via = []
        for axis in listed:
            value = num(params[axis])
            assert value is not None
            moves = value != 0 if not st.absolute else st.position.get(axis) != value
            if moves:
                via.append(axis + fmt(value * INCH if self.inch else value))
        axes = listed or ["X", "Y", "Z"]
        home = "G28 " + " ".join(f"{a}0" for a in axes)
        if via:
            self.replace(cmd, "G0 " + " ".join(via))
            self.after(home, note=f"{cmd.code}: then to its stored position")
        else:
            self.replace(cmd, home)
        self.restore_offsets(cmd, axes)
        number = "5161-5169" if cmd.code == "G28" else "5181-5189"
        self.report(
            TR_APPROX,
            f"{cmd.code} goes to the position stored in parameters {number} (the machine origin when none is "
            f"stored), which the file does not give: written as Hyrel's G28 on {' '.join(axes)}, which homes "
            "them; check the machine's stored position",
            key=cmd.code,
            cmd=cmd,
            aspects="position:" + "".join(axes),
        )

    def spindle(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is not None:
            self.rpm = s
        if self.rpm is None:
            # LinuxCNC's M3/M4 turn "at the 'S' speed" (m-code.adoc, "M3, M4, M5 Spindle Control"), none yet here;
            # Hyrel's M3 with no S turns at the speed set on the head ("M3 Spindle On, Clockwise")
            self.report(
                TR_APPROX,
                f"{cmd.code} with no spindle speed set yet: LinuxCNC turns at the S speed (none given), Hyrel's"
                f" {cmd.code} without S at the speed set on the head",
                key="M3-no-S",
                cmd=cmd,
                aspects=("spindle",),
            )
        self.spindle_on(cmd, self.rpm_percent(self.rpm) if self.rpm is not None else None)

    def tool_change(self, cmd: Command) -> None:
        self.tool_change_stops(cmd)  # (M6 stops the spindle, whatever tool it loads)
        index = num(cmd.params.get("T"))
        tool = int(index) if index is not None else self.prepared
        if tool is None or tool < 0:
            self.remove(cmd, TR_LOST, "tool change with no tool prepared", key="M6")
            return
        if tool == self.source.semantics.no_tool:
            # LinuxCNC: "T0 gets special handling: no tool will be selected" (other-code.adoc, "T: Select Tool")
            self.remove(
                cmd,
                TR_LOST,
                f"T{tool} M6 empties the spindle (no tool): Hyrel has no such tool change; dropped",
                key=("M6", tool),
                aspects=("head", "spindle"),
            )
            return
        self.select_tool(cmd, tool)

    # -- temperatures and fans: first README (S present: P = index) or final (P = value, T = index) ----------------

    def _flavour(self, cmd: Command) -> tuple[str | None, int | None]:
        params = cmd.params
        if "S" in params:
            index = num(params.get("P"))
            return params["S"], int(index) if index is not None else None
        index = num(params.get("T"))
        return params.get("P"), int(index) if index is not None else None

    def _temp(
        self, cmd: Command, code: str, address: int | None, temp: str | None, wait: bool, tool: int | None = None
    ) -> None:
        if temp is None:
            self.remove(cmd, TR_DROPPED, f"{cmd.code} without a temperature sets nothing", key=f"{cmd.code}-none")
            return
        self.temperature(cmd, code, address, temp, window=wait, tool=tool)
        if wait:
            self.report(
                TR_NOTE,
                "Machinekit waits until the temperature is in range (heating or cooling): written "
                f"with Hyrel's tolerance window R{fmt(self.opts.temp_window)}",
                key="mk-wait",
                cmd=cmd,
            )

    def m104(self, cmd: Command) -> None:
        temp, index = self._flavour(cmd)
        self._temp(cmd, "M104", self.head(index), temp, False, tool=index)

    def m109(self, cmd: Command) -> None:
        temp, index = self._flavour(cmd)
        self._temp(cmd, "M109", self.head(index), temp, True, tool=index)

    def m140(self, cmd: Command) -> None:
        temp = cmd.params.get("S", cmd.params.get("P"))
        self._temp(cmd, "M140", self.opts.bed, temp, False)

    def m141(self, cmd: Command) -> None:
        temp = cmd.params.get("S", cmd.params.get("P"))
        self._temp(cmd, "M141", self.opts.chamber, temp, False)

    def m190(self, cmd: Command) -> None:
        temp = cmd.params.get("S", cmd.params.get("P"))
        self._temp(cmd, "M190", self.opts.bed, temp, True)

    def m191(self, cmd: Command) -> None:
        temp = cmd.params.get("S", cmd.params.get("P"))
        self._temp(cmd, "M191", self.opts.chamber, temp, True)

    def m106(self, cmd: Command) -> None:
        if "P" not in cmd.params and "S" not in cmd.params:
            # remap.ini "M106 ... argspec=iPt": P is required (a capital in the argspec), and the README's form
            # is "M106 P<index> S<value>"; the interpreter refuses the line (Machinekit-FDM remap.ini, M106)
            self.untranslatable(cmd, "without P: the Machinekit FDM remap requires P and refuses the line", key="M106")
            return
        value, index = self._flavour(cmd)
        if "I" in cmd.params:
            self.report(
                TR_NOTE, "M106 I (execute at once) dropped: Hyrel executes M106 in order", key="M106-I", cmd=cmd
            )
        self.fan(cmd, self.head(index if index is not None else 0, "fan"), num(value), index=index)

    def m107(self, cmd: Command) -> None:
        index = num(cmd.params.get("T", cmd.params.get("P")))
        tool = int(index) if index is not None else 0
        self.fan_off(cmd, self.head(tool, "fan"), index=tool)

    def m221(self, cmd: Command) -> None:
        factor = num(cmd.params.get("P"))
        if factor is None:
            self.remove(cmd, TR_DROPPED, "M221 without a factor sets nothing", key="M221")
            return
        self.flow(cmd, self.head(None), factor)

    def m226(self, cmd: Command) -> None:
        self.pause_command(cmd, "M0")

    def beep(self, cmd: Command) -> None:
        self.before("M792 ; BEEP", note="M300 tone")
        self.consume(cmd)
        self.report(
            TR_NOTE, "tone written as Hyrel's BEEP action: frequency and duration are lost", key="M300", cmd=cmd
        )

    def m700(self, cmd: Command) -> None:
        self.velocity_extrusion(cmd)
        self.remove(
            cmd,
            TR_LOST,
            "velocity-extrusion cross-section (needs the layer height; set M221 W by hand)",
            key="M700",
            aspects="e",
        )

    def m701(self, cmd: Command) -> None:
        self.velocity_extrusion(cmd)
        width = cmd.params.get("P")
        address = self.head(None)
        if width is None or address is None:
            self.remove(cmd, TR_DROPPED, "M701 without a width sets nothing", key="M701")
            return
        self.replace(cmd, f"M221 T{address} W{width}")
        self.report(
            TR_NOTE, "velocity-extrusion line width written as Hyrel's M221 W (native flow)", key="M701", cmd=cmd
        )

    def m702(self, cmd: Command) -> None:
        self.velocity_extrusion(cmd)
        height = cmd.params.get("P")
        if height is None:
            self.remove(cmd, TR_DROPPED, "M702 without a height sets nothing", key="M702")
            return
        self.replace(cmd, f"M756 S{height}")
        self.report(
            TR_NOTE, "velocity-extrusion line height written as Hyrel's M756 (native flow)", key="M702", cmd=cmd
        )

    def fallback(self, cmd: Command) -> None:
        code = cmd.code or ""
        user_code = code[:1] == "M" and len(code) == 4 and code[1:].isdigit() and 100 <= int(code[1:]) <= 199
        if cmd.kind == "gcode" and user_code and code not in self.handlers:
            self.untranslatable(cmd, "user M-code (runs an external program)", key="M1xx")
            return
        super().fallback(cmd)
