"""HY offset rules: M6 head offsets, M660 tool-height registers and their H, G28 homing, G81.

Sources: the Hyrel Gcode page, "Controlling Position and Offsets" (G28 Send X, Y to Physical Home, M6
Declare Head Offsets, M660 Assign Tool Height Offset, T Tool Change) and "G81 Peck Drilling", and the
Hyrel firmware source (src/MCode.c M_Code_M6, M_Code_M660; src/GCode.c G_Code_G28); see docs/sources.md.
"""

from __future__ import annotations

from gclint.dialects.addressing import HEAD
from gclint.dialects.base import Param
from gclint.rules.base import Edit, Fix, Rule, Severity, register
from gclint.rules.dialect import ParamTableRule
from gclint.rules.hyrel.addressing import int_value, is_v5
from gclint.syntax.nodes import Command, Line, to_number

_AXES = ("X", "Y", "Z", "A", "B")
_FIXTURES = tuple(f"G{n}" for n in range(54, 60))


# -- HY004 ---------------------------------------------------------------------------------------------


@register
class G81WithoutAppliedM660(Rule):
    code = "HY004"
    name = "g81-without-applied-m660"
    severity = Severity.ERROR
    summary = "G81 peck drilling without an M660 tool-height offset set and applied (H on a move) before it"
    explanation = """
        "NOTE that an M660 offset must be set and applied BEFORE THIS COMMAND to allow for tool length."
        Set it with `M660 H<n> Z<offset>` and apply it with `H<n>` on a G1 (or a G0) before the G81.  Without it the
        drill's length is not accounted for and the pecks go to the wrong depth: into the bed, or not
        deep enough.  G28 and M30 clear the applied offset, so it must be applied again after them.
    """
    example_bad = """
        M660 H1 Z30
        G81 T20 X100 Y75 I3 P3 Q-2 Z-7.5 F200
    """
    example_good = """
        M660 H1 Z30
        G1 Z10 F600 H1
        G81 T20 X100 Y75 I3 P3 Q-2 Z-7.5 F200
    """
    source = "Gcode page, G81 Peck Drilling and M660 Assign Tool Height Offset"
    codes = ("G81",)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        st = self.state
        register = st.applied_height_register
        if register is not None and register in st.tool_height_offsets:
            return
        if register is not None:
            message = (
                f"G81: H{register} was applied at line {st.applied_height_line}, "
                f"but no M660 H{register} sets that register"
            )
        elif st.tool_height_offsets:
            stored = ", ".join(f"H{h}" for h in sorted(st.tool_height_offsets))
            message = f"G81: M660 stores {stored}, but no move applies it with H before the G81"
        else:
            message = "G81 without an M660 tool-height offset: set one (M660 H1 Z..) and apply it (G1 ... H1) first"
        self.report(line, f"{message} ('an M660 offset must be set and applied BEFORE THIS COMMAND')", node=cmd)


# -- HY005 ---------------------------------------------------------------------------------------------


@register
class M660EhrWithoutZHome(Rule):
    code = "HY005"
    name = "m660-ehr-without-z-home"
    severity = Severity.ERROR
    summary = "M660 on an Engine HR before any G28 Z0"
    explanation = """
        The Engine HR homes away from the print surface, so its tool-height offsets are measured from
        the Z home: "NOTE: You MUST have a G28 Z0 in your header to run this M660 on the EHR."  Without
        it the offset is applied to an unknown Z and the head can crash into the bed.  The rule applies
        when the printer is an EHR (`--printer ehr`).
    """
    example_bad = """
        ; gclint-test: printer=ehr
        M660 H2 Z28.2
    """
    example_good = """
        ; gclint-test: printer=ehr
        G28 Z0
        M660 H2 Z28.2
    """
    source = (
        "Gcode page, M660 Assign Tool Height Offset; Hyrel firmware source, src/MCode.c M_Code_M660 (H required) "
        "and inc/main.h NUM_TOOL_OFFSETS (60)"
    )
    codes = ("M660",)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        if self.state.z_homed_line is None and self.ctx.on_every_model(lambda p: p.needs_z_home_for_m660):
            self.report(
                line,
                f"M660 on an {self.ctx.profile.name.upper()} needs a G28 Z0 before it "
                f"('You MUST have a G28 Z0 in your header to run this M660 on the EHR'){self.ctx.model_note()}",
                node=cmd,
            )


# -- HY025 ---------------------------------------------------------------------------------------------


@register
class G28AxisValue(Rule):
    code = "HY025"
    name = "g28-axis-value"
    severity = Severity.WARNING
    summary = "G28 with no axis (homes nothing on Hyrel) or with a non-zero axis value (ignored)"
    explanation = """
        Hyrel's G28 homes only the axes it lists: "X0 ensures that the X axis is homed", and "Any axis
        not homed will have its position remain unchanged".  A bare `G28` (Marlin's "home all") homes
        nothing.  A value other than 0 does not move anywhere first: "We do not support intermediate
        positioning during homing."  Write `G28 X0 Y0` (and `Z0` where the axis has a home).
    """
    example_bad = "G28"
    example_good = "G28 X0 Y0"
    source = (
        "Gcode page, G28 Send X, Y to Physical Home; Hyrel firmware source, src/GCode.c G_Code_G28 and main.c (an "
        "axis with no home sensor)"
    )
    codes = ("G28",)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        params = cmd.params
        listed = [axis for axis in _AXES if axis in params]
        if not listed:
            self.report(
                line, "G28 with no axis homes nothing on Hyrel (only listed axes are homed): write G28 X0 Y0", node=cmd
            )
            return
        for axis in listed:
            message = home_value_message(cmd, axis)
            if message is not None:
                self.report(line, message, node=cmd.param(axis))


def home_value_message(cmd: Command, axis: str) -> str | None:
    """HY025's message for a G28 axis with a value other than 0 (explain says the same), or None."""
    raw = cmd.params.get(axis)
    value = to_number(raw) if raw is not None else None
    if value is None or value == 0:
        return None
    return (
        f"G28 {axis}{raw}: Hyrel homes {axis} and ignores the value ('We do not support intermediate positioning"
        f" during homing'); write {axis}0"
    )


# -- HY034 ---------------------------------------------------------------------------------------------


@register
class ToolHeightRegister(ParamTableRule):
    code = "HY034"
    name = "tool-height-register"
    severity = Severity.ERROR
    summary = "An H register outside 0-59, or H on a move applying a register that no M660 has set"
    explanation = """
        `M660 H<n> Z<offset>` stores a tool-height offset in register n; `H<n>` on a G1 applies it ("Hn is
        the stored head offset to apply (see M660 to store offsets)").  Applying a register that no M660
        has set applies whatever it holds (usually nothing), so the head prints at the wrong height
        (warning); M30 resets the registers, so they must be set again in the next job.  The firmware
        has registers 0-59: another number, or an M660 without H, is an error.  H0 (no offset) is not
        reported.

        The page gives H in G1's usage (G0's is `G0 Xn Yn Zn An Bn Fn`), but a G0 applies it too: the
        firmware's G0 and G1 both queue their move through `motionQ_addCommand`, which takes the register
        from H on any move but a G38 probe (Hyrel firmware source, src/GCode.c G_Code_G0_0 and G_Code_G1_0,
        src/MotorDrivers.c motionQ_addCommand).  Real Hyrel jobs write `G0 Z0 H2` with no M660 in the job
        (the register set on the machine), so on a G0 only the register's range is checked.
    """
    example_bad = """
        M660 H2 Z28.2
        G1 X50 Y75 F4800 H3
    """
    example_good = """
        M660 H2 Z28.2
        G1 X50 Y75 F4800 H2
    """
    source = (
        "Gcode page, G1 Working Move (Hn) and M660 Assign Tool Height Offset; Hyrel firmware source, src/MCode.c "
        "M_Code_M660, inc/main.h NUM_TOOL_OFFSETS (60), src/MotorDrivers.c motionQ_addCommand (H on G0 and G1)"
    )
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.codes = (*self.codes, "M30")
        self.warned: set[int] = set()
        self.reset_by_m30: dict[int, int] = {}  # register -> M30 line that reset it

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        return frozenset("H") if code in ("G0", "G1") else None  # a move matters only when it applies H

    def check(self, line: Line, cmd: Command) -> None:
        params = cmd.params
        code = cmd.code
        if code in ("G0", "G1"):
            if "H" not in params:
                return
            super().check(line, cmd)
            if code == "G0":
                return  # (real generators write "G0 Z0 H2" with no M660 in the job: the range only, as before)
            register = int_value(params["H"])
            st = self.state
            if register is None or register == 0 or register > 59 or register in st.tool_height_offsets:
                return
            if register in self.warned:
                return
            self.warned.add(register)
            reset = self.reset_by_m30.get(register)
            why = f"; M30 at line {reset} reset the M660 registers" if reset is not None else ""
            self.report(
                line,
                f"H{register} applies tool-height register {register}, but no M660 H{register} has set it{why}",
                node=cmd.param("H"),
                severity=Severity.WARNING,
            )
        elif code == "M660":
            super().check(line, cmd)
            register = int_value(params.get("H"))
            self.warned.discard(register)
        elif code == "M30":
            for register in self.state.tool_height_offsets:
                self.reset_by_m30[register] = line.number
            self.warned.clear()

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"{cmd.code}: {problem}: the firmware has tool-height registers 0-59"

    def missing_message(self, cmd: Command, p: Param) -> str:
        return "M660 needs H, the register to store the offset in (applied later with H on a G1)"


# -- HY038 ---------------------------------------------------------------------------------------------

_OFFSET_LETTERS = ("O", "X", "Y", "Z", "A", "B", "D", "I", "K")


def m6_message(params) -> str | None:
    """HY038's message for a Hyrel M6 with these parameters (explain says the same), or None: it declares offsets."""
    if not params:
        return (
            "M6 with no parameters does nothing on Hyrel (M6 declares head offsets); a T command alone changes the tool"
        )
    if "T" not in params or any(letter in params for letter in _OFFSET_LETTERS):
        return None
    return (
        f"M6 T{params['T']} looks like a tool change, but on Hyrel M6 declares head offsets "
        "(M6 T# O# X.. Y.. Z..) and this one declares none; change tools with a T command"
    )


@register
class M6UsedAsToolChange(Rule):
    code = "HY038"
    name = "m6-used-as-tool-change"
    severity = Severity.ERROR
    fixable = True
    fix_applicability = "unsafe"
    summary = "M6 written as a tool change (M6 T1, T1 M6): on Hyrel M6 declares head offsets"
    explanation = """
        On CNC controllers and in some slicers `M6` (with `T1 M6` or `M6 T1`) changes the tool.  On Hyrel
        "M6 declares that a particular head holds a set of X, Y, and/or Z offsets, which will be invoked
        during a T (tool change) command" (`M6 T# On Xn Yn Zn ...`), and "T executes a tool change...
        Do not confuse a T command with a T variable."  An `M6 T1` with no offset register and no
        offsets changes nothing, and the job keeps printing with the previous head; a bare `M6` does
        nothing.  Change tools with a T command alone: `T1`.  (An unsafe fix rewrites `M6 T1` to `T1`.)
    """
    example_bad = "M6 T1"
    example_good = """
        M6 T1 O2 X20 Y0 Z0
        T1
    """
    source = "Gcode page, M6 Declare Head Offsets and T Tool Change"
    codes = ("M6",)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        params = cmd.params
        message = m6_message(params)
        if message is None:
            return
        if not params:
            self.report(line, message, node=cmd)
            return
        fix = None
        address = self.ctx.interpreter.address(cmd)
        word, t_word = cmd.word, cmd.param("T")
        if (
            address is not None
            and address.kind == HEAD
            and word is not None
            and t_word is not None
            and len(cmd.words) == 1
        ):
            number = address.position if (is_v5(self.ctx) or address.position < 10) else None  # type: ignore[operator]
            if number is not None:
                fix = Fix(
                    f"Replace M6 T{params['T']} with the tool change T{number}",
                    (Edit(line.number, word.column, t_word.end_column, f"T{number}"),),
                    safe=False,
                )
        self.report(line, message, node=cmd, fix=fix)


# -- HY055 ---------------------------------------------------------------------------------------------


@register
class OffsetsClearedByG28(Rule):
    code = "HY055"
    name = "offsets-cleared-by-g28"
    severity = Severity.WARNING
    summary = "G28 clears G92, fixture (G54-G59), H and head (M6) offsets that the printing after it still relies on"
    explanation = """
        "After homing, a G28 also resets current offsets to 0 - including any may have been set with a
        G92 or an H (as defined in an M660 and invoked on a G1), performs a G53, and applies a head
        offset of 0 mm (as in an M6 O0)."  A G28 in the middle of a job (re-homing between parts, a
        homing macro, or a G28 after the T command that selected the head) therefore drops the offsets
        the job set up, and the printing that follows lands in the wrong place or at the wrong height
        unless the offsets are set again before the next printing move: G92, G54-G59, H on a G1, and
        for the head offsets a T command, which "invoke[s] all flow, prime, unprime, and offset
        parameters" of the head (or an `M6 T# ... I1`, "when you execute a tool change with T#").

        The work that follows is the printing, and also work without E: G1 "is a working move, during
        which you may be printing, milling, lasering, or doing other active work".  In a job that has
        not printed (milling, pick and place) or while a spindle turns, the first G1 or arc that moves
        an axis, or a G81, after the G28 is where the work resumes: a pick-and-place head loses its
        `M6 T1 O2 X102.4 Y-23.5` offset there as a print head does.

        The head offset counts when a T command selected a head before the G28 and the job does not
        declare that head's offsets as all zero (`M6 T0 O1 X0 Y0 Z0`, where an offset of 0 mm changes
        nothing); a job with no T command at all prints with "the only head loaded" and is not
        reported.  A G28 at the end of a job, with no work after it, is fine.
    """
    example_bad = """
        T1
        G28 X0 Y0
        G1 X20 Y10 E1 F1200
    """
    example_good = """
        G28 X0 Y0
        T1
        G1 X20 Y10 E1 F1200
    """
    source = "Gcode page, G28 Send X, Y to Physical Home, G1 Working Move and T Tool Change; T_v5, Explicit Mode"
    codes = ("G28", "G92", *_FIXTURES, "M30")
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.g28: Line | None = None  # the last G28 that cleared offsets still in use
        self.cleared: dict[str, tuple[str, int | None]] = {}  # kind -> (what, line set)
        self.again: dict[str, int] = {}  # kind -> first line that set it again after the G28
        self.set_at: dict[str, int] = {}  # kind -> line that last set it

    def check(self, line: Line, cmd: Command) -> None:
        code = cmd.code
        st = self.state
        if code == "G92":
            if any(axis in cmd.params for axis in _AXES):
                self.set_at["G92"] = line.number
                self.again.setdefault("G92", line.number)
            return
        if code in _FIXTURES:
            self.set_at["fixture"] = line.number
            self.again.setdefault("fixture", line.number)
            return
        self._settle()
        if code == "M30":
            return
        cleared: dict[str, tuple[str, int | None]] = {}
        if st.g92_offsets_active:
            cleared["G92"] = ("the G92 offsets", self.set_at.get("G92"))
        if st.fixture_offsets_active:
            cleared["fixture"] = ("the fixture offsets (G54-G59)", self.set_at.get("fixture"))
        if st.applied_height_register is not None:
            cleared["H"] = (f"the tool-height offset H{st.applied_height_register}", st.applied_height_line)
        head = st.tool
        if (
            st.head_reselected_line is not None
            and head is not None
            and 0 <= head <= 19
            and not st.head_offsets_zero(head)
        ):
            cleared["head"] = (f"the M6 head offsets of T{head}", st.tool_line)
        self.g28 = line if cleared else None
        self.cleared = cleared
        self.again = {}

    def finish(self) -> None:
        self._settle()

    def _settle(self) -> None:
        """Report the last G28 if printing resumed after it before its offsets were set again."""
        g28, self.g28 = self.g28, None
        if g28 is None:
            return
        st = self.state
        printed = st.first_print_since_home_line
        worked = st.first_work_since_home_line  # (milling, pick and place: a G1 with no E is work too)
        if worked is not None and (printed is None or printed > worked):
            resumed = worked
            resumes = (
                f"work resumes at line {worked} (G1 is 'a working move, during which you may be printing, "
                "milling, lasering, or doing other active work')"
            )
        elif printed is not None:
            resumed = printed
            resumes = f"printing resumes at line {printed}"
        else:
            return  # no work after the G28 (the usual G28 at the end of a job)
        again = dict(self.again)
        if st.applied_height_register is not None and st.applied_height_line is not None:
            again["H"] = st.applied_height_line
        if st.head_reselected_line is not None:
            again["head"] = st.head_reselected_line
        lost = {}
        for kind, (what, set_line) in self.cleared.items():
            when = again.get(kind)
            if when is None or when > resumed:
                lost[kind] = f"{what}{f' (line {set_line})' if set_line else ''}"
        if not lost:
            return
        how = ""
        if "head" in lost:
            how = (
                " (G28 'applies a head offset of 0 mm (as in an M6 O0)'; "
                "a T command before the work applies the head's offsets again)"
            )
        self.report(
            g28,
            f"G28 resets {', '.join(lost.values())} to 0, and {resumes} without setting them again{how}",
            node=g28.commands[0] if g28.commands else None,
        )


# -- HY061 ---------------------------------------------------------------------------------------------


@register
class HeadOffsetRegister(ParamTableRule):
    code = "HY061"
    name = "head-offset-register"
    severity = Severity.ERROR
    summary = (
        "M6 with an offset register outside 0-59, offsets stored in the fixed zero register O0, or offsets with no O"
    )
    explanation = """
        `M6 T# On Xn Yn Zn` stores head offsets in register O ("On is the Offset position where these
        are being stored"), invoked by the T command of that head.  The firmware has registers 0-59, and
        register 0 is the fixed zero offset (G28 "applies a head offset of 0 mm (as in an M6 O0)";
        the firmware's M6 "don't allow location 0 to change"): an O outside 0-59 or not whole, or offsets
        written to O0, are lost and the head prints without its offset.  `M6 O0` alone (apply the zero
        offset) is fine.

        An M6 that gives offsets but no register (`M6 T1 X25 Y0 Z0.5`) stores them nowhere: the page
        decodes an M6 without O as "(no offset registers, so ignore all offsets)" (its `M6 K1` example),
        so the head prints without them (warning).  Write the register: `M6 T1 O2 X25 Y0 Z0.5`.

        (An info for every M6 in a job would also be possible, since "Repetrel reads this data from
        the heads, and sends it to the printer before the gcode file is loaded"; gclint does not report
        it, because Repetrel's own job header is made of exactly these lines.)
    """
    example_bad = "M6 T0 O60 X20 Y-30 Z40"
    example_good = "M6 T0 O1 X20 Y-30 Z40"
    source = (
        "Gcode page, M6 Declare Head Offsets (parameters, M6 K1 example) and G28 Send X, Y to Physical Home; "
        "Hyrel firmware source, src/MCode.c M_Code_M6 (O 0-59; register 0 never changes)"
    )
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        super().check(line, cmd)
        params = cmd.params
        if "O" not in params:
            given = " ".join(f"{axis}{params[axis]}" for axis in _AXES if params.get(axis) is not None)
            if given:
                head = f" T{params['T']}" if params.get("T") is not None else ""
                self.report(
                    line,
                    f"M6{head} {given} has no O register: the page decodes an M6 without one as '(no offset "
                    f"registers, so ignore all offsets)'; store them in a register: M6{head} O<n> {given}",
                    node=cmd,
                    severity=Severity.WARNING,
                )
            return
        if int_value(params.get("O")) != 0:
            return
        offsets = [
            f"{axis}{params[axis]}"
            for axis in _AXES
            if params.get(axis) is not None and to_number(params[axis] or "") != 0
        ]
        if offsets:
            self.report(
                line,
                f"M6 O0 {' '.join(offsets)}: register O0 is the fixed zero offset; store offsets in O1-O59",
                node=cmd.param("O"),
            )

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"{cmd.code}: {problem}: the firmware has offset registers 0-59 (O0 is the fixed zero offset)"
