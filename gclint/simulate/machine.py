"""The part of a simulation every dialect shares: the line loop, positions (units, absolute/relative,
G92 offsets, workspaces), arcs, the E axis, and the synchronisation points.

A dialect's simulator (fdm.py, cnc.py, hyrel.py) subclasses ``Simulator`` with a table of handlers
(code -> method) written from its documentation, and says how its state looks in Hyrel terms
(``build_look``, ``end_state``).  Nothing here comes from the translator: the simulator is a second,
independent reading of the same pages, so that where the two disagree the diff shows it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

from gclint.dialects.base import Dialect
from gclint.simulate.trace import NATIVE, EndState, Look, Mapping, Move, Trace
from gclint.syntax.fastpath import PLAIN_MOVE
from gclint.syntax.nodes import ASSIGNMENT, GCODE, IMPLICIT, META, OWORD, Command
from gclint.syntax.parse import PARSE_LIMIT, code_before_long_comment, parse_line
from gclint.syntax.source import Source

INCH = 25.4
_AXIS_INDEX = {"X": 0, "Y": 1, "Z": 2, "A": 3, "B": 4}
_MOTION = frozenset({"G0", "G1", "G2", "G3", None})
_PLANES = {17: ("X", "Y", "I", "J"), 18: ("Z", "X", "K", "I"), 19: ("Y", "Z", "J", "K")}


def number(text: str | None) -> float | None:
    """A word's value as a float; None for a flag, an expression or a bad number."""
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        return None
    return value if value - value == 0 else None


class Simulator:
    """Runs one job; ``run`` yields its synchronisation points (``Move``), then ``trace`` holds the rest."""

    EXTRUDER: str | None = "E"  # the word that drives the extruder (Machinekit: A; CNC: None)
    AXES = "XYZAB"  # the axes that are positions (Machinekit: A is the extruder)
    G0_FEED = "modal"  # "modal" (Marlin: G0 and G1 share F), "one-shot" (Hyrel, Carvera), "rapid" (LinuxCNC)
    G0_EXTRUDES = False  # Marlin/RRF: G0 is G1 and extrudes
    E_FOLLOWS_G90 = False  # Marlin: G90/G91 also set the E mode; Machinekit: A is an axis
    DEFAULT_WCS: str | None = None  # the workspace in force at the start (LinuxCNC, Carvera: G54)
    FEED_ON_ANY_COMMAND = False  # LinuxCNC, Carvera: an F word sets the feed whatever the line's G code

    def __init__(self, dialect: Dialect, mapping: Mapping | None = None, *, cnc: bool = False) -> None:
        self.dialect = dialect
        self.mapping = mapping if mapping is not None else Mapping()
        self.cnc = cnc  # synchronise on every feed move (CNC jobs), not only on printing moves
        self.trace = Trace()
        self.handlers: dict[str, Callable[[Command, int], Move | None]] = self.table()
        # positions: machine coordinates (mm, from where the job starts); a program coordinate is the machine
        # coordinate minus the shift that G92 (and homing) set
        self.pos: list[float | None] = [None] * 5
        self.shift: list[float] = [0.0] * 5
        # tool or head offsets in force (Hyrel M6 O and M660/H): added to every absolute coordinate
        self.offset: list[float] = [0.0] * 5
        # per axis: the workspace its coordinate was set in (None: machine coordinates, no fixture offsets), and
        # the line that last set it outright (an absolute move, homing, G92): what came before that line
        # cannot have moved it (compare.py: which findings explain a position)
        self.frame: tuple[str | None, ...] = (None,) * 5
        self.anchor: list[int] = [0] * 5
        self.scale = 1.0  # 25.4 in inches
        self.absolute = True
        self.e_absolute = True
        self.e_pos: float | None = 0.0
        self.feed: float | None = None  # modal feed of working moves, mm/min
        self.plane = 17
        self.motion_mode: str | None = None
        self.wcs: str | None = self.DEFAULT_WCS
        self.inch_used = False
        self.ended = False  # the end of program ran: nothing after it runs
        self.end_line = 0
        self.line = 0
        self._look: Look | None = None
        self.pauses = 0  # pauses and dwell since the last synchronisation point (compared there)
        self.dwell = 0.0

    # -- the loop --------------------------------------------------------------------------------------

    def table(self) -> dict[str, Callable[[Command, int], Move | None]]:
        return {}

    def run(self, source: Source) -> Iterator[Move]:
        handlers = self.handlers
        plain_match = PLAIN_MOVE.fullmatch
        plain = self.plain_moves()
        n = 0
        for chunk in source.chunks():
            for raw, _ending in chunk:
                n += 1
                if self.ended:
                    continue
                self.line = n
                if plain and raw[:1] == "G":
                    m = plain_match(raw)
                    if m is not None:
                        digit, f_first, x, y, z, e, f = m.groups()
                        params = {}
                        if x is not None:
                            params["X"] = x
                        if y is not None:
                            params["Y"] = y
                        if z is not None:
                            params["Z"] = z
                        if e is not None:
                            params["E"] = e
                        f = f if f is not None else f_first
                        if f is not None:
                            params["F"] = f
                        move = self.motion("G1" if digit == "1" else "G0", params, n)
                        if move is not None:
                            yield move
                        continue
                if len(raw) > PARSE_LIMIT:  # one trailing comment made it too long: its commands run
                    raw = code_before_long_comment(raw) or raw
                commands = parse_line(raw).commands
                last = len(commands) - 1
                for k, cmd in enumerate(commands):
                    if self.ended:
                        break
                    if self.FEED_ON_ANY_COMMAND and "F" in cmd.params and cmd.code not in _MOTION:
                        f = number(cmd.params["F"])
                        if f is not None:
                            self.feed = f * self.scale
                    handler = handlers.get(cmd.code)  # type: ignore[arg-type]
                    if handler is not None:
                        move = handler(cmd, n)
                    else:
                        move = self.other(cmd, n)
                    if move is not None:
                        if k < last:
                            move.tail = True
                        yield move
        end = self.end_state()
        if end is not self.trace.end:
            end.pauses, end.dwell = self.pauses, self.dwell
        self.trace.end = end
        self.trace.end.line = self.end_line or n

    def plain_moves(self) -> bool:
        """Whether plain G0/G1 lines (X Y Z E F numbers only) may go straight to ``motion``."""
        return self.handlers.get("G1") == self.g1 and self.handlers.get("G0") == self.g0

    def other(self, cmd: Command, n: int) -> Move | None:
        """A command without a handler: implicit motion, tool commands; everything else does nothing
        here (the simulator models what the diff compares, nothing more)."""
        kind = cmd.kind
        if kind == IMPLICIT:
            return self.implicit(cmd, n)
        if kind == GCODE and cmd.code and cmd.code[0] == "T":
            self.tool_command(cmd, n)
        elif kind in (META, OWORD, ASSIGNMENT):
            self.note_once("program flow", "program flow or variables are not simulated")
        return None

    def implicit(self, cmd: Command, n: int) -> Move | None:
        params = cmd.params
        if "F" in params and not any(a in params for a in "XYZAB"):
            f = number(params["F"])
            if f is not None:
                self.feed = f * self.scale
            return None
        if self.motion_mode is None or not any(a in params for a in "XYZAB"):
            return None
        mode = self.motion_mode
        if mode in ("G2", "G3"):
            return self.arc(Command(mode, GCODE, cmd.column, params), n)
        return self.motion(mode, params, n)

    def tool_command(self, cmd: Command, n: int) -> None:
        """``T<n>``: the dialect says what it does."""

    def note_once(self, key: str, text: str) -> None:
        if text not in self.trace.notes:
            self.trace.notes.append(text)

    def dirty(self) -> None:
        """The look changed (a head, temperature, fan, flow, spindle... command ran)."""
        self._look = None

    def look(self) -> Look:
        look = self._look
        if look is None:
            look = self._look = self.build_look()
        return look

    def build_look(self) -> Look:
        return Look()

    def end_state(self) -> EndState:
        return EndState()

    # -- pauses and dwells -------------------------------------------------------------------------------

    def pause(self, cmd: Command, n: int) -> None:
        """A pause for the operator (M0, a filament change...): counted until the next working move."""
        self.pauses += 1

    def add_dwell(self, seconds: float | None) -> None:
        if seconds is not None and seconds > 0:
            self.dwell += seconds

    def g4_seconds(self, params: dict) -> float | None:
        """A dwell's length in seconds (the dialect says how S and P count)."""
        return None

    def g4(self, cmd: Command, n: int) -> None:
        self.add_dwell(self.g4_seconds(cmd.params))

    def end_program(self, cmd: Command, n: int) -> None:
        self.ended = True
        self.end_line = n

    # -- positions ---------------------------------------------------------------------------------------

    def machine(self) -> tuple:
        return tuple(self.pos)

    def frame_label(self, i: int = 0) -> str | None:
        """The coordinate frame a move sets axis ``i`` in: the workspace, None for machine coordinates."""
        wcs = self.wcs
        return None if wcs == "G53" else wcs

    def set_frame(self, i: int, label: str | None) -> None:
        if self.frame[i] != label:
            frame = list(self.frame)
            frame[i] = label
            self.frame = tuple(frame)

    def target(self, params: dict, xy: bool = True) -> list[float | None]:
        """The machine position after a move with these words."""
        new = list(self.pos)
        scale = self.scale
        absolute = self.absolute
        for letter in self.AXES:
            if letter in params:
                if not xy and letter in "XY":
                    continue
                i = _AXIS_INDEX[letter]
                try:
                    v = float(params[letter])  # type: ignore[arg-type]
                except (TypeError, ValueError):
                    new[i] = None
                    continue
                if absolute:
                    new[i] = v * scale + self.shift[i] + self.offset[i]
                    self.anchor[i] = self.line
                    label = self.frame_label(i)
                    if self.frame[i] != label:
                        self.set_frame(i, label)
                elif new[i] is not None:
                    new[i] = new[i] + v * scale  # type: ignore[operator]
        return new

    def logical(self, i: int) -> float | None:
        p = self.pos[i]
        return None if p is None else p - self.shift[i] - self.offset[i]

    def clear_shift(self) -> None:
        """G92 offsets cleared (G92.1, Hyrel G93 and G28): program coordinates are machine ones again."""
        self.shift = [0.0] * 5

    def set_position(self, cmd: Command, n: int) -> None:
        """G92: the current point gets these values (the machine does not move)."""
        params = cmd.params
        for letter in self.AXES:
            if letter in params:
                i = _AXIS_INDEX[letter]
                v = number(params[letter])
                if v is None:
                    continue
                machine = self.pos[i]
                if machine is None:  # an unknown place gets a known name: count from here
                    self.pos[i] = machine = v * self.scale
                self.shift[i] = machine - v * self.scale - self.offset[i]
                self.anchor[i] = self.line
                self.set_frame(i, self.frame_label(i))
        ext = self.EXTRUDER
        if ext is not None and ext in params:
            v = number(params[ext])
            self.e_pos = v * self.e_scale() if v is not None else None

    def e_scale(self) -> float:
        return self.scale

    def units(self, cmd: Command, n: int) -> None:
        self.scale = INCH if cmd.code == "G20" else 1.0
        if cmd.code == "G20":
            self.inch_used = True

    def positioning(self, cmd: Command, n: int) -> None:
        self.absolute = cmd.code == "G90"
        if self.E_FOLLOWS_G90:
            self.e_absolute = self.absolute

    def e_mode(self, cmd: Command, n: int) -> None:
        self.e_absolute = cmd.code == "M82"

    def set_plane(self, cmd: Command, n: int) -> None:
        self.plane = int(cmd.code[1:])  # type: ignore[index]

    def workspace(self, cmd: Command, n: int) -> None:
        self.wcs = cmd.code
        self.dirty()

    def home_axes(self, axes: str) -> None:
        """Homing: the listed axes go to machine 0 and their offsets are cleared."""
        for letter in axes:
            i = _AXIS_INDEX[letter]
            self.pos[i] = 0.0
            self.shift[i] = 0.0
            self.anchor[i] = self.line
            self.set_frame(i, None)  # home is a machine position

    def forget(self, axes: str) -> None:
        for letter in axes:
            self.pos[_AXIS_INDEX[letter]] = None

    # -- extrusion ---------------------------------------------------------------------------------------

    def extrusion(self, params: dict, rapid: bool) -> float | None:
        """The E advance of a move (> 0 deposits; updates the E position); None when the move has no E."""
        ext = self.EXTRUDER
        if ext is None or ext not in params:
            return None
        text = params[ext]
        v = number(text)
        if v is None:
            self.e_pos = None
            if text and ":" in text:
                # "Tools are driven using multiple values in the E field of G1 commands, each controlling the
                # corresponding drive" (RepRap page, M563; M160): the move deposits every drive's amount
                amounts = [number(part) for part in text.split(":")]
                if all(a is not None for a in amounts):
                    return sum(amounts) * self.e_scale()  # type: ignore[misc]
            return None
        v *= self.e_scale()
        if self.e_absolute:
            delta = v - self.e_pos if self.e_pos is not None else v
            self.e_pos = v
        else:
            delta = v
            if self.e_pos is not None:
                self.e_pos += v
        return delta

    # -- motion ------------------------------------------------------------------------------------------

    def cutting(self) -> bool:
        """A spindle or laser runs: every feed move is a working move, as in a CNC job (a Marlin spindle or
        laser job, research/dialects.md 1.2 M3/M4)."""
        return False

    def g0(self, cmd: Command, n: int) -> Move | None:
        return self.motion("G0", cmd.params, n)

    def g1(self, cmd: Command, n: int) -> Move | None:
        return self.motion("G1", cmd.params, n)

    def motion(self, mode: str, params: dict, n: int) -> Move | None:
        rapid = mode == "G0"
        self.motion_mode = mode
        f = params.get("F")
        feed = self.feed
        if f is not None:
            value = number(f)
            value = value * self.scale if value is not None else None
            if not rapid or self.G0_FEED == "modal":
                self.feed = feed = value
            elif self.G0_FEED == "one-shot":
                feed = value
            else:  # LinuxCNC: F sets the feed of later moves, the rapid itself ignores it
                self.feed = value
        start = self.machine()
        self.pos = self.target(params)
        delta = self.extrusion(params, rapid)
        if rapid and not self.G0_EXTRUDES:
            delta = None if delta is None else min(delta, 0.0)
        return self.sync(start, None, delta, None if rapid and self.G0_FEED != "modal" else feed, rapid)

    def sync(self, start: tuple, arc, delta, feed, rapid: bool, native: bool = False) -> Move | None:
        """A move ran: a synchronisation point when it prints (or, in a CNC job, when it is a feed move)."""
        end = self.machine()
        if end == start and arc is None:
            return None  # no motion (an extruder-only move, or a feed word)
        printing = native or (delta is not None and delta > 1e-9)
        if not printing and (rapid or not (self.cnc or self.cutting())):
            return None
        e = NATIVE if native else (delta if printing else None)
        move = Move(self.line, start, end, arc, e, feed, self.look(), rapid, self.frame, tuple(self.anchor))
        if self.pauses or self.dwell:
            move.pauses, move.dwell = self.pauses, self.dwell
            self.pauses, self.dwell = 0, 0.0
        return move

    def arc(self, cmd: Command, n: int) -> Move | None:
        """G2/G3: the end point and the circle (for the path check); the plane's centre words."""
        params = cmd.params
        self.motion_mode = cmd.code
        plane = self.plane if self.plane in _PLANES else 17
        a, b, ia, ib = _PLANES[plane]
        f = params.get("F")
        if f is not None:
            value = number(f)
            self.feed = value * self.scale if value is not None else None
        start = self.machine()
        self.pos = self.target(params)
        delta = self.extrusion(params, False)
        arc = None
        i_a, i_b = _AXIS_INDEX[a], _AXIS_INDEX[b]
        sa, sb = start[i_a], start[i_b]
        if sa is not None and sb is not None:
            r = number(params.get("R")) if "R" in params else None
            if r is not None and self.pos[i_a] is not None and self.pos[i_b] is not None:
                centre = _centre_from_radius(
                    self.pos[i_a] - sa,  # type: ignore[operator]
                    self.pos[i_b] - sb,  # type: ignore[operator]
                    r * self.scale,
                    cmd.code == "G2",
                )
            elif r is None:
                centre = ((number(params.get(ia)) or 0.0) * self.scale, (number(params.get(ib)) or 0.0) * self.scale)
            else:
                centre = None
            if centre is not None:
                cu, cv = sa + centre[0], sb + centre[1]
                clockwise = cmd.code == "G2"
                ea, eb = self.pos[i_a], self.pos[i_b]
                a0 = math.atan2(sb - cv, sa - cu)
                a1 = math.atan2(eb - cv, ea - cu) if ea is not None and eb is not None else a0
                turn = (a0 - a1) if clockwise else (a1 - a0)  # the way round, in the arc's direction
                turn %= 2 * math.pi
                if turn < 1e-9:
                    turn = 2 * math.pi  # the same start and end: a full circle
                turn += 2 * math.pi * self.extra_turns(params)
                arc = (plane, (cu, cv), math.hypot(centre[0], centre[1]), clockwise, a0, turn)
        native = self.arc_native(params)
        return self.sync(start, arc, delta, self.feed, False, native=native)

    def extra_turns(self, params: dict) -> int:
        """Full circles an arc makes before its end (Marlin, RepRapFirmware: P is the number of extra
        circles; LinuxCNC counts P turns, P1 being the plain arc)."""
        p = number(params.get("P"))
        return int(p) if p is not None and p >= 1 else 0

    def arc_native(self, params: dict) -> bool:
        """Whether an arc prints with a flow the machine computes itself (Hyrel: arcs with E)."""
        return False


def _centre_from_radius(dx: float, dy: float, radius: float, clockwise: bool) -> tuple[float, float] | None:
    """The centre offset of an R-form arc (the grbl/LinuxCNC formula; a negative R takes the long way)."""
    chord2 = dx * dx + dy * dy
    if chord2 == 0:
        return None
    disc = 4 * radius * radius - chord2
    if disc < -1e-6:
        return None
    h = -math.sqrt(max(disc, 0.0)) / math.sqrt(chord2)
    if not clockwise:
        h = -h
    if radius < 0:
        h = -h
    return (dx - dy * h) / 2, (dy + dx * h) / 2
