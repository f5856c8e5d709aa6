"""Machinekit FDM: the LinuxCNC interpreter with the remaps of Machinekit's FDM configuration.

The remaps (``remap.ini``: ``REMAP=G28 modalgroup=1 argspec=xyza ngc=g28``, ``M104``...) give some codes another
meaning than LinuxCNC's: G28 rapids the listed axes (all when none) to zero and resets the extruder axis A, since
"Machinekit does not support homing from GCode" (Machinekit-FDM-Standard, GCode.org "G28: Move to Origin" and
``subroutines/g28.ngc``); G30 is a probe.  A job that uses the remaps' own codes (``M104 P200``, ``G22``) is read
with them; a plain LinuxCNC program keeps LinuxCNC's G28 (gclint.dialects.semantics).  Sources: Machinekit-FDM
(github.com/machinekoder/Machinekit-FDM-Standard @ 397d429: GCode.md, remap.ini, subroutines/*.ngc).
"""

from __future__ import annotations

from gclint.dialects.base import Clue, Detection
from gclint.firmware.base import Firmware, code_set


def _remap_temperature(cmd) -> bool:
    # the final remap's "M104 P<temperature> T<index>": a value in P and no S (Marlin and Hyrel write S)
    params = cmd.params
    return "P" in params and "S" not in params


FDM_CODES = "G22 G23 G28 G29 G29.1 G29.2 G30 M104 M106 M107 M109 M140 M141 M190 M191 M200 M207 M221 M226 M280 M300"
FDM_CODES += " M400 M420 M700 M701 M702 M710"

MACHINEKIT_FDM = Firmware(
    name="machinekit-fdm",
    title="Machinekit FDM (LinuxCNC with the FDM remaps)",
    codes=code_set(FDM_CODES),
    dialect="machinekit",
    flavor=True,
    detection=Detection(
        patterns=((r"(?i)^;\s*gcode_flavor\s*=\s*machinekit", 8),),
        clues=(
            *(
                Clue(f"{code} P without S: a Machinekit FDM remap temperature", code, test=_remap_temperature, weight=4)
                for code in ("M104", "M109", "M140", "M190")
            ),
            Clue("G22: a Machinekit FDM retraction", "G22", weight=4),
            Clue("G23: a Machinekit FDM unretraction", "G23", weight=4),
            Clue("M700-M702: Machinekit velocity extrusion", "M700", weight=4),
        ),
    ),
    source="Machinekit-FDM: github.com/machinekoder/Machinekit-FDM-Standard @ 397d429, remap.ini",
    marks_dialect=False,
    semantics={"home": "zero-listed", "g30": None},
)
