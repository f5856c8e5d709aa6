"""A file the gate was asked to check, or found under a job's extension, is never passed unread (issue 25).

Before, a ``.nc``/``.cnc``/``.g``/``.tap`` whose head was two NUL bytes, a ``#!`` line, an INI section,
``key = value`` lines, an Org heading or a NetCDF magic number was "skipped as not G-code" with a note, in a
folder walk and under the pre-commit hook (``--force-exclude``): exit 0.  Now the security rules read it as a
firmware does (each line cut at its first NUL, as ``fgets`` into a C string), and it is exit 2 with one line
naming it and why, unless the user's own command line or ``--config`` excludes it."""

from __future__ import annotations

import io
import json
import re
from pathlib import Path

import pytest

from gclint.notgcode import CutAtNul

from .conftest import run_cli

SHELL = b"M792 ; SHELL C:\\x.exe\n"
# each head that made a walk skip a file, then a line a firmware runs
HEADS = {
    "nul": b"\0\0\n",
    "shebang": b"#!/bin/sh\n",
    "ini": b"[printer]\n",
    "key-value": b"a = 1\nb = 2\nc = 3\nd = 4\n",
    "org": b"* Heading\n",
    "netcdf": b"CDF\x01\0\0\0\0\n",
    "hdf5": b"\x89HDF\r\n\x1a\n\0\n",
}


def _errors(proc) -> list[str]:
    return [line for line in proc.stderr.decode().splitlines() if not line.startswith("gclint: note:")]


@pytest.mark.parametrize(
    ("head", "extension"), [(head, (".nc", ".cnc", ".g", ".tap")[i % 4]) for i, head in enumerate(sorted(HEADS))]
)
def test_a_job_is_read_whatever_its_head(tmp_path: Path, head: str, extension: str) -> None:
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    (jobs / f"job{extension}").write_bytes(HEADS[head] + SHELL)
    proc = run_cli("check", "--no-cache", "-f", "json", "jobs", cwd=tmp_path)
    found = [(f["path"], f["code"]) for f in json.loads(proc.stdout)]
    assert (f"jobs/job{extension}", "SC001") in found, (found, proc.stderr)
    if head != "key-value":  # (three settings lines and a command: read as G-code, SX001 on the settings)
        [error] = _errors(proc)
        assert f"jobs/job{extension}" in error and re.search("not (a )?G-code", error)
        assert proc.returncode == 2 and "only the security rules read it" in error, error


def test_the_reproducers(tmp_path: Path) -> None:
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    (jobs / "job.nc").write_bytes(b"#!/bin/sh\nrm /sd/config.txt\n")
    proc = run_cli("check", "--no-cache", "jobs", cwd=tmp_path)
    assert proc.returncode == 2 and b"SC003" in proc.stdout, proc.stderr
    [error] = _errors(proc)
    assert error.startswith("gclint: jobs/job.nc: a script (#!/bin/sh), not G-code:"), error
    (tmp_path / "stop.g").write_bytes(b'\0\0\nM30 "0:/sys/config.g"\n')
    proc = run_cli("check", "--no-cache", "--force-exclude", "--", "stop.g", cwd=tmp_path)
    assert proc.returncode == 2 and b"SC005" in proc.stdout, proc.stderr
    [error] = _errors(proc)
    assert "stop.g" in error and "binary data" in error


def test_a_line_ends_at_its_first_nul_byte_as_a_firmware_reads_it(tmp_path: Path) -> None:
    """M30 with a name ending in "\\0.txt": the firmware's string ends at the NUL, so the file it deletes is
    config.g; and what follows a NUL on a line is not a command of its own."""
    (tmp_path / "a.nc").write_bytes(b'\0\0\nM30 "0:/sys/config.g"\0.txt\nG4 P0\0M792 ; SHELL C:\\x.exe\n' + SHELL)
    proc = run_cli("check", "--no-cache", "-f", "json", "a.nc", cwd=tmp_path)
    found = sorted((f["line"], f["code"]) for f in json.loads(proc.stdout))
    assert found == [(2, "SC005"), (4, "SC001")], found
    assert proc.returncode == 2


def test_the_cut_stream_keeps_line_numbers_and_reads_in_any_sizes() -> None:
    data = b"a\0b\nc\n\0\0\n\nd\0" + b"\0" * 5000 + b"\ne"
    for size in (1, 3, 4096, -1):
        stream = CutAtNul(io.BytesIO(data), b"<")
        out = b""
        while True:
            block = stream.read(size)
            out += block
            if not block or size < 0:
                break
        assert out == b"<a\nc\n\n\nd\ne", size


def test_the_user_may_exclude_what_is_not_a_job(tmp_path: Path) -> None:
    jobs = tmp_path / "jobs"
    (jobs / "data").mkdir(parents=True)
    (jobs / "data" / "model.nc").write_bytes(HEADS["netcdf"] + b"\0" * 100)
    (jobs / "ok.gcode").write_text("; gclint: dialect=marlin\nG28\n")
    assert run_cli("check", "--no-cache", "jobs", cwd=tmp_path).returncode == 2
    assert run_cli("check", "--no-cache", "--extend-exclude", "jobs/data", "jobs", cwd=tmp_path).returncode == 0
    (tmp_path / "ci.toml").write_text('extend-exclude = ["jobs/data"]\n')
    assert run_cli("check", "--no-cache", "--config", "ci.toml", "jobs", cwd=tmp_path).returncode == 0
    (jobs / ".gclint.toml").write_text('extend-exclude = ["data"]\n')  # found beside the jobs: not enough
    proc = run_cli("check", "--no-cache", "jobs", cwd=tmp_path)
    assert proc.returncode == 2 and b"model.nc" in proc.stderr


@pytest.mark.parametrize("name", ["job.gc", "job.GC", "job.gcode ", "job.nc.", "job.g  "])
def test_job_names_a_walk_once_passed_over_are_checked(tmp_path: Path, name: str) -> None:
    """``.gc`` is a G-code extension; Windows and FAT drop trailing spaces and dots from a name, so
    ``job.gcode `` reaches a printer as ``job.gcode``."""
    (tmp_path / "jobs").mkdir()
    (tmp_path / "jobs" / name).write_bytes(SHELL)
    proc = run_cli("check", "--no-cache", "-f", "json", "jobs", cwd=tmp_path)
    assert proc.returncode == 1 and [f["code"] for f in json.loads(proc.stdout)] == ["SC001"], proc.stderr


def test_a_job_package_is_never_passed_unread(tmp_path: Path) -> None:
    """An Ultimaker Format Package is a ZIP archive with the G-code inside: the check cannot read it."""
    import zipfile

    (tmp_path / "jobs").mkdir()
    with zipfile.ZipFile(tmp_path / "jobs" / "print.ufp", "w") as package:
        package.writestr("/3D/model.gcode", SHELL)
    proc = run_cli("check", "--no-cache", "jobs", cwd=tmp_path)
    errors = _errors(proc)
    assert proc.returncode == 2 and any("print.ufp" in e and "ZIP archive" in e for e in errors), errors


@pytest.mark.parametrize("text", ["max_velocity = 300\nmax_accel = 3000\n", "max_velocity = 300\n"])
def test_a_short_key_value_file_is_not_read_as_klipper_commands(tmp_path: Path, text: str) -> None:
    # (Klipper would stop at "Unknown command": MAX_VELOCITY is no command; a gate must not say "passed")
    job = tmp_path / "printer.gcode"
    job.write_text(text)
    proc = run_cli("check", "--no-cache", str(job))
    assert proc.returncode == 2, proc.stdout
    assert "'key = value' configuration file" in proc.stderr.decode()


def test_a_klipper_command_with_key_value_words_is_g_code(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text("; gclint: dialect=marlin\nSET_FAN_SPEED FAN=part SPEED=0.5\n")
    assert run_cli("check", "--no-cache", "--flavor", "klipper", str(job)).returncode == 0
