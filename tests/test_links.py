"""Symbolic links in a checked folder (issue 25).  A link whose target is inside the same checkout (the
repository, else the folder walked) is checked, under the link's name and without a word of what the
target holds; a link out of it is not read and is exit 2.  A link to a file that is checked anyway is not
checked twice (``--fix`` then has nothing to trip over), and nothing is written through a link found in a
folder.  Links named on the command line are followed, as the user asked."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

from .conftest import run_cli

pytestmark = pytest.mark.skipif(not hasattr(os, "symlink"), reason="no symbolic links")

PAYLOAD = "M792 ; SHELL C:\\x.exe ; PAYLOAD-TEXT\n"


def _checkout(tmp_path: Path) -> Path:
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=False, capture_output=True)
    (tmp_path / "jobs").mkdir()
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "payload.txt").write_text(PAYLOAD)
    (tmp_path / "jobs" / "evil.gcode").symlink_to(Path("..", "docs", "payload.txt"))
    return tmp_path


@pytest.mark.parametrize("fmt", ["json", "sarif", "github", "junit", "text", "full", "html"])
def test_a_link_inside_the_checkout_is_checked_without_showing_its_target(tmp_path: Path, fmt: str) -> None:
    repo = _checkout(tmp_path)
    proc = run_cli("check", "--no-cache", "-f", fmt, "--", "jobs", cwd=repo)
    assert proc.returncode == 1, proc.stderr
    out = proc.stdout.decode()
    assert "SC001" in out and "jobs/evil.gcode" in out
    assert "PAYLOAD-TEXT" not in out and "PAYLOAD-TEXT" not in proc.stderr.decode()


def test_a_linked_finding_names_the_rule_and_the_target(tmp_path: Path) -> None:
    repo = _checkout(tmp_path)
    proc = run_cli("check", "--no-cache", "-f", "json", "--select", "SC", "--", "jobs", cwd=repo)
    [finding] = json.loads(proc.stdout)
    assert finding["path"] == "jobs/evil.gcode" and finding["code"] == "SC001" and finding["line"] == 1
    assert "docs/payload.txt" in finding["message"] and "not shown" in finding["message"]
    assert "fix" not in finding


def test_a_link_out_of_the_checkout_is_not_read_and_fails(tmp_path: Path) -> None:
    repo = tmp_path / "repo"
    repo.mkdir()
    _checkout(repo)
    (tmp_path / "outside.gcode").write_text(PAYLOAD)
    (repo / "jobs" / "out.gcode").symlink_to(tmp_path / "outside.gcode")
    proc = run_cli("check", "--no-cache", "-f", "sarif", "--", "jobs", cwd=repo)
    assert proc.returncode == 2 and b"PAYLOAD-TEXT" not in proc.stdout
    [error] = [line for line in proc.stderr.decode().splitlines() if "out.gcode" in line]
    assert "outside this checkout" in error and "not read" in error
    # the user's own exclusion is enough
    proc = run_cli("check", "--no-cache", "--extend-exclude", "jobs/out.gcode", "--", "jobs", cwd=repo)
    assert proc.returncode == 1 and b"outside" not in proc.stderr
    # under the pre-commit hook (--force-exclude), a named link is held to the same rule
    proc = run_cli("check", "--no-cache", "--force-exclude", "--", "jobs/out.gcode", cwd=repo)
    assert proc.returncode == 2 and b"outside this checkout" in proc.stderr
    proc = run_cli("check", "--no-cache", "--force-exclude", "-f", "json", "--", "jobs/evil.gcode", cwd=repo)
    assert proc.returncode == 1 and b"PAYLOAD-TEXT" not in proc.stdout
    # named without it, a link is followed: the user asked for that file
    proc = run_cli("check", "--no-cache", "--", "jobs/out.gcode", cwd=repo)
    assert proc.returncode == 1 and b"x.exe" in proc.stdout


def test_outside_a_repository_the_walked_folder_is_the_checkout(tmp_path: Path) -> None:
    jobs = tmp_path / "jobs"
    (jobs / "sub").mkdir(parents=True)
    (jobs / "sub" / "real.txt").write_text(PAYLOAD)
    (jobs / "in.gcode").symlink_to(jobs / "sub" / "real.txt")
    (tmp_path / "beside.txt").write_text(PAYLOAD)
    (jobs / "out.gcode").symlink_to(tmp_path / "beside.txt")
    proc = run_cli("check", "--no-cache", "-f", "json", "jobs", cwd=tmp_path)
    assert {f["path"] for f in json.loads(proc.stdout)} == {"jobs/in.gcode"}
    assert proc.returncode == 2 and b"jobs/out.gcode: a symbolic link to a file outside" in proc.stderr


def test_a_link_to_a_file_in_the_same_folder_is_checked_once_and_fixed_once(tmp_path: Path) -> None:
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    job = "; gclint: dialect=hyrel\nM109 T12 S200\nG1 X1 F600\nM30\n"  # HY008, a safe fix
    (jobs / "a.gcode").write_text(job)
    (jobs / "b.gcode").symlink_to("a.gcode")
    proc = run_cli("check", "--no-cache", "-f", "json", "jobs", cwd=tmp_path)
    assert [f["path"] for f in json.loads(proc.stdout)] == ["jobs/a.gcode"], proc.stdout
    assert b"jobs/b.gcode: a link to jobs/a.gcode, which is checked" in proc.stderr
    proc = run_cli("check", "--no-cache", "--fix", "jobs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (jobs / "a.gcode").read_text() != job and (jobs / "b.gcode").is_symlink()


def test_nothing_is_written_through_a_link_found_in_a_folder(tmp_path: Path) -> None:
    repo = _checkout(tmp_path)
    (repo / "docs" / "payload.txt").write_text("; gclint: dialect=hyrel\nM109 T12 S200\nM9999\nM30\n")
    before = (repo / "docs" / "payload.txt").read_text()
    for how in (["--fix", "--unsafe-fixes"], ["--add-noqa"]):
        run_cli("check", "--no-cache", *how, "--", "jobs", cwd=repo)
        assert (repo / "docs" / "payload.txt").read_text() == before, how
