"""Arcs (X9): Hyrel's G2/G3 draw XY arcs with I/J centres and compute their flow natively even under
M229 E1 (Hyrel Gcode page, G2), so an R-form arc gets its centre, and an arc in another plane, with extra
turns, in inches or whose E amount matters is written as G1 segments (geometry in arcs.py).

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

import math

import gclint.translate.arcs as arcs
from gclint.syntax.nodes import Command
from gclint.translate.findings import TR_APPROX, TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.mixin import TranslatorMixin
from gclint.translate.output import fmt, rewrite
from gclint.translate.words import INCH, num


class ArcMoves(TranslatorMixin):
    def arc_mode(self, cmd: Command) -> None:
        """G90.1/G91.1 (LinuxCNC, "Arc Distance Mode"): I, J and K are the centre's coordinates, or offsets from
        the start.  Hyrel's are offsets: each arc under G90.1 is written with the offsets of its centre."""
        if not self.source.semantics.arc_centre_modes:
            self.fallback(cmd)
            return
        self.arc_absolute = cmd.code == "G90.1"
        self.remove(
            cmd,
            TR_NOTE,
            "arc centres are absolute in the source; Hyrel's I and J are offsets: each arc is written with its centre "
            "as offsets from its start"
            if self.arc_absolute
            else "arc centres are offsets again, as on Hyrel",
            key=cmd.code,
        )

    def absolute_centre(self, cmd: Command, plane: int) -> Command | None:
        """An arc under G90.1 with its centre as offsets from its start; None (reported) when the start is not
        known or a centre word is missing ("When G90.1 is in effect I and J both must be specified")."""
        a, b, oa, ob, _ = arcs.PLANES[plane]
        params = cmd.params
        st = self.state
        sa, sb = st.position.get(a), st.position.get(b)
        ca, cb = num(params.get(oa)), num(params.get(ob))
        if ca is None or cb is None:
            self.untranslatable(
                cmd, f"G90.1 (absolute centres) needs both {oa} and {ob}: LinuxCNC refuses this arc", key="G90.1-arc"
            )
            return None
        if sa is None or sb is None:
            self.untranslatable(
                cmd, "an arc with an absolute centre (G90.1) from a start the file does not give", key="G90.1-start"
            )
            return None
        changed = dict(params)
        changed[oa], changed[ob] = fmt(ca - sa), fmt(cb - sb)
        return Command(cmd.code, cmd.kind, cmd.column, changed)

    def arc(self, cmd: Command) -> None:
        """G2/G3: R-form -> I/J, other planes, extra turns and E amounts that matter -> G1 segments (X9)."""
        if not self.hy.started_motion:
            self.before_motion()
        if self.hy.motors_off:
            self.rehome()
        st = self.state
        plane = st.plane if st.plane in arcs.PLANES else 17
        centre: dict[str, str | None] = {}  # (G90.1: the centre words to write, as offsets)
        if self.arc_absolute and "R" not in cmd.params:
            offsets = self.absolute_centre(cmd, plane)
            if offsets is None:
                return
            _, _, oa, ob, _ = arcs.PLANES[plane]
            scale = INCH if self.inch else 1.0  # (the offsets are in the source's units: X10, every length in mm)
            cmd, centre = offsets, {k: fmt((num(offsets.params[k]) or 0.0) * scale) for k in (oa, ob)}
        params = cmd.params
        ext = self.EXTRUDER
        mixing = ext in params and self.mixing_e(cmd)
        delta = self.e_delta(cmd) if ext in params and not mixing else None
        extruding = delta is not None and delta > 0
        if extruding and self.sync_due:
            self.sync_working_head()
        turns = num(params.get("P")) if "P" in params else None
        if turns is not None and self.TURNS_COUNT_THE_ARC:
            turns -= 1  # LinuxCNC: "P - number of turns", P1 being the plain arc
        if "R" not in params:
            a, b, oa, ob, _ = arcs.PLANES[plane]
            if not num(params.get(oa)) and not num(params.get(ob)):
                # Hyrel: "I=J=0 -> INVALID ARC" (Hyrel wiki, Gcode page, G2); the source rejects it too
                self.untranslatable(cmd, "arc with no centre (I and J both 0 or missing)", key="arc-no-centre")
                return
            self._check_radius(cmd, plane)
        if plane != 17 or (turns is not None and turns >= 1) or (extruding and self.evalues):
            self.linearize(cmd, plane, delta, int(turns or 0))
            return
        drop = ""
        add: tuple[str, ...] = ()
        values: dict[str, str | None] = dict(centre)
        if "R" in params:
            ij = self._centre(cmd)
            if ij is None:
                return
            drop += "R"
            scale = INCH if self.inch else 1.0
            values["I"], values["J"] = fmt(ij[0] * scale), fmt(ij[1] * scale)
            self.report(
                TR_NOTE, "R-form arc written with its centre I/J (Hyrel's G2/G3 take no R)", key="arc-R", cmd=cmd
            )
        if "K" in params:
            drop += "K"
        if "P" in params:
            drop += "P"
        if ext in params:
            if extruding:
                self.native_flow(cmd)
                if ext != "E":
                    drop += ext
                    add = ("E1",)
                else:
                    values["E"] = "1"
            else:
                drop += ext
                if self.evalues and self.e_absolute() and delta:
                    self.after(f"G92 E{self.scaled_e(params[ext])}", note="keeps Hyrel's E position")
        if self.inch:  # X10: every length in mm (the arc stays an arc)
            for letter in "XYZIJ":
                if letter in params and letter not in drop and letter not in values:
                    v = num(params[letter])
                    if v is not None:
                        values[letter] = fmt(v * INCH)
        if "F" in params:
            f = num(params["F"])
            if f is not None and self.feed_inches():
                f *= INCH
                values["F"] = fmt(f, 2)
            self.hy.feed = f
        else:
            feed = self.source_feed()
            if feed is not None and feed != self.hy.feed:
                add = (*add, "F" + fmt(feed, 2))
                self.hy.feed = feed
        extra = self.move_extra(cmd, False)
        if extra is not None:
            drop += extra[0]
            add = (*add, *extra[1])
        if drop or add or values:
            self.replace(cmd, rewrite(cmd, drop=drop, values=values, add=add))

    def _check_radius(self, cmd: Command, plane: int) -> None:
        """An I/J/K arc whose end is not on its circle: LinuxCNC and grbl refuse it ("radius to end of arc
        differs from radius to start"); Hyrel's drawing of it is not documented."""
        st = self.state
        params = cmd.params
        a, b, oa, ob, _ = arcs.PLANES[plane]
        sa, sb = st.position.get(a), st.position.get(b)
        if sa is None or sb is None:
            return
        ea, eb = num(params.get(a)), num(params.get(b))
        if not st.absolute:
            ea = sa + (ea or 0.0)
            eb = sb + (eb or 0.0)
        ea = sa if ea is None else ea
        eb = sb if eb is None else eb
        ia, ib = num(params.get(oa)) or 0.0, num(params.get(ob)) or 0.0
        r0 = math.hypot(ia, ib)
        r1 = math.hypot(ea - sa - ia, eb - sb - ib)
        unit = INCH if self.inch else 1.0
        if abs(r1 - r0) * unit > max(arcs.CHORD_TOLERANCE, 0.001 * r0 * unit):
            self.report(
                TR_APPROX,
                f"arc whose end is not on its circle (radius {fmt(r0 * unit, 3)} mm at the start, "
                f"{fmt(r1 * unit, 3)} mm at the end): the source firmware refuses or bends it",
                key="arc-radius",
                cmd=cmd,
                aspects=("path", "position"),
            )

    def _centre(self, cmd: Command) -> tuple[float, float] | None:
        """The I/J of an R-form XY arc (None, reported, when it cannot be computed)."""
        st = self.state
        params = cmd.params
        x0, y0 = st.position.get("X"), st.position.get("Y")
        radius = num(params.get("R"))
        if x0 is None or y0 is None or radius is None:
            self.untranslatable(
                cmd, "R-form arc from an unknown position: its centre cannot be computed", key="arc-unknown"
            )
            return None
        x1, y1 = num(params.get("X")), num(params.get("Y"))
        if st.absolute:
            dx = (x1 if x1 is not None else x0) - x0
            dy = (y1 if y1 is not None else y0) - y0
        else:
            dx, dy = x1 or 0.0, y1 or 0.0
        try:
            return arcs.centre_from_radius(dx, dy, radius, cmd.code == "G2")
        except arcs.ArcError as exc:
            self.untranslatable(cmd, f"arc cannot be drawn: {exc}", key="arc-error")
            return None

    def linearize(self, cmd: Command, plane: int, delta: float | None, turns: int) -> None:
        st = self.state
        params = cmd.params
        a, b, oa, ob, helix = arcs.PLANES[plane]
        start = {axis: st.position.get(axis) for axis in (a, b, helix)}
        if start[helix] is None and (helix not in params or not st.absolute):
            start[helix] = 0.0  # no helix, or a relative one: the segments need no absolute start
        elif start[helix] is None:
            start[helix] = num(params.get(helix))  # the helix from an unknown height: reached on the first segment
            if start[helix] is not None:
                self.report(
                    TR_APPROX,
                    f"helical arc from an unknown {helix}: the segments go to {helix}{params[helix]} at once",
                    key="arc-helix-unknown",
                    cmd=cmd,
                    aspects=("path",),
                )
        if any(v is None for v in start.values()):
            if "R" in params:
                self.untranslatable(
                    cmd, "R-form arc from an unknown position: its centre cannot be computed", key="arc-unknown"
                )
            else:
                self.remove(
                    cmd,
                    TR_UNTRANSLATABLE,
                    "arc from an unknown position cannot be written as segments",
                    key="arc-unknown",
                )
            return
        end: dict[str, float] = {}
        for axis in (a, b, helix):
            v = num(params.get(axis))
            if v is None:
                end[axis] = start[axis]  # type: ignore[assignment]
            elif st.absolute:
                end[axis] = v
            else:
                end[axis] = start[axis] + v  # type: ignore[operator]
        clockwise = cmd.code == "G2"
        try:
            if "R" in params:
                radius = num(params["R"])
                if radius is None:
                    raise arcs.ArcError("R is not a number")
                offsets = arcs.centre_from_radius(end[a] - start[a], end[b] - start[b], radius, clockwise)  # type: ignore[operator]
            else:
                offsets = (num(params.get(oa)) or 0.0, num(params.get(ob)) or 0.0)
            unit = INCH if self.inch else 1.0  # the tolerance is in mm, the geometry in the source's unit
            points = arcs.segments(
                start,  # type: ignore[arg-type]
                end,
                offsets,
                clockwise,
                plane,
                turns,
                tolerance=arcs.CHORD_TOLERANCE / unit,
                max_segment=arcs.MAX_SEGMENT / unit,
            )
        except arcs.ArcError as exc:
            self.untranslatable(cmd, f"arc cannot be drawn: {exc}", key="arc-error")
            return
        scale = INCH if self.inch else 1.0
        ext = self.EXTRUDER
        extruding = delta is not None and delta > 0
        if extruding and self.evalues and not self.hy.m229_written:
            self.before_extrusion()
        e_words: list[str | None] = [None] * len(points)
        escale = scale if self.E_LINEAR else 1.0  # an angular extruder axis is not scaled by G20
        if ext in params:
            if extruding and self.evalues:
                n = len(points)
                if self.e_absolute():
                    e0 = (st.e_position if ext == "E" else st.position.get("A")) or 0.0
                    for k in range(1, n):
                        e_words[k - 1] = "E" + fmt((e0 + delta * k / n) * escale, 5)  # type: ignore[operator]
                    e_words[-1] = "E" + self.scaled_e(params[ext])
                else:
                    done = 0.0
                    for k in range(1, n + 1):
                        total = round(delta * k / n * escale, 5)  # type: ignore[operator]
                        e_words[k - 1] = "E" + fmt(total - done, 5)
                        done = total
            elif extruding:
                self.native_flow(cmd)
                e_words = ["E1"] * len(points)
            elif self.evalues and self.e_absolute() and delta:
                self.after(f"G92 E{self.scaled_e(params[ext])}", note="keeps Hyrel's E position")
        feed_word = None
        if "F" in params:
            f = num(params["F"])
            if f is not None:
                f_scale = INCH if self.feed_inches() else 1.0
                feed_word = "F" + fmt(f * f_scale, 2)
                self.hy.feed = f * f_scale
        else:
            feed = self.source_feed()
            if feed is not None and feed != self.hy.feed:
                feed_word = "F" + fmt(feed, 2)
                self.hy.feed = feed
        extra = self.move_extra(cmd, False)
        extra_words = extra[1] if extra is not None else ()
        if "E1" in extra_words:  # a firing laser move: every segment fires
            extra_words = tuple(w for w in extra_words if w != "E1")
            e_words = ["E1"] * len(points)
        texts = []
        previous = {axis: start[axis] * scale for axis in (a, b, helix)}  # type: ignore[operator]
        for k, point in enumerate(points):
            words = ["G1"]
            for axis in ("X", "Y", "Z"):
                if axis not in point:
                    continue
                value = point[axis] * scale
                if st.absolute:
                    if axis == helix and axis not in params:
                        continue
                    words.append(axis + fmt(value, 4))
                else:
                    rounded = round(value, 4)
                    step = rounded - round(previous[axis], 4)
                    previous[axis] = rounded
                    if axis == helix and axis not in params:
                        continue
                    words.append(axis + fmt(step, 4))
            if e_words[k]:
                words.append(e_words[k])  # type: ignore[arg-type]
            if k == 0:
                if feed_word:
                    words.append(feed_word)
                words.extend(extra_words)
            texts.append(" ".join(words))
        reason = "R-form arc" if "R" in params else (f"arc in the G{plane} plane" if plane != 17 else "arc")
        self.replace(cmd, texts[0], note=f"{reason} written as {len(texts)} G1 segments")
        if len(texts) > 1:
            self.after(*texts[1:], note=f"{reason} segment", first=True)
        if plane != 17 or "R" in params or turns:
            self.report(
                TR_NOTE,
                f"{reason} written as G1 segments (Hyrel G2/G3 draw XY arcs with I/J only)",
                key=("arc", plane, "R" in params),
                cmd=cmd,
            )
        elif extruding and self.evalues:
            self.report(
                TR_NOTE,
                "extruding arc written as G1 segments so its E amount counts "
                "(Hyrel computes arc flow natively even under M229 E1)",
                key="arc-evalues",
                cmd=cmd,
            )
