"""``gclint diff`` and the stranger review of issue 13: each wrong translation the review found must show
as a difference, and the translator's own output must have none it does not explain.  (The translation
side: tests/test_translate_review13.py.)"""

from __future__ import annotations

import pytest

from gclint import dialects
from gclint.simulate import Mapping, diff_sources
from gclint.simulate.translation import explanations_from
from gclint.syntax.source import Source
from gclint.translate.options import TranslateOptions

from .test_diff import Wrong, diff_texts, translate_and_diff

MMU = "M104 S215\nM109 S215\nM83\nT0\nG1 X10 Y10 Z0.2 E1 F1200\nM104 S240\nT1\nG1 X20 Y20 E1\n"
SPINDLE = "G21\nG90\nM3 S255\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nM5\n"
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
    Wrong(
        "9: Marlin M109 S to a lower temperature written as a cooling wait",
        "marlin",
        "M83\nT0\nM109 S210\nG1 X1 E1 F100\nM109 S180\nG1 X2 E1\n",
        "M229 E1 D1\nM83\nT0\nM109 T0 S210\nG21\nG90\nG1 X1 E1 F100\nM109 T0 S180 R2\nG1 X2 E1\nM30\n",
        "temp",
    ),
    Wrong(
        "9: a bare M109 after M104 S0 written as a cooling wait (to 0 °C)",
        "marlin",
        "M83\nT0\nM109 S180\nG1 X1 E1 F100\nM104 S0\nM109\nG1 X2 E1\n",
        "M229 E1 D1\nM83\nT0\nM109 T0 S180\nG21\nG90\nG1 X1 E1 F100\nM104 T0 S0\nM109 T0 R2\nG1 X2 E1\nM30\n",
        "temp",
    ),
    Wrong(
        "5: a Marlin spindle job that loses its M3 (the diff saw no working move in it)",
        "marlin",
        SPINDLE,
        "G21\nG90\nT0\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nM30\n",
        "moves",
    ),
    Wrong(
        "5: a Marlin spindle job at the wrong power",
        "marlin",
        SPINDLE,
        "G21\nG90\nM3 T0 S50\nT0\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nM5 T0\nM30\n",
        "spindle",
    ),
]


def test_5_marlin_laser_power_on_moves_is_seen_and_explained() -> None:
    """Marlin's S on a move is the laser power (Marlin G-code reference, G0-G1): dropped by the translator
    (TR003), which the diff sees as moves that no longer cut, explained by that finding."""
    source = "G90\nG21\nM4 S0\nG0 X10 Y10\nG1 X20 Y10 S200 F3000\nG1 X20 Y20 S0\nM5\n"
    _, _, diff = translate_and_diff("marlin", source)
    assert diff.differences and not diff.unexplained()
    assert {d.explained_by[0] for d in diff.differences} == {"TR003"}  # type: ignore[index]


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


# -- (4) a finding explains only differences in what it is about, where it is -------------------------------


def test_4_a_g28_finding_does_not_explain_another_axis() -> None:
    """G28 homes Z in the source, not on Hyrel (TR003 G28, about Z): an X difference later is not that."""

    source = "G28\nG90\nM83\nM104 S200\nM109 S200\nG1 X10 Y10 Z0.2 E1 F1200\nG1 X20 Y10 E1\nG1 X30 Y10 E1\n"
    _, result, _ = translate_and_diff("marlin", source)
    assert any(f.code == "TR003" and "G28" in f.message for f in result.findings)
    wrong = (
        "M104 T0 S200\nM109 T0 S200\nG21\nG90\nG28 X0 Y0\nT0\nM229 E1 D1\nM83\nG1 X15 Y10 Z0.2 E1 F1200\n"
        "G1 X20 Y10 E1\nG1 X30 Y10 E1\nM30\n"
    )
    diff = diff_sources(
        Source.from_text(source, "source"),
        Source.from_text(wrong, "output"),
        dialects.get("marlin"),
        dialects.get("hyrel"),
        Mapping(),
        explanations_from(result),
    )
    position = [d for d in diff.differences if d.aspect == "position" and "X" in d.source]
    assert position and position[0].explained_by is None, [d.to_dict() for d in diff.differences]


# -- (8) inch helices with P turns ---------------------------------------------------------------------------


@pytest.mark.parametrize("turns", ["", " P2"])
def test_8_inch_helix_with_turns_has_no_false_difference(turns: str) -> None:
    source = f"G20 G90 G17\nG0 X0 Y0 Z0\nG1 X0 F10\nG2 X1 Y0 Z-0.1 I0.5 J0{turns}\nG1 X2\nM2\n"
    _, _, diff = translate_and_diff("machinekit", source)
    assert diff.differences == [] and diff.pairs == 2, [d.to_dict() for d in diff.differences]


def test_4_an_assumed_rpm_does_not_explain_a_spindle_left_off() -> None:
    """TR003 "rpm converted to percent of an assumed maximum" is about the speed (spindle:speed): it explains
    a speed that differs, not a spindle that does not run on the head that cuts."""

    settings = {"tool_map": "7=T3,3=T1"}
    _, result, diff = translate_and_diff("machinekit", TC, **settings)
    assert diff.differences == []  # (the speeds keep the source's proportions: compared relatively)
    wrong = WRONG[1].output  # the spindle on T0 while T3 cuts

    options = TranslateOptions()
    options.set("tool-map", "7=T3,3=T1")
    diff = diff_sources(
        Source.from_text(TC, "source"),
        Source.from_text(wrong, "output"),
        dialects.get("machinekit"),
        dialects.get("hyrel"),
        Mapping.from_options(options),
        explanations_from(result),
    )
    spindle = [d for d in diff.differences if d.aspect == "spindle"]
    assert spindle and spindle[0].explained_by is None, [d.to_dict() for d in diff.differences]
