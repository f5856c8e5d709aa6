"""Header and footer (X4-X6).  Nothing is read ahead (jobs stream): each header line is written before
the first command that needs it (``G21``/``G90`` and a ``T`` before the first move, ``M229 E1 D1`` before
the first extrusion, the ``T`` again after a G28, a re-home after M18/M84), and the footer (emitters,
spindles and air off, ``M30`` last) at the source's end of program or the end of the file.

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.rules.security import host_actions, shell_offsets
from gclint.syntax.nodes import GCODE, Command
from gclint.translate.findings import TR_ACTION, TR_APPROX, TR_NOTE
from gclint.translate.mixin import TranslatorMixin
from gclint.translate.output import fmt
from gclint.translate.words import INCH


class Program(TranslatorMixin):
    def rehome(self) -> None:
        """A move after M18/M84: "All axes with homes must be rehomed after an M18" (Hyrel Gcode page)."""
        self.hy.motors_off = False
        lines = ["G28 X0 Y0 Z0"]
        address = self.hy.focus if self.hy.focus is not None else self.focus_address()
        if address is not None:
            self.hy.focus = address
            lines.append(f"T{address}")  # G28 applies a head offset of 0: focus the head again
        self.before(*lines, note="re-home after M18/M84")
        self.report(
            TR_APPROX,
            "a move after the motors were disengaged: Hyrel must re-home every axis first, G28 X0 Y0 Z0 added",
            key="rehome",
            aspects="position",
        )

    def before_motion(self, focus: bool = True) -> None:
        """Header lines due before the first move: G21, G90 and a T (X5); ``focus=False`` before a G28,
        which applies a head offset of 0 (the T follows it, as in Hyrel's own header)."""
        self.hy.started_motion = True
        lines = []
        if not self.hy.units_seen:
            lines.append("G21")
            self.hy.units_seen = True
        if not self.hy.positioning_seen:
            lines.append("G90" if self.state.absolute else "G91")
            self.hy.positioning_seen = True
        if self.DEFAULT_WORKSPACE and not self.hy.workspace_seen:
            # the source works in its default workspace (LinuxCNC, Carvera: G54, the operator's work
            # origin); Hyrel applies no fixture offsets until a G54-G59 invokes the stored ones
            lines.append(self.DEFAULT_WORKSPACE)
            self.hy.workspace_seen = True
        if self.hy.focus is None and focus:
            address = self.focus_address()
            if address is not None:
                lines.append(f"T{address}")
                self.hy.focus = address
        if lines:
            self.before(*lines, note="header: units, positioning and head focus before the first move")

    def refocus(self) -> None:
        """After a G28: "applies a head offset of 0 mm (as in an M6 O0)" (Gcode page, G28), so the focused
        head is selected again for its offsets to apply."""
        address = self.hy.focus if self.hy.focus is not None else self.focus_address()
        if address is not None:
            self.hy.focus = address
            self.after(f"T{address}", note="head focus again after homing (G28 applies a head offset of 0)")

    def restore_offsets(self, cmd: Command, homed: list[str]) -> None:
        """After homing, Hyrel's G28 "resets current offsets to 0 - including any ... set with a G92 ...,
        performs a G53, and applies a head offset of 0 mm" (Gcode page, G28); the source keeps its workspace
        and the G92 offsets of the axes it did not home.  Written again: the workspace the job selected
        (Hyrel G28 clears them: Hyrel wiki, Gcode page, G28; docs/translation.md, Header and footer), the head focus
        (its offsets), then a G92 that puts each axis not homed back where the source has it (Hyrel keeps
        its machine position: "Any axis not homed will have its position remain unchanged")."""
        if self.wcs_selected:
            self.after(self.wcs, note="the workspace again after homing (Hyrel's G28 performs a G53)")
        self.refocus()
        kept = [a for a in "XYZ" if a in self.g92_axes and a not in homed]
        words, lost = [], []
        for axis in kept:
            value = self.state.position.get(axis)
            if value is None:
                lost.append(axis)
            else:
                words.append(axis + fmt(value * INCH if self.inch else value))
        if words:
            self.after("G92 " + " ".join(words), note="G92 offsets of the axes not homed (Hyrel's G28 clears them)")
            self.report(
                TR_NOTE,
                f"Hyrel's G28 clears the G92 offsets; the offsets of {' '.join(a for a in kept if a not in lost)} "
                "(not homed) are set again with G92",
                key="G28-G92",
                cmd=cmd,
            )
        if lost:
            self.report(
                TR_APPROX,
                f"Hyrel's G28 clears the G92 offsets; the offset of {' '.join(lost)} (not homed, position unknown) "
                "cannot be set again and is lost",
                key="G28-G92-lost",
                cmd=cmd,
                aspects=("position:" + "".join(lost), "offsets"),
            )
        self.g92_axes = set(kept) - set(lost)

    def before_extrusion(self) -> None:
        """``M229 E1 D1`` (and the E mode) before the first extrusion when E amounts carry the flow (X4)."""
        self.hy.m229_written = True
        lines = ["M229 E1 D1"]
        absolute = self.e_absolute()
        if self.hy.e_mode_written is None or self.hy.e_mode_written != absolute:
            lines.append("M82" if absolute else "M83")
            self.hy.e_mode_written = absolute
        self.before(*lines, note="header: the E values carry the flow")

    def e_absolute(self) -> bool:
        return self.state.e_absolute

    def footer(self) -> list[str]:
        """Emitters off, spindles off, air off, M30 last (X6)."""
        lines = [f"M620 T{a} E0" for a in sorted(self.hy.emitters_on)]
        lines += [f"M5 T{a}" for a in sorted(self.hy.spindles_on)]
        if self.hy.air_on:
            lines.append("M9")
        lines.append("M30")
        return lines

    def end_program(self, cmd: Command) -> None:
        """The source's end of program: the footer, with M30 in place of the command."""
        lines = self.footer()
        *first, last = lines
        if first:
            self.before(*first, note="footer")
        if cmd.code == "M30" and not cmd.params and cmd.kind == GCODE:
            pass  # M30 stays M30, byte for byte (not "M30 <text>", which Hyrel would read as a file name)
        else:
            self.replace(cmd, last)
        self.hy.ended = True
        self.hy.emitters_on.clear()
        self.hy.spindles_on.clear()
        self.hy.air_on = False

    # -- pauses --------------------------------------------------------------------------------------------

    def pause_command(self, cmd: Command, text: str = "M0") -> None:
        """Write a pause (``text``: M0 with the translator's own ``; gclint: ...`` message).  On Hyrel the
        text after M0 is a list of host actions ("SHELL C:\\program.exe - the computer will execute the
        file", Gcode page, M0 and M792): a source comment on the line that reads as one is removed (TR009),
        since in the source it was only a comment.  Actions are read as the SC rules read them: a keyword
        starting a segment (any case, without invisible characters), or SHELL anywhere."""
        line = self.line
        comments = line.parsed.comments  # type: ignore[union-attr]
        keywords = {k for c in comments for k, _, _ in host_actions(c.text)}
        if any(shell_offsets(c.text) for c in comments):
            keywords.add("SHELL")
        if keywords:
            self.replace(cmd, text)
            self._edit().strip_comments = True
            self.report(
                TR_ACTION,
                f"the comment on this pause would be a Repetrel action on Hyrel ({', '.join(sorted(keywords))}; SHELL "
                "runs a program, PIC/VID open files): removed",
                key="action",
                cmd=cmd,
                aspects=(),
            )
        elif text != cmd.code or cmd.params:
            self.replace(cmd, text)
