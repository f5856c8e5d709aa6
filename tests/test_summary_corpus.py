"""Issue 28: the summary against what the slicers say of their own jobs, over the whole corpus.

* Time: every corpus job that states the slicer's estimate, read here with patterns of this test's own.  The
  median job within 5 % of its slicer's estimate, each within 15 %.  What an estimate covers is the slicer's:
  PrusaSlicer and its forks (SuperSlicer, OrcaSlicer, BambuStudio) estimate the finished file, start and end
  G-code included (their GCodeProcessor reads the G-code they wrote: the first ``M73 ... R`` is the whole); the
  others estimate their own toolpaths, the layers, and not the start and end G-code the user wrote (Cura: its
  last ``;TIME_ELAPSED`` equals ``;TIME``; KISSlicer lists its path types, and "not including Z-travel").  So
  the summary's time of the layers is compared with theirs, where the job marks its layers.
* Layers: every corpus job with slicer layer marks, counted here with patterns of this test's own: the summary
  counts as many layers, and its Z range is the heights the marks state, where they state one.

Reading the corpus takes about ten seconds of one core, so the summaries are kept in pytest's cache, keyed by
the job's bytes and gclint's own sources: a run after a change to neither reads them back.
"""

from __future__ import annotations

import hashlib
import re
import statistics
from functools import cache
from pathlib import Path

import pytest

from gclint.summary import summarize_path
from tests.conftest import CORPUS, ROOT, needs_corpus

JOBS = (".gcode", ".gco", ".g")


def _hms(text: str) -> float:
    return sum(int(n) * {"d": 86400, "h": 3600, "m": 60, "s": 1}[u] for n, u in re.findall(r"(\d+)\s*([dhms])", text))


# the slicers' estimates: (pattern, seconds from its groups, what it covers)
ESTIMATES = [
    (r"^; estimated printing time \(normal mode\) = (.+)$", _hms, "file"),
    (r"^; model printing time: .*; total estimated time: (.+)$", _hms, "file"),
    (r"^;TIME:(\d+)\s*$", float, "layers"),
    (r"^;PRINT\.TIME:(\d+)\s*$", float, "layers"),
    (r"^;Print Time: ([\d.]+)\s*$", float, "layers"),
    (r"^; Estimated Build Time:\s+([\d.]+) minutes", lambda m: float(m) * 60, "layers"),
    (r"^;\s+Build time: (\d+) hours? (\d+) minutes?", lambda h, m: (int(h) * 60 + int(m)) * 60, "layers"),
    (r"^;Print time: (\d+) minutes", lambda m: float(m) * 60, "layers"),
    (r"^;Print time:\s+(\d+):(\d\d)\s*$", lambda h, m: (int(h) * 60 + int(m)) * 60, "layers"),
]

# the slicers' layer marks: (pattern, the group holding the height the mark states, or the pattern of the
# comment after it that does)
MARKS = [
    (r"^;LAYER_CHANGE\s*$", r"^;Z:([\d.]+)"),
    (r"^; CHANGE_LAYER\s*$", r"^; Z_HEIGHT: ([\d.]+)"),
    (r"^;LAYER:-?\d+\s*$", None),
    (r"^; layer \d+, Z ?= ?([\d.]+)\s*$", 1),
    (r"^; BEGIN_LAYER_(?:OBJECT|RAFT) z=([\d.]+)", 1),
]

# Jobs whose estimate is not of what the file holds, each with what shows it (checked below)
NO_MOVES = {  # a header whose moves were taken out: the estimate is of a print the file does not hold
    "cura-4.13.1_octoprint-autoprint_test_heating.gcode",
    "cura-4.2.1_tiny.gcode",
    "cura-4.5.0_griffin_UM3_test.gcode",
}
CUT = {  # a sample: layers taken out of the middle (;LAYER_COUNT:51, ten ;LAYER: marks; the time jumps)
    "cura-3.2.1_fast_sample.gcode",
}


def _code() -> str:
    digest = hashlib.sha256()
    for path in sorted((ROOT / "gclint").rglob("*")):
        if path.suffix in (".py", ".lark") and path.is_file():
            digest.update(path.read_bytes())
    return digest.hexdigest()


@cache
def _code_hash() -> str:
    return _code()


@pytest.fixture(scope="module")
def summary_of(request):
    """The summary's numbers this test reads, from pytest's cache when neither the job nor gclint changed."""
    store = getattr(request.config, "cache", None)

    def get(path: Path) -> dict:
        key = hashlib.sha256(path.read_bytes()).hexdigest() + _code_hash()
        name = "gclint-summary/" + re.sub(r"[^\w.-]", "_", str(path.relative_to(CORPUS)))
        kept = store.get(name, None) if store is not None else None
        if kept and kept.get("key") == key:
            return kept["summary"]
        s = summarize_path(str(path))
        found = {
            "time": s.time_s,
            "layers_time": s.layers_time_s,
            "layers": s.layers,
            "marks": s.layer_marks,
            "z_range": list(s.z_range) if s.z_range else None,
            "printing_moves": sum(h.printing_moves for h in s.heads),
        }
        if store is not None:
            store.set(name, {"key": key, "summary": found})
        return found

    return get


def _jobs() -> list[Path]:
    return sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in JOBS and p.is_file())


def _estimate(text: str) -> tuple[float, str] | None:
    for pattern, seconds, covers in ESTIMATES:
        m = re.search(pattern, text, re.M)
        if m:
            return seconds(*m.groups()), covers
    return None


def _layer_times(text: str) -> list[float]:
    """Cura's time of each layer, from its ``;TIME_ELAPSED`` (the time when each layer ends)."""
    ends = [float(t) for t in re.findall(r"^;TIME_ELAPSED:([\d.]+)", text, re.M)]
    return [b - a for a, b in zip([0.0, *ends], ends, strict=False)]


def _resets_e_mid_layer(block: str) -> bool:
    """A ``G92 E0`` between two moves that extrude, in one layer's lines."""
    extruding = [bool(re.match(r"G1 .*E\d", line)) for line in block.splitlines()]
    resets = [i for i, line in enumerate(block.splitlines()) if line.strip() == "G92 E0"]
    return any(any(extruding[:i]) and any(extruding[i:]) for i in resets)


def _slicers_estimate(text: str, estimate: float) -> tuple[float, int]:
    """The slicer's estimate with what its own per-layer times show to be an artefact taken out, and how many layers
    had one: Cura counts a ``G92 E0`` in the middle of a layer as a long move of the extruder
    (cura-4.10.0_kreistest: the two layers holding one take 285 s in its ;TIME_ELAPSED, its eight others, the
    same path, 77.5 s each).  Such a layer counts as long as the usual one."""
    layers = _layer_times(text)
    if len(layers) < 5:
        return estimate, 0
    usual = statistics.median(layers)
    blocks = re.split(r"^;TIME_ELAPSED:[\d.]+\s*$", text, flags=re.M)
    extra, fixed = 0.0, 0
    for i, (took, block) in enumerate(zip(layers, blocks, strict=False)):
        # (not the first: the start G-code before it resets E too)
        if i and took > 2 * usual and _resets_e_mid_layer(block):
            extra += took - usual
            fixed += 1
    return estimate - extra, fixed


@needs_corpus
def test_print_time_against_the_slicers_own_estimates(summary_of) -> None:
    rows = []
    no_moves, cut = set(), set()
    corrected: dict[str, int] = {}
    for path in _jobs():
        text = path.read_text(errors="replace")
        stated = _estimate(text)
        if stated is None:
            continue
        estimate, covers = stated
        s = summary_of(path)
        if not s["printing_moves"]:
            no_moves.add(path.name)
            continue
        if path.name in CUT:
            count = int(re.search(r"^;LAYER_COUNT:(\d+)", text, re.M).group(1))
            assert len(re.findall(r"^;LAYER:\d+", text, re.M)) < count / 2
            cut.add(path.name)
            continue
        estimate, fixed = _slicers_estimate(text, estimate)
        if fixed:
            corrected[path.name] = fixed
        ours = s["layers_time"] if covers == "layers" and s["layers_time"] is not None else s["time"]
        rows.append((path.relative_to(CORPUS), estimate, ours, (ours - estimate) / estimate))
    assert no_moves == NO_MOVES and cut == CUT and corrected == {"cura-4.10.0_kreistest.gcode": 2}
    table = "\n".join(f"{str(p):70} {e:8.0f} s {o:8.0f} s {d:+7.1%}" for p, e, o, d in rows)
    assert len(rows) >= 25, table
    errors = [abs(d) for *_, d in rows]
    assert statistics.median(errors) <= 0.05, table
    assert max(errors) <= 0.15, table


@needs_corpus
def test_layers_against_the_slicers_marks(summary_of) -> None:
    checked = 0
    problems = []
    for path in _jobs():
        text = path.read_text(errors="replace")
        found = next(((p, h, m) for p, h in MARKS if (m := list(re.finditer(p, text, re.M)))), None)
        if found is None:
            continue
        pattern, height, marks = found
        heights: list[float] = []
        if height == 1:
            heights = [float(m.group(1)) for m in marks]
        elif height is not None:
            heights = [float(z) for z in re.findall(height, text, re.M)]
        count = len(marks)
        if pattern.startswith("^; BEGIN_LAYER"):  # KISSlicer marks each object's part of a layer
            count = len([z for i, z in enumerate(heights) if i == 0 or z != heights[i - 1]])
        s = summary_of(path)
        checked += 1
        if s["layers"] != count:
            problems.append(f"{path.name}: {s['layers']} layers, {count} marks")
        if heights and s["z_range"] != [heights[0], heights[-1]]:
            problems.append(f"{path.name}: Z {s['z_range']}, marks {heights[0]} to {heights[-1]}")
    assert checked >= 25 and not problems, "\n".join(problems)


@needs_corpus
@pytest.mark.parametrize(
    ("name", "layers"),
    [  # the jobs issue 28 names, with their counts before (45, 5470, 108, 120 and 1)
        ("cura-2.3.1_puzzle.gcode", 119),
        ("prusaslicer-2.7.4_vase.gcode", 334),  # a spiral vase: its slicer's layers
        ("prusaslicer-2.8.0-alpha4_mmu_attribute_test.gcode", 206),
        ("bambustudio-01.07.06.92_xmas_pud_plate_1.gcode", 137),
        ("prusaslicer-2.8.1_mini_cube.gcode", 31),
    ],
)
def test_the_jobs_issue_28_names(summary_of, name: str, layers: int) -> None:
    assert summary_of(CORPUS / "marlin" / name)["layers"] == layers
