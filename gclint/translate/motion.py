"""Motion: G0/G1 and modal motion words, the E word (X7), the feed (Hyrel's G0 F is one-shot), inches
(X10), and the plain-move route that copies unchanged moves without building their tree.

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.syntax.nodes import GCODE, Command
from gclint.translate.findings import TR_APPROX, TR_LOST, TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.mixin import TranslatorMixin
from gclint.translate.output import fmt, rewrite
from gclint.translate.words import INCH, SCALED, fast_float, num

# comments that state the layer height: (text after ';', stated per layer)
_HEIGHT_HINTS = (("HEIGHT:", True), ("LAYER_HEIGHT:", True), ("Layer height:", False), ("layer_height =", False))


class Motion(TranslatorMixin):
    def implicit_move(self, cmd: Command) -> None:
        """Words with no G code: modal motion (Hyrel gets the G code written out), or a lone F (feed) or
        S (spindle speed) word, which LinuxCNC and Carvera keep for the following commands."""
        params = cmd.params
        mode = self.state.motion_mode
        if not any(a in params for a in "XYZAB"):
            if any(letter not in ("S", "F") for letter in params):  # (Prusa's "P0 S1 L2 D0": not a speed or feed)
                self.remove(cmd, TR_LOST, "words with no command; dropped", key="implicit")
                return
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
        handler(self, _with_code(cmd, mode))
        edit = self.edit
        if edit is None or self.index not in edit.replaced:
            self.replace(cmd, rewrite(cmd, code=mode))
            self._edit().changed = True

    def modal_feed(self, cmd: Command) -> None:
        """An F word on a line with no motion (``G54 G18 G21 F400``): LinuxCNC and the Carvera set the feed
        of later moves from it (``FEED_ON_ANY_COMMAND``).  Hyrel's G1 feed is modal: the F is dropped here and
        written on the next working move that needs it."""
        f = fast_float(cmd.params.get("F"))
        if f is None:
            return
        self.state.feed = f
        self.replace(cmd, rewrite(cmd, drop="F"))

    def mixing_e(self, cmd: Command) -> bool:
        """An E word with one amount per drive (``E1:2``): "Tools are driven using multiple values in the E
        field of G1 commands, each controlling the corresponding drive" (RepRap page, M563; M160 mixing).  A
        Hyrel head has one drive, and a clone squad makes several heads "perform the same exact (extrusion)
        commands" side by side (T_v5, M702), not one line of mixed material: reported, the E word dropped."""
        value = cmd.params.get(self.EXTRUDER)
        if value is None or ":" not in value:
            return False
        self.report(
            TR_UNTRANSLATABLE,
            f"E{value}: one amount per drive of a multi-drive (mixing) tool has no Hyrel counterpart (a Hyrel "
            "head has one drive; clone squads repeat the same moves on several heads); the E word is dropped "
            "and the move does not extrude",
            key="E-mixing",
            cmd=cmd,
            aspects=("e", "moves"),
        )
        return True

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
        if self.g53_next and cmd.code in ("G0", "G1"):
            self.g53_move(cmd, None, "".join(a for a in "XYZAB" if a in cmd.params))  # a G53 alone before it
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
        if ext in params and self.mixing_e(cmd):
            drop = ext
        elif ext in params:
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
                if self.sync_due:
                    self.sync_working_head()
                if g0:
                    # Marlin/RRF: G0 is G1 and extrudes (Marlin G-code reference G0-G1; Duet G-code dictionary G0/G1)
                    out_code = "G1"
                    g0 = False
                    self.extruding_rapid(cmd)
                if self.evalues:
                    if not self.hy.m229_written:
                        self.before_extrusion()
                    if ext != "E" or self.inch:
                        rename = {ext: "E"} if ext != "E" else None
                        values = {"E": self.scaled_e(params[ext])}
                else:
                    rename = {ext: "E"} if ext != "E" else None
                    values = {"E": "1"}
                    self.native_flow(cmd)
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
        f_inch = self.feed_inches()
        if f_inch:
            f = fast_float(params.get("F"))
            if f is not None:
                values = dict(values or {})
                values["F"] = fmt(f * INCH, 2)
        if "F" in params:
            if not g0:  # a G0 F is one-shot on Hyrel; where it is modal in the source, source_feed() differs next
                f = fast_float(params["F"])
                self.hy.feed = f * INCH if f is not None and f_inch else f
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
        hy = self.hy
        if hy.ended or not hy.started_motion or hy.motors_off or self.inch or self.extra_always or self.g53_next:
            return False
        st = self.state
        if e is not None:
            if (
                not g1
                or (x is None and y is None and z is None)
                or not self.evalues
                or not hy.m229_written
                or self.sync_due
            ):
                return False
            delta = float(e)
            if st.e_absolute and st.e_position is not None:
                delta -= st.e_position
            if not delta > 0:
                return False
        if g1:
            if f is not None:
                hy.feed = float(f)
            elif st.feed is not None and st.feed != hy.feed:
                return False
        self._last_ending = ending
        if not self._ending_known and ending:
            self.default_ending = ending
            self._ending_known = True
        hy.wrote_command = True
        self.interp.plain_move("G1" if g1 else "G0", number, x, y, z, e, f)
        return True

    # -- native flow: layer heights (M756) ---------------------------------------------------------------

    def layer_hint(self, raw: str) -> None:
        """A comment that states the layer height: PrusaSlicer/Orca ``;HEIGHT:0.2`` and Bambu ``; LAYER_HEIGHT:
        0.2`` per layer, Cura ``;Layer height: 0.2`` and a ``; layer_height = 0.2`` setting for the job."""
        text = raw.lstrip()
        if not text.startswith(";"):
            return
        body = text[1:].strip()
        for prefix, per_layer in _HEIGHT_HINTS:
            if body.startswith(prefix):
                value = fast_float(body[len(prefix) :].strip().split()[0] if body[len(prefix) :].strip() else None)
                if value is not None and value > 0:
                    if per_layer:
                        self.layer_height = value
                    elif self.default_layer_height is None:
                        self.default_layer_height = value
                return

    def native_flow(self, cmd: Command) -> None:
        """An extruding move in native flow: E1, the layer height, and (once) the finding that the flow is
        Hyrel's own, not the slicer's E amounts (Gcode page, Controlling Material Flow)."""
        if not self.native_reported:
            self.native_reported = True
            self.report(
                TR_APPROX,
                "native flow: Hyrel computes the flow from each move's length, the layer height (M756) and the "
                "head's width (M221 W); the slicer's E amounts are not used",
                key="native-flow",
                cmd=cmd,
                aspects="e",
            )
        self.layer_change(cmd)

    def layer_change(self, cmd: Command) -> None:
        """Native flow computes the flow from the layer height: "We declare M756 at the beginning of every
        layer" (Gcode page, M756).  At the first extruding move of a layer (a new Z): the height the
        slicer stated, else the rise from the layer below."""
        st = self.state
        z = st.position.get("Z")
        v = fast_float(cmd.params.get("Z"))
        if v is not None:
            z = v if st.absolute else (z + v if z is not None else None)
        if z is None:
            return
        if self.inch:
            z *= INCH
        previous = self.layer_z
        if previous is not None and abs(z - previous) < 1e-6:
            self.layer_moves += 1
            pending = self.pending_height
            if pending is not None and self.layer_moves == 2:
                self.pending_height = None
                self.write_height(pending)
            return
        one_move_layer = previous is not None and self.layer_moves <= 1
        self.single_move_layers = self.single_move_layers + 1 if one_move_layer else 0
        self.layer_z, self.layer_moves, self.pending_height = z, 1, None
        # the slicer's per-layer height, else the rise from the layer below: a height stated once for the
        # job (Cura's header ";Layer height: 0.2") is the nominal one, not the first layer's or a variable
        # layer's; it serves only when the rise says nothing
        height = self.layer_height
        if height is None:
            height = z - previous if previous is not None else z
            if not height > 0:
                if self.default_layer_height is None:
                    return
                height = self.default_layer_height
            if one_move_layer:
                # the layer below had one move: a spiral (Z rising on every move) has no layer height; wait
                # for a second move at this height before declaring it
                if self.single_move_layers >= 2 and not self.spiral:
                    self.spiral = True
                    if self.height_before is not None:
                        self.write_height(self.height_before)  # the spiral's first rise was no layer height
                    self.report(
                        TR_APPROX,
                        "Z changes on every extruding move (a spiral): the job states no layer height for "
                        "Hyrel's native flow (M756); use --flow evalues",
                        key="M756-spiral",
                        cmd=cmd,
                        aspects="e",
                    )
                self.pending_height = height
                return
        self.write_height(height)

    def write_height(self, height: float) -> None:
        height = float(fmt(height, 4))  # rises are float differences (0.5 - 0.4): compare what is written
        if height != self.height_written:
            self.height_before = self.height_written
            self.before(f"M756 S{fmt(height, 4)}", note="native flow: the layer height")
            self.height_written = height

    def extruding_rapid(self, cmd: Command) -> None:
        """A G0 that extrudes, written as G1 (Hyrel's G0 cannot extrude): exact where G0 is G1 (Marlin)."""

    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None:
        """Dialect hook: (letters to drop, words to add) for a move; None for no change."""
        return None

    def feed_inches(self) -> bool:
        """Whether this line's F words are inches per minute: the units in force when the source reads them (LinuxCNC
        sets the feed before the line's G20/G21 run: ``Semantics.words_first``; ``line_feed_inch``)."""
        line = self.line_feed_inch
        return self.inch if line is None else line

    def source_feed(self) -> float | None:
        feed = self.state.feed
        if feed is not None and self.inch:
            return feed * INCH
        return feed

    # The extrusion word is a length that G20 makes inches (X10: "multiply X Y Z I J K R F (and linear E) by
    # 25.4"); Machinekit's A is an angular axis, which G20 does not scale.
    E_LINEAR = True

    def scaled_e(self, text: str | None) -> str:
        if self.inch and self.E_LINEAR:
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
