"""Prusa Buddy firmware (32-bit: MK4/MK4S, MK3.5/MK3.9, MINI, XL, CORE One, iX).

Inventory: the Prusa Buddy firmware source (github.com/prusa3d/Prusa-Firmware-Buddy @ 818d812f): Prusa's own
dispatch table and the Marlin fork's.  The Marlin codes listed separately as gated behind
options no stock configuration sets (G10, M3-M5, M125, M413 ...) are left out: stock Buddy builds answer
"unknown" to them.  In Buddy, M862-M865 and M970-M977 have Prusa's meanings (the custom table runs first).
"""

from __future__ import annotations

from gclint.dialects.base import Detection
from gclint.firmware.base import Firmware, code_set

_G = (
    "G0 G1 G2 G3 G4 G12 G21 G26 G27 G28 G29 G30 G42 G53 G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3 G64 G80"
    " G90 G91 G92 G123 G162 G163 G425"
)
_M = (
    "M0 M1 M17 M18 M84 M20 M21 M22 M23 M24 M25 M26 M27 M28 M29 M30 M31 M32 M33 M34 M42 M46 M73 M74 M75 M76"
    " M77 M78 M80 M81 M82 M83 M85 M86 M92 M104 M104.1 M105 M106 M107 M108 M109 M110 M111 M112 M113 M114"
    " M115 M117 M118 M119 M120 M121 M122 M123 M140 M141 M142 M150 M151 M155 M190 M191 M200 M201 M203 M204"
    " M205 M206 M211 M217 M218 M220 M221 M226 M260 M261 M262 M263 M264 M265 M267 M268 M290 M300 M301 M302"
    " M303 M304 M305 M330 M331 M332 M333 M334 M340 M350 M400 M401 M402 M403 M410 M420 M421 M428 M486 M500"
    " M501 M502 M503 M504 M555 M556 M557 M569 M572 M591 M593 M600 M601 M602 M603 M604 M701 M702 M704 M705"
    " M706 M707 M708 M709 M851 M862.1 M862.2 M862.3 M862.4 M862.5 M862.6 M863 M864 M865 M876 M900 M906 M911"
    " M912 M913 M914 M919 M920 M958 M959 M960 M970 M972 M973 M974 M975 M976 M977 M997 M999 M1000 M1200"
    " M1600 M1601 M1700 M1701 M1702 M1703 M1704 M1959 M1977 M1978 M9140 M9150 M9200 M9201"
)
# T0..Tn (tool / MMU slot) and P0 (park tool, XL) are letter commands of their own.
_OTHER = "P0"

# printer_model / M862.3 names of the printers the section's title lists (MK4IS, MK4SMMU3, XL5IS ... start so)
MODELS = r"(?:MK4|MK3\.5|MK3\.9|MINI|XL|CORE ?ONE|IX)"

PRUSA_BUDDY = Firmware(
    name="prusa-buddy",
    title="Prusa Buddy firmware",
    codes=code_set(_G, _M, _OTHER),
    dialect="marlin",
    flavor=True,
    detection=Detection(
        patterns=(
            # PrusaSlicer's settings (the top block from 2.8, the end of every file) and the start G-code's
            # printer check (M862.3 P "MK4S": Prusa-Firmware-Buddy, M862.3)
            (rf"(?i)^;\s*printer_model\s*=\s*{MODELS}[\w.]*\s*$", 8),
            (rf'(?i)^\s*M862\.3\s*P\s*"{MODELS}[\w.]*"', 8),
            # PrusaSlicer's printer profile keywords ("; printer_notes = ...PRINTER_MODEL_MK3..."): the profile
            # the job was sliced with names the printer
            (rf"(?i)^;\s*printer_notes\s*=[^\n]*PRINTER_MODEL_{MODELS}", 8),
        )
    ),
    source="Prusa-Firmware-Buddy: github.com/prusa3d/Prusa-Firmware-Buddy @ 818d812f",
)
