"""HY068 head-command-on-bed: A head command (M106, M107, M221, M721, M722, M620) addressed to a bed or chamber (T24, T25, T46)

tests/test_rule_fixtures.py checks the fixture pair (tests/fixtures/rules/HY068_bad.gcode, _good.gcode) and the
rule's examples, tests/test_rule_snapshots.py pins its findings on the bad fixture; this table holds the cases
the fixtures do not.
"""

from __future__ import annotations

import pytest

from gclint.engine import Linter, Options

CODE = "HY068"

# A v5 job's head: M140/M190 T24 (a bed only in v5) make the file's addresses v5, so HY008 reads none of
# them as v4 (with fewer bed lines, two M620 T24 tip the file's evidence to v4, and HY008 reports them instead).
V5 = "M140 S60 T24\nM190 S60 T24\nM104 S215 T0\nT0\n"


def found(text: str, dialect: str = "hyrel") -> list[tuple[int, int]]:
    """(line, column) of each HY068 finding in ``text`` read as ``dialect``."""
    result = Linter(Options(dialect=dialect)).check_text(text, "<test>")
    return [(f.line, f.column) for f in result.findings if f.code == CODE]


@pytest.mark.parametrize(
    "text,expected",
    [
        # every code the rule listens to, on each bed address (the column is the T word's)
        (V5 + "M106 T24 S100\n", [(5, 6)]),
        (V5 + "M107 T25\n", [(5, 6)]),
        (V5 + "M221 S1.0 T24 P77 W0.5 Z0.3\n", [(5, 11)]),
        (V5 + "M721 S10000 E100 P-15 T25\n", [(5, 23)]),
        (V5 + "M722 T24 I1\n", [(5, 6)]),
        (V5 + "M620 T24 E1\nM620 T24 E0\n", [(5, 6), (6, 6)]),
        (V5 + "M106 T46 S50\n", [(5, 6)]),  # T46: all beds / chambers
        # close, not reported: a head, a yoke, all devices, the laser, no T, the bed commands themselves
        (V5 + "M106 T0 S100\n", []),
        (V5 + "M106 T41 S100\n", []),
        (V5 + "M106 T40 S100\n", []),  # all devices includes the heads
        (V5 + "M620 T21 E1\nM620 T21 E0\n", []),
        (V5 + "M106 S100\nM107\n", []),
        (V5 + "M140 T25 S60\nM141 T24 S40\n", []),
        (V5 + "M104 T24 S200\n", []),  # HY046's case, not this rule's
    ],
)
def test_where_hy068_reports(text: str, expected: list[tuple[int, int]]) -> None:
    assert found(text) == expected


def test_v4_numbering_is_not_a_bed() -> None:
    # hyrel-v4: T24 is yoke 2, position 4 (T_v4), a head; the v4 beds are T91/T92, read as v5 T24/T25 and
    # left to this rule only in v5 files
    assert found("M106 T24 S100\nM106 T91 S100\n", dialect="hyrel-v4") == []


def test_other_dialects_are_not_read() -> None:
    assert found("M106 T24 S100\n", dialect="marlin") == []
