"""The toolpath of a job, per layer and per head, for the HTML page's viewer.

The file is read again, streaming, by the reader of meaning (``gclint.simulate``: the events the summary and
the diff read too), so positions follow the dialect's semantics (G90/G91, G92, units, Hyrel G28 homing only
the listed axes, the focused head from T commands, LinuxCNC's order of execution) and a working move is one
that prints, or on a CNC machine one that cuts.  Arcs are drawn as their chord.

Layers.  Where the slicer marks its layers (``;LAYER_CHANGE`` PrusaSlicer and OrcaSlicer, ``;LAYER:n`` Cura,
``; CHANGE_LAYER`` Bambu Studio, ``; layer n, Z = z`` Simplify3D, ``; BEGIN_LAYER_OBJECT z=`` KISSlicer), a layer
is what runs from one marker to the next, as the slicer counts them; what runs before the first marker (the
start G-code: priming, a purge line) is drawn with the first layer.  The reader does not read comments, so the
markers are found here, in the lines the reader is given (``_Marked``).  Without markers, a layer is a height
at which the job works (prints, or cuts), lowest first; a height with a handful of working moves far above
or below the others (priming at Z15, a wipe while parking) is no layer of its own: it is drawn with the layer
worked just after it (or, at the end of the job, just before it).

Memory and the page stay bounded on multi-million-line jobs: each head keeps, in each layer, at most
``cap`` points, sampled at a stride that doubles whenever that fills (every move is seen, one in ``stride`` is
kept), and all of them together at most ``budget`` points: when that fills, ``cap`` halves and the layers
over it are thinned; past ``MAX_LAYERS`` layers (or a floor of a few points per head and layer), neighbouring
layers are drawn as one.  A thinned stroke is a working stroke only where every move it stands for works, so
sampling never draws material across a travel.

``fit`` is the box of the bulk of the working moves (the part), not of every move: a purge line at the bed's
edge or a parking move does not shrink the part on the page.
"""

from __future__ import annotations

import math
from array import array
from bisect import bisect_right
from dataclasses import dataclass, field

from gclint import dialects
from gclint.simulate import simulator_for
from gclint.simulate.events import Layer as LayerMark
from gclint.simulate.events import Move, ToolChange
from gclint.syntax.source import Source, SourceError

MAX_MARKERS = 2000
# Heads drawn each on its own; the moves of any further head (a job may name a million tools) are drawn
# together as one more path, so that memory and the page stay bounded.
MAX_HEADS = 64
OTHER_HEADS = "other"
BUDGET = 200_000  # points kept in all (a page of about 2 MB at most)
LAYER_CAP = 16_384  # points kept per head and layer before that layer is thinned
MIN_CAP = 16  # below this, layers are drawn together rather than thinned further
MAX_LAYERS = 4096  # layers kept apart (the slider's steps); past this, neighbours are drawn as one
MAX_STROKES = 16_384  # strokes (a head in a layer) kept apart; past this too (64 heads in each of 4096 layers)
FIT_POINTS = 40_000  # points the box of the part is found from (a sample of a bigger job's)

# A height with fewer working moves than this share of the median height's, and further than ``ISOLATED`` mm (or
# ``ISOLATED_STEPS`` layer steps) from the heights the job works at, is priming or parking, not a layer.
STRAY_SHARE = 0.25
ISOLATED = 2.0
ISOLATED_STEPS = 5


class Stroke:
    """The sampled moves of one head in one layer: points, and whether the move that ends at each works.
    Point 0 is where the head was when it came into the layer (a jump: a travel, not a stroke)."""

    __slots__ = ("xs", "ys", "work", "stride", "_seen", "_all_work")

    def __init__(self) -> None:
        self.xs = array("d")
        self.ys = array("d")
        self.work = bytearray()
        self.stride = 1
        self._seen = 0
        self._all_work = True  # every move since the last kept point worked

    def __len__(self) -> int:
        return len(self.xs)

    def add(self, x: float, y: float, working: bool) -> int:
        """One more move; returns the number of points kept (0 or 1)."""
        self._all_work = self._all_work and working
        self._seen += 1
        if self._seen < self.stride:
            return 0
        self._seen = 0
        self.xs.append(x)
        self.ys.append(y)
        self.work.append(1 if self._all_work else 0)
        self._all_work = True
        return 1

    def jump(self, x: float, y: float) -> int:
        """Start again at (x, y) without a stroke (the head came back into this layer, or took over)."""
        self.xs.append(x)
        self.ys.append(y)
        self.work.append(0)
        self._seen = 0
        self._all_work = True
        return 1

    def halve(self) -> int:
        """Keep one point in two (and the last); returns the number of points dropped."""
        n = len(self.xs)
        if n < 3:
            return 0
        last = n - 1
        xs, ys, work = self.xs[::2], self.ys[::2], self.work
        # the stroke from kept point i-1 to kept point i works only where both moves it joins work
        even, odd = work[2::2], work[1::2][: (n - 1) // 2]
        joined = (int.from_bytes(even, "big") & int.from_bytes(odd, "big")).to_bytes(len(even), "big")
        kept = bytearray(work[:1]) + joined
        if last % 2:  # (an odd last index is not among the even ones: keep the end of the path)
            xs.append(self.xs[last])
            ys.append(self.ys[last])
            kept.append(work[last])
        self.xs, self.ys, self.work = xs, ys, kept
        self.stride *= 2
        return n - len(xs)

    def extend(self, other: Stroke) -> None:
        """``other``'s points after these (the first of them is a jump: a travel joins the two)."""
        skip = 0
        if len(self.xs) and len(other.xs) and not other.work[0]:
            # (a jump to where these end, as when the head went from this layer to that one: one point)
            skip = int(other.xs[0] == self.xs[-1] and other.ys[0] == self.ys[-1])
        self.xs.extend(other.xs[skip:])
        self.ys.extend(other.ys[skip:])
        self.work.extend(other.work[skip:])
        self.stride = max(self.stride, other.stride)
        self._seen, self._all_work = other._seen, other._all_work


@dataclass
class Layer:
    """What a job does in one layer: each head's strokes, and the heights it works at."""

    strokes: dict[str | None, Stroke] = field(default_factory=dict)
    working: int = 0  # working moves drawn in this layer
    z_low: float = math.inf  # the working moves' heights
    z_high: float = -math.inf
    first: int = 0  # the line of its first move (time order)

    def absorb(self, other: Layer, heights: bool = True) -> None:
        """``other``'s strokes after these (and, with ``heights``, its heights as this layer's too)."""
        for head, stroke in other.strokes.items():
            mine = self.strokes.get(head)
            if mine is None:
                self.strokes[head] = stroke
            else:
                mine.extend(stroke)
        self.first = min(self.first, other.first)
        if heights:
            self.working += other.working
            self.z_low = min(self.z_low, other.z_low)
            self.z_high = max(self.z_high, other.z_high)

    @property
    def points(self) -> int:
        return sum(len(s) for s in self.strokes.values())


@dataclass
class Head:
    key: str | None
    label: str
    moves: int = 0  # moves drawn (before sampling)
    working_moves: int = 0


@dataclass
class Marker:
    """A flagged line: where the tool is once the line has run, and the layer it runs in."""

    x: float
    y: float
    head: str | None
    line: int
    layer: int | None = None  # (while reading: the layer's key; once read: its index in ``Toolpath.layers``)


@dataclass
class Toolpath:
    heads: dict[str | None, Head] = field(default_factory=dict)
    layers: list[Layer] = field(default_factory=list)  # lowest (or first) first
    markers: list[Marker] = field(default_factory=list)
    lines: int = 0
    by_markers: bool = False  # the layers are the slicer's (its layer markers)
    # past MAX_LAYERS or MAX_STROKES: this many of the slicer's layers drawn as one, or (by heights) the heights
    # within this many µm
    merged: int = 1
    error: str | None = None

    @property
    def stride(self) -> int:
        """The most moves one kept point stands for (1: every move is drawn)."""
        return max((s.stride for layer in self.layers for s in layer.strokes.values()), default=1)

    @property
    def sampled(self) -> bool:
        return self.stride > 1

    @property
    def points(self) -> int:
        return sum(layer.points for layer in self.layers)

    def bounds(self) -> tuple[float, float, float, float] | None:
        """The box of every point drawn (travel and markers too)."""
        box = [math.inf, math.inf, -math.inf, -math.inf]
        for layer in self.layers:
            for s in layer.strokes.values():
                if len(s):
                    box[0], box[2] = min(box[0], min(s.xs)), max(box[2], max(s.xs))
                    box[1], box[3] = min(box[1], min(s.ys)), max(box[3], max(s.ys))
        for m in self.markers:
            box[0], box[2] = min(box[0], m.x), max(box[2], m.x)
            box[1], box[3] = min(box[1], m.y), max(box[3], m.y)
        if box[0] > box[2]:
            return None
        return box[0], box[1], box[2], box[3]

    def fit(self) -> tuple[float, float, float, float] | None:
        """The box of the bulk of the working moves: the part, without a purge line or a parking move far
        from it (``fit_box``); the box of everything when nothing works."""
        xs: list[float] = []
        ys: list[float] = []
        for layer in self.layers:
            for s in layer.strokes.values():
                work, sx, sy = s.work, s.xs, s.ys
                for i in range(1, len(work)):
                    if work[i]:
                        if i == 1 or not work[i - 1]:  # (where a stroke starts)
                            xs.append(sx[i - 1])
                            ys.append(sy[i - 1])
                        xs.append(sx[i])
                        ys.append(sy[i])
        if not xs:
            return self.bounds()
        if len(xs) > FIT_POINTS:  # (the bulk is the bulk in a sample too)
            step = -(-len(xs) // FIT_POINTS)
            xs, ys = xs[::step], ys[::step]
        return fit_box(xs, ys)


def fit_box(xs: list[float], ys: list[float]) -> tuple[float, float, float, float]:
    """The box of the bulk of these points: the middle 96% of them on each axis, grown to take in every point
    near it (a skirt, a brim, the part's own edges), again and again, but not what lies far off."""
    n = len(xs)
    sx, sy = sorted(xs), sorted(ys)
    if n < 50:
        return sx[0], sy[0], sx[-1], sy[-1]
    cut = n // 50
    box = [sx[cut], sy[cut], sx[n - 1 - cut], sy[n - 1 - cut]]
    for _ in range(8):
        margin = max(3.0, 0.25 * max(box[2] - box[0], box[3] - box[1]))
        grown = list(box)
        for x, y in zip(xs, ys, strict=True):
            if box[0] - margin <= x <= box[2] + margin and box[1] - margin <= y <= box[3] + margin:
                if x < grown[0]:
                    grown[0] = x
                elif x > grown[2]:
                    grown[2] = x
                if y < grown[1]:
                    grown[1] = y
                elif y > grown[3]:
                    grown[3] = y
        if grown == box:
            break
        box = grown
    return box[0], box[1], box[2], box[3]


class _Builder:
    """Layers and strokes as the moves come (see the module's docstring for the bounds)."""

    def __init__(self, toolpath: Toolpath, budget: int, cap: int) -> None:
        self.toolpath = toolpath
        self.layers: dict[int | None, Layer] = {}  # key -> layer; None: before the first layer
        self.budget = budget
        self.cap = cap
        self.points = 0
        self.strokes = 0  # strokes in all the layers
        self.generation = 0  # layers merged so far (a stroke found before may be another layer's now)
        self.scale = 1  # keys are a marker's count, or a height in µm, divided by this (merging neighbours)

    def layer(self, raw: int | None, line: int) -> Layer:
        """The layer of ``raw`` (a marker's count or a height in µm; None: before the first layer)."""
        key = None if raw is None else raw // self.scale
        layer = self.layers.get(key)
        if layer is None:
            layer = self.layers[key] = Layer(first=line)
            if len(self.layers) > MAX_LAYERS:
                self.merge_neighbours()
                layer = self.layers[None if raw is None else raw // self.scale]
        return layer

    def stroke(self, raw: int | None, head: str | None, line: int) -> tuple[Layer, Stroke]:
        """The layer of ``raw`` and the stroke of ``head`` in it."""
        layer = self.layer(raw, line)
        stroke = layer.strokes.get(head)
        if stroke is None and self.strokes >= MAX_STROKES:
            self.merge_neighbours()
            layer = self.layer(raw, line)
            stroke = layer.strokes.get(head)
        if stroke is None:
            stroke = layer.strokes[head] = Stroke()
            self.strokes += 1
        return layer, stroke

    def kept(self, stroke: Stroke, added: int) -> None:
        self.points += added
        if len(stroke.xs) > self.cap:
            self.points -= stroke.halve()
        if self.points > self.budget:
            self.rebalance()

    def rebalance(self) -> None:
        while self.points > self.budget * 3 // 4:
            if self.cap > MIN_CAP:
                self.cap //= 2
            elif len(self.layers) > 1:
                self.merge_neighbours()
            else:
                break
            for layer in self.layers.values():
                for stroke in layer.strokes.values():
                    while len(stroke) > self.cap:
                        dropped = stroke.halve()
                        if not dropped:
                            break
                        self.points -= dropped

    def merge_neighbours(self) -> None:
        """Neighbouring layers become one (their keys halved, as often as it takes to halve their number):
        fewer layers, each with more moves."""
        before = len(self.layers)
        self.generation += 1
        while True:
            self.scale *= 2
            merged: dict[int | None, Layer] = {}
            for key in sorted(self.layers, key=lambda k: (k is not None, k)):
                layer = self.layers[key]
                new = None if key is None else key // 2
                if new in merged:
                    merged[new].absorb(layer)
                else:
                    merged[new] = layer
            self.layers = merged
            for m in self.toolpath.markers:
                if m.layer is not None:
                    m.layer //= 2
            if len(merged) <= max(3, before // 2):  # (keys halved often enough are all 0 or -1)
                break
        self.toolpath.merged = self.scale
        self.strokes = sum(len(layer.strokes) for layer in self.layers.values())

    def prelude(self) -> None:
        """The first layer marker: what ran before it (by heights) is the start of the job."""
        if not self.layers:
            return
        keys = sorted(self.layers, key=lambda k: self.layers[k].first)
        start = self.layers[keys[0]]
        for key in keys[1:]:
            start.absorb(self.layers[key])
        self.layers = {None: start}
        self.strokes = len(start.strokes)
        for m in self.toolpath.markers:
            m.layer = None
        self.scale = 1
        self.generation += 1
        self.toolpath.merged = 1

    def finish(self, by_markers: bool) -> None:
        layers = self.layers
        keyed = {k: v for k, v in layers.items() if k is not None}
        if not by_markers and len(keyed) > 2:
            self._fold_strays(keyed)
        order = sorted(keyed)
        start = layers.get(None)
        markers = self.toolpath.markers
        if start is not None and order:
            # (the start of the job, before its first layer, is drawn with the layer it leads into)
            target = order[0] if by_markers else min(order, key=lambda k: keyed[k].first)
            layer = keyed[target]
            start.absorb(layer)
            start.working, start.z_low, start.z_high = layer.working, layer.z_low, layer.z_high
            keyed[target] = start
            for m in markers:
                if m.layer is None:
                    m.layer = target
        self.toolpath.layers = [keyed[k] for k in order] or ([start] if start is not None else [])
        for m in markers:
            # (a flagged line in a layer that draws nothing is shown in the layer below it)
            m.layer = max(0, bisect_right(order, m.layer) - 1) if order and m.layer is not None else 0

    def _fold_strays(self, keyed: dict) -> None:
        """Heights with a handful of working moves far from every height the job really works at (priming
        above the bed, a wipe while parking) are drawn with the layer worked next to them in time."""
        counts = sorted(layer.working for layer in keyed.values())
        few = STRAY_SHARE * counts[len(counts) // 2]
        order = sorted(keyed)
        kept = [keyed[k].working >= few for k in order]
        if all(kept) or not any(kept):
            return
        real = [keyed[k] for k, keep in zip(order, kept, strict=True) if keep]
        steps = sorted(b.z_low - a.z_high for a, b in zip(real, real[1:], strict=False))
        far = max(ISOLATED, ISOLATED_STEPS * steps[len(steps) // 2]) if steps else ISOLATED
        # a few moves near a real layer (the tip of a spire, above its base) are a layer of their own, and so
        # are a few more near those: upwards, then downwards
        for indices in (range(len(order)), range(len(order) - 1, -1, -1)):
            near: Layer | None = None
            for i in indices:
                layer = keyed[order[i]]
                if kept[i]:
                    near = layer
                elif near is not None and layer.working and _gap(layer, near.z_low, near.z_high) <= far:
                    kept[i] = True
                    near = layer
        by_time = sorted((k for k, keep in zip(order, kept, strict=True) if keep), key=lambda k: keyed[k].first)
        for key, keep in zip(order, kept, strict=True):
            if keep:
                continue
            layer = keyed.pop(key)
            later = [k for k in by_time if keyed[k].first > layer.first]
            target = later[0] if later else by_time[-1]
            keyed[target].absorb(layer, heights=False)
            for m in self.toolpath.markers:
                if m.layer == key:
                    m.layer = target


def _gap(layer: Layer, low: float, high: float) -> float:
    if layer.z_high < low:
        return low - layer.z_high
    if layer.z_low > high:
        return layer.z_low - high
    return 0.0


def read_toolpath(
    path: str,
    dialect_name: str | None,
    flagged: set[int] | frozenset[int] = frozenset(),
    budget: int = BUDGET,
    cap: int = LAYER_CAP,
) -> Toolpath:
    """Replay ``path`` and collect its XY moves per layer and head, plus the position of each flagged line
    (where the tool is once that line has run)."""
    toolpath = Toolpath()
    if path == "-":
        toolpath.error = "standard input cannot be read twice"
        return toolpath
    try:
        dialect = dialects.get(dialect_name) if dialect_name else dialects.DEFAULT
    except dialects.UnknownDialect:
        dialect = dialects.DEFAULT
    heads = toolpath.heads
    markers = toolpath.markers
    build = _Builder(toolpath, budget, max(cap, MIN_CAP))
    waiting = sorted(flagged)  # flagged lines not marked yet, in order
    waits = len(waiting)
    at = 0
    last_xy: tuple[float, float] | None = None
    reader = simulator_for(dialect)
    tool: str | None = None  # the working tool (its moves are drawn as its head's)
    at_layer: int | None = None  # where the job is: layer markers passed, or the height worked at (µm)
    by_markers = False
    # the last move drawn: its layer's key, its head, and the builder's generation then (layers merged since?)
    into_key: object = object()
    into_head: object = object()
    into_generation = -1
    stroke = Stroke()
    layer = Layer()

    def mark(up_to: int) -> None:  # (flagged lines up to ``up_to`` run with the tool where it is now)
        nonlocal at
        while at < waits and waiting[at] <= up_to:
            if last_xy is not None and len(markers) < MAX_MARKERS:
                where = None if at_layer is None else at_layer // build.scale
                markers.append(Marker(last_xy[0], last_xy[1], tool, waiting[at], where))
            at += 1

    marks: str | None = None  # the kind of layer mark the job counts its layers with (the first one seen)
    try:
        finite = math.isfinite
        for event in reader.events(Source.open(path)):
            line = event.line
            if type(event) is LayerMark:  # (the slicer's mark that a layer begins: the reader finds them)
                marks = marks or event.marks
                if event.marks == marks:
                    if not by_markers:
                        by_markers = True
                        build.prelude()
                        at_layer = 0
                    at_layer = (at_layer or 0) + 1  # (0 from the first mark on)
                continue
            if at < waits and waiting[at] < line:
                mark(line - 1)
            if type(event) is ToolChange:
                tool = event.tool
                continue
            if type(event) is not Move or not event.point:
                continue
            point = event.point
            x, y = point[0], point[1]
            if x is None or y is None or (event.arc is None and (x, y) == last_xy):
                continue  # (no move in XY: nothing to draw; a Z hop, a layer change, a prime in place)
            if not (finite(x) and finite(y)):
                continue
            working = event.working
            z = point[2]
            if z is not None and not finite(z):
                z = None
            if working and not by_markers and z is not None:
                at_layer = math.floor(z * 1000)
            head = event.tool
            info = heads.get(head)
            if info is None:
                if len(heads) >= MAX_HEADS:
                    head = OTHER_HEADS
                    info = heads.get(head)
                    if info is None:
                        label = f"other heads (beyond the first {MAX_HEADS}, drawn together)"
                        info = heads[head] = Head(head, label)
                else:
                    info = heads[head] = Head(head, reader.tool_title(head) if head else "the working tool")
            info.moves += 1
            where = None if at_layer is None else at_layer // build.scale
            if where != into_key or head != into_head or build.generation != into_generation:
                layer, stroke = build.stroke(at_layer, head, line)
                if last_xy is not None:
                    # the head comes into this layer (or takes over) where the last move ended: a travel
                    build.kept(stroke, stroke.jump(*last_xy))
                into_key, into_head, into_generation = where, head, build.generation
            if working:
                info.working_moves += 1
                layer.working += 1
                if z is not None:
                    if z < layer.z_low:
                        layer.z_low = z
                    if z > layer.z_high:
                        layer.z_high = z
            if stroke.add(x, y, working):
                build.points += 1
                if len(stroke.xs) > build.cap or build.points > build.budget:
                    build.kept(stroke, 0)
            last_xy = (x, y)
        mark(reader.line_count)
        toolpath.by_markers = by_markers
        build.finish(by_markers)
    except SourceError as exc:
        toolpath.error = str(exc)
    except (RecursionError, MemoryError):
        toolpath.error = f"{path}: too complex to plot"
    toolpath.lines = reader.line_count
    return toolpath
