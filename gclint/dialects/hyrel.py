"""Hyrel (Repetrel / Hydra motion controller), firmware v5 and v4.

Every code, parameter and range here comes from the Hyrel wiki's "Gcode" page
(https://hyrel3d.com/wiki/index.php/Gcode; section names in the ``source`` fields), the T_v5 page and the
hidden-codes page Sekret! (addresses and revisions: docs/sources.md).  Ranges that a specific rule reports
carry that rule's code (``rule="HY0nn"``); the others are reported by DL003.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TypedDict

from gclint.dialects.addressing import (
    resolve_v4_command,
    resolve_v4_variable,
    resolve_v5,
)
from gclint.dialects.base import (
    Clue,
    Code,
    Detection,
    Dialect,
    LineMark,
    Param,
    code,
    has_all,
    has_any,
    table,
    value_at_least,
)
from gclint.dialects.habits import HYREL_HABITS
from gclint.dialects.semantics import DWELL_MS_S_SUM, WORKSPACES, Semantics, effects

P = Param


class _Bounds(TypedDict):  # (Param keyword arguments shared by many parameters)
    minimum: float
    maximum: float


class _Choices(TypedDict):
    choices: tuple[float, ...]


PCT = _Bounds(minimum=0, maximum=100)  # "Sn is the percentage (0-100)"
FLAG01 = _Choices(choices=(0, 1))

AXES = [P("X"), P("Y"), P("Z"), P("A"), P("B")]


def _axes(meaning: str) -> list[Param]:
    return [P(a.letter, f"{meaning} {a.letter}") for a in AXES]


def _move_axes() -> list[Param]:
    # G0/G1 "Any values not stipulated remain unchanged" ("(no change in A)", "(no change in B)")
    return [replace(p, absent=f"no change in {p.letter}") if p.letter in "AB" else p for p in _axes("target")]


# G1 "Hn is the stored head offset to apply (see M660 to store offsets)": "H2 (invoke offsets stored in register H2)"
_HEIGHT_REGISTER = P(
    "H",
    "apply the M660 tool-height register",
    minimum=0,
    maximum=59,
    integer=True,
    rule="HY034",
    says="invoke the offsets stored in register H{value}",
)
# G2 "We will print this element with our native Hyrel flow calculations (based on nozzle diameter, layer
# thickness, and feed rate) even if your gcode has enabled the use of E values with M229 E1 D1."
_NATIVE_FLOW = "printed with Hyrel's native flow (nozzle, layer, feed) even under M229 E1"
# G2.1 "Effective ending X/Y is always the same as the current XY and is not specified"
_LAPS_AROUND = "ends where it starts in X/Y (full laps around the center)"


def _turning(
    clockwise: tuple[str, str],
    counter: tuple[str, str],
    summary: str,
    *params: Param,
    does: tuple[str, ...] = (),
    notes: tuple[str, ...] = (),
) -> list[Code]:
    # G3, G3.x and M4: "Please refer to G2 (M3), above, for details. All options are identical, with the
    # exception of direction (counterclockwise)."  ``(code, section)`` of each; "{direction}" in the texts.
    return [
        code(
            name,
            summary.format(direction=direction),
            *params,
            source=section,
            does=tuple(text.format(direction=direction) for text in does),
            notes=notes,
        )
        for (name, section), direction in ((clockwise, "clockwise"), (counter, "counter-clockwise"))
    ]


def _aux(name: str, summary: str, section: str) -> Code:
    # "Sn is the percentage (0-100; no default - if no Sn, no change)" (Controlling Aux Devices)
    return code(name, summary, P("S", "percent power", rule="HY044", **PCT), source=section)


def _wait(target: Param, set_point: Param) -> list[Param]:
    # M109/M190/M191 "T# Sn Hn Cn Ln Un Rn [v5+] W0"; the readings are the page's examples ("H230 (but end
    # the wait once the target's temperature reaches 230°C)", "W0 (but do not pause until M116 is executed)")
    return [
        target,
        set_point,
        P(
            "H",
            "stop waiting once heated up to this absolute temperature",
            says="but end the wait once the temperature reaches {value}°C",
        ),
        P(
            "C",
            "stop waiting once cooled down to this absolute temperature",
            says="or end the wait once the temperature cools down to {value}°C",
        ),
        P(
            "L",
            "stop waiting this many degrees below S",
            says="but end the wait once the temperature reaches {value}°C below the set point",
        ),
        P(
            "U",
            "stop waiting this many degrees above S",
            says="or end the wait once the temperature reaches {value}°C above the set point",
        ),
        P(
            "R",
            "stop waiting within +/- this many degrees of S",
            says="but end the wait once the temperature is within +/-{value}°C of the set point",
        ),
        P(
            "W",
            "W0: set, do not wait until M116 (v5+)",
            choices=(0,),
            values={"0": "but do not pause until M116 is executed (v5+)"},
        ),
    ]


# "Sn (optional) is the new set temperature in °C; if omitted, no new target temperature is set" (M109)
_WAIT_S = P(
    "S",
    "set temperature, C (optional)",
    says="and set the temperature to {value}°C",
    absent="no S: no new temperature is set",
)
# M109 Wait for Temp (Head): "we have both heated and chilled (sub-ambient) heads": no lowest set point,
# but below 0 °C is mentioned (HY051, info).
_WAIT_HEAD = _wait(P("T", "target device"), replace(_WAIT_S, minimum=0, rule="HY051"))
# M190/M191: "T# is the target bed / chamber"; without T, the one with focus (the primary one)
_WAIT_BED = _wait(
    P(
        "T",
        "target device",
        says="target bed: {value}",
        absent="no T: use the bed with current focus (the primary bed)",
    ),
    _WAIT_S,
)
_WAIT_CHAMBER = _wait(
    P(
        "T",
        "target device",
        says="target chamber: {value}",
        absent="no T: use the chamber with current focus (the primary chamber)",
    ),
    _WAIT_S,
)

# G2/G2.x "In is the relative distance from the current X position to the center position about which
# to arc" ("I15 (15mm further in the X)"); "Sn dictates how many segments ...; 0.33333 mm is the default"
_CENTRE_I = "centered about a point {value} mm further in X"
_CENTRE_J = "centered about a point {value} mm further in Y"
_SEGMENTS = "default segments of 0.33333 mm"
# "En indicates a working or printing move" ("E1 (while extruding)")
_EXTRUDING = "while extruding"

_ARC = [
    P("X", "end X"),
    P("Y", "end Y"),
    P("Z", "end Z"),
    P("I", "centre X offset from the start", says=_CENTRE_I),
    P("J", "centre Y offset from the start", says=_CENTRE_J),
    P("F", "feed rate, mm/min", says="moving at {value} mm/min", absent="using the previously established F rate"),
    P("E", "printing move", says=_EXTRUDING),
    P("S", "segment length (<3) or segment count (>=3, full circles only)", absent=_SEGMENTS),
    # G2 Clockwise Arc: usage "G2 Xn Yn Zn In Jn Fn En Sn" -- no R (radius) and no K; the firmware
    # draws plain G2/G3 in XY only (Hyrel firmware source, src/GCode.c ProcessG2G3Command).
    P("R", "radius form is not supported", rule="HY017", forbidden=True),
    P("K", "K is not supported on G2/G3", rule="HY017", forbidden=True),
]

# G2.1/G2.2 examples: "L50 (complete no more than 50 laps)", "(complete all laps)", "P0.5 (0.5 mm between
# centers of travel of adjacent laps)", "F1200 (at a speed of 1200 mm/min)", "(moving at established G1 F speed)"
_LAPS = "complete no more than {value} laps"
_ALL_LAPS = "complete all laps"
_PITCH = "{value} mm between centers of travel of adjacent laps"
_SPIRAL_FEED = "at a speed of {value} mm/min"
_SPIRAL_FEED_ABSENT = "moving at the established G1 F speed"

_SPIRAL1 = [
    # G2.1 Spiral CW Arc^1: "Pn is the pitch ... (required)", "Ln ... must be a positive integer",
    # "Rn is a flag; 0 ... 1 ... 2", "Effective ending X/Y is always the same as the current XY".
    P("Z", "end Z"),
    P("I", "centre X offset", says=_CENTRE_I),
    P("J", "centre Y offset", says=_CENTRE_J),
    P("P", "pitch between laps, mm", required=True, rule="HY018", says=_PITCH),
    P("L", "number of laps", integer=True, minimum=1, rule="HY018", says=_LAPS, absent=_ALL_LAPS),
    P("E", "printing move", says=_EXTRUDING),
    P("S", "segment length or count", absent=_SEGMENTS),
    P(
        "R",
        "0 spiral in, 1 spiral out after inward jump, 2 spiral out",
        choices=(0, 1, 2),
        rule="HY018",
        values={
            "0": "spiral in toward the center from the current location",
            "1": "spiral out from the center to the current location (after an inward jump)",
            "2": "spiral out from the current position",
        },
        absent="default R0: spiral in toward the center",
    ),
    P("F", "feed rate", says=_SPIRAL_FEED, absent=_SPIRAL_FEED_ABSENT),
    P("X", "a G2.1/G3.1 spiral ends where it starts: no X", rule="HY018", forbidden=True),
    P("Y", "a G2.1/G3.1 spiral ends where it starts: no Y", rule="HY018", forbidden=True),
]

_SPIRAL2 = [
    P("X", "end X"),
    P("Y", "end Y"),
    P("Z", "end Z"),
    P("I", "centre X offset", says=_CENTRE_I),
    P("J", "centre Y offset", says=_CENTRE_J),
    P("P", "pitch between laps, mm", says=_PITCH),
    P("L", "number of laps", says=_LAPS, absent=_ALL_LAPS),
    P("E", "printing move", says=_EXTRUDING),
    P("S", "segment length or count", absent=_SEGMENTS),
    P("R", "direction flag"),
    P("F", "feed rate", says=_SPIRAL_FEED, absent=_SPIRAL_FEED_ABSENT),
]

_SPIRAL3 = [
    *_axes("end"),
    P("I", "centre X offset"),
    P("J", "centre Y offset"),
    P("K", "centre Z offset"),
    P("U", "normal vector X (G16 only)"),
    P("V", "normal vector Y (G16 only)"),
    P("W", "normal vector Z (G16 only)"),
    P("D", "displacement normal to the plane"),
    P("P", "pitch normal to the plane"),
    P("E", "printing move"),
    P("S", "segment length or count", absent=_SEGMENTS),
    P("F", "feed rate"),
]

# M3 "Sn - power (0-100%)", "Note: S0 is the same as turning it off", "Fn - optional; PWM in Hz", "(default
# PWM)", "Note: DO NOT CHANGE DIRECTION while the spindle is in motion."
_SPINDLE = [
    P("T", "target head"),
    P(
        "S",
        "power, percent",
        rule="HY023",
        says="at {value}% power",
        values={"0": "S0: the same as turning it off"},
        **PCT,
    ),
    P("F", "PWM frequency, Hz", says="PWM at {value} Hz", absent="default PWM"),
]
_SPINDLE_NOTES = ("do not change direction while the spindle is in motion",)


# The actions an M0 (or M792) runs from its comment, "M0 [ SAY | PIC | VID | SEND | BEEP | SHELL ]": "SAY sample
# message - the computer will use built-in text-to-speech", "PIC ... will display the image", "VID ... will play
# the video", "SEND ... will send the message to the Aux port", "BEEP - the computer will sound a beep", "SHELL
# C:\program.exe - the computer will execute the file" (M0 Stop Until Resume; M792 Execute Action)
ACTIONS = {
    "SAY": "announce text",
    "PIC": "display image",
    "VID": "play video",
    "SEND": "send to the Aux port",
    "BEEP": "sound a beep",
    "SHELL": "execute the program",
}


def _prime(action: str) -> list[Param]:
    # M721/M722 examples: "S10000 (set rate to 10,000 pps)", "E100 (set pulses to 100)", "I1 (now)", "(but no
    # immediate execution; execute when needed)"
    return [
        P("S", "speed, pulses per second (normally 10,000)", says="set rate to {value} pulses per second"),
        P("E", "motor pulses", says="set pulses to {value}"),
        P("P", "milliseconds relative to the end/start of the move"),
        P("T", "target head"),
        P(
            "I",
            "I1: execute now",
            values={"1": f"{action} now"},
            absent=f"no immediate execution: {action} when needed",
            **FLAG01,
        ),
    ]


HYREL_CODES = table(
    # -- Controlling Movement -------------------------------------------------------------------------
    code(
        "G0",
        "rapid (non-working) move",
        *_move_axes(),
        # "Fn is the feed rate ... Only on G0 is it not persistent"; "(no change in F, use settings-specified
        # feed rate)"
        P("F", "one-shot feed rate, mm/min", absent="no F: use the G0 speed from the settings (or M203)"),
        P("E", "not meaningful on G0 (HY030)"),
        # "Usage G0 Xn Yn Zn An Bn Fn" has no H (G1's has: "Hn is the stored head offset to apply"), but the
        # firmware applies it on a G0 as on a G1: both queue the move through motionQ_addCommand, which takes the
        # register from H (Hyrel firmware source, src/MotorDrivers.c; HY034)
        _HEIGHT_REGISTER,
        source="G0 Rapid Move",
    ),
    code(
        "G1",
        "working move",
        *_move_axes(),
        # "In native mode ... the value of Extrusion rate E will be ignored, but E will trigger a working
        # or printing move. In E-value mode (by adding M229 E1 Dn, the slicer-determined E value will be used"
        P(
            "E",
            "printing move (amount used only under M229 E1)",
            says="while extruding; native flow ignores the amount (M229 E1 D1 uses it)",
        ),
        P("F", "feed rate, mm/min (persistent)"),
        _HEIGHT_REGISTER,
        # "Sn is a one-time (non-persistent) material flow rate multiplier (rarely used) applied to this move
        # only": the page gives no limit; a multiplier of flow is not negative (HY033)
        P(
            "S",
            "one-shot flow multiplier",
            minimum=0,
            rule="HY033",
            says="one-time flow multiplier {value} for this move only",
        ),
        source="G1 Working Move",
        does=("working speed straight line move from the current location",),
    ),
    *_turning(
        ("G2", "G2 Clockwise Arc"),
        ("G3", "G3 Counterclockwise Arc"),
        "{direction} arc",
        *_ARC,
        does=("working speed {direction} arc/circle move from the current location",),
        notes=(_NATIVE_FLOW,),
    ),
    *_turning(
        ("G2.1", "G2.1 Spiral CW Arc^1"),
        ("G3.1", "G3.1 Spiral CCW Arc^1"),
        "{direction} spiral (laps around the start)",
        *_SPIRAL1,
        does=("working speed {direction} spiral move from the current location", _LAPS_AROUND),
    ),
    *_turning(
        ("G2.2", "G2.2 Spiral CW Arc^2"),
        ("G3.2", "G3.2 Spiral CCW Arc^2"),
        "{direction} spiral to X/Y",
        *_SPIRAL2,
        does=("working speed {direction} spiral move from the current location",),
    ),
    # "Unlike G2, G2.1 and G2.2, G2.3 is not bound to the X/Y plane."
    *_turning(
        ("G2.3", "G2.3 3-Space CW Arc"),
        ("G3.3", "G3.3 3-Space CCW Arc"),
        "{direction} 3-space arc",
        *_SPIRAL3,
        does=("working speed {direction} arc in 3-space (not bound to the X/Y plane)",),
    ),
    code(
        "G4",
        "timed pause (S seconds + P milliseconds)",
        P("S", "seconds", minimum=0),
        P("P", "milliseconds", minimum=0),
        source="G4 Timed Pause",
    ),
    code("G16", "arc plane: any (G2.x/G3.x only)", source="G16 Arc Plane: Any"),
    code("G17", "arc plane: XY (G2.x/G3.x only)", source="G17 Arc Plane: XY"),
    code("G18", "arc plane: XZ (G2.x/G3.x only)", source="G18 Arc Plane: XZ"),
    code("G19", "arc plane: YZ (G2.x/G3.x only)", source="G19 Arc Plane: YZ"),
    code(
        "M0",
        "pause until resume (text after ';' is shown; SAY/PIC/VID/SEND/BEEP/SHELL actions)",
        source="M0 Stop Until Resume",
        # "clicking the Play button ... will cause the job to resume"; "All text following the ; will be
        # echoed to the print mask"
        does=("pause until the operator clicks Play; text after ';' is shown on the print mask",),
    ),
    code("M203", "set G0 speed per axis, mm/min", *_axes("G0 speed, mm/min, for"), source="M203 Set G0 Speed"),
    # -- Controlling Temperature ----------------------------------------------------------------------
    code(
        "M104",
        "set head temperature (no wait)",
        P("S", "temperature, C", minimum=0, rule="HY051"),
        P("T", "target head"),
        P("C", "enable chiller (firmware)"),
        source="M104 Set Temp (Head)",
    ),
    # "S50 (target value of 50)", "C255 (of range 0-255)"; "all following M106 commands for the rest of this
    # print job will be based on this range"; "P100 (during extrusion moves at 100% duty cycle"
    code(
        "M106",
        "fan / UV LED duty",
        P("T", "target head"),
        P("S", "duty as a share of the C range", says="target value of {value}", absent="no speed"),
        P(
            "C",
            "range used by all later M106 (100 default, 255 for slicers)",
            minimum=1,
            maximum=255,
            rule="HY012",
            says="of range 0-{value}: all following M106 commands of this job use this range",
        ),
        P(
            "P",
            "duty during extrusion moves only, percent",
            rule="HY011",
            says="during extrusion moves only, at {value}% duty",
            **PCT,
        ),
        source="M106 Set Cooling / Etc.",
    ),
    # "this is essentially the same as an M106 S0 (setting it to 0 percent). This will also turn off the
    # Quiet Storm fan."
    code(
        "M107",
        "fan / UV LED off",
        P("T", "target head"),
        source="M107 Stop Cooling / Etc.",
        does=("set cooling/LEDs to 0% (same as M106 S0); also turns off the Quiet Storm fan",),
    ),
    code("M109", "wait for head temperature", *_WAIT_HEAD, source="M109 Wait for Temp (Head)"),
    code(
        "M116",
        "wait for all temperatures set with W0 (v5+)",
        source="M116 Wait for Temps (v5+)",
        does=("pause until every temperature set with W0 (M109/M190/M191) is reached",),
    ),
    code(
        "M140",
        "set bed temperature (no wait)",
        # "heated and chilled (sub-ambient) beds" (M190): the page gives no lowest set point
        P("S", "temperature, C"),
        # "T# is the target bed (default is the primary bed)"
        P("T", "target bed (default primary)", says="target bed: {value}", absent="no T: the primary bed"),
        source="M140 Set Temp (Bed)",
    ),
    code(
        "M141",
        "set chamber temperature (no wait)",
        # "heated and chilled (sub-ambient) chambers" (M191): the page gives no lowest set point
        P("S", "temperature, C"),
        # "T# is the target chamber (default is the primary chamber)"
        P("T", "target chamber", says="target chamber: {value}", absent="no T: the primary chamber"),
        source="M141 Set Temp (Chamber)",
    ),
    code("M190", "wait for bed temperature", *_WAIT_BED, source="M190 Wait for Temp (Bed)"),
    code("M191", "wait for chamber temperature", *_WAIT_CHAMBER, source="M191 Wait for Temp (Chamber)"),
    # -- Controlling Material Flow --------------------------------------------------------------------
    Code("G10", "not recognized by Repetrel (offsets: M6; retract: M721)", {}, False, "G10 UNUSED"),
    Code("G11", "not recognized by Repetrel (unretract: M722)", {}, False, "G11 UNUSED"),
    code("M82", "absolute E values (only under M229 E1)", source="M82 Absolute E-Values"),
    code("M83", "relative E values (only under M229 E1)", source="M83 Relative E-Values"),
    code(
        "M221",
        "flow: pulses per ul (P), multiplier (S), width (W), layer (Z)",
        P("P", "pulses per microliter (volumetric) or per mm (linear)", minimum=0.000001),
        # "Sn is the direct flow multiplier (to allow for undersized or oversized stock": no limit on the page;
        # "S1.0 (flow multiplier of 1.0)"
        P(
            "S",
            "direct flow multiplier (for undersized or oversized stock)",
            minimum=0,
            rule="HY033",
            says="flow multiplier of {value}",
        ),
        P("W", "path width, mm", minimum=0.000001),
        P("Z", "layer height, mm", minimum=0.000001),
        P("T", "target head"),
        source="M221 Set Flow Rate",
    ),
    code(
        "M229",
        "use E values (E1) or native flow (E0); D routing",
        # "En can be 0 (native flow calculation) or 1 (use E values)"; native flow is computed from the
        # speed, the layer height and the nozzle (G1, M221, M756)
        P(
            "E",
            "0 native flow, 1 use E values",
            choices=(0, 1),
            values={
                "0": "disabled: native flow from speed, layer height and nozzle; E marks printing moves",
                "1": "enabled: the slicer's E values drive the flow",
            },
        ),
        # "Dn how directed to head": D0 ... D3
        P(
            "D",
            "step routing 0-3",
            choices=(0, 1, 2, 3),
            values={
                "0": "flow calculations on the head controller; constant, not adjusted for acceleration",
                "1": "flow calculations directed via CANBUS and adjusted to motion acceleration/deceleration",
                "2": "on the motion controller, sent to the head via the C axis step pin, adjusted for acceleration",
                "3": "on the motion controller, sent via CANBUS and the C axis, adjusted for acceleration",
            },
        ),
        # "Sn sets a threshold in seconds; isolated non-printing moves below this threshold will not trigger
        # unprime/prime actions"
        P(
            "S",
            "seconds: shorter travels skip unprime/prime",
            minimum=0,
            says="isolated non-printing moves of under {value} seconds will not trigger unprime/prime actions",
        ),
        source="M229 Use E Values",
    ),
    code(
        "M721",
        "unprime (retract) settings; I1 unprimes now",
        *_prime("unprime (retract)"),
        source="M721 Set Unprime Values",
    ),
    code("M722", "prime settings; I1 primes now", *_prime("prime (advance)"), source="M722 Set Prime Values"),
    code(
        "M723",
        "manual extrusion (manual operation)",
        P("S", "pulses per second"),
        P("E", "pulses"),
        P("T", "target head"),
        source="M723 Set Manual Flow",
    ),
    code("M728", "motor current boost", P("S", "boost"), P("T", "target head"), source="M728 Set Motor Current Boost"),
    code(
        "M756",
        "layer height for native flow, mm",
        P("S", "layer height, mm", required=True, minimum=0.000001),
        source="M756 Set Height for Flow",
    ),
    # -- Controlling Position and Offsets -------------------------------------------------------------
    code("G20", "inches (experimental, unsupported)", source="G20 Set Units to Inches"),
    code("G21", "millimetres", source="G21 Set Units to Millimeters"),
    # "G28 sends the X and/or Y axes to the sensor-defined physical home position ..., then pop-off and
    # re-acquire the sensor threshold at a slower rate"; "After homing, a G28 also resets current offsets to
    # 0 - including any may have been set with a G92 or an H (as defined in an M660 and invoked on a G1),
    # performs a G53, and applies a head offset of 0 mm"; "Any axis not homed will have its position remain
    # unchanged"
    code(
        "G28",
        "home the listed axes (X0 Y0 [Z0 A0 B0]); clears G92, H and fixture offsets",
        *[P(a, f"home {a}", rule="HY025", says=f"home the {a} axis", absent=f"{a} remains unchanged") for a in "XYZAB"],
        P("I", "undocumented flag"),
        source="G28 Send X, Y to Physical Home",
        does=("send the listed axes to their sensor-defined physical home, then pop off and re-acquire slowly",),
        notes=(
            "afterwards G92 and H (M660) offsets are cleared, a G53 is performed and a head offset of 0 is applied",
        ),
    ),
    code("G53", "clear fixture offsets (modal)", source="G53 Clear Offsets"),
    *[
        code(f"G{n}", "store and apply fixture offsets", *_axes("offset in"), source="G54 - G59 - Set Offsets")
        for n in range(54, 60)
    ],
    code("G90", "absolute positioning (X Y Z A B)", source="G90 Absolute Positioning"),
    code("G91", "relative positioning (X Y Z A B)", source="G91 Relatative Positioning"),
    code(
        "G92",
        "set the current position",
        *_axes("new position of"),
        P("E", "new E position"),
        source="G92 Reset Coordinate Offsets",
    ),
    code("G93", "clear all G92 offsets (not inverse-time feed)", source="G93 Clear Coordinate Offsets"),
    # "M6 (Declare Head Offsets) ** T# (target head) ** O1 (offset stored in register "O1") ... ** (no move)";
    # "M6 K1 ... ** (all future T# or M6 commands) ... ** K1 (always force I0 with M6 unless K0 present"; "This
    # happens (for every head loaded) when you click print"; "T executes a tool change, invoking the parameters
    # specified in the M6" (T Tool Change)
    code(
        "M6",
        "declare head offsets (not a tool change)",
        # (the page decodes a T-less M6 only in its K1 example, "(all future T# or M6 commands)", which is about K)
        P("T", "head", absent="no T: no head is named (only the page's M6 K1 example has no T: K for all future M6)"),
        P(
            "O",
            "offset register",
            minimum=0,
            maximum=59,
            integer=True,
            rule="HY061",
            says='offset stored in register "O{value}"',
            # the M6 K1 example: "(no offset registers, so ignore all offsets)"
            absent="no offset register, so the offsets are ignored (as the page decodes an M6 without O)",
        ),
        *_axes("offset in"),
        P("D", "tool diameter", says="tool diameter {value} mm (pocket commands)"),
        P(
            "I",
            "I1: move now (non-persistent)",
            says="store the values, no move",
            values={"1": "store and move these distances"},
            absent="no move",
            **FLAG01,
        ),
        P(
            "K",
            "K1: always act as I0 (persistent)",
            says="use the I value",
            values={"1": "always force I0 with M6 unless K0 is given"},
            **FLAG01,
        ),
        source="M6 Declare Head Offsets",
        notes=("Repetrel sends one M6 per loaded head when a job starts; it is not a tool change (T is)",),
    ),
    # "H2 (store in register 2)"; "Z28.2 (+28.2 to Z position)"
    code(
        "M660",
        "store a tool-height offset register (apply with H on G1)",
        P(
            "H",
            "register",
            required=True,
            minimum=0,
            maximum=59,
            integer=True,
            rule="HY034",
            says="store in register {value}",
        ),
        P("Z", "Z offset, mm", says="{value} to the Z position"),
        P("D", "diameter (firmware)"),
        source="M660 Assign Tool Height Offset",
    ),
    # T_v5 M702: "T# is the head from which flow (pulse/prime/etc) settings will be copied and applied to the
    # group"; "a group of heads that will perform the same exact (extrusion) commands"; "Note that an M30
    # decommissions any clone squads that were in effect."
    code(
        "M702",
        "establish clone squad S (30-39) with T's flow settings",
        P("T", "head whose settings are copied", says="using the flow values (pulse, prime, unprime) from: {value}"),
        P(
            "S",
            "squad number",
            required=True,
            minimum=30,
            maximum=39,
            integer=True,
            rule="HY022",
            says="designate clone squad T{value}: its heads will perform the same extrusion commands",
        ),
        source="M702 Establish Clone Squad (T_v5)",
        notes=("an M30 decommissions every clone squad",),
    ),
    # M703 and M704 read T and S as a squad (S 30-39) or as a head to copy: gclint.explain.addressing
    code(
        "M703",
        "add head T to squad S (or make T copy head S)",
        P("T", "head"),
        P("S", "squad (30-39) or head to copy", required=True),
        P("P", "firmware parameter"),
        source="M703 Add to Clone Squad (T_v5)",
    ),
    code(
        "M704",
        "remove head T from squad S (or stop copying head S)",
        P("T", "head", says="head to remove: {value}"),
        P("S", "squad or head", required=True),
        source="M704 Remove from Clone Squad (T_v5)",
    ),
    # -- Controlling Lasers and UV Pens ---------------------------------------------------------------
    # "T# (target head - MUST be specified, can NOT be inherited)"; "En can be the default 0 (disable) or 1
    # (enable)"; "An is the duration in seconds after shut-off that the cooling remains active; default is 30
    # (but this will not override temperature safety measures)"
    code(
        "M620",
        "enable (E1) or disable (E0) a laser or UV pen",
        P(
            "T",
            "target device (must be given)",
            required=True,
            rule="HY020",
            says="target device: {value}",
            absent="T must be specified: M620 can NOT inherit the head with focus",
        ),
        P(
            "E",
            "0 disable, 1 enable",
            choices=(0, 1),
            values={"0": "disable", "1": "enable"},
            absent="no E: disable (E0 is the default)",
        ),
        P(
            "A",
            "cooling seconds after shut-off",
            minimum=0,
            says="cooling stays on for {value} s after shut-off (temperature safety still applies)",
        ),
        source="M620 Enable Device",
    ),
    # "No tool is specified; this will happen on the laser already enabled with M620"; "P40 (at 40% during
    # "printing" (E-value) moves)"; "Dn is the initial power (similar to a prime) to penetrate material
    # (optional; uses Pn if unspecified)"
    code(
        "M621",
        "laser power during printing moves, percent",
        P("P", "power", says="at {value}% during printing (E) moves", **PCT),
        P(
            "D",
            "pierce power",
            says="initial (pierce) power {value}% to penetrate the material",
            absent="no D: the initial power is P",
            **PCT,
        ),
        source="M621 Set Laser Power",
        does=("on the laser already enabled with M620 (no T)",),
    ),
    # "Dn is the duration, in miliseconds (only used for static exposures, not during moves)"; "P80 (power 80%)"
    code(
        "M623",
        "static emission for D ms at P percent",
        P("D", "duration, ms (UV pen max 60000, others 1000)", minimum=0, says="duration {value} milliseconds"),
        P("P", "power", says="power {value}%", **PCT),
        source="M623 Duration Emit",
        does=("static emission (not during moves) from the laser or UV pen",),
    ),
    # -- Controlling Spindles and Lathes --------------------------------------------------------------
    *_turning(
        ("M3", "M3 Turn On Spindle (CW)"),
        ("M4", "M4 Turn On Spindle (CCW)"),
        "spindle on {direction}, S percent power",
        *_SPINDLE,
        notes=_SPINDLE_NOTES,
    ),
    code("M5", "spindle off", P("T", "target head"), source="M5 Turn Off Spindle"),
    code("M253", "lathe on clockwise (16A only)", P("S", "speed, units/min"), source="M253 Turn On Lathe (CW)"),
    code(
        "M254", "lathe on counter-clockwise (16A only)", P("S", "speed, units/min"), source="M254 Turn On Lathe (CCW)"
    ),
    code("M255", "lathe off (if it has one)", source="M255 Turn Off Lathe"),
    # No section of its own: M253 turns the lathe "using the value set with M92 for RPM", "Sn - speed in
    # units per minute (default: RPM if set with M92 as steps per revolution)".  Parameters not given.
    code(
        "M92",
        "steps per revolution of the lathe (M253/M254 S is then in RPM); parameters not on the pages",
        open_params=True,
        source="M253 Turn On Lathe (CW) (names M92)",
    ),
    # The G81 example: "G81 (begin pecking cycle)", "I3 (move to Z starting position Z3, which will be our
    # greatest retract height)", "P3 (peck downward an additional 3mm at a time)", "Q-2 (retract upward 2mm after
    # each peck (to clear debris))", "Z-7.5 (peck to a maximum depth of 7.5mm)", "F200 (working (drilling) travel
    # speed of 200 mm/min)", "after this, the head will retract up to the I position ... before moving on"
    code(
        "G81",
        "peck drilling (needs an applied M660 offset)",
        P("T", "target head"),
        P("X", "X position"),
        P("Y", "Y position"),
        P(
            "I",
            "initial (retract) Z",
            says="move to Z starting position Z{value}, which will be the greatest retract height",
        ),
        P("R", "alias of I (firmware)"),
        P("P", "peck depth per cycle, mm", says="peck downward an additional {value} mm at a time"),
        P("Q", "retract after each peck, mm", says="retract upward {value} mm after each peck (to clear debris)"),
        P("Z", "final depth", says="peck to a maximum depth of {value} mm"),
        P("F", "Z feed, mm/min", says="working (drilling) travel speed of {value} mm/min"),
        source="G81 Peck Drilling",
        does=("begin pecking cycle",),
        notes=("after this, the head retracts to the I position before moving on to the next line",),
    ),
    # -- Reporting and Diagnostics --------------------------------------------------------------------
    code(
        "M701",
        "head reporting period",
        P("T", "target head"),
        P("P", "seconds between reports", minimum=0),
        source="M701 Set Head Reporting",
    ),
    code("M718", "stop logging to file", source="M718 Stop Logging to File"),
    code(
        "M719",
        "start logging to file",
        P("P", "seconds between entries", minimum=0),
        P("S", "S1 report everything", **FLAG01),
        *[P(x, f"report {x}") for x in "XYZABVEL"],
        source="M719 Start Logging to File",
    ),
    code(
        "M772",
        "reset metrics (S1 basic report, S255 all; bitmask of reports at M30)",
        P("S", "reports", minimum=0, maximum=255, integer=True),
        source="M772 Reset All Metrics",
    ),
    code("M773", "basic printing report", source="M773 Generate Basic Report"),
    code(
        "M797", "report sensors (I1: homed state)", P("I", "homed report"), source="M797 Report Sensors (hidden codes)"
    ),
    # -- Controlling Aux Devices ----------------------------------------------------------------------
    code("M7", "Aux1 (mist) on, percent", P("S", "percent", rule="HY044", **PCT), source="M7 Activate Aux 1"),
    code("M8", "Aux2 (flood) on, percent", P("S", "percent", rule="HY044", **PCT), source="M8 Activate Aux 2"),
    code("M9", "Aux1 and Aux2 off", source="M9 Deactivate Aux1 & Aux2"),
    code("M619", "map the aux port that M783 ties to", open_params=True, source="Code_Chart (M619)"),
    code(
        "M670",
        "gantry / Y-arm light, percent",
        P("S", "percent", rule="HY044", **PCT),
        P("P", "blink period, s", minimum=0),
        source="M670 Enable Gantry / Y-arm Light",
    ),
    _aux("M671", "danger lights (30M/ESR only)", "M671 Activate Danger Lights"),
    code(
        "M672",
        "Y-arm light follows a sensor",
        P(
            "S",
            "sensor code",
            choices=(0, 10, 11, 12, 13, 20, 21, 22, 23, 30, 31, 32, 33, 40, 41, 42, 43, 50, 51, 52, 53, 60, 61, 62, 63),
        ),
        source="M672 Set Gantry / Y-arm State",
    ),
    _aux("M673", "Y-arm light after the queue empties", "M673 Toggle Y-Arm Light Next (hidden codes)"),
    _aux("M675", "response LEDs (30M/16A only)", "M675 Activate Response LEDs"),
    _aux("M676", "recirculation fan (16A only)", "M676 Activate Recirc. Fan"),
    _aux("M677", "buzzer (older 30Ms only)", "M677 Activate Buzzer"),
    _aux("M678", "laser cross-hair (16A with CO2 laser only)", "M678 Activate Laser X-hair"),
    _aux("M679", "vacuum (30M/ESR only)", "M679 Activate Vacuum"),
    _aux("M684", "exhaust (16A only)", "M684 Activate Exhaust"),
    _aux("M685", "air (16A only)", "M685 Set Power on Air"),
    _aux("M689", "external head", "M689 Activate Ext. Head"),
    code("M783", "tie the mapped aux port to head T's extrusion", P("T", "head"), source="M783 Tie Aux to Extrusion"),
    # -- Other Commands -------------------------------------------------------------------------------
    code("M17", "engage all motors", source="M17 Engage Motors"),
    code("M18", "disengage all motors (re-home afterwards)", source="M18 Disengage Motors"),
    code("M84", "disengage all motors (same as M18)", source="M84 Disable Motors"),
    code("M30", "end of job: clears M229, M106 range, M660, squads, fixture offsets", source="M30 End of Program"),
    code("M790", "new-layer actions (camera)", source="M790 New Layer Actions"),
    code("M791", "snap a camera image", source="M791 Snap Image"),
    code("M792", "execute an action (SAY/PIC/VID/SEND/BEEP/SHELL after ';')", source="M792 Execute Action"),
    # -- Hidden codes (Sekret page) -------------------------------------------------------------------
    # M772 section: "Sn is a mask of which reports to auto send when M30 is processed ... Bit1 (0x02):
    # enables M774 report (system configuration), Bit2 (0x04): enables M774 report (queue metrics), Bit3
    # (0x08): enables M775 report (crashDataFromRam), Bit4 (0x10): enables M776 report (command and
    # motionQ usage), Bit5 (0x20): enables M779 report (slice timing)".  Their parameters are not given;
    # M777 and M778 are not named anywhere on the pages.
    code(
        "M774",
        "report: system configuration (also named for queue metrics); parameters not on the pages",
        open_params=True,
        source="M772 Reset All Metrics (hidden codes)",
    ),
    code(
        "M775",
        "report: crash data from RAM; parameters not on the pages",
        open_params=True,
        source="M772 Reset All Metrics (hidden codes)",
    ),
    code(
        "M776",
        "report: command and motion queue usage; parameters not on the pages",
        open_params=True,
        source="M772 Reset All Metrics (hidden codes)",
    ),
    code(
        "M779",
        "report: slice timing; parameters not on the pages",
        open_params=True,
        source="M772 Reset All Metrics (hidden codes)",
    ),
    # P: 0-5 with T, 0-29 without ("0 ... must specify probeHead via T arg"); "D only 1 is presently supported"
    code(
        "G38",
        "probe",
        *_axes("relative move"),
        P("T", "probe head"),
        P("P", "probe connection", minimum=0, maximum=29, integer=True, rule="HY062"),
        P("D", "only 1 is supported", choices=(1,), rule="HY062"),
        P("I", "polarity", **FLAG01),
        P("H", "head offset register"),
        P("O", "additional offset"),
        P("F", "feed rate (one-shot)"),
        source="G38 Distance Probing (hidden codes)",
    ),
    # -- Known only from Hyrel's own files ------------------------------------------------------------
    # Not on the Gcode, T_v5 or hidden-codes pages.  Hyrel's own slicer profile (corpus/hyrel/
    # oinkotariah__printer_30M-ESR_T1_Heated.ini, "BEGIN HYREL HEADER for a 30M/ESR ...") starts every
    # job with "M627 X0 Y0 Z0 J-500 K5 ; setup abort action"; what its parameters mean is not documented.
    code(
        "M627",
        "set up the abort action (undocumented: known from Hyrel's own slicer profile; parameters not catalogued)",
        open_params=True,
        source="not on the Hyrel pages; Hyrel's own PrusaSlicer profile start code ('; setup abort action')",
    ),
)


def _is_t_command(c: str) -> bool:
    # "T#" tool change: T0-T48 are addresses (T_v5); other numbers are reported by HY047.
    return c.startswith("T") and c[1:].lstrip("-").isdigit()


HYREL_DETECTION = Detection(
    patterns=(
        (r"(?i)repetrel|hyrel", 5),
        (r"(?i);\s*gcode_flavor\s*=\s*hyrel", 10),
    ),
    clues=(
        # T_v5 Default Mode: "M6 T0 O1 X0 Y0 Z0" declares a head and its offset register; a CNC M6 has no O.
        # (Repetrel writes one per loaded head; no other firmware's M6 takes O: as telling as a code only Hyrel has)
        Clue("M6 T# O# declares a head and its offset register (Hyrel)", "M6", test=has_all("T", "O"), weight=8),
        # M109/M190/M191 "Sn Hn Cn Ln Un Rn [v5+] W0": H C L U W are Hyrel's wait window.
        *(
            Clue(f"{c} H/C/L/U/W: a Hyrel temperature-wait window", c, test=has_any("H", "C", "L", "U", "W"))
            for c in ("M109", "M190", "M191")
        ),
        # Heads and beds have T addresses above 9 only on Hyrel (v5 T10-T48, v4 T11-T100); Marlin's
        # extruders are T0-T7, and Marlin/RRF address beds with I/H/P, not T.
        *(
            Clue(f"{c} T10 or above: a Hyrel device address", c, test=value_at_least("T", 10), weight=4)
            for c in ("M104", "M109")
        ),
        *(
            Clue(f"{c} T#: a Hyrel bed or chamber address", c, test=has_all("T"))
            for c in ("M140", "M141", "M190", "M191")
        ),
        Clue("M106 C: the Hyrel fan range (M106 Set Cooling)", "M106", test=has_all("C")),
        Clue("M620 T# E: Hyrel's enable-emitter command", "M620", test=has_all("T", "E")),
        # M3/M4/M5 "T# (target head)" (M3 Turn On Spindle (CW), M5 Turn Off Spindle): the spindle is a head
        # address; Marlin's, RepRapFirmware's and Carvera's spindles take no T
        *(Clue(f"{c} T#: a Hyrel spindle address", c, test=has_all("T")) for c in ("M3", "M4", "M5")),
    ),
    # The Marlin habits the HY rules catch (gclint.dialects.habits): a small cost, never evidence for Marlin.
    habits=HYREL_HABITS,
    # gclint's translator writes only Hyrel (gclint.translate.pairs): a "; gclint: ..." note on a command that is
    # not a directive (dialect=, disable=, enable=) is its mark: a pause "M0 ; gclint: pause (Carvera M600)",
    # with --annotate every line it added ("M229 E1 D1 ; gclint: added (...)").  The output reads as its target.
    line_marks=(
        LineMark(
            "gclint:",
            r"(?i)^[^;(]*\S[^;(]*[;(][ \t]*gclint:[ \t]*(?!(?:dialect|disable|enable)[ \t]*=)[a-z]",
            "a note gclint's translator writes (its output is Hyrel)",
            weight=6,
        ),
    ),
    prior=1.0,  # the first target: Hyrel wins where the evidence ties (docs/architecture.md, detection)
)
# What a Hyrel machine does with a line (Hyrel wiki, Gcode page; the section named at each effect).
HYREL_SEMANTICS = Semantics(
    dwell=DWELL_MS_S_SUM,  # "G4 Timed Pause": S seconds, P milliseconds, both add up
    e_values="native",  # "G1 Working Move": native flow unless "M229 E1 D1"
    g0_feed="one-shot",  # "G0 Rapid Move": F "non-persistent"
    home="listed",  # "G28 Send X, Y to Physical Home": "Any axis not homed will have its position remain unchanged"
    tool_select="address",  # T_v5: T commands and T variables share one address table
    fan_scale="range",  # "M106 Set Cooling / Etc.": S is a share of the range C (default C100)
    wait_r="tolerance",  # "M109 Wait for Temp (Head)": R is a tolerance
    effects=effects(
        WORKSPACES,  # "G54-59 Set Offsets"
        {
            "G16": "plane",
            "G28": "home-reset-offsets",  # "G28": "also resets current offsets to 0 ... performs a G53"
            "G2.1": "spiral-in-place",
            "G3.1": "spiral-in-place",
            "G2.2": "arc",
            "G3.2": "arc",
            "G2.3": "arc",
            "G3.3": "arc",
            "G53": "clear-fixture-offsets",  # "G53 Clear Offsets" (modal)
            "G81": "peck-drill",
            "G93": "clear-g92",
            "M0": "pause-with-actions",  # "M0 is a stop until resume command"; its comment lists Repetrel actions
            "M6": "declare-head-offsets",  # "M6 Declare Head Offsets"
            "M7": "aux",
            "M8": "aux",
            "M9": "aux-off",
            "M30": "end-of-job",  # "M30 End of Job": resets the job's state
            "M116": "wait-pending",  # "M116 Wait for W0 temperatures"
            "M221": "flow",
            "M229": "flow-mode",
            "M620": "emitter",
            "M621": "emitter-power",
            "M623": "emit",
            "M721": "unprime",
            "M722": "prime",
            "M660": "height-offset",
            "M702": "squad",
            "M703": "squad-add",
            "M704": "squad-remove",
            "M756": "layer-height",
        },
    ),
)

HYREL_V5 = Dialect(
    name="hyrel",
    title="Hyrel (Repetrel v5, unified T addressing)",
    family="hyrel",
    codes=HYREL_CODES,
    aliases=("hyrel-v5", "hyrel5"),
    detection=HYREL_DETECTION,
    open_codes=_is_t_command,
    unknown_severity="error",  # Hyrel firmware reuses numbers with other meanings (Hyrel firmware source, inc/GCode.h)
    unknown_note=(
        "Repetrel does not list {code}; Hyrel reuses many numbers for other things, so it is rejected or does "
        "something else"
    ),
    description="Hyrel 3D printers (30M, ESR, EHR, 16A) with Repetrel/firmware v5: T commands and T variables share one address table.",
    semantics=HYREL_SEMANTICS,
    sources=(
        "Gcode page: https://hyrel3d.com/wiki/index.php/Gcode (revision 4926, 2020-07-02)",
        "T_v5: https://hyrel3d.com/wiki/index.php/T_v5 (revision 4502, 2020-05-14)",
        "Sekret! (hidden codes): https://hyrel3d.in/wiki/index.php?title=Sekret%21 (revision 4283, 2020-05-10)",
    ),
    extras={
        "firmware": 5,
        "resolve_variable": resolve_v5,
        "resolve_command": resolve_v5,
    },
)


def _catalogued(name: str, letter: str) -> Param:
    """The parameter ``letter`` of v5's ``name`` (a KeyError when it is not catalogued)."""
    params = HYREL_CODES[name].params
    if params is None:
        raise KeyError(f"{name} has no parameter table")
    return params[letter]


HYREL_V4 = HYREL_V5.derive(
    "hyrel-v4",
    "Hyrel (Repetrel v4: T variables are device addresses T11-T15, T21-T25...)",
    add=[
        # "M116 is supported with version 5.x and later" (Gcode page): known, but not supported (HY027).
        replace(HYREL_CODES["M116"], summary="wait for W0 temperatures (v5+ only: not on v4)", supported=False),
        # v4 M702 seeds group S (50-57) with device T's settings (Hyrel v4 firmware source, Hydra4/src/MCode.c
        # M_Code_M702; changelog 4.200c in Hydra4/inc/main.h); explain reads it as the v5 squad (the T and S
        # readings and the M30 note of v5's M702)
        replace(
            HYREL_CODES["M702"],
            summary="seed group S (50-57) with device T's settings (v4)",
            params={
                "T": replace(_catalogued("M702", "T"), meaning="device whose settings are copied"),
                "S": replace(_catalogued("M702", "S"), meaning="group number", minimum=50, maximum=57),
            },
            source="T_v4; Hyrel v4 firmware source, Hydra4/src/MCode.c M_Code_M702",
        ),
        # v4 M703/M704 give a device an alias (Hydra4/src/MCode.c M_Code_M703, M_Code_M704); the v5 squad form
        # needs S, but v4 jobs also use other letters (M703 T14 P10 in the corpus), so nothing is required here.
        code(
            "M703",
            "add alias S to device T (v4)",
            P("T", "device", says="device: {value}"),
            P("S", "alias", says="gets the alias {value} (v4 cloning: commands sent to {value} reach this device too)"),
            P("P", "firmware parameter"),
            P("C", "seed group (4.0 firmware)"),
            source="T_v4; Hyrel v4 firmware source, Hydra4/src/MCode.c M_Code_M703",
        ),
        code(
            "M704",
            "remove alias S from device T (v4)",
            P("T", "device", says="device: {value}"),
            P("S", "alias", says="remove the alias {value}"),
            source="T_v4; Hyrel v4 firmware source, Hydra4/src/MCode.c M_Code_M704",
        ),
    ],
    aliases=("hyrel4",),
    sources=(
        *HYREL_V5.sources,
        "T_v4: https://hyrel3d.com/wiki/index.php?title=T_v4&oldid=7348",
        "Hyrel v4 firmware source: github.com/Karl690/HydraSt_407 @ 734de72 (Hydra4/main.c, Hydra4/src/MCode.c)",
    ),
    variant_of="hyrel",
    detection=HYREL_DETECTION,  # v4 or v5 is decided from the addresses the file uses (gclint.context)
    description="Hyrel firmware/Repetrel v4 and earlier: T commands are tool numbers 0-9, T variables inside M-codes are CAN device addresses.",
    extras={
        "firmware": 4,
        "resolve_variable": resolve_v4_variable,
        "resolve_command": resolve_v4_command,
    },
)
