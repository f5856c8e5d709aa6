"""Marlin 2.x (and the Marlin-like flavours of slicers: Prusa firmware, Bambu, Creality, Klipper hosts).

Inventory from the Marlin G-code reference (https://marlinfw.org/meta/gcode/) and Marlin's own dispatch
(Marlin source @ 005ec919, Marlin/src/gcode/gcode.cpp).  Parameters are not catalogued: Marlin
ignores letters it does not use.  Klipper extended commands (``SET_FAN_SPEED ...``) are accepted because
Klipper hosts read Marlin-flavour files.  What Prusa, Bambu and Klipper firmware add is in their own
inventories (gclint/firmware/): a file written for one of them (``Context.flavor``) is checked against
Marlin and that firmware.
"""

from __future__ import annotations

from gclint.dialects.base import Clue, Descriptions, Detection, Dialect, codes, describe, span, table
from gclint.dialects.semantics import DWELL_MS_S_WINS, WORKSPACES, Semantics, effects
from gclint.syntax.nodes import EXTENDED

_G = (
    "G0 G1 G2 G3 G4 G5 G6 G10 G11 G12 G17 G18 G19 G20 G21 G26 G27 G28 G29 G29.1 G29.2 G30 G31 G32 G33 G34 G35"
    " G38.2 G38.3 G38.4 G38.5 G42 G53 G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3 G60 G61 G76 G80 G90 G91 G92"
    " G92.1 G425"
)
_M = (
    "M0 M1 M3 M4 M5 M7 M8 M9 M10 M11 M16 M17 M18 M20 M21 M22 M23 M24 M25 M26 M27 M28 M29 M30 M31 M32 M33 M34"
    " M42 M43 M48 M73 M75 M76 M77 M78 M80 M81 M82 M83 M84 M85 M86 M87 M92 M100 M102 M104 M105 M106 M107 M108"
    " M109 M110 M111 M112 M113 M114 M115 M117 M118 M119 M120 M121 M122 M123 M125 M126 M127 M128 M129 M140 M141"
    " M143 M145 M149 M150 M154 M155 M163 M164 M165 M166 M190 M191 M192 M193 M200 M201 M202 M203 M204 M205"
    " M206 M207 M208 M209 M211 M217 M218 M220 M221 M226 M240 M250 M255 M256 M260 M261 M280 M281 M282 M290"
    " M300 M301 M302 M303 M304 M305 M306 M350 M351 M355 M360 M361 M362 M363 M364 M380 M381 M400 M401 M402"
    " M403 M404 M405 M406 M407 M410 M412 M413 M420 M421 M422 M423 M425 M428 M430 M486 M493 M500 M501 M502"
    " M503 M504 M510 M511 M512 M524 M540 M569 M575 M592 M593 M600 M603 M605 M665 M666 M672 M701 M702 M710"
    " M808 M851 M852 M860 M861 M862 M863 M864 M865 M866 M867 M868 M869 M871 M876 M900 M906 M907 M908 M909"
    " M910 M911 M912 M913 M914 M915 M916 M917 M918 M919 M928 M951 M993 M994 M995 M997 M999 M7219"
)
# In Marlin's dispatch (Marlin/src/gcode/gcode.cpp @ 005ec919) but not in the reference: the
# MMU3 codes, internal and board-specific ones.
_SOURCE = (
    "G800 M12 M293 M294 M309 M414 M485 M552 M553 M554 M704 M705 M706 M707 M708 M709 M800 M936 M1000 M1001"
    " M1002 M1003 M1004 M3426"
)

# What the common codes do, for ``gclint explain`` (Marlin G-code reference, marlinfw.org/meta/gcode/).
_MOVE = {
    "X": "X",
    "Y": "Y",
    "Z": "Z",
    "E": "extruder position",
    "F": "feed rate, mm/min (modal)",
    "S": "laser power (laser mode)",
}
_DESCRIPTIONS: Descriptions = {
    "G0": ("rapid move (Marlin treats G0 like G1)", _MOVE),
    "G1": ("linear move", _MOVE),
    "G2": (
        "clockwise arc",
        {
            **_MOVE,
            "I": "center X offset from the start",
            "J": "center Y offset from the start",
            "R": "radius",
            "P": "number of full circles",
        },
    ),
    "G3": (
        "counter-clockwise arc",
        {
            **_MOVE,
            "I": "center X offset from the start",
            "J": "center Y offset from the start",
            "R": "radius",
            "P": "number of full circles",
        },
    ),
    "G4": ("dwell", {"P": "milliseconds", "S": "seconds"}),
    "G10": ("retract (firmware retraction)", {"S": "S1: swap retraction (multi-extruder)"}),
    "G11": "recover (unretract) after G10",
    "G20": "units are inches",
    "G21": "units are millimetres",
    "G28": (
        "auto home (all axes, or only the listed ones)",
        {"X": "home X", "Y": "home Y", "Z": "home Z", "O": "skip if already homed", "R": "raise Z first, mm"},
    ),
    "G29": "bed leveling (probe the bed)",
    "G90": "absolute positioning (also absolute E)",
    "G91": "relative positioning (also relative E)",
    "G92": ("set the current position (no move)", {"X": "new X", "Y": "new Y", "Z": "new Z", "E": "new E position"}),
    "M0": ("stop and wait for the user", {"P": "time out, ms", "S": "time out, s"}),
    "M1": ("stop and wait for the user", {"P": "time out, ms", "S": "time out, s"}),
    "M3": ("spindle or laser on, clockwise", {"S": "speed or power", "I": "inline laser mode"}),
    "M4": ("spindle or laser on, counter-clockwise", {"S": "speed or power", "I": "inline laser mode"}),
    "M5": "spindle or laser off",
    "M17": "enable the steppers",
    "M18": ("disable the steppers", {"S": "inactivity time-out, s"}),
    "M73": ("set print progress (display)", {"P": "percent done", "R": "minutes remaining"}),
    "M82": "absolute E values",
    "M83": "relative E values",
    "M84": ("disable the steppers", {"S": "inactivity time-out, s"}),
    "M104": (
        "set hotend temperature (no wait)",
        {
            "S": "target temperature, C",
            "T": "extruder index",
            "B": "autotemp maximum",
            "F": "autotemp flag",
            "I": "material preset index",
        },
    ),
    "M105": "report temperatures",
    "M106": ("set fan speed", {"P": "fan index", "S": "speed 0-255", "T": "secondary speed"}),
    "M107": ("fan off", {"P": "fan index"}),
    "M109": (
        "wait for hotend temperature",
        {
            "S": "target; wait only while heating",
            "R": "target; wait while heating or cooling",
            "T": "extruder index",
            "B": "autotemp maximum",
            "F": "autotemp flag",
        },
    ),
    "M110": ("set the current line number", {"N": "line number"}),
    "M112": "emergency stop",
    "M114": "report the current position",
    "M115": "report firmware information",
    "M117": "show a message on the display",
    "M118": "print a message to the host",
    "M140": ("set bed temperature (no wait)", {"S": "target temperature, C", "I": "material preset index"}),
    "M141": ("set chamber temperature (no wait)", {"S": "target temperature, C"}),
    "M190": (
        "wait for bed temperature",
        {"S": "target; wait only while heating", "R": "target; wait while heating or cooling"},
    ),
    "M191": (
        "wait for chamber temperature",
        {"S": "target; wait only while heating", "R": "target; wait while heating or cooling"},
    ),
    "M200": ("filament diameter (volumetric extrusion)", {"D": "diameter, mm", "T": "extruder index"}),
    "M201": ("maximum acceleration per axis, units/s²", {"X": "X", "Y": "Y", "Z": "Z", "E": "E"}),
    "M203": ("maximum feed rate per axis, units/s", {"X": "X", "Y": "Y", "Z": "Z", "E": "E"}),
    "M204": (
        "starting accelerations, units/s²",
        {"P": "printing moves", "R": "retracts", "T": "travel moves", "S": "printing and travel (legacy)"},
    ),
    "M205": (
        "advanced motion settings",
        {
            "B": "minimum segment time, µs",
            "E": "E jerk",
            "J": "junction deviation, mm",
            "S": "minimum feed rate",
            "T": "minimum travel feed rate",
            "X": "X jerk",
            "Y": "Y jerk",
            "Z": "Z jerk",
        },
    ),
    "M206": ("home offsets", {"X": "X", "Y": "Y", "Z": "Z"}),
    "M207": ("firmware retraction settings", {"S": "length, mm", "F": "feed rate, mm/min", "Z": "Z lift, mm"}),
    "M220": ("feed rate percentage", {"S": "percent"}),
    "M221": ("flow percentage", {"S": "percent", "T": "extruder index"}),
    "M290": ("babystep", {"Z": "Z distance, mm"}),
    "M300": ("play a tone", {"S": "frequency, Hz", "P": "duration, ms"}),
    "M400": "wait until every move is finished",
    "M420": ("bed leveling state", {"S": "S1 enable, S0 disable", "Z": "fade height, mm"}),
    "M486": (
        "label or cancel objects",
        {
            "T": "number of objects",
            "S": "current object index",
            "C": "cancel the current object",
            "P": "cancel object index",
            "U": "un-cancel object index",
        },
    ),
    "M500": "save settings to EEPROM",
    "M501": "load settings from EEPROM",
    "M502": "reset settings to factory defaults",
    "M503": "report settings",
    "M600": "filament change (pause, unload, load)",
    "M900": ("linear advance", {"K": "advance factor"}),
}


def _open(code: str) -> bool:
    # T<n> selects extruder n; Marlin's "T" alone and Prusa MMU's T?/Tx/Tc are accepted too.
    return code[0] == "T"


# Content that marks Marlin-flavour G-code (the Marlin habits Hyrel's rules catch are Hyrel's habits, no clue).
MARLIN_CLUES = (Clue("a Klipper extended command (NAME KEY=VALUE)", kind=EXTENDED, weight=4),)

# What Marlin's machine does with a line (gclint.dialects.semantics names the sources; the Marlin G-code reference
# for G0, G90 and G28).  Pauses: M0/M1 "wait for user", M25 "pause SD print", M226 "wait for pin state", M600
# "filament change" (Marlin G-code reference).  M30 deletes a file from the SD card: no effect on the machine.
MARLIN_EFFECTS = effects(
    WORKSPACES,
    {
        "G53": "machine-coordinates",
        "G92.1": "clear-g92",
        "M0": "pause",
        "M1": "pause",
        "M25": "pause",
        "M226": "pause",
        "M600": "pause",
        "M7": "coolant",
        "M8": "coolant",
        "M9": "coolant-off",
        "M220": "feed-factor",
        "M221": "flow",
        # the settings in EEPROM: save, load, factory reset, validate (Marlin G-code reference, M500-M504)
        "M500": "save-settings",
        "M501": "load-settings",
        "M502": "factory-settings",
        "M504": "validate-settings",
    },
)
MARLIN_SEMANTICS = Semantics(
    dwell=DWELL_MS_S_WINS,
    g0_extrudes=True,  # "on Cartesians [G0] must be a direct alias for G1", E allowed (Marlin reference, G0-G1)
    g0_feed="modal",
    e_follows_g90=True,  # G90/G91 also set the E mode (Marlin reference, G90 and G91)
    arc_turns="extra",  # P full circles before the arc (ARC_P_CIRCLES: Marlin/src/gcode/motion/G2_G3.cpp)
    commands_per_line="first",
    # "G53: ... if (parser.chain()) process_parsed_command()": the move after G53 runs, in machine coordinates
    # (Marlin/src/gcode/geometry/G53-G59.cpp, with CNC_COORDINATE_SYSTEMS)
    chains=frozenset({"G53"}),
    home="all-if-none",
    tool_select="extruder",
    effects=MARLIN_EFFECTS,
)

MARLIN = Dialect(
    name="marlin",
    title="Marlin 2.x (Marlin-flavour slicer output, Prusa, Bambu, Klipper hosts)",
    family="reprap",
    codes=describe(table(codes(_G), codes(_M), codes(_SOURCE), codes(span("M", 810, 819))), _DESCRIPTIONS),
    aliases=("marlin2", "prusa", "klipper"),
    detection=Detection(
        patterns=(
            (r"(?i)^;\s*FLAVOR:\s*Marlin", 10),
            # a comment naming the firmware ("; Marlin 2.1.2", "; for Prusa MK4 firmware", "; Klipper", LightBurn's
            # "; Marlin device profile"): weak, as RepRapFirmware's and Smoothieware's names are
            (r"(?i)^[;(][^\n]*\b(?:Marlin|Klipper|Prusa(?!Slicer)(?! ?slicer))\b", 4),
            (r"(?i)^;\s*FLAVOR:\s*(?:RepRap|Griffin|UltiGCode)", 6),
            (
                r"(?i)^;\s*gcode_flavor\s*=\s*(?:marlin|marlin2|reprap|repetier|teacup|makerware|sailfish|mach3|smoothie|klipper|sprinter|no-extrusion)\s*$",
                10,
            ),
            (
                r"(?i)generated (?:by|with) (?:PrusaSlicer|Slic3r|SuperSlicer|OrcaSlicer|BambuStudio|Cura|Simplify3D|KISSlicer|ideaMaker|Skeinforge)",
                3,
            ),
            # Cura's own markers (";LAYER:0", ";TYPE:SKIRT", ";Layer count: 404"): Cura writes Marlin flavour
            # unless its ";FLAVOR:" line says otherwise (legacy Cura wrote none: "RepRap (Marlin/Sprinter)")
            (r"(?m)^;(?:LAYER:-?\d|TYPE:[A-Z]|Layer count: \d)", 5),
        ),
        extensions=(".gcode", ".gco"),
        clues=MARLIN_CLUES,
        prior=0.5,  # between Marlin and RepRapFirmware, a .gcode file with nothing else leans Marlin
    ),
    extended_commands=True,
    open_codes=_open,
    unknown_severity="warning",  # Marlin echoes "Unknown command" and goes on (Marlin/src/gcode/gcode.cpp)
    description="Marlin firmware and Marlin-flavour output of the common slicers.",
    semantics=MARLIN_SEMANTICS,
    sources=(
        "Marlin G-code reference: https://marlinfw.org/meta/gcode/ (MarlinDocumentation _gcode/*.md @ 9ceeb6e)",
        "Marlin source: github.com/MarlinFirmware/Marlin @ 005ec919, Marlin/src/gcode/gcode.cpp",
    ),
    extras={"fan_max": 255},
)
