"""Motion: G0/G1 and modal motion words, the E word (X7), the feed (Hyrel's G0 F is one-shot), inches
(X10), and the plain-move route that copies unchanged moves without building their tree.

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.syntax.nodes import GCODE, Command
from gclint.translate.findings import TR_LOST, TR_NOTE
from gclint.translate.output import fmt, rewrite
from gclint.translate.words import INCH, SCALED, fast_float, num


class Motion:
    def implicit_move(self, cmd: Command) -> None:
        """Words with no G code: modal motion (Hyrel gets the G code written out), or a lone F (feed) or
        S (spindle speed) word, which LinuxCNC and Carvera keep for the following commands."""
        params = cmd.params
        mode = self.state.motion_mode
        if not any(a in params for a in "XYZAB"):
            if "S" in params:
                self.speed_word(cmd)
            if "F" in params:
                self.replace(cmd, f"G1 F{params['F']}")
                self.hy.feed = fast_float(params["F"])
                return
            if "S" in params:
                self.consume(cmd)
                return
            self.remove(cmd, TR_LOST, "words with no command; dropped", key="implicit")
            return
        if mode is None:
            self.remove(cmd, TR_LOST, "axis words with no modal motion; dropped", key="implicit")
            return
        handler = self.handlers.get(mode)
        if handler is None:
            self.remove(cmd, TR_LOST, "modal motion with no Hyrel counterpart; dropped", key="implicit")
            return
        handler(_with_code(cmd, mode))
        edit = self.edit
        if edit is None or self.index not in edit.replaced:
            self.replace(cmd, rewrite(cmd, code=mode))
            self._edit().changed = True

    def e_delta(self, cmd: Command) -> float | None:
        """How far the extruder advances on this move, in source units (None: unknown)."""
        value = fast_float(cmd.params.get(self.EXTRUDER))
        if value is None:
            return None
        if not self.state.e_absolute:
            return value
        current = self.state.e_position
        if current is None:
            return value  # unknown position: assume a print move when the value is positive
        return value - current

    def move(self, cmd: Command) -> None:
        """G0/G1 (and implicit motion): E handling (X7), feed (G0 F is one-shot on Hyrel), inches (X10).

        The hot path: a plain G1 that needs no change returns after a few dictionary lookups."""
        if not self.hy.started_motion:
            self.before_motion()
        if self.hy.motors_off:
            self.rehome()
        params = cmd.params
        ext = self.EXTRUDER
        g0 = cmd.code == "G0"
        out_code: str | None = None
        drop = ""
        values: dict[str, str | None] | None = None
        add: tuple[str, ...] = ()
        rename = None
        if ext in params:
            if "X" not in params and "Y" not in params and "Z" not in params:
                self.extruder_only(cmd, self.e_delta(cmd))
                return
            if ext == "E":  # e_delta, inlined for the hot path
                delta = fast_float(params["E"])
                st = self.state
                if delta is not None and st.e_absolute and st.e_position is not None:
                    delta -= st.e_position
            else:
                delta = self.e_delta(cmd)
            if delta is not None and delta > 0:
                if g0:
                    out_code = "G1"  # Marlin/RRF: G0 is G1 and extrudes (dialects.md 1.1 G0)
                    g0 = False
                if self.evalues:
                    if not self.hy.m229_written:
                        self.before_extrusion()
                    if ext != "E" or self.inch:
                        rename = {ext: "E"} if ext != "E" else None
                        values = {"E": self.scaled_e(params[ext])}
                else:
                    rename = {ext: "E"} if ext != "E" else None
                    values = {"E": "1"}
            else:
                drop = ext
                if delta and self.evalues and self.e_absolute():
                    self.after(f"G92 E{self.scaled_e(params[ext])}", note="keeps Hyrel's E position")
        elif "E" in params:
            drop = "E"
        if self.inch:
            values = dict(values or {})
            for letter in SCALED:
                if letter in params and letter not in drop and letter not in values and letter != ext:
                    v = fast_float(params[letter])
                    if v is not None:
                        values[letter] = fmt(v * INCH)
            f = fast_float(params.get("F"))
            if f is not None:
                values["F"] = fmt(f * INCH, 2)
        if "F" in params:
            if not g0:  # a G0 F is one-shot on Hyrel; where it is modal in the source, source_feed() differs next
                f = fast_float(params["F"])
                self.hy.feed = f * INCH if f is not None and self.inch else f
        elif not g0:
            feed = self.state.feed
            if feed is not None:
                if self.inch:
                    feed *= INCH
                if feed != self.hy.feed:
                    add = (*add, "F" + fmt(feed, 2))
                    self.hy.feed = feed
        if self.extra_always or not self.EXTRA_LETTERS.isdisjoint(params):
            extra = self.move_extra(cmd, g0)
            if extra is not None:
                drop += extra[0]
                add = (*add, *extra[1])
        if out_code is None and not drop and not values and not add:
            return
        if drop and not add and all(letter in drop for letter in params):
            self.consume(cmd)  # nothing left to move (the words were dropped, with their findings)
            return
        self.replace(cmd, rewrite(cmd, code=out_code, drop=drop, values=values, add=add, rename=rename))

    def plain_move(
        self,
        g1: bool,
        number: int,
        x: str | None,
        y: str | None,
        z: str | None,
        e: str | None,
        f: str | None,
        ending: str,
    ) -> bool:
        """``translate_line`` for a plain move when ``move`` would leave it unchanged (True), else False
        with nothing done.  The unchanged case of ``move``: motion started, no re-homing due, no inch
        conversion or extra words, an extruding G1 with E values on (M229 written), and a feed that
        Hyrel already has.  tests/test_translate_plain.py checks that the output is the same without."""
        if self.hy.ended or not self.hy.started_motion or self.hy.motors_off or self.inch or self.extra_always:
            return False
        st = self.state
        if e is not None:
            if not g1 or (x is None and y is None and z is None) or not self.evalues or not self.hy.m229_written:
                return False
            delta = float(e)
            if st.e_absolute and st.e_position is not None:
                delta -= st.e_position
            if not delta > 0:
                return False
        if g1:
            if f is not None:
                self.hy.feed = float(f)
            elif st.feed is not None and st.feed != self.hy.feed:
                return False
        self._last_ending = ending
        if not self._ending_known and ending:
            self.default_ending = ending
            self._ending_known = True
        self.hy.wrote_command = True
        self.interp.plain_move("G1" if g1 else "G0", number, x, y, z, e, f)
        return True

    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None:
        """Dialect hook: (letters to drop, words to add) for a move; None for no change."""
        return None

    def source_feed(self) -> float | None:
        feed = self.state.feed
        if feed is not None and self.inch:
            return feed * INCH
        return feed

    def scaled_e(self, text: str | None) -> str:
        if self.inch:
            v = num(text)
            if v is not None:
                return fmt(v * INCH, 5)
        return text or "0"

    def extruder_only(self, cmd: Command, delta: float | None) -> None:
        """A move of the extruder alone (retract, unretract, prime): Hyrel's heads unprime and prime by
        themselves on print <-> travel transitions (M721/M722), so it is dropped, written as
        M721/M722 I1 (retract=explicit), or, when E values are absolute, kept as G92 E so Hyrel's E
        position stays the source's."""
        params = cmd.params
        if self.opts.retract == "explicit" and delta is not None and delta != 0:
            address = self.head(None)
            text = f"M721 T{address} I1" if delta < 0 else f"M722 T{address} I1"
            if address is None:
                self.remove(cmd, TR_NOTE, "retraction dropped", key="retract")
                return
            if self.evalues and self.e_absolute():
                self.after(f"G92 E{self.scaled_e(params[self.EXTRUDER])}", note="keeps Hyrel's E position")
            self.replace(cmd, text, note="TR004 explicit unprime/prime")
            return
        if self.evalues and self.e_absolute():
            self.replace(cmd, f"G92 E{self.scaled_e(params[self.EXTRUDER])}")
            self.report(
                TR_NOTE,
                "extruder-only move (retract/prime) left to the head's automatic unprime/prime; "
                "written as G92 E so Hyrel's E position stays the source's",
                key="e-only",
                cmd=cmd,
            )
            return
        self.remove(
            cmd,
            TR_NOTE,
            "extruder-only move (retract/prime) left to the head's automatic unprime/prime (M721/M722); dropped",
            key="e-only",
        )


def _with_code(cmd: Command, code: str) -> Command:
    """An implicit command seen as the modal code (for the handlers)."""
    return Command(code, GCODE, cmd.column, cmd.params, words=cmd.words)
