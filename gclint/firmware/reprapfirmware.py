"""RepRapFirmware 3.5 (Duet): the G/M codes it has built in, and its meta commands.

Inventory: the RepRapFirmware source (github.com/Duet3D/RepRapFirmware @ fc1cd16c, 3.5-dev:
``GCodes2.cpp`` and ``StringParser.cpp``).  Codes the firmware recognises only to answer that they are
gone (M305, M750-M756, the internal M998 and Q0) are left out.  Any other G/M number runs the macro file
of that name (``M1234.g``) if the machine has one, so the RepRapFirmware dialect accepts every number.
"""

from __future__ import annotations

from gclint.firmware.base import Firmware, code_set

_G = (
    "G0 G1 G2 G3 G4 G10 G11 G17 G18 G19 G20 G21 G28 G29 G30 G31 G32 G38.2 G38.3 G38.4 G38.5 G53 G54 G55 G56"
    " G57 G58 G59 G59.1 G59.2 G59.3 G60 G68 G69 G90 G91 G92 G93 G94"
)
_M = (
    "M0 M1 M2 M3 M4 M5 M17 M18 M84 M20 M21 M22 M23 M24 M25 M26 M27 M28 M29 M30 M32 M36 M36.1 M37 M38 M39 M42"
    " M73 M80 M81 M82 M83 M85 M92 M98 M99 M101 M102 M103 M104 M109 M105 M106 M107 M108 M110 M111 M112 M114"
    " M115 M116 M117 M118 M119 M120 M121 M122 M140 M190 M141 M191 M143 M144 M150 M200 M201 M201.1 M203 M204"
    " M205 M566 M206 M207 M208 M220 M221 M226 M260 M261 M280 M290 M291 M292 M300 M301 M304 M302 M303 M307"
    " M308 M309 M350 M374 M375 M376 M400 M401 M402 M404 M407 M408 M409 M425 M450 M451 M452 M453 M470 M471"
    " M472 M486 M500 M501 M502 M503 M505 M540 M550 M551 M552 M553 M554 M555 M556 M557 M558 M558.1 M558.2"
    " M559 M560 M561 M562 M563 M564 M567 M568 M569 M569.1 M569.2 M569.3 M569.4 M569.5 M569.6 M569.8 M570"
    " M571 M572 M574 M575 M576 M577 M579 M581 M582 M584 M585 M586 M586.4 M587 M587.1 M587.2 M588 M589 M591"
    " M592 M593 M594 M595 M596 M597 M598 M599 M600 M601 M606 M665 M666 M667 M669 M670 M671 M672 M673 M674"
    " M675 M701 M702 M703 M851 M905 M906 M911 M912 M913 M915 M916 M917 M918 M929 M950 M951 M952 M953 M954"
    " M955 M956 M957 M997 M999"
)
# Meta commands (bare lower-case words in files and macros, StringParser.cpp).
META_COMMANDS = frozenset(
    ["if", "elif", "else", "while", "break", "continue", "abort", "var", "global", "set", "echo", "skip"]
)

REPRAPFIRMWARE = Firmware(
    name="reprapfirmware",
    title="RepRapFirmware 3.5",
    codes=code_set(_G, _M),
    dialect="reprap",
    words=frozenset(w.upper() for w in META_COMMANDS),
    source="RepRapFirmware: github.com/Duet3D/RepRapFirmware @ fc1cd16c",
)
