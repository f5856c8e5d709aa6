"""``gclint summary``: what a job does, in numbers, read by the reader of meaning the ``diff`` uses
(``gclint.simulate``: its events, with the dialect's facts from ``gclint.dialects.semantics``).

Per file: the heads it uses, each with its set-points, whether it waits for them and how much it
extrudes; the flow mode; the layers and their Z range; the XY extent, against the printer's bed where the
slicer's settings give one (``bed_shape`` / ``printable_area``); the feed range; and an estimated time.

Layers are counted as the slicer counts them: its layer marks where the job has them (``simulate.events.Layer``:
``;LAYER_CHANGE``, ``;LAYER:n``, ``; CHANGE_LAYER``...), the Z range being that of the printing moves after the
first mark.  Without marks, the heights at which moves print along a path (a prime of the extruder alone, a
parking move, a travel are no layer), each one above every one before; a spiral (printing while Z rises) counts
a layer per turn of the path.

The time is planned (``gclint.timing``): every move with acceleration and junction speeds limited as the job's
machine limits them (the slicer's machine limits, the job's M201/M203/M204/M205, else the firmware's documented
defaults), plus G4 dwells as the dialect counts them, plus the tool changes' load and unload times where the
slicer states them.  Heating waits and what the firmware does on its own (homing, probing, start macros) are left
out; where no acceleration is known, each move takes its length divided by its feed (a G0 with no feed of its
own at the last feed): a lower bound.  Lengths are in mm and in the job's own coordinates (inches converted;
head offsets left out: where the tool tip goes on the work).
"""

from __future__ import annotations

import math
import re
from dataclasses import asdict, dataclass, field

from gclint import dialects
from gclint.context import Context
from gclint.engine import Linter, Options
from gclint.simulate import simulator_for
from gclint.simulate.events import Dwell, Flow, Heat, Layer, Limits, Move, Pause, Stop, ToolChange
from gclint.simulate.trace import NATIVE
from gclint.syntax.source import Source
from gclint.timing import Planner, limits_for, slicer_estimate, slicer_settings
from gclint.timing.limits import defaults_used, tool_change_times

_BED = re.compile(r"(?im)^;\s*(?:bed_shape|printable_area)\s*=\s*([-\d.x, ]+)$")
MAX_VALUES = 64  # distinct set-points listed per head or device (a job that sweeps them is not a list)


@dataclass
class HeadUse:
    """One head (or extruder) of a job."""

    head: str
    set_points: list[float] = field(default_factory=list)  # distinct, in the order the job first sets them
    waits: list[float] = field(default_factory=list)  # the set-points it waits for (distinct)
    more_set_points: int = 0  # settings of a value not listed (past MAX_VALUES distinct ones): counted
    extruded_mm: float = 0.0  # filament (E) the head's printing moves advance; native flow: not metered
    printing_moves: int = 0


@dataclass
class JobSummary:
    path: str
    read_as: str
    lines: int = 0
    heads: list[HeadUse] = field(default_factory=list)
    devices: dict[str, list[float]] = field(default_factory=dict)  # beds, chambers -> distinct set-points
    waited_devices: dict[str, list[float]] = field(default_factory=dict)
    more_device_set_points: dict[str, int] = field(default_factory=dict)  # past MAX_VALUES, per device
    flow: str = ""
    layers: int = 0
    z_range: tuple[float, float] | None = None
    x_range: tuple[float, float] | None = None
    y_range: tuple[float, float] | None = None
    bed: tuple[float, float, float, float] | None = None  # x0, y0, x1, y1 from the slicer's settings
    outside_bed: bool = False
    feed_range: tuple[float, float] | None = None  # mm/min, working moves
    printing_mm: float = 0.0
    travel_mm: float = 0.0
    unmeasured_moves: int = 0  # moves from (or to) a position the state does not know: not in the metres
    unmeasured_spirals: int = 0  # of which spirals (Hyrel G2.1/G2.2): their end is known, their path is not
    time_s: float = 0.0
    dwell_s: float = 0.0  # of which G4 dwells, as the dialect counts them
    error: str | None = None
    layer_marks: str = ""  # the kind of slicer mark the layers were counted by ("" : by printing heights)
    tool_change_s: float = 0.0  # of the time, tool changes at the slicer's load and unload times
    time_limits: str = ""  # where the acceleration and junction limits came from ("" : none known, a lower bound)
    time_junctions: str = ""  # how junctions are limited: "jerk", "junction deviation", "from rest" ("" : none)
    time_leaves_out: str = ""  # what the time does not count, in words
    slicer_time_s: float | None = None  # the slicer's own estimate, when the job states one
    layers_time_s: float | None = None  # of the time, from the first layer mark to the last printing move
    cutting_mm: float = 0.0  # of the travel, feed moves of a machine whose feed moves cut (Semantics.working)
    cnc: bool = False  # a job of such a machine that prints nothing (a mill, a lathe): no flow, no printing
    stopped: str = ""  # the line the machine refuses, stopping the program there (an interpreter error), and why

    def to_dict(self) -> dict:
        return asdict(self)


def summarize_path(path: str, options: Options | None = None) -> JobSummary:
    """The summary of the job at ``path`` (``-`` for standard input), checked-as with ``options``."""
    from gclint.syntax.source import SourceError

    try:
        source = Source.open(path, cut_long_lines=True) if path != "-" else Source.open("-", cut_long_lines=True)
    except SourceError as exc:
        return JobSummary(path, "", error=str(exc))
    try:
        return summarize(source, Linter(options or Options()).context_of(source))
    except SourceError as exc:
        return JobSummary(path, "", error=str(exc))


def summarize(source: Source, context: Context) -> JobSummary:
    """Read the job as ``context`` says (the same reader of meaning the ``diff`` uses: gclint.simulate) and
    count its events."""
    summary = JobSummary(source.display, context.label())
    dialect = dialects.reading(context.dialect, context.flavor)
    head_text, tail_text = source.head_text(), source.tail_text()
    summary.bed = _bed(head_text, tail_text)
    settings = slicer_settings(head_text, tail_text)
    stated = slicer_estimate(head_text, tail_text)
    if stated is not None:
        summary.slicer_time_s = stated[0]
    machine = dialect.variant_of or dialect.name
    limits, firmware, stated_limits = limits_for(machine, context.flavor, settings)
    planner = Planner(limits)
    job_limits: set[str] = set()  # the limits the job's own commands set
    loads, unloads = tool_change_times(settings)
    tool: str | None = None
    reader = simulator_for(dialect)
    heads: dict[str, HeadUse] = {}
    layers = _Layers()
    hyrel_flow = dialect.semantics.e_values == "native"
    cuts = dialect.semantics.working == "feeds"
    cutting_mm = 0.0
    flows: list[str] = ["native"] if hyrel_flow else []
    x_low = y_low = feed_low = math.inf
    x_high = y_high = feed_high = -math.inf
    printing_mm = travel_mm = 0.0
    unmeasured = 0
    group: list[HeadUse] = []  # the heads the working tool prints with (a clone squad: each of its heads)
    head_name: str | None = None
    membership = reader.membership  # (a squad's heads changed: ask again)
    spirals = 0
    flat_z: float | None = None  # (the height of the last printing move that kept its height)
    last_feed: float | None = None  # (a rapid with no speed of its own: at the last feed, a lower bound)
    was_printing = False  # (the time when the last printing move ends: where the last layer ends)
    sqrt = math.sqrt
    move = planner.move
    for event in reader.events(source):
        if type(event) is Move:
            e = event.e
            end = event.point
            if e is not None:
                name = event.tool or ""
                if name != head_name or reader.membership != membership:
                    membership = reader.membership
                    group = []
                    for each in reader.heads_of(name):
                        found = heads.get(each)
                        if found is None:
                            found = heads[each] = HeadUse(each)
                        group.append(found)
                    head_name = name
                if e is not NATIVE:  # filament: the net E of every move (retractions included)
                    for head in group:
                        head.extruded_mm += e
            if not end:  # (a move the reader could not place)
                continue
            start = event.origin
            arc = event.arc
            x0, y0, z0 = start[0], start[1], start[2]
            x1, y1, z1 = end[0], end[1], end[2]
            dz = z1 - z0 if z0 is not None and z1 is not None else 0.0
            if x0 is None or y0 is None or x1 is None or y1 is None or event.spiral:
                length = None
                unmeasured += 1
                if event.spiral:
                    spirals += 1
            elif arc is None:
                dx, dy = x1 - x0, y1 - y0
                length = sqrt(dx * dx + dy * dy + dz * dz)
            else:
                dx, dy = x1 - x0, y1 - y0
                length = _arc_length(arc, dz)
            feed = event.feed
            if e is not None and (e is NATIVE or e > 0):  # printing (an unretraction in place too: it feeds)
                for head in group:
                    head.printing_moves += 1
                was_printing = True
                if length is not None:
                    printing_mm += length
                if z1 is not None and start != end and not (z0 == z1 == flat_z):
                    # (not the extruder alone: a prime in place is no layer; nor a move on the same height)
                    layers.printing(start, end)
                    flat_z = z1 if z0 == z1 else None
                for x in (x0, x1) if length is not None and start != end else (x1,):  # (where it starts too)
                    if x is not None:
                        if x < x_low:
                            x_low = x
                        if x > x_high:
                            x_high = x
                for y in (y0, y1) if length is not None and start != end else (y1,):
                    if y is not None:
                        if y < y_low:
                            y_low = y
                        if y > y_high:
                            y_high = y
                if feed:
                    if feed < feed_low:
                        feed_low = feed
                    if feed > feed_high:
                        feed_high = feed
            else:
                if was_printing:
                    planner.watch("printing ends")
                    was_printing = False
                if length is not None and start != end:
                    travel_mm += length
                    if cuts and not event.rapid:
                        cutting_mm += length  # (a CNC machine: every feed move cuts)
            if feed:
                last_feed = feed
            elif event.rapid:
                feed = last_feed
            if feed and length is not None:
                de = e if e is not None and e is not NATIVE else 0.0
                if arc is None:
                    move(dx, dy, dz, de, feed)
                else:
                    into, out = _tangents(arc, dz, length)
                    move(dx, dy, dz, de, feed, length, into, out)
        elif type(event) is Stop:
            summary.stopped = f"line {event.line}: {event.why}"
        elif type(event) is Layer:
            if layers.mark(event) == 1:
                planner.watch("layers begin")
            flat_z = None
        elif type(event) is Limits:
            limits.update(event.values)
            planner.refresh()
            job_limits.update(event.values)
        elif type(event) is Dwell:
            planner.stop(event.seconds or 0.0)
            summary.dwell_s += event.seconds or 0.0
        elif type(event) is ToolChange:
            if tool is not None and (loads or unloads):
                change = _per_tool(unloads, tool) + _per_tool(loads, event.tool)
                planner.stop(change)
                summary.tool_change_s += change
            tool = event.tool
        elif type(event) is Heat:
            if event.wait:
                planner.stop()
            _temperature(summary, heads, event)
        elif type(event) is Pause:
            planner.stop()
        elif type(event) is Flow:
            mode = "E values (M229 E1)" if event.mode == "evalues" else "native"
            if flows[-1:] != [mode]:
                flows.append(mode)
    if was_printing:
        planner.watch("printing ends")
    summary.printing_mm, summary.travel_mm, summary.unmeasured_moves = printing_mm, travel_mm, unmeasured
    summary.unmeasured_spirals = spirals
    summary.cutting_mm = cutting_mm
    summary.cnc = cuts and not printing_mm and not any(h.printing_moves for h in heads.values())
    summary.time_s = planner.finish()
    begin, until = planner.watched.get("layers begin"), planner.watched.get("printing ends")
    if begin is not None and until is not None and until >= begin:
        summary.layers_time_s = until - begin
    summary.lines = reader.line_count
    summary.heads = list(heads.values())
    summary.flow = " then ".join(flows) if flows else "E amounts (extruder position)"
    summary.layers, summary.z_range, summary.layer_marks = layers.result()
    origin = []
    if planner.accelerated:
        if job_limits:
            origin.append("the job's own commands")
        if stated_limits:
            origin.append("the slicer's machine limits")
        if firmware and defaults_used(machine, context.flavor, stated_limits | job_limits):
            origin.append(f"{firmware}'s defaults" + (" for the rest" if origin else ""))
    if origin:
        summary.time_limits = ", ".join(origin[:-1]) + (" and " if len(origin) > 1 else "") + origin[-1]
        summary.time_junctions = (
            "from rest" if planner.from_rest else "jerk" if planner.classic else "junction deviation"
        )
    summary.time_leaves_out = (
        "heating waits, pauses for the operator"
        + ("" if summary.tool_change_s else ", tool changes")
        + " and what the firmware does on its own (homing, probing, start macros)"
    )
    if x_low <= x_high:
        summary.x_range = (x_low, x_high)
    if y_low <= y_high:
        summary.y_range = (y_low, y_high)
    if feed_low <= feed_high:
        summary.feed_range = (feed_low, feed_high)
    if summary.bed and summary.x_range and summary.y_range:
        x0, y0, x1, y1 = summary.bed
        summary.outside_bed = (
            summary.x_range[0] < x0 - 1e-6
            or summary.x_range[1] > x1 + 1e-6
            or summary.y_range[0] < y0 - 1e-6
            or summary.y_range[1] > y1 + 1e-6
        )
    return summary


class _Layers:
    """The layers: counted by the slicer's marks (one kind: the first seen) when the job has them, else by the
    heights at which moves print."""

    def __init__(self) -> None:
        self.kind: str | None = None
        self.marked = 0
        self.mark_z: float | None = None
        self.marked_low = math.inf
        self.marked_top = -math.inf
        # by heights: each printing height above every one before; a spiral's turns
        self.levels = 0
        self.low = math.inf
        self.top: float | None = None
        self.turn = 0.0  # the path's turn (radians) since the spiral's last layer
        self.heading: float | None = None

    def mark(self, layer: Layer) -> int:
        """Count a mark; the number of layers marked so far (0: a mark of another kind)."""
        if self.kind is None:
            self.kind = layer.marks
        elif layer.marks != self.kind:
            return 0
        if layer.z is not None:
            if layer.z == self.mark_z:
                return 0  # (another object's part of the same layer: KISSlicer marks each)
            self.mark_z = layer.z
        self.marked += 1
        return self.marked

    def printing(self, start: tuple, end: tuple) -> None:
        z = end[2]
        if z is None:
            return
        if self.kind is not None:
            if z < self.marked_low:
                self.marked_low = z
            if z > self.marked_top:
                self.marked_top = z
        top = self.top
        sx, sy, sz = start[0], start[1], start[2]
        ex, ey = end[0], end[1]
        if sz is not None and sz != z and sx is not None and sy is not None and (ex != sx or ey != sy):
            # printing while Z changes along a path: a spiral, a layer per turn of the path
            heading = math.atan2(ey - sy, ex - sx)
            if top is None or z > top + 1e-6:
                if self.heading is None:  # the spiral begins: its first layer
                    self.levels += 1
                    self.turn = 0.0
                else:
                    step = heading - self.heading
                    if step > math.pi:
                        step -= 2 * math.pi
                    elif step < -math.pi:
                        step += 2 * math.pi
                    self.turn += step
                    if abs(self.turn) >= 2 * math.pi:
                        self.levels += 1
                        self.turn -= math.copysign(2 * math.pi, self.turn)
                self.top = z
                if z < self.low:
                    self.low = z
            self.heading = heading
            return
        self.heading = None
        if top is None or z > top + 1e-6:
            self.levels += 1
            self.top = z
        if z < self.low:
            self.low = z

    def result(self) -> tuple[int, tuple[float, float] | None, str]:
        if self.kind is not None and self.marked:
            z_range = (self.marked_low, self.marked_top) if self.marked_low <= self.marked_top else None
            return self.marked, z_range, self.kind
        if self.top is None:
            return 0, None, ""
        return self.levels, (self.low, self.top), ""


def _per_tool(times: list[float], tool: str | None) -> float:
    """A tool's load (or unload) time: its own where the settings list one per filament, else the first."""
    if not times:
        return 0.0
    m = re.search(r"(\d+)$", tool or "")
    index = int(m.group(1)) if m else 0
    return times[index] if index < len(times) else times[0]


def _tangents(arc, dz: float, length: float) -> tuple[tuple | None, tuple | None]:
    """The directions (unit XYZ) an arc starts and ends in: along the circle, rising ``dz`` over its length (an
    arc in another plane: None, the planner takes its chord)."""
    plane, _, radius, clockwise, a0, turn = arc
    if plane != 17 or length <= 0 or radius <= 0:
        return None, None
    a1 = a0 - turn if clockwise else a0 + turn
    flat = radius * turn / length
    rise = dz / length
    sign = -1.0 if clockwise else 1.0
    into = (-math.sin(a0) * sign * flat, math.cos(a0) * sign * flat, rise)
    out = (-math.sin(a1) * sign * flat, math.cos(a1) * sign * flat, rise)
    return into, out


def _arc_length(arc, dz: float) -> float:
    """An arc's path length (mm): its turn and its rise (an arc in another plane: its rise is along another
    axis)."""
    plane, _, radius, _, _, turn = arc
    if plane == 17:
        return math.hypot(radius * turn, dz)
    return radius * turn


def _temperature(summary: JobSummary, heads: dict[str, HeadUse], heat: Heat) -> None:
    if heat.kind == "head":
        head = heads.setdefault(heat.device, HeadUse(heat.device))
        if not _note(head.set_points, heat.value):
            head.more_set_points += 1
        if heat.wait:
            _note(head.waits, heat.value)
        return
    kind = heat.device  # (a bed or chamber by its name: "bed", "chamber", Hyrel's "bed 2 (T25)")
    if not _note(summary.devices.setdefault(kind, []), heat.value):
        summary.more_device_set_points[kind] = summary.more_device_set_points.get(kind, 0) + 1
    if heat.wait:
        _note(summary.waited_devices.setdefault(kind, []), heat.value)


def _note(values: list[float], value: float) -> bool:
    """Add ``value`` to the distinct ``values`` unless there (True) or the list is full (False: one more)."""
    if value in values:
        return True
    if len(values) >= MAX_VALUES:
        return False
    values.append(value)
    return True


def _bed(head: str, tail: str | None) -> tuple[float, float, float, float] | None:
    for text in (head, tail or ""):
        m = _BED.search(text)
        if m:
            points = []
            for corner in m.group(1).split(","):
                x, _, y = corner.strip().partition("x")
                try:
                    points.append((float(x), float(y)))
                except ValueError:
                    return None
            if points:
                xs, ys = [p[0] for p in points], [p[1] for p in points]
                return min(xs), min(ys), max(xs), max(ys)
    return None


def render(summary: JobSummary) -> str:
    """The summary as text, one fact per line."""
    if summary.error:
        return f"{summary.path}: {summary.error}\n"
    out = [f"{summary.path}: {summary.read_as}, {summary.lines:,} lines"]
    for head in summary.heads:
        if head.set_points:
            temps = "set-points " + _listed(head.set_points, head.more_set_points) + " °C"
        else:
            temps = "no set-point in the job"
        waits = f"; waits for {', '.join(f'{t:g}' for t in dict.fromkeys(head.waits))}" if head.waits else ""
        extruded = f"; {head.extruded_mm:,.1f} mm of filament" if head.extruded_mm else ""
        out.append(f"  {head.head}: {temps}{waits}; {head.printing_moves:,} printing moves{extruded}")
    for kind, points in summary.devices.items():
        device_waits = summary.waited_devices.get(kind, [])
        waited = f"; waits for {', '.join(f'{t:g}' for t in dict.fromkeys(device_waits))}" if device_waits else ""
        listed = _listed(points, summary.more_device_set_points.get(kind, 0))
        out.append(f"  {kind}: set-points {listed} °C{waited}")
    if not summary.cnc:
        out.append(f"  flow: {summary.flow}")
    if summary.z_range:
        by = " (the slicer's layer marks)" if summary.layer_marks else ""
        out.append(f"  layers: {summary.layers:,}, Z {summary.z_range[0]:g} to {summary.z_range[1]:g} mm{by}")
    if summary.x_range and summary.y_range:
        extent = (
            f"  XY extent: X {summary.x_range[0]:g} to {summary.x_range[1]:g}, "
            f"Y {summary.y_range[0]:g} to {summary.y_range[1]:g} mm"
        )
        if summary.bed:
            x0, y0, x1, y1 = summary.bed
            where = "OUTSIDE" if summary.outside_bed else "within"
            extent += f" ({where} the bed {x0:g}..{x1:g} x {y0:g}..{y1:g} from the slicer's settings)"
        else:
            extent += " (the job does not say the bed's size)"
        out.append(extent)
    if summary.feed_range:
        out.append(f"  feed: {summary.feed_range[0]:g} to {summary.feed_range[1]:g} mm/min on printing moves")
    if summary.cnc:
        rapid = summary.travel_mm - summary.cutting_mm
        moves = f"  moves: {summary.cutting_mm / 1000:,.2f} m at feed (cutting), {rapid / 1000:,.2f} m rapid"
    else:
        moves = f"  moves: {summary.printing_mm / 1000:,.2f} m printing, {summary.travel_mm / 1000:,.2f} m travel"
    if summary.unmeasured_moves:
        n = summary.unmeasured_moves - summary.unmeasured_spirals
        spirals = summary.unmeasured_spirals
        parts = [f"{n:,} move{'s' if n != 1 else ''} from an unknown position"] if n else []
        if spirals:
            parts.append(f"{spirals:,} spiral{'s' if spirals != 1 else ''} (G2.1/G2.2: the path is not modelled)")
        moves += f" (and {' and '.join(parts)}, not measured)"
    out.append(moves)
    if summary.stopped:
        out.append(f"  stops at {summary.stopped}; nothing after it runs (the rest is not counted)")
    out.append(f"  estimated time: {_duration(summary.time_s)} ({_time_model(summary)})")
    if summary.layers_time_s is not None:
        out.append(
            f"  of which the layers: {_duration(summary.layers_time_s)} (from the first layer mark to the last"
            " printing move; the rest is the start and end sequences)"
        )
    if summary.slicer_time_s is not None:
        out.append(f"  the slicer's own estimate: {_duration(summary.slicer_time_s)}")
    return "\n".join(out) + "\n"


def _time_model(summary: JobSummary) -> str:
    if summary.time_junctions == "from rest":
        said = (
            f"moves planned with acceleration from {summary.time_limits}, each from rest (the job states no jerk"
            " or junction deviation)"
        )
    elif summary.time_limits:
        junctions = "jerk limits" if summary.time_junctions == "jerk" else "junction deviation"
        said = f"moves planned with acceleration and {junctions} from {summary.time_limits}"
    else:
        said = "moves at their feed: no acceleration known, a lower bound"
    parts = [said, "plus dwells"]
    if summary.tool_change_s:
        parts.append(f"tool changes at the slicer's load and unload times ({_duration(summary.tool_change_s)})")
    return "; ".join(parts) + f"; leaves out {summary.time_leaves_out}"


def _duration(seconds: float) -> str:
    minutes, secs = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes:02d} min" if hours else f"{minutes} min {secs:02d} s"


def _listed(values: list[float], more: int) -> str:
    text = ", ".join(f"{t:g}" for t in values)
    return f"{text} (and {more:,} more settings not listed)" if more else text
