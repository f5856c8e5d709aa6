"""What the words of a line make a dialect's machine do: typed facts, one home each.

Every dialect declares a ``Semantics`` (as sqlglot's dialect classes carry capability flags): how G4 counts
time, which word drives the extruder and what it means, what G0 does with E and with F, how arc centres are
given, in what order the commands of one line run and how many of them run, what G28 and G30 do, what T
selects, and the effect of each code (``effects``: code -> what it does).  Everything that reads a file
(the machine state the rules see, ``explain``, ``summary``, the toolpath, the ``diff`` simulator and the
translator's reader) asks these facts; no code outside ``gclint/dialects/`` tests a dialect's name.

The facts and where each comes from:

* G4.  Marlin: ``P`` milliseconds, ``S`` seconds, and when both are given S counts (Marlin's
  ``GcodeSuite::G4``: the S assignment follows the P one).  RepRapFirmware: the same (``GCodes::DoDwell``:
  ``if S ... else if P``).  Hyrel: S seconds, P milliseconds, "if you use both, the total value will be the
  pause duration" (Hyrel wiki, Gcode page, "G4 Timed Pause").  LinuxCNC and Machinekit: "P - seconds to
  dwell (floating point)" and S is the spindle speed (LinuxCNC documentation, ``docs/src/gcode/g-code.adoc``,
  "G4 Dwell").  Carvera (Smoothieware in grbl mode): "P is decimal seconds", S adds seconds (Smoothieware
  ``Robot.cpp``, G4; Carvera reports grbl mode, Carvera community docs).
* Order of execution within a line (LinuxCNC documentation, ``docs/src/gcode/overview.adoc``, "G-code Order
  of Execution"): feed mode, F, S, T, M62-M68, M6/M61, M3-M5, M70-M73, M7-M9, M48-M53, M100-M199, G4,
  planes, units, G40-G42, G43/G49, G54-G59.3, G61/G64, G90/G91, G98/G99, G28/G30/G10/G52/G92, motion, stops.
  Other dialects run a line's commands in the order they are written.
* Commands per line: Marlin reads the first command of a line; what follows are its parameters
  (``Marlin/src/gcode/parser.cpp``, ``GCodeParser::parse``).  RepRapFirmware runs every command of a line in
  turn (``src/GCodes/GCodeBuffer/StringParser.cpp``: "There is another command in the same line of gcode").
* Arc centres: ``G90.1`` makes I, J and K absolute, ``G91.1`` returns them to offsets (LinuxCNC ``g-code.adoc``,
  "G90.1, G91.1 Arc Distance Mode").
* G28/G30: LinuxCNC's "G28 axes - makes a rapid move to the position specified by axes including any offsets,
  then will make a rapid move to the absolute position of the values in parameters 5161-5166 for all axes
  specified"; bare G28 moves every axis there; G30 the same with parameters 5181-5189 (``g-code.adoc``,
  "G28, G28.1", "G30, G30.1").  Hyrel: "G28 sends the X and/or Y axes to the sensor-defined physical home
  ... Any axis not homed will have its position remain unchanged" (Gcode page, "G28").  Marlin and
  RepRapFirmware: G28 with no axis homes every axis.  Carvera: "G28 means goto clearance position" (Carvera
  community docs).
* T and M6: LinuxCNC's T selects the tool that the next M6 loads, and "T0 gets special handling: no tool will
  be selected" (``docs/src/gcode/other-code.adoc``, "T: Select Tool"); Marlin and RepRapFirmware change tools
  at T; Hyrel's T focuses a head by its address (Hyrel wiki, T_v5 page).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Literal

from gclint.syntax.nodes import ParsedLine
from gclint.syntax.parse import parse_line, read_blanks_ignored

# -- dwell --------------------------------------------------------------------------------------------------


def number(text: str | None) -> float | None:
    """A word's value as a float; None for a flag, an expression or a bad number."""
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        return None
    return value if value - value == 0 else None


# LinuxCNC's unary functions ("G-code Functions": ATAN[arg]/[arg], ABS, ACOS, ASIN, COS, EXP, FIX, FUP, ROUND, LN,
# SIN, SQRT, TAN, EXISTS; https://linuxcnc.org/docs/html/gcode/overview.html#gcode:functions): a word's value
# may start with one (``X SIN[30]``), as it may with ``[`` (an expression) or ``#`` (a parameter)
FUNCTIONS = frozenset("ATAN ABS ACOS ASIN COS EXP FIX FUP ROUND LN SIN SQRT TAN EXISTS".split())
_FUNCTION = re.compile(r"([A-Za-z]+)[ \t]*\[")


def computed(text: str | None) -> bool:
    """True when a word's value is computed when the line runs rather than written as a number: an expression
    (``[1+2]``, ``{...}``), a parameter (``#1``, ``#<_x>``) or a function (``SIN[30]``, ``ABS[-4]``,
    ``EXISTS[#<_foo>]``), with or without a sign.  A flag (None), a literal number or a quoted string is not."""
    if not text or text[0] == '"':
        return False
    body = text.lstrip("+-")
    if body[:1] in ("[", "{", "#"):
        return True
    m = _FUNCTION.match(body)
    return m is not None and m.group(1).upper() in FUNCTIONS


@dataclass(frozen=True)
class Dwell:
    """How G4 counts time: seconds per unit of ``P`` and of ``S`` (None: the letter is not a dwell word),
    and which counts when both are written (``"s"``: S alone; ``"sum"``: they add up).  ``required``: the word a G4
    must have, else the interpreter refuses the line and stops the program."""

    def refused(self, params: Mapping[str, str | None]) -> bool:
        """True when the machine refuses this G4 and stops the program (the ``required`` word is missing)."""
        return self.required is not None and self.required not in params

    p_seconds: float | None
    s_seconds: float | None
    both: Literal["s", "sum"] = "sum"
    required: str | None = None  # the word without which G4 is an error that stops the program (LinuxCNC: P)

    def seconds(self, params: Mapping[str, str | None]) -> float | None:
        """The dwell's length in seconds (never negative), or None when the line gives no time."""
        p = number(params.get("P")) if self.p_seconds is not None else None
        s = number(params.get("S")) if self.s_seconds is not None else None
        if p is None and s is None:
            return None
        if s is not None and self.both == "s":
            return max(0.0, s * self.s_seconds)  # type: ignore[operator]
        total = (p * self.p_seconds if p is not None else 0.0) + (s * self.s_seconds if s is not None else 0.0)  # type: ignore[operator]
        return max(0.0, total)

    def unit(self, letter: str) -> str | None:
        """``"ms"`` or ``"s"``: what one unit of ``letter`` is on G4; None when it is not a dwell word."""
        per = self.p_seconds if letter == "P" else self.s_seconds if letter == "S" else None
        if per is None:
            return None
        return "ms" if per == 0.001 else "s" if per == 1.0 else f"{per:g} s"

    def describe(self) -> str:
        """How P and S combine, in words (explain)."""
        if self.p_seconds is not None and self.s_seconds is not None:
            return "S and P add up" if self.both == "sum" else "S counts, P is ignored, when both are given"
        return ""


# -- order of execution ----------------------------------------------------------------------------------------

_WORDS_FIRST = ("F", "S", "T")  # LinuxCNC sets feed, speed and the prepared tool before any command of the line


def _codes(*groups: str) -> frozenset[str]:
    out: set[str] = set()
    for group in groups:
        out.update(group.split())
    return frozenset(out)


# LinuxCNC documentation, overview.adoc, "G-code Order of Execution" (the words F, S and T are its steps 2-4:
# ``Semantics.words_first``).  A code in none of the steps runs where a user-defined M-code would, before the
# dwell and the motion (the FDM remaps of Machinekit are M-codes of that range or G-codes the INI remaps).
LINUXCNC_ORDER: tuple[frozenset[str], ...] = (
    _codes("G93 G94 G95"),
    _codes("T"),  # "Select tool (T)": a T word our parser reads as a command of its own (``t1 m6``)
    _codes("M62 M63 M64 M65 M66 M67 M68"),
    _codes("M6 M61"),
    _codes("M3 M4 M5"),
    _codes("M70 M71 M72 M73"),
    _codes("M7 M8 M9"),
    _codes("M48 M49 M50 M51 M52 M53"),
    frozenset(f"M{n}" for n in range(100, 200)),
    _codes("G4"),
    _codes("G17 G18 G19 G17.1 G18.1 G19.1"),
    _codes("G20 G21"),
    _codes("G40 G41 G42 G41.1 G42.1"),
    _codes("G43 G43.1 G43.2 G49"),
    _codes("G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3"),
    _codes("G61 G61.1 G64"),
    _codes("G90 G91 G90.1 G91.1"),
    _codes("G98 G99"),
    _codes("G28 G30 G10 G52 G92 G92.1 G92.2 G92.3 G28.1 G30.1"),
    _codes("G0 G1 G2 G3 G33 G33.1 G38.2 G38.3 G38.4 G38.5 G73 G76 G80 G81 G82 G83 G84 G85 G86 G87 G88 G89 G53"),
    _codes("M0 M1 M2 M30 M60"),
)
_UNLISTED_STEP = 8  # (the user-defined M-codes' step)
_MOTION_STEP = len(LINUXCNC_ORDER) - 2


# -- effects -------------------------------------------------------------------------------------------------------

# What a code does, by name.  The interpreters map each effect to the code that carries it out; a dialect's
# table says which of its codes has which effect (a code with no effect changes nothing the model keeps).
Effect = str

COMMON_EFFECTS: dict[str, Effect] = {
    "G0": "rapid",
    "G1": "linear",
    "G2": "arc",
    "G3": "arc",
    "G4": "dwell",
    "G17": "plane",
    "G18": "plane",
    "G19": "plane",
    "G20": "inch",
    "G21": "mm",
    "G90": "absolute",
    "G91": "relative",
    "G92": "set-position",
    "G28": "home",
    "M82": "e-absolute",
    "M83": "e-relative",
    "M104": "set-head-temperature",
    "M109": "wait-head-temperature",
    "M140": "set-bed-temperature",
    "M190": "wait-bed-temperature",
    "M141": "set-chamber-temperature",
    "M191": "wait-chamber-temperature",
    "M106": "fan",
    "M107": "fan-off",
    "M3": "spindle-cw",
    "M4": "spindle-ccw",
    "M5": "spindle-off",
    "M18": "motors-off",
    "M84": "motors-off",
}
WORKSPACES = {f"G{n}": "workspace" for n in range(54, 60)}


# -- the facts -----------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Semantics:
    """How a dialect's machine reads a line.  Each field is one fact (the module docstring names the sources).

    * ``dwell``: how G4 counts time.
    * ``extruder``: the word that drives the extruder (``"E"``; ``"A"`` on Machinekit, where E is not a word;
      None where nothing extrudes).  ``e_values``: what an E amount means: ``"amount"`` (the filament it
      feeds), ``"native"`` (Hyrel native flow: an E marks a printing move and the machine meters the flow,
      unless ``M229 E1 D1`` asks for the amounts: Hyrel wiki, Gcode page, "G1 Working Move", "M229").
    * ``g0_extrudes``: G0 is G1 and deposits what its E says (Marlin, RepRapFirmware in FDM mode).
      ``g0_feed``: what F on G0 does: ``"modal"`` (shared with G1), ``"one-shot"`` (this move only: Hyrel,
      Carvera), ``"rapid"`` (the rapid ignores it, later moves use it: LinuxCNC).
    * ``e_follows_g90``: G90/G91 set the E mode too (Marlin; Machinekit's extruder is an axis).
    * ``working``: what a working move is: ``"extrudes"`` (a printer: a move that deposits) or ``"feeds"``
      (a CNC machine: every feed move cuts).
    * ``arc_centre_modes``: G90.1/G91.1 switch I J K between absolute and offsets.  ``arc_turns``: what P on
      G2/G3 counts: ``"extra"`` full circles before the end (Marlin, RepRapFirmware), ``"turns"`` (LinuxCNC:
      P1 is the plain arc), None (no P).
    * ``order``: the steps in which a line's commands run (None: as written); ``words_first``: the letters
      set before any command of the line (LinuxCNC's F, S and T).  ``commands_per_line``: ``"all"`` or
      ``"first"`` (the others are the first one's parameters and do nothing), except after a code of
      ``chains``, which runs the rest of its line as a command (Marlin's G53: ``parser.chain()``).
    * ``home``: what G28 does: ``"listed"`` (homes the listed axes only), ``"all-if-none"`` (no axis: every
      axis), ``"predefined"`` (through the listed point to a stored position: LinuxCNC), ``"clearance"``
      (to a clearance position the file does not state: Carvera), ``"zero-listed"`` (a rapid to the listed
      axes' zero: Machinekit FDM's remap).  ``g30``: ``"predefined"`` or None.
    * ``tool_select``: what ``T<n>`` does: ``"address"`` (focuses the head at that address: Hyrel),
      ``"extruder"`` (changes to tool n), ``"prepare"`` (prepares tool n for the next tool change).
      ``no_tool``: the T number that means "no tool"; ``probe_tool``: the T number of the machine's probe (Carvera:
      "M6 | Auto tool change, T0 indicates wireless probe, T-1 indicates None",
      https://carvera-community.gitbook.io/docs/firmware/supported-commands/mcodes).
    * ``feed_on_any_command``: an F word sets the feed whatever the line's code (LinuxCNC, Carvera).
      ``default_workspace``: the workspace in force at the start.
    * ``fan_scale``: what M106 S counts: ``"255"`` (0-255, Marlin), ``"255-or-fraction"`` (RepRapFirmware:
      0-1 as a fraction, above 1 of 255), ``"range"`` (a share of the range M106 C set, default 100: Hyrel,
      "M106 Set Cooling / Etc.").  ``wait_r``: what R on M109/M190 is: ``"target"`` (a set-point waited for
      while heating or cooling: Marlin, RepRapFirmware), ``"tolerance"`` (the window the wait accepts: Hyrel,
      "M109 Wait for Temp (Head)"), None (no R).  ``heat_words``: which words carry a set-point and the tool it
      is for: ``"S"`` (S, and T the tool) or ``"remap"`` (Machinekit FDM: the README's ``M104 P<index> S<temp>``,
      else the remap's ``M104 P<temp> T<index>``: Machinekit-FDM remap.ini "argspec=iPt").
    * ``user_programs``: M100-M199 run the external program of that name where the dialect has no code of its
      own by that number (LinuxCNC's M-code documentation, "M100-M199 User Defined Commands").
    * ``blanks_ignored``: spaces and tabs outside comments do not count, even inside a number (LinuxCNC: "Spaces
      and tabs are allowed anywhere on a line of code ... 'G0X +0. 12 34Y 7' is equivalent to 'G0 x+0.1234 Y7'",
      https://linuxcnc.org/docs/html/gcode/overview.html#_format_of_a_line).
    * ``tool_change_stops_spindle``: the tool change (M6) leaves the spindle stopped, and only a later M3/M4 starts
      it (LinuxCNC: "When the tool change is complete: The spindle will be stopped", M-codes, "M6 Tool Change",
      https://linuxcnc.org/docs/html/gcode/m-code.html#mcode:m6; Carvera: "M6 | Auto tool change", the ATC
      swaps the tool in a stopped spindle: https://carvera-community.gitbook.io/docs/firmware/supported-commands/mcodes).
    * ``effects``: code -> effect (``COMMON_EFFECTS`` and the dialect's own).
    """

    dwell: Dwell
    extruder: str | None = "E"
    e_values: Literal["amount", "native"] = "amount"
    g0_extrudes: bool = False
    g0_feed: Literal["modal", "one-shot", "rapid"] = "modal"
    e_follows_g90: bool = False
    working: Literal["extrudes", "feeds"] = "extrudes"
    arc_centre_modes: bool = False
    arc_turns: Literal["extra", "turns"] | None = None
    order: tuple[frozenset[str], ...] | None = None
    words_first: tuple[str, ...] = ()
    commands_per_line: Literal["all", "first"] = "all"
    chains: frozenset[str] = frozenset()  # (``first``) codes that run the rest of their line as the next command
    home: Literal["listed", "all-if-none", "predefined", "clearance", "zero-listed"] = "all-if-none"
    g30: Literal["predefined"] | None = None
    tool_select: Literal["address", "extruder", "prepare"] = "extruder"
    no_tool: int | None = None
    probe_tool: int | None = None  # the T number of the machine's probe (Carvera: T0, the wireless probe)
    feed_on_any_command: bool = False
    default_workspace: str | None = None
    fan_scale: Literal["range", "255", "255-or-fraction"] = "255"
    wait_r: Literal["target", "tolerance"] | None = "target"
    heat_words: Literal["S", "remap"] = "S"
    user_programs: bool = False
    blanks_ignored: bool = False
    tool_change_stops_spindle: bool = False
    effects: Mapping[str, Effect] = field(default_factory=lambda: dict(COMMON_EFFECTS))

    def parse(self, raw: str) -> ParsedLine:
        """One line as this dialect's machine reads it (``blanks_ignored``: ``X 2 0`` is X20)."""
        return read_blanks_ignored(raw) if self.blanks_ignored else parse_line(raw)

    def set_point(self, params: Mapping[str, str | None], wait: bool) -> tuple[float | None, str | None]:
        """The temperature a set or wait command gives (°C, None: none) and the word that names its tool
        (None: the active one)."""
        if self.heat_words == "remap":
            if "S" in params:
                return number(params["S"]), "P" if "P" in params else None
            return number(params.get("P")), "T" if "T" in params else None
        if "S" in params:
            value = number(params["S"])
        elif wait and self.wait_r == "target" and "R" in params:
            value = number(params["R"])  # Marlin's M109 R: a target it waits for heating or cooling
        else:
            value = None
        return value, "T" if "T" in params else None

    def effect(self, code: str | None) -> Effect | None:
        return self.effects.get(code) if code is not None else None

    def codes_with(self, *effects: Effect) -> frozenset[str]:
        """The codes that have one of ``effects``."""
        return frozenset(code for code, effect in self.effects.items() if effect in effects)

    def running(self, commands: tuple) -> tuple:
        """The commands of one line that run, in the order they run (``commands``: the line's ``Command``
        nodes as written)."""
        if len(commands) < 2:
            return commands
        if self.commands_per_line == "first":
            first = commands[:1]
            if commands[0].code in self.chains:
                return first + self.running(commands[1:])
            return first
        if self.order is None:
            return commands
        return tuple(sorted(commands, key=self._step))

    def ignored(self, commands: tuple) -> tuple:
        """The commands of a line that do not run (Marlin: all but the first, and what a chain runs)."""
        if self.commands_per_line != "first" or len(commands) < 2:
            return ()
        ran = {id(cmd) for cmd in self.running(commands)}
        return tuple(cmd for cmd in commands if id(cmd) not in ran)

    def _step(self, cmd) -> int:
        code = cmd.code
        if code is None:  # axis words alone: the modal motion; words that are set first alone (S10000 M3): first
            params = cmd.params
            if params and all(letter in self.words_first for letter in params):
                return -1
            return _MOTION_STEP
        if code[0] == "T":
            code = "T"
        for index, step in enumerate(self.order or ()):
            if code in step:
                return index
        return _UNLISTED_STEP

    def derive(self, **changes) -> Semantics:
        """These facts with some changed (``effects`` given as a delta: ``{"M30": "end-program"}``; an effect of
        None removes the code)."""
        delta = changes.pop("effects", None)
        if delta is not None:
            table = dict(self.effects)
            for code, effect in delta.items():
                if effect is None:
                    table.pop(code, None)
                else:
                    table[code] = effect
            changes["effects"] = table
        return replace(self, **changes)


def effects(*tables: Mapping[str, Effect | None]) -> dict[str, Effect]:
    """``COMMON_EFFECTS`` with the tables' changes applied in turn (an effect of None removes the code)."""
    out: dict[str, Effect] = dict(COMMON_EFFECTS)
    for t in tables:
        for code, effect in t.items():
            if effect is None:
                out.pop(code, None)
            else:
                out[code] = effect
    return out


# The dwells (sources in the module docstring).
DWELL_MS_S_WINS = Dwell(p_seconds=0.001, s_seconds=1.0, both="s")  # Marlin, RepRapFirmware
DWELL_MS_S_SUM = Dwell(p_seconds=0.001, s_seconds=1.0, both="sum")  # Hyrel
# LinuxCNC, Machinekit: "It is an error if: the P number is negative or not specified" (g-code.adoc, "G4 Dwell",
# https://linuxcnc.org/docs/html/gcode/g-code.html#gcode:g4; interp_check.cc: NCE_DWELL_TIME_MISSING_WITH_G4)
DWELL_P_SECONDS = Dwell(p_seconds=1.0, s_seconds=None, required="P")
DWELL_SECONDS_SUM = Dwell(p_seconds=1.0, s_seconds=1.0, both="sum")  # Smoothieware in grbl mode (Carvera)
DWELL_UNKNOWN = Dwell(p_seconds=None, s_seconds=None)  # a dialect whose G4 the project does not know (generic)
