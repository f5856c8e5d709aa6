"""LinuxCNC (RS274NGC): the G and M codes its interpreter documents.

Inventory: the LinuxCNC documentation (https://linuxcnc.org/docs/html/gcode/g-code.html and m-code.html;
source github.com/LinuxCNC/linuxcnc @ 5c41560e, docs/src/gcode/*.adoc).  M100-M199
are user-defined (an external program of that name), and ``REMAP=`` lines in a machine's INI file can
define any unallocated code: those are the machine's own, declared with ``extend-known-codes``.  The
Machinekit dialect (gclint/dialects/machinekit.py) is this language plus the FDM remaps.
"""

from __future__ import annotations

from gclint.firmware.base import Firmware, code_set

G_CODES = (
    "G0 G1 G2 G3 G4 G5 G5.1 G5.2 G5.3 G7 G8 G10 G17 G17.1 G18 G18.1 G19 G19.1 G20 G21 G28 G28.1 G30 G30.1 G33"
    " G33.1 G38.2 G38.3 G38.4 G38.5 G40 G41 G41.1 G42 G42.1 G43 G43.1 G43.2 G49 G52 G53 G54 G55 G56 G57 G58"
    " G59 G59.1 G59.2 G59.3 G61 G61.1 G64 G70 G71 G71.1 G71.2 G72 G72.1 G72.2 G73 G74 G76 G80 G81 G82 G83 G84"
    " G85 G86 G87 G88 G89 G90 G90.1 G91 G91.1 G92 G92.1 G92.2 G92.3 G93 G94 G95 G96 G97 G98 G99"
)
M_CODES = (
    "M0 M1 M2 M3 M4 M5 M6 M7 M8 M9 M19 M30 M48 M49 M50 M51 M52 M53 M60 M61 M62 M63 M64 M65 M66 M67 M68 M70"
    " M71 M72 M73 M98 M99"
)

LINUXCNC = Firmware(
    name="linuxcnc",
    title="LinuxCNC",
    codes=code_set(G_CODES, M_CODES),
    dialect="machinekit",
    source="LinuxCNC documentation: https://linuxcnc.org/docs/html/gcode/ (github.com/LinuxCNC/linuxcnc @ 5c41560e)",
)
