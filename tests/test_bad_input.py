"""Bad input, one row per case, through the real command line (subprocess) for ``check`` and ``translate``.

Every row must end with the exit code the contract gives (0 clean, 1 findings, 2 unreadable or usage error),
a clear message (one line on stderr naming the file when the file cannot be used), no traceback, and
within seconds (a generous limit against hangs such as regular-expression blow-ups, not a benchmark).
"""

from __future__ import annotations

import codecs
import json
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from .conftest import run_cli

LIMIT = 20.0  # seconds per command


@dataclass
class Case:
    name: str
    make: Callable[[Path], Path]  # builds the input under tmp_path, returns the path to give the CLI
    check: tuple[int, ...]  # allowed exit codes of "gclint check"
    translate: tuple[int, ...]  # allowed exit codes of "gclint translate --from marlin --to marlin"
    message: str = ""  # expected in stderr (exit 2) or in a finding's message (exit 1) of check
    codes: tuple[str, ...] = ()  # finding codes that must be reported by check
    identity: bool = True  # translate output must equal the input bytes
    translate_message: str = ""  # expected in stderr of translate (exit 2)


def _file(name: str, data: bytes | str) -> Callable[[Path], Path]:
    def make(tmp: Path) -> Path:
        path = tmp / name
        path.write_bytes(data.encode("utf-8", "surrogateescape") if isinstance(data, str) else data)
        return path

    return make


def _missing(tmp: Path) -> Path:
    return tmp / "missing.gcode"


def _empty_folder(tmp: Path) -> Path:
    (tmp / "jobs").mkdir()
    (tmp / "jobs" / "notes.txt").write_text("not G-code")
    return tmp / "jobs"


def _gcode_folder(tmp: Path) -> Path:
    (tmp / "jobs" / "sub").mkdir(parents=True)
    (tmp / "jobs" / "a.gcode").write_text("G28\nG1 X10 Y10 F3000\n")
    (tmp / "jobs" / "sub" / "b.nc").write_text("G21\nG0 X0 Y0\n")
    return tmp / "jobs"


CASES = [
    Case("missing file", _missing, (2,), (2,), "no such file", translate_message="no such file"),
    Case("folder without G-code", _empty_folder, (2,), (2,), "no G-code files", translate_message="is a folder"),
    Case("folder with G-code", _gcode_folder, (0, 1), (2,), translate_message="is a folder"),
    Case("empty file", _file("empty.gcode", b""), (0,), (0,)),
    Case("whitespace only", _file("blank.gcode", b"  \n\t\n\r\n   "), (0,), (0,)),
    Case(
        "binary data", _file("random.gcode", bytes(range(256)) * 20), (2,), (2,), "binary", translate_message="binary"
    ),
    Case(
        "binary G-code",
        _file("part.bgcode.gcode", b"GCDE\x01\x00\x00\x00" + bytes(200)),
        (2,),
        (2,),
        "binary G-code",
        translate_message="binary G-code",
    ),
    Case(
        "PNG renamed",
        _file("image.gcode", b"\x89PNG\r\n\x1a\n" + bytes(100)),
        (2,),
        (2,),
        "PNG",
        translate_message="PNG",
    ),
    Case("one NUL byte", _file("nul.gcode", b"G28\nG1 X1\x00 Y2\n"), (1,), (0,), codes=("SX001",)),
    Case("1 MB number", _file("long_number.gcode", "G1 X" + "1" * 1_000_000 + "\n"), (0, 1), (0,)),
    Case(
        "1 MB garbage line",
        _file("long_garbage.gcode", "G1 X1 )" * 150_000 + "\n"),
        (1,),
        (0,),
        "not parsed",
        ("SX001",),
    ),
    Case("1 MB comment", _file("long_comment.gcode", "; " + "abc " * 250_000 + "\nG28\n"), (0, 1), (0,)),
    Case("1 MB line, no newline", _file("no_newline.gcode", "G1 X1 Y" + "2" * 1_000_000), (0, 1), (0,)),
    Case(
        "100k nested parentheses",
        _file("parens.gcode", "(" * 100_000 + ")" * 100_000 + "\n"),
        (1,),
        (0,),
        codes=("SX001",),
    ),
    Case(
        "99k open parentheses", _file("open_parens.gcode", "G1 X1 " + "(" * 99_000 + "\n"), (1,), (0,), codes=("SX005",)
    ),
    Case("50k nested brackets", _file("brackets.gcode", "G1 X" + "[" * 50_000 + "]" * 50_000 + "\n"), (0, 1), (0,)),
    Case("50k open brackets", _file("open_brackets.gcode", "G1 X" + "[" * 50_000 + "\n"), (1,), (0,), codes=("SX001",)),
    Case(
        "words ending in junk (regex blow-up)",
        _file("redos.gcode", "G1" + " X1111" * 20_000 + " !\n"),
        (1,),
        (0,),
        codes=("SX001",),
    ),
    Case(
        "unclosed comment",
        _file("unclosed.gcode", "G1 X10 (move to the clamp\n"),
        (1,),
        (0,),
        "never closed",
        ("SX005",),
    ),
    Case("1e309", _file("exp.gcode", "G1 X1e309 Y1\n"), (0, 1), (0,)),
    Case(
        "hex values (fuzz)", _file("hex.gcode", "; gclint: dialect=hyrel\nM229 E0x0 D1\nM229 E0x1 D0x1\n"), (0, 1), (0,)
    ),
    Case("hex addresses", _file("hex_t.gcode", "M104 T0x1 S200\nT0x1\nM6 T0x2 O1\n"), (0, 1), (0,)),
    Case("NaN", _file("nan.gcode", "G1 XNaN Y1\nG1 X1 YNaN\n"), (0, 1), (0,)),
    Case("--1", _file("minus.gcode", "G1 X--1 Y1\n"), (1,), (0,), "not a number", ("SX006",)),
    Case(
        "5000-digit number",
        _file("digits.gcode", "G1 X" + "9" * 5000 + " Y1\nM104 S" + "9" * 5000 + "\n"),
        (0, 1),
        (0,),
    ),
    Case("5000-digit code", _file("code.gcode", "G" + "1" * 5000 + " X1\nM" + "0" * 5000 + "1\n"), (0, 1), (0,)),
    Case("lowercase", _file("lower.gcode", "g28\ng1 x10 y20 f3000\nm104 s200\n"), (0, 1), (0,)),
    Case("no spaces", _file("nospace.gcode", "G28\nG1X10Y20F3000\nG0X0Y0S12000M3\n"), (0, 1), (0,)),
    Case(
        "bad N sequence", _file("lineno.gcode", "N10 G1 X1 F600*0\nN5 G1 X2*103\n"), (1,), (0,), "count up", ("SX003",)
    ),
    Case("bad checksum", _file("checksum.gcode", "N1 G1 X1*99\n"), (1,), (0,), "checksum", ("SX004",)),
    Case("checksum mid-line", _file("checksum_mid.gcode", "N1 G1 *12 X1\n"), (1,), (0,), codes=("SX001",)),
    Case("checksum without number", _file("checksum_empty.gcode", "N1 G1 X1*\n"), (1,), (0,), codes=("SX001",)),
    Case("latin-1 comment", _file("latin1.gcode", b"; caf\xe9 \xb0C\nG28\n"), (0, 1), (0,)),
    Case("UTF-8 BOM, CRLF", _file("bom.gcode", b"\xef\xbb\xbfG28\r\nG1 X1\r\n"), (0, 1), (0,)),
    Case(
        "UTF-16 with BOM",
        _file("utf16.gcode", codecs.BOM_UTF16_LE + "G28\r\nG1 X1 ; \u00e9\r\n".encode("utf-16-le")),
        (0, 1),
        (0,),
    ),
    Case(
        "UTF-16 cut short (odd byte count)",
        _file("utf16_odd.gcode", codecs.BOM_UTF16_LE + "G28\r\nG1 X1\r\n".encode("utf-16-le") + b"G"),
        (2,),
        (2,),
        "not valid UTF-16",
        translate_message="not valid UTF-16",
    ),
    Case("CR only, no final newline", _file("cr.gcode", b"G28\rG1 X1\rG1 X2"), (0, 1), (0,)),
    Case("lone surrogate-like bytes", _file("bytes.gcode", b"G1 X1 ; \xed\xa0\x80 \xff\xfe\n"), (0, 1), (0,)),
    Case(
        "control characters", _file("controls.gcode", b"G1 X1\x07\x1b[31m Y2\n\x0cG28\n"), (1,), (0,), codes=("SX001",)
    ),
    Case(
        # translate refuses what check refuses (a translation of a script or random bytes would be garbage)
        "script, not G-code",
        _file("script.gcode", b"#!/bin/sh\nrm -rf /\n"),
        (2,),
        (2,),
        "not G-code",
        translate_message="not G-code",
    ),
]


def _assert_clean(
    proc, case: Case, path: Path, allowed: tuple[int, ...], elapsed: float, what: str, message: str
) -> None:
    stderr = proc.stderr.decode("utf-8", "replace")
    assert "Traceback" not in stderr, f"{case.name} ({what}): traceback\n{stderr[-3000:]}"
    assert (
        proc.returncode in allowed
    ), f"{case.name} ({what}): exit {proc.returncode}, expected {allowed}\n{stderr[-2000:]}"
    assert elapsed < LIMIT, f"{case.name} ({what}): {elapsed:.1f} s"
    if proc.returncode == 2:
        lines = [line for line in stderr.splitlines() if line.strip()]
        assert len(lines) == 1, f"{case.name} ({what}): expected one line on stderr, got {lines}"
        assert path.name in lines[0], f"{case.name} ({what}): the message does not name the file: {lines[0]}"
        if message:
            assert message in lines[0], f"{case.name} ({what}): {lines[0]}"


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_check(case: Case, tmp_path: Path) -> None:
    path = case.make(tmp_path)
    start = time.monotonic()
    proc = run_cli("check", "--jobs", "1", "--format", "json", str(path), timeout=LIMIT * 3)
    elapsed = time.monotonic() - start
    _assert_clean(proc, case, path, case.check, elapsed, "check", case.message)
    if proc.returncode in (0, 1):
        findings = json.loads(proc.stdout)
        assert (proc.returncode == 1) == any(f["severity"] in ("error", "warning") for f in findings)
        found = {f["code"] for f in findings}
        assert set(case.codes) <= found, f"{case.name}: expected {case.codes}, got {sorted(found)}"
        if case.message and proc.returncode == 1:
            assert any(case.message in f["message"] for f in findings), findings[:5]
        for f in findings:
            assert f["line"] >= 1 and f["column"] >= 1
            assert Path(f["path"]).name != "" and (path.is_dir() or Path(f["path"]).name == path.name)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_translate(case: Case, tmp_path: Path) -> None:
    path = case.make(tmp_path)
    out = tmp_path / "out" / "translated.gcode"
    out.parent.mkdir()
    start = time.monotonic()
    proc = run_cli("translate", "--from", "marlin", "--to", "marlin", str(path), "-o", str(out), timeout=LIMIT * 3)
    elapsed = time.monotonic() - start
    _assert_clean(proc, case, path, case.translate, elapsed, "translate", case.translate_message)
    if proc.returncode == 0 and case.identity:
        assert out.read_bytes() == path.read_bytes(), f"{case.name}: translate to the same dialect changed the file"
    if proc.returncode == 2:
        assert not out.exists(), f"{case.name}: output written although the input could not be read"
    assert not [p.name for p in out.parent.iterdir() if p.name.startswith(".gclint-")], "temporary file left behind"


def test_binary_on_stdin_names_stdin() -> None:
    proc = run_cli("check", "-", input=bytes(range(256)) * 10, timeout=LIMIT * 3)
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "Traceback" not in stderr
    assert len(stderr.strip().splitlines()) == 1 and "-" in stderr


def test_stdin_filename_is_used_in_messages() -> None:
    proc = run_cli("check", "-", "--stdin-filename", "job.gcode", input=b"\x00\x01" * 100, timeout=LIMIT * 3)
    assert proc.returncode == 2 and "job.gcode" in proc.stderr.decode()


def test_device_file_of_zeros(tmp_path: Path) -> None:
    if not Path("/dev/zero").exists():
        pytest.skip("no /dev/zero")
    start = time.monotonic()
    proc = run_cli("check", "/dev/zero", timeout=LIMIT * 3)
    assert proc.returncode == 2 and "binary" in proc.stderr.decode() and "Traceback" not in proc.stderr.decode()
    assert time.monotonic() - start < LIMIT


def test_one_bad_file_among_good_ones(tmp_path: Path) -> None:
    good = tmp_path / "good.gcode"
    good.write_text("G28\nG1 X1 (unclosed\n")
    bad = tmp_path / "bad.gcode"
    bad.write_bytes(bytes(range(256)) * 4)
    proc = run_cli("check", "--format", "json", str(good), str(bad), str(tmp_path / "missing.gcode"), timeout=LIMIT * 3)
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "Traceback" not in stderr
    lines = stderr.strip().splitlines()
    assert len(lines) == 2 and "bad.gcode" in stderr and "missing.gcode" in stderr
    assert any(f["code"] == "SX005" for f in json.loads(proc.stdout)), "the good file was still checked"


@pytest.mark.parametrize(
    "args,message",
    [
        (("check", "--dialect", "klingon", "x.gcode"), "unknown dialect"),
        (("check", "--printer", "99z", "x.gcode"), "unknown printer"),
        (("check", "--loaded", "T99", "x.gcode"), "T99"),
        (("check", "--format", "pdf", "x.gcode"), "unknown format"),
        (("check", "--config", "nonexistent.toml", "x.gcode"), "nonexistent.toml"),
        (("translate", "--from", "marlin", "--to", "klingon", "x.gcode"), "unknown dialect"),
        (("translate", "--from", "marlin", "--to", "marlin", "--in-place", "-"), "standard input"),
        (("translate", "--from", "marlin", "--to", "marlin", "--tool-map", "zero=T2", "x.gcode"), "zero"),
        # only ASCII digits are numbers (issue 12, item 15)
        (("check", "--loaded", "T\u00b2", "x.gcode"), "--loaded"),
        (("check", "--loaded", "T\u0661", "x.gcode"), "--loaded"),
        (("check", "--loaded", "T" + "9" * 5000, "x.gcode"), "--loaded"),
        (("translate", "--from", "marlin", "--to", "hyrel", "--tool-map", "0=T\u00b2", "x.gcode"), "--tool-map"),
        (("translate", "--from", "marlin", "--to", "hyrel", "--tool-map", "\u0661=T2", "x.gcode"), "--tool-map"),
        (("translate", "--from", "marlin", "--to", "hyrel", "--tool-map", "9" * 5000 + "=T2", "x.gcode"), "--tool-map"),
    ],
)
def test_usage_errors_exit_2_in_one_line(args, message, tmp_path: Path) -> None:
    (tmp_path / "x.gcode").write_text("G28\n")
    proc = run_cli(*args, cwd=tmp_path, timeout=LIMIT * 3)
    stderr = proc.stderr.decode()
    assert proc.returncode == 2, (proc.returncode, stderr)
    assert "Traceback" not in stderr and message in stderr
    assert len([line for line in stderr.splitlines() if line.strip()]) == 1, stderr


HUGE = "9" * 5000


@pytest.mark.parametrize("source", ["marlin", "reprap", "machinekit", "carvera", "hyrel-v4"])
def test_translate_to_hyrel_survives_absurd_numbers(tmp_path: Path, source: str) -> None:
    path = tmp_path / "huge.gcode"
    path.write_text(
        f"G28\nT{HUGE}\nM104 T{HUGE} S{HUGE}\nG4 P{HUGE}\nM106 S{HUGE}\n"
        f"G1 X{HUGE} E{HUGE} F{HUGE}\nG2 X1 Y1 I{HUGE} J0\n"
    )
    proc = run_cli("translate", "--from", source, "--to", "hyrel", str(path), timeout=LIMIT * 3)
    stderr = proc.stderr.decode()
    assert "Traceback" not in stderr and "internal error" not in stderr, stderr
    assert proc.returncode in (0, 1), stderr


@pytest.mark.parametrize("dialect", ["hyrel", "hyrel-v4", "marlin", "reprap", "machinekit", "carvera"])
def test_check_survives_absurd_numbers_in_every_dialect(tmp_path: Path, dialect: str) -> None:
    path = tmp_path / "huge.gcode"
    path.write_text(
        f"M{HUGE}\nG{HUGE} X1\nT{HUGE}\nN{HUGE} G1 X1*{HUGE}\nM104 T{HUGE} S{HUGE}\nM109 T{HUGE} S200 H{HUGE}\n"
        f"G4 P{HUGE}\nM106 S{HUGE} P{HUGE}\nM3 S{HUGE}\nM6 T{HUGE} O{HUGE}\nM660 H{HUGE}\nG81 X1 H{HUGE}\n"
        f"M229 E{HUGE} D{HUGE}\nG2 X1 Y1 I{HUGE} J0\n"
    )
    proc = run_cli("check", "--dialect", dialect, "--select", "ALL", "--format", "json", str(path), timeout=LIMIT * 3)
    stderr = proc.stderr.decode()
    assert "Traceback" not in stderr and "internal error" not in stderr, stderr
    assert proc.returncode in (0, 1), stderr
    json.loads(proc.stdout)


NINES = "9" * 308


@pytest.mark.parametrize(
    "text",
    [
        f"G1 X{NINES} Y1\nG1 X-{NINES} Y-{NINES}\nG1 X1 (unclosed\n",
        f"G1 X{'9' * 400} Y1\nG1 X-{'9' * 400} Y-1\nG1 X1 (unclosed\n",
        f"G91\nG1 X{NINES} Y{NINES}\nG1 X{NINES} Y{NINES}\nG1 X{NINES}\nG1 X1 (unclosed\n",
        f"G1 X0 Y0\nG2 X1 Y0 I{NINES} J{NINES}\nG20\nG1 X{NINES} Y1\nG1 X1 (unclosed\n",
    ],
    ids=["opposite extremes", "overflow to infinity", "relative sum overflows", "arcs and inches"],
)
def test_every_report_survives_extreme_coordinates(tmp_path: Path, text: str) -> None:
    job = tmp_path / "extreme.gcode"
    job.write_text(text)
    for fmt in ("html", "sarif", "json", "junit", "full"):
        proc = run_cli("check", "--no-cache", "--format", fmt, str(job), timeout=LIMIT * 3)
        stderr = proc.stderr.decode()
        assert proc.returncode == 1 and "internal error" not in stderr and "Traceback" not in stderr, (fmt, stderr)


def test_undecodable_file_name_in_every_format(tmp_path: Path) -> None:
    import os

    name = os.fsdecode(b"caf\xe9 \xff.gcode")
    job = tmp_path / name
    job.write_text("G1 X1 (unclosed\n")
    for fmt in ("text", "full", "grouped", "json", "sarif", "github", "junit", "html"):
        proc = run_cli("check", "--no-cache", "--format", fmt, str(job), timeout=LIMIT * 3)
        stderr = proc.stderr.decode()
        assert proc.returncode == 1 and "internal error" not in stderr and "Traceback" not in stderr, (fmt, stderr)
        if fmt in ("json", "sarif"):
            json.loads(proc.stdout)


# -- every row through the result cache and every report format (issue 12) -----------------------------------------

HUMAN_FORMATS = ("text", "concise", "full", "grouped", "github")


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_cache_and_every_report(case: Case, tmp_path: Path) -> None:
    """The cache gives back exactly what a check gives, for every bad input, and every report renders it: no
    exception, machine formats parse, human formats carry no raw control character."""
    import io
    import xml.etree.ElementTree as ET

    from gclint import runner
    from gclint.cache import ResultCache
    from gclint.engine import Options
    from gclint.reports import ReportContext, formats

    path = case.make(tmp_path)
    files, problems = runner.collect([str(path)])
    cache = ResultCache(str(tmp_path / "cache"))
    first = problems + runner.run(files, Options(), {}, cache=cache)
    second = problems + runner.run(files, Options(), {}, cache=cache)

    def key(results):
        return [
            (r.path, r.error, [(f.line, f.column, f.code, f.severity, f.message) for f in r.findings]) for r in results
        ]

    assert key(second) == key(first)
    cacheable = [r for r in first if r.error is None and r.path in files]
    assert cache.hits == len(cacheable), (cache.hits, len(cacheable))
    for name, writer in formats().items():
        out = io.StringIO()
        writer(second, out, ReportContext(tool_version="0", statistics=True))
        text = out.getvalue()
        if name in ("json", "sarif"):
            json.loads(text)
        elif name == "junit":
            ET.fromstring(text.split("\n", 1)[1])
        elif name in HUMAN_FORMATS:
            assert not any(c in text for c in "\x1b\x07\x00\x0c\x9b"), f"{case.name}: raw control character in {name}"


@pytest.mark.parametrize("source", ["hyrel-v4", "marlin", "reprap"])
def test_translate_survives_hex_values(tmp_path: Path, source: str) -> None:
    path = tmp_path / "hex.gcode"
    path.write_text("M104 T0x1 S200\nT0x1\nM6 T0x2 O1\nM229 E0x1 D0x1\nM106 S0xff\n")
    proc = run_cli("translate", "--from", source, "--to", "hyrel", str(path), timeout=LIMIT * 3)
    stderr = proc.stderr.decode()
    assert proc.returncode in (0, 1) and "internal error" not in stderr, stderr
