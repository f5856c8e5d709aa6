"""Folder walks (issue 12, items 12 and 15): nothing is skipped in silence.  An unreadable folder or file is
one line on stderr and exit 2 while everything else is still checked; hidden folders are walked and links
to folders are not followed (as ruff does), with a note; version-control folders are skipped.  What a
review found a hostile commit could hide from a walk is in test_walk_review.py."""

from __future__ import annotations

import functools
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from gclint import runner

from .conftest import ROOT, run_cli

HOSTILE = "; gclint: dialect=hyrel\nM792 ; SHELL C:\\x.exe\n"
CLEAN = "; gclint: dialect=hyrel\nG28 X0 Y0\n"


def _tree(tmp_path: Path) -> Path:
    jobs = tmp_path / "jobs"
    (jobs / "sub").mkdir(parents=True)
    (jobs / "a.gcode").write_text(CLEAN)
    (jobs / "sub" / "b.gcode").write_text(HOSTILE)
    return jobs


def test_an_unreadable_folder_is_reported(tmp_path: Path, monkeypatch) -> None:
    jobs = _tree(tmp_path)
    (jobs / "z").mkdir()
    (jobs / "z" / "c.gcode").write_text(CLEAN)
    real_scandir = os.scandir

    def scandir(path):
        if os.path.basename(path) == "sub":
            raise PermissionError(13, "Permission denied")
        return real_scandir(path)

    monkeypatch.setattr(os, "scandir", scandir)
    files, problems = runner.collect([str(jobs)])
    assert [Path(f).name for f in files] == ["a.gcode", "c.gcode"]
    [problem] = problems
    assert problem.path.endswith("sub") and "cannot read this folder: Permission denied" in problem.error


@functools.cache
def _as_nobody() -> list[str] | None:
    """A command prefix that runs as an unprivileged user (root reads everything), or None; None too when
    that user cannot read gclint itself (a checkout in a private folder, as ``mktemp -d`` makes)."""
    if not hasattr(os, "getuid"):
        return None
    if os.getuid() != 0:
        return []
    setpriv = shutil.which("setpriv")
    if setpriv is None:
        return None
    prefix = [setpriv, "--reuid=65534", "--regid=65534", "--clear-groups"]
    probe = subprocess.run(
        [*prefix, sys.executable, "-c", "import gclint"],
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        capture_output=True,
    )
    return prefix if probe.returncode == 0 else None


def _run_unprivileged(prefix: list[str], *args: str, cwd: Path) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "GCLINT_CACHE_DIR"}
    env["PYTHONPATH"] = str(ROOT)
    return subprocess.run(
        [*prefix, sys.executable, "-m", "gclint", "check", "--no-cache", *args],
        capture_output=True,
        cwd=cwd,
        env=env,
        timeout=120,
    )


def _open_up(path: Path) -> None:
    for parent in [path, *path.parents]:
        if parent == Path("/"):
            break
        os.chmod(parent, os.stat(parent).st_mode | 0o755)


@pytest.mark.skipif(_as_nobody() is None, reason="cannot run as an unprivileged user")
def test_unreadable_folder_and_file_through_the_command_line(tmp_path: Path) -> None:
    prefix = _as_nobody()
    jobs = _tree(tmp_path)
    locked = jobs / "locked"
    locked.mkdir()
    (locked / "c.gcode").write_text(CLEAN)
    secret = tmp_path / "secret.gcode"
    secret.write_text(CLEAN)
    _open_up(jobs / "sub")
    for f in (jobs / "a.gcode", jobs / "sub" / "b.gcode"):
        f.chmod(0o644)
    locked.chmod(0o700 if prefix else 0o000)
    secret.chmod(0o600 if prefix else 0o000)
    try:
        proc = _run_unprivileged(prefix, "--format", "json", str(jobs), str(secret), cwd=tmp_path)
    finally:
        locked.chmod(0o755)
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "Traceback" not in stderr and "Usage" not in stderr, stderr
    lines = sorted(line for line in stderr.splitlines() if line.strip())
    assert len(lines) == 2, lines
    assert "locked" in lines[0] and "Permission denied" in lines[0], lines
    assert "secret.gcode" in lines[1] and "permission denied" in lines[1].lower(), lines
    assert "SC001" in {f["code"] for f in json.loads(proc.stdout)}, "the readable files were not all checked"
    for f in (jobs / "a.gcode", jobs / "sub" / "b.gcode"):
        f.write_text(CLEAN + "M30\n")
    locked.chmod(0o700 if prefix else 0o000)
    try:
        proc = _run_unprivileged(prefix, str(jobs), cwd=tmp_path)
    finally:
        locked.chmod(0o755)
    assert proc.returncode == 2 and b"All checks passed" not in proc.stdout, proc.stdout
    assert b"could not be checked" in proc.stdout


def test_hidden_folders_are_walked_and_tool_folders_are_not(tmp_path: Path) -> None:
    jobs = _tree(tmp_path)
    (jobs / ".queue").mkdir()
    (jobs / ".queue" / "next.gcode").write_text(HOSTILE)
    (jobs / ".git").mkdir()
    (jobs / ".git" / "x.gcode").write_text(HOSTILE)
    files, problems = runner.collect([str(jobs)])
    names = [os.path.relpath(f, jobs) for f in files]
    assert names == ["a.gcode", os.path.join(".queue", "next.gcode"), os.path.join("sub", "b.gcode")]
    assert problems == []


@pytest.mark.skipif(not hasattr(os, "symlink"), reason="no symbolic links")
def test_links_to_folders_are_not_followed_and_said_so(tmp_path: Path) -> None:
    jobs = _tree(tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "x.gcode").write_text(HOSTILE)
    (jobs / "linked").symlink_to(elsewhere, target_is_directory=True)
    (jobs / "sub" / "loop").symlink_to(jobs, target_is_directory=True)
    (jobs / "job-link.gcode").symlink_to(elsewhere / "x.gcode")  # outside the folder: not read, exit 2
    (jobs / "inside-link.gcode").symlink_to(jobs / "sub" / "b.gcode")  # inside, but b.gcode is checked
    notes: list[str] = []
    files, problems = runner.collect([str(jobs)], notes)
    assert [os.path.relpath(f, jobs) for f in files] == ["a.gcode", os.path.join("sub", "b.gcode")]
    # (a link to a folder outside the walk fails the check; one to a folder the walk reads anyway is a note)
    assert len(notes) == 2 and sum("not followed" in n for n in notes) == 1, notes
    assert any("loop" in n for n in notes) and any("linked" in p.error for p in problems)
    assert any("inside-link.gcode" in n and "not checked twice" in n for n in notes)
    [problem] = [p for p in problems if "job-link.gcode" in (p.error or "")]
    assert "outside" in problem.error and "not read" in problem.error
    from .conftest import run_cli

    proc = run_cli("check", "--no-cache", str(jobs), timeout=60)
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "linked" in stderr and "not followed" in stderr, stderr


def test_jobs_are_capped_with_a_note(tmp_path: Path) -> None:
    from .conftest import run_cli

    jobs = _tree(tmp_path)
    proc = run_cli("check", "--no-cache", "--jobs", "100000", str(jobs), timeout=120)
    stderr = proc.stderr.decode()
    assert proc.returncode == 1 and "--jobs 100000" in stderr and "using" in stderr, stderr


def test_show_settings_says_where_the_cache_is(tmp_path: Path) -> None:
    from .conftest import run_cli

    jobs = _tree(tmp_path)
    proc = run_cli("check", "--show-settings", str(jobs), env={"XDG_CACHE_HOME": str(tmp_path / "xdg")})
    shown = proc.stdout.decode()
    assert proc.returncode == 0 and f"Result cache: {tmp_path / 'xdg' / 'gclint' / 'projects'}" in shown, shown


def test_other_formats_with_a_shared_extension_are_not_passed_but_can_be_excluded(tmp_path: Path) -> None:
    """A gate cannot tell a NetCDF .nc or an ANTLR .g in a jobs folder from a job dressed up as one (issue 25):
    each is one error line (exit 2), until the user's own command line or --config excludes it."""
    from tests.conftest import run_cli

    folder = tmp_path / "jobs"
    folder.mkdir()
    (folder / "ok.gcode").write_text("; gclint: dialect=marlin\nG28\nG1 X1 F600\n")
    (folder / "data.nc").write_bytes(b"CDF\x01\x00\x00\x00\x00binary netcdf")
    (folder / "Expr.g").write_text("grammar Expr;\nexpr : term ('+' term)* ;\n")
    proc = run_cli("check", "--no-cache", str(folder))
    err = proc.stderr.decode()
    assert proc.returncode == 2, err
    lines = err.splitlines()
    assert [line for line in lines if "data.nc" in line and "NetCDF" in line and "not a job" in line], err
    assert [line for line in lines if "Expr.g" in line and "ANTLR" in line], err
    proc = run_cli("check", "--no-cache", "--extend-exclude", "data.nc,Expr.g", str(folder))
    assert proc.returncode == 0, proc.stderr
    (folder / "broken.gcode").write_bytes(bytes(range(256)) * 4)  # a .gcode is G-code by name: broken
    proc = run_cli("check", "--no-cache", "--extend-exclude", "data.nc,Expr.g", str(folder))
    assert proc.returncode == 2 and "broken.gcode" in proc.stderr.decode() and "binary" in proc.stderr.decode()


def test_a_text_file_with_gcode_lines_is_read_whatever_its_first_line(tmp_path):
    """The job's author writes the first line: '#!x' or a NetCDF magic number over G-code lines must not hide
    the lines a firmware runs; a real NetCDF file (binary) and an ANTLR grammar are not passed either."""
    folder = tmp_path / "w"
    folder.mkdir()
    (folder / "job.nc").write_bytes(b"#!x\nG0 X0 Y0\nrm /sd/config.txt\nM30\n")
    (folder / "job2.nc").write_bytes(b"CDF\x01\nG0 X0 Y0\nrm /sd/config.txt\nM30\n")
    (folder / "real.nc").write_bytes(b"CDF\x01\x00\x00\x00\x00G0\n")
    (folder / "grammar.g").write_bytes(b"grammar T;\nrule : A ;\n")
    proc = run_cli("check", "--no-cache", "-f", "json", str(folder))
    err = proc.stderr.decode()
    assert proc.returncode == 2, err
    assert "job.nc: a script" in err and "job2.nc: NetCDF" in err and "real.nc: NetCDF data" in err
    assert "grammar.g: an ANTLR grammar" in err
    found = {(Path(f["path"]).name, f["line"], f["code"]) for f in json.loads(proc.stdout)}
    assert {("job.nc", 3, "SC003"), ("job2.nc", 3, "SC003")} <= found, found


def _deep(root: Path, depth: int) -> Path:
    path = root
    for _ in range(depth):
        path = path / "d"
        path.mkdir()
        (path / "a.gcode").write_text(CLEAN)
    return path


@pytest.mark.parametrize("in_repository", [False, True])
def test_deep_folders_cost_a_bounded_number_of_lookups_per_folder(tmp_path: Path, monkeypatch, in_repository) -> None:
    """Issue 25: 1,500 nested folders took 103 s (each file's folders were resolved, matched and searched
    for .git and configuration files from the top again).  Counted, not timed: file-system lookups grow
    with the number of folders, not with its square."""
    if in_repository:
        (tmp_path / ".git").mkdir()
        (tmp_path / ".gitignore").write_text("*.tmp\n")
    calls = [0]
    for name in ("stat", "lstat"):
        real = getattr(os, name)

        def counted(*args, real=real, **kwargs):
            calls[0] += 1
            return real(*args, **kwargs)

        monkeypatch.setattr(os, name, counted)
    counts = []
    for depth in (100, 200):
        top = tmp_path / f"t{depth}"
        top.mkdir()
        _deep(top, depth)
        from gclint.config import clear_found

        clear_found()
        calls[0] = 0
        files, problems = runner.collect([str(top)])
        assert len(files) == depth and problems == []
        for path in files:
            runner.options_for(path, runner.Options(), {}, None)
        counts.append(calls[0])
    assert counts[1] < 2.3 * counts[0] and counts[1] < 20 * 200, counts


def test_a_tree_1500_folders_deep_is_walked(tmp_path: Path) -> None:
    (tmp_path / ".git").mkdir()
    bottom = _deep(tmp_path, 1500)
    try:
        files, problems = runner.collect([str(tmp_path)])
        assert len(files) == 1500 and problems == []
    finally:  # (pytest removes old temporary folders with shutil.rmtree, which recurses once per folder)
        while bottom != tmp_path:
            (bottom / "a.gcode").unlink()
            bottom.rmdir()
            bottom = bottom.parent
