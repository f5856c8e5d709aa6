"""RepRapFirmware 3.x (Duet): G/M codes, meta commands (if, var, echo...), {expressions}, macros.

Inventory from the Duet G-code dictionary (https://docs.duet3d.com/User_manual/Reference/Gcodes) and the codes
the firmware's source has built in (RepRapFirmware @ fc1cd16c, gclint/firmware/reprapfirmware.py).  RepRapFirmware runs
a macro file for a code it does not know (sys/M<n>.g, sys/G<n>.g), so no G or M code is unknown there
(DL001 speaks only of constructs it has not, such as Klipper's extended commands, and then as a warning).
"""

from __future__ import annotations

from gclint.dialects.base import Clue, Descriptions, Detection, Dialect, codes, describe, table
from gclint.dialects.marlin import MARLIN_SEMANTICS
from gclint.firmware.reprapfirmware import REPRAPFIRMWARE
from gclint.syntax.nodes import META, is_number

_G = (
    "G0 G1 G2 G3 G4 G10 G11 G17 G18 G19 G20 G21 G22 G23 G28 G29 G30 G31 G32 G38.2 G38.3 G38.4 G38.5 G53 G54 G55"
    " G56 G57 G58 G59 G59.1 G59.2 G59.3 G60 G68 G69 G90 G91 G92 G93 G94"
)
_M = (
    "M0 M1 M2 M3 M4 M5 M6 M7 M8 M9 M17 M18 M20 M21 M22 M23 M24 M25 M26 M27 M28 M29 M30 M32 M36 M36.1 M37 M38"
    " M39 M42 M73 M80 M81 M82 M83 M84 M86 M92 M98 M99 M101 M102 M103 M104 M105 M106 M107 M108 M109 M110 M111"
    " M112 M114 M115 M116 M117 M118 M119 M120 M121 M122 M140 M141 M143 M144 M150 M190 M191 M200 M201 M201.1"
    " M203 M204 M205 M206 M207 M208 M220 M221 M226 M260 M260.1 M260.2 M261 M261.1 M261.2 M280 M290 M291 M292"
    " M300 M301 M302 M303 M304 M305 M307 M308 M309 M350 M374 M375 M376 M400 M401 M402 M404 M408 M409 M409.1"
    " M450 M451 M452 M453 M470 M471 M472 M486 M500 M501 M502 M503 M505 M540 M550 M551 M552 M553 M554 M555"
    " M556 M557 M558 M559 M560 M561 M562 M563 M564 M566 M567 M568 M569 M569.1 M569.2 M569.3 M569.4 M569.5"
    " M569.6 M569.7 M569.8 M569.9 M570 M571 M572 M573 M574 M575 M576 M577 M578 M579 M580 M581 M582 M584 M585"
    " M586 M586.4 M587 M588 M589 M591 M592 M593 M594 M595 M596 M597 M598 M599 M600 M601 M602 M603 M605 M650 M651"
    " M665 M666 M667 M669 M671 M672 M673 M674 M675 M701 M702 M703 M851 M905 M906 M907 M908 M909 M910 M911 M912"
    " M913 M914 M915 M916 M917 M918 M929 M950 M951 M952 M953 M954 M955 M956 M957 M997 M998 M999"
)

META_KEYWORDS = frozenset(
    ["if", "elif", "else", "while", "break", "continue", "var", "global", "set", "echo", "abort", "return", "skip"]
)


def macro_file(path: str) -> bool:
    """Whether ``path`` is a RepRapFirmware system or macro file: ``.g``, or under ``sys/`` or ``macros/``."""
    parts = path.replace("\\", "/").lower().split("/")
    return parts[-1].endswith(".g") or "sys" in parts[:-1] or "macros" in parts[:-1]


def system_file(path: str) -> bool:
    """Whether ``path`` is a RepRapFirmware system file: a ``.g`` file right in a ``sys/`` folder (config.g and
    the files it runs); a job (``.gcode``) placed there, or deeper, is not."""
    parts = path.replace("\\", "/").lower().split("/")
    return len(parts) >= 2 and parts[-2] == "sys" and parts[-1].endswith(".g")


# What the common codes do, for ``gclint explain`` (Duet G-code dictionary).
_MOVE = {
    "X": "X",
    "Y": "Y",
    "Z": "Z",
    "E": "extruder position",
    "F": "feed rate, mm/min (modal)",
    "H": "H1: homing move that stops at the endstop, H2: move motors individually",
    "S": "S1: endstop-checking move (homing; the older form of H1)",
}
_DESCRIPTIONS: Descriptions = {
    "G0": ("rapid move", _MOVE),
    "G1": ("linear move", _MOVE),
    "G2": ("clockwise arc", {**_MOVE, "I": "center X offset", "J": "center Y offset", "R": "radius"}),
    "G3": ("counter-clockwise arc", {**_MOVE, "I": "center X offset", "J": "center Y offset", "R": "radius"}),
    "G4": ("dwell", {"P": "milliseconds", "S": "seconds"}),
    "G10": (
        "tool offsets and temperatures (with P), else firmware retraction",
        {
            "P": "tool number",
            "X": "X offset",
            "Y": "Y offset",
            "Z": "Z offset",
            "R": "standby temperature, C",
            "S": "active temperature, C",
        },
    ),
    "G11": "unretract (firmware retraction)",
    "G20": "units are inches",
    "G21": "units are millimetres",
    "G28": ("home (runs homeall.g, or homex.g... for the listed axes)", {"X": "home X", "Y": "home Y", "Z": "home Z"}),
    "G29": "mesh bed compensation (probe, load or stop)",
    "G30": "single Z probe",
    "G32": "run bed.g (bed levelling)",
    "G90": "absolute positioning",
    "G91": "relative positioning",
    "G92": ("set the current position (no move)", {"X": "new X", "Y": "new Y", "Z": "new Z", "E": "new E position"}),
    "M0": "stop: cancel the print (runs stop.g)",
    "M1": "sleep (runs sleep.g)",
    "M3": ("spindle or laser on, clockwise", {"S": "speed or power", "P": "spindle number"}),
    "M4": ("spindle on, counter-clockwise", {"S": "speed", "P": "spindle number"}),
    "M5": "spindle or laser off",
    "M82": "absolute E values",
    "M83": "relative E values",
    "M84": "disable the motors",
    "M98": ("run a macro file", {"P": "file name"}),
    "M99": "return from a macro",
    "M104": (
        "set tool temperature (no wait)",
        {"S": "active temperature, C", "R": "standby temperature, C", "T": "tool number"},
    ),
    "M106": (
        "fan speed",
        {"P": "fan number", "S": "speed, 0-1 or 0-255", "H": "thermostatic heaters", "T": "thermostatic temperature"},
    ),
    "M107": "fan 0 off",
    "M109": (
        "set tool temperature and wait",
        {"S": "active temperature, C", "R": "standby temperature, C", "T": "tool number"},
    ),
    "M116": ("wait for temperatures", {"P": "tool number", "H": "heater number", "C": "chamber", "S": "tolerance, C"}),
    "M117": "show a message",
    "M118": ("send a message", {"P": "destination", "S": "the message"}),
    "M140": (
        "set bed temperature (no wait)",
        {"S": "active temperature, C", "R": "standby temperature, C", "H": "heater number"},
    ),
    "M141": ("set chamber temperature (no wait)", {"S": "temperature, C", "H": "heater number"}),
    "M190": (
        "wait for bed temperature",
        {"S": "target; wait only while heating", "R": "target; wait while heating or cooling"},
    ),
    "M191": (
        "wait for chamber temperature",
        {"S": "target; wait only while heating", "R": "target; wait while heating or cooling"},
    ),
    "M201": ("maximum accelerations, mm/s²", {"X": "X", "Y": "Y", "Z": "Z", "E": "E"}),
    "M203": ("maximum feed rates, mm/min", {"X": "X", "Y": "Y", "Z": "Z", "E": "E", "I": "minimum overall speed"}),
    "M204": ("accelerations", {"P": "printing moves, mm/s²", "T": "travel moves, mm/s²"}),
    "M207": (
        "firmware retraction settings",
        {
            "S": "length, mm",
            "R": "extra restart length, mm",
            "F": "retract speed, mm/min",
            "T": "unretract speed, mm/min",
            "Z": "Z hop, mm",
        },
    ),
    "M220": ("speed factor", {"S": "percent"}),
    "M221": ("extrusion factor", {"S": "percent", "D": "extruder drive"}),
    "M291": ("show a message box", {"P": "message", "R": "title", "S": "mode (0-7)", "T": "time-out, s"}),
    "M292": "acknowledge a message box",
    "M400": "wait until every move is finished",
    "M500": "save parameters to config-override.g",
    "M550": ("set the machine name", {"P": "name"}),
    "M563": ("define a tool", {"P": "tool number", "D": "extruder drives", "H": "heaters", "F": "fans", "S": "name"}),
    "M566": ("maximum instantaneous speed changes (jerk), mm/min", {"X": "X", "Y": "Y", "Z": "Z", "E": "E"}),
    "M568": (
        "tool settings",
        {"P": "tool number", "S": "active temperature, C", "R": "standby temperature, C", "A": "heater state"},
    ),
    "M569": ("stepper driver settings", {"P": "driver number", "S": "direction"}),
    "M572": ("pressure advance", {"D": "extruder drive", "S": "seconds"}),
    "M574": "endstop configuration",
    "M584": "map axes to drivers",
    "M906": ("motor currents, mA", {"X": "X", "Y": "Y", "Z": "Z", "E": "E", "I": "idle factor, percent"}),
    "M950": (
        "create a heater, fan, spindle or GPIO port",
        {
            "H": "heater",
            "F": "fan",
            "P": "GPIO output",
            "J": "GPIO input",
            "C": "pin name",
            "Q": "PWM frequency, Hz",
            "T": "sensor number",
        },
    ),
}


def _open(code: str) -> bool:
    # Tools T0-T49, T-1 (deselect), T with an expression; any other G/M code may be a macro file.
    return code[0] in "TGM"


def _object_model(cmd) -> bool:
    return any(v and v[0] == "{" for v in cmd.params.values())


# Content that marks RepRapFirmware 3 (Duet G-code dictionary; RepRapFirmware source @ fc1cd16c).
REPRAP_CLUES = (
    Clue("a meta command (if, while, var, set, global, abort)", kind=META, test=lambda c: c.code != "echo", weight=4),
    Clue("an echo command (RepRapFirmware or Carvera console)", "echo", weight=1),
    # (a CNC M98 calls a numbered subprogram: M98 P100)
    Clue('M98 P"file": calls a macro file by name', "M98", test=lambda c: not is_number(c.params.get("P") or "")),
    Clue("an object-model expression {...}", test=_object_model, contains="{"),
    # "string parameters ... enclosed in double quotes" (Duet G-code dictionary):
    # M291 P"message", M4000 S"tool name" (Prusa's M862.3 P "MK4S" is its flavour's own pattern)
    Clue(
        'a quoted string parameter (P"...")',
        test=lambda c: any(v and v[0] == '"' for v in c.params.values()),
        weight=2,
        contains='"',
    ),
    # LinuxCNC's G10 always has L (G10 L2 P1 R45 rotates a coordinate system)
    Clue(
        "G10 P# R/S: tool temperatures",
        "G10",
        test=lambda c: "P" in c.params and "L" not in c.params and ("R" in c.params or "S" in c.params),
    ),
    Clue("T-1: deselects every tool", "T-1"),
    # "G1 H1: ... the move is terminated when the endstop switch is triggered", H2 moves motors individually
    # (Duet G-code dictionary, G0/G1); Marlin's moves have no H, Hyrel's H
    # applies an M660 register (a Hyrel job with no M660 gets HY034, gclint.dialects.habits)
    *(
        Clue(f"{c} H1/H2/H3/H4: a homing move", c, test=lambda c: c.params.get("H") in ("1", "2", "3", "4"))
        for c in ("G0", "G1")
    ),
)

# RepRapFirmware reads a line as Marlin does (G0 is G1 in FDM mode, G4 S counts when both are given: GCodes.cpp
# DoDwell) except: G90/G91 leave the E mode alone ("extrusion is NOT set to absolute using G90"), every command of a
# line runs (StringParser.cpp), M0/M1/M2 end the job, M116 waits for every set-point, G10/M568 set tool
# temperatures (Duet G-code dictionary: G90, M0-M2, M116, G10, M568).
REPRAP_SEMANTICS = MARLIN_SEMANTICS.derive(
    e_follows_g90=False,
    fan_scale="255-or-fraction",  # M106 S: "0-1, or 0-255 above 1" (Duet G-code dictionary, M106)
    commands_per_line="all",
    effects={
        "M0": "end-program",
        "M1": "end-program",
        "M2": "end-program",
        "M116": "wait-all",
        "G10": "tool-temperature-or-offset",
        "M568": "tool-temperature",
        "M563": "define-tool",
        # not Marlin's EEPROM: RepRapFirmware's M500 writes sys/config-override.g (Duet G-code dictionary, M500)
        "M500": None,
        "M501": None,
        "M502": None,
        "M504": None,
    },
)

REPRAP = Dialect(
    name="reprap",
    title="RepRapFirmware 3.x (Duet)",
    family="reprap",
    codes=describe(table(codes(_G), codes(_M), codes(sorted(REPRAPFIRMWARE.codes))), _DESCRIPTIONS),
    aliases=("rrf", "reprapfirmware", "duet"),
    detection=Detection(
        patterns=(
            (r"(?i)^;\s*gcode_flavor\s*=\s*reprapfirmware", 12),
            (r"(?i)^;\s*FLAVOR:\s*RepRap\s*\(RepRap\)", 8),
            # a post-processor or macro that names its firmware ("generated to target ... RRF")
            (r"(?i)^[;(].*\b(?:RepRapFirmware|RRF|Duet ?[23W]\w*)\b", 4),
        ),
        extensions=(".g",),
        clues=REPRAP_CLUES,
        prior=0.2,
    ),
    meta_commands=True,
    open_codes=_open,
    unknown_severity="warning",
    description="Duet RepRapFirmware 3: meta commands, object-model expressions, macro files.",
    semantics=REPRAP_SEMANTICS,
    meta_keywords=META_KEYWORDS,
    macro_file=macro_file,
    system_file=system_file,
    sources=(
        "Duet G-code dictionary: https://docs.duet3d.com/User_manual/Reference/Gcodes (Duet3D/wiki-content @ 91f2348)",
        "RepRapFirmware source: github.com/Duet3D/RepRapFirmware @ fc1cd16c (3.5-dev)",
    ),
    extras={"fan_max": 255},
)
