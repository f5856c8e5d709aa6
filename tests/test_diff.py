"""``gclint diff``: the meaning diff of a job and its translation (gclint/simulate).

Three kinds of tests:

* rows in the manner of sqlglot: a source job and a *wrong* Hyrel output for it, and the aspect the
  diff must find (each row is a mistake issue 13 names, so the diff proves the translator does not make
  it any more);
* translations of the same jobs, which the diff must find equal, or different only where a warning-level
  TR finding says so;
* the corpus: every job of every flow, translated and diffed, with no unexplained difference.  By default
  each job is sampled (its first and last lines, a job of its own: both sides see the same text), so the
  test stays fast; ``GCLINT_SLOW=1`` diffs every job whole.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gclint import dialects
from gclint.simulate import Mapping, diff_sources
from gclint.simulate.compare import align
from gclint.simulate.trace import Look, Move
from gclint.simulate.translation import explanations_from
from gclint.syntax.source import Source
from gclint.translate import TranslationResult, translate_source, translator_for
from gclint.translate.options import TranslateOptions

from .conftest import CORPUS, SLOW, needs_corpus, run_cli, sample_bytes


def diff_texts(source_dialect: str, source: str, output: str, to: str = "hyrel", **settings: str):
    options = TranslateOptions()
    for key, value in settings.items():
        options.set(key.replace("_", "-"), value)
    return diff_sources(
        Source.from_text(source, "source"),
        Source.from_text(output, "output"),
        dialects.get(source_dialect),
        dialects.get(to),
        Mapping.from_options(options),
    )


def translate_and_diff(source_dialect: str, source: str, to: str = "hyrel", **settings: str):
    options = TranslateOptions()
    for key, value in settings.items():
        options.set(key.replace("_", "-"), value)
    src, dst = dialects.get(source_dialect), dialects.get(to)
    result = TranslationResult("t.gcode", src.name, dst.name)
    text = "".join(translate_source(Source.from_text(source, "t"), translator_for(src, dst, options), result))
    diff = diff_sources(
        Source.from_text(source, "source"),
        Source.from_text(text, "output"),
        src,
        dst,
        Mapping.from_options(options),
        explanations_from(result),
    )
    return text, result, diff


# -- the diff finds the mistakes of issue 13 ----------------------------------------------------------------


@dataclass(frozen=True)
class Wrong:
    """A source job, a wrong Hyrel translation of it, and the aspect the diff must report."""

    item: str
    dialect: str
    source: str
    output: str
    aspect: str
    settings: dict = field(default_factory=dict)


def _chords(radius_in: float, segments: int) -> str:
    """A full circle of ``radius_in`` inches (centre at X=radius) as ``segments`` chords, in mm."""
    lines = []
    for k in range(1, segments + 1):
        a = math.pi - 2 * math.pi * k / segments
        x = (radius_in + radius_in * math.cos(a)) * 25.4
        y = radius_in * math.sin(a) * 25.4
        lines.append(f"G1 X{x:.4f} Y{y:.4f}")
    return "\n".join(lines)


SINGLE_NOZZLE = "M104 S215\nM109 S215\nG90\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nT2\nG1 X2 Y2 E1\nG1 X3 Y3 E1\n"
DUAL = (
    "M104 T0 S210\nM104 T1 S210\nM109 T0 S210\nM109 T1 S210\nG90\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\n"
    "M106 S255\nG1 X2 Y2 E1\nT1\nG1 X3 Y3 E1\nM107\n"
)
WRONG = [
    Wrong(
        "2: a single-nozzle job prints with a head it never heated",
        "marlin",
        SINGLE_NOZZLE,
        "M104 T0 S215\nM109 T0 S215\nG90\nM229 E1 D1\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nT2\nG1 X2 Y2 E1\n"
        "G1 X3 Y3 E1\nM30\n",
        "temp",
    ),
    Wrong(
        "4: the part fan stays on the old head",
        "marlin",
        DUAL,
        "M104 T0 S210\nM104 T1 S210\nM109 T0 S210\nM109 T1 S210\nG90\nM229 E1 D1\nM83\nT0\n"
        "G1 X1 Y1 Z0.2 E1 F600\nM106 C255\nM106 T0 S255\nG1 X2 Y2 E1\nT1\nG1 X3 Y3 E1\nM107 T1\nM30\n",
        "fan",
    ),
    Wrong(
        "4: the final M107 switches off one head only",
        "marlin",
        DUAL,
        "M104 T0 S210\nM104 T1 S210\nM109 T0 S210\nM109 T1 S210\nG90\nM229 E1 D1\nM83\nT0\n"
        "G1 X1 Y1 Z0.2 E1 F600\nM106 C255\nM106 T0 S255\nG1 X2 Y2 E1\nT1\nM106 T1 S255\nG1 X3 Y3 E1\n"
        "M107 T1\nM30\n",
        "end",
    ),
    Wrong(
        "2: a head left hot at the end",
        "marlin",
        SINGLE_NOZZLE + "M104 S0\n",
        "M104 T0 S215\nM109 T0 S215\nG90\nM229 E1 D1\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nT2\nM109 T2 S215\n"
        "G1 X2 Y2 E1\nG1 X3 Y3 E1\nM104 T2 S0\nM30\n",
        "end",
    ),
    Wrong(
        "3: an inch circle cut into 12 chords (the tolerance applied in inches)",
        "machinekit",
        "G20\nG90\nG0 X0 Y0 Z0\nG1 F10\nG2 X0 Y0 I0.5 J0\nM2\n",
        "G21\nG90\nG54\nT0\nG0 X0 Y0 Z0\nG1 F254\n" + _chords(0.5, 12) + "\nM30\n",
        "path",
    ),
    Wrong(
        "1: the passes after the Carvera's first M30 are lost",
        "carvera",
        "G90\nG54\nG1 X1 F100\nM30\nG1 X2\nG1 X3\nM30\n",
        "G90\nG54\nT0\nG1 X1 F100\nM30\n",
        "moves",
    ),
    Wrong(
        "8: a Machinekit job written with E (the extruder is A) extrudes on Hyrel",
        "machinekit",
        "G90\nG1 X1 Y1 F600\nG1 X2 Y2 E1\n",
        "G90\nG54\nT0\nG1 X1 Y1 F600\nM229 E1 D1\nM82\nG1 X2 Y2 E1\nM30\n",
        "e",
    ),
    Wrong(
        "9: G53 moves switch on stored G54 offsets for the rest of the job",
        "marlin",
        "G90\nM83\nG1 X1 Y1 Z0.2 E1 F600\nG53 G1 X5 Y5\nG1 X6 Y6 E1\n",
        "G90\nM229 E1 D1\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nG53\nG1 X5 Y5\nG54\nG1 X6 Y6 E1\nM30\n",
        "wcs",
    ),
    Wrong(
        "9: Marlin M3 O128 loses its power",
        "machinekit",  # a CNC job: every feed move is compared (the spindle's power on it)
        "G90\nM3 S1000\nG1 X1 F100\n",
        "G90\nG54\nT0\nM3 T0 S50\nG1 X1 F100\nM30\n",
        "spindle",
        {"spindle_max_rpm": "1000"},
    ),
    Wrong(
        "9: a move after a tool Hyrel does not have goes on with the head before it",
        "marlin",
        "M104 T0 S200\nM104 T1 S200\nG90\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nT9\nG1 X2 Y2 E1\n",
        "M104 T0 S200\nM104 T1 S200\nG90\nM229 E1 D1\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nG1 X2 Y2 E1\nM30\n",
        "head",
    ),
]


@pytest.mark.parametrize("row", WRONG, ids=[w.item for w in WRONG])
def test_diff_finds_the_wrong_translation(row: Wrong) -> None:
    result = diff_texts(row.dialect, row.source, row.output, **row.settings)
    assert row.aspect in {d.aspect for d in result.differences}, [d.to_dict() for d in result.differences]


@pytest.mark.parametrize("row", WRONG, ids=[w.item for w in WRONG])
def test_the_translation_has_no_unexplained_difference(row: Wrong) -> None:
    """The translator's own output for the same source: equal, or different where a TR finding says so."""
    _, result, diff = translate_and_diff(row.dialect, row.source, **row.settings)
    unexplained = [d.to_dict() for d in diff.unexplained()]
    assert not unexplained, unexplained
    for d in diff.differences:
        code = d.explained_by[0]  # type: ignore[index]
        assert any(f.code == code and f.severity.label in ("warning", "error") for f in result.findings)


def test_translation_equal_in_meaning() -> None:
    text, result, diff = translate_and_diff("marlin", DUAL)
    assert diff.differences == [] and diff.pairs == 3
    assert "M107 T0\nM106 T1 S255\nG1 X3 Y3 E1" in text  # the part fan follows the tool
    assert text.splitlines()[-2:] == ["M107 T1", "M30"]


def test_single_nozzle_job_heats_every_head_it_prints_with() -> None:
    text, result, diff = translate_and_diff("marlin", SINGLE_NOZZLE + "M104 S0\n")
    lines = text.splitlines()
    assert lines[lines.index("T2") + 1] == "M109 T2 S215"  # waited for, as the nozzle was
    assert lines[-3:] == ["M104 T2 S0", "M104 T0 S0", "M30"]  # the nozzle is off on every head
    assert diff.differences == []


def test_inch_arcs_keep_the_tolerance_in_mm() -> None:
    # a 1-inch circle in the XZ plane becomes segments: at most 0.02 mm from the arc
    text, _, diff = translate_and_diff("machinekit", "G20\nG90\nG18\nG0 X0 Y0 Z0\nG1 F10\nG2 X0 Z0 I0.5 K0\nM2\n")
    assert not [d for d in diff.differences if d.aspect == "path"]
    assert sum(1 for line in text.splitlines() if line.startswith("G1 X")) > 60
    # in the XY plane it stays an arc, in mm
    text, _, diff = translate_and_diff("machinekit", "G20\nG90\nG0 X0 Y0 Z0\nG1 F10\nG2 X0 Y0 I0.5 J0\nM2\n")
    assert "G2 X0 Y0 I12.7 J0" in text.splitlines() and diff.differences == []


def test_explained_differences_name_their_finding() -> None:
    text, result, diff = translate_and_diff(
        "marlin", "M104 T0 S200\nG90\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nT9\nG1 X2 Y2 E1\n"
    )
    head = [d for d in diff.differences if d.aspect == "head"]
    assert head and head[0].explained_by == ("TR007", 6)
    assert "the head that was printing (T0) goes on printing for it" in result.findings[0].message


# -- the command line ------------------------------------------------------------------------------------


def test_cli_diff_exit_codes(tmp_path: Path) -> None:
    source = tmp_path / "dual.gcode"
    source.write_text(DUAL)
    good = tmp_path / "good.gcode"
    translated = run_cli("translate", "--from", "marlin", "--to", "hyrel", str(source), "-o", str(good))
    assert translated.returncode == 0
    same = run_cli("diff", str(source), str(good), "--from", "marlin", "--to", "hyrel")
    assert same.returncode == 0, same.stdout + same.stderr
    assert b"0 differences over 3 matched working moves (0 unexplained)." in same.stdout
    piped = run_cli("diff", "-", str(good), "--from", "marlin", "--to", "hyrel", input=DUAL.encode())
    assert piped.returncode == 0, piped.stderr  # standard input is read once, translated and simulated
    bad = tmp_path / "bad.gcode"
    bad.write_text(WRONG[1].output)
    differs = run_cli("diff", str(source), str(bad), "--from", "marlin", "--to", "hyrel", "--format", "json")
    assert differs.returncode == 1
    data = json.loads(differs.stdout)
    assert data["unexplained"] >= 1 and {d["aspect"] for d in data["differences"]} >= {"fan"}
    assert data["differences"][0]["explained_by"] is None
    # usage errors and unreadable files: exit 2, one line, no traceback
    for args in (
        ("diff", str(source), str(tmp_path / "missing.gcode"), "--from", "marlin", "--to", "hyrel"),
        ("diff", str(source), str(good), "--from", "nonsense", "--to", "hyrel"),
        ("diff", str(source), str(good), "--from", "marlin", "--to", "marlin"),
        ("diff", str(source), str(good), "--from", "marlin", "--to", "hyrel", "--tool-map", "0=T24"),
    ):
        run = run_cli(*args)
        assert run.returncode == 2, args
        assert b"Traceback" not in run.stderr and len(run.stderr.strip().splitlines()) == 1, run.stderr


def test_cli_diff_fail_on_unexplained(tmp_path: Path) -> None:
    source = tmp_path / "t9.gcode"
    source.write_text("M104 T0 S200\nG90\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nT9\nG1 X2 Y2 E1\n")
    out = tmp_path / "out.gcode"
    assert run_cli("translate", "--from", "marlin", "--to", "hyrel", str(source), "-o", str(out)).returncode == 0
    assert run_cli("diff", str(source), str(out), "--from", "marlin", "--to", "hyrel").returncode == 1
    run = run_cli("diff", str(source), str(out), "--from", "marlin", "--to", "hyrel", "--fail-on", "unexplained")
    assert run.returncode == 0, run.stdout
    assert b"[explained by TR007" in run.stdout


# -- the corpus --------------------------------------------------------------------------------------------

EXTENSIONS = (".gcode", ".g", ".nc", ".ngc", ".cnc", ".tap")


@dataclass(frozen=True)
class Flow:
    """A corpus folder translated from ``dialect`` with ``settings``.  ``small``: each job read as a smaller
    sample (its first 1,000 and last 300 lines; the options' flows, to stay fast); ``to_machinekit``: Marlin
    jobs first turned into Machinekit ones by Machinekit's own filter (tests/mutations.gcode_to_ngc), the
    Machinekit print jobs the corpus does not have."""

    folder: str
    dialect: str
    settings: tuple[tuple[str, str], ...] = ()
    small: bool = False
    to_machinekit: bool = False

    @property
    def name(self) -> str:
        extra = ",".join(f"{k}={v}" for k, v in self.settings) or "evalues"
        return f"{self.folder}-{'gcode-to-ngc' if self.to_machinekit else self.dialect}-{extra}"


# Every translation option, each in a flow where it matters
FLOWS = [
    Flow("marlin", "marlin"),
    Flow("marlin", "marlin", (("flow", "native"),)),
    Flow("marlin", "marlin", (("retract", "explicit"),), small=True),
    Flow("marlin", "marlin", (("max-feed", "convert"), ("home-z", "on"), ("printer", "ehr")), small=True),
    Flow(
        "marlin",
        "marlin",
        (("tool-map", "0=T1,1=T0"), ("fan-map", "2=T22"), ("bed", "T25"), ("temp-window", "5")),
        small=True,
    ),
    Flow(
        "marlin",
        "marlin",
        (("spindle-max-rpm", "10000"), ("spindle-stop-dwell", "2"), ("spindle", "T3"), ("laser", "T21")),
        small=True,
    ),
    Flow("reprap", "reprap"),
    Flow("reprap", "reprap", (("flow", "native"),)),
    Flow("reprap", "reprap", (("tool-offsets", "m6"), ("chamber", "T25")), small=True),
    Flow("reprap", "reprap", (("retract", "explicit"), ("spindle-max-rpm", "10000")), small=True),
    Flow("machinekit", "machinekit"),
    Flow("machinekit", "machinekit", (("flow", "native"),)),
    Flow("machinekit", "machinekit", (("retract", "explicit"), ("spindle-max-rpm", "10000")), small=True),
    Flow("linuxcnc", "machinekit"),
    Flow("linuxcnc", "machinekit", (("flow", "native"),), small=True),
    Flow("linuxcnc", "machinekit", (("spindle-max-rpm", "10000"), ("spindle-stop-dwell", "2")), small=True),
    Flow("carvera", "carvera"),
    Flow("carvera", "carvera", (("spindle-max-rpm", "12000"), ("air", "M685"), ("laser", "T21")), small=True),
    Flow("carvera", "carvera", (("air", "M8"), ("tool-map", "1=T1,2=T2,3=T3")), small=True),
    Flow("hyrel", "hyrel-v4"),
    Flow("other", "marlin", small=True),
    Flow("marlin", "machinekit", small=True, to_machinekit=True),
    Flow("marlin", "machinekit", (("flow", "native"),), small=True, to_machinekit=True),
    Flow("marlin", "machinekit", (("retract", "explicit"),), small=True, to_machinekit=True),
]

# Differences the diff reports that are not changes of meaning, with why: (folder-relative job, part of a flow's
# name, aspect) -> why.  (Each entry is needed: with it removed, the test fails.)
_SHIFTED = (
    "a plasma job: its G0 that moves A (read as the extruder) is a working move in the output (TR003), so the moves "
    "before the first cut pair one off and the M3 pairs with the move before it"
)
KNOWN = {
    **{
        ("linuxcnc/linuxcnc/nc_files/plasmac/metric_pipe.ngc", flow, "spindle"): _SHIFTED
        for flow in ("linuxcnc-machinekit-evalues", "native", "spindle-max-rpm")
    },
    ("linuxcnc/linuxcnc/nc_files/plasmac/metric_pipe.ngc", "native", "layer"): (
        "a G0 that moves A is written as a printing G1 (TR003 on that line): its Z is taken as a layer height (50 mm)"
    ),
}


def _jobs(folder: str) -> list[Path]:
    out = []
    for base, _, names in os.walk(CORPUS / folder):
        for name in names:
            if name.lower().endswith(EXTENSIONS) or (folder == "reprap" and "." not in name):
                out.append(Path(base) / name)
    return sorted(out)


def _sample(path: Path, small: bool = False) -> bytes | None:
    data = path.read_bytes()
    if b"\0" in data[:4096]:
        return None  # binary (the translator refuses it)
    if small and not SLOW:
        lines = data.splitlines(keepends=True)
        if len(lines) > 1300:
            data = b"".join(lines[:1000] + lines[-300:])
    return sample_bytes(data)


@needs_corpus
@pytest.mark.parametrize("flow", FLOWS, ids=[f.name for f in FLOWS])
def test_corpus_translations_have_no_unexplained_difference(flow: Flow) -> None:
    from .mutations import gcode_to_ngc

    src, dst = dialects.get(flow.dialect), dialects.get("hyrel")
    problems = []
    jobs = 0
    for path in _jobs(flow.folder):
        data = _sample(path, flow.small)
        if data is None:
            continue
        options = TranslateOptions()
        for key, value in flow.settings:
            options.set(key, value)
        try:
            source = Source.from_bytes(data, str(path))
            if flow.to_machinekit:
                text = "".join(raw + ending for chunk in source.chunks() for raw, ending in chunk)
                data = gcode_to_ngc(text).encode("utf-8", "surrogateescape")
                source = Source.from_bytes(data, str(path))
        except Exception:  # not G-code (the translator refuses it too)
            continue
        result = TranslationResult(str(path), src.name, dst.name)
        text = "".join(translate_source(source, translator_for(src, dst, options), result))
        diff = diff_sources(
            Source.from_bytes(data, str(path)),
            Source.from_text(text, "output"),
            src,
            dst,
            Mapping.from_options(options),
            explanations_from(result),
        )
        jobs += 1
        job = str(path.relative_to(CORPUS))
        for d in diff.unexplained():
            if not any(k[0] == job and k[1] in flow.name and k[2] == d.aspect for k in KNOWN):
                problems.append(f"{job}:{d.source_line}: {d.aspect}: {d.source} -> {d.output}")
    assert jobs > 0
    assert not problems, "\n".join(problems[:20])


# -- the alignment always ends -----------------------------------------------------------------------------

_points = st.lists(st.tuples(st.integers(0, 4), st.integers(0, 4)), max_size=40)


def _moves(points: list[tuple[int, int]]) -> list[Move]:
    out, previous = [], (0.0, 0.0, 0.0, None, None)
    for n, (x, y) in enumerate(points, 1):
        end = (float(x), float(y), 0.0, None, None)
        out.append(Move(n, previous, end, None, 1.0, 1200.0, Look()))
        previous = end
    return out


@settings(max_examples=200, deadline=None)
@given(source=_points, output=_points)
def test_alignment_consumes_both_sides(source, output) -> None:
    """Whatever the two jobs, every move of each is accounted for exactly once (and the walk ends)."""
    src, out = _moves(source), _moves(output)
    seen_src, seen_out = [], []
    for s, run, _ in align(src, out):
        if s is not None:
            seen_src.append(s.line)
        seen_out.extend(m.line for m in run)
    assert seen_src == [m.line for m in src] and seen_out == [m.line for m in out]


def test_cli_diff_error_lines_escape_file_names(tmp_path: Path) -> None:
    """Issue 25: a file name's escape sequences reached the terminal raw in diff's error lines."""
    source = tmp_path / "x\x1b[31mred.gcode"
    source.write_text("G28\nG1 X1 F600\n")
    proc = run_cli("diff", str(source), str(tmp_path / "gone\x1b[2J.gcode"), "--from", "marlin", "--to", "hyrel")
    assert proc.returncode == 2 and b"\x1b" not in proc.stderr and b"gone\\x1b[2J.gcode" in proc.stderr, proc.stderr


def test_cli_diff_reads_the_source_as_its_firmware(tmp_path: Path) -> None:
    """The diff reads SOURCE with the firmware the job says it was written for, as translate does: a Machinekit
    FDM job (M104 P, M140 P) homes with its g28.ngc remap (moves to 0), not LinuxCNC's stored position."""
    source = tmp_path / "fdm.ngc"
    source.write_text("M140 P60\nM104 P200\nG28 XY\nG1 X10 Y10 A1 F1000\nG28 Z\nG1 X20 Y10 A2\nM2\n")
    out = tmp_path / "fdm.hy.gcode"
    assert run_cli("translate", "--from", "machinekit", "--to", "hyrel", str(source), "-o", str(out)).returncode == 0
    run = run_cli("diff", str(source), str(out), "--from", "machinekit", "--to", "hyrel")
    assert run.returncode == 0 and b"0 differences" in run.stdout, run.stdout


def test_cli_diff_escapes_file_names_in_its_report(tmp_path: Path) -> None:
    source = tmp_path / "x\x1b[31mred.gcode"
    source.write_text(DUAL)
    bad = tmp_path / "bad\x1b[2J.gcode"
    bad.write_text(WRONG[1].output)
    proc = run_cli("diff", str(source), str(bad), "--from", "marlin", "--to", "hyrel")
    assert proc.returncode == 1 and b"\x1b" not in proc.stdout and b"bad\\x1b[2J.gcode" in proc.stdout, proc.stdout
