"""HY motion rules: what G0/G1 mean on Hyrel, units, motors, axes, offsets and probing.

Sources: the Hyrel Gcode page ("Controlling Movement", "Controlling Position and Offsets", "Other
Commands"), the hidden-codes page Sekret! (G38) and the Hyrel firmware source; see docs/sources.md.

G0/G1 lines are the hot path (millions per job).  The rules that look at them (``MoveRule``) do not each
listen to G0/G1: they join the file's ``MoveChecks``, a G0/G1 listener declared to the engine
(``rules.base.MoveListener``, ``FileContext.move_listener``), which the engine calls once per G0/G1 line and
which calls a rule only when the line has what that rule cares about (an E word, an S word, motors
off...), so an ordinary G1 costs a few dict lookups in total; the engine asks it (``wants_plain``,
``wants_in_run``) which plain moves and lines of runs it must read.  Rules in other modules (flow.py) join
the same way.
"""

from __future__ import annotations

from itertools import chain, count, islice
from math import inf
from typing import ClassVar, Protocol

from gclint.machine.state import NATIVE
from gclint.rules.base import MoveListener, Rule, RunFinding, Severity, register
from gclint.syntax.fastpath import (
    E_NOT_FORWARD,
    PLAIN_NUMBER,
    RUN_G0_E,
    RUN_G1_E_FIRST,
    run_amounts,
    run_line_starts,
)
from gclint.syntax.nodes import Command, Line, to_number

_ARCS = ("G2", "G3", "G2.1", "G3.1", "G2.2", "G3.2", "G2.3", "G3.3")


def _moves_axis(params: dict) -> bool:
    return "X" in params or "Y" in params or "Z" in params or "A" in params or "B" in params


class _Member(Protocol):
    def move(self, line: Line, cmd: Command) -> None: ...


# MoveChecks' slots, one per member rule
_SLOTS = (
    "rapid_e",
    "travel_prints",
    "relative_print",
    "flow_multiplier",
    "motors_off",
    "axis_on_model",
    "feed_undefined",
    "inverse_time",
    "slicer_e",
)


class MoveChecks(MoveListener):
    """The G0/G1 checks of the Hyrel rules of one file, run in one call per line: the file's listener of
    this kind (``ctx.move_listener(MoveChecks)``, ``rules.base.MoveListener``), which the engine calls for
    G0/G1 lines and asks about plain moves and runs.

    Each slot holds the rule to call, or None when the rule is not enabled or has nothing left to look
    for (rules clear and set their own slot).
    """

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.rapid_e: RapidMoveWithE | None = None  # HY030: G0 with E
        self.travel_prints: TravelMarkedPrinting | None = None  # HY031: native-flow G1 with E
        self.relative_print: PrintingInRelativeMode | None = None  # HY032: G1 with E under G91
        self.flow_multiplier: _Member | None = None  # HY033: G1 S
        self.motors_off: MotionAfterMotorsOff | None = None  # HY039: any move after M18/M84
        self.axis_on_model: AxisNotOnModel | None = None  # HY042: A/B words
        self.feed_undefined: G1FeedUndefined | None = None  # HY050: G1 before any working F
        self.inverse_time: NonModalG53OrInverseTime | None = None  # HY053: only while watching a G93
        self.slicer_e: _Member | None = None  # HY060: E amounts that look sliced

    def join(self, rule: Rule, slot: str | None = None) -> None:
        """Make ``rule`` a member, called from ``move`` while it holds ``slot`` (None: the rule sets its
        slot itself when it has something to look for, as HY053 does while it watches a G93)."""
        super().join(rule)
        if slot is not None:
            setattr(self, slot, rule)

    def drop(self, rule: Rule) -> None:
        super().drop(rule)
        for slot in _SLOTS:
            if getattr(self, slot) is rule:
                setattr(self, slot, None)

    def release(self) -> None:
        super().release()
        for slot in _SLOTS:
            setattr(self, slot, None)

    def wants_plain(self, mode: str, x: str | None, y: str | None, z: str | None, e: str | None, f: str | None) -> bool:
        """Whether ``move`` would call a member for a plain move (a G0/G1 with only X Y Z E F words,
        given as source texts or None): the engine builds the line's tree only then.  Mirrors
        ``move`` for lines without S, A or B; tests/test_plain_moves.py checks that they agree."""
        st = self.state
        motors_off = self.motors_off
        if motors_off is not None and st.motors_off_line is not None and st.motors_off_line != motors_off.reported_for:
            return True
        if mode == "G1":
            if e is not None:
                travel = self.travel_prints
                if (
                    travel is not None
                    and st.flow_mode == NATIVE
                    and ((x is None and y is None) or not _prints_forward(st, travel, e))
                ):
                    return True
                if self.relative_print is not None and not st.absolute and not self.relative_print.reported:
                    return True
                if self.slicer_e is not None:
                    return True
            if self.feed_undefined is not None and not st.working_feed_set:
                return True
            return self.inverse_time is not None
        return e is not None and self.rapid_e is not None

    def wants_in_run(self, text: str, start: int, end: int) -> list[int | RunFinding] | None:
        """The starts of the lines of a run (``text[start:end]``, whole lines of plain moves, comments and
        empty lines: gclint.runs) whose moves ``wants_plain`` may want, in any order, or None when it may
        want any move of the run.  Decided with the state at the run's start: the engine reads the lines
        given on their own, and what reading them changes (a member clearing its slot, the working feed
        set) never makes another line of the run wanted.  A line given may be one no member wants.
        HY031's moves come as its findings (``TravelMarkedPrinting.in_run``): while this answers with
        lines, no other member looks at a G1 of a run.  It answers for the members' checks of arcs too
        (HY032, HY039, HY042, HY050, HY053: each looks at a plain arc of a run only where it answers None)."""
        st = self.state
        motors_off = self.motors_off
        relative_print = self.relative_print
        if (
            (
                motors_off is not None
                and st.motors_off_line is not None
                and st.motors_off_line != motors_off.reported_for
            )
            or self.slicer_e is not None  # (every G1 with E, until the amounts look sliced)
            or (self.feed_undefined is not None and not st.working_feed_set)
            or self.inverse_time is not None
            or (relative_print is not None and not st.absolute and not relative_print.reported)
        ):
            return None
        found: list[int | RunFinding] = []
        if self.travel_prints is not None and st.flow_mode == NATIVE:
            found += self.travel_prints.in_run(text, start, end)
        if self.rapid_e is not None:
            found += run_line_starts(RUN_G0_E, text, start, end)
        return found

    def move(self, line: Line, cmd: Command) -> None:
        """The G0/G1 hook (the engine's, for every G0/G1 line read): calls each member only when the line has
        what it looks for."""
        p = cmd.params
        st = self.state
        if cmd.code == "G1":
            if "E" in p:
                travel = self.travel_prints
                if travel is not None and st.flow_mode == NATIVE:
                    e = p["E"]
                    if e is None or not ("X" in p or "Y" in p) or not _prints_forward(st, travel, e):
                        travel.move(line, cmd)
                if self.relative_print is not None and not st.absolute and not self.relative_print.reported:
                    self.relative_print.move(line, cmd)
                if self.slicer_e is not None:
                    self.slicer_e.move(line, cmd)
            if self.feed_undefined is not None and not st.working_feed_set:
                self.feed_undefined.move(line, cmd)
            if "S" in p and self.flow_multiplier is not None:
                self.flow_multiplier.move(line, cmd)
            if self.inverse_time is not None:
                self.inverse_time.move(line, cmd)
        elif "E" in p and self.rapid_e is not None:
            self.rapid_e.move(line, cmd)
        motors_off = self.motors_off
        if motors_off is not None and st.motors_off_line is not None and st.motors_off_line != motors_off.reported_for:
            motors_off.move(line, cmd)
        if self.axis_on_model is not None and ("A" in p or "B" in p):
            self.axis_on_model.move(line, cmd)


def _prints_forward(st, travel: TravelMarkedPrinting, e: str) -> bool:
    """Whether a G1 with X or Y and this E text is a move HY031 finds fine (it extrudes forward), decided
    without a call to the rule for the common moves: a positive relative amount (slicers, M83), the
    same amount as the last good move while the E position still equals it (native jobs write E1 on
    every printing move), or an absolute E that goes forward (slicers, M82)."""
    if st.e_absolute:
        if e == travel.fine and st.e_position == travel.fine_value:
            return True
        try:
            value = float(e)
        except ValueError:
            return False
        return value > 0 and (st.e_position is None or value >= st.e_position)
    return e == travel.fine or (e[0] != "-" and bool(e.strip("+0.")))


class MoveRule(Rule):
    """A rule that looks at G0/G1 lines through the file's ``MoveChecks`` (see the module docstring).

    ``slot`` names its place in ``MoveChecks``; ``move(line, cmd)`` is called for G0/G1 lines while the
    slot holds the rule, ``check(line, cmd)`` for the other codes the rule lists (never G0 or G1).
    """

    slot: ClassVar[str | None] = None
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.moves = ctx.move_listener(MoveChecks)
        self.moves.join(self, self.slot)
        # (its arcs in runs: the listener answers for the members' checks of arcs too, wants_in_run)
        self.run_filter = self.moves.wants_in_run

    def move(self, line: Line, cmd: Command) -> None:
        """Called for G0/G1 lines (when the slot is set)."""


# -- G0 / G1 -------------------------------------------------------------------------------------------


@register
class RapidMoveWithE(MoveRule):
    code = "HY030"
    name = "e-on-rapid-move"
    severity = Severity.WARNING
    summary = "E on a G0 rapid move: G0 never prints"
    explanation = """
        On Hyrel, G0 "is a rapid positioning move. It is not a working move, meaning that your equipment
        will not be printing".  An E word on G0 does not make it print (the firmware reports an invalid E
        argument and drops it); slicers for Marlin, where G0 and G1 are the same move, sometimes write
        extruding G0 moves.  Use G1 for a move that should print.
    """
    example_bad = "G0 X20 Y20 E1"
    example_good = "G1 X20 Y20 E1 F1200"
    source = (
        "Gcode page, G0 Rapid Move; Hyrel firmware source, src/GCode.c G_Code_G0_0 (E reported invalid and removed)"
    )
    slot = "rapid_e"

    def move(self, line: Line, cmd: Command) -> None:
        self.report(
            line,
            "G0 is a rapid, non-working move: its E is ignored and nothing prints (use G1 to print)",
            node=cmd.param("E") or cmd,
        )


@register
class TravelMarkedPrinting(MoveRule):
    code = "HY031"
    name = "travel-marked-printing"
    severity = Severity.WARNING
    summary = "In native flow any E makes a G1 print, even a zero or negative amount"
    explanation = """
        In native flow (no `M229 E1`), "the value of Extrusion rate E will be ignored, but E will trigger
        a working or printing move".  A move whose E amount is zero or goes backwards (a slicer's
        retract-while-travelling or wipe) is meant as a travel, but Hyrel prints along it.  A G1 with
        only an E word (a slicer's retract or prime) moves nowhere, so native flow, which dispenses by
        move length, does nothing with it: the head's own unprime/prime settings (M721/M722) do that job.
        Remove E from travel moves, drop E-only lines, or enable E values with `M229 E1 D1`.
    """
    example_bad = """
        G1 X10 Y10 E1 F1200
        G1 X30 Y10 E-0.5
    """
    example_good = """
        G1 X10 Y10 E1 F1200
        G1 X30 Y10
    """
    source = "Gcode page, G1 Working Move"
    slot = "travel_prints"

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        # The E text and value of the last move found fine: the G0/G1 listener skips the call for a move
        # with the same E (and X or Y) while the E position still equals it.
        self.fine: str | None = None
        self.fine_value = 0.0

    def move(self, line: Line, cmd: Command) -> None:
        # called for G1 lines with E while native flow is active
        p = cmd.params
        if not _moves_axis(p):
            self.report(line, _E_ONLY, node=cmd)
            return
        text = p["E"]
        if text is None:
            return
        try:
            value = float(text)
        except ValueError:
            return
        st = self.state
        message = _travel_message(text, value, st.e_absolute, st.e_position)
        if message is None:
            self.fine, self.fine_value = text, value
            return
        self.report(line, message, node=cmd.param("E") or cmd)

    def in_run(self, text: str, start: int, end: int) -> list[RunFinding]:
        """The findings ``move`` would make on the G1 moves of a run (``text[start:end]``, whole lines of
        plain moves, comments, empty lines and M-codes without E: gclint.runs), read one after the other
        from the state at the run's start: no line of a run changes the flow or the E mode, and the E
        position is followed as the moves change it (an absolute E is the position; every move or arc
        of a run with E has a number).  In a move of a run the only letters are its words'."""
        st = self.state
        found: list[RunFinding] = []
        e_only = set()  # (where the E word of each G1 with E and no axis is)
        for at in run_line_starts(RUN_G1_E_FIRST, text, start, end):  # (G1 with E before any X or Y)
            stop = text.find("\n", at)
            if text.find("X", at, stop) < 0 and text.find("Y", at, stop) < 0 and text.find("Z", at, stop) < 0:
                found.append(RunFinding(at, self, 1, 3, _E_ONLY))  # (at the command: "G1", columns 1-3)
                e_only.add(text.find("E", at, stop))
        if st.e_absolute:  # (an amount that goes back from the one before, or is not positive)
            pattern, at = run_amounts(text, start, end)
            amounts = pattern.findall(text, at, end)
            values = list(map(float, amounts))
            last = st.e_position
            before = chain((-inf if last is None else last,), values)
            hits = [i for i, value, previous in zip(count(), values, before) if value <= 0 or value < previous]
            matches = pattern.finditer(text, at, end)
            skipped = 0
            for i in hits:
                at = next(islice(matches, i - skipped, None)).start(1) - 1  # (the i-th amount's E)
                skipped = i + 1
                if at not in e_only:
                    self._at_e(text, start, at, amounts[i], values[i], values[i - 1] if i else last, found)
        else:  # (a negative or zero amount, wherever it is: _at_e skips those of comments, G0 and arcs)
            for m in E_NOT_FORWARD.finditer(text, start, end):
                at = m.start()
                amount = PLAIN_NUMBER.match(text, at + 1)
                if at not in e_only and amount is not None:
                    self._at_e(text, start, at, amount.group(), float(amount.group()), None, found)
        return found

    def _at_e(self, text: str, start: int, at: int, amount: str, value: float, last: float | None, found: list) -> None:
        """Add ``move``'s finding, if any, for the E word at ``at`` (of ``amount``) if it is a G1's that
        moves an axis (the E position before it is ``last``)."""
        line = text.rfind("\n", start, at) + 1 or start
        if text.startswith("G1", line):
            message = _travel_message(amount, value, self.state.e_absolute, last)
            if message is not None:  # (at the E word: its letter and number)
                found.append(RunFinding(line, self, at - line + 1, at - line + 2 + len(amount), message))


_E_ONLY = (
    "G1 with only E does nothing in native flow (no motion, nothing dispensed): the head's "
    "M721/M722 unprime/prime do the retracts; remove it or enable E values with M229 E1 D1"
)


def native_e_message(params, e_absolute: bool, e_position: float | None) -> str | None:
    """HY031's message for a G1 with E in native flow (explain says the same), or None: it prints as meant."""
    if not _moves_axis(params):
        return _E_ONLY
    text = params.get("E")
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return _travel_message(text, value, e_absolute, e_position)


def _travel_message(text: str, value: float, e_absolute: bool, e_position: float | None) -> str | None:
    """HY031's message for a G1 moving an axis with E ``text`` (of ``value``), or None: it extrudes forward."""
    if value <= 0:
        why = f"E{text} extrudes nothing"
    elif e_absolute and e_position is not None and value < e_position:
        why = f"E{text} goes back from E{e_position:g} (a retract while moving)"
    else:
        return None
    return f"{why}, but in native flow any E makes this G1 print along the move; remove E to make it a travel"


@register
class PrintingInRelativeMode(MoveRule):
    code = "HY032"
    name = "printing-in-relative-mode"
    severity = Severity.WARNING
    summary = "Printing moves under G91 relative positioning"
    explanation = """
        "Absolute is the default and should be used in the majority of cases; there will be problems with
        an entire model sliced in relative mode.  Relative is intended for special operations like
        drilling holes."  Relative positioning is fine for a bed drop (`G91`, `G0 Z5`, `G90`); printing
        in it is not.  Reported once for each stretch of G91.
    """
    example_bad = """
        G91
        G1 X10 Y0 E1 F1200
    """
    example_good = """
        G90
        G1 X10 Y0 E1 F1200
    """
    source = "Gcode page, G1 Working Move and G91 Relative Positioning"
    codes = (*_ARCS, "G90")
    slot = "relative_print"

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.reported = False  # reported in the current stretch of G91

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.code == "G90":
            self.reported = False
        elif "E" in cmd.params and not self.state.absolute:
            self.move(line, cmd)

    def move(self, line: Line, cmd: Command) -> None:
        # called for lines with E under G91; an E-only line (a retract) is not printing a model
        if self.reported or not (_moves_axis(cmd.params) or cmd.code != "G1") or not self._prints(cmd):
            return
        self.reported = True
        self.report(
            line,
            f"{cmd.code} prints in relative positioning (G91): Hyrel expects models in absolute "
            "positioning (G90); relative is meant for special operations",
            node=cmd,
        )

    def _prints(self, cmd: Command) -> bool:
        """Whether the author means the move to print (a zero or negative E is HY031's business)."""
        text = cmd.params["E"]
        if text is None:
            return self.state.flow_mode == NATIVE  # a bare E marks a printing move
        value = to_number(text)
        if value is None:
            return False
        st = self.state
        if st.flow_mode == NATIVE or not st.e_absolute:
            return value > 0  # native jobs write E1 on printing moves
        return st.e_position is None or value > st.e_position


@register
class G1FeedUndefined(MoveRule):
    code = "HY050"
    name = "g1-feed-undefined"
    severity = Severity.WARNING
    summary = "A working move with no feed rate set yet (a G0 F does not count)"
    explanation = """
        "a G0 command will take an F variable as a nonpersistent, one-time velocity setting"; "Only on G0
        is it not persistent".  A G1 (or arc) uses the last F given on a working move.  A job whose only
        F so far was on G0 (as in Marlin files, where G0 F carries over to G1) runs its first working move
        at an unknown speed.  Give F on the first G1.  Reported once per file.
    """
    example_bad = """
        G0 X10 Y10 F3000
        G1 X20 Y10 E1
    """
    example_good = """
        G0 X10 Y10 F3000
        G1 X20 Y10 E1 F1200
    """
    source = "Gcode page, G0 Rapid Move and G1 Working Move"
    codes = _ARCS
    slot = "feed_undefined"

    def check(self, line: Line, cmd: Command) -> None:
        if self.moves.feed_undefined is not None and not self.state.working_feed_set:
            self.move(line, cmd)

    def move(self, line: Line, cmd: Command) -> None:
        # called for G1 lines while no working feed is set
        p = cmd.params
        if "F" in p or not (_moves_axis(p) or cmd.code != "G1"):
            return
        self.moves.feed_undefined = None  # once per file
        self.report(
            line,
            f"{cmd.code} has no feed rate: no F has been given on a working move yet (F on G0 is one-shot); add F",
            node=cmd,
        )


@register
class MotionAfterMotorsOff(MoveRule):
    code = "HY039"
    name = "motion-after-motors-off"
    severity = Severity.ERROR
    summary = "A move after M18/M84 before the axes with homes are homed again"
    explanation = """
        M18 (and M84, which invokes it) cuts power to all motors so the bed and yoke can be pushed by
        hand: "All axes with homes must be rehomed after an M18."  Positions are lost, so a move before
        the axes are homed again goes to the wrong place.  Which axes have homes: X and Y on every
        Hyrel ("G28 sends the X and/or Y axes to the sensor-defined physical home position"), and Z, A
        or B where the job itself homes them ("Z0 ensures that the Z axis is homed"): the pages do not
        say which models have a Z home, and a 30M's own Hyrel header homes X and Y only, so gclint asks
        for `G28 Z0` only in a job that homes Z.  Reported once per M18/M84.
    """
    example_bad = """
        M18
        G0 X10 Y10
    """
    example_good = """
        M18
        G28 X0 Y0
        G0 X10 Y10
    """
    source = "Gcode page, M18 Disengage Motors"
    codes = (*_ARCS, "G81", "G38")
    slot = "motors_off"

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.reported_for: int | None = None  # the M18/M84 line already reported

    def check(self, line: Line, cmd: Command) -> None:
        if self.state.motors_off_line is not None:
            self.move(line, cmd)

    def move(self, line: Line, cmd: Command) -> None:
        st = self.state
        off = st.motors_off_line
        if off == self.reported_for:
            return
        # any move until every axis is homed again: a position lost on one axis (Z) is a crash on another
        self.reported_for = off
        left = " ".join(f"{a}0" for a in "XYZAB" if a in st.axes_to_rehome)
        self.report(
            line,
            f"{cmd.code} after the motors were disengaged (M18/M84 on line {off}): 'All axes with homes must "
            f"be rehomed after an M18'; re-home with G28 {left} before moving",
            node=cmd,
        )


@register
class AxisNotOnModel(MoveRule):
    code = "HY042"
    name = "axis-not-on-model"
    severity = Severity.ERROR
    summary = "An A or B axis word on a printer model without that axis"
    explanation = """
        "All Hyrel printers have built-in support for three axes. Hyrel model 16A and EHR printers may be
        expanded to five."  The 30M and ESR have no A or B axis, so A/B words cannot run there (files
        from Machinekit, where A is the extruder, or from 4th-axis CNC jobs).  Checked wherever the
        pages give a code A and B: moves (G0, G1, the arcs), homing (G28 "A0 ensures that the A axis is
        homed"), G92, G0 speeds (M203 "An is the new speed in the A axis for G0 moves"), fixture offsets
        (G54-G59 "An is the offset in mm in the A axis"), head offsets (M6 "An is the offset in the A
        axis") and probing (G38).  Choose the printer with `--printer` (`ehr`, `16a`, `16a-dual` have
        A/B); the message names the model gclint checked for.
    """
    example_bad = "; gclint-test: printer=30m\nG1 X10 Y10 A90 F1200"
    example_good = "; gclint-test: printer=30m\nG1 X10 Y10 F1200"
    source = "Gcode page, G0 Rapid Move / G1 Working Move note on axes; G28, G92, M203, G54 - G59, M6 parameters"
    codes = (*_ARCS, "G28", "G92", "G38", "M203", *(f"G{n}" for n in range(54, 60)), "M6")
    slot = "axis_on_model"

    def __init__(self, ctx) -> None:
        self.missing = tuple(a for a in ("A", "B") if ctx.on_every_model(lambda p, a=a: a not in p.axes))
        if not self.missing:
            self.codes = ()  # the model has A and B: nothing to check
        super().__init__(ctx)
        if not self.missing:
            self.moves.axis_on_model = None

    def check(self, line: Line, cmd: Command) -> None:
        if self.missing:
            self.move(line, cmd)

    def move(self, line: Line, cmd: Command) -> None:
        for axis in self.missing:
            if axis in cmd.params:
                self.report(
                    line,
                    f"{cmd.code} {axis}: the {self.ctx.profile.name.upper()} has no {axis} axis "
                    f"(only EHR and 16A printers may be expanded to five axes){self.ctx.model_note()}",
                    node=cmd.param(axis) or cmd,
                )


# -- other motion codes ----------------------------------------------------------------------------------


@register
class G10G11Unsupported(Rule):
    code = "HY015"
    name = "g10-g11-unsupported"
    severity = Severity.ERROR
    summary = "G10/G11 are not recognized by Repetrel"
    explanation = """
        "G10 is not recognized by Repetrel.  On some other printers, this will set tool offsets; we do
        this via M6.  On some other printers, this will do a retract; we do this via M721."  Likewise G11
        (unretract) is done with M722.  Marlin firmware retraction, RepRapFirmware tool temperatures
        (`G10 P0 S210`) and LinuxCNC offset tables (`G10 L2 P1 X..`) all have to be rewritten.
    """
    example_bad = "G10"
    example_good = "M721 T0 I1"
    source = "Gcode page, G10 UNUSED and G11 UNUSED"
    codes = ("G10", "G11")
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        p = cmd.params
        if cmd.code == "G11":
            hint = "to prime (unretract) use M722 (M722 T# I1 primes now)"
        elif "L" in p:
            hint = "declare head offsets with M6 T# O.. X.. Y.. Z.., fixture offsets with G54-G59"
        elif "P" in p and ("S" in p or "R" in p):
            hint = "set tool temperatures with M104 T# S.."
        elif "P" in p or _moves_axis(p):
            hint = "declare head offsets with M6 T# O.. X.. Y.. Z.."
        else:
            hint = "to unprime (retract) use M721 (M721 T# I1 unprimes now)"
        self.report(line, f"{cmd.code} is not recognized by Repetrel: {hint}", node=cmd)


@register
class InchUnits(Rule):
    code = "HY026"
    name = "inch-units"
    severity = Severity.WARNING
    summary = "G20 inches are experimental and unsupported on Hyrel"
    explanation = """
        "Working with G20 is experimental and unsupported on Hyrel equipment.  Use at your own risk."
        Convert the job to millimetres (G21, the default).
    """
    example_bad = "G20"
    example_good = "G21"
    source = "Gcode page, G20 Set Units to Inches"
    codes = ("G20",)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        message = "G20 (inches) is experimental and unsupported on Hyrel equipment: use millimetres (G21)"
        self.report(line, message, node=cmd)


@register
class NonModalG53OrInverseTime(MoveRule):
    code = "HY053"
    name = "non-modal-g53-or-inverse-time"
    severity = Severity.WARNING
    summary = "G53 used as a one-line machine-coordinate move, or G93 used as inverse-time feed"
    explanation = """
        Two codes mean something else on Hyrel.  Hyrel's G53 "sets the fixture offsets to (0,0,0,0,0)"
        for all later moves; elsewhere (LinuxCNC, RepRapFirmware, Marlin) `G53 G0 X.. Y..` moves in
        machine coordinates for that line only.  A G53 with axis words or a move on its line is that
        non-modal use (warning).  Hyrel's G93 "clears ALL offsets implemented via G92"; in LinuxCNC and
        Carvera it switches to inverse-time feed, where every move carries its own F.  A G93 followed by
        moves that each give a new F (or by G94) is inverse-time G-code, which Hyrel cannot run (error).
    """
    example_bad = "G53 G0 X0 Y0"
    example_good = """
        G53
        G0 X0 Y0
    """
    source = "Gcode page, G53 Clear Offsets and G93 Clear Coordinate Offsets"
    codes = ("G53", "G93", "G94", "G2", "G3")
    slot = None  # sets MoveChecks.inverse_time only while watching a G93

    # inverse time is assumed when this many working moves after G93 all carry F, with changing values
    _WATCH_MOVES = 5
    _DISTINCT_F = 3

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.g93: Line | None = None  # the G93 being watched
        self.feeds: set[str] = set()
        self.moves_seen = 0
        self.reported_g93: set[int] = set()

    def check(self, line: Line, cmd: Command) -> None:
        code = cmd.code
        if code == "G53":
            self._g53(line, cmd)
        elif code == "G93":
            self.g93, self.feeds, self.moves_seen = line, set(), 0
            self.moves.inverse_time = self
        elif code == "G94":
            if self.g93 is not None:
                self._inverse_time("G94 (units-per-minute feed) follows it")
        elif self.g93 is not None:
            self.move(line, cmd)

    def _g53(self, line: Line, cmd: Command) -> None:
        moves_after = False
        seen = False
        for other in line.commands:
            if other is cmd:
                seen = True
            elif seen and other.code in ("G0", "G1", "G2", "G3"):
                moves_after = True
        if moves_after or _moves_axis(cmd.params):
            self.report(
                line,
                "G53 on Hyrel clears the fixture offsets for all later moves (it is modal, not a one-line "
                "machine-coordinate move): put G53 on its own line and check the moves that follow",
                node=cmd,
            )

    def move(self, line: Line, cmd: Command) -> None:
        # working moves while a G93 is watched
        p = cmd.params
        if not _moves_axis(p):
            return
        f = p.get("F")
        if f is None:
            self._stop()
            return
        self.feeds.add(f)
        self.moves_seen += 1
        if self.moves_seen >= self._WATCH_MOVES:
            if len(self.feeds) >= self._DISTINCT_F:
                self._inverse_time(f"the {self.moves_seen} working moves after it each set their own F")
            self._stop()

    def _stop(self) -> None:
        self.g93 = None
        self.moves.inverse_time = None

    def _inverse_time(self, evidence: str) -> None:
        g93 = self.g93
        if g93 is None or g93.number in self.reported_g93:
            return
        self.reported_g93.add(g93.number)
        cmd = next((c for c in g93.commands if c.code == "G93"), None)
        self.report(
            g93,
            f"G93 looks like inverse-time feed ({evidence}), which Hyrel does not support: on Hyrel G93 only "
            "clears G92 offsets; convert the feeds to mm/min",
            node=cmd,
            severity=Severity.ERROR,
        )
        self._stop()


@register
class G0SpeedLooksLikeMmPerS(Rule):
    code = "HY057"
    name = "g0-speed-looks-like-mm-per-s"
    severity = Severity.WARNING
    summary = "M203 X/Y below 600: Hyrel's G0 speeds are mm/min, this looks like mm/s"
    explanation = """
        Hyrel's M203 sets the G0 (rapid) speed per axis in mm/min ("M203 Y2000" = 2000 mm/min).  Marlin and
        Carvera use M203 for a maximum feed rate in mm/s, so a copied `M203 X200 Y200` makes Hyrel's
        rapids crawl at 200 mm/min.  Values below 600 mm/min on X or Y are reported.  (The speeds on the
        machine "are set based on testing; exceed them at your own risk.")
    """
    example_bad = "M203 X200 Y200"
    example_good = "M203 X12000 Y12000"
    source = "Gcode page, M203 Set G0 Speed"
    codes = ("M203",)
    families = ("hyrel",)

    LOWEST_XY = 600.0  # mm/min

    def check(self, line: Line, cmd: Command) -> None:
        for axis in ("X", "Y"):
            value = cmd.get(axis)
            if value is not None and value < self.LOWEST_XY:
                self.report(
                    line,
                    f"M203 {axis}{cmd.raw(axis)} is {value:g} mm/min on Hyrel (G0 speed); it looks like mm/s "
                    f"from Marlin/Carvera (= {value * 60:g} mm/min)",
                    node=cmd.param(axis) or cmd,
                )


@register
class PauseSAndPAdd(Rule):
    code = "HY058"
    name = "pause-s-and-p-add"
    severity = Severity.INFO
    summary = "G4 with both S and P: Hyrel pauses for the sum"
    explanation = """
        "You may use S or P, or if you use both, the total value will be the pause duration."  Marlin
        uses S and ignores P when both are given, so a pause written for Marlin lasts longer on Hyrel.
    """
    example_bad = "G4 S1 P500"
    example_good = "G4 P1500"
    source = "Gcode page, G4 Timed Pause"
    codes = ("G4",)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        p = cmd.params
        if "S" in p and "P" in p:
            s, ms = cmd.get("S"), cmd.get("P")
            total = f" = {s + ms / 1000:g} s in total" if s is not None and ms is not None else ""
            message = f"G4 S and P add up on Hyrel (S seconds + P milliseconds{total}); Marlin would use S only"
            self.report(line, message, node=cmd)


@register
class ProbeParameters(Rule):
    code = "HY062"
    name = "probe-parameters"
    severity = Severity.ERROR
    summary = "G38 probe: connection P, probe head T and D must fit together"
    explanation = """
        G38 (hidden codes page) probes by moving until contact.  P is the probe connection: 0-5 when T names
        the head carrying the probe, 0-29 otherwise, where "0 : No direct connect probe; canbus based probe
        one *** must specify probeHead via T arg" (so P0 without T is an error) and 5, 10, 15, 20, 25 are
        unused.  "D only 1 is presently supported" (another D is a warning).  The firmware needs P and D.
    """
    example_bad = "G38 Z-9 P0 D1 F200"
    example_good = "G38 Z-9 T0 P3 D1 I1 F200"
    source = "Hidden codes page, G38 Distance Probing"
    codes = ("G38",)
    families = ("hyrel",)

    _UNUSED = (5, 10, 15, 20, 25)

    def check(self, line: Line, cmd: Command) -> None:
        p = cmd.params
        has_t = "T" in p
        if "P" not in p or p["P"] is None:
            self.report(line, "G38 needs P (the probe connection)", node=cmd)
        else:
            value = to_number(p["P"])
            node = cmd.param("P") or cmd
            if value is None:
                pass
            elif value != int(value) or not 0 <= value <= (5 if has_t else 29):
                limit = "0-5 with T (a probe on a head)" if has_t else "0-29 without T"
                self.report(line, f"G38 P{p['P']}: the probe connection must be {limit}", node=node)
            elif value == 0 and not has_t:
                message = "G38 P0 is a CAN-bus probe on a head: it must specify the probe head with T"
                self.report(line, message, node=node)
            elif not has_t and int(value) in self._UNUSED:
                self.report(line, f"G38 P{p['P']} is an unused probe connection", node=node, severity=Severity.WARNING)
        if "D" not in p or p["D"] is None:
            self.report(line, "G38 needs D1 (the only probing mode presently supported)", node=cmd)
        elif to_number(p["D"]) != 1:
            message = f"G38 D{p['D']}: only D1 is presently supported"
            self.report(line, message, node=cmd.param("D") or cmd, severity=Severity.WARNING)
