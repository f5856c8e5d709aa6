"""Issue 28: the reader's quick way through plain G0/G1 lines (``Simulator.plain_event``, taken by ``events`` while
``fast_plain`` and ``plain_now`` say so) gives the same events and the same end state as its general way
(``motion``, ``target``, ``extrusion``), on the corpus's Marlin and RepRapFirmware jobs and on the cases where the
state matters (relative moves, G92, inches, M220, G53, tool offsets)."""

from __future__ import annotations

from pathlib import Path

import pytest

from gclint.dialects import get
from gclint.engine import Linter, Options
from gclint.simulate import simulator_for
from gclint.simulate.trace import Move
from gclint.syntax.source import Source
from tests.conftest import CORPUS, SLOW, needs_corpus

SLOTS = [s for s in Move.__slots__ if s != "look"] + ["look"]


def _key(event) -> tuple:
    if type(event) is Move:
        return ("Move", *(getattr(event, s) for s in SLOTS))
    return (type(event).__name__, repr(event))


def _events(source: Source, dialect: str, quick: bool) -> tuple[list, object]:
    reader = simulator_for(get(dialect))
    if not quick:
        reader.fast_plain = lambda: False  # type: ignore[method-assign]
    events = [_key(e) for e in reader.events(source)]
    return events, reader.trace.end


CASES = {
    "relative moves and E": "G28\nG91\nG1 X10 Y5 E1 F1200\nG1 X-3 Z0.2\nG90\nM83\nG1 X1 E0.5\nG0 X2 Y3 E-0.2\n",
    "G92 and absolute E": "G28\nM82\nG92 X5 Y5 E10\nG1 X10 Y10 E11 F600\nG92 E0\nG1 X20 E0.5\nG1 E-1\nG1 E0\n",
    "inches": "G20\nG28\nG1 X1 Y1 E0.1 F60\nG21\nG1 X10 E1\n",
    "feed factor": "G28\nG1 X10 Y10 E1 F1200\nM220 S50\nG1 X20 E2\nG0 X0\nM220 S100\nG1 X5 E3\n",
    "G53 alone, then a move": "G28\nG54\nG92 X10\nG53\nG1 X5 Y5 E1 F600\nG1 X6\n",
    "unknown start": "G1 X10 Y10 E1 F1200\nG1 Z0.3\nG1 X11 Y12 E2\n",
    "tools": "T0\nG28\nG1 X1 Y1 E1 F900\nT1\nG1 X2 Y2 E2\nT0\nG1 X3 E3\n",
}


@pytest.mark.parametrize("dialect", ["marlin", "reprap"])
@pytest.mark.parametrize("name", sorted(CASES))
def test_the_quick_way_gives_the_same_events(name: str, dialect: str) -> None:
    text = CASES[name] + ("G10 P1 X5 Y-3\nT1\nG1 X4 Y4 E4\n" if dialect == "reprap" else "")
    quick = _events(Source.from_text(text), dialect, True)
    general = _events(Source.from_text(text), dialect, False)
    assert quick == general


def _corpus_jobs() -> list[Path]:
    if not CORPUS.is_dir():
        return []
    return sorted(p for p in (CORPUS / "marlin").rglob("*") if p.suffix == ".gcode") + sorted(
        p for p in (CORPUS / "reprap").rglob("*") if p.suffix in (".g", ".gcode")
    )


def _sample(path: Path, folder: Path) -> str:
    """The job, or its first 1,500 and last 500 lines (GCLINT_SLOW=1: all of it): the start and end G-code, the
    first layers and the last, where the states change."""
    lines = path.read_bytes().splitlines(keepends=True)
    if SLOW or len(lines) <= 2000:
        return str(path)
    copy = folder / path.name
    copy.write_bytes(b"".join(lines[:1500] + lines[-500:]))
    return str(copy)


@needs_corpus
def test_the_quick_way_gives_the_same_events_on_the_corpus(tmp_path: Path) -> None:
    differ = []
    for path in _corpus_jobs():
        job = _sample(path, tmp_path)
        dialect = Linter(Options()).context_of(Source.open(job, cut_long_lines=True)).dialect
        if dialect not in ("marlin", "reprap"):
            continue
        quick = _events(Source.open(job, cut_long_lines=True), dialect, True)
        general = _events(Source.open(job, cut_long_lines=True), dialect, False)
        if quick != general:
            differ.append(path.name)
    assert not differ
