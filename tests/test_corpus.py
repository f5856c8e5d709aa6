"""The real-file corpus (../shared/corpus, read in place).

* Every G-code file parses with its folder's dialect with no SX error, except the faults listed below
  (each is a real fault in the file, explained) and files whose provenance note starts with
  EXPECTED-INVALID (interpreter tests meant to be rejected; they may or may not be).
* Text files that are not G-code (INI configuration, Org documents, shell/Python scripts) are refused
  with one clear line, and nothing else is.
* Binary files (.bgcode) are refused with one clear line.
* ``gclint translate --from D --to D`` gives back every text file byte for byte.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from gclint.cli import main
from gclint.engine import Linter, Options
from gclint.rules.base import Severity

from .conftest import CORPUS, corpus_job, needs_corpus, run_cli

pytestmark = needs_corpus

FOLDER_DIALECT = {
    "hyrel": "hyrel-v4",
    "linuxcnc": "machinekit",
    "other": "auto",
    "marlin": "marlin",
    "reprap": "reprap",
    "machinekit": "machinekit",
    "carvera": "carvera",
}

# Real faults in real files, reported as SX errors: (relative path) -> {(line, code)}.
KNOWN_SX_FAULTS = {
    # The fixture's own comment on the line says "checksum failed": the deliberate wrong checksum.
    "other/cncjs-gcode-parser_special-fields.gcode": {(8, "SX004")},
    # "M118 testing mismatched brackets": deliberately broken expressions, "these will halt".
    "carvera/Carvera_Community_Firmware/TEST_basicMathFunctions.cnc": {(145, "SX001"), (151, "SX001"), (154, "SX001")},
    # "M462 X125/2 Y110/2": G-code has no arithmetic outside [ ]; Smoothieware's parser reads X125.
    "carvera/Carvera_Community_Firmware/TEST_ProbingM460toM465.cnc": {(131, "SX001")},
    # "o110 if [EXISTS[#<x>]": one "]" missing; LinuxCNC stops with "unclosed expression".
    "machinekit/taz_cramps/subroutines/g28.ngc": {(9, "SX001"), (12, "SX001"), (15, "SX001"), (18, "SX001")},
}


def _provenance() -> dict[str, str]:
    out = {}
    with open(CORPUS / "provenance.jsonl", encoding="utf-8") as fh:
        for line in fh:
            entry = json.loads(line)
            out[entry["local"]] = entry.get("note", "")
    return out


def _files(folder: str) -> list[Path]:
    return sorted(p for p in (CORPUS / folder).rglob("*") if p.is_file())


def _is_binary(path: Path) -> bool:
    return path.suffix == ".bgcode"


def _is_not_gcode(path: Path) -> bool:
    """Configuration, documentation and scripts that live beside the G-code in the corpus."""
    if path.suffix in (".ini", ".org"):
        return True
    with open(path, "rb") as fh:
        return fh.read(2) == b"#!"


@pytest.mark.parametrize("folder", sorted(FOLDER_DIALECT))
def test_every_file_parses_with_its_folder_dialect(folder):
    dialect = FOLDER_DIALECT[folder]
    linter = Linter(Options(dialect=dialect, select=["SX"]))
    notes = _provenance()
    checked = 0
    unexpected: dict[str, list] = {}
    for path in _files(folder):
        rel = path.relative_to(CORPUS).as_posix()
        result = linter.check_path(str(path))
        if _is_binary(path):
            assert result.error and "binary G-code" in result.error, rel
            continue
        if _is_not_gcode(path):
            assert result.error and "not G-code" in result.error, (rel, result.error)
            assert "\n" not in result.error
            continue
        assert result.error is None, (rel, result.error)
        checked += 1
        errors = {(f.line, f.code) for f in result.findings if f.severity == Severity.ERROR}
        if notes.get(rel, "").startswith("EXPECTED-INVALID"):
            continue
        expected = KNOWN_SX_FAULTS.get(rel, set())
        if errors != expected:
            unexpected[rel] = sorted(errors ^ expected)
    assert not unexpected, unexpected
    assert checked > 0


def test_no_gcode_file_is_refused_as_not_gcode():
    """The not-G-code test is conservative: it refuses exactly the INI, Org and script files."""
    refused, expected = set(), set()
    linter = Linter(Options(select=["SX"]))
    for folder in FOLDER_DIALECT:
        for path in _files(folder):
            if _is_binary(path):
                continue
            rel = path.relative_to(CORPUS).as_posix()
            if _is_not_gcode(path):
                expected.add(rel)
            result = linter.check_path(str(path))
            if result.error and "not G-code" in result.error:
                refused.add(rel)
    assert refused == expected
    assert len(expected) >= 20


def _text_files() -> list[Path]:
    return [p for folder in FOLDER_DIALECT for p in _files(folder) if not _is_binary(p)]


def test_identity_translation_is_byte_for_byte(tmp_path):
    runner = CliRunner()
    count = 0
    for path in _text_files():
        dialect = FOLDER_DIALECT[path.relative_to(CORPUS).parts[0]]
        dialect = "marlin" if dialect == "auto" else dialect
        out = tmp_path / "out.gcode"
        job = corpus_job(path)  # (a long job's first and last lines, unless GCLINT_SLOW)
        result = runner.invoke(main, ["translate", "--from", dialect, "--to", dialect, job, "-o", str(out)])
        if _is_not_gcode(path):  # refused as ``check`` refuses it
            assert result.exit_code == 2 and "not G-code" in result.output, (path, result.output)
            continue
        assert result.exit_code == 0, (path, result.output)
        assert out.read_bytes() == Path(job).read_bytes(), path
        count += 1
    assert count > 500


@pytest.mark.parametrize(
    "rel,dialect",
    [
        ("hyrel/unidentified_idx23519466326__shape1_v4.gcode", "hyrel-v4"),
        ("other/cncjs-gcode-parser_special-fields.gcode", "marlin"),
        ("carvera/CarveraController/LED/PCB-NO-UV-MASK.nc", "carvera"),
        ("reprap/MillenniumOS/macro/movement/G8000.g", "reprap"),
    ],
)
def test_identity_translation_subprocess(tmp_path, rel, dialect):
    out = tmp_path / "out"
    proc = run_cli("translate", "--from", dialect, "--to", dialect, str(CORPUS / rel), "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    assert out.read_bytes() == (CORPUS / rel).read_bytes()


def test_binary_files_exit_2_with_one_line():
    for path in (CORPUS / "other").glob("*.bgcode"):
        proc = run_cli("check", str(path))
        assert proc.returncode == 2
        err = proc.stderr.decode()
        assert err.count("\n") == 1 and str(path) in err and "binary G-code" in err
        assert "Traceback" not in err


def test_empty_file_is_clean():
    proc = run_cli("check", str(CORPUS / "other" / "empty_file.gcode"))
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr.decode()


def test_corpus_folder_walk_has_no_crash():
    proc = run_cli("check", str(CORPUS / "hyrel"), "--dialect", "hyrel-v4", "--format", "json", "--exit-zero")
    assert proc.returncode == 0, proc.stderr
    data = json.loads(proc.stdout)
    assert isinstance(data, list)
    for f in data:
        assert {"path", "line", "column", "code", "severity", "message"} <= set(f)
    assert os.path.basename(data[0]["path"]).endswith(".gcode") if data else True
