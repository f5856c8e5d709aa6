"""The XY toolpath of a job, per head, for the HTML report's plot.

The file is read again, streaming, by the reader of meaning (``gclint.simulate``: the events the summary and
the diff read too), so positions follow the dialect's semantics (G90/G91, G92, units, Hyrel G28 homing only
the listed axes, the focused head from T commands, LinuxCNC's order of execution) and a working move is one
that prints, or on a CNC machine one that cuts.  Memory stays bounded on multi-million-line jobs: each head keeps at most
``2 * budget`` points, sampled at a stride that doubles whenever the budget fills (every move is seen,
one in ``stride`` is kept).  Arcs are drawn as their chord.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint import dialects
from gclint.simulate import simulator_for
from gclint.simulate.events import Move, ToolChange
from gclint.syntax.source import Source, SourceError

MAX_MARKERS = 2000
# Heads drawn each on its own; the moves of any further head (a job may name a million tools) are drawn
# together as one more path, so that memory and the page stay bounded.
MAX_HEADS = 64
OTHER_HEADS = "other"


@dataclass
class HeadPath:
    """The sampled moves of one head: ``(x, y, working)``; ``working`` is the move that ends there."""

    key: str | None
    label: str
    points: list[tuple[float, float, bool]] = field(default_factory=list)
    moves: int = 0  # moves seen (before sampling)
    working_moves: int = 0
    stride: int = 1
    _seen: int = 0
    _pending_work: bool = False

    def add(self, x: float, y: float, working: bool, budget: int) -> None:
        self.moves += 1
        if working:
            self.working_moves += 1
        self._seen += 1
        if self._seen < self.stride:
            # A skipped move still counts: if it worked, the kept point after it draws a working stroke.
            if working and self.points:
                self._pending_work = True
            return
        self._seen = 0
        working = working or self._pending_work
        self._pending_work = False
        self.points.append((x, y, working))
        if len(self.points) >= 2 * budget:
            self.points = self.points[::2]
            self.stride *= 2

    def jump(self, x: float, y: float) -> None:
        """Start a stroke at (x, y) without counting a move (the head took over from another one)."""
        self.points.append((x, y, False))
        self._pending_work = False


@dataclass
class Marker:
    x: float
    y: float
    head: str | None
    line: int


@dataclass
class Toolpath:
    heads: dict[str | None, HeadPath] = field(default_factory=dict)
    markers: list[Marker] = field(default_factory=list)
    lines: int = 0
    error: str | None = None

    @property
    def sampled(self) -> bool:
        return any(h.stride > 1 for h in self.heads.values())

    def bounds(self) -> tuple[float, float, float, float] | None:
        xs = [p[0] for h in self.heads.values() for p in h.points] + [m.x for m in self.markers]
        ys = [p[1] for h in self.heads.values() for p in h.points] + [m.y for m in self.markers]
        if not xs:
            return None
        return min(xs), min(ys), max(xs), max(ys)


def read_toolpath(
    path: str, dialect_name: str | None, flagged: set[int] | frozenset[int] = frozenset(), budget: int = 6000
) -> Toolpath:
    """Replay ``path`` and collect its XY moves per head, plus the position of each flagged line (where the
    tool is once that line has run)."""
    toolpath = Toolpath()
    if path == "-":
        toolpath.error = "standard input cannot be read twice: no plot"
        return toolpath
    try:
        dialect = dialects.get(dialect_name) if dialect_name else dialects.DEFAULT
    except dialects.UnknownDialect:
        dialect = dialects.DEFAULT
    heads = toolpath.heads
    markers = toolpath.markers
    waiting = sorted(flagged)  # flagged lines not marked yet, in order
    at = 0
    last_xy: tuple[float, float] | None = None
    last_head: object = object()
    reader = simulator_for(dialect)

    tool: str | None = None  # the working tool (its moves are drawn as its head's)

    def mark(up_to: int) -> None:  # (flagged lines up to ``up_to`` run with the tool where it is now)
        nonlocal at
        while at < len(waiting) and waiting[at] <= up_to:
            if last_xy is not None and len(markers) < MAX_MARKERS:
                markers.append(Marker(last_xy[0], last_xy[1], tool, waiting[at]))
            at += 1

    try:
        source = Source.open(path)
        for event in reader.events(source):
            kind = type(event)
            if kind is ToolChange:
                mark(event.line - 1)
                tool = event.tool
                continue
            if kind is not Move or not event.point:
                continue
            mark(event.line - 1)
            x, y = event.point[0], event.point[1]
            if x is None or y is None or (event.origin == event.point and event.arc is None):
                continue
            head = event.tool
            path_of = heads.get(head)
            if path_of is None and len(heads) >= MAX_HEADS:
                head = OTHER_HEADS
                path_of = heads.get(head)
                if path_of is None:
                    label = f"other heads (beyond the first {MAX_HEADS}, drawn together)"
                    path_of = heads[head] = HeadPath(head, label)
            if path_of is None:
                path_of = heads[head] = HeadPath(head, reader.tool_title(head) if head else "the working tool")
            if head != last_head and last_xy is not None:
                # a new head starts where the last one stopped: a travel, not a stroke
                path_of.jump(*last_xy)
            path_of.add(x, y, event.working, budget)
            last_xy = (x, y)
            last_head = head
        mark(reader.line_count)
    except SourceError as exc:
        toolpath.error = str(exc)
    except (RecursionError, MemoryError):
        toolpath.error = f"{path}: too complex to plot"
    toolpath.lines = reader.line_count
    return toolpath
