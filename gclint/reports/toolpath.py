"""The XY toolpath of a job, per head, for the HTML report's plot.

The file is read again, streaming, through gclint's own ``Source``, parser and machine ``Interpreter``,
so positions follow the dialect's semantics (G90/G91, G92, Hyrel G28 homing only the listed axes, the
focused head from T commands).  Memory stays bounded on multi-million-line jobs: each head keeps at most
``2 * budget`` points, sampled at a stride that doubles whenever the budget fills (every move is seen,
one in ``stride`` is kept).  Arcs are drawn as their chord.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint import dialects
from gclint.dialects.addressing import resolve_v5
from gclint.machine.interpreter import Interpreter
from gclint.machine.state import NATIVE, MachineState
from gclint.syntax.nodes import IMPLICIT, Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source, SourceError

_WORKING = frozenset({"G1", "G2", "G3", "G2.1", "G3.1", "G2.2", "G3.2", "G2.3", "G3.3", "G81"})
_MOTION = _WORKING | {"G0", "G28", "G92"}
MAX_MARKERS = 2000
# Heads drawn each on its own; the moves of any further head (a job may name a million tools) are drawn
# together as one more path, so that memory and the page stay bounded.
MAX_HEADS = 64
OTHER_HEADS = "other"


@dataclass
class HeadPath:
    """The sampled moves of one head: ``(x, y, working)``; ``working`` is the move that ends there."""

    key: int | str | None
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
    head: int | None
    line: int


@dataclass
class Toolpath:
    heads: dict[int | str | None, HeadPath] = field(default_factory=dict)
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


def head_label(key: int | None, family: str) -> str:
    if key is None:
        return "focused head (no T command)"
    if family == "hyrel":
        return resolve_v5(key).label
    return f"tool T{key}"


def read_toolpath(
    path: str, dialect_name: str | None, flagged: set[int] | frozenset[int] = frozenset(), budget: int = 6000
) -> Toolpath:
    """Replay ``path`` and collect its XY moves per head, plus the position of each flagged line."""
    toolpath = Toolpath()
    if path == "-":
        toolpath.error = "standard input cannot be read twice: no plot"
        return toolpath
    try:
        dialect = dialects.get(dialect_name) if dialect_name else dialects.DEFAULT
    except dialects.UnknownDialect:
        dialect = dialects.DEFAULT
    state = MachineState()
    interpreter = Interpreter(dialect, state)
    apply = interpreter.apply
    position = state.position
    fff = dialect.family in ("hyrel", "reprap")  # printers: a working move extrudes; CNC: every G1 cuts
    heads = toolpath.heads
    markers = toolpath.markers
    number = 0
    last_xy: tuple[float, float] | None = None
    last_head: object = object()
    try:
        source = Source.open(path)
        for chunk in source.chunks():
            for raw, _ending in chunk:
                number += 1
                parsed = parse_line(raw)
                commands = parsed.commands
                if not commands:
                    continue
                line = Line(number, raw, _ending, parsed)
                moved = False
                working = False
                for cmd in commands:
                    code = cmd.code
                    if cmd.kind == IMPLICIT:
                        code = state.motion_mode
                    if code in _MOTION and ("X" in cmd.params or "Y" in cmd.params or code == "G28"):
                        moved = True
                        if code in _WORKING:
                            if not fff:
                                working = True
                            elif "E" in cmd.params:
                                working = _extrudes(state, cmd.params.get("E"), dialect.family)
                    state.line_number = number
                    apply(cmd, line)
                if moved or number in flagged:
                    x = position.get("X")
                    y = position.get("Y")
                    if x is None or y is None:
                        continue
                    head = state.tool
                    if moved:
                        path_of = heads.get(head)
                        if path_of is None and len(heads) >= MAX_HEADS:
                            head = OTHER_HEADS
                            path_of = heads.get(head)
                            if path_of is None:
                                label = f"other heads (beyond the first {MAX_HEADS}, drawn together)"
                                path_of = heads[head] = HeadPath(head, label)
                        if path_of is None:
                            path_of = heads[head] = HeadPath(head, head_label(head, dialect.family))
                        if head != last_head and last_xy is not None:
                            # a new head starts where the last one stopped: a travel, not a stroke
                            path_of.jump(*last_xy)
                        path_of.add(x, y, working, budget)
                        last_xy = (x, y)
                        last_head = head
                    if number in flagged and len(markers) < MAX_MARKERS:
                        markers.append(Marker(x, y, head, number))
    except SourceError as exc:
        toolpath.error = str(exc)
    except (RecursionError, MemoryError):
        toolpath.error = f"{path}: too complex to plot"
    toolpath.lines = number
    return toolpath


def _extrudes(state: MachineState, e: str | None, family: str) -> bool:
    # Hyrel native flow: "E will trigger a working or printing move" whatever its value (G1 section).
    if family == "hyrel" and state.flow_mode == NATIVE:
        return True
    try:
        value = float(e) if e is not None else 0.0
    except ValueError:
        return False
    if state.e_absolute:
        return state.e_position is None or value > state.e_position
    return value > 0
