"""Translation tests as tables, in the manner of sqlglot's ``validate_all``: one row per construct.

A row: the translation-table row (docs/translation.md: a pair's table or an X rule) it covers, the source line(s), the expected Hyrel line(s)
("" when the command is dropped), the TR codes the translation reports for it, and optionally the
hyrel-v4 output and translation settings.  Rows marked ``out=`` are consciously left out of the
translation: the row documents why and checks the finding that reports it.

Each row is translated after a short prelude (units, positioning, E mode, focus, fan range, a first
extrusion) so that the header work the translator does once per file does not show in every row; the
header and footer have rows of their own (``prelude=""``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from gclint import dialects
from gclint.syntax.source import Source
from gclint.translate import TranslationResult, translate_source, translator_for
from gclint.translate.options import TranslateOptions

PRELUDES = {
    "marlin": "G21\nG90\nM83\nT0\nM106 S0\nG1 X0 Y0 Z0.2 F1200 E1\n",
    "reprap": "G21\nG90\nM83\nT0\nM106 S0\nG1 X0 Y0 Z0.2 F1200 E1\n",
    "machinekit": "G21\nG90\nT0 M6\nM106 P0 S0\nG1 X0 Y0 Z0.2 F1200 A1\n",
    "carvera": "G21\nG90\nG1 X0 Y0 Z0 F1000\n",
}
START, END = "; >>>", "; <<<"


def translate(source: str, text: str, target: str = "hyrel", **settings: str) -> tuple[str, TranslationResult]:
    """Translate ``text`` (the whole file) and return the output and the result with its findings.  The setting
    ``flavor`` names the firmware the job is read as written for (``gclint.dialects.reading``)."""
    options = TranslateOptions()
    flavor = settings.pop("flavor", None)
    for key, value in settings.items():
        options.set(key.replace("_", "-"), value)
    translator = translator_for(dialects.reading(source, flavor), dialects.get(target), options)
    result = TranslationResult("t.gcode", source, target)
    out = "".join(translate_source(Source.from_text(text, "t.gcode"), translator, result))
    return out, result


def translate_rows(
    source: str, rows: str, target: str = "hyrel", prelude: str | None = None, **settings: str
) -> tuple[list[str], list[str]]:
    """The output lines the translator writes for ``rows`` (between markers) and the TR codes reported
    on them."""
    prelude = PRELUDES[source] if prelude is None else prelude
    text = f"{prelude}{START}\n{rows}\n{END}\n"
    out, result = translate(source, text, target, **settings)
    lines = out.splitlines()
    got = lines[lines.index(START) + 1 : lines.index(END)]
    first = prelude.count("\n") + 2
    codes = sorted({f.code for f in result.findings if f.line >= first})
    return got, codes


@dataclass(frozen=True)
class Row:
    """One construct: ``src`` (source lines) -> ``hyrel`` (expected lines) and the TR codes ``tr``."""

    row: str  # the translation-table row (or X rule) it covers
    src: str
    hyrel: str
    tr: str = ""
    v4: str | None = None  # expected hyrel-v4 output, when the row checks it
    settings: dict = field(default_factory=dict)
    out: str = ""  # consciously left out of the translation: why
    prelude: str | None = None


def validate(source: str, row: Row) -> None:
    got, codes = translate_rows(source, row.src, prelude=row.prelude, **row.settings)
    expected = row.hyrel.split("\n") if row.hyrel else []
    assert got == expected, f"{row.row}: {row.src!r}"
    assert codes == sorted(set(row.tr.split())), f"{row.row}: findings {codes}"
    if row.v4 is not None:
        got4, _ = translate_rows(source, row.src, target="hyrel-v4", prelude=row.prelude, **row.settings)
        assert got4 == (row.v4.split("\n") if row.v4 else []), f"{row.row} (hyrel-v4)"
    if row.out:
        assert row.tr, f"{row.row}: a row left out must name the finding that reports it"


def ids(rows: list[Row]) -> list[str]:
    return [f"{i:03d}-{r.row[:40]}" for i, r in enumerate(rows)]


# -- 2.0 cross-dialect rules and 2.1 Marlin / RepRapFirmware -> Hyrel ------------------------------------------

MARLIN = [
    # Marlin reads one command a line (parser.cpp): the rest never runs there, and is dropped, said
    Row("Marlin: the second command of a line never runs", "G91 G1 X10", "G91", "TR002"),
    # X1 allow-list output; X2 explicit addressing
    Row("X1 unknown code never passed through", "M3.9 S1", "", "TR002"),
    Row("X1 number collision (M204 = no-ramp speed on Hyrel)", "M204 P1500", "", "TR002"),
    Row("X2 explicit address", "M104 S200", "M104 T0 S200", v4="M104 T11 S200"),
    # X4/X5 header: before the first move and the first extrusion
    Row("X5 header: G21, G90, T before the first move", "G1 X1 Y1 F600", "G21\nG90\nT0\nG1 X1 Y1 F600", prelude=""),
    Row("X5 header: units and positioning already set", "G21\nG91\nG1 X1", "G21\nG91\nT0\nG1 X1", prelude=""),
    Row(
        "X4 evalues: M229 E1 D1 and the E mode before the first extrusion",
        "G1 X1 Y1 E0.5 F600",
        "G21\nG90\nT0\nM229 E1 D1\nM82\nG1 X1 Y1 E0.5 F600",
        prelude="",
    ),
    Row("X4 evalues: M229 before M82/M83", "M83", "M229 E1 D1\nM83", prelude=""),
    Row(
        "X4 native: E reduced to E1 (Hyrel computes the flow: TR003)",
        "G1 X1 Y1 E0.5 F600",
        "G21\nG90\nT0\nG1 X1 Y1 E1 F600",
        "TR003",
        prelude="",
        settings={"flow": "native"},
    ),
    Row("X5 fan range before the first M106", "M106 S128", "M106 C255\nM106 T0 S128", prelude=""),
    Row(
        "X5 T before the first move follows the tool map",
        "G0 X1",
        "G21\nG90\nT2\nG0 X1",
        prelude="",
        settings={"tool_map": "0=T2"},
        v4="G21\nG90\nT2\nG0 X1",
    ),
    # G0
    Row("2.1 G0 X Y Z [F] (no dE)", "G0 X10 Y20 F3000", "G0 X10 Y20 F3000"),
    Row("2.1 G0 F modal in Marlin: the next G1 gets it", "G0 X10 F9000\nG1 X20 E1", "G0 X10 F9000\nG1 X20 E1 F9000"),
    Row("2.1 G0 ... E>0 (Marlin G0 = G1)", "G0 X10 E0.4", "G1 X10 E0.4"),
    # G1 and E (X7)
    Row("2.1 G1 X Y E(dE>0) evalues: unchanged", "G1 X10 Y10 E0.5", "G1 X10 Y10 E0.5"),
    Row("2.1 G1 X Y E(dE>0) native: E1", "G1 X10 Y10 E0.5", "G1 X10 Y10 E1", settings={"flow": "native"}),
    Row("2.1 G1 X Y E(dE<=0) relative E: E stripped", "G1 X10 Y10 E-0.5", "G1 X10 Y10"),
    Row(
        "2.1 G1 X Y E(dE<=0) absolute E: E stripped, G92 keeps Hyrel's E",
        "M82\nG1 X10 Y10 E0.5",
        "M82\nG1 X10 Y10\nG92 E0.5",
    ),
    Row("2.1 G1 E only (retract) relative: dropped", "G1 E-0.8 F2100", "", "TR004"),
    Row("2.1 G1 E only (retract) absolute: G92 E", "M82\nG1 E0.2 F2100", "M82\nG92 E0.2", "TR004"),
    Row(
        "2.1 G1 E only (retract), retract=explicit",
        "G1 E-0.8 F2100\nG1 E0.8",
        "M721 T0 I1\nM722 T0 I1",
        settings={"retract": "explicit"},
    ),
    Row("2.1 G1 E only: its F is carried to the next G1", "G1 E-0.8 F2100\nG1 X5", "G1 X5 F2100", "TR004"),
    Row(
        "2.1 G1 ... S (Marlin laser power): M621 P before the move, E1",
        "M3 S0\nG1 X10 S200",
        "M3 T0 S0\nM620 T0 E1\nM621 P78.4\nG1 X10 E1",
        "TR003",
    ),
    Row("2.1 G1 ... S with no M3/M4: the laser enabled, not fired", "G1 X10 S200", "M620 T0 E1\nG1 X10", "TR003"),
    Row("2.1 G1 without F after a feed-only line", "G1 F4437\nG1 X5 E0.1", "G1 F4437\nG1 X5 E0.1"),
    # G2/G3 (X9)
    Row("2.1 G2 X Y I J E native: E1", "G2 X10 Y0 I5 J0 E1", "G2 X10 Y0 I5 J0 E1", settings={"flow": "native"}),
    # 2.1 G2 X Y I J E in evalues mode: G1 segments carrying E, see test_arc_evalues_segments
    Row("2.1 G2 travel arc (no E)", "G2 X10 Y0 I5 J0", "G2 X10 Y0 I5 J0"),
    Row(
        "2.1 G2/G3 R: centre I/J",
        "G1 X0 Y0\nG2 X10 Y0 R5",
        "G1 X0 Y0\nG2 X10 Y0 I5 J0",
        "TR004",
        settings={"flow": "native"},
    ),
    Row("2.1 G2/G3 R too small for the chord", "G1 X0 Y0\nG2 X10 Y0 R2", "G1 X0 Y0", "TR005"),
    # 2.1 G2/G3 P (extra turns): G1 segments, see test_arc_turns
    Row(
        "2.1 G2/G3 S (laser power)",
        "M3 S0\nG2 X10 Y0 I5 J0 S100",
        "M3 T0 S0\nM620 T0 E1\nM621 P39.2\nG2 X10 Y0 I5 J0 E1",
        "TR003",
    ),
    Row("2.1 G2/G3 K dropped in the XY plane", "G2 X10 Y0 I5 J0 K1", "G2 X10 Y0 I5 J0"),
    # 2.1 G2/G3 in G18/G19: G1 segments, see test_arc_other_plane
    # G4
    Row("2.1 G4 S P (Marlin: S wins)", "G4 S1 P500", "G4 S1", "TR004"),
    Row("2.1 G4 P (ms, same as Hyrel)", "G4 P500", "G4 P500"),
    # G10/G11
    Row("2.1 G10 firmware retract", "G10", "", "TR004"),
    Row("2.1 G10 S1 (swap retract)", "G10 S1", "", "TR004"),
    Row("2.1 G11 firmware recover", "G11", "", "TR004"),
    Row("2.1 G10/G11 retract=explicit", "G10\nG11", "M721 T0 I1\nM722 T0 I1", settings={"retract": "explicit"}),
    # G17-G21
    Row("2.1 G17", "G17", "G17"),
    Row("2.1 G20 inches: G21 and lengths converted", "G20\nG1 X1 Y2 F10", "G21\nG1 X25.4 Y50.8 F254", "TR004"),
    Row("2.1 G21", "G21", "G21"),
    # G28
    Row("2.1 G28 (no args): X and Y, then the head focused again", "G28", "G28 X0 Y0\nT0", "TR003"),
    Row(
        "2.1 G28 (no args) on an EHR: Z too (M660 needs G28 Z0)", "G28", "G28 X0 Y0 Z0\nT0", settings={"printer": "ehr"}
    ),
    Row("2.1 G28 (no args), home-z", "G28", "G28 X0 Y0 Z0\nT0", settings={"home_z": "true"}),
    Row("2.1 G28 X Y (flags)", "G28 X Y", "G28 X0 Y0\nT0"),
    Row("2.1 G28 X0 Y0 unchanged", "G28 X0 Y0", "G28 X0 Y0\nT0"),
    Row("X5 header before a first G28: the T after it", "G28", "G21\nG90\nG28 X0 Y0\nT0", "TR003", prelude=""),
    Row("2.1 G28 W (Prusa: no mesh) option dropped", "G28 W", "G28 X0 Y0\nT0", "TR003 TR004"),
    Row("2.1 G29 (levelling)", "G29", "", "TR002"),
    Row("2.1 G30 (probe)", "G30", "", "TR002"),
    Row("2.1 M420 (levelling on/off)", "M420 S1", "", "TR002"),
    # G53-G59, G90-G93
    # no workspace selected: none to invoke again after it (Hyrel's G54 would apply stored offsets)
    Row("2.1 G53 G1 prefix", "G53 G1 X10", "G53\nG1 X10", "TR003"),
    Row("2.1 G53 G1 prefix in a workspace", "G55\nG53 G1 X10", "G55\nG53\nG1 X10\nG55", "TR003 TR004"),
    Row("2.1 G54 select", "G55", "G55", "TR004"),
    Row("2.1 G59.1", "G59.1", "", "TR005", out="Hyrel has no G59.1-G59.3"),
    Row("2.1 G90 on Marlin also sets absolute E: M82", "G90", "G90\nM82"),
    Row("2.1 G90 with E already absolute", "M82\nG90", "M82\nG90"),
    Row("2.1 G91 on Marlin also sets relative E: M83", "M82\nG91", "M82\nG91\nM83"),
    Row("2.1 G92 X Y Z E", "G92 E0", "G92 E0"),
    Row("2.1 bare G92", "G92", "", "TR004"),
    Row("2.1 G92.1", "G92.1", "G93", "TR004"),
    # M0-M9
    Row("2.1 M0 (Marlin)", "M0", "M0"),
    Row("2.1 M0 S (timeout): Hyrel waits for Resume", "M0 S30", "M0", "TR003"),
    Row("2.1 M1 (Marlin: M0 alias)", "M1", "M0"),
    Row("2.1 M3 S (PWM 0-255)", "M3 S255", "M3 T0 S100", "TR003"),
    Row(
        "2.1 M3 then M4: stopped first, then a pause until it stands still",
        "M3 S255\nM4 S255",
        "M3 T0 S100\nM5 T0\nM0 ; gclint: spindle stopped; resume when it stands still\nM4 T0 S100",
        "TR003",
    ),
    Row(
        "2.1 M3 then M4 with spindle-stop-dwell",
        "M3 S255\nM4 S255",
        "M3 T0 S100\nM5 T0\nG4 S5\nM4 T0 S100",
        "TR003",
        settings={"spindle_stop_dwell": "5"},
    ),
    Row("2.1 M5", "M3 S128\nM5", "M3 T0 S50.2\nM5 T0", "TR003"),
    Row("2.1 M5 with spindle=T20", "M5", "M5 T20", settings={"spindle": "T20"}, v4="M5 T26"),
    Row(
        "2.1 M3 laser (SPINDLE_LASER)",
        "M3 S255",
        "M3 T0 S100",
        "TR003",
        out="Marlin laser mode is not detected from the file: M3/M4 is written as a spindle",
    ),
    Row("2.1 M7/M8/M9", "M7\nM8\nM9", "M7\nM8\nM9"),
    # M17/M18/M84
    Row("2.1 M17 axes", "M17 X", "M17", "TR004"),
    Row("2.1 M84 (no args)", "M84", "M84"),
    Row("2.1 M84 X Y E: all motors", "M84 X Y E", "M84", "TR003"),
    Row("2.1 M84 E only", "M84 E", "", "TR002"),
    Row("2.1 M84 S (timeout)", "M84 S600", "", "TR002"),
    Row("2.1 a move after M84: re-home", "M84\nG1 X5", "M84\nG28 X0 Y0 Z0\nT0\nG1 X5", "TR003"),
    Row("2.1 G28 X Y after M84 homes Z too", "M84\nG28 X Y\nG1 X5", "M84\nG28 X0 Y0 Z0\nT0\nG1 X5", "TR003"),
    Row("2.1 M30 (delete file): the deletion is not made", "M30 old.gco", "", "TR002"),
    Row("2.1 M30 naming no file deletes nothing", "M30", "", "TR001"),
    Row("2.1 OctoPrint @pause: Hyrel's pause", "@pause", "M0 ; gclint: pause (@pause)", "TR003"),
    Row("2.1 OctoPrint @cancel: dropped, the rest ran under OctoPrint only", "@cancel", "", "TR002"),
    Row("2.1 an OctoPrint plugin's @ command", "@BEDLEVELVISUALIZER", "", "TR001"),
    # M82/M83
    Row("2.1 M82 evalues", "M82", "M82"),
    Row("2.1 M83 native: dropped", "M83", "", "TR004", settings={"flow": "native"}, prelude="G21\n"),
    # temperatures
    Row("2.1 M104 S", "M104 S215", "M104 T0 S215", v4="M104 T11 S215"),
    Row("2.1 M104 T1 S", "M104 T1 S215", "M104 T1 S215", v4="M104 T12 S215"),
    Row("2.1 M104 T1 with --tool-map 1=T3", "M104 T1 S215", "M104 T3 S215", settings={"tool_map": "1=T3"}),
    Row("2.1 M104 I (preset)", "M104 I1", "", "TR005"),
    Row("2.1 M104 F B (autotemp)", "M104 S215 B240 F1", "M104 T0 S215", "TR004"),
    Row("2.1 M104 tool not on the printer", "M104 T7 S215", "", "TR007"),
    Row("2.1 M105 M114 M115 M119 M503 M27 M31 M155", "M105\nM114\nM115\nM119\nM503\nM27\nM31\nM155 S1", "", "TR001"),
    Row("2.1 M106 S (0-255 with C255)", "M106 S128", "M106 T0 S128"),
    Row("2.1 M106 (no S: full)", "M106", "M106 T0 S255"),
    Row("2.1 M106 P0 (part fan of the focused head)", "T1\nM106 P0 S255", "T1\nM106 T1 S255"),
    Row("2.1 M106 P2 unmapped", "M106 P2 S255", "", "TR002"),
    # (v5 Aux1 T22 has no certain v4 address: the v4 map rates aux T16 "medium", so it stays, with TR006)
    Row("2.1 M106 P2 mapped", "M106 P2 S255", "M106 T22 S255", settings={"fan_map": "2=T22"}, v4="M106 T22 S255"),
    Row("2.1 M106 T (secondary speed)", "M106 S255 T128", "M106 T0 S255", "TR004"),
    Row("2.1 M107", "M107", "M107 T0"),
    Row("2.1 M107 P0", "M107 P0", "M107 T0"),
    Row("2.1 M109 S", "M109 S215", "M109 T0 S215"),
    Row("2.1 M109 R (target heating or cooling)", "M109 R180", "M109 T0 S180 R2", "TR004", v4="M109 T11 S180 R2"),
    Row("2.1 M109 R with temp-window 5", "M109 R180", "M109 T0 S180 R5", "TR004", settings={"temp_window": "5"}),
    Row("2.1 M109 B F (autotemp)", "M109 S215 B240 F1", "M109 T0 S215", "TR004"),
    Row("2.1 M112", "M112", "", "TR005"),
    Row("2.1 M117", "M117 Printing...", "", "TR001"),
    Row("2.1 M140 S", "M140 S60", "M140 T24 S60", v4="M140 T91 S60"),
    Row("2.1 M141 S", "M141 S40", "M141 T24 S40"),
    Row("2.1 M190 S", "M190 S60", "M190 T24 S60"),
    Row("2.1 M191 S", "M191 S40", "M191 T24 S40"),
    Row("2.1 M190 R", "M190 R60", "M190 T24 S60 R2", "TR004"),
    Row("2.1 M191 R", "M191 R40", "M191 T24 S40 R2", "TR004"),
    Row("2.1 M190 T (annealing time)", "M190 S60 T600", "M190 T24 S60", "TR003"),
    Row("2.1 M200 D (volumetric)", "M200 D1.75", "", "TR003"),
    Row("2.1 M200 native", "M200 D1.75", "", "TR001", settings={"flow": "native"}),
    Row(
        "2.1 M201 M204 M205 M566 M900 M593",
        "M201 X1000\nM204 P1500\nM205 X8\nM566 X900\nM900 K0.2\nM593 F40",
        "",
        "TR002",
    ),
    Row("2.1 M203 dropped", "M203 X200 Y200", "", "TR002"),
    Row(
        "2.1 M203 max-feed=convert (mm/s -> mm/min)",
        "M203 X200 Y200 Z12 E120",
        "M203 X12000 Y12000 Z720",
        "TR003",
        settings={"max_feed": "convert"},
    ),
    Row(
        "2.1 M207 (+M208), X8 retraction conversion",
        "M207 S4 F2400\nM208 S0.2",
        "",
        "TR002",
        out="needs the head's pulses per mm; Hyrel heads carry their own M721/M722 unprime/prime settings",
    ),
    Row("2.1 M209", "M209 S1", "", "TR002"),
    Row("2.1 M220 S100", "M220 S100", "", "TR001"),
    Row("2.1 M220 S<p>", "M220 S90", "", "TR002", out="F values are not rescaled; the speed factor is dropped"),
    Row("2.1 M221 S<percent> -> multiplier", "M221 S95", "M221 T0 S0.95"),
    Row("2.1 M221 T1 S", "M221 T1 S110", "M221 T1 S1.1", v4="M221 T12 S1.1"),
    Row("2.1 M226 (Marlin: wait for pin)", "M226 P4 S1", "", "TR002"),
    Row("2.1 M280", "M280 P0 S90", "", "TR002"),
    Row("2.1 M300", "M300 S440 P200", "M792 ; BEEP", "TR004"),
    Row("2.1 M400", "M400", "", "TR001"),
    Row("2.1 M500-M503", "M500\nM501\nM502", "", "TR001"),
    Row("2.1 M600", "M600", "M0 ; gclint: filament change", "TR003"),
    Row(
        "2.1 M605 S2 (duplication)",
        "M605 S2",
        "",
        "TR002",
        out="clone squads (M702/M703) need the heads' settings; set them up by hand",
    ),
    Row("2.1 M701/M702 (filament)", "M701\nM702", "", "TR002"),
    Row("2.1 M710", "M710 S255", "", "TR001"),
    Row("2.1 T<n>", "T1", "T1", v4="T1"),
    Row("2.1 T<n> F S (Marlin)", "T1 S1", "T1", "TR004"),
    Row("2.1 T<n> mapped", "T1", "T3", settings={"tool_map": "1=T3"}),
    Row("2.1 T<n> beyond the printer", "T5", "", "TR007"),
    Row("2.1 T? (MMU query)", "T?", "", "TR005"),
    Row("2.1 Klipper host macro", "PRINT_START BED=60", "", "TR005"),
    Row("2.1 Klipper object labels", "EXCLUDE_OBJECT_START NAME=a", "", "TR001"),
    Row("2.1 Bambu M620 (AMS, collides with Hyrel's laser M620)", "M620 S0A", "", "TR005"),
    Row("2.1 comment kept on a changed line", "M104 S200 ; heat", "M104 T0 S200 ; heat"),
    Row("2.1 comment kept on a dropped line", "M204 P1500 ; accel", "; accel", "TR002"),
    Row(
        "X11 long lines",
        "M117 " + "x" * 120,
        "",
        "TR001",
        out="lines over 100 characters are the checker's HY029; the translator keeps comments as they are",
    ),
]

REPRAP = [
    Row("2.1 RRF G1 S outside laser mode (no M452): dropped", "G1 X10 S200", "G1 X10", "TR003"),
    Row(
        "2.1 RRF M452 (laser mode): M3 S and G1 S are laser power (M620/M621, E1)",
        "M452\nM3 S255\nG1 X10\nG1 X20 S0\nM5\nM451",
        "M620 T0 E1\nM621 P100\nG1 X10 E1\nG1 X20\nM621 P0\nM620 T0 E0",
        "TR003",
    ),
    Row("2.1 RRF G1 H1 (homing move)", "G1 H1 X-240 F3000", "", "TR005", out="homing macros are machine-specific"),
    Row(
        "2.1 RRF M203 max-feed=convert (already mm/min)",
        "M203 X12000 Y12000",
        "M203 X12000 Y12000",
        "TR003",
        settings={"max_feed": "convert"},
    ),
    Row("2.1 RRF M221 D (drive) S", "T1\nM221 D1 S95", "T1\nM221 T1 S0.95"),
    Row("2.1 RRF G10 P R S (tool temperatures)", "G10 P0 R150 S210", "M104 T0 S210", "TR003"),
    Row("2.1 RRF G10 P S", "G10 P1 S210", "M104 T1 S210", v4="M104 T12 S210"),
    Row("2.1 RRF G10 L1 P X Y Z (tool offset)", "G10 L1 P0 X-9 Y39 Z-5", "", "TR002"),
    Row("2.1 RRF G10 P X Y Z (tool offset)", "G10 P0 X-9 Y39 Z-5", "", "TR002"),
    Row(
        "2.1 RRF G10 L1 P X Y Z, tool-offsets=m6",
        "G10 L1 P1 X10 Y0 Z0.5",
        "M6 T1 O2 X-10 Y0 Z-0.5",
        "TR003",
        settings={"tool_offsets": "m6"},
    ),
    Row(
        "2.1 RRF G10 P X Y Z, tool-offsets=m6",
        "G10 P1 X-9 Y39 Z-5",
        "M6 T1 O2 X9 Y-39 Z5",
        "TR003",
        settings={"tool_offsets": "m6"},
        v4="M6 T12 O2 X9 Y-39 Z5",
    ),
    Row(
        "2.1 RRF G10 P X S, tool-offsets=m6",
        "G10 P0 X-9 S200",
        "M6 T0 O1 X9\nM104 T0 S200",
        "TR003",
        settings={"tool_offsets": "m6"},
    ),
    Row("2.1 RRF G10 L2 P", "G10 L2 P1 X10 Y10", "", "TR005", out="workspace origins: use Repetrel fixture offsets"),
    Row("2.1 RRF G10 L20 P", "G10 L20 P1 X0", "", "TR005", out="needs a known machine position; not translated"),
    Row("2.1 RRF bare G10 (firmware retract)", "G10", "", "TR004"),
    Row("2.1 RRF M568 P S R", "M568 P0 S210 R150", "M104 T0 S210", "TR003"),
    # RepRapFirmware's DoDwell: "if (gb.Seen('S')) ... else if (gb.Seen('P'))": S counts alone, as on Marlin
    # (src/GCodes/GCodes.cpp); Hyrel would add them up
    Row("2.1 RRF G4 S P: S counts", "G4 S1 P500", "G4 S1", "TR004"),
    Row("2.1 RRF G91 leaves E alone", "M82\nG91", "M82\nG91"),
    Row("2.1 RRF G0/G1 R (restore point)", "G1 R1 X0 Y0 Z2", "", "TR005"),
    Row("2.1 RRF G93 (inverse time)", "G93", "", "TR005", out="per-move feed conversion is not implemented"),
    Row("2.1 RRF G94", "G94", "", "TR001"),
    Row("2.1 RRF M0 (stop)", "M0", "M0", "TR003"),
    Row("2.1 RRF M1 (sleep)", "M1", "M0", "TR003"),
    Row("2.1 RRF M2 (end): footer", "M2", "M30", prelude="M104 S200\n"),
    Row("2.1 RRF M3 S (rpm)", "M3 S12000", "M3 T0 S80", "TR003"),
    Row("2.1 RRF M3 S with spindle-max-rpm", "M3 S12000", "M3 T0 S50", "TR003", settings={"spindle_max_rpm": "24000"}),
    Row("2.1 RRF M106 S0.5 (0-1 fraction)", "M106 S0.5", "M106 T0 S128"),
    Row("2.1 RRF M106 S1 (full)", "M106 S1", "M106 T0 S255"),
    Row("2.1 RRF M106 S200 (0-255)", "M106 S200", "M106 T0 S200"),
    Row("2.1 RRF M106 configuration", 'M106 P1 C"Part" H-1', "", "TR001"),
    Row("2.1 RRF M109 T selects the tool", "M109 T1 S210", "M109 T1 S210\nT1"),
    Row(
        "2.1 RRF M116",
        "M104 T0 S210\nM140 S60\nM116",
        "M104 T0 S210\nM140 T24 S60\nM109 T0 S210 R2\nM190 T24 S60 R2",
        "TR004",
    ),
    Row("2.1 RRF M116 S (tolerance)", "M104 S210\nM116 S5", "M104 T0 S210\nM109 T0 S210 R5", "TR004"),
    Row("2.1 RRF M140 P1 (second bed)", "M140 P1 S60", "M140 T25 S60", v4="M140 T92 S60"),
    Row("2.1 RRF M140 S-273.1 (off)", "M140 S-273.1", "M140 T24 S0"),
    Row("2.1 RRF M226 (pause)", "M226", "M0", "TR003"),
    Row("2.1 RRF M291 S2 (blocking message)", 'M291 P"Check the bed" S2', "M0 ; gclint: message", "TR003"),
    Row("2.1 RRF M563 M584 M950 (configuration)", 'M563 P0 D0 H1\nM584 X0 Y1\nM950 H1 C"out1"', "", "TR001"),
    Row("2.1 RRF M98 (macro call)", 'M98 P"homeall.g"', "", "TR005"),
    Row("2.1 RRF unknown code runs a macro file", "M4000 S1", "", "TR005"),
    Row("2.1 RRF T-1", "T-1", "", "TR002"),
    Row("2.1 RRF T P0 (no macros)", "T1 P0", "T1", "TR004"),
    Row("2.1 RRF T{expression}", "T{param.T}", "", "TR005"),
    Row("2.1 RRF meta command", "if move.axes[0].homed\n  G1 X10", "  G1 X10", "TR005"),
    Row("2.1 RRF expression parameter", "G1 X{var.x} Y10", "", "TR005"),
]


# -- issue 13: meaning kept for multi-tool, CNC and inch jobs --------------------------------------------------

ISSUE_13 = [
    Row(
        "2: a single-nozzle job heats each head it prints with (and waits, as for the nozzle)",
        "M104 S215\nM109 S215\nT1\nG1 X5 Y5 E1",
        "M104 T0 S215\nM109 T0 S215\nT1\nM109 T1 S215\nG1 X5 Y5 E1",
        "TR004",
    ),
    Row(
        "2: a single nozzle's flow goes with it; its heater off is off on every head",
        "M104 S215\nM221 S90\nT1\nG1 X5 Y5 E1\nM104 S0",
        "M104 T0 S215\nM221 T0 S0.9\nT1\nM104 T1 S215\nM221 T1 S0.9\nG1 X5 Y5 E1\nM104 T1 S0\nM104 T0 S0",
        "TR004",
    ),
    Row(
        "4: the part fan (M106 without P) follows the tool; M107 stops it on the head that has it",
        "M104 T0 S200\nM104 T1 S200\nM106 S255\nT1\nG1 X5 Y5 E1\nT0\nG1 X6 Y6 E1\nM107",
        "M104 T0 S200\nM104 T1 S200\nM106 T0 S255\nT1\nM107 T0\nM106 T1 S255\nG1 X5 Y5 E1\nT0\nM107 T1\n"
        "M106 T0 S255\nG1 X6 Y6 E1\nM107 T0",
        "TR004",  # the fan count note (a Marlin printer may have a fan per extruder)
    ),
    Row(
        "4: an M107 while two heads blow switches off both",
        "M104 T0 S200\nM104 T1 S200\nM106 S255\nM106 P1 S255\nM107",
        "M104 T0 S200\nM104 T1 S200\nM106 T0 S255\nM106 T1 S255\nM107 T0",
        settings={"fan_map": "1=T1"},
    ),
    Row("3: an inch arc stays an arc, in mm", "G20\nG2 X1 Y0 I0.5 J0", "G21\nG2 X25.4 Y0 I12.7 J0", "TR004"),
    Row(
        "7: native flow declares the layer height the slicer states (M756) at each layer",
        "M83\n;HEIGHT:0.2\nG1 Z0.2 F600\nG1 X1 Y1 E1\n;HEIGHT:0.3\nG1 Z0.5\nG1 X2 Y2 E1",
        ";HEIGHT:0.2\nG21\nG90\nT0\nG1 Z0.2 F600\nM756 S0.2\nG1 X1 Y1 E1\n;HEIGHT:0.3\nG1 Z0.5\nM756 S0.3\nG1 X2 Y2 E1",
        "TR003 TR004",
        prelude="",
        settings={"flow": "native"},
    ),
    Row(
        "7: native flow, no stated height: the rise from the layer below",
        "M83\nG1 Z0.2 F600\nG1 X1 Y1 E1\nG1 X0 Y1 E1\nG1 Z0.35\nG1 X2 Y2 E1",
        "G21\nG90\nT0\nG1 Z0.2 F600\nM756 S0.2\nG1 X1 Y1 E1\nG1 X0 Y1 E1\nG1 Z0.35\nM756 S0.15\nG1 X2 Y2 E1",
        "TR003 TR004",
        prelude="",
        settings={"flow": "native"},
    ),
    Row(
        "7: native flow, a spiral (Z rises on every move): no height to declare, reported",
        "M83\nG1 Z0.2 F600\nG1 X1 Y1 E1\nG1 X0 Y1 E1\nG1 X1 Y2 Z0.21 E1\nG1 X2 Y2 Z0.22 E1\nG1 X3 Y2 Z0.23 E1",
        # the first rise reads as a layer of 0.01; once Z rises on every move, the height before is declared again
        "G21\nG90\nT0\nG1 Z0.2 F600\nM756 S0.2\nG1 X1 Y1 E1\nG1 X0 Y1 E1\nM756 S0.01\nG1 X1 Y2 Z0.21 E1\n"
        "G1 X2 Y2 Z0.22 E1\nM756 S0.2\nG1 X3 Y2 Z0.23 E1",
        "TR003 TR004",
        prelude="",
        settings={"flow": "native"},
    ),
    Row("9: Marlin M3 O (power as PWM 0-255)", "M3 O128", "M3 T0 S50.2", "TR003"),
    Row(
        "9: a tool the printer has no head for: the head before goes on printing (and heating) for it",
        "M104 S200\nT9\nM104 S210\nG1 X5 Y5 E1",
        "M104 T0 S200\nM104 T0 S210\nG1 X5 Y5 E1",
        "TR007",
    ),
    Row("10: M0 whose comment Hyrel would run (SHELL)", "M0 ; SHELL C:\\evil.exe", "M0", "TR009"),
    Row("10: M0 whose comment Hyrel would show (PIC)", "M0 (PIC C:\\x.png)", "M0", "TR009"),
    Row("10: M600 whose comment Hyrel would run", "M600 ; SAY hello", "M0 ; gclint: filament change", "TR003 TR009"),
    Row("10: M0 with a plain comment stays as it is", "M0 ; wait for me", "M0 ; wait for me"),
]


@pytest.mark.parametrize("row", ISSUE_13, ids=ids(ISSUE_13))
def test_issue_13(row: Row) -> None:
    validate("marlin", row)


def test_arc_before_any_z_word_is_kept() -> None:
    """An extruding arc under M229 E1 before any Z word: written as segments (no Z needed), not dropped."""
    got, codes = translate_rows("marlin", "G2 X10 Y0 I5 J0 E1", prelude="G21\nG90\nM83\nG1 X0 Y0 F600\n")
    assert len(got) == 18 and all(line.startswith("G1 X") and " Z" not in line for line in got)
    assert got[-1] == "G1 X10 Y0 E0.05556" and codes == ["TR004"]


def test_tool_map_to_a_bed_is_refused() -> None:
    options = TranslateOptions()
    with pytest.raises(ValueError, match=r"a tool maps to a head \(T0-T19\); T24 is Bed1"):
        options.set("tool-map", "0=T24")


def test_one_command_per_line_on_changed_lines() -> None:
    got, codes = translate_rows("carvera", "G0 X0.000 Y0.000 S10000M3")
    assert got == ["G0 X0.000 Y0.000", "M3 T0 S66.7"] and codes == ["TR003"]
    got, _ = translate_rows("carvera", "N5 G20 G90 (inch)")
    assert got == ["N5 G21", "G90 (inch)"]


def test_annotate_marks_every_added_line() -> None:
    """--annotate: every line the translator adds says so (header, carried state, segments, footer)."""
    source = "M104 S215\nM109 S215\nM106 S255\nT1\nG1 X5 Y5 E1\nG2 X9 Y5 I2 J0 E1\nG53 G1 X1\nM300 S440 P10\n"
    options = TranslateOptions(annotate=True)
    translator = translator_for(dialects.get("marlin"), dialects.get("hyrel"), options)
    result = TranslationResult("t", "marlin", "hyrel")
    out = "".join(translate_source(Source.from_text("G21\nG90\nM82\n" + source), translator, result))
    lines = out.splitlines()
    source_lines = set(("G21\nG90\nM82\n" + source).splitlines())
    # a line with a command that is not in the source says why it is there (a note longer than Hyrel's 100
    # characters is on the comment lines just before it)
    added = [i for i, line in enumerate(lines) if line not in source_lines and not line.startswith(";")]
    assert len(added) > 10
    for i in added:
        assert "; gclint:" in lines[i] or lines[i - 1].startswith(";"), lines[i]


def test_long_lines_fit_in_100_characters() -> None:
    long_comment = "; " + "word " * 40
    source = f"M104 S210 ; {'x' * 110}\n{long_comment}\nM0 ; {'y' * 120}\n"
    out, result = translate("marlin", source)
    assert all(len(line) <= 100 for line in out.splitlines())
    assert "M104 T0 S210" in out.splitlines()
    assert {f.code for f in result.findings} >= {"TR003", "TR004"}


@pytest.mark.parametrize("row", MARLIN, ids=ids(MARLIN))
def test_marlin(row: Row) -> None:
    validate("marlin", row)


@pytest.mark.parametrize("row", REPRAP, ids=ids(REPRAP))
def test_reprap(row: Row) -> None:
    validate("reprap", row)


# Marlin rows that read differently on RepRapFirmware (their RRF form is in REPRAP, or the code is
# Marlin-only: RepRapFirmware runs a macro file for a code it does not know).
_NOT_RRF = (
    "RRF",
    "rrf table",
    "on Marlin",
    "G4 S P",
    "M3 S (PWM",
    "M3 then M4",
    "M5",
    "M0 ",
    "M1 ",
    "M30 ",
    "M226",
    "M190 T",
    "M106 T (",
    "Klipper",
    "Bambu",
    "X1 unknown",
    "M3 laser",
    "laser power",  # Marlin's inline laser power; RepRapFirmware's needs M452 (REPRAP rows)
    "the laser enabled",
    "T<n> F S",
    "M84 S",
    "M106 P2",
    "M200",
    "G28 W",
    "M203 max-feed",
    "M221 T1",
    "M112",
    "M209",
    "M155",
    "M503",
    "M701",
    "M710",
    "M420",
    "M593",
    "G30",
    "Marlin: ",  # (one command a line: RepRapFirmware runs them all, StringParser.cpp)
)
RRF_TOO = [r for r in MARLIN if not any(d in r.row for d in _NOT_RRF)]


@pytest.mark.parametrize("row", RRF_TOO, ids=ids(RRF_TOO))
def test_marlin_rows_hold_for_reprap_too(row: Row) -> None:
    """Most Marlin rows are the same on RepRapFirmware; the ones that differ are in REPRAP."""
    validate("reprap", row)


def test_arc_evalues_segments() -> None:
    """An extruding arc under M229 E1: G1 segments on the circle whose E amounts add up to the arc's."""
    import math

    got, codes = translate_rows("marlin", "G1 X0 Y0\nG2 X2 Y0 I1 J0 E0.4")
    assert got[0] == "G1 X0 Y0" and got[-1].startswith("G1 X2 Y0 E")
    points = [dict((w[0], float(w[1:])) for w in line.split()[1:]) for line in got[1:]]
    assert len(points) > 4
    for p in points:
        assert math.isclose(math.hypot(p["X"] - 1, p["Y"]), 1, abs_tol=1e-3)
        assert p["Y"] >= -1e-9  # clockwise from (0,0) to (2,0) about (1,0) passes over the top
    assert math.isclose(sum(p["E"] for p in points), 0.4, abs_tol=1e-4)
    assert codes == ["TR004"]


def test_arc_evalues_absolute_e() -> None:
    got, _ = translate_rows("marlin", "M82\nG92 E10\nG1 X0 Y0\nG2 X2 Y0 I1 J0 E10.4")
    assert got[-1] == "G1 X2 Y0 E10.4"
    values = [float(line.split("E")[-1]) for line in got[3:]]
    assert values == sorted(values) and values[0] > 10


def test_arc_other_plane() -> None:
    """G18 (XZ plane; grbl's axis order Z, X): the arc passes through Z-1 at X1, Y stays."""
    import math

    got, codes = translate_rows("marlin", "G1 X0 Y0 Z0\nG18\nG2 X2 Z0 I1 K0", flow="native")
    assert got[:2] == ["G1 X0 Y0 Z0", "G18"]
    points = [dict((w[0], float(w[1:])) for w in line.split()[1:]) for line in got[2:]]
    assert all("Y" not in p for p in points) and points[-1] == {"X": 2, "Z": 0}
    for p in points:
        assert math.isclose(math.hypot(p["X"] - 1, p["Z"]), 1, abs_tol=1e-3) and p["Z"] <= 1e-9
    assert codes == ["TR004"]


def test_arc_turns() -> None:
    """G2 with P1: one extra full circle, written as G1 segments that end where the arc ends."""
    got, codes = translate_rows("marlin", "G1 X0 Y0\nG2 X0 Y0 I1 J0 P1")
    assert got[0] == "G1 X0 Y0"
    assert all(line.startswith("G1 X") for line in got[1:])
    assert got[-1] == "G1 X0 Y0"
    assert len(got) > 20  # two full circles of radius 1
    assert codes == ["TR004"]


def test_footer_appended_at_end_of_file() -> None:
    out, _ = translate("marlin", "G1 X1 F600\nM107\n")
    assert out.splitlines()[-1] == "M30"
    assert out.endswith("M30\n")


def test_footer_keeps_a_missing_final_newline() -> None:
    out, _ = translate("marlin", "G1 X1 F600\nM107")
    assert out.endswith("M107 T0\nM30")


def test_footer_turns_spindle_off() -> None:
    out, _ = translate("marlin", "G1 X1 F600\nM3 S255\n")
    assert out.splitlines()[-2:] == ["M5 T0", "M30"]


def test_no_footer_for_a_file_without_commands() -> None:
    out, _ = translate("marlin", "; just a comment\nM117 hello\n")
    assert out == "; gclint: dialect=hyrel (written by gclint translate from marlin)\n; just a comment\n"


def test_untouched_lines_are_byte_for_byte() -> None:
    text = "G1 X1.000  Y2 F600 ;  spaced\r\nG1 X2 Y3\tE0.1\r\n;comment\r\n\r\n"
    out, _ = translate("marlin", "M83\r\n" + text)
    assert text in out


def test_checksum_recomputed_on_a_changed_line() -> None:
    from gclint.rules.syntax import compute_checksum

    out, _ = translate("marlin", "N10 M104 S200*99\n")
    line = out.splitlines()[1]
    head, _, value = line.partition("*")
    assert head == "N10 M104 T0 S200"
    assert int(value) == compute_checksum(head)


def test_annotate_marks_changed_and_dropped_lines() -> None:
    options = TranslateOptions(annotate=True)
    translator = translator_for(dialects.get("marlin"), dialects.get("hyrel"), options)
    result = TranslationResult("t", "marlin", "hyrel")
    out = "".join(translate_source(Source.from_text("M104 S200\nM204 P1500\nG1 X1 F600\n"), translator, result))
    lines = out.splitlines()[1:]  # (after the line that says what the output is)
    assert lines[0] == "M104 T0 S200 ; gclint: was 'M104 S200'"
    assert lines[1].startswith("; gclint: dropped 'M204 P1500' (TR002")
    assert "G1 X1 F600" in lines  # untouched
    assert any(line.startswith("G21 ; gclint: added") for line in lines)
    assert lines[-1].startswith("M30 ; gclint: added")


def test_repeated_findings_are_counted_not_listed() -> None:
    _, result = translate("marlin", "M204 P1\nM204 P2\nM204 P3\n")
    assert [f.code for f in result.findings] == ["TR002"]
    assert "3 lines like this" in result.findings[0].message
