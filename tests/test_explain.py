"""``gclint explain``: commands decoded in the printer's own terms, checked against the "decoded and
executed by the printer as follows" sections of the Hyrel Gcode page, plus the T_v5 page, v4
addressing and the other dialects' tables.  One row per example: dialect, G-code, texts that must
appear in the explanation (in order), texts that must not."""

from __future__ import annotations

import json
import string
from dataclasses import replace

import pytest

from gclint import dialects
from gclint.explain import explain_text
from tests.conftest import CORPUS, needs_corpus, run_cli

ROWS = [
    # M109 windows (Gcode page, "M109 Wait for Temp (Head)", examples 1-7)
    (
        "hyrel",
        "M109 T0 S240 L10 U5",
        [
            "wait for head temperature",
            "T0 (target head T0 (yoke 1, position 1))",
            "S240 (and set the temperature to 240°C)",
            "L10 (but end the wait once the temperature reaches 10°C below",
            "U5 (or end the wait once the temperature reaches 5°C above",
            "anywhere between 230°C and 245°C",
        ],
        ["warning"],
    ),
    ("hyrel", "M109 T1 S240 R5", ["within +/-5°C of the set point", "between 235°C and 245°C"], []),
    ("hyrel", "M109 T1 S240 H230", ["reaches 230°C", "230°C or more"], []),
    ("hyrel", "M109 T0 S240 W0", ["do not pause until M116 is executed"], []),
    (
        "hyrel",
        "T3\nM109 R10",
        [
            "switch to head T3: yoke 1, position 4",
            "no T: use the head with current focus (T3)",
            "no S: no new temperature is set",
            "+/-10°C",
        ],
        [],
    ),
    (
        "hyrel",
        "M109 T0 S240 H235 U5",
        ["warning: the Hyrel page says: use EITHER (H and/or C) OR (L and/or U) OR (R)"],
        [],
    ),
    ("hyrel", "M109 T40 S200", ["all devices (T40)", "will FAIL (non-fatally) on a virtual or group address"], []),
    ("hyrel", "M190 T24 S60 R3", ["wait for bed temperature", "Bed1 / Chamber1 (T24)", "between 57°C and 63°C"], []),
    ("hyrel", "M191 S45", ["wait for chamber temperature", "no T: use the chamber with current focus"], []),
    # M106 and the C range (Gcode page, "M106 Set Cooling / Etc.")
    ("hyrel", "M106 C255", ["on all tools", "no speed", "C255 (of range 0-255: all following M106"], []),
    (
        "hyrel",
        "M106 C255\nM106 T1 S127",
        ["S127 (target value of 127 of range 0-255: 49.8% duty)", "set by M106 C at line 1"],
        [],
    ),
    ("hyrel", "M106 T0 S50", ["of range 0-100: 50% duty", "default 0-100"], []),
    ("hyrel", "M106 T0 P100", ["P100 (during extrusion moves only, at 100% duty)"], []),
    # T addressing, v5 and v4 (T_v5 "Chart of Addresses"; T_v4 and the Hyrel v4 firmware source)
    ("hyrel", "T0", ["switch to head T0: yoke 1, position 1, and invoke all its flow, prime, unprime and offset"], []),
    ("hyrel", "T7", ["head T7: yoke 2, position 3"], []),
    ("hyrel", "M702 T0 S30\nT30", ["designate clone squad T30", "virtual head / clone squad T30"], []),
    ("hyrel-v4", "M109 T11 S240", ["head at yoke 1, position 1 (v4 T11 = v5 T0)"], []),
    ("hyrel-v4", "M104 T0 S0", ["all devices (v4 T0 = v5 T40)", "(off)"], []),
    ("hyrel-v4", "M6 T12 O2 X0 Y0", ["yoke 1, position 2 (v4 T12 = v5 T1)", 'offset stored in register "O2"'], []),
    # M229 (Gcode page, "M229 Use E Values")
    ("hyrel", "M229 E1 D1", ["E1 (enabled", "D1 (flow calculations directed via CANBUS"], ["illegal"]),
    ("hyrel", "M229 E1 D0", ["warning: E1 D0 is an illegal combination"], []),
    ("hyrel", "M229 E0 D0 S0.02", ["isolated non-printing moves of under 0.02 seconds"], []),
    # lasers and UV pens
    (
        "hyrel",
        "M620 T21 E1\nM621 P40\nM623 P80 D500",
        [
            "CO2 laser (T21)",
            "E1 (enable)",
            "P40 (at 40% during printing (E) moves)",
            "P80 (power 80%)",
            "D500 (duration 500 milliseconds)",
        ],
        ["no M620"],
    ),
    ("hyrel", "M620 E1", ["warning: T must be specified"], []),
    ("hyrel", "M621 P40", ["warning: no M620 T# E1 enabled a laser"], []),
    ("hyrel", "M623 P80 D90000", ["D is above the UV pen maximum of 60,000 ms"], []),
    # arcs and spirals (G2, G2.1 examples)
    (
        "hyrel",
        "G2 X50 Y75 I15 J20 E1 S6",
        [
            "clockwise arc",
            "I15 (centered about a point 15 mm further in X)",
            "S6 (made up of 6 segments",
            "using the previously established F rate",
        ],
        [],
    ),
    (
        "hyrel",
        "G2.1 Z10 I15 J20 P0.5 L50 E1 S9 R1 F1200",
        [
            "clockwise spiral",
            "L50 (complete no more than 50 laps)",
            "P0.5 (0.5 mm between centers",
            "R1 (spiral out from the center",
            "F1200 (at a speed of 1200 mm/min)",
        ],
        [],
    ),
    ("hyrel", "G2.1 I15 J20 P1.2 E1", ["complete all laps", "default segments of 0.33333 mm", "default R0"], []),
    ("hyrel", "G2 X10 Y10 R5", ["R5 (radius form is not supported"], []),
    # homing and offsets (G28, M660 + G1 H)
    (
        "hyrel",
        "G28 X0 Y0",
        ["X0 (home the X axis)", "Z remains unchanged", "G92 and H (M660) offsets are cleared"],
        ["no axis listed"],
    ),
    ("hyrel", "G28", ["warning: no axis listed: Hyrel homes only the axes named"], []),
    (
        "hyrel",
        "M660 H2 Z28.2\nG1 X50 Y75 F4800 H2",
        [
            "H2 (store in register 2)",
            "Z28.2 (+28.2 to the Z position)",
            "H2 (invoke the offsets stored in register H2: Z+28.2 stored by M660)",
        ],
        [],
    ),
    ("hyrel", "G1 X1 H3", ["no M660 H3 stored an offset"], []),
    (
        "hyrel",
        "G81 T0 X100 Y75 I3 P3 Q-2 Z-7.5 F200",
        ["peck downward an additional 3 mm", "maximum depth of 7.5 mm", "an M660 offset must be set and applied"],
        [],
    ),
    # moves (G0/G1 examples)
    ("hyrel", "G0 X50 Y75 Z10", ["rapid (non-working)", "X50 (to X50)", "use the G0 speed from the settings"], []),
    (
        "hyrel",
        "G91\nG1 X-5 E1 F1800",
        ["-5 mm in X", "while extruding; native flow ignores the amount", "F1800 (moving at 1800 mm/min)"],
        [],
    ),
    (
        "hyrel",
        "M0 ; SAY Hello Wilbur ; PIC C:\\mr_ed.png",
        ["SAY Hello Wilbur (announce text: Hello Wilbur)", "PIC C:\\mr_ed.png (display image: C:\\mr_ed.png)"],
        [],
    ),
    ("hyrel", "M0 ; SHELL C:\\program.exe", ["warning: SHELL runs a program"], []),
    ("hyrel", "G4 S0.5 P500", ["S0.5 (0.5 s)", "P500 (500 ms)", "1 s in all"], []),
    ("hyrel", "M204 S1000", ["not a code of Hyrel", "warning: Repetrel does not list M204"], []),
    # other dialects
    (
        "marlin",
        "M109 S200\nM109 R180",
        ["wait for hotend temperature", "wait only while heating", "wait while heating or cooling"],
        [],
    ),
    ("marlin", "M106 S127", ["fan speed 127 of 255: 49.8%"], []),
    ("marlin", "G28", ["no axis listed: home all axes"], []),
    ("marlin", "M204 P500 T1000", ["starting accelerations", "P500 (printing moves: 500)"], []),
    ("marlin", "T1", ["select tool 1"], []),
    (
        "reprap",
        "G10 P0 S200 R150",
        ["tool offsets and temperatures", "P0 (tool number: 0)", "R150 (standby temperature, C: 150)"],
        [],
    ),
    ("reprap", "M106 P1 S0.5", ["fan number 1", "50% (RepRapFirmware reads 0-1 as a fraction)"], []),
    ("machinekit", "G4 P2", ["P2 (2 s)"], []),
    ("machinekit", "T2 M6", ["select tool 2", "tool change to the tool selected by T", "(T2)"], []),
    (
        "carvera",
        "M3 S10000\nM6 T3",
        ["start the spindle clockwise", "S10000 (at 10000 RPM)", "T3 (change to tool 3)"],
        [],
    ),
    ("marlin", "SET_FAN_SPEED FAN=part SPEED=0.5", ["Klipper extended command", "FAN=part"], []),
    # Repetrel's header declares each loaded head with M6 T# O...: the declaration takes effect on its own
    # line (T_v5, Two Heads Loaded); a head no line declares is still not loaded
    (
        "hyrel",
        "M6 T0 O1 X0 Y0 Z0\nM6 T1 O2 X0 Y0 Z0\nM104 T1 S200",
        ["target head T1", 'offset stored in register "O2"', "M104"],
        ["warning: no head is loaded at T1"],
    ),
    ("hyrel", "M6 T0 O1 X0 Y0 Z0\nM104 T2 S200", ["warning: no head is loaded at T2"], []),
]


def _text(dialect: str, gcode: str) -> str:
    return "\n".join(e.render() for e in explain_text(gcode, dialects.get(dialect)))


@pytest.mark.parametrize("dialect,gcode,expected,absent", ROWS, ids=[f"{r[0]}:{r[1][:30]}" for r in ROWS])
def test_explanations(dialect, gcode, expected, absent):
    text = _text(dialect, gcode)
    position = 0
    for piece in expected:
        found = text.find(piece, position)
        assert found >= 0, f"{piece!r} missing (or out of order) in:\n{text}"
        position = found
    for piece in absent:
        assert piece not in text, f"{piece!r} should not be in:\n{text}"


def test_cli_expression():
    proc = run_cli("explain", "-e", "M109 T0 S240 L10 U5")
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout.decode()
    assert "* M109 (wait for head temperature)" in out
    assert "** note: the wait ends when the temperature is anywhere between 230°C and 245°C" in out


def test_cli_json_and_dialect():
    proc = run_cli("explain", "-e", "M109 S200", "-e", "M106 S255", "--dialect", "marlin", "--format", "json")
    data = json.loads(proc.stdout)
    assert data["dialect"] == "marlin"
    assert [c["code"] for c in data["commands"]] == ["M109", "M106"]
    assert data["commands"][1]["items"][0] == {"word": "S255", "text": "fan speed 255 of 255: 100%", "warning": False}


def test_cli_file_keeps_state_between_lines(tmp_path):
    job = tmp_path / "job.gcode"
    job.write_text("; gclint: dialect=hyrel\nM106 C255\nT1\nM106 S255\nM109 R5\n")
    out = run_cli("explain", str(job)).stdout.decode()
    assert "4: M106 S255" in out and "100% duty" in out
    assert "no T: use the head with current focus (T1)" in out


@needs_corpus
def test_cli_on_a_v4_corpus_job():
    job = CORPUS / "hyrel" / "unidentified_idx23519466326__shape1_v4.gcode"
    proc = run_cli("explain", str(job))
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout.decode()
    assert out.startswith("; dialect: hyrel-v4")
    assert "(v4 T12 = v5 T1)" in out


def test_cli_usage_errors():
    assert run_cli("explain").returncode == 2
    assert run_cli("explain", "-e", "G1", "--dialect", "nonsense").returncode == 2
    proc = run_cli("explain", "/nonexistent.gcode")
    assert proc.returncode == 2 and b"Traceback" not in proc.stderr


def test_every_dialect_explains_every_code_it_lists():
    """No code of any table crashes the decoder, with or without parameters."""
    for dialect in dialects.all_dialects():
        for code in dialect.codes:
            for line in (code, f"{code} X1 Y2 S3 P4 T0 E1 F100 H1 R2 I1 J1 L1 D1"):
                explained = explain_text(line, dialect)
                assert explained and explained[0].title, (dialect.name, line)


def test_table_readings_are_well_formed():
    """``Param.says`` has no placeholder but ``{value}``; ``Param.values`` are keyed by numbers as written."""
    for dialect in dialects.all_dialects():
        for spec in dialect.codes.values():
            for param in (spec.params or {}).values():
                fields = {name for _, name, _, _ in string.Formatter().parse(param.says) if name is not None}
                assert fields <= {"value"}, (dialect.name, spec.code, param.letter, fields)
                for key in param.values or {}:
                    float(key)


def test_readings_come_from_the_dialect_table():
    """What a word does, what the code does and what happens without a word are read from the code table:
    a dialect that words M621 otherwise is explained in its own words."""
    hyrel = dialects.get("hyrel")
    m621 = hyrel.spec("M621")
    reworded = replace(
        m621,
        does=("fire the laser",),
        params={
            "P": replace(m621.params["P"], says="{value} percent while printing"),
            "D": replace(m621.params["D"], absent="no D: pierce at P"),
        },
    )
    dialect = hyrel.derive("hyrel-reworded", "Hyrel, reworded", add=[reworded])
    rendered = explain_text("M620 T21 E1\nM621 P40", dialect)[1].render()
    assert rendered.splitlines()[1:] == [
        "** note: fire the laser",
        "** P40 (40 percent while printing)",
        "** note: no D: pierce at P",
    ]
