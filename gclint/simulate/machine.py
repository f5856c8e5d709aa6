"""The reader of meaning: what a job makes its machine do, line by line, as typed events.

The part every dialect shares lives here: the line loop (which commands of a line run, and in what order), positions
(units, absolute/relative, G92 offsets, workspaces), arcs (their centre modes and turns), the extruder, dwells, and
the events (``gclint.simulate.events``).  Every fact that differs between dialects is the dialect's
(``gclint.dialects.semantics``: G4's units, what G0 does with E and F, G28, T...).  A dialect's simulator
(fdm.py, cnc.py, hyrel.py) subclasses ``Simulator`` for what a machine's devices are (heads, beds, fans,
spindles, lasers) and says how its state looks in Hyrel terms (``build_look``, ``end_state``).

``events`` yields every event (the summary and the toolpath read those); ``run`` yields the synchronisation points
the meaning diff compares.  Nothing here comes from the translator: the translator writes, this reads, so that
where the two disagree the diff shows it.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterator

from gclint.dialects.base import Dialect
from gclint.dialects.semantics import number
from gclint.simulate.events import LAYER_MARKS, Dwell, Event, Heat, Ignored, Layer, Pause, ProgramEnd, Stop, ToolChange
from gclint.simulate.trace import NATIVE, EndState, Look, Mapping, Move, Trace
from gclint.syntax.fastpath import PLAIN_MOVE
from gclint.syntax.nodes import ASSIGNMENT, GCODE, IMPLICIT, META, OWORD, Command
from gclint.syntax.parse import PARSE_LIMIT, code_before_long_comment
from gclint.syntax.source import Source

INCH = 25.4
_AXIS_INDEX = {"X": 0, "Y": 1, "Z": 2, "A": 3, "B": 4}
_MOTION = frozenset({"G0", "G1", "G2", "G3", None})
# the effects that set a temperature: (what is heated, whether the machine waits)
_HEAT = {
    "set-head-temperature": ("head", False),
    "wait-head-temperature": ("head", True),
    "set-bed-temperature": ("bed", False),
    "wait-bed-temperature": ("bed", True),
    "set-chamber-temperature": ("chamber", False),
    "wait-chamber-temperature": ("chamber", True),
}
_PLANES = {17: ("X", "Y", "I", "J"), 18: ("Z", "X", "K", "I"), 19: ("Y", "Z", "J", "K")}
_LAYER_MARKS = tuple((kind, re.compile(pattern)) for kind, pattern in LAYER_MARKS)


def layer_mark(raw: str) -> tuple[str, float | None] | None:
    """The slicer's layer mark a comment line is (``events.LAYER_MARKS``): its kind and the height it states; None
    when it is none."""
    if "LAYER" not in raw and "layer" not in raw:
        return None
    for kind, pattern in _LAYER_MARKS:
        m = pattern.fullmatch(raw)
        if m is not None:
            return kind, number(m.group(1)) if m.groups() else None
    return None


class Simulator:
    """Runs one job; ``events`` yields everything it does, ``run`` its synchronisation points (``Move``), then
    ``trace`` holds the rest."""

    def __init__(self, dialect: Dialect, mapping: Mapping | None = None, *, cnc: bool = False) -> None:
        self.dialect = dialect
        facts = self.facts = dialect.semantics
        self.extruder = facts.extruder  # the word that drives the extruder (Machinekit: A; CNC: None)
        self.axes = "".join(a for a in "XYZAB" if a != facts.extruder)  # the axes that are positions
        self._axis_of = {a: _AXIS_INDEX[a] for a in self.axes}
        self._names: dict = {}  # tool -> its name (``named``)
        self.g0_feed = facts.g0_feed
        self.g0_extrudes = facts.g0_extrudes
        self.feed_on_any = facts.feed_on_any_command
        self.mapping = mapping if mapping is not None else Mapping()
        self.cnc = cnc  # synchronise on every feed move (CNC jobs), not only on printing moves
        self.trace = Trace()
        self.arc_absolute = False  # G90.1: I J K are absolute (LinuxCNC)
        self.listening = False  # ``events``: every move and event is wanted, not only the synchronisation points
        self._events: list[Event] = []
        self.line_count = 0  # lines read (when the file is done)
        self._point: tuple = (None,) * 5  # (``events``) where the last move ended, in the job's coordinates
        self._tool: str | None = None  # (``events``) the working tool last announced
        self.handlers: dict[str, Callable[[Command, int], Move | None]] = self.table()
        shared = {"dwell": self.g4, "arc-absolute": self.arc_mode, "arc-relative": self.arc_mode}
        for code, effect in facts.effects.items():
            if effect in shared:  # (what every machine does the same way, wherever its table leaves it out)
                self.handlers.setdefault(code, shared[effect])
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
        # what F words count in: the units in force, except where the dialect reads a line's F before its G20/G21 run
        # (``Semantics.words_first``: LinuxCNC's "Set feed rate (F)" comes before "Set length units"): the units in
        # force before the line, until the line is done
        self.feed_scale = 1.0
        self._feed_first = "F" in facts.words_first
        self.absolute = True
        self.e_absolute = True
        self.e_pos: float | None = 0.0
        self.feed: float | None = None  # modal feed of working moves, mm/min
        self.plane = 17
        self.motion_mode: str | None = None
        self.wcs: str | None = facts.default_workspace
        self.inch_used = False
        self.ended = False  # the end of program ran: nothing after it runs
        self.end_line = 0
        self.line = 0
        self._look: Look | None = None
        self.pauses = 0  # pauses and dwell since the last synchronisation point (compared there)
        self.dwell = 0.0
        self.spiral = False  # (while a model's spiral handler runs) the move is a spiral: a move even in place
        # (``events``) counts changes of what a tool name covers (``heads_of``): a reader of the events asks again
        self.membership = 0

    # -- the loop --------------------------------------------------------------------------------------

    def table(self) -> dict[str, Callable[[Command, int], Move | None]]:
        return {}

    def run(self, source: Source) -> Iterator[Move]:
        """The synchronisation points of the job (its working moves, with the pauses and dwells before each)."""
        for event in self._read(source):
            if type(event) is Move:
                yield event

    def events(self, source: Source) -> Iterator[Event]:
        """Every event of the job, in the order the machine runs them: each move (``Move``: working or not,
        rapid or not), dwell, pause, set-point (``Heat``), command that does not run (``Ignored``) and the end
        of the program."""
        self.listening = True
        yield from self._read(source)

    def read_job(self, source: Source) -> None:
        """Before the first line: what the job's own settings say of its machine (gclint.machine.job_settings)."""

    def _read(self, source: Source) -> Iterator[Event]:
        self.read_job(source)
        handlers = self.handlers
        plain_match = PLAIN_MOVE.fullmatch
        plain = self.plain_moves()
        facts = self.facts
        pending = self._events
        marks = self.listening  # (``events``: a slicer's layer marks are events too)
        fast = self.listening and plain and self.fast_plain()
        n = 0
        for chunk in source.chunks():
            for raw, _ending in chunk:
                n += 1
                if self.ended:
                    continue
                self.line = n
                if marks and raw[:1] == ";":
                    mark = layer_mark(raw)
                    if mark is not None:
                        yield Layer(n, *mark)
                        continue
                if plain and raw[:1] == "G":
                    m = plain_match(raw)
                    if m is not None and fast and self.plain_now():
                        move = self.plain_event(m.groups(), n)
                        if move is not None:
                            yield move
                        if pending:
                            yield from pending
                            pending.clear()
                        continue
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
                        if pending:
                            yield from pending
                            pending.clear()
                        continue
                if len(raw) > PARSE_LIMIT:  # one trailing comment made it too long: its commands run
                    raw = code_before_long_comment(raw) or raw
                written = facts.parse(raw).commands  # (LinuxCNC ignores blanks: X 2 0 is X20)
                commands = facts.running(written)
                if len(commands) < len(written) and self.listening:
                    for cmd in facts.ignored(written):
                        pending.append(Ignored(n, cmd.code, "only the first command of a line runs"))
                if facts.words_first:
                    self.line_words(commands, n)
                last = len(commands) - 1
                for k, cmd in enumerate(commands):
                    if self.ended:
                        break
                    if self.feed_on_any and "F" in cmd.params and cmd.code not in _MOTION:
                        f = number(cmd.params["F"])
                        if f is not None:
                            self.feed = f * self.feed_scale
                    handler = handlers.get(cmd.code)
                    if handler is not None:
                        move = handler(cmd, n)
                    else:
                        move = self.other(cmd, n)
                    if self.listening:
                        if cmd.code in facts.effects:
                            heat = _HEAT.get(facts.effects[cmd.code])
                            if heat is not None:
                                self.heat_event(cmd, n, *heat)
                        tool = self.tool_name()
                        if tool != self._tool:
                            self._tool = tool
                            pending.append(ToolChange(n, tool))
                    if move is not None:
                        if k < last:
                            move.tail = True
                        yield move
                    if pending:
                        yield from pending
                        pending.clear()
                self.feed_scale = self.scale
        self.line_count = n
        end = self.end_state()
        if end is not self.trace.end:
            end.pauses, end.dwell = self.pauses, self.dwell
        self.trace.end = end
        self.trace.end.line = self.end_line or n
        if self.listening:
            yield ProgramEnd(self.trace.end.line, self.ended)

    def line_words(self, commands: tuple, n: int) -> None:
        """LinuxCNC sets a line's feed, speed and tool before its commands run ("G-code Order of Execution"):
        the F, S and T words wherever they are on the line (not G4's P, not a motion's S on a laser)."""
        for cmd in commands:
            params = cmd.params
            if "F" in params and cmd.code not in _MOTION:
                f = number(params["F"])
                if f is not None:
                    self.feed = f * self.feed_scale

    def emit(self, event: Event) -> None:
        """An event for ``events`` (not for ``run``: the diff reads the moves and the trace)."""
        if self.listening:
            self._events.append(event)

    # -- set-points, in the dialect's own terms (``events``) ---------------------------------------------------

    def heat_event(self, cmd: Command, n: int, kind: str, wait: bool) -> None:
        value = self.heat_value(cmd, wait)
        if value is None:
            return
        self.emit(Heat(n, self.heat_device(cmd, kind), kind, value, wait and self.waits(cmd)))

    def heat_value(self, cmd: Command, wait: bool) -> float | None:
        """The set-point a temperature command gives (the dialect's words: ``Semantics.set_point``)."""
        return self.facts.set_point(cmd.params, wait)[0]

    def heat_device(self, cmd: Command, kind: str) -> str:
        """What a temperature command heats: its tool (the dialect's word for it, else the active one), the bed
        or the chamber."""
        if kind != "head":
            return kind
        word = self.facts.set_point(cmd.params, False)[1]
        tool = number(cmd.params.get(word)) if word is not None else None
        if tool is not None and tool == int(tool) and tool >= 0:
            return self.tool_label(int(tool))
        return self.tool_name()

    def waits(self, cmd: Command) -> bool:
        """Whether a wait command waits here (Hyrel's W0 waits at M116 instead)."""
        return True

    def tool_label(self, tool: int | None) -> str:
        return "extruder 0" if tool is None else f"extruder {tool}"

    def tool_name(self) -> str:
        """The working tool in the dialect's own terms."""
        return self.named(None)

    def named(self, tool) -> str:
        """``tool_label(tool)``, made once per tool (every move asks)."""
        name = self._names.get(tool)
        if name is None:
            name = self._names[tool] = self.tool_label(tool)
        return name

    def heads_of(self, name: str) -> tuple[str, ...]:
        """The heads a working tool's name (``tool_name``) prints with: itself, or the heads of a clone squad
        (Hyrel).  It may change when ``membership`` does."""
        return (name,)

    def tool_title(self, name: str) -> str:
        """A tool's name (``tool_name``) as a legend says it."""
        return name

    def located(self, move: Move) -> Move:
        """(``events``) ``move`` with its tool and where it starts and ends in the job's coordinates."""
        move.tool = self.tool_name()
        move.origin = self._point  # (as the job wrote it: a tool change between does not move the point)
        pos, shift, offset = self.pos, self.shift, self.offset
        x, y, z, a, b = pos
        self._point = move.point = (
            None if x is None else x - shift[0] - offset[0],
            None if y is None else y - shift[1] - offset[1],
            None if z is None else z - shift[2] - offset[2],
            None if a is None else a - shift[3] - offset[3],
            None if b is None else b - shift[4] - offset[4],
        )
        return move

    def placed(self) -> None:
        """(``events``) Homing or G92 named the current position anew: the next move starts there."""
        if self.listening:
            self._point = tuple(self.logical(i) for i in range(5))

    def plain_moves(self) -> bool:
        """Whether plain G0/G1 lines (X Y Z E F numbers only) may go straight to ``motion``."""
        return self.handlers.get("G1") == self.g1 and self.handlers.get("G0") == self.g0

    def fast_plain(self) -> bool:
        """Whether ``events`` may read plain G0/G1 lines by ``plain_event`` (while ``plain_now``): a machine whose
        G0 extrudes and shares G1's modal F, whose extruder is E, and whose ``motion`` is the one here or does the
        same for such lines (a simulator says so by overriding this and ``plain_now``)."""
        return (
            type(self).motion is Simulator.motion
            and self.g0_feed == "modal"
            and self.g0_extrudes
            and self.extruder == "E"
        )

    def plain_now(self) -> bool:
        """Whether the state lets ``plain_event`` read the next plain line (``fast_plain``)."""
        return True

    def plain_event(self, words: tuple, n: int) -> Move | None:
        """``motion`` for a plain G0/G1 line (``syntax.fastpath.PLAIN_MOVE``'s groups), as ``motion``, ``target``
        and ``extrusion`` do it, without a dictionary of words: the same state and the same events, faster
        (``tests/test_reader_plain_events.py`` compares the two on the corpus)."""
        digit, f_first, x, y, z, e, f = words
        rapid = digit == "0"
        self.motion_mode = "G0" if rapid else "G1"
        if f is None:
            f = f_first
        scale = self.scale
        if f is not None:
            self.feed = float(f) * self.feed_scale
        pos = self.pos
        start = tuple(pos)
        if x is not None or y is not None or z is not None:
            new = list(pos)
            if self.absolute:
                shift, offset, anchor = self.shift, self.offset, self.anchor
                for i, text in ((0, x), (1, y), (2, z)):
                    if text is not None:
                        new[i] = float(text) * scale + shift[i] + offset[i]
                        anchor[i] = n
                        label = self.frame_label(i)
                        if self.frame[i] != label:
                            self.set_frame(i, label)
            else:
                for i, text in ((0, x), (1, y), (2, z)):
                    if text is not None and new[i] is not None:
                        new[i] = new[i] + float(text) * scale  # type: ignore[operator]
            self.pos = new
        delta = None
        if e is not None:
            v = float(e) * self.e_scale()
            if self.e_absolute:
                e_pos = self.e_pos
                delta = v - e_pos if e_pos is not None else v
                self.e_pos = v
            else:
                delta = v
                if self.e_pos is not None:
                    self.e_pos += v
        return self.sync(start, None, delta, self.feed, rapid)

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
                self.feed = f * self.feed_scale
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
        self.emit(Pause(n, cmd.code))

    def add_dwell(self, seconds: float | None) -> None:
        if seconds is not None and seconds > 0:
            self.dwell += seconds

    def g4(self, cmd: Command, n: int) -> None:
        # the dialect says what P and S count (gclint.dialects.semantics.Dwell)
        rule = self.facts.dwell
        if rule.refused(cmd.params):
            # the interpreter refuses the line ("Dwell time missing with g4", LinuxCNC): the program stops here
            self.emit(
                Stop(n, "G4", f"G4 without {rule.required}: the interpreter refuses the line and stops the program")
            )
            self.end_program(cmd, n)
            return
        seconds = rule.seconds(cmd.params)
        self.add_dwell(seconds)
        self.emit(Dwell(n, seconds))

    def arc_mode(self, cmd: Command, n: int) -> None:
        """G90.1 / G91.1: I, J and K absolute, or offsets from the start (LinuxCNC, "Arc Distance Mode")."""
        self.arc_absolute = cmd.code == "G90.1"

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
        axis_of = self._axis_of
        for letter, text in params.items():
            i = axis_of.get(letter)
            if i is None or (i < 2 and not xy):
                continue
            try:
                v = float(text)
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
        for letter in self.axes:
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
        ext = self.extruder
        if ext is not None and ext in params:
            v = number(params[ext])
            self.e_pos = v * self.e_scale() if v is not None else None
        self.placed()

    def e_scale(self) -> float:
        return self.scale

    def units(self, cmd: Command, n: int) -> None:
        self.scale = INCH if cmd.code == "G20" else 1.0
        if not self._feed_first:
            self.feed_scale = self.scale  # (else when the line is done: ``_read``)
        if cmd.code == "G20":
            self.inch_used = True

    def positioning(self, cmd: Command, n: int) -> None:
        self.absolute = cmd.code == "G90"
        if self.facts.e_follows_g90:
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
        self.placed()

    def forget(self, axes: str) -> None:
        for letter in axes:
            self.pos[_AXIS_INDEX[letter]] = None
        self.placed()

    # -- extrusion ---------------------------------------------------------------------------------------

    def extrusion(self, params: dict, rapid: bool) -> float | None:
        """The E advance of a move (> 0 deposits; updates the E position); None when the move has no E."""
        ext = self.extruder
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
                known = [a for a in amounts if a is not None]
                if len(known) == len(amounts):
                    return sum(known) * self.e_scale()
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
        laser job, Marlin G-code reference, M3-M4)."""
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
            value = value * self.feed_scale if value is not None else None
            if not rapid or self.g0_feed == "modal":
                self.feed = feed = value
            elif self.g0_feed == "one-shot":
                feed = value
            else:  # LinuxCNC: F sets the feed of later moves, the rapid itself ignores it
                self.feed = value
        start = self.machine()
        self.pos = self.target(params)
        delta = self.extrusion(params, rapid)
        if rapid and not self.g0_extrudes:
            delta = None if delta is None else min(delta, 0.0)
        if rapid and self.g0_feed != "modal":
            # a one-shot F is this rapid's own speed (Hyrel, Carvera); without one, and on LinuxCNC, the rapid runs
            # at the machine's rapid speed, which the file does not say
            feed = value if f is not None and self.g0_feed == "one-shot" else None
        return self.sync(start, None, delta, feed, rapid)

    def sync(self, start: tuple, arc, delta, feed, rapid: bool, native: bool = False) -> Move | None:
        """A move ran: a synchronisation point when it prints (or, in a CNC job, when it is a feed move)."""
        end = self.machine()
        listening = self.listening
        spiral = self.spiral
        if end == start and arc is None and not spiral:
            if listening and delta:  # an extruder-only move (a retraction, a prime): an event
                self._events.append(
                    self.located(Move(self.line, start, end, None, delta, feed, self.look(), rapid, working=False))
                )
            return None  # no motion (an extruder-only move, or a feed word)
        printing = native or (delta is not None and delta > 1e-9)
        if not printing and (rapid or not (self.cnc or self.cutting())):
            if listening:  # a travel move: an event, not a synchronisation point
                travel = Move(
                    self.line, start, end, arc, delta, feed, self.look(), rapid, self.frame, tuple(self.anchor), False
                )
                travel.spiral = spiral
                self._events.append(self.located(travel))
            return None
        e = NATIVE if native else (delta if printing else None)
        move = Move(self.line, start, end, arc, e, feed, self.look(), rapid, self.frame, tuple(self.anchor))
        move.spiral = spiral
        if listening:
            self.located(move)
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
            self.feed = value * self.feed_scale if value is not None else None
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
                    self.pos[i_a] - sa,
                    self.pos[i_b] - sb,
                    r * self.scale,
                    cmd.code == "G2",
                )
            elif r is None:
                centre = ((number(params.get(ia)) or 0.0) * self.scale, (number(params.get(ib)) or 0.0) * self.scale)
                if self.arc_absolute:  # G90.1: I J K are the centre's program coordinates, not offsets
                    centre = (
                        centre[0] + self.shift[i_a] + self.offset[i_a] - sa,
                        centre[1] + self.shift[i_b] + self.offset[i_b] - sb,
                    )
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
        """Full circles an arc makes before its end: P extra circles (Marlin, RepRapFirmware), P turns with P1
        the plain arc (LinuxCNC), none where P is no word of G2/G3 (the dialect's ``arc_turns``)."""
        p = number(params.get("P"))
        if p is None or p < 1:
            return 0
        turns = self.facts.arc_turns
        if turns == "extra":
            return int(p)
        if turns == "turns":
            return int(p) - 1
        return 0

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
