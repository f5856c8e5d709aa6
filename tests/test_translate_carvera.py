"""Carvera -> Hyrel (docs/translation.md, Carvera -> Hyrel), as a table.  Helpers: test_translate_tables."""

from __future__ import annotations

import pytest

from .test_translate_tables import Row, ids, translate, validate

RUNNING = "G21\nG90\nM3 S12000\nM7\nG1 X0 Y0 Z0 F1000\n"

CARVERA = [
    Row("2.3 G0 X Y Z F (one-shot in both)", "G0 X10 Y20 F3000", "G0 X10 Y20 F3000"),
    Row("2.3 G0 A on a printer without A", "G0 X1 A90", "G0 X1", "TR005"),
    Row("2.3 G0 A alone on a printer without A", "G0 A90", "", "TR005"),
    Row("2.3 G0 A on an EHR", "G0 X1 A90", "G0 X1 A90", settings={"printer": "ehr"}),
    Row("2.3 G1/G2/G3 F", "G1 X10 F500\nG2 X20 Y0 I5 J0", "G1 X10 F500\nG2 X20 Y0 I5 J0"),
    Row("2.3 G4 P (seconds)", "G4 P1.5", "G4 S1.5", "TR004"),
    Row("2.3 G10 L2/L20", "G10 L2 P1 X0", "", "TR005", out="workspace origins: use Repetrel fixture offsets"),
    Row("2.3 G17-G19", "G17\nG18\nG19", "G17\nG18\nG19"),
    Row("2.3 G20: G21 and lengths converted", "G20\nG0 X1", "G21\nG0 X25.4", "TR004"),
    Row(
        "2.3 G28 (clearance position)",
        "G28",
        "",
        "TR002",
        out="the Carvera's clearance position has no Hyrel counterpart; Hyrel's G28 would home and clear offsets",
    ),
    Row("2.3 G29 (wait for the queue)", "G29", "", "TR001"),
    Row("2.3 G30-G33, G38.x (probing)", "G30\nG38.2 Z-5 F100", "", "TR005"),
    Row("2.3 G53 line (machine coordinates)", "G53 G0 Z-3", "G53\nG0 Z-3\nG54", "TR003"),
    Row("2.3 G53 after G0 (G90 G0 G53 Z-3): one command a line", "G90 G0 G53 Z-3", "G53\nG90\nG0 Z-3\nG54", "TR003"),
    Row(
        "2.3 G53 alone: the next G0/G1 is in machine coordinates",
        "G53\nG0 Z-3\nG0 X1",
        "G53\nG0 Z-3\nG54\nG0 X1",
        "TR003",
    ),
    Row("2.3 G54-G59", "G54", "G54", "TR004"),
    Row("2.3 G90/G91", "G91\nG90", "G91\nG90"),
    Row("2.3 G92", "G92 X0 Y0", "G92 X0 Y0"),
    Row("2.3 G92.1", "G92.1", "G93", "TR004"),
    Row("2.3 G92.4", "G92.4 Z0", "", "TR005"),
    Row("2.3 G93 (inverse time)", "G93", "", "TR005", out="per-move feed conversion is not implemented"),
    Row("2.3 G94", "G94", "", "TR001"),
    Row("2.3 M1 (optional stop)", "M1", "", "TR001"),
    Row("2.3 M2: spindle and air off, M30", "M2", "M5 T0\nM9\nM30", prelude=RUNNING),
    Row("2.3 M3 S (rpm, Carvera maximum assumed)", "M3 S12000", "M3 T0 S80", "TR003"),
    # the spindle is still on at the end of these rows' files: the footer stops it (TR003)
    Row("2.3 M3 S with spindle-max-rpm", "M3 S12000", "M3 T0 S50", "TR003", settings={"spindle_max_rpm": "24000"}),
    Row(
        "2.3 M3 S above the maximum: clamped", "M3 S30000", "M3 T0 S100", "TR003", settings={"spindle_max_rpm": "24000"}
    ),
    Row("2.3 S word before M3 (S10000 M3)", "S12000 M3", "M3 T0 S50", "TR003", settings={"spindle_max_rpm": "24000"}),
    Row(
        "2.3 spindle on a Hyrel head",
        "M3 S12000",
        "M3 T2 S50",
        "TR003",
        settings={"spindle_max_rpm": "24000", "spindle": "T2"},
        v4="M3 T13 S50",
    ),
    Row("2.3 M5", "M5", "M5 T0"),
    Row("2.3 M6 T (manual change on one spindle)", "M6 T2", "M0 ; gclint: change to tool 2", "TR003"),
    Row("2.3 T M6 (prepared tool)", "T3 M6", "M0 ; gclint: change to tool 3", "TR003"),
    Row(
        "2.3 M6 with a running spindle",
        "M3 S6000\nM6 T2",
        "M3 T0 S25\nM5 T0\nM0 ; gclint: change to tool 2",
        "TR003 TR004",  # (TR004: the tool change stops the spindle)
        settings={"spindle_max_rpm": "24000"},
    ),
    Row("2.3 M6 T with the tool map", "M6 T2", "T1", settings={"tool_map": "2=T1"}),
    Row("2.3 M6 T0 (probe) / T-1 (empty)", "M6 T0\nT-1 M6", "", "TR002"),
    Row("2.3 M7/M9 (air) on Aux1", "M7\nM9", "M7\nM9"),
    Row("2.3 M7/M9 (air) on the 16A's air port", "M7\nM9", "M685 S100\nM685 S0", settings={"air": "M685"}),
    Row("2.3 M17, M18, M84", "M17\nM84", "M17\nM84"),
    # "M30 | End of the program, no action on the Carvera" (Carvera M-code table, M30): the code after it runs
    Row("2.3 M30: no action on the Carvera", "M30\nG1 X5", "G1 X5", "TR001"),
    Row("2.3 M82/M83", "M82\nM83", "", "TR001"),
    Row("2.3 M97 M98 M99 (jumps, subprograms)", "M97 P14\nM98 P1001 L4\nM99", "", "TR005"),
    Row("2.3 O-word", "o100 if [#1 GT 2]", "", "TR005"),
    Row("2.3 variables", "#1 = 2", "", "TR005"),
    Row("2.3 M118 (console)", "M118 hello", "", "TR001"),
    Row("2.3 M105 M114 M115 M119 M27 M957", "M105\nM114\nM115\nM119\nM27", "", "TR001"),
    Row("2.3 M112", "M112", "", "TR005"),
    Row("2.3 M117", "M117 hello", "", "TR001"),
    Row("2.3 M203 (mm/s)", "M203 X100", "", "TR002"),
    Row("2.3 M204 M205", "M204 S100\nM205 X0.05", "", "TR002"),
    Row("2.3 M220 S (feed override)", "M220 S80", "", "TR002", out="F values are not rescaled"),
    Row("2.3 M221 (soft endstops)", "M221 S0", "", "TR001"),
    Row("2.3 M223 (spindle override)", "M223 S80", "", "TR002", out="spindle percentages are not rescaled"),
    Row(
        "2.3 M321 laser mode, M3, S power on moves, M322",
        "M321\nM3\nG0 X1 Y1\nG1 X2 S0.5 F1000\nG1 X3 S0\nG1 X4 S0.5\nM5\nG1 X5\nM322",
        "M620 T0 E1\nG0 X1 Y1\nM621 P50\nG1 X2 F1000 E1\nG1 X3\nG1 X4 E1\nG1 X5\nM620 T0 E0",
        "TR003",
    ),
    Row(
        "2.3 laser on another device",
        "M321\nM322",
        "M620 T21 E1\nM620 T21 E0",
        "TR003",
        settings={"laser": "T21"},
        v4="M620 T41 E1\nM620 T41 E0",
    ),
    Row("2.3 M325 (laser power override)", "M325 S50", "", "TR002"),
    Row("2.3 M331 M332 M335", "M331\nM332\nM335", "", "TR001"),
    Row(
        "2.3 M333/M334 optional stop mode (the M1 after them)",
        "M334\nM1\nM333\nM1",
        "M0 ; gclint: optional stop (M334)",
        "TR001 TR004",
    ),
    Row("2.3 M336 line-by-line mode (pauses after each line)", "M336", "", "TR002"),
    Row("2.3 M400", "M400", "", "TR001"),
    Row("2.3 M460-M499 (probing, ATC, TLO)", "M460 X25 L3\nM491\nM493.2 T5\nM490.1", "", "TR005"),
    Row("2.3 M370-M375 (levelling)", "M370\nM375", "", "TR002"),
    Row("2.3 M600 (pause)", "M600", "M0 ; gclint: pause (Carvera M600)"),
    Row("2.3 M601", "M601", "", "TR001"),
    Row("2.3 M670 (probe defaults; Hyrel's M670 is a light)", "M670 S5", "", "TR002"),
    Row("2.3 M801/M802 (vacuum)", "M801 S80\nM802", "M679 S80\nM679 S0", "TR003"),
    Row("2.3 M811/M812 (spindle fan)", "M811 S100\nM812", "", "TR001"),
    Row("2.3 M821/M822 (light)", "M821\nM822", "M670 S100\nM670 S0", "TR004"),
    Row("2.3 M851/M852 (extended port)", "M851 S100\nM852", "", "TR002", out="map it to an aux port by hand"),
    Row("2.3 M881-M888, M1000", "M881 Swifi\nM885\nM1000 ls", "", "TR001"),
    Row("2.3 M958 (spindle PID)", "M958 P1", "", "TR002"),
    Row("2.3 modal motion (axis words alone)", "G1 X1 F100\nX2 Y2\nG0 Z5\nZ10", "G1 X1 F100\nG1 X2 Y2\nG0 Z5\nG0 Z10"),
    Row("2.3 a lone F word", "F500\nG1 X3", "G1 F500\nG1 X3"),
    Row("2.3 echo (console)", "echo hello", "", "TR001"),
]


@pytest.mark.parametrize("row", CARVERA, ids=ids(CARVERA))
def test_carvera(row: Row) -> None:
    validate("carvera", row)


def test_carvera_header_focuses_the_spindle_head() -> None:
    out, _ = translate("carvera", "G90 G94\nG17\nG21\nT1 M6\nS10000 M3\nG0 X1\nM30\n", spindle_max_rpm="20000")
    assert out.splitlines()[1:] == [
        "G90",
        "G17",
        "G21",
        "M0 ; gclint: change to tool 1",
        "M3 T0 S50",
        "G54",
        "T0",
        "G0 X1",
        "M5 T0",
        "M30",
    ]


def test_carvera_footer_at_end_of_file_without_m30() -> None:
    out, _ = translate("carvera", "M321\nM3\nG1 X1 S0.3 F100\n")
    assert out.splitlines()[-2:] == ["M620 T0 E0", "M30"]
