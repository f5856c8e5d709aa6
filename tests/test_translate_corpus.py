"""Every marlin, reprap, machinekit and carvera job of the corpus translates to Hyrel, and the output
passes gclint's Hyrel check with no error-level finding.

What a translation cannot carry over is reported as TR findings (and dropped from the output, X1), so the
Hyrel output itself must be clean.  ``ALLOWED`` would list an error the checker keeps finding on purpose,
with the TR finding that explains it; it is empty.
"""

from __future__ import annotations

import os
from collections import Counter
from pathlib import Path

import pytest

from gclint import dialects
from gclint.dialects.hyrel import HYREL_CODES
from gclint.engine import Linter, Options
from gclint.rules.base import Severity
from gclint.syntax.nodes import GCODE, TEXT
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source
from gclint.translate import TranslationResult, translate_source, translator_for
from gclint.translate.options import TranslateOptions

from .conftest import CORPUS, corpus_job, needs_corpus

EXTENSIONS = (".gcode", ".g", ".nc", ".ngc", ".cnc", ".tap")
FOLDERS = ("marlin", "reprap", "machinekit", "carvera")
ALLOWED: dict[tuple[str, str], str] = {}  # (path relative to the corpus, check code) -> the TR finding that explains it


def jobs(folder: str) -> list[Path]:
    root = CORPUS / folder
    if not root.is_dir():
        return []
    out = []
    for base, _, names in os.walk(root):
        for name in names:
            # job files, and RepRapFirmware's extension-less macro files (macros/Home XYZ)
            if name.lower().endswith(EXTENSIONS) or (folder == "reprap" and "." not in name):
                out.append(Path(base) / name)
    return sorted(out)


def translated(path: Path, folder: str, flow: str = "evalues", whole: bool = False) -> tuple[str, TranslationResult]:
    options = TranslateOptions()
    options.flow = flow
    translator = translator_for(dialects.get(folder), dialects.get("hyrel"), options)
    result = TranslationResult(str(path), folder, "hyrel")
    src = Source.open(str(path) if whole else corpus_job(path))  # (a big job's head and tail, unless GCLINT_SLOW=1)
    return "".join(translate_source(src, translator, result)), result


LINTER = Linter(Options(dialect="hyrel"))


def _errors(text: str, path: Path) -> list:
    findings = LINTER.check_text(text, str(path)).findings
    rel = str(path.relative_to(CORPUS))
    return [f for f in findings if f.severity == Severity.ERROR and (rel, f.code) not in ALLOWED]


def _not_hyrel(text: str) -> Counter:
    """Commands in ``text`` that are not Hyrel codes (X1: nothing unknown passes through)."""
    unknown: Counter = Counter()
    for raw in text.splitlines():
        for cmd in parse_line(raw).commands:
            if cmd.kind in (GCODE, TEXT):
                if cmd.code not in HYREL_CODES and not (cmd.code or "").startswith("T"):
                    unknown[cmd.code] += 1
            else:
                unknown[cmd.kind] += 1
    return unknown


@needs_corpus
@pytest.mark.parametrize("folder", FOLDERS)
def test_every_job_translates_to_clean_hyrel(folder: str) -> None:
    """No error-level check finding in the output, and only Hyrel codes written (X1)."""
    paths = jobs(folder)
    assert paths, f"no jobs in {folder}"
    problems = []
    unknown: Counter = Counter()
    for path in paths:
        text, result = translated(path, folder)
        for f in _errors(text, path):
            line = text.splitlines()[f.line - 1] if f.line <= len(text.splitlines()) else ""
            problems.append(f"{path.relative_to(CORPUS)}:{f.line}: {f.code} {f.message} | {line[:80]}")
        unknown.update(_not_hyrel(text))
    assert not problems, "\n".join(problems[:30])
    assert not unknown, unknown.most_common(20)


@needs_corpus
@pytest.mark.parametrize("folder", ["marlin", "machinekit"])
def test_native_flow_output_is_clean_too(folder: str) -> None:
    problems = []
    small = [p for p in jobs(folder) if p.stat().st_size < 400_000]
    for path in small[:15]:
        text, _ = translated(path, folder, flow="native")
        problems += [f"{path.name}:{f.line}: {f.code} {f.message}" for f in _errors(text, path)]
    assert not problems, "\n".join(problems[:30])


@needs_corpus
def test_marlin_job_keeps_its_moves_byte_for_byte() -> None:
    path = CORPUS / "marlin" / "prusaslicer-2.8.1_mini_cube.gcode"
    text, result = translated(path, "marlin", whole=True)
    source = path.read_text(encoding="utf-8")
    moves = [line for line in source.splitlines() if line.startswith("G1 X") and " E" in line and "E-" not in line]
    out_lines = set(text.splitlines())
    assert all(m in out_lines for m in moves)  # relative E, extruding moves: untouched
    assert result.lines_changed < len(source.splitlines()) // 4  # dropped M73/M204, retracts, header
