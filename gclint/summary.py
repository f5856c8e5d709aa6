"""``gclint summary``: what a job does, in numbers, read by the reader of meaning the ``diff`` uses
(``gclint.simulate``: its events, with the dialect's facts from ``gclint.dialects.semantics``).

Per file: the heads it uses, each with its set-points, whether it waits for them and how much it
extrudes; the flow mode; the layers and the Z range of the printing moves; the XY extent, against the
printer's bed where the slicer's settings give one (``bed_shape`` / ``printable_area``); the feed range;
and an estimated time.

The time model is deliberately simple (and the same for every dialect), so that two jobs compare: each
move takes its length divided by the feed in force (arcs by their arc length; a G0 with no feed of its own
at the last feed), plus G4 dwells as the dialect counts them; heating, acceleration and tool changes are not
counted.  It is a lower bound, not a promise.  Lengths are in mm and in the job's own coordinates (inches
converted; head offsets left out: where the tool tip goes on the work).
"""

from __future__ import annotations

import math
import re
from dataclasses import asdict, dataclass, field

from gclint import dialects
from gclint.context import Context
from gclint.engine import Linter, Options
from gclint.simulate import simulator_for
from gclint.simulate.events import Dwell, Flow, Heat, Move
from gclint.simulate.trace import NATIVE
from gclint.syntax.source import Source

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
    time_s: float = 0.0
    dwell_s: float = 0.0  # of which G4 dwells, as the dialect counts them
    error: str | None = None

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
    summary.bed = _bed(source.head_text(), source.tail_text())
    reader = simulator_for(dialect)
    heads: dict[str, HeadUse] = {}
    layers = 0  # printing heights above every one before (the layers), counted, with the lowest and top
    z_low = z_top = None
    last_z: float | None = None
    hyrel_flow = dialect.semantics.e_values == "native"
    flows: list[str] = ["native"] if hyrel_flow else []
    feed_low, feed_high = math.inf, -math.inf
    box = [math.inf, -math.inf, math.inf, -math.inf, math.inf, -math.inf]
    last_feed: float | None = None  # (a rapid with no speed of its own: at the last feed, a lower bound)
    for event in reader.events(source):
        kind = type(event)
        if kind is Move:
            e = event.e
            name = event.tool or ""
            if e is not None and e is not NATIVE:  # filament: the net E of every move (retractions included)
                heads.setdefault(name, HeadUse(name)).extruded_mm += e
            if not event.point:  # (a move the reader could not place)
                continue
            start, end = event.origin, event.point
            length = _length(start, end, event.arc)
            if length is None:
                summary.unmeasured_moves += 1
            printing = e is not None and (e is NATIVE or e > 0)  # (an unretraction in place too: it feeds)
            feed = event.feed
            if printing:
                heads.setdefault(name, HeadUse(name)).printing_moves += 1
                if length is not None:
                    summary.printing_mm += length
                z = end[2]
                if z is not None and (last_z is None or abs(z - last_z) > 1e-6):
                    if z_top is None or z > z_top + 1e-6:
                        layers += 1
                        z_top = z
                        z_low = z if z_low is None else min(z_low, z)
                    last_z = z
                for i, value in enumerate(end[:3]):
                    if value is not None:
                        box[2 * i] = min(box[2 * i], value)
                        box[2 * i + 1] = max(box[2 * i + 1], value)
                if feed:
                    feed_low, feed_high = min(feed_low, feed), max(feed_high, feed)
            elif length is not None and start != end:
                summary.travel_mm += length
            if feed:
                last_feed = feed
            elif event.rapid:
                feed = last_feed
            if feed and feed > 0 and length is not None:
                summary.time_s += length / feed * 60
        elif kind is Dwell:
            summary.time_s += event.seconds or 0.0
            summary.dwell_s += event.seconds or 0.0
        elif kind is Heat:
            _temperature(summary, heads, event)
        elif kind is Flow:
            mode = "E values (M229 E1)" if event.mode == "evalues" else "native"
            if flows[-1:] != [mode]:
                flows.append(mode)
    summary.lines = reader.line_count
    summary.heads = list(heads.values())
    summary.flow = " then ".join(flows) if flows else "E amounts (extruder position)"
    summary.layers = layers
    if z_low is not None and z_top is not None:
        summary.z_range = (z_low, z_top)
    if box[0] <= box[1]:
        summary.x_range = (box[0], box[1])
    if box[2] <= box[3]:
        summary.y_range = (box[2], box[3])
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


def _length(start: tuple, end: tuple, arc) -> float | None:
    """A move's path length (mm): an arc's turn and its rise, or the straight line; None when it starts or ends
    where the reader does not know (it still prints, with its known end in the extent)."""
    if not start or None in start[:2] or None in end[:2]:
        return None
    dz = (end[2] - start[2]) if start[2] is not None and end[2] is not None else 0.0
    if arc is not None:
        plane, _, radius, _, _, turn = arc
        if plane == 17:
            return math.hypot(radius * turn, dz)
        return radius * turn  # (an arc in another plane: its rise is along another axis)
    return math.hypot(math.dist(start[:2], end[:2]), dz)


def _temperature(summary: JobSummary, heads: dict[str, HeadUse], heat: Heat) -> None:
    if heat.kind == "head":
        head = heads.setdefault(heat.device, HeadUse(heat.device))
        if not _note(head.set_points, heat.value):
            head.more_set_points += 1
        if heat.wait:
            _note(head.waits, heat.value)
        return
    kind = heat.kind
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
    for kind, temps in summary.devices.items():
        waits = summary.waited_devices.get(kind, [])
        waited = f"; waits for {', '.join(f'{t:g}' for t in dict.fromkeys(waits))}" if waits else ""
        listed = _listed(temps, summary.more_device_set_points.get(kind, 0))
        out.append(f"  {kind}: set-points {listed} °C{waited}")
    out.append(f"  flow: {summary.flow}")
    if summary.z_range:
        out.append(f"  layers: {summary.layers:,}, Z {summary.z_range[0]:g} to {summary.z_range[1]:g} mm")
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
    moves = f"  moves: {summary.printing_mm / 1000:,.2f} m printing, {summary.travel_mm / 1000:,.2f} m travel"
    if summary.unmeasured_moves:
        n = summary.unmeasured_moves
        moves += f" (and {n:,} move{'s' if n != 1 else ''} from an unknown position, not measured)"
    out.append(moves)
    out.append(f"  estimated time: {_duration(summary.time_s)} (moves at their feed plus dwells; no heating)")
    return "\n".join(out) + "\n"


def _duration(seconds: float) -> str:
    minutes, secs = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes:02d} min" if hours else f"{minutes} min {secs:02d} s"


def _listed(values: list[float], more: int) -> str:
    text = ", ".join(f"{t:g}" for t in values)
    return f"{text} (and {more:,} more settings not listed)" if more else text
