"""Makera Carvera (Smoothieware-based community firmware): milling, laser and 4th-axis jobs.

Inventory from the Carvera community docs (github.com/Carvera-Community/docs @ 3a9d423: the M-code table
firmware/supported-commands/mcodes/README.md and the G-code table gcodes.md).  Carvera runs
in grbl mode: G4 P is seconds; M3 S is RPM; M6 T is an automatic tool change; M7/M9 are air.  The firmware
is built on Smoothieware, whose console commands (``echo``, ``play``...) a Carvera file may hold
(Smoothieware source @ bb41e992, gclint/firmware/smoothieware.py): CarveraController's own test
programs print their progress with ``echo``.  M321.2 and M322.2 (laser mode on and off without the tool
drop and offset change) are in Makera's firmware source (github.com/MakeraInc/CarveraFirmware @ 9acba62,
src/modules/tools/laser/Laser.cpp), not in the table; CarveraController's board test runs them.
"""

from __future__ import annotations

from gclint.dialects.base import Clue, Descriptions, Detection, Dialect, codes, describe, span, table
from gclint.dialects.machinekit import NGC_LANGUAGE_CLUES
from gclint.dialects.semantics import DWELL_SECONDS_SUM, WORKSPACES, Semantics, effects
from gclint.firmware.smoothieware import SMOOTHIEWARE

_G = (
    "G0 G1 G2 G3 G4 G10 G17 G18 G19 G20 G21 G28 G28.1 G29 G30 G31 G32 G33 G38.2 G38.3 G38.4 G38.5 G53 G54 G55"
    " G56 G57 G58 G59 G80 G90 G91 G92 G92.1 G92.4 G93 G94"
)
_M = (
    "M0 M1 M2 M3 M5 M6 M7 M9 M17 M18 M20 M21 M23 M24 M25 M26 M27 M30 M32 M82 M83 M84 M92 M97 M98 M98.1 M99"
    " M105 M112 M114 M115 M117 M118 M118.1 M119 M120 M121 M203 M203.1 M204 M205 M206 M220 M221 M223 M306 M321"
    " M321.2 M322 M322.2 M323 M324 M325 M331 M332 M333 M334 M335 M336 M370 M374 M375 M400 M460 M461 M462 M463 M464 M465"
    " M466 M467 M468 M469 M470 M471 M472 M473 M474 M475 M476 M477 M478 M479 M480 M481 M482 M483 M484 M485"
    " M486 M487 M488 M489 M490 M490.1 M490.2 M491 M491.1 M492 M493 M493.1 M493.2 M493.3 M494 M495 M495.1 M495.2"
    " M495.3 M496 M496.1 M496.2 M496.3 M496.4 M496.5 M497 M497.1 M497.2 M498 M499 M500 M501 M502 M503 M504 M561"
    " M565 M600 M601 M665 M670 M801 M802 M811 M812 M821 M822 M831 M832 M841 M842 M851 M852 M881 M882 M885 M886"
    " M887 M888 M957 M958 M1000"
)

# What the common codes do, for ``gclint explain`` (Carvera M-code table; Smoothieware in grbl mode).
_MOVE = {
    "X": "X",
    "Y": "Y",
    "Z": "Z",
    "A": "A axis (4th axis, degrees)",
    "F": "feed rate, mm/min",
    "S": "laser power or spindle speed",
}
_DESCRIPTIONS: Descriptions = {
    "G0": ("rapid move", _MOVE),
    "G1": ("linear move at feed rate", _MOVE),
    "G2": (
        "clockwise arc",
        {**_MOVE, "I": "center X offset", "J": "center Y offset", "K": "center Z offset", "R": "radius"},
    ),
    "G3": (
        "counter-clockwise arc",
        {**_MOVE, "I": "center X offset", "J": "center Y offset", "K": "center Z offset", "R": "radius"},
    ),
    "G4": ("dwell", {"P": "seconds (grbl mode)", "S": "seconds"}),
    "G10": (
        "set a work coordinate system",
        {"L": "L2: values, L20: so the current position gets them", "P": "coordinate system number"},
    ),
    "G17": "arc plane XY",
    "G18": "arc plane XZ",
    "G19": "arc plane YZ",
    "G20": "units are inches",
    "G21": "units are millimetres",
    "G28": "go to the clearance position",
    "G38.2": "probe toward the workpiece, stop on contact, error if none",
    "G53": "move in machine coordinates (this line only)",
    "G54": "use work coordinate system 1",
    "G55": "use work coordinate system 2",
    "G56": "use work coordinate system 3",
    "G57": "use work coordinate system 4",
    "G58": "use work coordinate system 5",
    "G59": "use work coordinate system 6",
    "G90": "absolute positioning",
    "G91": "relative positioning",
    "G92": ("set the current position (offset)", _MOVE),
    "M1": "optional stop (pauses when M333 optional stop mode is on)",
    "M2": "end of program: stop the spindle and the air",
    "M3": ("start the spindle", {"S": "speed, RPM"}),
    "M5": "stop the spindle",
    "M6": ("automatic tool change (ATC) and tool length offset", {"T": "tool number (T0 wireless probe, T-1 none)"}),
    "M7": "air on",
    "M9": "air off",
    "M30": "end of program (no action on the Carvera)",
    "M98": ("run a macro from gcodes/macros", {"P": "macro number"}),
    "M99": "return from a subprogram",
    "M203": ("maximum feed rates, mm/s", {"X": "X", "Y": "Y", "Z": "Z"}),
    "M220": ("feed speed override", {"S": "percent"}),
    "M221": ("soft endstops", {"S": "S0 off, S1 on"}),
    "M223": ("spindle speed override", {"S": "percent"}),
    "M321": "enter laser mode (drops the tool, calibrates the collet)",
    "M321.2": "enter laser mode, keeping the tool and the Z offset (Makera firmware, Laser.cpp)",
    "M322": "exit laser mode",
    "M322.2": "exit laser mode, keeping the Z offset (Makera firmware, Laser.cpp)",
    "M323": "laser test mode (very low power, for focusing)",
    "M324": "exit laser test mode",
    "M325": ("laser power override", {"S": "percent"}),
    "M331": "auto vacuum on (runs with the spindle)",
    "M332": "auto vacuum off",
    "M400": "wait until every move is finished",
    "M490.1": "tighten the spindle collet",
    "M490.2": "loosen the collet and drop the tool",
    "M491": "calibrate the tool length offset of the current tool",
    "M493.2": ("set the current tool number", {"T": "tool (T-1 empty, T0 probe)"}),
    "M600": "pause the current file",
    "M601": "resume the current file",
    "M801": ("vacuum on", {"S": "power, percent"}),
    "M802": "vacuum off",
    "M811": ("spindle cooling fan on", {"S": "power, percent"}),
    "M812": "spindle cooling fan off",
    "M821": "light on",
    "M822": "light off",
}


def _open(code: str) -> bool:
    return code[0] == "T" or "#" in code


# Smoothieware in grbl mode, as the Carvera community docs describe it: G4 P and S in seconds, G0 F for that move
# only ("F applies to that line only", gcodes/g0-default-rapid-feed.md), G28 to the clearance position, T with M6,
# F on any line, G54 at the start (Carvera community docs, gcodes.md).  M7 is the air, M801/M802 the vacuum, M821/M822
# the light (Carvera M-code table).
CARVERA_SEMANTICS = Semantics(
    dwell=DWELL_SECONDS_SUM,
    extruder=None,
    g0_feed="one-shot",
    working="feeds",
    home="clearance",
    tool_select="prepare",
    wait_r=None,
    feed_on_any_command=True,
    default_workspace="G54",
    tool_change_stops_spindle=True,
    no_tool=-1,  # "M6 | Auto tool change, T0 indicates wireless probe, T-1 indicates None" (Carvera M-code table,
    probe_tool=0,  # https://carvera-community.gitbook.io/docs/firmware/supported-commands/mcodes)
    effects=effects(
        WORKSPACES,
        {
            "G53": "machine-coordinates",
            "G92.1": "clear-g92",
            "G93": "inverse-time",
            "G94": "units-per-minute",
            "M2": "end-program",
            "M30": "end-program",
            "M6": "tool-change",
            "M98": "run-macro-file",  # "M98 P<n>: run gcodes/macros/<n>.cnc" (Carvera M-code table)
            "M600": "pause",
            "M25": "pause",
            "M1": "optional-stop",
            "M7": "air",
            "M9": "air-off",
            "M104": None,
            "M109": None,
            "M140": None,
            "M190": None,
            "M141": None,
            "M191": None,
            "M106": None,
            "M107": None,
            "M82": None,
            "M83": None,
        },
    ),
)

CARVERA = Dialect(
    name="carvera",
    title="Makera Carvera (Smoothieware community firmware)",
    family="smoothie",
    codes=describe(table(codes(_G), codes(_M)), _DESCRIPTIONS),
    aliases=("smoothieware", "makera"),
    detection=Detection(
        # (not in gclint's own notes: the translator's "; gclint: pause (Carvera M600)" names the source)
        patterns=(
            (r"(?im)^(?![^\n]*gclint:)[^\n]*(?:carvera|makera)", 10),
            # the firmware Carvera's is built on, named by the CAM ("; Smoothieware device profile": LightBurn)
            (r"(?im)^[;(][^\n]*\bsmoothieware\b", 5),
        ),
        extensions=(".nc", ".cnc", ".tap"),
        clues=(*NGC_LANGUAGE_CLUES, Clue("an echo command (RepRapFirmware or Carvera console)", "echo", weight=1)),
    ),
    owords=True,
    words=SMOOTHIEWARE.words,
    open_codes=_open,
    unknown_severity="warning",
    description="Carvera desktop CNC: milling with ATC, laser, 4th axis.",
    semantics=CARVERA_SEMANTICS,
    console=True,
    sources=(
        "Carvera M-code table: github.com/Carvera-Community/docs, firmware/supported-commands/mcodes/README.md",
        "Carvera G-code table: github.com/Carvera-Community/docs, firmware/supported-commands/gcodes.md",
        "Smoothieware source: github.com/Smoothieware/Smoothieware @ bb41e992",
    ),
    extras={"max_rpm": 15000},
)

_ = span
