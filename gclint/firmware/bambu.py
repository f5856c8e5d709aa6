"""Bambu Lab printers (X1, P1, A1, H2D, H2C), as their own slicer profiles use them.

Bambu publishes no G-code reference: this inventory lists the codes found in Bambu's
machine profiles (bambulab/BambuStudio resources/profiles/BBL/machine, several commits) and those
BambuStudio itself writes ("slicer" in the section).  Sub-codes are separate codes; G28.14/G28.140 and
G29.2/G29.20 are distinct on the printer, but gclint's parser reads a sub-code as a decimal (G28.140 is
G28.14), which is harmless here: both are in the inventory.  Bambu's M970-M977 and M1002 are unrelated to
Prusa Buddy's and Marlin's codes of the same numbers.
"""

from __future__ import annotations

from gclint.dialects.base import Detection
from gclint.firmware.base import Firmware, code_set

_G = (
    "G0 G1 G90 G91 G92 G17 G21 G2 G3 G28 G28.14 G28.140 G29 G29.1 G29.2 G29.4 G29.7 G29.9 G29.20 G29.99 G38"
    " G380 G39 G39.1 G39.3 G39.4 G130 G150 G150.1 G150.2 G150.3 G151 G383 G383.3 G383.4 G383.7 G392 G2814"
    " G3811"
)
_M = (
    "M17 M18 M73 M73.2 M83 M104 M109 M106 M140 M190 M141 M191 M142 M145 M145.2 M201.2 M204 M211 M220 M221"
    " M400 M412 M481 M500 M620 M620.1 M620.3 M620.6 M620.10 M620.11 M620.13 M620.14 M620.15 M620.17 M621"
    " M622 M622.1 M623 M624 M625 M628 M629 M630 M640 M640.1 M640.2 M640.4 M640.7 M640.8 M641 M900 M901"
    " M960 M963 M964 M969 M970 M970.2 M970.3 M971 M972 M973 M974 M975 M976 M977 M980.3 M981 M982.2 M983"
    " M983.1 M983.3 M983.4 M984 M991 M993 M1002 M1003 M1006 M1007 M1009 M1012.5 M1012.7 M1015.3 M1015.4"
    " M1026 M9711 M9712 M9713 M9833 M9833.2"
)
# T<n> (and T1000, T1100, T255, T65279, T65535) are tool commands of their own; SYNC T{...} (H2D flush
# timing) is a bare word.
_WORDS = frozenset({"SYNC"})

BAMBU = Firmware(
    name="bambu",
    title="Bambu Lab firmware",
    codes=code_set(_G, _M),
    words=_WORDS,
    dialect="marlin",
    flavor=True,
    # P on G2/G3 counts the turns (P1: one circle), not Marlin's extra circles: BambuStudio's spiral lift writes
    # "G2/G3 Z.. I.. J.. P1" with a radius for one turn at the travel slope (src/libslic3r/GCodeWriter.cpp,
    # GCodeWriter::travel_to_xyz and _spiral_travel_to_z: "radius = delta(2) / (2 * PI * atan(slope))").  Bambu's
    # firmware is not public: this is its vendor's slicer's reading, the best source there is.
    semantics={"arc_turns": "turns"},
    detection=Detection(
        patterns=(
            # BambuStudio's settings block (in the head): the printer, not the slicer, decides (BambuStudio
            # also slices for other printers: "; printer_model = Creality K1 Max")
            (r"(?i)^;\s*printer_model\s*=\s*Bambu Lab\b[^\n]*", 8),
            (r"^;\s*BambuStudio\b[^\n]*", 2),
        )
    ),
    source="BambuStudio machine profiles: github.com/bambulab/BambuStudio, resources/profiles/BBL/machine",
)
