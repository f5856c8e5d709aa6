"""HY arc rules: G2/G3 and Hyrel's spirals (G2.1/G3.1, G2.2/G3.2) and 3-space arcs (G2.3/G3.3).

Sources: the Hyrel Gcode page ("G2 Clockwise Arc" ... "G3.3 3-Space CCW Arc", "G16"-"G19") and the
Hyrel firmware source (src/GCode.c: arc checks, G2.1/G3.1), see docs/sources.md.  Hyrel's plain G2/G3 take I/J only
(no R, no K), draw in the XY plane, and are printed with native flow even under M229 E1.
"""

from __future__ import annotations

import re

from gclint.dialects.base import Param
from gclint.rules.base import Rule, Severity, register
from gclint.rules.dialect import ParamTableRule
from gclint.syntax.fastpath import RUN_ARC, RUN_ARC_E, has_arcs, run_line_starts
from gclint.syntax.nodes import Command, Line, to_number

_PLAIN = ("G2", "G3")
_ALL_ARCS = ("G2", "G3", "G2.1", "G3.1", "G2.2", "G3.2", "G2.3", "G3.3")

# An arc of a run (plain number words: RUN_ARC) with no non-zero I or J: each word another letter's, or an I
# or J of zeros (from the line break before it)
_NO_CENTRE_ARC = re.compile(
    r"\nG[23](?:[ \t]++(?:[XYZEF][^ \t\r\n]*+|[IJ][-+]?+0*+\.?+0*+(?=[ \t\r\n])))*+[ \t]*+(?=\r?\n)"
)

# End and start closer than this (mm) are the same point: G-code is usually written to 3 decimals.
FULL_CIRCLE_TOLERANCE = 0.001


def arc_is_full_circle(cmd: Command, state) -> bool | None:
    """Whether a G2/G3 ends where it starts in XY (a complete 360 degree circle).

    X/Y omitted means "no change", so a full circle.  In absolute mode the end is compared with the
    current position; in relative mode (G91) the X/Y words are the displacement itself.  None when it
    cannot be known (start position unknown, a value that is not a number).
    """
    p = cmd.params
    for axis in ("X", "Y"):
        if axis not in p:
            continue
        text = p[axis]
        if text is None:
            continue  # a bare letter: no value, no change
        value = to_number(text)
        if value is None:
            return None
        if state.absolute:
            start = state.position.get(axis)
            if start is None:
                return None
            if abs(value - start) > FULL_CIRCLE_TOLERANCE:
                return False
        elif abs(value) > FULL_CIRCLE_TOLERANCE:
            return False
    return True


def _centre_is_zero(cmd: Command) -> bool:
    """True when I and J are both zero or omitted ("default 0"); False when either is non-zero or unknown."""
    p = cmd.params
    for letter in ("I", "J"):
        text = p.get(letter)
        if text is None:
            continue
        value = to_number(text)
        if value is None or value != 0:
            return False
    return True


@register
class ArcSegmentCountNotFullCircle(Rule):
    code = "HY016"
    name = "arc-segment-count-not-full-circle"
    severity = Severity.ERROR
    summary = "G2/G3 S of 3 or more (a segment count) on an arc that is not a full circle"
    explanation = """
        Hyrel's arc S sets the segments: "S values less than 3.0 dictate the length in mm of each segment
        for this element; S values of 3.0 or more dictate how many total segments comprise this element -
        only allowed on complete circles of 360°".  An arc whose end differs from its start (in absolute
        mode X/Y differ from the current position; in relative mode X/Y are not 0) cannot take a segment
        count, and the firmware ignores it.  Omitting X and Y draws a full circle.  S of 0 or less is no
        segment length at all (warning).
    """
    example_bad = """
        G1 X0 Y0 F1200
        G2 X20 Y0 I10 J0 E1 S6
    """
    example_good = """
        G1 X0 Y0 F1200
        G2 I10 J0 E1 S6
    """
    source = "Gcode page, G2 Clockwise Arc"
    codes = _PLAIN
    families = ("hyrel",)

    def run_filter(self, text: str, start: int, end: int) -> list[int]:
        """None of the arcs of a run (gclint.runs): they carry no S."""
        return []

    def check(self, line: Line, cmd: Command) -> None:
        text = cmd.params.get("S")
        if text is None:
            return
        s = to_number(text)
        if s is None:
            return
        if s <= 0:
            message = f"{cmd.code} S{text}: S must be a segment length (below 3 mm) or a segment count (3 or more)"
            self.report(line, message, node=cmd.param("S") or cmd, severity=Severity.WARNING)
        elif s >= 3 and arc_is_full_circle(cmd, self.state) is False:
            self.report(
                line,
                f"{cmd.code} S{text} is a segment count, only allowed on complete 360° circles, but this arc ends "
                "elsewhere: use S below 3 (segment length in mm) or omit X/Y for a full circle",
                node=cmd.param("S") or cmd,
            )


@register
class ArcRadiusOrK(ParamTableRule):
    code = "HY017"
    name = "arc-radius-or-k"
    severity = Severity.ERROR
    summary = "G2/G3 with R or K, or with no centre (I = J = 0)"
    explanation = """
        Hyrel's G2/G3 usage is `G2 Xn Yn Zn In Jn Fn En Sn`: the centre is given by I and J (relative to
        the start, "default 0").  There is no radius form (R) and no K: plain arcs are XY only.  With I
        and J both 0 (or omitted) the arc has no centre and the firmware stops with an invalid-arc error.
        Convert R arcs to I/J (slicers' arc fitting and CAM posts can write I/J).
    """
    example_bad = "G2 X20 Y0 R10 F1200"
    example_good = "G2 X20 Y0 I10 J0 F1200"
    source = "Gcode page, G2 Clockwise Arc"
    families = ("hyrel",)

    def run_filter(self, text: str, start: int, end: int) -> list[int]:
        """The arcs of a run (gclint.runs: no R or K) with no non-zero I or J."""
        return run_line_starts(_NO_CENTRE_ARC, text, start, end) if has_arcs(text, start, end) else []

    def check(self, line: Line, cmd: Command) -> None:
        super().check(line, cmd)  # R and K are forbidden (table: G2/G3)
        if "R" not in cmd.params and _centre_is_zero(cmd):
            self.report(
                line,
                f"{cmd.code} has no centre: I and J are both 0 or omitted (the firmware rejects the arc)",
                node=cmd,
            )

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"{cmd.code}: {problem}"


@register
class SpiralLapParameters(ParamTableRule):
    code = "HY018"
    name = "spiral-lap-parameters"
    severity = Severity.ERROR
    summary = "G2.1/G3.1 spiral: P required, L a positive integer, R 0/1/2, no X/Y"
    explanation = """
        G2.1/G3.1 spiral around a centre and end where they started: "Pn is the pitch (how close the laps
        are) in mm (required)"; "Ln is the number of laps to complete (must be a positive integer)"; "Rn is
        a flag; 0 to spiral in (default), 1 to spiral out (after inward jump), 2 spiral out from current
        position"; "Effective ending X/Y is always the same as the current XY and is not specified" (the
        firmware stops on X/Y).  The firmware also needs L with R2 and a centre (I and J not both 0).
    """
    example_bad = "G2.1 X10 I15 J20 E1"
    example_good = "G2.1 I15 J20 P1.2 E1"
    source = "Gcode page, G2.1 Spiral CW Arc^1; Hyrel firmware source, src/GCode.c ProcessG2_1G3_1Command"
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        super().check(line, cmd)  # P required, L, R, X/Y (table: G2.1/G3.1)
        p = cmd.params
        if p.get("R") is not None and to_number(p["R"]) == 2 and "L" not in p:  # type: ignore[arg-type]
            message = f"{cmd.code} R2 (spiral out from here) needs L, the number of laps"
            self.report(line, message, node=cmd.param("R") or cmd)
        if _centre_is_zero(cmd):
            self.report(line, f"{cmd.code} has no centre: I and J are both 0 or omitted", node=cmd)

    def missing_message(self, cmd: Command, p: Param) -> str:
        return f"{cmd.code} needs P, the pitch between laps in mm (required)"

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"{cmd.code}: {problem}"


@register
class SpiralNeedsPitchOrLaps(Rule):
    code = "HY019"
    name = "spiral-needs-pitch-or-laps"
    severity = Severity.ERROR
    summary = "G2.2/G3.2 spiral with neither P (pitch) nor L (laps)"
    explanation = """
        G2.2/G3.2 spiral from the current position to X/Y: "if P and L values conflict, L will be modified
        to match what P will allow; at least one must be specified".  Without both the spiral is undefined
        (error); with both, L may be changed to fit P (info).
    """
    example_bad = "G2.2 X12 I25 E1"
    example_good = "G2.2 X12 I25 P4 E1"
    source = "Gcode page, G2.2 Spiral CW Arc^2"
    codes = ("G2.2", "G3.2")
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        p = cmd.params
        if "P" not in p and "L" not in p:
            message = f"{cmd.code} needs P (pitch between laps, mm) or L (number of laps); at least one must be given"
            self.report(line, message, node=cmd)
        elif "P" in p and "L" in p:
            self.report(
                line,
                f"{cmd.code} with both P and L: if they conflict, L is changed to match P",
                node=cmd.param("L") or cmd,
                severity=Severity.INFO,
            )


@register
class ArcEAmountIgnored(Rule):
    code = "HY037"
    name = "arc-e-amount-ignored"
    severity = Severity.WARNING
    summary = "An arc with E under M229 E1: the E amount is ignored, arcs use native flow"
    explanation = """
        Every Hyrel arc says: "We will print this element with our native Hyrel flow calculations (based on
        nozzle diameter, layer thickness, and feed rate) even if your gcode has enabled the use of E values
        with M229 E1 D1."  The E amount of an arc (from a slicer's arc fitting) only marks it as printing;
        its flow is the native one, so it may over- or under-extrude next to the E-driven lines.  Which
        layer thickness the native calculation of an arc uses under M229 E1 the pages do not say: M756
        "is ignored if you are using M229 E1 D1" (HY014), and M221 Z is the head's layer thickness that
        "your gcode M756 will overwrite".  Turn off arc fitting in the slicer, or check the head's flow
        settings (M221 W and Z).
    """
    example_bad = """
        M229 E1 D1
        G1 X0 Y0 F1200
        G2 X20 Y0 I10 J0 E0.8
    """
    example_good = """
        M229 E1 D1
        G1 X0 Y0 F1200
        G1 X20 Y0 E0.8
    """
    source = "Gcode page, G2 Clockwise Arc"
    codes = _ALL_ARCS
    families = ("hyrel",)

    def run_filter(self, text: str, start: int, end: int) -> list[int]:
        """The arcs of a run with E under M229 E1 (a line of a run changes neither)."""
        return (
            run_line_starts(RUN_ARC_E, text, start, end) if self.state.e_values() and has_arcs(text, start, end) else []
        )

    def check(self, line: Line, cmd: Command) -> None:
        if "E" in cmd.params and self.state.e_values():
            self.report(
                line,
                f"{cmd.code} is printed with native flow even under M229 E1 (line {self.state.m229_line}): its E "
                "amount is ignored; the flow is 'based on nozzle diameter, layer thickness, and feed rate', and "
                "the pages do not say which layer thickness, M756 being ignored under M229 E1 D1",
                node=cmd.param("E") or cmd,
            )


@register
class PlainArcInOtherPlane(Rule):
    code = "HY052"
    name = "plain-arc-in-other-plane"
    severity = Severity.WARNING
    summary = "G2/G3 after G16/G18/G19: plain arcs are drawn in the XY plane only"
    explanation = """
        "G16 through G19 only apply to G2.x and G3.x commands."  Plain G2/G3 are always drawn in the XY
        plane, so an arc written for the XZ or YZ plane (G18/G19 in LinuxCNC or Marlin) is drawn in XY on
        Hyrel.  Use G2.3/G3.3 for arcs outside the XY plane.
    """
    example_bad = """
        G18
        G2 X10 Z5 I5 J0 F600
    """
    example_good = """
        G18
        G2.3 X10 Z5 I5 K0 F600
    """
    source = "Gcode page, G16-G19 Arc Plane"
    codes = _PLAIN
    families = ("hyrel",)

    def run_filter(self, text: str, start: int, end: int) -> list[int]:
        """Every arc of a run outside the XY plane (a line of a run does not change the plane)."""
        return (
            run_line_starts(RUN_ARC, text, start, end) if self.state.plane != 17 and has_arcs(text, start, end) else []
        )

    def check(self, line: Line, cmd: Command) -> None:
        plane = self.state.plane
        if plane != 17:
            message = (
                f"{cmd.code} is drawn in the XY plane: the G{plane} plane applies only to G2.x/G3.x arcs "
                "(use G2.3/G3.3)"
            )
            self.report(line, message, node=cmd)


@register
class ArcNormalOutsideG16(Rule):
    code = "HY064"
    name = "arc-normal-outside-g16"
    severity = Severity.WARNING
    summary = "G2.3/G3.3 with U, V or W outside G16: the normal vector is ignored"
    explanation = """
        G2.3 and G3.3 draw arcs in 3-space; U, V and W are "the X/Y/Z component of a vector normal to the
        working plane".  The page: "If we are in G16 mode, Un, Vn, Wn define the vector normal to the
        work plane.  If we are in G17 (X/Y plane) or G18 (X/Z plane) or G19 (Y/Z plane) mode, these are
        ignored."  A G2.3 with U/V/W under G17 (the default), G18 or G19 is drawn in that plane, not in
        the one the vector describes.  Put G16 before it, or drop U/V/W.
    """
    example_bad = """
        G17
        G2.3 X10 Y0 Z5 I5 J0 K0 U0 V1 W1
    """
    example_good = """
        G16
        G2.3 X10 Y0 Z5 I5 J0 K0 U0 V1 W1
    """
    source = "Gcode page, G2.3 3-Space CW Arc (note on G16-G19) and G3.3 3-Space CCW Arc"
    codes = ("G2.3", "G3.3")
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        plane = self.state.plane
        if plane == 16:
            return
        given = [letter for letter in "UVW" if letter in cmd.params]
        if given:
            word = cmd.param(given[0])
            self.report(
                line,
                f"{cmd.code} {'/'.join(given)} under G{plane}: the normal vector applies only in G16 mode ('If we "
                "are in G17 ... or G18 ... or G19 ... mode, these are ignored'); the arc is drawn in the "
                f"G{plane} plane",
                node=word or cmd,
            )
