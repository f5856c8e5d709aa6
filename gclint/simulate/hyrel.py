"""Hyrel (Repetrel v5, and v4 through its addresses), as the target of a translation.  Every fact is from the
Hyrel wiki's Gcode page (https://hyrel3d.com/wiki/index.php/Gcode, section named) or T_v5:

* G0 is a rapid, non-working move with a one-shot F; G1 is a working move whose F persists (G0, G1).
* Flow: without ``M229 E1`` any E marks a printing move and Hyrel computes the flow (native); with
  ``M229 E1 D1`` the E values are used (M229, "Controlling Material Flow"), as absolute or relative
  amounts (M82, M83).  Arcs compute their flow natively even under M229 E1 (Hyrel wiki, Gcode page, G2).
* ``M104``/``M109 T# S``: a head's set-point; M109 waits, ``W0`` waits only at ``M116`` (M109, M116).
* ``M106 T# S`` is a share of the range ``C`` (default C100, "use C255 to be compatible with most
  slicers"), which holds until M30; ``P`` is the duty during extrusion moves only; M107 is M106 S0.
* ``M221 T# S`` is a flow multiplier (1.0 = as the head stores it).
* ``T#`` focuses a head; ``G28`` homes only the listed axes and clears G92 and fixture offsets (G28);
  ``G53`` clears fixture offsets (modal); ``G54``-``G59`` invoke stored offsets; ``G93`` clears G92 offsets.
* ``M3``/``M4 T# S`` run a spindle at a percent, S0 is off; ``M5 T#`` stops it.
* ``M620 T# E1`` enables a laser or UV emitter, ``M621 P`` sets its power; it fires on printing moves.
* ``M7``/``M8 S`` Aux1/Aux2 (default S100), ``M9`` both off; ``M679`` vacuum, ``M685`` air, ``M670`` light.
* ``M221 T# W Z``: the head's bead width and layer height for native flow; ``M756 S`` "will overwrite the Z
  value from the M221 command" (M756), ignored under ``M229 E1 D1``.
* ``M721``/``M722 T# S E P``: how much the head unprimes and primes on a print <-> travel transition; with
  ``I1`` "execute an unprime [prime] with the previously specified values at that point in the gcode".
* ``M30`` ends the job ("No gcode after an M30 will be executed as part of the previous job") and resets
  M229, the M106 range, fixture offsets, the head index (to 0).
* ``M18``/``M84`` cut the motors: "All axes with homes must be rehomed after an M18".
"""

from __future__ import annotations

from dataclasses import replace

from gclint.dialects.addressing import (
    BED,
    GROUP,
    HEAD,
    VIRTUAL,
    Address,
    address_number,
    members,
    resolve_v5,
    wait_fails,
)
from gclint.simulate.devices import DeviceModel
from gclint.simulate.events import Flow, Heat
from gclint.simulate.heat import Heater, heat_set, heat_wait, heater_look
from gclint.simulate.machine import number
from gclint.simulate.trace import AUX_PORTS, EndState, Look, Move
from gclint.syntax.nodes import Command

_GROUP_HEADS = {
    40: range(0, 20),
    47: range(0, 20),
    41: range(0, 5),
    42: range(5, 10),
    43: range(10, 15),
    44: range(15, 20),
}


class Head:
    __slots__ = ("heat", "waited", "fan", "fan_p", "flow", "width", "height", "unprime", "prime")

    def __init__(self, height: float | None = None) -> None:
        self.heat: Heater | None = None  # a nozzle's (heat.py); None: never set
        self.waited: float | None = None  # a bed's or chamber's set-point waited for
        self.fan = 0.0  # S, in the range's units
        self.fan_p: float | None = None  # P: duty during extrusion moves
        self.flow = 1.0
        self.width: float | None = None  # M221 W (None: as the head stores it)
        self.height = height  # M221 Z, M756 S
        self.unprime: tuple | None = None  # M721 S E P
        self.prime: tuple | None = None  # M722 S E P


class HyrelSimulator(DeviceModel):
    def __init__(self, dialect, mapping=None, *, cnc: bool = False) -> None:
        super().__init__(dialect, mapping, cnc=cnc)
        self.resolve_variable = dialect.extras.get("resolve_variable", resolve_v5)
        self.resolve_command = dialect.extras.get("resolve_command", resolve_v5)
        self.evalues = False
        self.focus: int | None = None
        self.heads: dict[int, Head] = {}
        self.fan_range = 100.0
        self.spindles: dict[int, tuple[str, float | None]] = {}
        self.emitters: set[int] = set()
        self.laser_power: float | None = None
        self.aux: dict[str, float] = {}
        self.pending_w0: dict[int, bool] = {}  # M109 W0: the head waits at M116 (both ways?)
        self.ran = False  # a command ran since the last M30 (the job's end state is worth keeping)
        self._one_shot: float | None = None  # G1 S: this move's flow multiplier
        self.head_offsets: dict[int, tuple[list[float], bool]] = {}  # M6 T# O: (X Y Z A B, move on T: I1)
        self.registers: dict[int, float] = {}  # M660 H<n> Z<mm>
        self.head_offset = [0.0] * 5  # the focused head's M6 offsets, invoked by T
        self.height = 0.0  # the Z of the M660 register a G1 H invoked
        self.layer_height: float | None = None  # M756 S: every head's layer height for native flow
        # clone squads (M702 S establishes one, M703 T# S adds a head, M704 T# S removes it; M30 decommissions
        # them): squad address -> its heads (Hyrel wiki, T_v5 page; Gcode page, M30 End of Program)
        self.squads: dict[int, set[int]] = {}
        self.known: set[int] = set()  # heads the job declares (M6) or selects (T#): what a group covers here
        # (``events``) set-points per device name and kind, and the W0 ones M116 waits for (M109 Example 7, M116)
        self.set_points: dict[tuple[str, str], float] = {}
        self.w0_devices: dict[tuple[str, str], None] = {}

    def table(self):
        h = {
            "G0": self.g0,
            "G1": self.g1,
            "G2": self.arc,
            "G3": self.arc,
            "G20": self.units,
            "G21": self.units,
            "G28": self.home,
            "G53": self.g53,
            "G90": self.positioning,
            "G91": self.positioning,
            "G92": self.set_position,
            "G93": self.g93,
            "M82": self.e_mode,
            "M83": self.e_mode,
            "M229": self.m229,
            "M104": self.m104,
            "M109": self.m109,
            "M116": self.m116,
            "M140": self.bed,
            "M190": self.bed,
            "M141": self.bed,
            "M191": self.bed,
            "M106": self.m106,
            "M107": self.m107,
            "M221": self.m221,
            "M756": self.m756,
            "M721": self.m721,
            "M722": self.m721,
            "M3": self.spindle_on,
            "M4": self.spindle_on,
            "M5": self.spindle_off,
            "M620": self.m620,
            "M621": self.m621,
            "M7": self.aux_on,
            "M8": self.aux_on,
            "M679": self.aux_on,
            "M685": self.aux_on,
            "M670": self.aux_on,
            "M9": self.aux_off,
            "M18": self.motors_off,
            "M84": self.motors_off,
            "M30": self.m30,
            "M6": self.m6,
            "M660": self.m660,
            "G4": self.g4,
            "M0": self.pause,  # "M0 is a stop until resume command" (M0)
            "M702": self.m702,
            "M703": self.m703,
            "M704": self.m703,
            # spirals (Gcode page, "G2.1 Spiral CW Arc^1", "G2.2 Spiral CW Arc^2", G3.1, G3.2)
            "G2.1": self.spiral_move,
            "G3.1": self.spiral_move,
            "G2.2": self.spiral_move,
            "G3.2": self.spiral_move,
        }
        for n in range(54, 60):
            h[f"G{n}"] = self.workspace
        return h

    # -- addresses ----------------------------------------------------------------------------------------

    def addresses(self, cmd: Command, default_focus: bool = True) -> list[int]:
        """The v5 addresses a command's T variable designates (a group: its heads); no T: the focused head."""
        text = cmd.params.get("T")
        value = number(text) if text is not None else None
        if value is None or value != int(value):
            return [self.focus] if default_focus and self.focus is not None else []
        address = self.resolve_variable(int(value)).v5
        if address is None:
            return []
        if address in _GROUP_HEADS:
            return [a for a in _GROUP_HEADS[address] if a in self.heads] or []
        return [address]

    def tool_label(self, tool: int | None) -> str:
        return "the focused head" if tool is None else f"T{tool}"

    def tool_name(self) -> str:
        return self.named(self.focus)

    def tool_title(self, name: str) -> str:
        digits = name[1:]
        return resolve_v5(int(digits)).label if name[:1] == "T" and digits.isdigit() else name

    def heat_device(self, cmd: Command, kind: str) -> str:
        """A head by its address (a group or a virtual head by its name), else the focused head; beds and
        chambers by kind (T_v5 Chart of Addresses)."""
        if kind != "head":
            return kind
        value = number(cmd.params.get("T"))
        if value is None or value != int(value):
            return self.tool_name()
        address = self.resolve_variable(int(value))
        if address.kind == "head" and address.v5 is not None:
            return self.tool_label(address.v5)
        return address.label

    def waits(self, cmd: Command) -> bool:
        return "W" not in cmd.params  # "W0": the wait happens at M116 (M109, M116)

    def heat_event(self, cmd: Command, n: int, kind: str, wait: bool) -> None:
        """A set-point per device the command reaches (``heat_targets``).  A wait on a virtual or group address
        sets the temperature and does not wait (``addressing.wait_fails``, as HY003 reads it); one with W0
        waits at M116."""
        value = self.heat_value(cmd, wait)
        if value is None:
            return
        targets, fails = self.heat_targets(cmd, kind)
        waits = wait and not fails and self.waits(cmd)
        w0 = wait and not fails and not waits and number(cmd.params.get("W")) == 0
        for device, device_kind in targets:
            key = (device, device_kind)
            self.set_points[key] = value
            if w0:
                self.w0_devices[key] = None
            else:
                self.w0_devices.pop(key, None)  # (a later plain set-point or wait replaces the W0 one)
            self.emit(Heat(n, device, device_kind, value, waits))

    def heat_targets(self, cmd: Command, kind: str) -> tuple[list[tuple[str, str]], bool]:
        """The devices (name, kind) a temperature command sets, and whether a wait on its address fails.  The
        T variable is read as the HY rules read it (``resolve_variable``; HY046: ``M190 T0`` addresses head T0);
        without T, a head code sets the focused head, a bed or chamber code the primary one ("default is the
        primary bed / chamber", T_v5).  A group (T40-T48) or a clone squad (T30-T39) sets its members
        (``addressing.members``): a squad's heads, a group's heads or beds that the job uses; none known: the
        address itself."""
        text = cmd.params.get("T")
        t = address_number(text) if text is not None else None
        if t is None:
            if kind != "head":
                return [(kind, kind)], False
            if self.focus is None:
                return [(self.tool_name(), kind)], False
            address = resolve_v5(self.focus)
        else:
            address = self.resolve_variable(t)
        if address.v5 is None:
            return [(address.label, kind)], False
        if address.kind in (VIRTUAL, GROUP):
            wanted = HEAD if kind == "head" else BED
            known = self.known | set(self.heads)
            covered = [
                m
                for m in dict.fromkeys(members(address.v5, self.squads))
                if resolve_v5(m).kind == wanted and (m in known or address.kind == VIRTUAL)
            ]
            if not covered:
                name = self.named(address.v5) if address.kind == VIRTUAL else address.label
                return [(name, kind)], wait_fails(address)
            return [self.device_name(resolve_v5(m), kind) for m in covered], wait_fails(address)
        return [self.device_name(address, kind)], False

    def device_name(self, address: Address, kind: str) -> tuple[str, str]:
        """(name, kind) of one physical device: a head by its T, Bed1 / Chamber1 (T24) as "bed" / "chamber",
        Bed2 / Chamber2 (T25) with its address."""
        if address.kind == HEAD and address.v5 is not None:
            return self.named(address.v5), "head"
        if address.kind == BED:
            kind = kind if kind != "head" else "bed"
            return (kind if address.v5 == 24 else f"{kind} 2 (T{address.v5})"), kind
        return address.label, kind

    def heads_of(self, name: str) -> tuple[str, ...]:
        """A clone squad prints with its heads (T_v5: M703 "adds a single head to the Clone Squad")."""
        digits = name[1:]
        if name[:1] == "T" and digits.isdigit():
            squad = self.squads.get(int(digits))
            if squad:
                return tuple(self.named(m) for m in sorted(squad))
        return (name,)

    # -- clone squads -------------------------------------------------------------------------------------

    def m702(self, cmd: Command, n: int) -> None:
        """``M702 S<squad>``: establish a clone squad (empty until M703 adds heads), as the interpreter does."""
        squad = address_number(cmd.params.get("S"))
        if squad is not None:
            self.squads[squad] = set()
            self.membership += 1

    def m703(self, cmd: Command, n: int) -> None:
        """``M703 T# S<squad>`` adds head T# to the squad, ``M704`` removes it (no M702, no squad)."""
        squad = address_number(cmd.params.get("S"))
        if squad not in self.squads:
            return
        for address in self.addresses(cmd):
            if cmd.code == "M703":
                self.squads[squad].add(address)
            else:
                self.squads[squad].discard(address)
        self.membership += 1

    def spiral_move(self, cmd: Command, n: int) -> Move | None:
        """G2.1/G3.1 and G2.2/G3.2: a spiral.  G2.1 "Effective ending X/Y is always the same as the current XY and
        is not specified"; G2.2 "specifies final X/Y (and Z) location"; "An end Z can be supplied" (Gcode page,
        G2.1 Spiral CW Arc^1, G2.2 Spiral CW Arc^2).  The path between (laps, pitch, reverse code) is not
        modelled: the move is marked a spiral (``Move.spiral``), its length unknown.  E marks it printing, with
        the native flow of arcs."""
        params = cmd.params
        f = params.get("F")
        if f is not None:
            value = number(f)
            self.feed = value * self.feed_scale if value is not None else None
        start = self.machine()
        self.pos = self.target(params, xy=cmd.code in ("G2.2", "G3.2"))
        delta = self.extrusion(params, False)
        self.spiral = True
        try:
            return self.sync(start, None, delta, self.feed, False, native=self.arc_native(params))
        finally:
            self.spiral = False

    def head(self, address: int) -> Head:
        head = self.heads.get(address)
        if head is None:
            head = self.heads[address] = Head(self.layer_height)
        return head

    def tool_command(self, cmd: Command, n: int) -> None:
        text = (cmd.code or "T")[1:]
        if not text.isdigit():
            return
        address = self.resolve_command(int(text)).v5
        if address is not None:
            self.focus = address
            self.known.add(address)
            # "M6 declares that a particular head holds a set of X, Y, and/or Z offsets, which will be invoked
            # during a T (tool change) command"; I1 "store values and move these distances" (M6)
            values, moves = self.head_offsets.get(address, ([0.0] * 5, False))
            if moves:
                for i in range(5):
                    p = self.pos[i]
                    if p is not None:
                        self.pos[i] = p + values[i] - self.head_offset[i]
            self.head_offset = list(values)
            self.apply_offsets()
            self.dirty()

    def dirty(self) -> None:
        super().dirty()
        self.ran = True

    # -- motion and flow --------------------------------------------------------------------------------

    def motion(self, mode: str, params: dict, n: int) -> Move | None:
        self.ran = True
        if mode == "G0" and "E" in params:
            params = {k: v for k, v in params.items() if k != "E"}  # G0 E is stripped (Hyrel firmware source)
        # "Sn is a one-time (non-persistent) material flow rate multiplier (rarely used) applied to this move
        # only" (G1): the move's flow is the head's times S (Hyrel firmware source clamps it to 0-15.99)
        if mode == "G1" and "H" in params:  # "Hn is the stored head offset to apply" (G1), until G28
            h = number(params.get("H"))
            self.height = self.registers.get(int(h), 0.0) if h is not None else 0.0
            self.apply_offsets()
        s = number(params.get("S")) if mode == "G1" and "S" in params else None
        self._one_shot = None if s is None else max(0.0, min(s, 15.99))
        try:
            return super().motion(mode, params, n)
        finally:
            self._one_shot = None

    def sync(self, start, arc, delta, feed, rapid, native=False):
        self.ran = True
        if not self.evalues and delta is not None and not rapid:
            native = True  # any E (even a negative one) marks a printing move in native flow
        move = super().sync(start, arc, delta, feed, rapid, native=native)
        if move is not None and self._one_shot is not None:
            move.look = replace(move.look, flow=round(move.look.flow * self._one_shot, 4))
        return move

    def arc(self, cmd: Command, n: int) -> Move | None:
        saved = self.plane
        self.plane = 17  # plain G2/G3 draw XY arcs with I/J (the planes apply to G2.x/G3.x)
        try:
            return super().arc(cmd, n)
        finally:
            self.plane = saved

    def arc_native(self, params: dict) -> bool:
        return "E" in params

    def m6(self, cmd: Command, n: int) -> None:
        """``M6 T# On Xn Yn Zn An Bn In``: head T#'s offsets ("X20 (X+20)"), invoked by the next T# (M6)."""
        params = cmd.params
        if "O" not in params:
            return  # M6 K1 and the like: behaviour during tool changes only
        for address in self.addresses(cmd, default_focus=False):
            self.known.add(address)
            values = [(number(params.get(a)) or 0.0) for a in "XYZAB"]
            self.head_offsets[address] = (values, number(params.get("I")) == 1)

    def m660(self, cmd: Command, n: int) -> None:
        """``M660 H<register> Z<mm>``: "Z28.2 (+28.2 to Z position)" once a G1 invokes H<register> (M660)."""
        h, z = number(cmd.params.get("H")), number(cmd.params.get("Z"))
        if h is not None and z is not None:
            self.registers[int(h)] = z

    def apply_offsets(self) -> None:
        self.offset = [self.head_offset[i] + (self.height if i == 2 else 0.0) for i in range(5)]

    def m229(self, cmd: Command, n: int) -> None:
        e = number(cmd.params.get("E"))
        if e is not None:
            self.evalues = e == 1
            self.emit(Flow(n, "evalues" if self.evalues else "native"))
            self.dirty()  # the layer height matters in native flow only

    def home(self, cmd: Command, n: int) -> None:
        listed = "".join(a for a in "XYZAB" if a in cmd.params)
        self.clear_shift()  # offsets cleared; an axis not homed keeps its (machine) position
        # "resets current offsets to 0 - including ... an H (as defined in an M660 and invoked on a G1) ... and
        # applies a head offset of 0 mm (as in an M6 O0)" (G28)
        self.height = 0.0
        self.head_offset = [0.0] * 5
        self.apply_offsets()
        self.home_axes(listed)
        self.wcs = None
        self.dirty()

    def g53(self, cmd: Command, n: int) -> None:
        self.wcs = None
        self.dirty()

    def g93(self, cmd: Command, n: int) -> None:
        self.clear_shift()

    def motors_off(self, cmd: Command, n: int) -> None:
        self.forget("XY")

    def m30(self, cmd: Command, n: int) -> None:
        self.end_line = n
        self.trace.end = self.end_state()
        self.trace.end.line = n
        self.trace.end.pauses, self.trace.end.dwell = self.pauses, self.dwell
        self.evalues = False
        self.emit(Flow(n, "native"))
        self.fan_range = 100.0
        self.trace.end.ended = True
        self.wcs = None
        self.focus = 0
        if self.squads:  # "decommissions any clone squads that were in effect" (M30)
            self.squads.clear()
            self.membership += 1
        self.dirty()
        self.ran = False

    # -- heat, fans, flow -----------------------------------------------------------------------------------

    def m104(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        if s is None:
            return
        for address in self.addresses(cmd):
            head = self.head(address)
            head.heat = heat_set(head.heat, s)
            self.pending_w0.pop(address, None)
        self.dirty()

    def m109(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        w0 = number(cmd.params.get("W")) == 0 and "W" in cmd.params
        # C, U and R bound the wait from above too; without them it waits while heating only (heat.heat_wait)
        both_ways = any(letter in cmd.params for letter in "CUR")
        for address in self.addresses(cmd):
            head = self.head(address)
            if s is not None:
                head.heat = heat_set(head.heat, s)
            if head.heat is None:
                continue
            if w0:
                self.pending_w0[address] = both_ways
            else:
                head.heat = heat_wait(head.heat, head.heat[0], both_ways)
                self.pending_w0.pop(address, None)
        self.dirty()

    def m116(self, cmd: Command, n: int) -> None:
        """ "wait for any set temps (M109, M190, M191) with W0 values before proceding" (M116)."""
        for address, both_ways in self.pending_w0.items():
            head = self.head(address)
            if head.heat is not None:
                head.heat = heat_wait(head.heat, head.heat[0], both_ways)
                if address in (24, 25):
                    head.waited = head.heat[0]
        self.pending_w0.clear()
        if self.listening:
            for device, kind in self.w0_devices:
                self.emit(Heat(n, device, kind, self.set_points[(device, kind)], True))
        self.w0_devices.clear()
        self.dirty()

    def bed(self, cmd: Command, n: int) -> None:
        wait = cmd.code in ("M190", "M191")
        s = number(cmd.params.get("S"))
        addresses = self.addresses(cmd, default_focus=False) or [24]
        for address in addresses:
            head = self.head(address)
            if s is not None:
                head.heat = heat_set(head.heat, s)
            if wait and "W" not in cmd.params and head.heat is not None:
                head.waited = head.heat[0]
                self.pending_w0.pop(address, None)
            elif wait and number(cmd.params.get("W")) == 0 and head.heat is not None:
                self.pending_w0[address] = False  # "W0 (but do not pause until M116 is executed)" (M190, M116)
        self.dirty()

    def m106(self, cmd: Command, n: int) -> None:
        params = cmd.params
        c = number(params.get("C"))
        if c is not None and c > 0:
            self.fan_range = c
        if "S" not in params and "P" not in params and c is not None:
            return  # the range only
        if "T" in params:
            targets = self.addresses(cmd, default_focus=False)
        else:  # "(on all tools)"
            targets = sorted({a for a in self.heads if a < 20} | ({self.focus} if self.focus is not None else set()))
        s = number(params.get("S")) if "S" in params else (100.0 if "P" not in params else None)
        p = number(params.get("P"))
        for address in targets:
            head = self.head(address)
            if s is not None:
                head.fan = s / self.fan_range
            if p is not None:
                head.fan_p = p / 100  # P is a percent of the duty cycle
        self.dirty()

    def m107(self, cmd: Command, n: int) -> None:
        targets = self.addresses(cmd, default_focus=False) if "T" in cmd.params else list(self.heads)
        for address in targets:
            head = self.head(address)
            head.fan = 0.0
            head.fan_p = None
        self.dirty()

    def m221(self, cmd: Command, n: int) -> None:
        s, w, z = (number(cmd.params.get(letter)) for letter in "SWZ")
        for address in self.addresses(cmd):
            head = self.head(address)
            if s is not None:
                head.flow = s
            if w is not None:
                head.width = w
            if z is not None:
                head.height = z
        self.dirty()

    def m756(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        if s is None:
            return
        self.layer_height = s
        for head in self.heads.values():
            head.height = s
        self.dirty()

    def m721(self, cmd: Command, n: int) -> None:
        """M721 (unprime) / M722 (prime): the head's settings; with I1 one now."""
        params = cmd.params
        settings = tuple(number(params.get(letter)) for letter in "SEP")
        for address in self.addresses(cmd):
            head = self.head(address)
            if any(v is not None for v in settings):
                if cmd.code == "M721":
                    head.unprime = settings
                else:
                    head.prime = settings
            if number(params.get("I")) == 1:
                (self.unprime if cmd.code == "M721" else self.prime)(address)
        self.dirty()

    # -- spindles, emitters, aux --------------------------------------------------------------------------

    def spindle_on(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        for address in self.addresses(cmd):
            if s is not None and s == 0:
                self.spindles.pop(address, None)  # "S0 is the same as turning it off"
            else:
                self.spindles[address] = (cmd.code, None if s is None else round(s, 1))  # type: ignore[assignment]
        self.dirty()

    def cutting(self) -> bool:
        return bool(self.spindles)

    def spindle_direction(self) -> str | None:
        spindle = self.spindles.get(self.focus) if self.focus is not None else None
        return spindle[0] if spindle else None

    def spindle_off(self, cmd: Command, n: int) -> None:
        for address in self.addresses(cmd):
            self.spindles.pop(address, None)
        self.dirty()

    def m620(self, cmd: Command, n: int) -> None:
        e = number(cmd.params.get("E"))
        for address in self.addresses(cmd, default_focus=False):  # "MUST be specified, can NOT be inherited"
            if e == 1:
                self.emitters.add(address)
            else:
                self.emitters.discard(address)
        self.dirty()

    def m621(self, cmd: Command, n: int) -> None:
        p = number(cmd.params.get("P"))
        if p is not None:
            self.laser_power = p
            self.dirty()

    def aux_on(self, cmd: Command, n: int) -> None:
        s = number(cmd.params.get("S"))
        value = 100.0 if s is None else s
        name = AUX_PORTS[cmd.code]  # type: ignore[index]
        if value > 0:
            self.aux[name] = value
        else:
            self.aux.pop(name, None)
        self.dirty()

    def aux_off(self, cmd: Command, n: int) -> None:
        self.aux.pop("aux1", None)
        self.aux.pop("aux2", None)
        self.dirty()

    # -- Hyrel terms ------------------------------------------------------------------------------------------

    def fan_of(self, head: Head) -> float:
        value = head.fan_p if head.fan_p is not None else head.fan
        return round(max(0.0, min(1.0, value)), 3)

    def build_look(self) -> Look:
        focus = self.focus
        head = self.heads.get(focus) if focus is not None else None
        if head is None:
            temp: tuple = (None, False, None)
            fan, flow = 0.0, 1.0
        else:
            temp = heater_look(head.heat)
            fan, flow = self.fan_of(head), round(head.flow, 4)
        layer = None
        if not self.evalues and not self.emitters:  # (an E on a laser's move marks it firing: no material)
            height = head.height if head is not None else self.layer_height
            layer = (head.width if head is not None else None, (height,) if height is not None else ())
        prime = (head.unprime, head.prime) if head is not None and (head.unprime or head.prime) else None
        beds = tuple(
            sorted(
                (a, h.heat[0], h.waited == h.heat[0])
                for a, h in self.heads.items()
                if a in (24, 25) and h.heat is not None
            )
        )
        spindle = None
        if self.spindles:
            # the spindle that turns where the job works: the focused head's (a spindle left on another head
            # is not the one cutting); with no head focused, the lowest address that runs
            spindle = self.spindles.get(focus) if focus is not None else self.spindles[min(self.spindles)]
        fans = tuple(
            (f"T{a} fan", self.fan_of(h)) for a, h in sorted(self.heads.items()) if a >= 20 and self.fan_of(h) > 0
        )
        return Look(
            head=focus,
            temp=temp,
            fan=fan,
            flow=flow,
            beds=beds,
            spindle=spindle,
            laser=self.laser_power if self.emitters else None,
            aux=fans + tuple(sorted(self.aux.items())),
            wcs=self.wcs,
            units="inch" if self.scale != 1.0 else "mm",
            layer=layer,
            prime=prime,
        )

    def end_state(self) -> EndState:
        if not self.ran and self.trace.end.line:
            # the last M30 ended the job: what was on then
            return self.trace.end if self.pure else self.finish_end(self.trace.end)
        heaters = {a: h.heat[0] for a, h in self.heads.items() if h.heat is not None and h.heat[0] > 0}
        fans: dict = {}
        for a, h in self.heads.items():
            value = round(max(0.0, min(1.0, h.fan)), 3)
            if value > 0:
                fans[a if a < 20 else f"T{a} fan"] = value
        end = EndState(
            # nothing ran since the last M30 (or at all: a job with nothing to end)
            ended=not self.ran,
            heaters=heaters,
            fans=fans,
            spindles={a: d for a, (d, _) in self.spindles.items()},
            emitters=frozenset(self.emitters),
            aux=dict(self.aux),
        )
        return end if self.pure else self.finish_end(end)
