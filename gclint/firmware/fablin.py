"""FABlin: FABtotum's fork of Marlin 1.0, the firmware of the FABtotum Personal Fabricator (printing, milling and
laser heads on one machine).

Inventory: the FABlin source (github.com/FABtotum/FABlin @ 3d30f20d, master, 1.1.1.3 and two documentation
commits), ``Marlin/Marlin_main.cpp``: the ``case`` labels of ``process_commands()``'s G and M switches as the
shipped configuration compiles them (``Marlin/Configuration.h``, ``Configuration_heads.h`` and ``pins.h`` with
``MOTHERBOARD 25``, run through the C preprocessor).  That configuration sets ``ENABLE_LASER_MODE``,
``EXTERNAL_ENDSTOP_Z_PROBING``, ``ENABLE_AUTO_BED_LEVELING``, ``THERMISTOR_HOTSWAP``,
``SELECTABLE_AUTO_FAN_ON_TEMP_CHANGE``, ``AUTO_REPORT_TEMPERATURES``, ``NUM_SERVOS 2``, and leaves unset
``SDSUPPORT`` (M20-M30, M32, M928), ``ULTIPANEL`` (M0, M1), ``FWRETRACT`` (G10, G11, M207-M209), ``PS_ON_PIN``
(M80), ``FILAMENTCHANGEENABLE`` (M600), ``PIDTEMPBED`` (M304), ``DOGLCD`` (M250), ``DEBUG`` (M41, M995-M997) and
``THERMISTOR_INPUT_HOTSWAP`` (M803): those cases are not compiled and are left out.  M110 has no case: the line
reader (``get_command()``) takes the line number of a line that holds "M110".  ``T<n>`` changes the tool
(``tools.change``).  The switches have no ``default``: a G or M code without a case is skipped silently.

What the codes the FABtotum jobs use do (the same file):

* ``G4``: ``P`` milliseconds, then ``S`` seconds (``codenum = code_value() * 1000``: S wins when both are
  written); with neither, no wait (the jobs' bare ``G4`` only waits for the moves to finish,
  ``st_synchronize()``), as Marlin's dialect reads it.
* ``M728`` ("RASPI ALIVE"): white ambient light and the start tune on the beeper (unless ``M735 S1``, silent):
  the FABtotum Cura profile writes it at the start and end of a print ("FAB bep bep").
* ``M793 S<id>``: set (and report) the installed head's soft ID (``Configuration_heads.h``: 1 hybrid, 2 print
  v2, 3 mill v2, 4 laser, 5 4th/5th axis, 6 direct drive, 7 laser pro, 8 digitizer; 100 and above third party).
* ``M60 S<0-255>``: laser power at once; ``M61 S<0-255>``: finish the moves, then laser power (255 without S);
  ``M62``: laser off (after the moves when the last power was an M61); only in laser working mode
  (``M450 S``, ``M452``; ``M451`` printing, ``M453`` milling), else an error and no power.  ``M3``/``M4
  S<RPM>``, ``M5``: the milling motor.
* ``M700 S<0-255>`` the laser's soft PWM, ``M701-M706`` ambient and head lights, ``M718-M727`` head and accessory power, ``M729-M735`` shutdown, error
  and door settings, ``M740-M754`` sensor readings, ``M760-M767`` board and firmware identity, ``M778-M794``
  head identity and smart-head commands, ``M800-M805`` thermistor and sensor settings, ``M852`` the laser's
  inactivity timer, ``M2208`` a TMC2208 driver's settings (experimental).
"""

from __future__ import annotations

from gclint.dialects.base import Detection
from gclint.firmware.base import Firmware, code_set

_G = "G0 G1 G2 G3 G4 G27 G28 G29 G30 G38 G90 G91 G92"
_M = (
    "M3 M4 M5 M17 M18 M31 M42 M43 M60 M61 M62 M81 M82 M83 M84 M85 M92 M104 M105 M106 M107 M109 M110 M114 M115"
    " M117 M119 M120 M121 M140 M150 M155 M190 M200 M201 M203 M204 M205 M206 M218 M220 M221 M226 M240 M280 M300"
    " M301 M302 M303 M350 M351 M400 M401 M402 M403 M450 M451 M452 M453 M500 M501 M502 M503 M563 M564 M575"
    " M700 M701 M702 M703 M704 M705 M706 M710 M711 M712 M714 M718 M719 M720 M721 M722 M723 M724 M725 M726 M727"
    " M728 M729 M730 M731 M732 M733 M734 M735 M740 M741 M742 M743 M744 M745 M746 M747 M750 M751 M752 M753 M754"
    " M756 M760 M761 M762 M763 M764 M765 M766 M767 M778 M779 M782 M784 M785 M786 M790 M792 M793 M794 M800 M801"
    " M802 M804 M805 M852 M907 M908 M998 M999 M2208"
)

FABLIN = Firmware(
    name="fablin",
    title="FABtotum FABlin firmware",
    codes=code_set(_G, _M),
    dialect="marlin",
    flavor=True,
    detection=Detection(
        patterns=(
            # the start and end G-code of FABtotum's Cura profile: "M728 ;FAB bep bep (start the print, ...)",
            # "M728 ; FAB Beep" (M728: the start tune, above)
            (r"(?i)^\s*M728\b[^\n]*;\s*FAB\s+(?:bep\s+bep|beep)\b[^\n]*", 8),
            # FABtotum's own laser engraving tool: ";FABtotum laser engraving, coded on ..."
            (r"(?i)^\s*;\s*FABtotum\b[^\n]*", 8),
        )
    ),
    source="FABlin source: github.com/FABtotum/FABlin @ 3d30f20d, Marlin/Marlin_main.cpp process_commands()",
)
