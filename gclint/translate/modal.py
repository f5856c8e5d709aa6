"""Modal codes shared by every source: units (X10), positioning and the E mode, G92, workspaces, dwell,
firmware retraction.

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.syntax.nodes import Command
from gclint.translate.findings import TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.output import fmt, rewrite
from gclint.translate.words import INCH, num


class Modal:
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
        if cmd.params:
            self.replace(cmd, cmd.code or "G54")
        self.report(
            TR_NOTE,
            f"{cmd.code} selects Hyrel's stored fixture offsets (Repetrel Settings > Fixture "
            "Offsets); G54 with values would store new ones",
            key="wcs",
            cmd=cmd,
        )

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
        self.after("M82" if absolute else "M83", note=note)
        self.hy.e_mode_written = absolute

    def set_position(self, cmd: Command) -> None:
        """G92: same meaning (X Y Z A B E); Machinekit's extruder A becomes E; inches converted."""
        params = cmd.params
        if not params:
            self.remove(cmd, TR_NOTE, "G92 without axes changes nothing here; dropped", key="G92-bare")
            return
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
                aspects="position",
            )
        if drop or values or add:
            self.replace(cmd, rewrite(cmd, drop=drop, values=values, add=add))

    def dwell_seconds(self, cmd: Command) -> None:
        """G4 P<seconds> (LinuxCNC, Carvera grbl mode) -> G4 S<seconds> (Hyrel P is milliseconds)."""
        params = cmd.params
        if "P" in params:
            self.replace(cmd, rewrite(cmd, drop="P", first=("S" + (params["P"] or "0"),)))
            self.report(
                TR_NOTE, "G4 P is seconds in the source, milliseconds on Hyrel: written as G4 S", key="G4", cmd=cmd
            )
