"""The RepRap firmwares of the 2015 RepRap wiki G-code page (FiveD, Teacup, Sprinter and their kin), as
Skeinforge-era slicers wrote for them: ``M101``/``M103`` turn the extruder on and off, ``M108`` sets its
speed.  Marlin answers "Unknown command" to those, so a file that uses them was written for one of these
firmwares, and gclint checks it against the page that documents them.

Source: the RepRap wiki G-code page (https://reprap.org/wiki/G-code) as revised on 15 January 2015 by Adrianbowyer
(every code with a heading of its own on the page).
"""

from __future__ import annotations

from gclint.dialects.base import Clue, Detection
from gclint.firmware.base import Firmware, code_set

_G = "G0 G1 G2 G3 G4 G10 G20 G21 G28 G90 G91 G92"
_M = (
    "M0 M1 M3 M4 M5 M7 M8 M9 M10 M11 M17 M18 M20 M21 M22 M23 M24 M25 M26 M27 M28 M29 M30 M31 M32 M36 M40 M41"
    " M42 M43 M80 M81 M82 M83 M84 M92 M98 M99 M101 M102 M103 M104 M105 M106 M107 M108 M109 M110 M111 M112"
    " M113 M114 M115 M116 M117 M118 M119 M120 M121 M122 M123 M124 M126 M127 M128 M129 M130 M131 M132 M133"
    " M134 M135 M136 M140 M141 M142 M143 M144 M160 M190 M200 M201 M202 M203 M204 M205 M207 M208 M209 M210"
    " M211 M220 M221 M226 M227 M228 M229 M230 M240 M241 M245 M246 M251 M280 M300 M301 M302 M303 M304 M305"
    " M306 M320 M321 M322 M340 M360 M361 M362 M363 M364 M365 M370 M371 M372 M373 M374 M375 M400 M420 M500"
    " M501 M502 M503 M540 M550 M551 M552 M553 M554 M555 M556 M557 M558 M559 M560 M561 M562 M563 M564 M565"
    " M566 M567 M568 M569 M570 M571 M572 M573 M574 M665 M666 M906 M909 M998 M999"
)

REPRAP_2015 = Firmware(
    name="reprap-2015",
    title="RepRap firmwares of the 2015 RepRap G-code page (FiveD, Teacup, Sprinter)",
    plural=True,
    codes=code_set(_G, _M),
    dialect="marlin",
    flavor=True,
    detection=Detection(
        patterns=((r"(?i)^[;(].*\bskeinforge\b[^\n]*", 4),),
        clues=(
            # "M101: Turn extruder 1 on (Forward)", "M103: Turn all extruders off", "M108: Set Extruder Speed"
            *(
                Clue(f"{c}: an extruder on/off or speed code of the older RepRap firmwares", c, weight=5)
                for c in ("M101", "M103", "M108")
            ),
        ),
    ),
    source="RepRap wiki G-code page, https://reprap.org/wiki/G-code (revision of 2015-01-15)",
    # the page lists every firmware's codes of its time, Hyrel's numbers among them (M229, M721...): they
    # tell no dialect, only this flavour once the file is read as Marlin-flavour
    marks_dialect=False,
)
