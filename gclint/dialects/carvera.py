"""Makera Carvera (Smoothieware-based community firmware): milling, laser and 4th-axis jobs.

Inventory from ../shared/seeds/carvera-mcodes.md and research/dialects.md section 1.8 [CV].  Carvera runs
in grbl mode: G4 P is seconds; M3 S is RPM; M6 T is an automatic tool change; M7/M9 are air.
"""

from __future__ import annotations

from gclint.dialects.base import Detection, Dialect, codes, span, table

_G = (
    "G0 G1 G2 G3 G4 G10 G17 G18 G19 G20 G21 G28 G28.1 G29 G30 G31 G32 G33 G38.2 G38.3 G38.4 G38.5 G53 G54 G55"
    " G56 G57 G58 G59 G80 G90 G91 G92 G92.1 G92.4 G93 G94"
)
_M = (
    "M0 M1 M2 M3 M5 M6 M7 M9 M17 M18 M20 M21 M23 M24 M25 M26 M27 M30 M32 M82 M83 M84 M92 M97 M98 M98.1 M99"
    " M105 M112 M114 M115 M117 M118 M118.1 M119 M120 M121 M203 M203.1 M204 M205 M206 M220 M221 M223 M306 M321"
    " M322 M323 M324 M325 M331 M332 M333 M334 M335 M336 M370 M374 M375 M400 M460 M461 M462 M463 M464 M465"
    " M466 M467 M468 M469 M470 M471 M472 M473 M474 M475 M476 M477 M478 M479 M480 M481 M482 M483 M484 M485"
    " M486 M487 M488 M489 M490 M490.1 M490.2 M491 M491.1 M492 M493 M493.1 M493.2 M493.3 M494 M495 M495.1 M495.2"
    " M495.3 M496 M496.1 M496.2 M496.3 M496.4 M496.5 M497 M497.1 M497.2 M498 M499 M500 M501 M502 M503 M504 M561"
    " M565 M600 M601 M665 M670 M801 M802 M811 M812 M821 M822 M831 M832 M841 M842 M851 M852 M881 M882 M885 M886"
    " M887 M888 M957 M958 M1000"
)


def _open(code: str) -> bool:
    return code[0] == "T" or "#" in code


CARVERA = Dialect(
    name="carvera",
    title="Makera Carvera (Smoothieware community firmware)",
    family="smoothie",
    codes=table(codes(_G), codes(_M)),
    aliases=("smoothieware", "makera"),
    detection=Detection(
        patterns=(
            (r"(?i)carvera|makera", 10),
            (r"^\s*M49[0-9](?:\.\d)?\b", 6),
            (r"^\s*M32[1-5]\b", 5),
            (r"^\s*M46[0-9]\b", 5),
            (r"(?i)^\s*echo\s", 2),
            (r"^\s*M118\.1\b", 3),
        ),
        extensions=(".nc", ".cnc", ".tap"),
        extension_weight=3,
    ),
    owords=True,
    open_codes=_open,
    unknown_severity="warning",
    description="Carvera desktop CNC: milling with ATC, laser, 4th axis.",
    sources=("seeds/carvera-mcodes.md", "research/dialects.md section 1.8 [CV]"),
    extras={"max_rpm": 15000},
)

_ = span
