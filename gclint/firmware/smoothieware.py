"""Smoothieware (edge): the G/M codes its modules handle and the console commands it accepts in a file.

Inventory: the Smoothieware source (github.com/Smoothieware/Smoothieware @ bb41e992).  Codes a machine's configuration
assigns (switch and temperature-switch modules: any G or M number) are the machine's own, declared with
``extend-known-codes``.  Carvera's community firmware is built on Smoothieware (Carvera community docs: M115 reports
X-GRBL_MODE:1; Smoothieware Robot.cpp, G4): the Carvera dialect takes its console commands (``echo``) from here.
"""

from __future__ import annotations

from gclint.firmware.base import Firmware, code_set

_G = (
    "G0 G1 G2 G3 G4 G10 G11 G17 G18 G19 G20 G21 G28 G28.1 G28.2 G28.3 G28.4 G28.5 G28.6 G29 G30 G31 G32 G38.2"
    " G38.3 G38.4 G38.5 G43.1 G43.2 G49 G53 G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3 G80 G81 G82 G83 G90 G91"
    " G92 G92.1 G92.2 G92.3 G92.4 G98 G99"
)
_M = (
    "M2 M3 M5 M17 M18 M84 M20 M21 M23 M24 M25 M26 M27 M28 M29 M30 M32 M48 M82 M83 M92 M104 M109 M105 M140"
    " M190 M110 M112 M114 M114.1 M114.2 M114.3 M114.4 M114.5 M115 M117 M119 M120 M121 M143 M200 M203 M203.1"
    " M204 M205 M206 M207 M208 M211 M220 M221 M301 M303 M304 M305 M306 M360 M361 M362 M363 M364 M366 M370"
    " M374 M374.1 M375 M375.1 M400 M404 M405 M406 M407 M500 M501 M502 M503 M504 M557 M561 M565 M600 M600.1"
    " M601 M665 M666 M670 M906 M907 M909 M909.1 M911 M911.1 M911.2 M911.3 M957 M958 M999 M1000"
)
# Console commands (SimpleShell.cpp's command table and modules): a lower-case first word.
_CONSOLE = """
    ls cd pwd cat echo rm mv mkdir upload reset dfu break help version mem get set_temp switch net load save
    remount calc_thermistor thermistors md5sum test config-get config-set config-load play progress abort
    suspend resume fire
"""
CONSOLE_COMMANDS = frozenset(_CONSOLE.split())

SMOOTHIEWARE = Firmware(
    name="smoothieware",
    title="Smoothieware",
    codes=code_set(_G, _M),
    dialect="carvera",
    words=frozenset(w.upper() for w in CONSOLE_COMMANDS),
    source="Smoothieware: github.com/Smoothieware/Smoothieware @ bb41e992",
)
