"""Prusa MK3 / MK3S / MK2.5S firmware (8-bit, Prusa-Firmware).

Inventory: the Prusa MK3 firmware source (github.com/prusa3d/Prusa-Firmware @ 0c9bf5d4, 3.14.0-BETA1): the
"### ..." blocks of ``process_commands()`` checked against the ``case`` labels.  G82-G85 are inside
``#if 0`` (not compiled) and left out; plain M862 has no action of its own (only M862.x).
"""

from __future__ import annotations

from gclint.dialects.base import Detection
from gclint.firmware.base import Firmware, code_set

_G = "G0 G1 G2 G3 G4 G10 G11 G21 G28 G29 G30 G31 G32 G75 G76 G80 G81 G86 G87 G88 G90 G91 G92 G98 G99"
_M = (
    "M0 M1 M17 M18 M84 M20 M21 M22 M23 M24 M25 M125 M601 M26 M27 M28 M29 M30 M31 M32 M42 M44 M45 M46 M47 M48"
    " M72 M73 M75 M76 M77 M78 M79 M80 M81 M82 M83 M85 M86 M92 M104 M105 M106 M107 M109 M110 M112 M113 M114"
    " M115 M117 M118 M119 M120 M121 M123 M140 M150 M155 M190 M200 M201 M203 M204 M205 M206 M207 M208 M209"
    " M214 M220 M221 M226 M240 M280 M300 M301 M302 M303 M304 M310 M350 M351 M400 M403 M405 M406 M420 M500"
    " M501 M502 M503 M509 M540 M552 M600 M602 M603 M850 M851 M860 M861 M862.1 M862.2 M862.3 M862.4 M862.5"
    " M862.6 M900 M907 M908 M910 M911 M912 M913 M914 M915 M916 M917 M918 M928 M701 M702 M704 M705 M706 M707"
    " M708 M709"
)
# D-codes (debug, DEBUG_DCODES and others); T0-T4 and Tx/Tc/T? are tool commands of their own.
_D = "D-1 D0 D1 D2 D3 D4 D5 D6 D7 D8 D9 D10 D12 D20 D21 D22 D23 D70 D80 D81 D106 D2130 D9125"
# Non-G/M command words (whole word at the start of a line).
_WORDS = frozenset(
    ["PRUSA", "CRASH_DETECTED", "CRASH_RECOVER", "CRASH_CANCEL", "BACKLASH_X", "BACKLASH_Y"]
    + [f"TMC_SET_{what}_{axis}" for what in ("WAVE", "STEP", "CHOP") for axis in "XYZE"]
)

# printer_model / M862.3 names of the printers the section's title lists (MK3S, MK3SMMU2S, MK2.5S ...), and
# the MK2/MK2S (MK2S, MK2SMM), whose firmware is the same Prusa-Firmware at an older release (PrusaSlicer's
# MK2 profile: "M115 U3.2.3 ; tell printer latest fw version", "MK2 firmware only supports the old M204
# format"): the nearest inventory gclint has, not that release's own
MODELS = r"(?:MK3(?![.\d])|MK2\.5|MK2(?![.\d]))"

PRUSA_MK3 = Firmware(
    name="prusa-mk3",
    title="Prusa MK3 firmware",
    codes=code_set(_G, _M, _D),
    words=_WORDS,
    dialect="marlin",
    flavor=True,
    detection=Detection(
        patterns=(
            (rf"(?i)^;\s*printer_model\s*=\s*{MODELS}[\w.]*\s*$", 8),
            (rf'(?i)^\s*M862\.3\s*P\s*"{MODELS}[\w.]*"', 8),
            # PrusaSlicer's printer profile keywords ("; printer_notes = ...PRINTER_MODEL_MK3..."): the profile
            # the job was sliced with names the printer
            (rf"(?i)^;\s*printer_notes\s*=[^\n]*PRINTER_MODEL_{MODELS}", 8),
        )
    ),
    source="Prusa-Firmware: github.com/prusa3d/Prusa-Firmware @ 0c9bf5d4",
)
