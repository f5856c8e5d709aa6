"""``gclint diff`` and the stranger review of issue 13: each wrong translation the review found must show
as a difference, and the translator's own output must have none it does not explain.  (The translation
side: tests/test_translate_review13.py.)"""

from __future__ import annotations

import pytest

from .test_diff import Wrong, diff_texts, translate_and_diff

MMU = "M104 S215\nM109 S215\nM83\nT0\nG1 X10 Y10 Z0.2 E1 F1200\nM104 S240\nT1\nG1 X20 Y20 E1\n"
TC = "G21 G90\nT7 M6\nM3 S10000\nG1 X10 F100\nT3 M6\nG1 X20\nM2\n"

WRONG = [
    Wrong(
        "2: a head first used after an M104 prints cold (the source's nozzle was waited hot)",
        "marlin",
        MMU,
        "M104 T0 S215\nM109 T0 S215\nM229 E1 D1\nM83\nT0\nG1 X10 Y10 Z0.2 E1 F1200\nM104 T0 S240\nT1\n"
        "M104 T1 S240\nG1 X20 Y20 E1\nM30\n",
        "temp",
        {"tool_map": "0=T0,1=T1"},
    ),
    Wrong(
        "3: the spindle stays on T0 while the mapped head T3 cuts",
        "machinekit",
        TC,
        "G21\nG90\nT3\nM3 T0 S66.7\nG54\nG1 X10 F100\nT1\nG1 X20\nM5 T0\nM30\n",
        "spindle",
        {"tool_map": "7=T3,3=T1", "spindle_max_rpm": "15000"},
    ),
]


@pytest.mark.parametrize("row", WRONG, ids=[w.item for w in WRONG])
def test_diff_finds_the_wrong_translation(row: Wrong) -> None:
    result = diff_texts(row.dialect, row.source, row.output, **row.settings)
    assert row.aspect in {d.aspect for d in result.differences}, [d.to_dict() for d in result.differences]


@pytest.mark.parametrize("row", WRONG, ids=[w.item for w in WRONG])
def test_the_translation_has_no_difference(row: Wrong) -> None:
    _, _, diff = translate_and_diff(row.dialect, row.source, **row.settings)
    assert [d.aspect for d in diff.differences if d.aspect in (row.aspect, "end")] == [], [
        d.to_dict() for d in diff.differences
    ]
