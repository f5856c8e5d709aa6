"""Modal codes shared by every source: units (X10), positioning and the E mode, G92, workspaces, dwell,
firmware retraction.

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.syntax.nodes import GCODE, Command
from gclint.translate.findings import TR_APPROX, TR_DROPPED, TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.mixin import TranslatorMixin
from gclint.translate.output import fmt, rewrite
from gclint.translate.words import INCH, num


class Modal(TranslatorMixin):
    def keep(self, cmd: Command) -> None:
        """Same code, same meaning."""

    def units(self, cmd: Command) -> None:
        self.hy.units_seen = True
        inch = cmd.code == "G20"
        feed = self.state.feed
        if feed is not None and inch != self.inch:
            # the modal feed keeps its speed across a change of units (Marlin keeps it in mm/min; LinuxCNC
            # converts it): in the new unit it is another number
            self.state.feed = feed / INCH if inch else feed * INCH
        e = self.state.e_position
        if e is not None and inch != self.inch and self.E_LINEAR:
            # an absolute E compares with the E position in the same units: G20 makes E inches too (X10: "multiply
            # X Y Z I J K R F (and linear E) by 25.4"), so the position the source reached is another number there
            self.state.e_position = e / INCH if inch else e * INCH
        self.inch = inch
        if cmd.code == "G20":
            self.replace(cmd, "G21")
            self.report(
                TR_NOTE,
                "inches: Hyrel's G20 is unsupported; written as G21 and every length converted to mm",
                key="G20",
                cmd=cmd,
            )

    def workspace(self, cmd: Command) -> None:
        """G54-G59 select a workspace elsewhere; on Hyrel they (re)apply the stored fixture offsets, and
        with values they would store new ones (Gcode page, G54 - G59), so values are dropped."""
        self.hy.workspace_seen = True
        self.wcs = cmd.code or "G54"
        self.wcs_selected = True
        if cmd.params:
            self.replace(cmd, cmd.code or "G54")
        self.report(
            TR_NOTE,
            f"{cmd.code} selects Hyrel's stored fixture offsets (Repetrel Settings > Fixture "
            "Offsets); G54 with values would store new ones",
            key="wcs",
            cmd=cmd,
        )

    # -- G53: machine coordinates ------------------------------------------------------------------------

    def machine_coordinates(self, cmd: Command) -> None:
        """G53: machine coordinates for one move in every source ("Machine coordinates for the move it
        prefixes", Marlin; "Non-modal, rest of line only", RepRapFirmware; "Non-modal; requires G0/G1 active",
        LinuxCNC; "the directly following G0/G1 will be executed in MCS", Carvera community docs,
        gcodes.md G53).  Hyrel's G53 is modal "Clear Offsets" ("sets the fixture offsets to (0,0,0,0,0)", Gcode page,
        G53), so the move is written as ``G53`` / the move / the workspace the job had selected (docs/translation.md,
        The pairs).  One implementation for every source."""
        line = self.line
        assert line is not None
        commands = line.parsed.commands
        rest = commands[self.index + 1 :]
        if any(a in cmd.params for a in "XYZAB"):
            # the words are on G53 itself (LinuxCNC "G53 Z-2", "G0 G53 Z-2"): the move is in the motion mode of
            # the line, else the modal one
            before = [c for c in commands[: self.index] if c.code in ("G0", "G1")]
            mode = before[-1].code if before else self.state.motion_mode
            if mode not in ("G0", "G1"):
                self.untranslatable(cmd, "G53 needs G0 or G1 for its move", key="G53-mode", aspects=("position",))
                return
            for c in before:  # the bare motion word is carried by the move written below
                if not c.params:
                    self._edit().replaced[commands.index(c)] = ""
            self.g53_move(cmd, _as_move(cmd, mode), _axes(cmd))
            # the source's coordinates of this point are its machine's: not the program ones the arcs and
            # relative moves after it count from
            for axis in "XYZAB":
                if axis in cmd.params:
                    self.state.position.forget(axis)
        elif any(c.code in ("G0", "G1", "G2", "G3") for c in rest):
            self.consume(cmd)
            self.g53_move(cmd, None, _axes(next(c for c in rest if c.code in ("G0", "G1", "G2", "G3"))))
        elif self.G53_ALONE == "next":
            self.g53_next = True  # "the directly following G0/G1 will be executed in MCS" (Carvera)
            self.consume(cmd)
        elif self.G53_ALONE == "drop":
            self.remove(cmd, TR_DROPPED, "G53 with no move on its line does nothing here", key="G53-alone")

    def g53_move(self, cmd: Command, move: Command | None, axes: str) -> None:
        """``G53`` before the move (``move``: its command, when the G53 carries its words; None when the move
        is a command of its own), the selected workspace again after it; ``axes``: the axes it moves."""
        self.g53_next = False
        self.report(
            TR_APPROX,
            f"G53 move: written as G53 before the move (Hyrel's G53 is modal; G92 and head offsets still apply, "
            f"and {self.MACHINE} coordinates are not the Hyrel's)"
            + (f"; {self.wcs} invoked again after it" if self.wcs_selected else ""),
            key="G53",
            cmd=cmd,
            aspects=("position:" + (axes or "XYZAB"), "wcs"),
        )
        self.before("G53", note="G53: machine coordinates for this move")
        if move is not None:
            self.move(move)
            edit = self._edit()
            if edit.replaced.get(self.index) is None:
                self.replace(cmd, rewrite(move))
        if self.wcs_selected:
            # Hyrel's G53 stays in force; the workspace the source had selected is invoked again.  A job that
            # never selected one had no fixture offsets, and Hyrel has none after G53 either.
            self.after(self.wcs, note="the workspace again after the G53 move")

    def clear_g92(self, cmd: Command) -> None:
        """G92.1 (clear the G92 offsets) is Hyrel's G93 ("G93 clears ALL offsets implemented via G92")."""
        self.replace(cmd, "G93")
        self.report(TR_NOTE, "G92.1 (clear G92 offsets) written as Hyrel's G93", key="G92.1", cmd=cmd)

    def firmware_retract(self, cmd: Command, code: str, what: str, key: str) -> None:
        """A source retract/unretract: left to the head's automatic unprime/prime, or with
        ``retract=explicit`` written as ``M721/M722 T# I1`` (Gcode page, M721/M722: "I1 ... now")."""
        if self.opts.retract == "explicit":
            address = self.head(None)
            if address is not None:
                self.replace(cmd, f"{code} T{address} I1", note=f"TR004 {what} -> {code} I1")
                return
        self.remove(
            cmd,
            TR_NOTE,
            f"{what} left to the head's automatic unprime/prime (set retract=explicit for M721/M722 I1)",
            key=key,
        )

    def positioning(self, cmd: Command) -> None:
        """G90/G91: same meaning for X Y Z; the E mode follows where the source couples them."""
        self.hy.positioning_seen = True
        absolute = cmd.code == "G90"
        note = self.E_MODE_FOLLOWS_POSITIONING
        if note is None or not self.evalues or not self.hy.m229_written or self.hy.e_mode_written == absolute:
            return
        mode = "M82" if absolute else "M83"
        line = self.line
        if line is not None and len(line.parsed.commands) > 1:
            # other commands on the line (G91 G1 X10 A0.5): the E mode right after G90/G91, before the move that
            # the source runs after it (written one command a line, in the order the source runs them)
            glue = line.ending or self.default_ending
            self.replace(cmd, f"{rewrite(cmd)}{glue}{mode}", note=note)
        else:
            self.after(mode, note=note)
        self.hy.e_mode_written = absolute

    def set_position(self, cmd: Command) -> None:
        """G92: same meaning (X Y Z A B E); Machinekit's extruder A becomes E; inches converted."""
        params = cmd.params
        if not params:
            self.remove(cmd, TR_NOTE, "G92 without axes changes nothing here; dropped", key="G92-bare")
            return
        self.g92_axes.update(a for a in "XYZ" if a in params)
        values: dict[str, str] = {}
        drop = ""
        ext = self.EXTRUDER
        add: tuple[str, ...] = ()
        if ext != "E" and ext in params:
            drop += ext
            value = params[ext] or "0"
            add = ("E" + (self.scaled_e(value) if self.inch else value),)
        if self.inch:
            for letter in "XYZE":
                if letter in params and letter not in drop:
                    v = num(params[letter])
                    if v is not None:
                        values[letter] = fmt(v * INCH)
        axes = self.opts.printer.axes
        lost = []
        for letter in params:
            if letter == ext or letter in "XYZ" or (letter == "E" and ext == "E"):
                continue
            if letter in "AB" and letter in axes:
                continue
            if letter not in drop:
                drop += letter
            if letter in "AB":
                lost.append(letter)
        if lost:
            self.report(
                TR_UNTRANSLATABLE,
                f"G92 {' '.join(lost)} dropped: the {self.opts.printer.name} has no such axis",
                key=("G92-axes", *lost),
                cmd=cmd,
                aspects=("position:" + "".join(lost), "offsets"),  # the offset lasts
            )
        if drop or values or add:
            self.replace(cmd, rewrite(cmd, drop=drop, values=values, add=add))

    def dwell(self, cmd: Command) -> None:
        """G4: the pause the source machine makes, as its dialect counts it (``Semantics.dwell``: the number
        ``explain``, the summary and the diff use), written so that Hyrel pauses as long; kept as written when
        Hyrel reads the same time from the same words."""
        params = cmd.params
        source, hyrel = self.source.semantics.dwell, self.target.semantics.dwell
        if source.refused(params):
            name = self.source.title.split(" (")[0]
            self.untranslatable(
                cmd,
                f'G4 without {source.required}: {name} refuses the line and stops the program ("Dwell time missing '
                'with g4"); nothing after it would run there',
                key="G4-refused",
                aspects=("*",),
            )
            return
        seconds = source.seconds(params)
        idle = [letter for letter in "PS" if letter in params and source.unit(letter) is None]
        if not idle and seconds == hyrel.seconds(params):
            return
        if "S" in idle and hasattr(self, "speed_word"):
            # LinuxCNC: the S word of any line is the spindle speed, set before the dwell ("G-code Order of
            # Execution"): a running spindle changes speed here
            self.speed_word(cmd)
        name = self.source.title.split(" (")[0]
        if seconds is None:
            self.replace(cmd, rewrite(cmd, drop="PS"))
            self.report(TR_NOTE, f"G4 gives {name} no time: no pause; its words dropped", key="G4", cmd=cmd)
            return
        only_p = "P" in params and "S" not in params and source.p_seconds == 1.0
        text = "S" + (params["P"] or "0") if only_p else "S" + fmt(seconds)
        self.replace(cmd, rewrite(cmd, drop="PS", first=(text,)))
        if source.p_seconds != hyrel.p_seconds and "P" in params:
            why = "G4 P is seconds in the source, milliseconds on Hyrel"
        elif source.both != hyrel.both and "P" in params and "S" in params:
            why = f"G4 with S and P: {name} uses S alone, Hyrel would add them"
        else:
            why = f"G4: {name} pauses {fmt(seconds)} s"
        extra = "; S is the spindle speed there, not a time" if "S" in idle else ""
        self.report(TR_NOTE, f"{why}{extra}: written as G4 {text}", key="G4", cmd=cmd)


def _as_move(cmd: Command, mode: str) -> Command:
    """The words of a G53 that carries its move, as that move."""
    return Command(mode, GCODE, cmd.column, cmd.params, words=cmd.words)


def _axes(cmd: Command) -> str:
    return "".join(a for a in "XYZAB" if a in cmd.params)
