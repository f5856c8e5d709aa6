"""Binary G-code (.bgcode): the security rules read the G-code blocks gclint can decode, never compressed bytes as
text, and the file stays an error (exit 2) naming the blocks it could not read."""

from __future__ import annotations

import struct
import zlib

import pytest

from gclint.bgcode import decode
from tests.conftest import CORPUS, run_cli


def _block(kind: int, text: bytes, compression: int = 0, encoding: int = 0) -> bytes:
    body = zlib.compress(text) if compression == 1 else text
    header = struct.pack("<HHI", kind, compression, len(text))
    if compression:
        header += struct.pack("<I", len(body))
    return header + struct.pack("<H", encoding) + body + b"\0\0\0\0"


def _file(*blocks: bytes) -> bytes:
    return b"GCDE" + struct.pack("<IH", 1, 1) + b"".join(blocks)


def test_plain_and_deflated_gcode_blocks_are_decoded():
    data = _file(
        _block(0, b"Producer=test\n"),
        _block(1, b"G28\n"),
        _block(1, b"M30 /sys/config.g\n", compression=1),
        _block(1, b"\x12\x34", compression=3),  # (heatshrink: not decoded)
        _block(1, b"G1 X1\n", encoding=1),  # (MeatPack: not decoded)
    )
    assert decode(data) == (b"G28\nM30 /sys/config.g\n", 2)


def test_a_hostile_block_fails_the_gate_and_compressed_bytes_are_not_read_as_text(tmp_path):
    (tmp_path / "a.bgcode").write_bytes(_file(_block(1, b"G28\nM30 /sys/config.g\n", compression=1)))
    proc = run_cli("check", "--no-cache", str(tmp_path / "a.bgcode"))
    out = (proc.stdout + proc.stderr).decode()
    assert proc.returncode == 2 and "SC005" in out, out


@pytest.mark.skipif(not (CORPUS / "other").is_dir(), reason="the corpus is not here")
def test_real_prusaslicer_files_are_one_error_with_no_finding():
    for path in sorted((CORPUS / "other").glob("*.bgcode")):
        proc = run_cli("check", "--no-cache", str(path))
        out = (proc.stdout + proc.stderr).decode()
        assert proc.returncode == 2 and "cannot read (heatshrink, MeatPack)" in out and " SC0" not in out, out
