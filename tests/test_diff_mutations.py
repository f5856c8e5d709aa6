"""``gclint diff``, mutation-tested (issue 27): a few real corpus jobs translated by gclint, their output edited
once per mutant (tests/mutations.py).  The full run, with the kill rate per kind of edit, is
``python bench/bench_mutations.py``."""

from __future__ import annotations

import pytest

from .conftest import needs_corpus
from .mutations import FAST, judge, mutants, prepare


@needs_corpus
def test_the_diff_kills_meaning_changing_edits_and_keeps_quiet_on_the_others() -> None:
    changing = killed = 0
    survivors, alarms = [], []
    for job in FAST:
        prepared = prepare(job)
        assert not prepared.unexplained, (job.name, [d.to_dict() for d in prepared.unexplained])
        for mutant in mutants(prepared.translation, prepared.cnc, per_kind=2):
            verdict = judge(prepared, mutant)
            if mutant.preserving:
                if verdict.new:
                    alarms.append((job.name, mutant.line + 1, mutant.kind, [d.to_dict() for d in verdict.new]))
            elif not verdict.undoes:
                changing += 1
                if verdict.killed:
                    killed += 1
                else:
                    survivors.append((job.name, mutant.line + 1, mutant.kind, mutant.what))
    assert changing >= 100
    assert not alarms, alarms
    assert killed >= 0.98 * changing, survivors


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("G1 X1 Y2 E0.5 F1200 ; move\n", "G1 X1 Y2 A0.5 F1200 ; move\n"),
        ("G92 E0\n", "G92 A0\n"),
        ("M104 S200 T1\n", "M104 P200 T1\n"),
        ("G4 P500\n", "G4 P0.5\n"),
        ("G10\nG11\n", "G22\nG23\n"),
        ("M82 ; absolute E\n", "\n"),
    ],
)
def test_gcode_to_ngc_rewrites_as_machinekits_filter(text: str, expected: str) -> None:
    from .mutations import gcode_to_ngc

    assert gcode_to_ngc(text) == expected + "M2 ; end of program\n"
