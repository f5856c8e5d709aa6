"""Compare two simulations at their synchronisation points (a meaning diff, after sqlglot's semantic diff).

The source job and its translation are walked together, working move by working move.  A source move
is matched with the output moves that make it: usually one, several when an arc became segments (each
segment must stay on the source's arc, within the chord tolerance).  A move one side has and the other
has not is found by looking a few moves ahead on each side.  Lines the translator adds (header, footer,
re-homing) are not working moves, so they do not count; what they change shows in the state of the moves
that follow.

For each matched pair every aspect is compared (trace.ASPECTS): where the move ends, the path, what it
deposits, the feed, what happened since the previous working move (the pauses, in their order among the
spindle's changes; the total dwell; the unprimes and primes), and the state it runs in (head, set-point and
wait, fan, flow, layer height in native flow, beds, spindle, laser, aux, workspace, units, the head's
unprime and prime settings).  A state that differs over many moves is one ``Difference`` with a count (and
a trail of the values on the way).  Finally the end states are compared: what is still hot, blowing,
spinning or emitting, and whether the job ends.

A difference is *explained* when the translation reported a warning-level TR finding for it: a finding
whose aspects include the difference's, on a source line between the last move where the aspect agreed
and the move where it first differs (that move's own line included when commands follow the move there:
they run after it), and not before the source line that last set what differs (``Move.marks``: what
came before that line cannot have caused it); for the end state anywhere after the line that last set
the device that differs, about the end or about the kind of every device that differs.  A finding about
one source device (``tool:9``, ``fan:3``) explains only differences about it.

When the output compared is not the translator's own (an edited file, another tool's), its differences are
explained only where the translator's own output has the very same difference (``Explanations.reference``):
a finding explains what the translator did, not what was done to its output afterwards.
"""

from __future__ import annotations

import math
import re
import zlib
from bisect import bisect_right
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from gclint.simulate.trace import ASPECTS, LOOK_ASPECTS, NATIVE, PART_FAN, EndState, Move

_DEVICE_LABEL = re.compile(r"(tool|fan) (\d+)(?: \(no head\))?")
POSITION_TOLERANCE = 0.002  # mm: the translator writes 4 decimals; inches converted from 4 decimals
CHORD_TOLERANCE = 0.02  # mm: the largest distance allowed between a segment and the arc it replaces
FEED_TOLERANCE = 0.011  # mm/min (the translator writes 2 decimals)
FAN_TOLERANCE = 0.0025  # of full speed (less than one step of 255: 0.0039; more than rounding to one)
LOOKAHEAD = 8  # moves looked ahead on each side to tell a missing move from an extra one
MAX_SEGMENTS = 20000  # output moves one source move may become (an arc's segments)


@dataclass
class Difference:
    aspect: str
    source_line: int | None
    output_line: int | None
    source: str
    output: str
    count: int = 1
    explained_by: tuple[str, int] | None = None  # (TR code, source line)
    # the values on every move it lasts, as a checksum: two differences with the same start and count but
    # other values on the way are not the same (``Diff._match``)
    trail: int = 0

    def to_dict(self) -> dict:
        return {
            "aspect": self.aspect,
            "source_line": self.source_line,
            "output_line": self.output_line,
            "source": self.source,
            "output": self.output,
            "count": self.count,
            "explained_by": (
                {"code": self.explained_by[0], "line": self.explained_by[1]} if self.explained_by else None
            ),
        }


@dataclass
class Explanations:
    """Warning-level TR findings, by aspect: ``entries`` is a list of (code, aspects, sorted lines).

    A finding explains a difference only when it is about that quantity and that place:

    * about it: its aspects name the difference's aspect ("*": any).  A position finding may name its axes
      (``position:Z``: a G28 that does not home Z, a G53 move in Z); it explains only differences in them.
      A spindle finding about its speed only (``spindle:speed``: an assumed maximum rpm) explains a
      difference in speed, not one in whether the spindle runs.
    * at that place: it is on a source line after the last working move where the aspect agreed.  For a
      position, also not before the line that last set the differing axes outright (an absolute move,
      homing, G92: ``anchor``), since what came before that line cannot have moved them; only a finding
      about coordinate offsets that last (``offsets``: a G92 or workspace origin that is lost) reaches
      across it.
    """

    entries: list[tuple[str, frozenset[str], list[int]]] = field(default_factory=list)
    # the differences of the translator's own output, explained (None: the output compared is that output)
    reference: list[Difference] | None = None

    def find(
        self,
        aspect: str,
        lo: float,
        hi: int,
        axes: str = "",
        anchor: int = 0,
        devices: frozenset[str] = frozenset(),
        mark: int = 0,
    ) -> tuple[str, int] | None:
        """The first finding for ``aspect`` on a line in (lo, hi]; a position (``axes`` differ, set outright
        on line ``anchor``) and a spindle speed (``axes`` "speed") as the class says; ``devices``: the source
        devices the difference is about (``tool:9``, ``fan:3``), for findings about one device; ``mark``: the
        source line that last set what differs (a finding on it or after it only; a native-flow layer height
        comes from Z, so a lost offset reaches across it as for a position)."""
        best: tuple[str, int] | None = None
        for code, aspects, lines in self.entries:
            start = lo
            if mark and not (aspect == "layer" and "offsets" in aspects):
                start = max(lo, mark - 1)
            if aspect == "position":
                if "offsets" not in aspects:
                    if not ("*" in aspects or "position" in aspects or _names_axes(aspects, axes)):
                        continue
                    start = max(lo, anchor - 1)  # a finding on the anchoring line itself counts
            elif (
                aspect not in aspects
                and "*" not in aspects
                and not (axes and f"{aspect}:{axes}" in aspects)
                and not (aspect == "layer" and "e" in aspects)  # native flow computes the E from the layer
            ):
                continue
            i = bisect_right(lines, start)
            if i < len(lines) and lines[i] <= hi and (best is None or lines[i] < best[1]):
                best = (code, lines[i])
        if best is None and devices:
            best = self._devices(aspect, max(lo, mark - 1), hi, devices)
        return best

    def _devices(self, aspect: str, lo: float, hi: int, devices: frozenset[str]) -> tuple[str, int] | None:
        """A difference about source devices each of which a finding in (lo, hi] is about (``tool:9``,
        ``fan:3``): the first of those findings; None when one device has none."""
        if not all(aspect in _DEVICE_ASPECTS.get(d.split(":", 1)[0], ()) for d in devices):
            return None
        first: tuple[str, int] | None = None
        for device in devices:
            found: tuple[str, int] | None = None
            for code, aspects, lines in self.entries:
                if device not in aspects:
                    continue
                i = bisect_right(lines, lo)
                if i < len(lines) and lines[i] <= hi and (found is None or lines[i] < found[1]):
                    found = (code, lines[i])
            if found is None:
                return None
            if first is None or found[1] < first[1]:
                first = found
        return first


# What a finding about one source device (an aspect ``tool:<n>`` or ``fan:<n>``) may explain: a difference in
# these aspects that is about that device alone (the head a move is printed by; the fan that differs)
_DEVICE_ASPECTS = {"tool": frozenset({"head", "temp", "flow", "spindle", "end"}), "fan": frozenset({"aux", "end"})}


def _device(label) -> str | None:
    """The source device a Hyrel-terms label names when the printer has no address for it: ``tool 9 (no
    head)`` (trace.Mapping.head) -> ``tool:9``, ``fan 3`` (heat.aux_fans) -> ``fan:3``; None otherwise."""
    if not isinstance(label, str):
        return None
    m = _DEVICE_LABEL.fullmatch(label)
    return f"{m.group(1)}:{m.group(2)}" if m else None


def _names_axes(aspects: frozenset[str], axes: str) -> bool:
    """Whether a ``position:<axes>`` aspect covers every differing axis."""
    return bool(axes) and any(a.startswith("position:") and set(axes) <= set(a[9:]) for a in aspects)


class _Peek:
    """An iterator with a look-ahead buffer."""

    def __init__(self, items: Iterable[Move]) -> None:
        self.it = iter(items)
        self.buffer: deque[Move] = deque()
        self.done = False

    def get(self, i: int) -> Move | None:
        buffer = self.buffer
        while len(buffer) <= i and not self.done:
            try:
                buffer.append(next(self.it))
            except StopIteration:
                self.done = True
        return buffer[i] if i < len(buffer) else None

    def pop(self) -> Move:
        self.get(0)
        return self.buffer.popleft()


def _close(a: float | None, b: float | None, tol: float = POSITION_TOLERANCE) -> bool:
    if a is None or b is None:
        return a is b
    return abs(a - b) <= tol


def _xy_match(a: tuple, b: tuple) -> bool:
    return _close(a[0], b[0]) and _close(a[1], b[1])


def _plane_axes(plane: int) -> tuple[int, int]:
    return {17: (0, 1), 18: (2, 0), 19: (1, 2)}.get(plane, (0, 1))


def _arc_progress(point: tuple, move: Move, before: float) -> float | None:
    """How far round the source arc an output point is (radians from its start, in its direction), if it
    lies on the arc beyond ``before``; None if not (off the circle, backwards, or past the end)."""
    plane, (cu, cv), r, clockwise, a0, turn = move.arc
    u, v = _plane_axes(plane)
    pu, pv = point[u], point[v]
    if pu is None or pv is None or abs(math.hypot(pu - cu, pv - cv) - r) > CHORD_TOLERANCE + POSITION_TOLERANCE:
        return None
    angle = math.atan2(pv - cv, pu - cu)
    step = ((a0 - angle) if clockwise else (angle - a0)) % (2 * math.pi)
    laps = max(0.0, (before - step) // (2 * math.pi) + 1) if step < before - 1e-6 else 0.0
    progress = step + 2 * math.pi * laps
    if progress < before - 1e-6 or progress > turn + 1e-6:
        return None
    return progress


def _on_path(point: tuple, move: Move) -> bool:
    """Whether an output point lies on the source move's path (an intermediate segment end)."""
    if move.arc is not None:
        return _arc_progress(point, move, 0.0) is not None
    start, end = move.start, move.end
    if any(start[i] is None or end[i] is None or point[i] is None for i in (0, 1)):
        return False
    return _distance_to_segment(point, start, end) <= POSITION_TOLERANCE


def _distance_to_segment(p: tuple, a: tuple, b: tuple) -> float:
    ax, ay, bx, by, px, py = a[0], a[1], b[0], b[1], p[0], p[1]
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / length2))
    return math.hypot(px - (ax + t * dx), py - (ay + t * dy))


def align(source: Iterable[Move], output: Iterable[Move]) -> Iterator[tuple[Move | None, list[Move], int | None]]:
    """Triples (source move, the output moves that make it, None); (move, [], None) for a source move the
    output has not; (None, [move], line) for an output move the source has not, with the line of the next
    source move (None at the end)."""
    src, out = _Peek(source), _Peek(output)
    while True:
        s = src.get(0)
        if s is None:
            while out.get(0) is not None:
                yield None, [out.pop()], None
            return
        if out.get(0) is None:
            yield src.pop(), [], None
            continue
        run = _run(s, out)
        if run:
            src.pop()
            yield s, run, None
            continue
        o = out.get(0)
        assert o is not None
        missing = _ahead(src, o.end)  # is the output move a later source move? the ones before it are missing
        if missing:
            for _ in range(missing):
                yield src.pop(), [], None
            continue
        extra = _ahead(out, s.end)  # is the source move a later output move? the ones before it are extra
        if extra:
            for _ in range(extra):
                yield None, [out.pop()], s.line
            continue
        yield src.pop(), [out.pop()], None  # the same move, ending elsewhere


def _ahead(moves: _Peek, end: tuple) -> int:
    """How many moves ahead (1 to LOOKAHEAD) one ends at ``end``'s X Y; 0 if none does."""
    for i in range(1, LOOKAHEAD + 1):
        later = moves.get(i)
        if later is None:
            return 0
        if _xy_match(later.end, end):
            return i
    return 0


def _run(s: Move, out: _Peek) -> list[Move] | None:
    """The output moves that make source move ``s``: intermediate ends on its path (going forward round an
    arc), the last at its end."""
    k = 0
    limit = MAX_SEGMENTS if s.arc is not None else 64
    progress = 0.0
    while k < limit:
        o = out.get(k)
        if o is None:
            return None
        if _xy_match(o.end, s.end) and (s.arc is None or k == 0 or _arc_done(o.end, s, progress)):
            return [out.pop() for _ in range(k + 1)]
        if _xy_match(o.end, s.start) and (s.arc is None or k == 0):
            # a move that stays at the start is not a piece of this one (an arc with turns passes its start
            # again on each lap: there ``_arc_progress`` decides)
            return None
        if s.arc is not None:
            ahead = _arc_progress(o.end, s, progress)
            if ahead is None:
                return None
            progress = ahead
        elif not _on_path(o.end, s):
            return None
        k += 1
    return None


def _arc_done(point: tuple, move: Move, progress: float) -> bool:
    """Whether an output point at the arc's end point closes it (and is not the end of an earlier lap)."""
    turn = move.arc[5]
    return progress > turn - 2 * math.pi + 1e-6 or turn <= 2 * math.pi + 1e-6


# -- describing values ------------------------------------------------------------------------------------


def _num(v: float | None, places: int = 4) -> str:
    if v is None:
        return "unknown"
    text = f"{v:.{places}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _position(end: tuple, axes: Iterable[int], frames: tuple | None = None) -> str:
    """``X1 Z2``; with ``frames``, each coordinate's workspace: ``Z-2 (machine coordinates)``, ``Z-2 (G55)``."""
    parts = []
    for i in axes:
        text = f"{'XYZAB'[i]}{_num(end[i])}"
        if frames is not None:
            text += f" ({frames[i] or 'machine coordinates'})"
        parts.append(text)
    return " ".join(parts)


def _e(value) -> str:
    if value is None:
        return "nothing"
    if value == NATIVE:
        return "native flow (computed by Hyrel)"
    return f"E {_num(value, 5)}"


def _head(value) -> str:
    if value is None:
        return "none"
    return f"T{value}" if isinstance(value, int) else str(value)


def _temp(value: tuple) -> str:
    target, ready, heated = value
    if target is None:
        return "no set-point"
    if ready:
        return f"{_num(target, 1)} °C (waited for)"
    before = f"at least {_num(heated, 1)} °C" if heated is not None else "never heated before"
    return f"{_num(target, 1)} °C (not waited for; {before})"


def _beds(value: tuple) -> str:
    if not value:
        return "none"
    return ", ".join(f"T{a} {_num(t, 1)} °C ({'waited for' if w else 'not waited for'})" for a, t, w in value)


def _spindle(value) -> str:
    if value is None:
        return "off"
    direction, pct = value[:2]
    if pct is None and len(value) > 2:
        return f"{direction} {_num(value[2], 1)} rpm"
    return f"{direction} {_num(pct, 1) + ' %' if pct is not None else '(speed unknown)'}"


def _aux(value: tuple) -> str:
    return (
        ", ".join(
            f"{name} {_num(v * 100, 1)} %" if v <= 1.0 and "fan" in name else f"{name} {_num(v, 1)}"
            for name, v in value
        )
        or "none"
    )


def _layer(value) -> str:
    if value is None:
        return "E values (no layer height)"
    width, heights = value
    height = " or ".join(_num(h) for h in heights) if heights else "unknown"
    return f"layer height {height}" + (f", width {_num(width)}" if width is not None else "")


def _prime(value) -> str:
    if value is None:
        return "the head's own unprime/prime"
    unprime, prime = value

    def settings(v) -> str:
        return (
            "unset" if v is None else " ".join(f"{k}{_num(x)}" for k, x in zip("SEP", v, strict=True) if x is not None)
        )

    return f"unprime {settings(unprime)}, prime {settings(prime)}"


def _primes(events: tuple) -> str:
    if not events:
        return "no unprime or prime"
    return ", ".join(f"{kind} {_head(head)}" for kind, head in events)


_DESCRIBE: dict[str, Callable[[Any], str]] = {
    "head": _head,
    "temp": _temp,
    "fan": lambda v: f"{_num(v * 100, 1)} %",
    "flow": lambda v: _num(v, 4),
    "beds": _beds,
    "spindle": _spindle,
    "laser": lambda v: "off" if v is None else f"{_num(v, 1)} %",
    "aux": _aux,
    "wcs": lambda v: v or "no fixture offsets",
    "units": str,
    "layer": _layer,
    "prime": _prime,
}


def _same(aspect: str, a, b) -> bool:
    if aspect == "fan":
        return abs(a - b) <= FAN_TOLERANCE
    if aspect == "flow":
        return abs(a - b) <= 1e-4
    if aspect == "temp":
        # not waited for at the set-point: how hot the nozzle was waited to before matters (a head never
        # heated prints cold where the source's nozzle was hot)
        return a[1] == b[1] and _close(a[0], b[0], 1e-6) and (a[1] or _close(a[2], b[2], 1e-6))
    if aspect == "spindle":
        if a is None or b is None:
            return a is b
        return a[0] == b[0] and _close(a[1], b[1], 0.11)
    if aspect == "laser":
        return _close(a, b, 0.11)
    if aspect == "aux":
        return len(a) == len(b) and all(x[0] == y[0] and abs(x[1] - y[1]) <= 0.5 for x, y in zip(a, b, strict=True))
    if aspect == "layer":
        return _same_layer(a, b)
    return a == b


def _same_layer(a, b) -> bool:
    """Native flow's bead: the same width, and a layer height both sides allow (where the source knows none:
    any; where the output sets none, the head's own, which is not the source's)."""
    if a is None or b is None:
        return a is b
    (wa, ha), (wb, hb) = a, b
    if not _close(wa, wb, 1e-4):
        return False
    return not ha or any(abs(x - y) <= 1e-4 for x in ha for y in hb)


# -- the diff -----------------------------------------------------------------------------------------------


class Diff:
    """Walks two simulations and gathers the differences.  ``native``: the translation asked for native flow
    (an E amount becomes Hyrel's own flow computation, compared through the layer height instead)."""

    def __init__(self, explanations: Explanations | None = None, *, native: bool = False) -> None:
        self.explanations = explanations
        # explained by the window of findings (below), or by the translator's own differences (``reference``)
        self.windows = explanations is not None and explanations.reference is None
        self.native = native
        self.differences: list[Difference] = []
        self.open: dict[str, Difference] = {}
        self.last_ok: dict[str, int] = {}
        self.last_all_ok: float = 0
        self.last_line: float = 0  # the last matched source move
        self.pairs = 0  # matched moves
        self.spindle_scale: tuple[float, float] | None = None  # (percent / rpm, rpm) of the first pair compared

    def run(self, source: Iterable[Move], output: Iterable[Move]) -> None:
        for s, run, next_line in align(source, output):
            if s is None:
                o = run[0]
                where = f"a working move to {_position(o.end, (0, 1, 2))}"
                self.differ("moves", next_line, o.line, "nothing", where, hi=next_line if next_line else 1 << 62)
                continue
            if not run:
                self.differ("moves", s.line, None, f"a working move to {_position(s.end, (0, 1, 2))}", "nothing")
                continue
            self.pairs += 1
            self.compare(s, run)

    def compare(self, s: Move, run: list[Move]) -> None:
        o = run[-1]
        first = run[0]
        bad: list[str] = []
        # where it ends
        axes = [
            i
            for i in range(5)
            if not _close(s.end[i], o.end[i]) or (s.frames[i] != o.frames[i] and s.end[i] is not None)
        ]
        if axes:
            bad.append("position")
            frames = any(s.frames[i] != o.frames[i] for i in axes)
            self.differ(
                "position",
                s.line,
                o.line,
                _position(s.end, axes, s.frames if frames else None),
                _position(o.end, axes, o.frames if frames else None),
                axes="".join("XYZAB"[i] for i in axes),
                anchor=max(s.anchors[i] for i in axes),
            )
        # the path
        deviation = _deviation(s, run)
        if deviation is not None:
            bad.append("path")
            self.differ(
                "path",
                s.line,
                first.line,
                "the source's " + ("arc" if s.arc else "line"),
                f"deviates {_num(deviation, 3)} mm",
            )
        # what it deposits
        e_out = _sum_e(run)
        if not _same_e(s.e, e_out, len(run)) and not (self.native and e_out == NATIVE and _deposits(s.e)):
            bad.append("e")
            self.differ("e", s.line, first.line, _e(s.e), _e(e_out))
        # feed
        for m in run:
            if not _close(s.feed, m.feed, FEED_TOLERANCE):
                bad.append("feed")
                # in inverse time a feed that agreed by chance (a move of unit length) does not clear the mode:
                # the finding on the G93 line explains it still
                self.differ("feed", s.line, m.line, _feed(s.feed), _feed(m.feed), reach=s.feed_mode)
                break
        # pauses, dwells, unprimes and primes since the previous working move (and those of the output moves
        # of this one)
        pauses = sum(m.pauses for m in run)
        trail = first.trail if len(run) == 1 else tuple(t for m in run for t in m.trail)
        if s.pauses != pauses or (pauses and s.trail != trail):
            bad.append("pause")
            self.differ("pause", s.line, first.line, _pauses(s.pauses, s.trail), _pauses(pauses, trail))
        dwell = sum(m.dwell for m in run)
        if not _same_dwell(s.dwell, dwell):
            bad.append("dwell")
            self.differ("dwell", s.line, first.line, _dwell(s.dwell), _dwell(dwell))
        primes = first.primes if len(run) == 1 else tuple(p for m in run for p in m.primes)
        if s.primes != primes:
            bad.append("prime")
            self.differ("prime", s.line, first.line, _primes(s.primes), _primes(primes), event=True)
        # the state it runs in
        a, b = s.look, first.look
        skipped: tuple[str, ...] = ()  # aspects that do not matter on this move (neither agree nor differ)
        if s.e is None and first.e is None:
            skipped = ("laser", "layer")  # the power matters while the laser fires, the layer while printing
        elif e_out != NATIVE and s.e != NATIVE:
            skipped = ("layer",)  # the layer height matters where Hyrel computes the flow
        if a != b:
            for aspect in LOOK_ASPECTS:
                if aspect in skipped:
                    continue
                va, vb = getattr(a, aspect), getattr(b, aspect)
                if aspect == "spindle":
                    same = self._same_spindle(va, vb)
                else:
                    same = _same(aspect, va, vb)
                if not same:
                    bad.append(aspect)
                    describe = _DESCRIBE[aspect]
                    # a speed that differs in proportion (no maximum known) is no matter of the maximum assumed
                    detail = "speed" if aspect == "spindle" and va and vb and va[0] == vb[0] and len(va) < 3 else ""
                    self.differ(
                        aspect,
                        s.line,
                        first.line,
                        describe(va),
                        describe(vb),
                        axes=detail,
                        devices=_devices(aspect, a, b),
                        mark=_mark(s.marks, aspect, va, vb),
                    )
        # a finding on the move's own line may be about a command after the move there (it runs later)
        ok_line = s.line - 0.5 if s.tail else s.line
        self.last_line = ok_line
        if not bad:
            if self.open:
                for aspect in list(self.open):
                    if aspect not in skipped:
                        self.close(aspect)
            if not (self.open and skipped):
                self.last_all_ok = ok_line
            else:
                for aspect in ASPECTS:
                    if aspect not in self.open and aspect != "moves":
                        self.last_ok[aspect] = ok_line
            return
        # a pair that ends in different places may be two different moves (a move lost before it): what agrees
        # there says little, so the findings before it still explain what differs next
        paired = "position" not in bad
        for aspect in list(self.open):
            if aspect not in bad and aspect not in skipped:
                self.close(aspect)
                if paired:
                    self.last_ok[aspect] = ok_line
        if paired:
            for aspect in ASPECTS:
                if aspect not in bad and aspect != "moves" and aspect not in skipped:
                    self.last_ok[aspect] = ok_line

    def _same_spindle(self, a, b) -> bool:
        """The spindle's direction and speed.  Where the source gives rpm and no maximum is known (no
        spindle-max-rpm), the speeds are compared relatively: the first pair sets the scale, and every later
        speed must keep it (a halved speed, a speed left unchanged where the source's changed)."""
        if a is None or b is None:
            return a is b
        if a[0] != b[0]:
            return False
        if len(a) < 3 or a[1] is not None or b[1] is None:
            return _close(a[1], b[1], 0.11)
        rpm, pct = a[2], b[1]
        if rpm <= 0:
            return False
        if self.spindle_scale is None:
            self.spindle_scale = (pct / rpm, rpm)
            return True
        scale, first = self.spindle_scale
        # the percent is written to 0.1: the scale carries that rounding, in proportion to the speed
        return abs(pct - rpm * scale) <= 0.11 + 0.06 * rpm / first

    def differ(
        self,
        aspect: str,
        source_line,
        output_line,
        source: str,
        output: str,
        hi: int | None = None,
        axes: str = "",
        anchor: int = 0,
        devices: frozenset[str] = frozenset(),
        reach: int = 0,
        event: bool = False,
        mark: int = 0,
    ) -> None:
        """A difference on this pair; one going on since an earlier pair only counts.  ``anchor``: the line that
        set the differing axes outright; ``mark``: the source line that last set what differs in a state (a
        finding before it cannot explain it); ``event``: the difference is in what happened since the previous
        working move (unprimes and primes), not a state that lasts."""
        current = self.open.get(aspect)
        if current is not None and not event:
            current.count += 1
            current.trail = zlib.crc32(f"{source}\0{output}".encode("utf-8", "surrogateescape"), current.trail)
            return
        diff = Difference(aspect, source_line, output_line, source, output)
        if self.windows:
            lo = max(self.last_all_ok, self.last_ok.get(aspect, 0))
            if reach:
                lo = min(lo, reach - 1)
            top = hi if hi is not None else (source_line if source_line is not None else 1 << 62)
            diff.explained_by = self.explanations.find(  # type: ignore[union-attr]
                aspect, lo, top, axes, anchor if aspect == "position" else 0, devices, mark
            )
        self.open[aspect] = diff
        self.differences.append(diff)

    def close(self, aspect: str) -> None:
        self.open.pop(aspect, None)

    def finish(self, source: EndState, output: EndState) -> None:
        for aspect in list(self.open):
            self.close(aspect)
        # pauses, dwells, unprimes and primes after the last working move
        trailing: tuple[tuple[str, Any, Any, Callable[[Any, Any], bool], Callable[[Any], str]], ...] = (
            ("pause", (source.pauses, source.trail), (output.pauses, output.trail), _same_pauses, _pause_trail),
            ("dwell", source.dwell, output.dwell, _same_dwell, _dwell),
            ("prime", source.primes, output.primes, lambda x, y: x == y, _primes),
        )
        for aspect, a, b, same, describe in trailing:
            if same(a, b):
                continue
            diff = Difference(aspect, source.line or None, output.line or None, describe(a), describe(b))
            if self.windows:
                diff.explained_by = self.explanations.find(aspect, self.last_line, 1 << 62)  # type: ignore[union-attr]
            self.differences.append(diff)
        ends: tuple[tuple[str, dict, dict], ...] = (
            ("program", {"end": "ended"} if source.ended else {}, {"end": "ended"} if output.ended else {}),
            ("heaters", source.heaters, output.heaters),
            ("fans", source.fans, _fold_part_fan(source.fans, output.fans)),
            ("spindles", source.spindles, output.spindles),
            ("emitters", {k: "on" for k in source.emitters}, {k: "on" for k in output.emitters}),
            ("aux", source.aux, output.aux),
        )
        for name, end_a, end_b in ends:
            if _same_end(end_a, end_b):
                continue
            percent = name == "fans"
            if name == "program":
                text_a, text_b = ("an end of program (M30)" if x else "no end of program" for x in (end_a, end_b))
            else:
                text_a, text_b = f"{name}: {_end(end_a, percent)}", f"{name}: {_end(end_b, percent)}"
            diff = Difference("end", source.line or None, output.line or None, text_a, text_b)
            if self.windows:
                diff.explained_by = self._explain_end(name, end_a, end_b, source.marks)
            self.differences.append(diff)
        if self.explanations is not None and self.explanations.reference is not None:
            self._match(self.explanations.reference)

    def _match(self, reference: list[Difference]) -> None:
        """Explain each difference by the same difference of the translator's own output (its aspect, where it
        starts in the source, both values, how many moves it lasts), with that one's explanation."""
        by_key: dict[tuple, list[Difference]] = {}
        for d in reference:
            by_key.setdefault(_key(d), []).append(d)
        for d in self.differences:
            same = by_key.get(_key(d))
            d.explained_by = same.pop(0).explained_by if same else None

    def _explain_end(self, name: str, a: dict, b: dict, marks: dict) -> tuple[str, int] | None:
        """A finding for an end-state difference: about the end, or about the kind of every device that
        differs (a nozzle's heater: temp; a bed: beds; a head's fan: fan; another fan: aux), or about those
        very devices (``tool:9``, ``fan:3``), on or after the source line that last set one of them."""
        assert self.explanations is not None
        if name == "program":
            return None  # every source job ends; nothing the translator reports drops Hyrel's end of program
        keys = [k for k in set(a) | set(b) if k not in a or k not in b or not _same_end({k: a[k]}, {k: b[k]})]
        kinds = {_end_kind(name, k) for k in keys}
        devices = {_device(k) for k in keys}
        set_at = [marks[f"{name}:{k}"] for k in keys if f"{name}:{k}" in marks]
        lo = min(set_at) - 1 if set_at and len(set_at) == len([k for k in keys if k in a]) else 0
        found = self.explanations.find("end", lo, 1 << 62)
        if found is None and len(kinds) == 1:
            found = self.explanations.find(kinds.pop(), lo, 1 << 62)
        if found is None and None not in devices:
            found = self.explanations.find("end", lo, 1 << 62, devices=frozenset(devices))  # type: ignore[arg-type]
        return found


def _key(d: Difference) -> tuple:
    return (d.aspect, d.source_line, d.source, d.output, d.count, d.trail)


def _deposits(e) -> bool:
    return e == NATIVE or (e is not None and e > 1e-9)


def _mark(marks: dict, aspect: str, a, b) -> int:
    """The source line that last set what differs in a look aspect (0: not known); for beds and aux, the
    earliest of the devices that differ."""
    if not marks:
        return 0
    if aspect in ("beds", "aux"):
        x = {item[0]: item[1:] for item in a or ()}
        y = {item[0]: item[1:] for item in b or ()}
        lines = [marks.get(f"{aspect}:{k}", 0) for k in set(x) | set(y) if x.get(k) != y.get(k)]
        return min(lines) if lines else marks.get(aspect, 0)
    return marks.get(aspect, 0)


def _end_kind(name: str, key) -> str:
    """The aspect an end-state device belongs to."""
    if name == "heaters":
        return "beds" if isinstance(key, int) and key >= 20 else "temp"
    if name == "fans":  # the part fan and heads' fans (a tool with no head included); other fans are aux
        head = key == PART_FAN or (isinstance(key, int) and key < 20) or (_device(key) or "").startswith("tool:")
        return "fan" if head else "aux"
    return _END_ASPECT[name][0]


def _devices(aspect: str, a, b) -> frozenset[str]:
    """The source devices a look difference is about: the head label of a tool with no head (``head``,
    ``temp``, ``flow``); the fans that differ (``aux``)."""
    if aspect in ("head", "temp", "flow", "spindle"):
        found = {_device(a.head)} - {None}
        return frozenset(found)  # type: ignore[arg-type]
    if aspect == "aux":
        x, y = dict(a.aux), dict(b.aux)
        keys = [k for k in set(x) | set(y) if k not in x or k not in y or abs(x[k] - y[k]) > 0.5]
        found = {_device(k) for k in keys}
        return frozenset() if None in found else frozenset(found)  # type: ignore[arg-type]
    return frozenset()


_END_ASPECT = {
    "heaters": ("temp", "beds"),
    "fans": ("fan", "aux"),
    "spindles": ("spindle",),
    "emitters": ("laser",),
    "aux": ("aux",),
}


def _fold_part_fan(source: dict, output: dict) -> dict:
    """The output's end fans with its head fans read as the source's one part fan (Marlin's fan 0 is one fan;
    Hyrel's fans are per head, and the translation moves it to the head that prints): the head fans the
    source has no key for, when they all run at one speed."""
    if PART_FAN not in source or PART_FAN in output:
        return output
    heads = [k for k in output if isinstance(k, int) and k < 20 and k not in source]
    values = [output[k] for k in heads]
    if not heads or max(values) - min(values) > FAN_TOLERANCE:
        return output
    folded = {k: v for k, v in output.items() if k not in heads}
    folded[PART_FAN] = values[0]
    return folded


def _same_end(a: dict, b: dict) -> bool:
    if set(a) != set(b):
        return False
    for k, v in a.items():
        w = b[k]
        if isinstance(v, float) and isinstance(w, float | int):
            if abs(v - w) > 0.006 and abs(v - w) > 1e-6 * abs(v):
                return False
        elif v != w:
            return False
    return True


def _end(d: dict, percent: bool = False) -> str:
    if not d:
        return "all off"
    parts = []
    for k, v in sorted(d.items(), key=lambda kv: str(kv[0])):
        key = f"T{k}" if isinstance(k, int) else str(k)
        if percent and isinstance(v, float | int):
            parts.append(f"{key} {_num(v * 100, 1)} %")
        else:
            parts.append(f"{key} {_num(v, 3) if isinstance(v, float) else v}")
    return ", ".join(parts)


def _pauses(n: int, trail: tuple = ()) -> str:
    text = "no pause" if not n else f"{n} pause{'s' if n != 1 else ''}"
    return f"{text} ({', '.join(trail)})" if trail and any(t != "pause" for t in trail) else text


def _same_pauses(a: tuple, b: tuple) -> bool:
    return a[0] == b[0] and (not a[0] or a[1] == b[1])


def _pause_trail(value: tuple) -> str:
    return _pauses(*value)


def _dwell(seconds: float) -> str:
    return "no dwell" if not seconds else f"dwell {_num(seconds, 3)} s"


def _same_dwell(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-3 + 1e-6 * abs(a)


def _feed(v: float | None) -> str:
    return "unknown" if v is None else f"F{_num(v, 2)}"


def _sum_e(run: list[Move]):
    total = None
    for m in run:
        if m.e == NATIVE:
            return NATIVE
        if m.e is not None:
            total = (total or 0.0) + m.e
    return total


def _same_e(a, b, segments: int) -> bool:
    if a is None or b is None or a == NATIVE or b == NATIVE:
        return a == b
    return abs(a - b) <= 2e-5 * segments + 1e-6 * abs(a) + 1e-9


def _deviation(s: Move, run: list[Move]) -> float | None:
    """How far the output's way from the source's start to its end strays from the source's path, when
    more than the tolerance allows (None: within it)."""
    if s.arc is not None:
        plane, (cu, cv), r, clockwise = s.arc[:4]
        u, v = _plane_axes(plane)
        if len(run) == 1 and run[0].arc is not None:
            _, (ou, ov), orad, ocw = run[0].arc[:4]
            if _close(ou, cu) and _close(ov, cv) and ocw == clockwise:
                return None
            return max(math.hypot(ou - cu, ov - cv), abs(orad - r))
        worst = 0.0
        previous = s.start
        for m in run:
            a, b = previous, m.end
            previous = b
            if a[u] is None or a[v] is None or b[u] is None or b[v] is None:
                continue
            radial = abs(math.hypot(b[u] - cu, b[v] - cv) - r)
            chord = math.hypot(b[u] - a[u], b[v] - a[v])
            sagitta = r - math.sqrt(max(r * r - chord * chord / 4, 0.0)) if chord < 2 * r else r
            worst = max(worst, radial, sagitta)
        return worst if worst > CHORD_TOLERANCE + POSITION_TOLERANCE else None
    if len(run) == 1:
        return None
    worst = 0.0
    for m in run[:-1]:
        if m.end[0] is None or m.end[1] is None or s.start[0] is None or s.start[1] is None:
            continue
        worst = max(worst, _distance_to_segment(m.end, s.start, s.end))
    return worst if worst > POSITION_TOLERANCE else None
