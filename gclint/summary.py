"""``gclint summary``: what a job does, in numbers, read with the same machine state the check uses.

Per file: the heads it uses, each with its set-points, whether it waits for them and how much it
extrudes; the flow mode; the layers and the Z range of the printing moves; the XY extent, against the
printer's bed where the slicer's settings give one (``bed_shape`` / ``printable_area``); the feed range;
and an estimated time.

The time model is deliberately simple (and the same for every dialect), so that two jobs compare: each
move takes its length divided by the feed in force (arcs by their arc length; a G0 with no feed of its own
at the last feed), plus G4 dwells; heating, acceleration and tool changes are not counted.  It is a lower
bound, not a promise.
"""

from __future__ import annotations

import math
import re
from dataclasses import asdict, dataclass, field

from gclint.context import Context
from gclint.dialects import get as get_dialect
from gclint.engine import Linter, Options
from gclint.machine.interpreter import Interpreter
from gclint.machine.state import EVALUES, NATIVE
from gclint.syntax.nodes import Command, Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source

_WAITS = {"M109": "head", "M190": "bed", "M191": "chamber"}
_SETS = {"M104": "head", "M109": "head", "M140": "bed", "M190": "bed", "M141": "chamber", "M191": "chamber"}
_BED = re.compile(r"(?im)^;\s*(?:bed_shape|printable_area)\s*=\s*([-\d.x, ]+)$")
_AXES = "XYZ"
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
    """Run the job through the machine state (``context`` says as what) and count."""
    summary = JobSummary(source.display, context.label())
    dialect = get_dialect(context.dialect)
    summary.bed = _bed(source.head_text(), source.tail_text())
    interpreter = Interpreter(dialect)
    st = interpreter.state
    heads: dict[str, HeadUse] = {}
    layers = 0  # printing heights above every one before (the layers), counted, with the lowest and top
    z_low = z_top = None
    last_z: float | None = None
    flows: list[str] = []
    feed_low, feed_high = math.inf, -math.inf
    box = [math.inf, -math.inf, math.inf, -math.inf, math.inf, -math.inf]
    number = 0
    for chunk in source.chunks():
        for raw, ending in chunk:
            number += 1
            parsed = parse_line(raw)
            line = Line(number, raw, ending, parsed)
            for cmd in parsed.commands:
                before = _where(st)
                e_before = st.e_position
                code = cmd.code
                interpreter.apply(cmd, line)
                if code in _SETS:
                    _temperature(summary, heads, cmd, st, interpreter)
                elif code == "G4":
                    summary.time_s += _dwell(cmd, dialect.family)
                if code not in ("G0", "G1", "G2", "G3", None) or cmd.kind not in ("gcode", "implicit"):
                    continue
                after = _where(st)
                # None: the move starts (or ends) where the state does not know; it is still a move, and
                # still prints, with its known end in the extent; only its length (and time) is unknown
                length = _length(before, after, cmd)
                if length is None:
                    summary.unmeasured_moves += 1
                feed = st.feed
                # Marlin and RRF: G0 is G1 ("E allowed (extrudes)", research/dialects.md), so a G0 that
                # extrudes prints (slicers' purge lines); elsewhere G0 is a rapid, non-working move
                working = code != "G0" or dialect.family == "reprap"
                printing = working and _printed(e_before, st.e_position, cmd, interpreter)
                name = _head_name(st.tool, dialect.family)
                # filament: the net E of every move (a retraction takes back what the unretraction gives)
                metered = st.flow_mode != NATIVE or not interpreter.is_hyrel  # (native flow: not metered)
                if metered and e_before is not None and st.e_position is not None and st.e_position != e_before:
                    heads.setdefault(name, HeadUse(name)).extruded_mm += st.e_position - e_before
                if printing:
                    heads.setdefault(name, HeadUse(name)).printing_moves += 1
                    if length is not None:
                        summary.printing_mm += length
                    z = after[2]
                    if z is not None and (last_z is None or abs(z - last_z) > 1e-6):
                        if z_top is None or z > z_top + 1e-6:
                            layers += 1
                            z_top = z
                            z_low = z if z_low is None else min(z_low, z)
                        last_z = z
                    for i, value in enumerate(after):
                        if value is not None:
                            box[2 * i] = min(box[2 * i], value)
                            box[2 * i + 1] = max(box[2 * i + 1], value)
                    if feed:
                        feed_low, feed_high = min(feed_low, feed), max(feed_high, feed)
                elif length is not None:
                    summary.travel_mm += length
                if feed and feed > 0 and length is not None:
                    summary.time_s += length / feed * 60
            if interpreter.is_hyrel:
                mode = "E values (M229 E1)" if st.flow_mode == EVALUES else "native"
                if not flows or flows[-1] != mode:
                    flows.append(mode)
    summary.lines = number
    summary.heads = list(heads.values()) + [h for h in summary.heads if h.head not in heads]
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


def _where(st) -> tuple[float | None, float | None, float | None]:
    pos = st.position
    return pos.get("X"), pos.get("Y"), pos.get("Z")


def _length(before, after, cmd: Command) -> float | None:
    if None in before[:2] or None in after[:2]:
        return None
    dz = (after[2] - before[2]) if before[2] is not None and after[2] is not None else 0.0
    chord = math.dist(before[:2], after[:2])
    if cmd.code in ("G2", "G3") and ("I" in cmd.params or "J" in cmd.params):
        i, j = cmd.get("I") or 0.0, cmd.get("J") or 0.0
        radius = math.hypot(i, j)
        if radius > 0:
            cx, cy = before[0] + i, before[1] + j
            a0 = math.atan2(before[1] - cy, before[0] - cx)
            a1 = math.atan2(after[1] - cy, after[0] - cx)
            sweep = (a0 - a1) if cmd.code == "G2" else (a1 - a0)
            sweep %= 2 * math.pi
            if sweep == 0:
                sweep = 2 * math.pi  # a full circle
            return math.hypot(radius * sweep, dz)
    return math.hypot(chord, dz)


def _printed(e_before: float | None, e_after: float | None, cmd: Command, interpreter: Interpreter) -> bool:
    if "E" not in cmd.params:
        return False
    if interpreter.is_hyrel and interpreter.state.flow_mode == NATIVE:
        return True  # "E will trigger a working or printing move" (Hyrel G1)
    return e_before is not None and e_after is not None and e_after > e_before


def _head_name(tool: int | None, family: str) -> str:
    if tool is None:
        return "the focused head" if family == "hyrel" else "extruder 0"
    return f"T{tool}" if family == "hyrel" else f"extruder {tool}"


def _temperature(summary: JobSummary, heads: dict[str, HeadUse], cmd: Command, st, interpreter: Interpreter) -> None:
    value = cmd.get("S") if cmd.get("S") is not None else (cmd.get("R") if not interpreter.is_hyrel else None)
    if value is None:
        return
    kind = _SETS[str(cmd.code)]
    waits = cmd.code in _WAITS and not (interpreter.is_hyrel and "W" in cmd.params)
    if kind == "head":
        # without T the command acts on the active tool: Marlin and RRF ("T = hotend idx (default
        # active)", research/dialects.md) and Hyrel (Gcode page, "M109 Wait for Temp (Head)", Example 6:
        # "(no T# - use head with current focus)"; T_v5, Default Mode)
        address = interpreter.address(cmd) if interpreter.is_hyrel else None
        if address is not None:
            tool = address.v5
        elif not interpreter.is_hyrel and cmd.get("T") is not None:
            tool = cmd.get("T")
        else:
            tool = st.tool
        name = _head_name(int(tool) if tool is not None else None, interpreter.family)
        if address is not None and address.kind != "head":
            name = address.label
        head = heads.setdefault(name, HeadUse(name))
        if not _note(head.set_points, value):
            head.more_set_points += 1
        if waits:
            _note(head.waits, value)
        return
    if not _note(summary.devices.setdefault(kind, []), value):
        summary.more_device_set_points[kind] = summary.more_device_set_points.get(kind, 0) + 1
    if waits:
        _note(summary.waited_devices.setdefault(kind, []), value)


def _note(values: list[float], value: float) -> bool:
    """Add ``value`` to the distinct ``values`` unless there (True) or the list is full (False: one more)."""
    if value in values:
        return True
    if len(values) >= MAX_VALUES:
        return False
    values.append(value)
    return True


def _dwell(cmd: Command, family: str) -> float:
    # G4 P: milliseconds (Marlin, RRF, Hyrel), seconds on LinuxCNC/Carvera; S: seconds
    p, s = cmd.get("P"), cmd.get("S")
    if s is not None:
        return max(0.0, s)
    if p is not None:
        return max(0.0, p if family in ("linuxcnc", "smoothie") else p / 1000)
    return 0.0


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
