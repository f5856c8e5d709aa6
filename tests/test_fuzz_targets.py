"""The fuzz targets' checks on seeds and random inputs, without atheris (fuzz/run.sh runs them for real)."""

from __future__ import annotations

import importlib.util
import json
import random
import sys

import pytest

from .conftest import ROOT

FUZZ = ROOT / "fuzz"


def _target(name: str):
    sys.path.insert(0, str(FUZZ))
    try:
        spec = importlib.util.spec_from_file_location(name, FUZZ / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    finally:
        sys.path.remove(str(FUZZ))


@pytest.fixture(scope="module")
def reports():
    return _target("fuzz_reports")


def _seeds() -> list[bytes]:
    sys.path.insert(0, str(FUZZ))
    try:
        import _common
    finally:
        sys.path.remove(str(FUZZ))
    lines = list(_common.SEED_LINES)
    return [*lines, b"\n".join(lines), b"\x1b[2J" + b"\r\n".join(lines), "M117 \u202eevil\x9b\n".encode()]


def test_reports_target_on_seeds(reports) -> None:
    for seed in _seeds():
        for first in (0, 2, 4):
            reports.one_input(bytes([first]) + seed)


ENTRIES = [
    b"",
    b"null",
    b"{}",
    json.dumps({"format": 2}).encode(),
    b'{"format": 2, "settings": "x", "path": "p", "sha256": "0", "result": {"findings": [1, "a", null]}}',
    bytes(range(256)),
    b"[" * 5000,
]


def test_reports_target_on_forged_entries(reports) -> None:
    for entry in ENTRIES:
        reports.one_input(b"\x01" + entry)


def test_reports_target_on_random_bytes(reports) -> None:
    rng = random.Random(12)
    alphabet = b"GMTXYZEFSP0123456789.-; ()*\n\r\t\x1b\x00\x9b\xff=:\"'"
    for _ in range(150):
        data = bytes(rng.choice(alphabet) for _ in range(rng.randint(1, 200)))
        reports.one_input(data)
