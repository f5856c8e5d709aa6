"""Habits: the Marlin (and slicer) habits a Hyrel job is known to carry, as data.

A habit is a line that is a mistake on Hyrel but natural on another firmware: a bare ``G28``, ``M109 R215``,
``M106 S255`` with no range.  The HY rules exist to catch them, so when gclint.context weighs what a file is,
a habit costs the Hyrel reading a little (a Hyrel job with a mistake in it) and is no evidence for the other
firmware: a Hyrel job that homes with a bare ``G28`` is still a Hyrel job, and HY025 reports the line.

Each habit names the rule that reports it; the fact behind it is the Hyrel wiki's (Gcode page, the section
named at each).
"""

from __future__ import annotations

from gclint.dialects.base import Habit
from gclint.syntax.nodes import GCODE


def _value(cmd, letter: str) -> float | None:
    try:
        return cmd.get(letter)
    except (TypeError, ValueError):
        return None


def _over(letter: str, limit: float):
    def test(cmd, state) -> bool:
        value = _value(cmd, letter)
        return value is not None and value > limit

    return test


def _fan_over_range(cmd, state) -> bool:
    # "Cn is the range (0-100 or 0-255) ... default is C100" (M106 Set Cooling / Etc.): S above 100 with no C
    # range set on this line or before is a 0-255 fan value
    value = _value(cmd, "S")
    return value is not None and value > 100 and "C" not in cmd.params and not state.fan_range


def _h_without_register(cmd, state) -> bool:
    # "Hn is the stored head offset to apply (see M660 to store offsets)" (G1 Working Move): an H no M660 set is
    # RepRapFirmware's homing-move H1/H2, a mistake on Hyrel (HY034)
    value = _value(cmd, "H")
    return value is not None and value not in state.height_registers


def _e_mode_without_m229(cmd, state) -> bool:
    # "M82/M83 ... only used with M229 E1" (M82 Absolute E-Values, M83 Relative E-Values)
    return not state.e_values


def marlin_style_r(cmd) -> bool:
    """A Hyrel wait whose R looks like a Marlin target (HY035): R above 50 with no S.  The page sets no limit
    on the tolerance, and its own "M109 R10" (M109 Example 6) is Hyrel's."""
    if cmd.get("S") is not None:
        return False
    r = cmd.get("R")
    return r is not None and r > 50


HYREL_HABITS = (
    # "Any axis not homed will have its position remain unchanged" (G28 Send X, Y to Physical Home)
    Habit("G28 with no axis (on Hyrel it homes nothing)", "HY025", "G28", GCODE, lambda c, s: not c.params),
    # "R ... is how close the relative temperature needs to be to the set temp" (M109 Wait for Temp (Head))
    *(
        Habit(
            f"{c} R with no S (a Marlin target; on Hyrel R is a tolerance)",
            "HY035",
            c,
            GCODE,
            # (what HY035 reports: an R above 50 with no S; the page's own "M109 R10" (Example 6) is Hyrel's)
            lambda c, s: marlin_style_r(c),
        )
        for c in ("M109", "M190", "M191")
    ),
    Habit("M106 S above 100 with no C range (a 0-255 fan value)", "HY011", "M106", GCODE, _fan_over_range),
    # "Sn - power (0-100%)" (M3 Turn On Spindle (CW)): an rpm is another firmware's spindle speed
    *(
        Habit(f"{c} S above 100 (an rpm; Hyrel's S is a percentage)", "HY023", c, GCODE, _over("S", 100))
        for c in ("M3", "M4")
    ),
    # "M6 declares that a particular head holds a set of X, Y, and/or Z offsets" (M6 Declare Head Offsets): an
    # M6 with nothing to declare is a CNC tool change
    Habit(
        "M6 with no offset (a tool change; Hyrel's M6 declares offsets)",
        "HY038",
        "M6",
        GCODE,
        lambda c, s: not any(k in c.params for k in "OXYZABDIK"),
    ),
    # "G10 UNUSED", "G11 UNUSED": not recognized by Repetrel
    *(Habit(f"{c}: firmware retraction (not recognized by Repetrel)", "HY015", c, GCODE) for c in ("G10", "G11")),
    # "G20 Set Units to Inches": experimental, unsupported
    Habit("G20 inches (experimental on Hyrel)", "HY026", "G20", GCODE),
    *(
        Habit(f"{c} with no M229 E1 (E modes count only with E values)", "HY013", c, GCODE, _e_mode_without_m229)
        for c in ("M82", "M83")
    ),
    *(
        Habit(f"{c} H with no M660 register set (RepRapFirmware's homing move)", "HY034", c, GCODE, _h_without_register)
        for c in ("G0", "G1")
    ),
    # "Sn is a ... flow rate multiplier" (M221 Set Flow Rate): above 2 it is a percentage
    Habit("M221 S above 2 (a flow percentage; Hyrel's S is a multiplier)", "HY033", "M221", GCODE, _over("S", 2)),
    # "In native mode ... the value of Extrusion rate E will be ignored, but E will trigger a working or
    # printing move" (G1 Working Move): sliced amounts and retracts with no M229 E1
    Habit("E amounts with no M229 E1 (native flow ignores them)", "HY060", fact="e_amounts"),
    Habit(
        "a G1 with a zero or negative E (a retract: in native flow an E-only G1 does nothing, and on a move it prints)",
        "HY031",
        fact="e_retract",
    ),
    # "G0 Rapid Move": a rapid never prints (Marlin's G0 is G1 and extrudes)
    Habit("E on a G0 rapid move", "HY030", fact="e_on_g0"),
)
