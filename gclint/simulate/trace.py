"""What a simulation yields: the working moves of a job (its synchronisation points) and its end state,
each described in Hyrel terms so that a source job and its translation can be compared.

A ``Move`` is one printing move (FDM jobs: a move that deposits material) or one cutting move (CNC jobs:
a G1/G2/G3 feed move), with where it ends (machine coordinates, mm), how much it deposits, its feed and
a ``Look``: the head doing the work and that head's set-point, readiness, fan and flow, the beds, the
spindle, the laser and the workspace, all as a Hyrel printer would see them.  ``Mapping`` says how a
source machine's tools, fans and devices correspond to Hyrel addresses (the user's configuration:
``--tool-map``, ``fan-map``, ``bed``...), so a source simulation can describe itself in Hyrel terms.
"""

from __future__ import annotations

from dataclasses import dataclass, field

NATIVE = "native"  # Hyrel computes the flow itself (native flow, or an arc): no E amount to compare
AXES = "XYZAB"
ASPECTS = (
    "moves",  # a working move one job has and the other has not
    "position",
    "path",  # the way between two points (arc chords, a line that became something else)
    "e",  # material deposited on the move
    "feed",
    "head",  # the head doing the work (the focused head)
    "temp",  # the working head's set-point, whether it was waited for, and the heat it was last waited at
    "fan",  # the working head's part-cooling fan
    "flow",  # the working head's flow multiplier (M221)
    "layer",  # native flow: the bead's layer height (M756, M221 Z) and width (M221 W) Hyrel computes the flow from
    "prime",  # unprimes and primes done now (M721/M722 I1; the source's retractions) and the head's settings
    "beds",  # beds and chambers: set-points and waits
    "spindle",
    "laser",
    "aux",  # other fans and aux ports (air, vacuum)
    "wcs",  # the fixture offsets (workspace) applied
    "units",
    "pause",  # pauses for the operator (M0, M600...) since the previous working move
    "dwell",  # seconds of dwell (G4) since the previous working move
    "end",  # what is still on when the job ends
)


@dataclass
class Mapping:
    """Source devices -> Hyrel addresses (the user's translation configuration)."""

    tool_map: dict[int, int] = field(default_factory=dict)
    fan_map: dict[int, int] = field(default_factory=dict)
    bed: int = 24
    chamber: int = 24
    spindle: int | None = None
    laser: int | None = None
    spindle_max_rpm: float | None = None
    positions: tuple[int, ...] = (0, 1, 2, 3)
    air: str = "M7"  # where a CNC source's air goes (Hyrel aux port code)
    # native: Hyrel computes the flow of a printing move itself (an E amount becomes native flow by request)
    flow: str = "evalues"
    # explicit: the source's retractions are the translation's unprimes and primes (M721/M722 I1); auto: Hyrel's
    # heads unprime and prime by themselves on print <-> travel transitions, which nothing in the job says
    retract: str = "auto"

    def head(self, tool: int) -> int | str:
        """The Hyrel head of source tool ``tool``, or a label when the printer has none for it."""
        address = self.tool_map.get(tool, tool)
        if address in self.positions:
            return address
        return f"tool {tool} (no head)"

    def spindle_address(self) -> int:
        return self.spindle if self.spindle is not None else self.tool_map.get(0, 0)

    def laser_address(self) -> int:
        return self.laser if self.laser is not None else self.tool_map.get(0, 0)

    @classmethod
    def from_options(cls, options) -> Mapping:
        """From a ``TranslateOptions`` (the same settings ``gclint translate`` takes)."""
        return cls(
            tool_map=dict(options.tool_map),
            fan_map=dict(options.fan_map),
            bed=options.bed,
            chamber=options.chamber,
            spindle=options.spindle,
            laser=options.laser,
            spindle_max_rpm=options.spindle_max_rpm,
            positions=tuple(options.printer.positions),
            air=options.air,
            flow=options.flow,
            retract=options.retract,
        )


# The end-state key of a source printer's one part-cooling fan (Marlin's fan 0: it cools whatever tool prints)
PART_FAN = "part fan"

# Hyrel's aux ports by what they are (Gcode page, Controlling Aux Devices): the name the diff shows.
AUX_PORTS = {"M7": "aux1", "M8": "aux2", "M679": "vacuum", "M685": "air", "M670": "light"}


@dataclass(frozen=True)
class Look:
    """The state a working move runs in, in Hyrel terms (compared aspect by aspect)."""

    head: int | str | None = None
    # (set-point, waited for at that set-point, the set-point last waited for: the nozzle is at least that hot)
    temp: tuple[float | None, bool, float | None] = (None, False, None)
    fan: float = 0.0  # fraction of full speed
    flow: float = 1.0  # multiplier
    beds: tuple = ()  # ((address, set-point, waited), ...) for beds/chambers with a set-point
    spindle: tuple | None = None  # (direction "M3"/"M4", percent or None)
    laser: float | None = None  # power percent while firing
    aux: tuple = ()  # ((device, value), ...) other fans and aux ports that are on
    wcs: str | None = None
    units: str = "mm"
    # native flow: (bead width or None, the layer heights the move may be computed with); None: the E amounts are
    # used (E values), so no height matters.  A source may allow several heights (the one its slicer states
    # and the rise from the layer below); Hyrel has one.  An empty tuple: no height known.
    layer: tuple | None = None
    # the working head's unprime and prime settings (M721/M722 without I1: S, E, P), Hyrel only
    prime: tuple | None = None


# The aspects of a Look, compared one by one (compare.py)
LOOK_ASPECTS = ("head", "temp", "fan", "flow", "layer", "beds", "spindle", "laser", "aux", "wcs", "units", "prime")


class Move:
    """One synchronisation point."""

    __slots__ = (
        "line",
        "start",
        "end",
        "arc",
        "e",
        "feed",
        "look",
        "rapid",
        "frames",
        "anchors",
        "pauses",
        "dwell",
        "tail",
        "feed_mode",
        "working",
        "tool",
        "origin",
        "point",
        "primes",
        "marks",
        "trail",
        "spiral",
    )

    def __init__(
        self, line, start, end, arc, e, feed, look, rapid=False, frames=(None,) * 5, anchors=(0,) * 5, working=True
    ) -> None:
        self.line = line  # 1-based line number in its file
        self.start = start  # (x, y, z, a, b) machine mm, None where unknown
        self.end = end
        self.arc = arc  # None, or (plane, centre (u, v), radius, clockwise) in machine mm
        self.e = e  # deposited E (mm of filament), NATIVE, or None (nothing deposited / no extruder)
        self.feed = feed  # mm/min, None unknown
        self.look = look
        self.rapid = rapid
        self.frames = frames  # per axis: the workspace its coordinate is in (None: machine coordinates)
        self.anchors = anchors  # per axis: the line that last set it outright (absolute move, homing, G92)
        self.pauses = 0  # pauses for the operator since the previous synchronisation point
        self.dwell = 0.0  # seconds of dwell since the previous synchronisation point
        self.tail = False  # commands follow the move on its line (they run after it)
        self.feed_mode = 0  # the line that set the feed mode in force when it is not units per minute (G93)
        # a working move (it prints, or a CNC feed move cuts): a synchronisation point of the diff; else a travel
        # move, which only ``Simulator.events`` yields (``e`` is then its E advance, a retraction say, or None)
        self.working = working
        # (``Simulator.events`` only) the working tool in the dialect's own terms ("T0", "extruder 1"), and where
        # the move starts and ends in the job's own coordinates (mm, without the head and G92 offsets: where the
        # tool tip is on the work, as the file wrote it)
        self.tool: str | None = None
        self.origin: tuple = ()
        self.point: tuple = ()
        # unprimes and primes since the previous synchronisation point, in Hyrel terms: (("unprime", head), ...)
        self.primes: tuple = ()
        # per look aspect (a bed or aux device by itself: "beds:24"), the source line that last changed it
        # (``Anchored``): a finding before that line cannot explain a difference in it
        self.marks: dict = _NO_MARKS
        # where there were pauses since the previous synchronisation point: the pauses and the spindle's
        # direction changes in their order ("pause", "M3", "off", "pause"...): which pause it was
        self.trail: tuple = ()
        # a spiral (Hyrel G2.1/G2.2, G3.1/G3.2): its end is known, its path is not (laps, pitch): no length
        self.spiral = False

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"Move(line={self.line}, end={self.end}, e={self.e}, feed={self.feed})"


_NO_MARKS: dict = {}


@dataclass
class EndState:
    """What is still on when the job ends, in Hyrel terms."""

    line: int = 0
    # the job ends with an end of program: Hyrel's M30 ("No gcode after an M30 will be executed as part of the
    # previous job"; it resets M229, the fan range, the offsets); a source job ends with its file, or its own end
    ended: bool = False
    heaters: dict = field(default_factory=dict)  # address -> set-point (> 0 only)
    fans: dict = field(default_factory=dict)  # address -> fraction (> 0 only)
    spindles: dict = field(default_factory=dict)  # address -> direction
    emitters: frozenset = frozenset()
    aux: dict = field(default_factory=dict)
    pauses: int = 0  # pauses after the last working move
    dwell: float = 0.0  # seconds of dwell after the last working move
    primes: tuple = ()  # unprimes and primes after the last working move
    trail: tuple = ()  # the pauses after the last working move among the spindle's changes (``Move.trail``)
    # per device of the end state ("heaters:24", "program"), the source line that last changed it (``Anchored``)
    marks: dict = field(default_factory=dict)


@dataclass
class Trace:
    """A finished simulation: its moves were streamed; this is what remains."""

    end: EndState = field(default_factory=EndState)
    notes: list[str] = field(default_factory=list)
