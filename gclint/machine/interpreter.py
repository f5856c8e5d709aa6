"""Apply commands to a ``MachineState`` with the semantics of a dialect.

What a code does is the dialect's fact (``gclint.dialects.semantics``: ``Semantics.effects`` maps each code to
its effect, and the fields say how G0, G28, T, E and the commands of one line behave); this module carries each
effect out on the state the rules read.  The same code can mean different things (M30 ends a Hyrel job but
deletes a file on Marlin; G90 resets the E mode on Marlin only): the dialect's table says which.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache, partial, reduce
from operator import add

from gclint.dialects.addressing import Address, members, resolve_v5
from gclint.dialects.base import Dialect
from gclint.machine.state import EVALUES, NATIVE, MachineState
from gclint.syntax.fastpath import PLAIN_NUMBER, run_amounts
from gclint.syntax.nodes import GCODE, IMPLICIT, Command, Line, is_number, to_number

Handler = Callable[[Command, Line], None]

_AXES = "XYZAB"
_MOTION = frozenset({"G0", "G1", "G2", "G3"})
_RUN_MODES = {"0": "G0", "1": "G1", "2": "G2", "3": "G3"}  # (the digit of a move or arc of a run)


def _int(text: str | None) -> int | None:
    """An integer parameter value (``"12"``, ``"12.0"``), or None."""
    if text is None or not is_number(text) or len(text) > 12:
        return None
    value = to_number(text)  # (hex such as "0x0b" included; None when not finite)
    return int(value) if value is not None and value == int(value) else None


def _last_word(text: str, letter: str, start: int, end: int, not_on: str = "") -> int:
    """Where the last ``letter`` word of a move line (not a ``not_on`` one, "G0" say) in ``text[start:end]``
    (plain moves and comments) is, or -1."""
    at = text.rfind(letter, start, end)
    while at >= 0:
        line = text.rfind("\n", start, at) + 1 or start
        if text[line] == "G" and not (not_on and text.startswith(not_on, line)):
            return at
        at = text.rfind(letter, start, line)
    return -1


def _number_at(text: str, at: int) -> str:
    """The number that starts at ``at`` in a run's text (the run's pattern found one there)."""
    m = PLAIN_NUMBER.match(text, at)
    if m is None:  # pragma: no cover - the run pattern and this reader out of step
        raise ValueError(f"no number at {at}")
    return m.group()


class Interpreter:
    """Tracks ``state`` through the commands of one file."""

    def __init__(self, dialect: Dialect, state: MachineState | None = None) -> None:
        self.dialect = dialect
        self.state = state if state is not None else MachineState()
        self.semantics = facts = dialect.semantics
        self.resolve_variable: Callable[[int], Address] = dialect.extras.get("resolve_variable", resolve_v5)  # type: ignore[assignment]
        self.resolve_command: Callable[[int], Address] = dialect.extras.get("resolve_command", resolve_v5)  # type: ignore[assignment]
        # T commands and T variables name devices by their address (Hyrel): groups, clone squads, v4 numbers
        self.addressed = facts.tool_select == "address"
        self.native_flow = facts.e_values == "native"  # an E marks a printing move unless M229 E1 D1
        self.g0_feed_one_shot = facts.g0_feed == "one-shot"
        present = set(facts.effects.values())
        self.height_registers = "height-offset" in present  # G1 H<n> applies the register an M660 stored
        self.w0_waits = "wait-pending" in present  # a wait with W0 waits at M116 (Hyrel)
        fan = dialect.spec("M106")
        self.fan_ranges = fan is not None and fan.param("C") is not None  # M106 C sets the range of S (Hyrel)
        # (functions of the class, not bound methods: a table of bound methods would hold the interpreter in
        # a reference cycle, and each file's state and findings until the garbage collector's next full pass)
        self.handlers = _handlers(type(self), facts)

    # -- addressing ----------------------------------------------------------------------------------

    def address(self, cmd: Command, letter: str = "T") -> Address | None:
        """The device a command's T variable designates (v4 numbers translated); None without T."""
        number = _int(cmd.params.get(letter))
        if number is None:
            return None
        return self.resolve_variable(number)

    def target(self, cmd: Command) -> int | None:
        """The v5 address of the device a command acts on: its T variable, else the focused head."""
        address = self.address(cmd)
        if address is not None:
            return address.v5
        return self.state.tool

    def tool_command_address(self, cmd: Command) -> Address | None:
        """The address a ``T<n>`` command line selects, or None when ``n`` is not a number."""
        if cmd.kind != GCODE or not cmd.code or cmd.code[0] != "T":
            return None
        number = _int(cmd.code[1:])
        return None if number is None else self.resolve_command(number)

    # -- dispatch ------------------------------------------------------------------------------------

    def handler_for(self, cmd: Command) -> Handler:
        """The function that applies commands with ``cmd``'s code (the engine caches it per code)."""
        handler = self.handlers.get(cmd.code)  # type: ignore[arg-type]
        return partial(handler, self) if handler is not None else self.apply

    def moves_plainly(self, code: str) -> bool:
        """Whether ``code`` (G0, G1, G2 or G3) is applied as ``plain_move`` and ``plain_run`` apply it."""
        handler = self.handlers.get(code)
        if code in ("G2", "G3"):
            return handler is type(self)._arc
        motion = type(self)._motion
        return isinstance(handler, partial) and handler.func is motion and handler.keywords == {"mode": code}

    def apply(self, cmd: Command, line: Line) -> None:
        handler = self.handlers.get(cmd.code)  # type: ignore[arg-type]
        if handler is not None:
            handler(self, cmd, line)
        elif cmd.kind == IMPLICIT:
            mode = self.state.motion_mode
            if mode is not None and any(a in cmd.params for a in _AXES):
                self._motion(cmd, line, mode)
            elif "F" in cmd.params and self.semantics.feed_on_any_command:
                # a lone F word sets the modal feed (LinuxCNC, Carvera/grbl): "F1000" on its own line
                try:
                    self.state.feed = float(cmd.params["F"] or "")
                except ValueError:
                    self.state.feed = None
        elif cmd.kind == GCODE and cmd.code and cmd.code[0] == "T":
            self._tool(cmd, line)

    # -- motion --------------------------------------------------------------------------------------

    def _arc(self, cmd: Command, line: Line) -> None:
        self._motion(cmd, line, cmd.code)  # type: ignore[arg-type]

    def _spiral_in_place(self, cmd: Command, line: Line) -> None:
        # G2.1: "Effective ending X/Y is always the same as the current XY" (Hyrel Gcode page)
        self._motion(cmd, line, cmd.code, xy=False)  # type: ignore[arg-type]

    def _motion(self, cmd: Command, line: Line, mode: str, xy: bool = True) -> None:
        # The hot path: one call per G0/G1 line of a multi-million-line job.
        st = self.state
        p = cmd.params
        if st.absolute and xy:
            st.position.values.update(p)  # axis texts, converted only if read (see Position)
        else:
            pos = st.position
            for axis in _AXES:
                if axis in p and (xy or axis not in "XY"):
                    v = p[axis]
                    if st.absolute:
                        pos.set_raw(axis, v)
                        continue
                    try:
                        pos.add(axis, float(v))  # type: ignore[arg-type]
                    except (TypeError, ValueError):
                        pos.forget(axis)
        if "F" in p and not (mode == "G0" and self.g0_feed_one_shot):
            try:
                st.feed = float(p["F"])  # type: ignore[arg-type]
            except (TypeError, ValueError):
                st.feed = None
            if mode != "G0":
                st.working_feed_set = True
        st.moved = True
        if st.first_move_line is None:
            st.first_move_line = line.number
        if (
            st.first_work_since_home_line is None
            and mode != "G0"
            and (not st.printed or st.spindles)
            and ("X" in p or "Y" in p or "Z" in p or "A" in p or "B" in p)
        ):
            st.first_work_since_home_line = line.number
        if mode in _MOTION:
            st.motion_mode = mode
        if "E" in p:
            self._extrude(p["E"], mode, line.number)
        if self.height_registers and "H" in p and mode in ("G0", "G1"):
            # (G1's "Hn is the stored head offset to apply"; a G0 applies it too: the firmware's G0 and G1 both
            # queue the move through motionQ_addCommand, which takes the register from H: HY034)
            register = _int(p["H"])
            if register != st.applied_height_register or st.applied_height_line is None:
                st.applied_height_line = line.number
            st.applied_height_register = register

    def plain_move(
        self, mode: str, number: int, x: str | None, y: str | None, z: str | None, e: str | None, f: str | None
    ) -> None:
        """``_motion`` for the commonest line, a G0/G1 with nothing but X Y Z E F words holding plain
        numbers (the engine matches those lines without building a tree; values are source texts)."""
        st = self.state
        if st.absolute:
            values = st.position.values
            if x is not None:
                values["X"] = x
            if y is not None:
                values["Y"] = y
            if z is not None:
                values["Z"] = z
        else:
            pos = st.position
            if x is not None:
                pos.add("X", float(x))
            if y is not None:
                pos.add("Y", float(y))
            if z is not None:
                pos.add("Z", float(z))
        if f is not None and not (mode == "G0" and self.g0_feed_one_shot):
            st.feed = float(f)
            if mode != "G0":
                st.working_feed_set = True
        st.moved = True
        if st.first_move_line is None:
            st.first_move_line = number
        if (
            st.first_work_since_home_line is None
            and mode != "G0"
            and (not st.printed or st.spindles)
            and (x is not None or y is not None or z is not None)
        ):
            st.first_work_since_home_line = number
        st.motion_mode = mode
        if e is not None:
            self._extrude(e, mode, number)

    def plain_run(self, text: str, start: int, end: int) -> bool:
        """Apply ``text[start:end]``, whole lines that are plain moves, comments, empty lines, M-codes that
        change nothing and, where the engine allows them, arcs (``fastpath.run_pattern``, ``runs.CodeLines``),
        as ``plain_move`` and ``_arc`` would one
        line after the other, without cutting the text into lines: what a run leaves is its last X, Y, Z,
        F, E and motion mode.  Returns False, having changed nothing, when the run may change more than
        that (relative moves, the first move, feed or print of the job): then the caller applies the
        lines one by one."""
        if text[start] != "G" and text.find("\nG", start, end) < 0:
            return True  # (no move: comments, empty lines, M-codes that change nothing)
        st = self.state
        if not st.absolute or st.first_move_line is None:
            return False
        if st.first_work_since_home_line is None and (not st.printed or st.spindles):
            return False  # a move of the run may be the first work since the last G28: it sets its line
        e_at = _last_word(text, "E", start, end)
        if e_at >= 0 and (
            st.first_print_since_tool_line is None  # (first: it is the one a tool change clears)
            or st.first_print_since_home_line is None
            or st.first_print_since_m30_line is None
            or not st.printed
        ):
            return False  # a move of the run may be the first print: it sets line numbers
        f_at = _last_word(text, "F", start, end, "G0" if self.g0_feed_one_shot else "")  # (one-shot: no feed)
        if f_at >= 0 and not st.working_feed_set:
            return False
        number = _number_at
        values = st.position.values
        for axis in "XYZ":
            at = _last_word(text, axis, start, end)
            if at >= 0:
                values[axis] = number(text, at + 1)
        if f_at >= 0:
            st.feed = float(number(text, f_at + 1))
        last = text.rfind("\nG", start, end) + 1
        st.motion_mode = _RUN_MODES[text[last + 1 if last else start + 1]]
        st.moved = True
        if e_at >= 0:
            if st.e_absolute:
                st.e_position = float(number(text, e_at + 1))
            elif st.e_position is not None:  # (summed in order, as one move after the other does)
                pattern, at = run_amounts(text, start, end)
                amounts = pattern.findall(text, at, end)
                st.e_position = reduce(add, map(float, amounts), st.e_position)
        return True

    def _extrude(self, e: str | None, mode: str, number: int) -> None:
        st = self.state
        try:
            value = float(e) if e is not None else None
        except ValueError:
            value = None
        if mode != "G0":
            # Hyrel native flow: "E will trigger a working or printing move" whatever its value (G1
            # section); elsewhere a move extrudes when E advances.
            if self.native_flow and st.flow_mode == NATIVE:
                printing = True
            elif value is None:
                printing = False
            elif st.e_absolute:
                printing = st.e_position is None or value > st.e_position
            else:
                printing = value > 0
            if printing:
                if not st.printed:
                    st.printed = True
                    st.first_print_line = number
                if st.first_print_since_home_line is None:
                    st.first_print_since_home_line = number
                if st.first_print_since_m30_line is None:
                    st.first_print_since_m30_line = number
                if st.first_print_since_tool_line is None:
                    st.first_print_since_tool_line = number
        if value is None:
            st.e_position = None
        elif st.e_absolute:
            st.e_position = value
        elif st.e_position is not None:
            st.e_position += value

    def _plane(self, cmd: Command, line: Line) -> None:
        plane = _PLANES.get(cmd.code)  # type: ignore[arg-type]
        if plane is not None:  # (LinuxCNC's UVW planes G17.1-G19.1 have no arcs: the plane stays)
            self.state.plane = plane

    def _units(self, cmd: Command, line: Line) -> None:
        """G20/G21: the job's numbers are inches or mm from here on; the current position is the same place,
        named in the new unit (LinuxCNC's ``convert_length_units`` converts it; Marlin keeps mm inside)."""
        st = self.state
        unit = "inch" if cmd.code == "G20" else "mm"
        if unit != st.units:
            factor = 1 / 25.4 if unit == "inch" else 25.4
            for axis in "XYZ":
                value = st.position.get(axis)
                if value is not None:
                    st.position.set(axis, value * factor)
            st.units = unit

    def _g90(self, cmd: Command, line: Line) -> None:
        self.state.absolute = True
        if self.semantics.e_follows_g90:
            self.state.e_absolute = True

    def _g91(self, cmd: Command, line: Line) -> None:
        self.state.absolute = False
        if self.semantics.e_follows_g90:
            self.state.e_absolute = False

    def _g92(self, cmd: Command, line: Line) -> None:
        st = self.state
        for axis in _AXES:
            v = cmd.params.get(axis)
            if v is not None:
                before, shift = st.position.get(axis), st.g92_shift.get(axis, 0.0)
                st.position.set_raw(axis, v)
                after = st.position.get(axis)
                known = before is not None and after is not None and shift is not None
                st.g92_shift[axis] = shift + (before - after) if known else None  # type: ignore[operator]
        if "E" in cmd.params:
            e = cmd.params["E"]
            try:
                st.e_position = float(e) if e is not None else 0.0
            except ValueError:
                st.e_position = None
        if any(a in cmd.params for a in _AXES):
            st.g92_offsets_active = True

    def _clear_g92(self, cmd: Command, line: Line) -> None:
        st = self.state
        st.g92_offsets_active = False
        for axis, shift in st.g92_shift.items():
            if shift is None:
                st.position.forget(axis)
            elif shift:
                st.position.add(axis, shift)
        st.g92_shift = {}

    def _home_and_reset(self, cmd: Command, line: Line) -> None:
        # Hyrel: after homing, "a G28 also resets current offsets to 0 - including any may have been set with
        # a G92 or an H ..., performs a G53, and applies a head offset of 0 mm (as in an M6 O0)" (Gcode page,
        # "G28 Send X, Y to Physical Home")
        st = self.state
        st.head_reselected_line = None
        st.g92_offsets_active = False
        st.g92_shift = {}
        st.fixture_offsets_active = False
        st.applied_height_register = None
        st.applied_height_line = None
        st.first_print_since_home_line = None
        st.first_work_since_home_line = None
        self._g28(cmd, line)

    def _g28(self, cmd: Command, line: Line) -> None:
        st = self.state
        listed = [a for a in _AXES if a in cmd.params]
        home = self.semantics.home
        if home == "listed":
            homed = listed
        elif home == "all-if-none":
            homed = listed or ["X", "Y", "Z"]  # Marlin/RRF: bare G28 homes all axes
        else:
            # a stored position (LinuxCNC), the clearance position (Carvera), the zero of the axes (the FDM
            # remap, in the program's frame): none the rules' state can place
            for axis in listed or list(_AXES):
                st.position.forget(axis)
            st.moved = True
            return
        for axis in homed:
            st.position.set(axis, 0.0)
            st.homed_axes.add(axis)
            st.axes_with_homes.add(axis)
        if "Z" in homed:
            st.z_homed_line = line.number
        st.axes_to_rehome.difference_update(homed)
        if not st.axes_to_rehome:  # "All axes with homes must be rehomed after an M18" (M18)
            st.motors_off_line = None
        st.moved = True

    def _g53(self, cmd: Command, line: Line) -> None:
        # Hyrel G53 is modal "Clear Offsets" (Gcode page, "G53 Clear Offsets")
        self.state.fixture_offsets_active = False

    def _fixture(self, cmd: Command, line: Line) -> None:
        self.state.fixture_offsets_active = True

    def _g93(self, cmd: Command, line: Line) -> None:
        # Hyrel G93 clears G92 offsets (not inverse-time feed)
        self._clear_g92(cmd, line)

    def _g81(self, cmd: Command, line: Line) -> None:
        st = self.state
        for axis in "XY":
            v = cmd.params.get(axis)
            if v is not None:
                st.position.set_raw(axis, v)
        st.moved = True
        if st.first_work_since_home_line is None:  # (peck drilling is work: "make holes")
            st.first_work_since_home_line = line.number

    def _motors_off(self, cmd: Command, line: Line) -> None:
        # "All axes with homes must be rehomed after an M18." (Hyrel Gcode page, M18).  Which axes have homes:
        # X and Y ("G28 Send X, Y to Physical Home"), and Z, A, B where the job itself homes them; the pages
        # do not say which models have a Z home (a 30M's own Hyrel header homes X and Y only)
        st = self.state
        st.motors_off_line = line.number
        st.axes_to_rehome = set(st.axes_with_homes)
        st.homed_axes.clear()

    # -- heads and tools -----------------------------------------------------------------------------

    def _tool(self, cmd: Command, line: Line) -> None:
        address = self.tool_command_address(cmd)
        if address is None:
            return
        st = self.state
        select = self.semantics.tool_select
        if select == "prepare":  # the tool the next M6 loads (LinuxCNC, Carvera)
            st.prepared_tool = address.number
            return
        if select == "address":
            st.tool = address.v5
            # "T0 (Switch to far left head, and invoke all flow, prime, unprime, and offset parameters)"
            if st.head_reselected_line is None:
                st.head_reselected_line = line.number
        else:
            st.tool = address.number
        st.tool_line = line.number
        st.first_print_since_tool_line = None

    def _tool_change(self, cmd: Command, line: Line) -> None:
        # CNC M6: change to the tool prepared by T, on the line or before it (LinuxCNC; Carvera M6 T<n>); the
        # dialect's "no tool" number empties the spindle (LinuxCNC T0)
        st = self.state
        number = _int(cmd.params.get("T"))
        if number is None:
            number = st.prepared_tool
        if number is None:
            return
        st.tool = None if number == self.semantics.no_tool else number
        st.tool_line = line.number
        st.first_print_since_tool_line = None

    def _declare_head(self, cmd: Command, line: Line) -> None:
        # Repetrel sends "M6 T# O..." for every loaded head at job start (T_v5, Default Mode); an M6 T#
        # without O is a tool change written the CNC way (HY038), not a declaration
        params = cmd.params
        address = self.address(cmd) if "O" in params else None
        if address is None or address.position is None:
            return
        st = self.state
        st.declared_heads.setdefault(address.position, line.number)
        offsets = st.declared_offsets.setdefault(address.position, {})
        for axis in _AXES:
            if axis in params:
                text = params[axis]
                offsets[axis] = float(text) if text is not None and is_number(text) else None
        # "M6 T# O1 X20 Y-30 Z40 I1: This happens when you execute a tool change with T#, and so it
        # triggers the move (I1) to properly position the next head."
        if _int(params.get("I")) == 1 and st.head_reselected_line is None:
            st.head_reselected_line = line.number

    def _m702(self, cmd: Command, line: Line) -> None:
        squad = _int(cmd.params.get("S"))
        if squad is not None:
            self.state.squads[squad] = set()

    def _m703(self, cmd: Command, line: Line) -> None:
        squad = _int(cmd.params.get("S"))
        head = self.target(cmd)
        # "M703 adds a single head to the Clone Squad we established with an M702" (T_v5): no M702, no squad
        if squad in self.state.squads and head is not None:
            self.state.squads[squad].add(head)

    def _m704(self, cmd: Command, line: Line) -> None:
        squad = _int(cmd.params.get("S"))
        head = self.target(cmd)
        if squad in self.state.squads and head is not None:
            self.state.squads[squad].discard(head)

    # -- temperatures, fans, flow ----------------------------------------------------------------------

    def _set_temp(self, cmd: Command, line: Line) -> None:
        st = self.state
        if cmd.code in ("M140", "M190") or cmd.code in ("M141", "M191"):
            device = self.address(cmd)
            target = device.v5 if device is not None else 24
        else:
            target = self.target(cmd)
        if target is None:
            target = -1  # the focused head, unknown
        # the set-point as the dialect writes it (Marlin's M109 R, Machinekit's remap P: Semantics.set_point)
        s = self.semantics.set_point(cmd.params, cmd.code in ("M109", "M190", "M191"))[0]
        if s is not None:
            st.targets[target] = s
            if self.addressed and target >= 30:
                for member in self._members(target):
                    st.targets[member] = s
        if self.w0_waits and cmd.code in ("M109", "M190", "M191"):
            w = cmd.params.get("W")
            if w is not None and _int(w) == 0:
                st.pending_w0[target] = line.number
            else:  # a plain wait on the device also waits for what an earlier W0 set
                st.pending_w0.pop(target, None)

    def _members(self, address: int) -> list[int]:
        """The devices a group or virtual address covers: the T_v5 groups, a clone squad's heads."""
        return members(address, self.state.squads)

    def _fan_range(self, cmd: Command, line: Line) -> None:
        if not self.fan_ranges:
            return
        c = cmd.get("C")
        if c is not None and c > 0:
            self.state.fan_range = c
            self.state.fan_range_line = line.number

    def _m229(self, cmd: Command, line: Line) -> None:
        e = _int(cmd.params.get("E"))
        if e == 1:
            self.state.flow_mode = EVALUES
            self.state.m229_line = line.number
        elif e == 0:
            self.state.flow_mode = NATIVE
            self.state.m229_line = line.number

    def _m756(self, cmd: Command, line: Line) -> None:
        self.state.layer_height = cmd.get("S")

    def _m660(self, cmd: Command, line: Line) -> None:
        register = _int(cmd.params.get("H"))
        if register is not None:
            self.state.tool_height_offsets[register] = cmd.get("Z")

    # -- lasers and spindles -------------------------------------------------------------------------

    def _m620(self, cmd: Command, line: Line) -> None:
        address = self.address(cmd)
        if address is None or address.v5 is None:
            return
        e = _int(cmd.params.get("E"))
        if e == 1:
            self.state.emitters_enabled[address.v5] = line.number
            self.state.laser_enabled_any = True
        elif e == 0 or e is None:
            # groups (v5 T40/T47, v4 T100) switch off every emitter
            if address.kind == "group":
                self.state.emitters_enabled.clear()
            else:
                self.state.emitters_enabled.pop(address.v5, None)

    def _spindle_on(self, cmd: Command, line: Line) -> None:
        device = self.target(cmd) if self.addressed else 0
        if device is None:
            device = -1
        s = cmd.get("S")
        if s is not None and s == 0:  # "S0 is the same as turning it off" (M3 section)
            self.state.spindles.pop(device, None)
            return
        self.state.spindles[device] = ("cw" if cmd.code == "M3" else "ccw", line.number)

    def _spindle_off(self, cmd: Command, line: Line) -> None:
        device = self.target(cmd) if self.addressed else 0
        if device is None or "T" not in cmd.params:
            self.state.spindles.clear() if device is None else self.state.spindles.pop(device, None)
        else:
            self.state.spindles.pop(device, None)

    # -- end of job ------------------------------------------------------------------------------------

    def _end_of_job(self, cmd: Command, line: Line) -> None:
        # M30: "dissolves any cloning setups, changes head index to 0, clears fixture offsets (G53), clears
        # any M229 E-value settings, resets M106 persistent range, ... resets M660 head offsets to 0"
        st = self.state
        st.after_m30 = True
        st.m30_line = line.number
        st.flow_mode = NATIVE
        st.fan_range = 100.0
        st.fan_range_line = None
        st.tool_height_offsets.clear()
        st.applied_height_register = None
        st.applied_height_line = None
        st.first_print_since_m30_line = None
        st.first_print_since_tool_line = None
        st.head_reselected_line = None
        if st.squads:
            st.squads_dissolved_line = line.number
        st.squads.clear()
        st.fixture_offsets_active = False
        st.tool = 0  # "changes head index to 0"
        st.tool_line = line.number

    def _end_of_program(self, cmd: Command, line: Line) -> None:
        self.state.after_m30 = True
        self.state.m30_line = line.number


# -- the handler tables ----------------------------------------------------------------------------------

Method = Callable[[Interpreter, Command, Line], None]
Entry = str | tuple[str, str] | Method

_PLANES = {"G16": 16, "G17": 17, "G18": 18, "G19": 19}


def _ignore(self: Interpreter, cmd: Command, line: Line) -> None:
    return None


def _sets(field: str, value: object) -> Method:
    return lambda self, cmd, line: setattr(self.state, field, value)


def _m116(self: Interpreter, cmd: Command, line: Line) -> None:
    self.state.pending_w0.clear()


# Each effect (gclint.dialects.semantics) and what carries it out on the state: the name of a method (looked up on
# the interpreter's class, so that a subclass or a test may replace one), a motion method's name and mode, or a
# function.  An effect not listed changes nothing the rules read (pauses, coolant, feed modes...).
_BY_EFFECT: dict[str, Entry] = {
    "rapid": ("_motion", "G0"),
    "linear": ("_motion", "G1"),
    "arc": "_arc",
    "spiral-in-place": "_spiral_in_place",
    "dwell": _ignore,
    "plane": "_plane",
    "inch": "_units",
    "mm": "_units",
    "absolute": "_g90",
    "relative": "_g91",
    "set-position": "_g92",
    "clear-g92": "_clear_g92",
    "home": "_g28",
    "home-reset-offsets": "_home_and_reset",
    "arc-absolute": _sets("arc_absolute", True),
    "arc-relative": _sets("arc_absolute", False),
    "e-absolute": _sets("e_absolute", True),
    "e-relative": _sets("e_absolute", False),
    "set-head-temperature": "_set_temp",
    "wait-head-temperature": "_set_temp",
    "set-bed-temperature": "_set_temp",
    "wait-bed-temperature": "_set_temp",
    "set-chamber-temperature": "_set_temp",
    "wait-chamber-temperature": "_set_temp",
    "fan": "_fan_range",
    "motors-off": "_motors_off",
    "clear-fixture-offsets": "_g53",
    "machine-coordinates": _ignore,
    "workspace": "_fixture",
    "peck-drill": "_g81",
    "spindle-cw": "_spindle_on",
    "spindle-ccw": "_spindle_on",
    "spindle-off": "_spindle_off",
    "declare-head-offsets": "_declare_head",
    "tool-change": "_tool_change",
    "end-of-job": "_end_of_job",
    "end-program": "_end_of_program",
    "wait-pending": _m116,
    "flow-mode": "_m229",
    "emitter": "_m620",
    "height-offset": "_m660",
    "squad": "_m702",
    "squad-add": "_m703",
    "squad-remove": "_m704",
    "layer-height": "_m756",
}


@cache
def _table(effects: tuple[tuple[str, str], ...]) -> dict[str, Entry]:
    """The handlers of a dialect whose codes have these ``effects``."""
    return {code: _BY_EFFECT[effect] for code, effect in effects if effect in _BY_EFFECT}


def _handlers(cls: type[Interpreter], facts) -> dict[str, Method]:
    def resolve(entry: Entry) -> Method:
        if isinstance(entry, str):
            return getattr(cls, entry)
        if isinstance(entry, tuple):
            return partial(getattr(cls, entry[0]), mode=entry[1])
        return entry

    return {code: resolve(entry) for code, entry in _table(tuple(sorted(facts.effects.items()))).items()}
