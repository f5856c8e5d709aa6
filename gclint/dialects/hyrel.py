"""Hyrel (Repetrel / Hydra motion controller), firmware v5 and v4.

Every code, parameter and range here comes from ../shared/seeds/hyrel-gcode-reference.wiki.txt (the
"Gcode" page; section names in the ``source`` fields), the T_v5 page and the hidden-codes page, as
catalogued in ../shared/research/dialects.md sections 1.8 and 3.  Ranges that a specific rule reports
carry that rule's code (``rule="HY0nn"``); the others are reported by DL003.
"""

from __future__ import annotations

from gclint.dialects.addressing import (
    resolve_v4_command,
    resolve_v4_variable,
    resolve_v5,
)
from gclint.dialects.base import Clue, Code, Detection, Dialect, Param, code, has_all, has_any, table, value_at_least

P = Param
PCT = dict(minimum=0, maximum=100)  # "Sn is the percentage (0-100)"
FLAG01 = dict(choices=(0, 1))

AXES = [P("X"), P("Y"), P("Z"), P("A"), P("B")]


def _axes(meaning: str) -> list[Param]:
    return [P(a.letter, f"{meaning} {a.letter}") for a in AXES]


def _aux(name: str, summary: str, section: str) -> Code:
    # "Sn is the percentage (0-100; no default - if no Sn, no change)" (Controlling Aux Devices)
    return code(name, summary, P("S", "percent power", rule="HY044", **PCT), source=section)


_WAIT = [
    P("T", "target device"),
    P("S", "set temperature, C (optional)"),
    P("H", "stop waiting once heated up to this absolute temperature"),
    P("C", "stop waiting once cooled down to this absolute temperature"),
    P("L", "stop waiting this many degrees below S"),
    P("U", "stop waiting this many degrees above S"),
    P("R", "stop waiting within +/- this many degrees of S"),
    P("W", "W0: set, do not wait until M116 (v5+)", choices=(0,)),
]
# M109 Wait for Temp (Head): "Sn ... is the new set temperature in °C"; "we have both heated and chilled
# (sub-ambient) heads": no lowest set point, but below 0 °C is mentioned (HY051, info).
_WAIT_HEAD = [P("S", "set temperature, C (optional)", minimum=0, rule="HY051") if p.letter == "S" else p for p in _WAIT]

_ARC = [
    P("X", "end X"),
    P("Y", "end Y"),
    P("Z", "end Z"),
    P("I", "centre X offset from the start"),
    P("J", "centre Y offset from the start"),
    P("F", "feed rate, mm/min"),
    P("E", "printing move"),
    P("S", "segment length (<3) or segment count (>=3, full circles only)"),
    # G2 Clockwise Arc: usage "G2 Xn Yn Zn In Jn Fn En Sn" -- no R (radius) and no K; the firmware
    # draws plain G2/G3 in XY only (research/dialects.md H19).
    P("R", "radius form is not supported", rule="HY017", forbidden=True),
    P("K", "K is not supported on G2/G3", rule="HY017", forbidden=True),
]

_SPIRAL1 = [
    # G2.1 Spiral CW Arc^1: "Pn is the pitch ... (required)", "Ln ... must be a positive integer",
    # "Rn is a flag; 0 ... 1 ... 2", "Effective ending X/Y is always the same as the current XY".
    P("Z", "end Z"),
    P("I", "centre X offset"),
    P("J", "centre Y offset"),
    P("P", "pitch between laps, mm", required=True, rule="HY018"),
    P("L", "number of laps", integer=True, minimum=1, rule="HY018"),
    P("E", "printing move"),
    P("S", "segment length or count"),
    P("R", "0 spiral in, 1 spiral out after inward jump, 2 spiral out", choices=(0, 1, 2), rule="HY018"),
    P("F", "feed rate"),
    P("X", "a G2.1/G3.1 spiral ends where it starts: no X", rule="HY018", forbidden=True),
    P("Y", "a G2.1/G3.1 spiral ends where it starts: no Y", rule="HY018", forbidden=True),
]

_SPIRAL2 = [
    P("X", "end X"),
    P("Y", "end Y"),
    P("Z", "end Z"),
    P("I", "centre X offset"),
    P("J", "centre Y offset"),
    P("P", "pitch between laps, mm"),
    P("L", "number of laps"),
    P("E", "printing move"),
    P("S", "segment length or count"),
    P("R", "direction flag"),
    P("F", "feed rate"),
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
    P("S", "segment length or count"),
    P("F", "feed rate"),
]

_PRIME = [
    P("S", "speed, pulses per second (normally 10,000)"),
    P("E", "motor pulses"),
    P("P", "milliseconds relative to the end/start of the move"),
    P("T", "target head"),
    P("I", "I1: execute now", **FLAG01),
]

HYREL_CODES = table(
    # -- Controlling Movement -------------------------------------------------------------------------
    code(
        "G0",
        "rapid (non-working) move",
        *_axes("target"),
        P("F", "one-shot feed rate, mm/min"),
        P("E", "not meaningful on G0 (HY030)"),
        P("H", "apply the M660 tool-height register", minimum=0, maximum=59, integer=True, rule="HY034"),
        source="G0 Rapid Move",
    ),
    code(
        "G1",
        "working move",
        *_axes("target"),
        P("E", "printing move (amount used only under M229 E1)"),
        P("F", "feed rate, mm/min (persistent)"),
        P("H", "apply the M660 tool-height register", minimum=0, maximum=59, integer=True, rule="HY034"),
        P("S", "one-shot flow multiplier", minimum=0, maximum=15.99, rule="HY033"),
        source="G1 Working Move",
    ),
    code("G2", "clockwise arc", *_ARC, source="G2 Clockwise Arc"),
    code("G3", "counter-clockwise arc", *_ARC, source="G3 Counterclockwise Arc"),
    code("G2.1", "clockwise spiral (laps around the start)", *_SPIRAL1, source="G2.1 Spiral CW Arc^1"),
    code("G3.1", "counter-clockwise spiral (laps around the start)", *_SPIRAL1, source="G3.1 Spiral CCW Arc^1"),
    code("G2.2", "clockwise spiral to X/Y", *_SPIRAL2, source="G2.2 Spiral CW Arc^2"),
    code("G3.2", "counter-clockwise spiral to X/Y", *_SPIRAL2, source="G3.2 Spiral CCW Arc^2"),
    code("G2.3", "clockwise 3-space arc", *_SPIRAL3, source="G2.3 3-Space CW Arc"),
    code("G3.3", "counter-clockwise 3-space arc", *_SPIRAL3, source="G3.3 3-Space CCW Arc"),
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
    code(
        "M106",
        "fan / UV LED duty",
        P("T", "target head"),
        P("S", "duty as a share of the C range"),
        P("C", "range used by all later M106 (100 default, 255 for slicers)", minimum=1, maximum=255, rule="HY012"),
        P("P", "duty during extrusion moves only, percent", rule="HY011", **PCT),
        source="M106 Set Cooling / Etc.",
    ),
    code("M107", "fan / UV LED off", P("T", "target head"), source="M107 Stop Cooling / Etc."),
    code("M109", "wait for head temperature", *_WAIT_HEAD, source="M109 Wait for Temp (Head)"),
    code("M116", "wait for all temperatures set with W0 (v5+)", source="M116 Wait for Temps (v5+)"),
    code(
        "M140",
        "set bed temperature (no wait)",
        # "heated and chilled (sub-ambient) beds" (M190): the page gives no lowest set point
        P("S", "temperature, C"),
        P("T", "target bed (default primary)"),
        source="M140 Set Temp (Bed)",
    ),
    code(
        "M141",
        "set chamber temperature (no wait)",
        # "heated and chilled (sub-ambient) chambers" (M191): the page gives no lowest set point
        P("S", "temperature, C"),
        P("T", "target chamber"),
        source="M141 Set Temp (Chamber)",
    ),
    code("M190", "wait for bed temperature", *_WAIT, source="M190 Wait for Temp (Bed)"),
    code("M191", "wait for chamber temperature", *_WAIT, source="M191 Wait for Temp (Chamber)"),
    # -- Controlling Material Flow --------------------------------------------------------------------
    Code("G10", "not recognized by Repetrel (offsets: M6; retract: M721)", {}, False, "G10 UNUSED"),
    Code("G11", "not recognized by Repetrel (unretract: M722)", {}, False, "G11 UNUSED"),
    code("M82", "absolute E values (only under M229 E1)", source="M82 Absolute E-Values"),
    code("M83", "relative E values (only under M229 E1)", source="M83 Relative E-Values"),
    code(
        "M221",
        "flow: pulses per ul (P), multiplier (S), width (W), layer (Z)",
        P("P", "pulses per microliter (volumetric) or per mm (linear)", minimum=0.000001),
        P("S", "flow multiplier (1.0 = as sliced)", minimum=0, maximum=15.99, rule="HY033"),
        P("W", "path width, mm", minimum=0.000001),
        P("Z", "layer height, mm", minimum=0.000001),
        P("T", "target head"),
        source="M221 Set Flow Rate",
    ),
    code(
        "M229",
        "use E values (E1) or native flow (E0); D routing",
        P("E", "0 native flow, 1 use E values", choices=(0, 1)),
        P("D", "step routing 0-3", choices=(0, 1, 2, 3)),
        P("S", "seconds: shorter travels skip unprime/prime", minimum=0),
        source="M229 Use E Values",
    ),
    code("M721", "unprime (retract) settings; I1 unprimes now", *_PRIME, source="M721 Set Unprime Values"),
    code("M722", "prime settings; I1 primes now", *_PRIME, source="M722 Set Prime Values"),
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
    code(
        "G28",
        "home the listed axes (X0 Y0 [Z0 A0 B0]); clears G92, H and fixture offsets",
        P("X", "home X", rule="HY025"),
        P("Y", "home Y", rule="HY025"),
        P("Z", "home Z", rule="HY025"),
        P("A", "home A", rule="HY025"),
        P("B", "home B", rule="HY025"),
        P("I", "undocumented flag"),
        source="G28 Send X, Y to Physical Home",
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
    code(
        "M6",
        "declare head offsets (not a tool change)",
        P("T", "head"),
        P("O", "offset register", minimum=0, maximum=59, integer=True, rule="HY061"),
        *_axes("offset in"),
        P("D", "tool diameter"),
        P("I", "I1: move now (non-persistent)", **FLAG01),
        P("K", "K1: always act as I0 (persistent)", **FLAG01),
        source="M6 Declare Head Offsets",
    ),
    code(
        "M660",
        "store a tool-height offset register (apply with H on G1)",
        P("H", "register", required=True, minimum=0, maximum=59, integer=True, rule="HY034"),
        P("Z", "Z offset, mm"),
        P("D", "diameter (firmware)"),
        source="M660 Assign Tool Height Offset",
    ),
    code(
        "M702",
        "establish clone squad S (30-39) with T's flow settings",
        P("T", "head whose settings are copied"),
        P("S", "squad number", required=True, minimum=30, maximum=39, integer=True, rule="HY022"),
        source="M702 Establish Clone Squad (T_v5)",
    ),
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
        P("T", "head"),
        P("S", "squad or head", required=True),
        source="M704 Remove from Clone Squad (T_v5)",
    ),
    # -- Controlling Lasers and UV Pens ---------------------------------------------------------------
    code(
        "M620",
        "enable (E1) or disable (E0) a laser or UV pen",
        P("T", "target device (must be given)", required=True, rule="HY020"),
        P("E", "0 disable, 1 enable", choices=(0, 1)),
        P("A", "cooling seconds after shut-off", minimum=0),
        source="M620 Enable Device",
    ),
    code(
        "M621",
        "laser power during printing moves, percent",
        P("P", "power", **PCT),
        P("D", "pierce power", **PCT),
        source="M621 Set Laser Power",
    ),
    code(
        "M623",
        "static emission for D ms at P percent",
        P("D", "duration, ms (UV pen max 60000, others 1000)", minimum=0),
        P("P", "power", **PCT),
        source="M623 Duration Emit",
    ),
    # -- Controlling Spindles and Lathes --------------------------------------------------------------
    code(
        "M3",
        "spindle on clockwise, S percent power",
        P("T", "target head"),
        P("S", "power, percent", rule="HY023", **PCT),
        P("F", "PWM frequency, Hz"),
        source="M3 Turn On Spindle (CW)",
    ),
    code(
        "M4",
        "spindle on counter-clockwise, S percent power",
        P("T", "target head"),
        P("S", "power, percent", rule="HY023", **PCT),
        P("F", "PWM frequency, Hz"),
        source="M4 Turn On Spindle (CCW)",
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
    code(
        "G81",
        "peck drilling (needs an applied M660 offset)",
        P("T", "target head"),
        P("X", "X position"),
        P("Y", "Y position"),
        P("I", "initial (retract) Z"),
        P("R", "alias of I (firmware)"),
        P("P", "peck depth per cycle, mm"),
        P("Q", "retract after each peck, mm"),
        P("Z", "final depth"),
        P("F", "Z feed, mm/min"),
        source="G81 Peck Drilling",
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
        Clue("M6 T# O# declares a head and its offset register (Hyrel)", "M6", test=has_all("T", "O"), weight=4),
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
        # What a Hyrel job never says: marks for the dialects that have the code.  They weigh less than
        # what only Hyrel has: in a Hyrel job they are the very mistakes gclint is there to find.
        # "R ... is how close the relative temperature needs to be to the set temp" (M109): never a target
        *(
            Clue(
                f"{c} R as a target temperature (on Hyrel R is a tolerance)",
                c,
                test=value_at_least("R", 40, without="S"),
                weight=2,
                against=True,
            )
            for c in ("M109", "M190", "M191")
        ),
        # "Sn is the percent of duty cycle ... Cn is the range (0-100 or 0-255) ... default is C100" (M106)
        Clue(
            "M106 S above 100 with no C range (a 0-255 fan value)",
            "M106",
            test=value_at_least("S", 101, without="C"),
            weight=1,
            against=True,
        ),
        # "Any axis not homed will have its position remain unchanged" (G28): a bare G28 homes nothing on Hyrel
        Clue(
            "G28 with no axis (home all; on Hyrel it homes nothing)",
            "G28",
            test=lambda c: not c.params,
            weight=2,
            against=True,
        ),
        # "Sn - power (0-100%)" (M3 Turn On Spindle): an rpm is another firmware's spindle speed
        *(
            Clue(
                f"{c} S above 100 (an rpm; Hyrel's S is a percentage)",
                c,
                test=value_at_least("S", 101),
                weight=2,
                against=True,
            )
            for c in ("M3", "M4")
        ),
        # "M6 declares that a particular head holds a set of X, Y, and/or Z offsets" (M6): an M6 T1 with
        # nothing to declare is a CNC tool change
        Clue(
            "M6 with no offset (a CNC tool change; Hyrel's M6 declares offsets)",
            "M6",
            test=lambda c: not any(k in c.params for k in "OXYZABDIK"),
            weight=2,
            against=True,
        ),
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
    unknown_severity="error",  # Hyrel firmware reuses numbers with other meanings (dialects.md X1)
    description="Hyrel 3D printers (30M, ESR, EHR, 16A) with Repetrel/firmware v5: T commands and T variables share one address table.",
    sources=(
        "seeds/hyrel-gcode-reference.wiki.txt",
        "seeds/hyrel-T_v5-addressing.wiki.txt",
        "seeds/hyrel-hidden-codes.wiki.txt",
    ),
    extras={
        "firmware": 5,
        "resolve_variable": resolve_v5,
        "resolve_command": resolve_v5,
    },
)


HYREL_V4 = HYREL_V5.derive(
    "hyrel-v4",
    "Hyrel (Repetrel v4: T variables are device addresses T11-T15, T21-T25...)",
    add=[
        # "M116 is supported with version 5.x and later" (Gcode page): known, but not supported (HY027).
        Code("M116", "wait for W0 temperatures (v5+ only: not on v4)", {}, False, "M116 Wait for Temps (v5+)"),
        # v4 M702 seeds group S (50-57) with device T's settings (hyrel_v4.md section 4: 4.200c).
        code(
            "M702",
            "seed group S (50-57) with device T's settings (v4)",
            P("T", "device whose settings are copied"),
            P("S", "group number", required=True, minimum=50, maximum=57, integer=True, rule="HY022"),
            source="T_v4 / hyrel_v4.md section 4",
        ),
        # v4 M703/M704 give a device an alias (hyrel_v4.md section 4); the v5 squad form needs S, but v4
        # jobs also use other letters (M703 T14 P10 in the corpus), so nothing is required here.
        code(
            "M703",
            "add alias S to device T (v4)",
            P("T", "device"),
            P("S", "alias"),
            P("P", "firmware parameter"),
            P("C", "seed group (4.0 firmware)"),
            source="T_v4 / hyrel_v4.md section 4",
        ),
        code(
            "M704",
            "remove alias S from device T (v4)",
            P("T", "device"),
            P("S", "alias"),
            source="T_v4 / hyrel_v4.md section 4",
        ),
    ],
    aliases=("hyrel4",),
    detection=HYREL_DETECTION,  # v4 or v5 is decided from the addresses the file uses (gclint.context)
    description="Hyrel firmware/Repetrel v4 and earlier: T commands are tool numbers 0-9, T variables inside M-codes are CAN device addresses.",
    extras={
        "firmware": 4,
        "resolve_variable": resolve_v4_variable,
        "resolve_command": resolve_v4_command,
    },
)
