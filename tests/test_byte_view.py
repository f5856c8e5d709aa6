"""A UTF-16/32 file is also read as bytes, as a firmware that ignores its byte order mark reads it (a
file can decode to a harmless comment and read as commands byte by byte: security review of issue 12)."""

from __future__ import annotations

from pathlib import Path

from gclint.engine import Linter, Options
from gclint.syntax.source import ByteView, Source, SourceError
from tests.conftest import run_cli


def _polyglot(payload: bytes) -> bytes:
    body = b"XX\n" + payload
    body += b" " * (len(body) % 2)  # whole UTF-16 units
    return b"\xff\xfe;\x00 \x00" + body + b"\n\x00"  # decoded: one ";" comment line of CJK characters


def test_a_file_that_reads_two_ways_is_checked_both_ways(tmp_path: Path) -> None:
    job = tmp_path / "poly.cnc"
    job.write_bytes(_polyglot(b"G4 P0\nM792 ; SHELL C:\\evil.exe\n"))
    decoded = [raw for raw, _ in Source.open(str(job)).lines()]
    assert decoded[0].startswith(";") and "SHELL" not in "".join(decoded)  # what a decoder sees
    proc = run_cli("check", "--no-cache", str(job))
    out = proc.stdout.decode()
    assert proc.returncode == 1, out
    assert "SC001 [error] read as bytes" in out and "line 3: M792 SHELL" in out


def test_plain_utf16_gives_nothing_in_the_byte_view() -> None:
    text = "\ufeffG28\nG1 X1 F100 ; 中文注释 — 温度\nM104 S200\nM30\n"
    for encoding in ("utf-16-le", "utf-16-be", "utf-32-le"):
        source = Source.from_bytes(text.encode(encoding), "job.gcode")
        list(source.lines())
        assert source.byte_view is not None and source.byte_view.lines == [], encoding
    result = Linter(Options(dialect="marlin")).check_source(Source.from_bytes(text.encode("utf-16-le"), "j"))
    assert not [f for f in result.findings if f.code.startswith("SC")]


def test_utf8_files_have_no_byte_view() -> None:
    source = Source.from_text("G28\nM792 ; SHELL x\n", "job.gcode")
    list(source.lines())
    assert source.byte_view is None


def test_the_byte_view_is_bounded() -> None:
    view = ByteView("big.gcode")
    line = b"G1 X1 Y1\n" * 1000
    try:
        for _ in range(ByteView.LIMIT // 8000 + 2):  # (8,000 characters kept a feed)
            view.feed(line, False)
    except SourceError as exc:
        assert "reads two ways" in str(exc)
    else:
        raise AssertionError("no limit")
