"""Issue 24: every consumer reads a file's meaning from one model, and they agree.

Over the corpus (each job read as ``gclint check`` reads it, with no flags), and on the dwell the issue names:

* every dwell: the reader's events (``gclint.simulate``: the diff's simulator, the summary and the toolpath read
  them), ``explain`` (each G4's ``seconds``), the summary's dwell total, and the translator (its Hyrel output,
  read back, pauses as long);
* every move: where the rules' machine state (``gclint.machine.Interpreter``, the engine's hot path) puts the tool
  after each line, and where the reader does;
* every set-point: each one the reader reports is one the rules' state holds after its line.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from gclint import dialects
from gclint.context import infer_source
from gclint.explain.explainer import explain_source
from gclint.machine.interpreter import Interpreter
from gclint.simulate import simulator_for
from gclint.simulate.events import Dwell, Heat, Move
from gclint.summary import summarize
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source, SourceError
from gclint.translate import TranslationResult, translate_source, translator_for
from gclint.translate.pairs import TO_HYREL
from tests.conftest import CORPUS, corpus_job, needs_corpus

_TEXT = (".gcode", ".gco", ".g", ".nc", ".ngc", ".cnc", ".tap", ".test")


def _jobs() -> list[Path]:
    if not CORPUS.is_dir():
        return []
    return sorted(p for p in CORPUS.rglob("*") if p.is_file() and p.suffix.lower() in _TEXT and p.stat().st_size)


def _read(path: str, dialect):
    reader = simulator_for(dialect)
    dwells: dict[int, float] = {}
    points: dict[int, tuple] = {}
    heats: list[tuple[int, float]] = []
    for event in reader.events(Source.open(path)):
        kind = type(event)
        if kind is Dwell and event.seconds is not None:
            dwells[event.line] = dwells.get(event.line, 0.0) + event.seconds
        elif kind is Move and event.point:
            points[event.line] = event.point
        elif kind is Heat:
            heats.append((event.line, event.value))
    return dwells, points, heats


def _close(a: float | None, b: float | None) -> bool:
    return a is None or b is None or math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-6)


@needs_corpus
@pytest.mark.parametrize("job", _jobs(), ids=lambda p: str(p.relative_to(CORPUS)))
def test_the_consumers_agree(job: Path, tmp_path: Path) -> None:
    path = corpus_job(job)
    try:
        context = infer_source(Source.open(path), path)
    except SourceError:
        pytest.skip("not a text job")
    dialect = dialects.get(context.dialect)
    dwells, points, heats = _read(path, dialect)
    problems: list[str] = []

    # explain: the same seconds on the same lines
    explained: dict[int, float] = {}
    for exp in explain_source(Source.open(path), dialect):
        if exp.seconds is not None:
            explained[exp.line] = explained.get(exp.line, 0.0) + exp.seconds
    if explained != pytest.approx(dwells):
        problems.append(f"explain dwells {explained} != reader dwells {dwells}")

    # the summary: the reader's dwells, all of them
    summary = summarize(Source.open(path), context)
    if not _close(summary.dwell_s, sum(dwells.values())):
        problems.append(f"summary dwell {summary.dwell_s} != {sum(dwells.values())}")

    # the rules' state: where each line's move takes the tool, on the axes the line names in absolute mode (the
    # rules' state does not carry head offsets: an axis a move leaves alone may be elsewhere under a new head),
    # and its set-points
    interpreter = Interpreter(dialect)
    state = interpreter.state
    running = dialect.semantics.running
    targets_by_line: dict[int, set[float]] = {}
    wanted = {line for line, _ in heats}
    source = Source.open(path)
    number = 0
    for chunk in source.chunks():
        for raw, ending in chunk:
            number += 1
            if state.after_m30 and interpreter.semantics.effects.get("M30") != "end-of-job":
                break
            parsed = parse_line(raw)
            line = Line(number, raw, ending, parsed)
            named: set[str] = set()
            for cmd in running(parsed.commands):
                interpreter.apply(cmd, line)
                named.update(a for a in "XYZ" if a in cmd.params)
            if number in wanted:
                targets_by_line[number] = set(state.targets.values())
            point = points.get(number)
            if point is None or state.units != "mm" or not state.absolute:
                continue
            for i, axis in enumerate("XYZ"):
                if axis not in named:
                    continue
                mine = state.position.get(axis)
                if mine is not None and point[i] is not None and not _close(mine, point[i]):
                    problems.append(f"line {number}: {axis} {mine} (rules) != {point[i]} (reader): {raw.strip()[:60]}")
                    break
            if len(problems) > 10:
                break
    for line, value in heats:
        held = targets_by_line.get(line, set())
        if value not in held:
            problems.append(f"line {line}: the reader's set-point {value} is not in the rules' state {sorted(held)}")
            if len(problems) > 20:
                break

    # the translator: its Hyrel output pauses as long as the source
    if dialect.name in TO_HYREL and dwells:
        translated = tmp_path / "translated.gcode"
        translated.write_text(_translated(path, dialect))
        back = sum(_read(str(translated), dialects.get("hyrel"))[0].values())
        if not _close(back, sum(dwells.values())):
            problems.append(f"translated dwell {back} != source {sum(dwells.values())}")
    assert not problems, "\n".join(problems[:20])


def _translated(path: str, dialect) -> str:
    translator = translator_for(dialect, dialects.get("hyrel"))
    result = TranslationResult(path, dialect.name, "hyrel")
    return "".join(translate_source(Source.open(path), translator, result))


@pytest.mark.parametrize(
    ("dialect", "seconds"),
    [("hyrel", 1.5), ("hyrel-v4", 1.5), ("marlin", 1.0), ("reprap", 1.0), ("machinekit", 500.0), ("carvera", 501.0)],
)
def test_one_dwell_per_dialect(tmp_path: Path, dialect: str, seconds: float) -> None:
    """``G4 S1 P500``: Hyrel adds S and P ("if you use both, the total value will be the pause duration"), Marlin
    and RepRapFirmware count S alone, LinuxCNC's P is seconds and S the spindle speed, Smoothieware in grbl mode
    adds S seconds to P seconds.  The same number in the reader, explain, the summary and the translation."""
    job = tmp_path / "dwell.gcode"
    job.write_text("G4 S1 P500\n")
    read_as = dialects.get(dialect)
    dwells, _, _ = _read(str(job), read_as)
    assert dwells == {1: seconds}
    [exp] = [e for e in explain_source(Source.open(str(job)), read_as) if e.code == "G4"]
    assert exp.seconds == seconds
    context = infer_source(Source.open(str(job)), str(job), dialect=dialect)
    assert summarize(Source.open(str(job)), context).dwell_s == seconds
    if read_as.name in TO_HYREL:
        back = tmp_path / "back.gcode"
        back.write_text(_translated(str(job), read_as))
        assert _read(str(back), dialects.get("hyrel"))[0] == {2: seconds}  # (after the line saying what it is)
