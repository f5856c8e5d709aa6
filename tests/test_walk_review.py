"""What a black-box security review found a hostile commit could hide from a CI gate or pre-commit hook that
runs gclint over a folder, and what gclint does now:

1. a committed .gitignore hid a tracked job: tracked files are never left out by .gitignore, and what the
   user's own patterns leave out is said (one line; -v lists each; "all excluded" says what and why);
2. jobs in tool-named folders (node_modules, venv, ...) were skipped in silence: files git tracks there
   are checked, and the untracked ones are counted in the note unless the folder is where one is expected;
3. committed links to files outside the walked folder were read (into SARIF snippets): not read, a note;
4. folder --fix/--add-noqa wrote through such links: they are never written;
5. a FIFO where postprocess writes its report hung the export: one line, no hang.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from gclint import runner
from gclint.excludes import Excluder, LeftOut

from .conftest import run_cli

HOSTILE = "M792 ; SHELL C:\\evil.exe\n"  # SC001 in any dialect that reads it as Hyrel (by content)
CLEAN = "; gclint: dialect=hyrel\nG28 X0 Y0\nM30\n"
needs_git = pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
needs_links = pytest.mark.skipif(not hasattr(os, "symlink"), reason="no symbolic links")


def _git(repo: Path, *args: str) -> None:
    subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True)


def _repo(tmp_path: Path) -> Path:
    """A repository with jobs/ok.gcode (clean) and jobs/evil.gcode (hostile), neither tracked yet."""
    _git(tmp_path, "init", "-q")
    (tmp_path / "jobs").mkdir()
    (tmp_path / "jobs" / "ok.gcode").write_text(CLEAN)
    (tmp_path / "jobs" / "evil.gcode").write_text(HOSTILE)
    return tmp_path


def _codes(proc: subprocess.CompletedProcess) -> set[tuple[str, str]]:
    return {(Path(f["path"]).as_posix(), f["code"]) for f in json.loads(proc.stdout)}


def _notes(proc: subprocess.CompletedProcess) -> list[str]:
    return [line for line in proc.stderr.decode().splitlines() if line.startswith("gclint: note:")]


# -- 1. .gitignore and exclude patterns -----------------------------------------------------------------------


@needs_git
def test_a_tracked_job_is_checked_though_a_committed_gitignore_names_it(tmp_path: Path) -> None:
    repo = _repo(tmp_path)
    (repo / ".gitignore").write_text("evil.gcode\n")
    _git(repo, "add", ".gitignore")
    _git(repo, "add", "-f", "jobs/evil.gcode")
    proc = run_cli("check", "--no-cache", "-f", "json", "--", "jobs", cwd=repo)
    assert proc.returncode == 1 and ("jobs/evil.gcode", "SC001") in _codes(proc), proc.stderr
    # pre-commit passes the staged file by name, with --force-exclude
    proc = run_cli("check", "--no-cache", "--force-exclude", "--", "jobs/evil.gcode", cwd=repo)
    assert proc.returncode == 1 and b"SC001" in proc.stdout and b"no files left" not in proc.stderr
    # a .gitignored folder holding a tracked job is entered for it
    (repo / ".gitignore").write_text("jobs/\n")
    proc = run_cli("check", "--no-cache", "-f", "json", ".", cwd=repo)
    assert proc.returncode == 1 and ("jobs/evil.gcode", "SC001") in _codes(proc), proc.stderr
    # the untracked clean job beside it is still ignored, and said to be
    assert ("jobs/ok.gcode", "HY010") not in _codes(proc)
    assert any("1 G-code file excluded (.gitignore: jobs/ok.gcode)" in n for n in _notes(proc)), _notes(proc)


@needs_git
def test_an_untracked_gitignored_job_is_left_out_with_a_note(tmp_path: Path) -> None:
    repo = _repo(tmp_path)
    (repo / ".gitignore").write_text("evil.gcode\n")
    proc = run_cli("check", "--no-cache", "--", "jobs", cwd=repo)
    assert proc.returncode == 0, proc.stdout
    assert "gclint: note: 1 G-code file excluded (.gitignore: jobs/evil.gcode); -v lists them" in _notes(proc)
    proc = run_cli("check", "--no-cache", "-v", "--", "jobs", cwd=repo)
    assert "gclint: note: jobs/evil.gcode: ignored by .gitignore" in _notes(proc), _notes(proc)
    proc = run_cli("check", "--no-cache", "-q", "--", "jobs", cwd=repo)
    assert proc.returncode == 0 and _notes(proc) == []
    proc = run_cli("check", "--no-cache", "--force-exclude", "--", "jobs/evil.gcode", cwd=repo)
    assert proc.returncode == 0
    assert "no files left to check (all excluded): 1 G-code file excluded (.gitignore: jobs/evil.gcode)" in (
        proc.stderr.decode()
    )


@needs_git
def test_exclude_patterns_still_exclude_tracked_jobs_but_say_so(tmp_path: Path) -> None:
    repo = _repo(tmp_path)
    (repo / "gclint.toml").write_text('extend-exclude = ["jobs/evil.gcode"]\n')
    _git(repo, "add", "jobs")
    config = ("--config", "gclint.toml")  # the user's own configuration (a found one cannot exclude: issue 25)
    proc = run_cli("check", "--no-cache", *config, "--", "jobs", cwd=repo)
    assert proc.returncode == 0 and b"SC001" not in proc.stdout  # the user asked for it
    assert "gclint: note: 1 G-code file excluded (extend-exclude: jobs/evil.gcode); -v lists them" in _notes(proc)
    proc = run_cli("check", "--no-cache", "-v", *config, "--", "jobs", cwd=repo)
    assert "gclint: note: jobs/evil.gcode: excluded by extend-exclude 'jobs/evil.gcode' (gclint.toml)" in _notes(proc)
    proc = run_cli("check", "--no-cache", "--force-exclude", *config, "--", "jobs/evil.gcode", cwd=repo)
    assert proc.returncode == 0
    err = proc.stderr.decode()
    assert "no files left to check (all excluded): 1 G-code file excluded (extend-exclude: jobs/evil.gcode)" in err
    proc = run_cli("check", "--no-cache", "--exclude", "evil.gcode", "--", "jobs", cwd=repo)
    assert "1 G-code file excluded (exclude: jobs/evil.gcode)" in proc.stderr.decode()


def test_an_excluded_folder_is_counted_and_its_first_files_named(tmp_path: Path) -> None:
    (tmp_path / "archive").mkdir()
    for n in range(5):
        (tmp_path / "archive" / f"old{n}.gcode").write_text(HOSTILE)
    (tmp_path / "archive" / "notes.txt").write_text("not G-code\n")
    (tmp_path / "ok.gcode").write_text(CLEAN)
    (tmp_path / "gclint.toml").write_text('extend-exclude = ["archive"]\n')
    proc = run_cli("check", "--no-cache", "--config", "gclint.toml", ".", cwd=tmp_path)
    assert proc.returncode == 0
    names = ", ".join(f"archive/old{n}.gcode" for n in range(3))
    assert f"gclint: note: 5 G-code files excluded (extend-exclude: {names} and 2 more); -v lists them" in _notes(
        proc
    ), _notes(proc)


def test_past_the_counting_budget_an_excluded_folder_is_named(tmp_path: Path, monkeypatch) -> None:
    (tmp_path / "a" / "deeper").mkdir(parents=True)
    (tmp_path / "a" / "x.gcode").write_text(HOSTILE)
    (tmp_path / "a" / "deeper" / "y.gcode").write_text(HOSTILE)
    (tmp_path / "ok.gcode").write_text(CLEAN)
    monkeypatch.setattr(runner, "COUNT_BUDGET", 1)  # a's two entries use it up
    left_out: list[LeftOut] = []
    files, problems = runner.collect([str(tmp_path)], [], Excluder(extend_exclude=["a"]), left_out=left_out)
    assert [Path(f).name for f in files] == ["ok.gcode"] and problems == []
    assert [(Path(x.path).name, x.folder) for x in left_out] == [("deeper", True), ("x.gcode", False)]
    from gclint.excludes import summary

    assert summary(left_out).startswith("at least 1 G-code file excluded (extend-exclude: ")


@needs_git
def test_without_git_neither_gitignore_nor_tool_folders_leave_anything_out(tmp_path: Path) -> None:
    """Issue 25: when git cannot say which files it tracks, a .gitignore from the change (or a
    node_modules folder) must not hide the tracked jobs it names: everything is checked, with one note."""
    repo = _repo(tmp_path)
    (repo / ".gitignore").write_text("evil.gcode\n")
    (repo / "jobs" / "node_modules").mkdir()
    (repo / "jobs" / "node_modules" / "dep.gcode").write_text(HOSTILE)
    _git(repo, "add", "-f", "jobs/evil.gcode", "jobs/node_modules/dep.gcode")
    no_git = tmp_path / "empty-path"
    no_git.mkdir()
    proc = run_cli("check", "--no-cache", "-f", "json", "--", "jobs", cwd=repo, env={"PATH": str(no_git)})
    notes = _notes(proc)
    assert proc.returncode == 1, proc.stderr
    assert {("jobs/evil.gcode", "SC001"), ("jobs/node_modules/dep.gcode", "SC001")} <= _codes(proc)
    [note] = [n for n in notes if "git" in n]
    assert "cannot tell which files git tracks (git is not installed)" in note and "every G-code file" in note
    assert not any("excluded" in n for n in notes), notes


@needs_git
def test_when_git_refuses_the_repository_nothing_is_left_out(tmp_path: Path) -> None:
    """ "dubious ownership" (a checkout owned by another user, as in CI containers): git answers nothing."""
    repo = _repo(tmp_path)
    (repo / ".gitignore").write_text("evil.gcode\n")
    fake = tmp_path / "bin"
    fake.mkdir()
    git = fake / "git"
    git.write_text("#!/bin/sh\necho \"fatal: detected dubious ownership in repository at '$PWD'\" >&2\nexit 128\n")
    git.chmod(0o755)
    proc = run_cli("check", "--no-cache", "-f", "json", "--", "jobs", cwd=repo, env={"PATH": f"{fake}:/usr/bin:/bin"})
    assert proc.returncode == 1 and ("jobs/evil.gcode", "SC001") in _codes(proc), proc.stderr
    assert any("dubious ownership" in n and "every G-code file" in n for n in _notes(proc)), _notes(proc)


@needs_git
def test_git_is_asked_about_the_repository_at_hand_and_runs_nothing_of_it(tmp_path: Path) -> None:
    repo = _repo(tmp_path)
    (repo / ".gitignore").write_text("evil.gcode\n")
    _git(repo, "add", "-f", "jobs/evil.gcode")
    marker = tmp_path / "fsmonitor-ran"
    _git(repo, "config", "core.fsmonitor", f"touch {marker}; true")
    other = tmp_path / "other"
    _git(other.parent, "init", "-q", str(other))
    # a git hook's environment (pre-commit) names a repository and index: not the ones asked about here
    env = {"GIT_DIR": str(other / ".git"), "GIT_INDEX_FILE": str(other / ".git" / "index")}
    proc = run_cli("check", "--no-cache", "-f", "json", "--", "jobs", cwd=repo, env=env)
    assert proc.returncode == 1 and ("jobs/evil.gcode", "SC001") in _codes(proc), proc.stderr
    assert not marker.exists(), "gclint ran the repository's core.fsmonitor command"


# -- 2. tool folders ------------------------------------------------------------------------------------------

TOOL_FOLDERS = ("node_modules", "venv", ".venv", "__pycache__", ".tox", "site-packages", ".mypy_cache")
TOOL_FOLDERS += (".ruff_cache", ".pytest_cache", ".hg", ".svn", ".bzr")


@pytest.mark.parametrize("name", TOOL_FOLDERS)
def test_jobs_in_a_tool_folder_inside_a_jobs_folder_are_said(tmp_path: Path, name: str) -> None:
    jobs = tmp_path / "jobs"  # (no repository: the top of the walk is where a tool folder is usual)
    (jobs / name).mkdir(parents=True)
    (jobs / "ok.gcode").write_text(CLEAN)
    (jobs / name / "evil.gcode").write_text(HOSTILE)
    left_out: list[LeftOut] = []
    files, problems = runner.collect([str(tmp_path)], [], Excluder(), left_out=left_out)
    assert [Path(f).name for f in files] == ["ok.gcode"] and problems == []
    [item] = left_out
    assert Path(item.path) == jobs / name / "evil.gcode" and not item.why.quiet and not item.folder


@needs_git
def test_tool_folders_through_the_command_line(tmp_path: Path) -> None:
    repo = _repo(tmp_path)
    (repo / "jobs" / "evil.gcode").unlink()
    for folder in ("jobs/node_modules", "jobs/venv", ".venv", "node_modules"):
        (repo / folder).mkdir()
        (repo / folder / "part.gcode").write_text(HOSTILE)
    proc = run_cli("check", "--no-cache", ".", cwd=repo)
    assert proc.returncode == 0
    said = "2 G-code files excluded (tool folder: jobs/node_modules/part.gcode, jobs/venv/part.gcode)"
    assert f"gclint: note: {said}; -v lists them" in _notes(proc), _notes(proc)  # not the root-level ones
    proc = run_cli("check", "--no-cache", "-v", ".", cwd=repo)
    assert "gclint: note: .venv: a tool folder, not walked (its files tracked by git are checked)" in _notes(proc)
    # committed jobs in tool folders are checked, wherever the folder is
    _git(repo, "add", "-f", "jobs/venv/part.gcode", "node_modules/part.gcode")
    proc = run_cli("check", "--no-cache", "-f", "json", ".", cwd=repo)
    assert proc.returncode == 1
    found = {path for path, code in _codes(proc) if code == "SC001"}
    assert found == {"jobs/venv/part.gcode", "node_modules/part.gcode"}, proc.stderr
    assert "1 G-code file excluded (tool folder: jobs/node_modules/part.gcode)" in proc.stderr.decode()
    # pre-commit names them
    proc = run_cli("check", "--no-cache", "--force-exclude", "--", "jobs/venv/part.gcode", cwd=repo)
    assert proc.returncode == 1 and b"SC001" in proc.stdout


def test_outside_a_repository_a_tool_folder_at_the_top_is_usual(tmp_path: Path) -> None:
    (tmp_path / ".venv").mkdir()
    (tmp_path / ".venv" / "x.gcode").write_text(HOSTILE)
    (tmp_path / "sub" / "node_modules").mkdir(parents=True)
    (tmp_path / "sub" / "node_modules" / "y.gcode").write_text(HOSTILE)
    (tmp_path / "ok.gcode").write_text(CLEAN)
    left_out: list[LeftOut] = []
    files, _ = runner.collect([str(tmp_path)], [], Excluder(), left_out=left_out)
    assert [Path(f).name for f in files] == ["ok.gcode"]
    assert [(Path(x.path).name, x.why.quiet) for x in left_out] == [(".venv", True), ("y.gcode", False)]


# -- 3. and 4. links to files outside the walked folder ---------------------------------------------------------


@needs_links
def test_a_link_to_a_file_outside_the_folder_is_not_read(tmp_path: Path) -> None:
    secret = tmp_path / "home" / "id_ed25519"
    secret.parent.mkdir()
    secret.write_text("M104 S200 ; PRIVATE-KEY-MATERIAL\nG1 X1 E1\n")
    jobs = tmp_path / "repo" / "jobs"
    jobs.mkdir(parents=True)
    (jobs / "ok.gcode").write_text(CLEAN)
    (jobs / "k.gcode").symlink_to(secret)
    proc = run_cli("check", "--no-cache", "-f", "sarif", "--", "jobs", cwd=jobs.parent)
    assert b"PRIVATE-KEY-MATERIAL" not in proc.stdout
    errors = [line for line in proc.stderr.decode().splitlines() if "jobs/k.gcode" in line]
    assert len(errors) == 1 and "a symbolic link to a file outside this checkout" in errors[0], errors
    assert "not read" in errors[0] and proc.returncode == 2  # (a job the gate could not read: issue 25)
    # named, it is read: the user asked for it
    proc = run_cli("check", "--no-cache", "-f", "sarif", "--", "jobs/k.gcode", cwd=jobs.parent)
    assert b"jobs/k.gcode" in proc.stdout


@needs_links
@pytest.mark.parametrize("how", ["--fix", "--add-noqa", "--unsafe-fixes"])
def test_folder_fixes_never_write_through_links_out_of_the_folder(tmp_path: Path, how: str) -> None:
    outside = tmp_path / "outside"
    outside.mkdir()
    farm = outside / "farmjob.gcode"
    job = "; gclint: dialect=hyrel\nM229 E1 D0\nM109 T12 S200\nG1 X1 F600\nM30\n"  # HY001, v4 numbering
    farm.write_text(job)
    jobs = tmp_path / "repo" / "jobs"
    jobs.mkdir(parents=True)
    (jobs / "ok.gcode").write_text(CLEAN)
    (jobs / "abs.gcode").symlink_to(farm)
    (jobs / "rel.gcode").symlink_to(Path("..", "..", "outside", "farmjob.gcode"))
    args = ["--fix", "--unsafe-fixes"] if how == "--unsafe-fixes" else [how]
    run_cli("check", "--no-cache", *args, "--", "jobs", cwd=jobs.parent)
    assert farm.read_text() == job and farm.is_file() and (jobs / "abs.gcode").is_symlink()


@needs_links
def test_a_link_put_in_the_folder_after_the_walk_is_not_fixed(tmp_path: Path, monkeypatch) -> None:
    """The walk saw a file; by the time fixes are written it is a link out of the folder: not written."""
    from click.testing import CliRunner

    from gclint import cli

    outside = tmp_path / "outside.gcode"
    job = "; gclint: dialect=hyrel\nM109 T12 S200\nG1 X1 F600\nM30\n"
    outside.write_text(job)
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    (jobs / "a.gcode").write_text(job)
    real_run = runner.run

    def run_then_swap(*args, **kwargs):
        results = real_run(*args, **kwargs)
        (jobs / "a.gcode").unlink()
        (jobs / "a.gcode").symlink_to(outside)
        return results

    monkeypatch.setattr(runner, "run", run_then_swap)
    result = CliRunner().invoke(cli.main, ["check", "--no-cache", "--fix", "--unsafe-fixes", "--", str(jobs)])
    assert outside.read_text() == job
    assert "outside the folder: not fixed" in result.output and result.exit_code == 2, result.output


# -- 5. postprocess and a FIFO where the report goes ----------------------------------------------------------


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes")
def test_a_fifo_at_the_report_path_does_not_hang_postprocess(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(CLEAN)
    os.mkfifo(tmp_path / "job.gcode.gclint.txt")
    proc = run_cli("postprocess", str(job), timeout=30)  # before: blocked for ever opening the FIFO
    err = proc.stderr.decode()
    assert proc.returncode == 0, err
    assert "job.gcode.gclint.txt: is a named pipe that nothing reads (the report was not written)" in err


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes")
def test_a_fifo_with_a_reader_is_written(tmp_path: Path) -> None:
    import threading

    from gclint.io import OutputError, write_text

    fifo = tmp_path / "out.fifo"
    os.mkfifo(fifo)
    with pytest.raises(OutputError, match="named pipe that nothing reads"):
        write_text(str(fifo), lambda out: out.write("x\n"))
    got: list[bytes] = []
    ready = threading.Event()

    def read() -> None:
        ready.set()
        with open(fifo, "rb") as f:
            got.append(f.read())

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    ready.wait()
    for _ in range(100):  # the reader's open() is under way once the writer's open succeeds
        try:
            write_text(str(fifo), lambda out: out.write("report\n" * 20000))  # more than a pipe's buffer
            break
        except OutputError:
            import time

            time.sleep(0.05)
    reader.join(timeout=10)
    assert got == [b"report\n" * 20000]


@needs_links
def test_pre_commit_does_not_follow_a_named_link_to_a_folder(tmp_path):
    # (a second stranger's attack: --force-exclude held what pre-commit names to a walk, but a named link to a
    # folder was walked, outside the checkout too, and --fix wrote there)
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "a.gcode").write_text("M106 S255\n")
    repo = tmp_path / "repo"
    repo.mkdir()
    os.symlink(outside, repo / "lnk")
    proc = run_cli("check", "--no-cache", "--force-exclude", "--fix", "lnk", cwd=repo)
    assert proc.returncode == 2 and "a symbolic link to a folder, not followed" in proc.stderr.decode()
    assert (outside / "a.gcode").read_text() == "M106 S255\n"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes")
def test_pre_commit_naming_a_pipe_does_not_hang(tmp_path):
    os.mkfifo(tmp_path / "job.gcode")
    proc = run_cli("check", "--no-cache", "--force-exclude", "job.gcode", cwd=tmp_path, timeout=30)
    assert proc.returncode == 2 and "a named pipe, not a file" in proc.stderr.decode()


@pytest.mark.parametrize("name", ["a.bgcode", "b.gcode.3mf", "c.gcode\t", "d.GCODE. "])
def test_a_walk_finds_jobs_it_cannot_read_and_says_so(tmp_path, name):
    (tmp_path / "ok.gcode").write_text(CLEAN)
    (tmp_path / name).write_bytes(b"GCDE\x01\x00" if name.endswith("bgcode") else HOSTILE.encode())
    proc = run_cli("check", "--no-cache", ".", cwd=tmp_path)
    shown = (proc.stdout + proc.stderr).decode()
    assert proc.returncode == (2 if name.endswith("bgcode") else 1) and name.rstrip(" \t.") in shown, shown


def test_a_flashforge_gx_job_is_found_and_its_gcode_still_gated(tmp_path):
    (tmp_path / "ok.gcode").write_text(CLEAN)
    (tmp_path / "job.gx").write_bytes(b"xgcode 1.0\n\x00\x00\x00\x00BM\x00\x00\nG28\nM30 /sys/config.g\n")
    proc = run_cli("check", "--no-cache", ".", cwd=tmp_path)
    shown = (proc.stdout + proc.stderr).decode()
    assert proc.returncode == 2 and "FlashForge .gx job" in shown and "SC005" in shown, shown


def test_a_link_to_a_folder_found_by_a_walk_fails_the_check(tmp_path):
    (tmp_path / "payload").mkdir()
    (tmp_path / "payload" / "evil.gcode").write_text("M30 /sys/config.g\n")
    (tmp_path / "jobs").mkdir()
    (tmp_path / "jobs" / "ok.gcode").write_text(CLEAN)
    (tmp_path / "jobs" / "sub").symlink_to(tmp_path / "payload")
    proc = run_cli("check", "--no-cache", "jobs", cwd=tmp_path)
    assert proc.returncode == 2 and b"a symbolic link to a folder" in proc.stderr, proc.stderr
