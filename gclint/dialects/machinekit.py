"""Machinekit FDM (LinuxCNC interpreter with the FDM remaps), also used for plain LinuxCNC programs.

The FDM codes come from the Machinekit-FDM remap.ini (github.com/machinekoder/Machinekit-FDM-Standard @ 397d429)
and its first README (GCode.md, December 2014: M104 P<index> S<temp>, M106 P<index> S<pwm> I, M109 P S).  The base
language is LinuxCNC's RS274NGC: O-words, #parameters, [expressions], user M-codes M100-M199.
"""

from __future__ import annotations

from gclint.dialects.base import Clue, Descriptions, Detection, Dialect, Param, code, codes, describe, span, table
from gclint.dialects.semantics import DWELL_P_SECONDS, LINUXCNC_ORDER, WORKSPACES, Semantics, effects
from gclint.firmware.linuxcnc import G_CODES, M_CODES
from gclint.syntax.nodes import ASSIGNMENT, GCODE, IMPLICIT, OWORD

P = Param

# The base language: LinuxCNC's G and M codes (LinuxCNC docs @ 5c41560e, gclint/firmware/linuxcnc.py).
_LINUXCNC_G = G_CODES
_LINUXCNC_M = M_CODES
# Machinekit-FDM remap.ini (final flavour: value in P, index in T) and the flavour of its first README ("Machinekit
# Flavor GCode", Dec 2014).
_FDM = [
    code(
        "M104",
        "set extruder temperature",
        P("P", "temperature (final) or sensor index (seed)"),
        P("S", "temperature (seed)"),
        P("T", "extruder index (final)"),
        P("I", "immediate"),
        source="remap.ini / first README (Dec 2014)",
    ),
    code(
        "M106",
        "fan / device PWM",
        P("P", "PWM value (final) or device index (seed)"),
        P("S", "PWM 0-255 (seed)"),
        P("T", "fan index (final)"),
        P("I", "execute immediately"),
        source="remap.ini / first README (Dec 2014)",
    ),
    code(
        "M107", "fan off", P("T", "fan index"), P("P", "device index (seed)"), P("I", "immediate"), source="remap.ini"
    ),
    code(
        "M109",
        "set extruder temperature and wait",
        P("P", "temperature (final) or sensor index (seed)"),
        P("S", "temperature (seed)"),
        P("T", "extruder index"),
        source="remap.ini / first README (Dec 2014)",
    ),
    code(
        "M140", "set bed temperature", P("P", "temperature"), P("S", "temperature (RepRap style)"), P("I", "immediate")
    ),
    code(
        "M141",
        "set chamber temperature",
        P("P", "temperature"),
        P("S", "temperature (RepRap style)"),
        P("I", "immediate"),
    ),
    code("M190", "bed temperature and wait", P("P", "temperature"), P("S", "temperature (RepRap style)")),
    code("M191", "chamber temperature and wait", P("P", "temperature"), P("S", "temperature (RepRap style)")),
    code("M200", "filament diameter (velocity extrusion)", P("D", "diameter", required=True)),
    code("M207", "retraction length and speed", P("P", "length, mm"), P("Q", "speed, mm/s")),
    code("M221", "extrusion scale factor", P("P", "factor (0.96 = 96 %)")),
    *codes("G22 G23 G28 G29 G29.1 G29.2 G30 M226 M280 M300 M400 M420 M700 M701 M702 M710 M600 M601 M306"),
    # LinuxCNC refuses a G4 with no P: "Dwell time missing with g4" (src/emc/rs274ngc/interp_check.cc,
    # NCE_DWELL_TIME_MISSING_WITH_G4; g-code.adoc "G4 Dwell": "It is an error if: the P number is negative or not
    # specified", https://linuxcnc.org/docs/html/gcode/g-code.html#gcode:g4): the program stops there
    code(
        "G4",
        "dwell",
        P("P", "seconds to dwell", required=True, minimum=0),
        P("S", "spindle speed (set before the dwell)"),
        source="LinuxCNC g-code.adoc, interp_check.cc",
    ),
]

# What the common RS274NGC codes do, for ``gclint explain`` (LinuxCNC G-code and M-code references).
_MOVE = {"X": "X", "Y": "Y", "Z": "Z", "A": "A axis", "B": "B axis", "C": "C axis", "F": "feed rate (G94: units/min)"}
_CYCLE = {**_MOVE, "R": "retract plane", "P": "dwell at the bottom, s", "Q": "peck increment", "L": "repeats"}
_DESCRIPTIONS: Descriptions = {
    "G0": ("rapid move", _MOVE),
    "G1": ("linear move at feed rate", _MOVE),
    "G2": (
        "clockwise arc",
        {
            **_MOVE,
            "I": "center X offset",
            "J": "center Y offset",
            "K": "center Z offset",
            "R": "radius",
            "P": "number of turns",
        },
    ),
    "G3": (
        "counter-clockwise arc",
        {
            **_MOVE,
            "I": "center X offset",
            "J": "center Y offset",
            "K": "center Z offset",
            "R": "radius",
            "P": "number of turns",
        },
    ),
    "G4": ("dwell", {"P": "seconds"}),
    "G10": (
        "set the tool table or a coordinate system",
        {
            "L": "what to set (L1/L10 tool, L2/L20 coordinate system)",
            "P": "tool or coordinate system number",
            "R": "radius",
        },
    ),
    "G17": "arc plane XY",
    "G18": "arc plane XZ",
    "G19": "arc plane YZ",
    "G20": "units are inches",
    "G21": "units are millimetres",
    "G28": "go to the position stored with G28.1 (through the listed axes' intermediate point)",
    "G28.1": "store the current absolute position for G28",
    "G30": "go to the position stored with G30.1",
    "G33": "spindle-synchronised motion (threading)",
    "G38.2": "straight probe toward the workpiece, stop on contact, error if no contact",
    "G40": "cutter compensation off",
    "G41": ("cutter compensation left", {"D": "tool number"}),
    "G42": ("cutter compensation right", {"D": "tool number"}),
    "G43": ("tool length offset", {"H": "tool number (default: the loaded tool)"}),
    "G49": "cancel tool length offset",
    "G53": "move in machine coordinates (this line only)",
    "G54": "use coordinate system 1",
    "G55": "use coordinate system 2",
    "G56": "use coordinate system 3",
    "G57": "use coordinate system 4",
    "G58": "use coordinate system 5",
    "G59": "use coordinate system 6",
    "G61": "exact path mode",
    "G90.1": "arc centres absolute: I J K are coordinates",
    "G91.1": "arc centres incremental: I J K are offsets from the start",
    "G64": ("path blending", {"P": "path tolerance", "Q": "naive cam tolerance"}),
    "G80": "cancel canned cycle",
    "G81": ("drilling cycle", _CYCLE),
    "G82": ("drilling cycle with dwell", _CYCLE),
    "G83": ("peck drilling cycle", _CYCLE),
    "G90": "absolute distance mode",
    "G91": "incremental distance mode",
    "G92": ("coordinate system offset: the current point gets these values", _MOVE),
    "G93": "inverse time feed mode",
    "G94": "units per minute feed mode",
    "G95": "units per revolution feed mode",
    "G98": "canned cycles return to the initial level",
    "G99": "canned cycles return to the R level",
    "M0": "pause the program (resume with cycle start)",
    "M1": "optional pause",
    "M2": "end of program",
    "M3": ("spindle on, clockwise", {"S": "speed, RPM"}),
    "M4": ("spindle on, counter-clockwise", {"S": "speed, RPM"}),
    "M5": "spindle off",
    "M6": ("tool change to the tool selected by T", {"T": "tool number"}),
    "M7": "mist coolant on",
    "M8": "flood coolant on",
    "M9": "coolant off",
    "M30": "end of program (rewind)",
    "M60": "pallet change pause",
    "M61": ("set the current tool number without a change", {"Q": "tool number"}),
    "M62": ("digital output on, synchronised with motion", {"P": "output number"}),
    "M63": ("digital output off, synchronised with motion", {"P": "output number"}),
    "M64": ("digital output on, now", {"P": "output number"}),
    "M65": ("digital output off, now", {"P": "output number"}),
    "M66": ("wait on an input", {"P": "digital input", "E": "analog input", "L": "wait mode", "Q": "time-out, s"}),
    "M67": ("analog output, synchronised with motion", {"E": "output number", "Q": "value"}),
    "M68": ("analog output, now", {"E": "output number", "Q": "value"}),
}


def _open(code: str) -> bool:
    # T<n> selects a tool; M100-M199 are user M-codes (external programs); G#<x> codes are computed.
    if code[0] == "T" or "#" in code or "[" in code:
        return True
    if code[0] == "M" and code[1:].isdigit() and len(code) <= 4:  # no int() of a 5000-digit code
        return 100 <= int(code[1:]) <= 199
    return False


def _bracket_expression(cmd) -> bool:
    return cmd.kind == GCODE and any(v and v[0] in "[#" for v in cmd.params.values())


# Content that marks Machinekit/LinuxCNC (Machinekit-FDM remap.ini, LinuxCNC docs; docs/translation.md, Machinekit).
# The RS274NGC program language (O-words, # parameters, [expressions]) is Carvera's too.
NGC_LANGUAGE_CLUES = (
    # "S10000 M3": a spindle speed written as a word of its own, before the M3 (RS274NGC)
    Clue("an S word on its own (a spindle speed)", kind=IMPLICIT, test=lambda c: "S" in c.params, weight=2),
    Clue("a # parameter assignment", kind=ASSIGNMENT, weight=4),
    Clue("a [expression] or #parameter value", test=_bracket_expression, weight=2, contains="[#"),
)
MACHINEKIT_CLUES = (
    *NGC_LANGUAGE_CLUES,
    # LinuxCNC's O-word control flow ("o100 sub", "o<name> call", "o101 if [...]": LinuxCNC documentation,
    # o-code.adoc); Carvera's subprograms are M98/M99 calls of numbered programs
    Clue("an O-word (o100 sub/if/while/call)", kind=OWORD, weight=4),
    # the remap.ini M-codes take the value in P ("M104 P200"), where the others write S
    *(
        Clue(
            f"{c} P# without S: a Machinekit remap temperature",
            c,
            test=lambda c: "P" in c.params and "S" not in c.params,
        )
        for c in ("M104", "M109", "M140", "M190")
    ),
    # the extruder is the A axis: a working move with A and no E
    # a C axis: five-axis LinuxCNC machines (Carvera's 4th axis is A, Hyrel's rotary axes A and B; but an
    # E3D tool changer on RepRapFirmware locks tools with C: weak)
    *(Clue(f"{c} C#: a C axis", c, test=lambda c: "C" in c.params, weight=1) for c in ("G0", "G1")),
    # "G41 D- ... D - tool number" (LinuxCNC documentation, gcode/g-code.adoc, "G41, G42 Cutter Compensation"):
    # Marlin's G42 is a move to a mesh point, "G42 [F] [I] [J]" (marlinfw.org/docs/gcode/G042.html)
    *(
        Clue(f"{c} D#: cutter compensation by a tool's diameter", c, test=lambda c: "D" in c.params, weight=1)
        for c in ("G41", "G42")
    ),
    # (weak, less than Hyrel's prior: Carvera's 4th axis and Hyrel's A/B axes move A too)
    Clue("G1 A#: extrusion on the A axis", "G1", test=lambda c: "A" in c.params and "E" not in c.params, weight=0.5),
)

# The LinuxCNC interpreter's reading of a line, which Machinekit shares (gclint.dialects.semantics names the
# sections of the LinuxCNC documentation): the order of execution, G90.1/G91.1, G28/G30 through a point to a stored
# position, T that the next M6 loads (T0: no tool), G4 P in seconds, F on any line, G54 at the start.  The extruder
# is the A axis (Machinekit-FDM GCode.org G28 and subroutines/g28.ngc; machinekit-cnc scripts/gcode-to-ngc rewrites
# E to A).
MACHINEKIT_SEMANTICS = Semantics(
    dwell=DWELL_P_SECONDS,
    extruder="A",
    g0_feed="rapid",
    e_follows_g90=True,
    working="feeds",
    arc_centre_modes=True,
    arc_turns="turns",
    order=LINUXCNC_ORDER,
    words_first=("F", "S", "T"),
    home="predefined",
    g30="predefined",
    tool_select="prepare",
    no_tool=0,
    wait_r=None,  # the FDM remaps' M109 takes P (value) and T (index): Machinekit-FDM remap.ini "argspec=tP"
    heat_words="remap",
    feed_on_any_command=True,
    default_workspace="G54",
    user_programs=True,
    blanks_ignored=True,
    tool_change_stops_spindle=True,
    effects=effects(
        WORKSPACES,
        {f"G59.{n}": "workspace" for n in (1, 2, 3)},
        {
            "G17.1": "plane",
            "G18.1": "plane",
            "G19.1": "plane",
            "G90.1": "arc-absolute",
            "G91.1": "arc-relative",
            "G92.1": "clear-g92",
            "G92.2": "clear-g92",
            "G30": "predefined-position",
            "G53": "machine-coordinates",
            "G93": "inverse-time",
            "G94": "units-per-minute",
            "M0": "pause",
            "M60": "pause",
            "M1": "optional-stop",
            "M2": "end-program",
            "M30": "end-program",
            "M6": "tool-change",
            "M61": "set-tool",
            "M98": "call-subroutine",  # Fanuc-style "M98 P<n>": the job's own O<n> (interp_o_word.cc)
            "M7": "coolant",
            "M8": "coolant",
            "M9": "coolant-off",
            "M226": "pause",  # the FDM remap's pause (Machinekit-FDM remap.ini, M226; docs/translation.md)
            "M221": "flow",
            "M18": None,  # (no motors-off code in LinuxCNC)
            "M84": None,
        },
    ),
)

MACHINEKIT = Dialect(
    name="machinekit",
    title="Machinekit FDM / LinuxCNC (RS274NGC with the FDM remaps)",
    family="linuxcnc",
    codes=describe(table(codes(_LINUXCNC_G), codes(_LINUXCNC_M), _FDM), _DESCRIPTIONS),
    aliases=("linuxcnc", "machinekit-fdm"),
    detection=Detection(
        patterns=(
            (r"(?i)^;\s*gcode_flavor\s*=\s*machinekit", 12),
            (r"(?i)^[;(][^\n]*\b(?:LinuxCNC|Machinekit|EMC2)\b", 4),  # (a comment naming the controller: weak)
        ),
        extensions=(".ngc",),
        clues=MACHINEKIT_CLUES,
        prior=0.05,  # an RS274NGC program Carvera runs as well is more often LinuxCNC's (it shares Carvera's clues)
    ),
    owords=True,
    not_move_words="E",  # the extruder is A (Machinekit-FDM subroutines/g28.ngc; gcode-to-ngc: E -> A)
    open_codes=_open,
    unknown_severity="error",  # the LinuxCNC interpreter stops on an unknown code
    unknown_note="the machinekit interpreter stops on an unknown code",
    description="Machinekit's FDM configuration of the LinuxCNC interpreter; also plain LinuxCNC programs.",
    semantics=MACHINEKIT_SEMANTICS,
    machine_ini=True,
    sources=(
        "Machinekit-FDM: github.com/machinekoder/Machinekit-FDM-Standard (GCode.md of Dec 2014; remap.ini @ 397d429)",
        "machinekit-cnc: github.com/machinekit/machinekit-cnc @ 93065fc (remap-subroutines/fdm, scripts/gcode-to-ngc)",
        "LinuxCNC docs: https://linuxcnc.org/docs/html/gcode/g-code.html (source @ 5c41560e)",
    ),
    extras={"fan_max": 255},
)

_ = span
