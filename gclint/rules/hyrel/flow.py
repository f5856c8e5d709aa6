"""HY flow rules: native flow versus E values (M229), fans (M106), flow settings (M221, M756, M721/M722).

Sources: the Hyrel Gcode page ("Controlling Material Flow", "M106 Set Cooling / Etc.") and the Hyrel
firmware source (src/MCode.c), see docs/sources.md.  Hyrel's two ways to control flow: native flow (the default)
ignores E amounts and computes flow from speed, layer height and width; `M229 E1 D1` uses the slicer's
E values.  ``MachineState.flow_mode`` says which one is active.
"""

from __future__ import annotations

from gclint.dialects.addressing import BED, GROUP
from gclint.dialects.base import Param
from gclint.rules.base import Rule, Severity, register
from gclint.rules.dialect import ParamTableRule
from gclint.rules.hyrel.addressing import is_v5, reported_as_v4
from gclint.rules.hyrel.motion import MoveChecks, MoveRule
from gclint.syntax.nodes import Command, Line, to_number


def _fmt(value: float) -> str:
    return f"{value:g}"


@register
class M229E1D0(Rule):
    code = "HY001"
    name = "m229-e1-d0"
    severity = Severity.ERROR
    summary = "M229 E1 D0 is an illegal combination"
    explanation = """
        M229 switches Hyrel between native flow (E0) and the slicer's E values (E1); D chooses how the
        steps reach the head: D0 on the head controller, D1-D3 through the motion controller.  The page
        says: "Note: E1 D0 is an illegal combination."  `M229 E1 D1` is "the default way to enable E
        values".  M229 E1 without D is not reported: the page does not say what an omitted D means, and
        the firmware, given E1 with no routing chosen (D0 or none), sends the steps through the CAN bus and
        the C axis, as D3 does ("force canbus E steps when using E values": src/MCode.c M_Code_M229).
    """
    example_bad = "M229 E1 D0"
    example_good = "M229 E1 D1"
    source = (
        "Gcode page, M229 Use E Values; Hyrel firmware source, src/MCode.c M_Code_M229 (D0 is 'NOT VALID with '"
        "'Use E Value')"
    )
    codes = ("M229",)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        p = cmd.params
        e = to_number(p["E"]) if p.get("E") is not None else None  # type: ignore[arg-type]
        d = to_number(p["D"]) if p.get("D") is not None else None  # type: ignore[arg-type]
        if e == 1 and d == 0:
            self.report(
                line,
                "M229 E1 D0 is an illegal combination: use M229 E1 D1 to enable E values",
                node=cmd.param("D") or cmd,
            )


@register
class FanDutyOverRange(ParamTableRule):
    code = "HY011"
    name = "fan-duty-over-range"
    severity = Severity.WARNING
    summary = "M106 S above the active C range, or P above 100 %"
    explanation = """
        Hyrel's M106 S is a duty cycle within the range set by C: "if unspecified, the default is C100
        (use C255 to be compatible with most slicers)", and "all following M106 commands for the rest of
        this print job will be based on this range".  A slicer's `M106 S255` with the default range asks
        for 255 % of the range, which the pages do not define (whatever Repetrel makes of it, it is not
        the half speed a slicer's S128 means on the 0-255 scale): put `M106 C255` in the header.  P is
        "the percent of duty cycle ... to come on only during extrusion moves" (0-100), not Marlin's fan
        index; the page gives `M106 T# Sn` and `M106 T# Pn` as two forms, and does not say which one
        counts when a line has both.
    """
    example_bad = "M106 T0 S128"
    example_good = """
        M106 C255
        M106 T0 S128
    """
    source = "Gcode page, M106 Set Cooling / Etc."
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        super().check(line, cmd)  # P 0-100 (table: M106 P)
        p = cmd.params
        text = p.get("S")
        if text is None:
            return
        duty = to_number(text)
        if duty is None:
            return
        st = self.state
        c = cmd.get("C")
        if c is not None and c > 0:
            fan_range, where = c, "on this line"
        else:
            fan_range = st.fan_range
            where = f"set on line {st.fan_range_line}" if st.fan_range_line is not None else "the default"
        if duty > fan_range:
            hint = "; slicer fan values are 0-255: add M106 C255 before it" if duty <= 255 and fan_range != 255 else ""
            self.report(
                line,
                f"M106 S{text} is above the fan range C{_fmt(fan_range)} ({where}): S is a share of that range, and "
                f"the pages do not say what a duty above it does{hint}",
                node=cmd.param("S") or cmd,
            )
        if "P" in p:
            self.report(
                line,
                "M106 with both S and P: the page gives 'M106 T# Sn' and 'M106 T# Pn' (duty during extrusion only) "
                "as two forms and does not say which one counts on one line",
                node=cmd.param("P") or cmd,
            )

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"M106: {problem} (P is the percent duty during extrusion moves only, 0-100; not a fan index)"


@register
class FanRangeValue(ParamTableRule):
    code = "HY012"
    name = "fan-range-value"
    severity = Severity.WARNING
    summary = "M106 C outside 1-255 (warning) or other than 100/255 (info)"
    explanation = """
        "Cn is the range (0-100 or 0-255) that we will use; if unspecified, the default is C100 (use C255
        to be compatible with most slicers)."  The range stays until M30.  A value outside 1-255 is beyond
        both ranges the page gives (warning: the pages do not say what Repetrel makes of it); any other
        value in 1-255 is not one of the two documented ranges either (info).
    """
    example_bad = "M106 C1000"
    example_good = "M106 C255"
    source = "Gcode page, M106 Set Cooling / Etc.; Hyrel firmware source, src/MCode.c M_Code_M106 (C held to 1-255)"
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        super().check(line, cmd)  # C 1-255 (table: M106 C)
        c = cmd.get("C")
        if c is not None and 1 <= c <= 255 and c not in (100, 255):
            self.report(
                line,
                f"M106 C{cmd.raw('C')}: the documented fan ranges are C100 (the default) and C255 (slicers)",
                node=cmd.param("C") or cmd,
                severity=Severity.INFO,
            )

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"M106: {problem} (the fan range: the page gives C100 and C255)"


@register
class EModeWithoutM229(Rule):
    code = "HY013"
    name = "e-mode-without-m229"
    severity = Severity.INFO
    summary = "M82/M83 while E values are not enabled (M229 E1)"
    explanation = """
        M82 and M83 choose absolute or relative E values: "Note, this only works on v4 and later, when E
        values are enabled via M229."  In native flow the E amounts are ignored, so M82/M83 there changes
        nothing: info, as an ignored command changes nothing the printer does.  A native-flow job (E1 on
        its printing moves) can drop the line; a job whose E words are amounts needs `M229 E1 D1` first
        (the rules on its moves say so).
    """
    example_bad = "M83"
    example_good = """
        M229 E1 D1
        M83
    """
    source = "Gcode page, M82 Absolute E-Values / M83 Relative E-Values"
    codes = ("M82", "M83")
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        if not self.state.e_values():
            message = (
                f"{cmd.code} has no effect: E values are not enabled (M229 E1 D1 enables them; a native-flow job can"
                " drop the line)"
            )
            self.report(line, message, node=cmd)


@register
class M756IgnoredUnderM229(Rule):
    code = "HY014"
    name = "m756-ignored-under-m229"
    severity = Severity.INFO
    summary = "M756 layer height while E values are enabled: ignored"
    explanation = """
        M756 sets the layer height that native flow uses: "Note: this command is ignored if you are using
        M229 E1 D1 to enable use of E values."  Under M229 E1 the slicer's E amounts set the flow of
        G1 moves, so the layer height written here has no effect on them.  An ignored command changes
        nothing the printer does, so this is info, once per M229 E1 (Hyrel's own slicer profile writes
        `M756 S[layer_height]` at every layer after `M229 E1 D1`, so that the same profile serves
        native flow).

        Arcs are the one place the pages leave open: every arc is printed "with our native Hyrel flow
        calculations (based on nozzle diameter, layer thickness, and feed rate) even if your gcode has
        enabled the use of E values with M229 E1 D1" (G2), while the M756 note makes no exception for
        them.  So in a job with arcs under M229 E1, the pages do not say whether an M756 sets their layer
        thickness; gclint says what the M756 page says (ignored), and HY037 says the same of the arcs.
    """
    example_bad = """
        M229 E1 D1
        M756 S0.2
    """
    example_good = """
        M229 E0
        M756 S0.2
    """
    source = "Gcode page, M756 Set Height for Flow"
    codes = ("M756",)
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.reported_for: int | None = None  # the M229 E1 line already reported

    def check(self, line: Line, cmd: Command) -> None:
        st = self.state
        if st.e_values() and st.m229_line != self.reported_for:
            self.reported_for = st.m229_line
            self.report(
                line,
                f"M756 is ignored: E values are enabled (M229 E1 on line {st.m229_line}); 'this command is ignored if "
                "you are using M229 E1 D1 to enable use of E values' (so are the M756 lines after it, until "
                "M229 E0)",
                node=cmd,
            )


@register
class FlowMultiplierRange(ParamTableRule):
    code = "HY033"
    name = "flow-multiplier-range"
    severity = Severity.WARNING
    summary = "G1 S / M221 S is a flow multiplier: a negative one asks for negative flow"
    explanation = """
        On Hyrel, `G1 ... Sn` is "a one-time (non-persistent) material flow rate multiplier (rarely used)
        applied to this move only", and M221 S "is the direct flow multiplier (to allow for undersized
        or oversized stock"; the page's example decodes `S1.0` as "(flow multiplier of 1.0)".  The pages
        give no upper limit, so any multiplier from 0 up is taken as written (`M221 S2.5` asks for 2.5
        times the flow, as a generator may mean it).  A negative multiplier is no stock size and asks for
        a negative flow: that is reported.  (On Marlin/RRF, S on G1 is laser power and M221 S a
        percentage; on Hyrel `M221 S95` is a multiplier of 95.)  The ranges are data in
        gclint/dialects/hyrel.py (`rule="HY033"`).
    """
    example_bad = "M221 T0 S-1"
    example_good = "M221 T0 S1.0"
    source = "Gcode page, G1 Working Move (Sn) and M221 Set Flow Rate (Sn)"
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        # G1 S is checked from the file's G0/G1 listener (``move``), not through the table's G0/G1 codes
        self.codes = tuple(c for c in self.codes if c not in ("G0", "G1"))
        self.moves = ctx.move_listener(MoveChecks)
        self.moves.join(self, "flow_multiplier")
        self.run_filter = self.moves.wants_in_run

    def move(self, line: Line, cmd: Command) -> None:
        """G1 lines with S (called by ``MoveChecks.move``)."""
        ParamTableRule.check(self, line, cmd)

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return (
            f"{cmd.code}: {problem}: S is a flow multiplier ('to allow for undersized or oversized stock'); "
            "a negative one asks for negative flow"
        )


@register
class PrimeSpeedUnits(Rule):
    code = "HY054"
    name = "prime-speed-units"
    severity = Severity.WARNING
    summary = "M721/M722 S is motor pulses per second (normally 10,000), not mm/s"
    explanation = """
        M721 (unprime) and M722 (prime) take S, "the speed at which unprime moves should be executed; this
        is normally 10,000" motor pulses per second, and E, a number of motor pulses.  A speed below 100
        looks like a retract speed in mm/s or mm/min copied from another firmware (Marlin's M207 F, RRF's
        M207 S), and makes the unprime crawl or never finish.  Lines with E0 (no unprime) are not reported.
    """
    example_bad = "M721 T0 S35 E100 P-15"
    example_good = "M721 T0 S10000 E100 P-15"
    source = "Gcode page, M721 Set Unprime Values and M722 Set Prime Values"
    codes = ("M721", "M722")
    families = ("hyrel",)

    LOWEST = 100.0

    def check(self, line: Line, cmd: Command) -> None:
        speed = cmd.get("S")
        if speed is None or speed >= self.LOWEST:
            return
        if cmd.get("E") == 0:
            return  # no pulses to move: the speed does not matter
        action = "unprime" if cmd.code == "M721" else "prime"
        self.report(
            line,
            f"{cmd.code} S{cmd.raw('S')}: the {action} speed is in motor pulses per second (normally 10,000); "
            f"{_fmt(speed)} looks like mm/s or mm/min from another firmware",
            node=cmd.param("S") or cmd,
        )


@register
class SlicerEWithoutM229(MoveRule):
    code = "HY060"
    name = "slicer-e-without-m229"
    severity = Severity.INFO
    summary = "Sliced E amounts in a file that never enables E values: native flow ignores them"
    explanation = """
        "If you do not use that command [M229 E1 D1], we do not use that E value (except to distinguish
        printing from non-printing moves) we calculate for flow based purely on travel speed, declared
        layer thickness, and nozzle diameter."  A file whose G1 moves carry changing E amounts, as slicers
        write them, and that has no M229 at all, prints with Hyrel's native flow: the widths come from
        M221 W and M756/M221 Z, not from the slicer.  Add `M229 E1 D1` to the header to use the E values.
        Reported once per file, at the first G1 with E.
    """
    example_bad = """
        G1 X10 Y10 E0.52 F1200
        G1 X20 Y10 E1.04
        G1 X20 Y20 E1.57
        G1 X10 Y20 E2.09
        G1 X10 Y11 E2.56
        M30
    """
    example_good = """
        M229 E1 D1
        G1 X10 Y10 E0.52 F1200
        G1 X20 Y10 E1.04
        G1 X20 Y20 E1.57
        G1 X10 Y20 E2.09
        G1 X10 Y11 E2.56
        M30
    """
    source = "Gcode page, Controlling Material Flow and G1 Working Move"
    slot = "slicer_e"

    DISTINCT = 5  # this many different E amounts look sliced (native Hyrel jobs write E1 on every move)
    # Sliced E amounts change from the first moves on: after this many G1 with E and fewer than DISTINCT
    # amounts, the job writes E as a printing mark and the rule stops looking.
    LOOK_AT = 2000

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.first: Line | None = None
        self.last: str | None = None
        self.amounts: list[str] = []
        self.sliced = False
        self.left = self.LOOK_AT

    def move(self, line: Line, cmd: Command) -> None:
        # called for G1 lines with E until the amounts look sliced
        text = cmd.params["E"]
        self.left -= 1
        if self.left <= 0:
            self.moves.slicer_e = None  # (this one is the last looked at)
        if text == self.last or text is None:
            return
        if self.state.m229_line is not None:
            self.moves.slicer_e = None  # the file uses M229: nothing to report
            return
        self.last = text
        if self.first is None:
            self.first = line
        if text not in self.amounts:
            self.amounts.append(text)
            if len(self.amounts) >= self.DISTINCT:
                self.sliced = True
                self.moves.slicer_e = None

    def finish(self) -> None:
        if self.sliced and self.state.m229_line is None and self.first is not None:
            shown = ", ".join(f"E{a}" for a in self.amounts[:3])
            self.report(
                self.first,
                f"the E amounts look sliced ({shown}, ...) but the file never enables E values: native flow "
                "ignores them and computes flow from speed, layer height (M756, M221 Z) and width (M221 W); "
                "add M229 E1 D1 to use them",
            )


# -- HY068 ---------------------------------------------------------------------------------------------

# What each head command does to its target (Gcode page, the code's section), for the message.
_HEAD_COMMAND_ACTS = {
    "M106": "sets a head's cooling fan or crosslinking LEDs",
    "M107": "turns off a head's cooling fan or crosslinking LEDs",
    "M221": "sets a head's flow (pulses per microliter, multiplier, width, height)",
    "M721": "sets a head's unprime (retract) values",
    "M722": "sets a head's prime (advance) values",
    "M620": "enables a head or emitter (laser, UV pen)",
}
_ALL_BEDS = 46  # T_v5, "Logical/Vurtual Device Addresses": T46 "All Beds / Chambers"


@register
class HeadCommandOnBed(Rule):
    code = "HY068"
    name = "head-command-on-bed"
    severity = Severity.WARNING
    summary = "A head command (M106, M107, M221, M721, M722, M620) addressed to a bed or chamber (T24, T25, T46)"
    explanation = """
        On Repetrel v5, M106, M107, M221, M721 and M722 act on the device of their T word, and the Gcode
        page says what that device is: "T# is the target head" (M106 Set Cooling / Etc., M721 Set
        Unprime Values, M722 Set Prime Values), "T# (target head)" (M107 Stop Cooling / Etc.), "T# is the
        tool (head) to which these values will be applied" (M221 Set Flow Rate), and for M620 Enable
        Device "T# (target head - MUST be specified, can NOT be inherited)" (its Parameters list says
        "T# is the tool position").  The T_v5 page's Chart of Addresses gives T24 to "Bed1 / Chamber1",
        T25 to "Bed2 / Chamber2" and T46 to "All Beds / Chambers": `M106 T24 S100` addresses a bed, which
        has no cooling fan, no flow and no prime, so the head the line was meant for is left unchanged.
        It is most often a T copied from an `M140 T24` line, or a v4 head number (v4 T24 was yoke 2,
        position 4: HY008 reports that reading when the file's addresses are v4).  Write the head's v5
        address (T0-T19), its yoke (T41-T44) or omit T for the focused head where the page allows it.
        What the firmware does with the line is not on the pages (inferred: it is ignored or refused,
        confidence low); M140/M141 are the bed and chamber commands.  Only v5 files: in v4 numbering
        T24 and T25 are heads.
    """
    # (the bed lines make the file's addresses v5: alone, M106 T24 reads as v4 numbering, HY008's case)
    example_bad = """
        M140 S60 T24
        M190 S60 T24
        M106 T24 S100
    """
    example_good = """
        M140 S60 T24
        M190 S60 T24
        M106 T0 S100
    """
    source = (
        "Gcode page, M106 Set Cooling / Etc., M107 Stop Cooling / Etc., M221 Set Flow Rate, "
        "M721 Set Unprime Values, M722 Set Prime Values, M620 Enable Device (T# is the target head); "
        "T_v5, Chart of Addresses"
    )
    codes = ("M106", "M107", "M221", "M721", "M722", "M620")
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        if "T" not in cmd.params or not is_v5(self.ctx) or reported_as_v4(self.ctx, cmd):
            return
        address = self.ctx.interpreter.address(cmd)
        if address is None:
            return
        if address.kind != BED and not (address.kind == GROUP and address.v5 == _ALL_BEDS):
            return
        code = str(cmd.code)
        self.report(
            line,
            f"{code} {_HEAD_COMMAND_ACTS[code]} (T# is the target head), but T{cmd.params['T']} is "
            f"{address.label}: write the head's address (T0-T19, or a yoke T41-T44); a bed or chamber is "
            "set with M140/M141",
            node=cmd.param("T"),
        )
