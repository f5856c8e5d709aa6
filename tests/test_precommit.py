"""The pre-commit hook, run by the real pre-commit in a throw-away git repository of G-code jobs.

The hook source is a temporary clone of this repository with the current working files committed on
top (pre-commit needs a committed revision), so the test checks the .pre-commit-hooks.yaml and the
code being worked on.  pre-commit builds the hook's environment with pip, like on a user's machine,
so the test needs the package index (PyPI) the first time; the environments are cached for the session.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import ROOT

GOOD = "; gclint: dialect=hyrel\nM6 T0 O1 X0 Y0 Z0\nG28 X0 Y0\nT0\nM109 T0 S200\nG1 X10 Y10 E1 F1200\nM30\n"
BAD = "; gclint: dialect=hyrel\nG28 X0 Y0\nG1 X10 X20 Y10 E1 F1200\nM9999\n"


def _pre_commit() -> list[str]:
    try:
        import pre_commit  # noqa: F401
    except ImportError:
        if os.environ.get("CI"):
            pytest.fail("pre-commit is not installed; it belongs in the test extras")
        pytest.skip("pre-commit is not installed (pip install pre-commit)")
    return [sys.executable, "-m", "pre_commit"]


def _git(*args: str, cwd: Path) -> str:
    env = dict(
        os.environ,
        GIT_AUTHOR_NAME="gclint test",
        GIT_AUTHOR_EMAIL="test@example.invalid",
        GIT_COMMITTER_NAME="gclint test",
        GIT_COMMITTER_EMAIL="test@example.invalid",
    )
    proc = subprocess.run(["git", *args], cwd=cwd, capture_output=True, env=env, timeout=120)
    assert proc.returncode == 0, proc.stderr.decode()
    return proc.stdout.decode().strip()


@pytest.fixture(scope="module")
def hook_repo(tmp_path_factory) -> tuple[Path, str]:
    """A clone of this repository with the working files (tracked and new) committed; returns (path, rev)."""
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    src = tmp_path_factory.mktemp("hook-source") / "gclint"
    _git("clone", "--quiet", "--no-hardlinks", str(ROOT), str(src), cwd=src.parent)
    listed = _git("ls-files", "-z", "--cached", "--others", "--exclude-standard", cwd=ROOT)
    for name in filter(None, listed.split("\0")):
        origin = ROOT / name
        if origin.is_file():
            target = src / name
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(origin, target)
        elif not origin.exists() and (src / name).exists():
            (src / name).unlink()  # deleted in the working tree
    _git("add", "-A", cwd=src)
    if _git("status", "--porcelain", cwd=src):
        _git("commit", "--quiet", "--no-verify", "-m", "working tree under test", cwd=src)
    return src, _git("rev-parse", "HEAD", cwd=src)


@pytest.fixture(scope="module")
def pre_commit_home(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("pre-commit-home")


def _jobs_repo(tmp_path: Path, hook_repo: tuple[Path, str]) -> Path:
    repo = tmp_path / "jobs"
    repo.mkdir()
    _git("init", "--quiet", cwd=repo)
    src, rev = hook_repo
    (repo / ".pre-commit-config.yaml").write_text(
        f"repos:\n  - repo: {src.as_posix()}\n    rev: {rev}\n    hooks:\n      - id: gclint\n"
    )
    return repo


def _run(repo: Path, home: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, PRE_COMMIT_HOME=str(home), PRE_COMMIT_COLOR="never")
    env.pop("GCLINT_CACHE_DIR", None)
    return subprocess.run([*_pre_commit(), "run", "--all-files"], cwd=repo, capture_output=True, env=env, timeout=900)


def test_hook_passes_good_jobs_and_fails_bad_ones(tmp_path, hook_repo, pre_commit_home):
    _pre_commit()
    repo = _jobs_repo(tmp_path, hook_repo)
    (repo / "part.gcode").write_text(GOOD)
    (repo / "notes.txt").write_text(BAD)  # not G-code by name: never passed to gclint
    (repo / "cnc").mkdir()
    (repo / "cnc" / "PLATE.NGC").write_text("G21\nG0 X0 Y0\nG1 X10 F100\nM2\n")
    _git("add", "-A", cwd=repo)
    passed = _run(repo, pre_commit_home)
    output = passed.stdout.decode() + passed.stderr.decode()
    assert passed.returncode == 0, output
    assert "gclint (G-code linter)" in output and "Passed" in output

    (repo / "jobs").mkdir()
    (repo / "jobs" / "broken job.GCODE").write_text(BAD)
    _git("add", "-A", cwd=repo)
    failed = _run(repo, pre_commit_home)
    output = failed.stdout.decode() + failed.stderr.decode()
    assert failed.returncode == 1, output
    assert "Failed" in output
    assert "jobs/broken job.GCODE:3:" in output and "SX002" in output
    assert "notes.txt" not in output


def test_hook_definition_matches_gcode_names():
    import re

    _pre_commit()
    import yaml  # pre-commit's own dependency

    hooks = {h["id"]: h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())}
    hook = hooks["gclint"]
    assert hook["entry"] == "gclint check --force-exclude" and hook["language"] == "python" and "types" not in hook
    pattern = re.compile(hook["files"])
    for name in ("a.gcode", "b.GCO", "c.g", "d.nc", "e.ngc", "f.cnc", "g.TAP", "h.gc", "i.ufp", "j.gcode ", "k.nc."):
        assert pattern.search(name), name  # (as a walk finds them: runner.is_job_name)
    for name in ("a.gcode.bak", "notes.txt", "g.py"):
        assert not pattern.search(name), name


# -- file names are never options (issue 12, item 4) --------------------------------------------------------------

EVIL = "; gclint: dialect=hyrel\nM792 ; SHELL C:\\x.exe\n"


def _hostile_names(repo: Path) -> None:
    (repo / "cfg.gcode").write_text('select = ["XX999"]\n')  # a "configuration" that switches every rule off
    (repo / "--config=cfg.gcode").write_text(EVIL)
    (repo / "--output=good.gcode").write_text(EVIL)
    (repo / "good.gcode").write_text(GOOD)
    (repo / "-o").mkdir()
    (repo / "-o" / "x.gcode").write_text(GOOD)


def test_file_names_are_never_options_through_the_exact_hook_entry(tmp_path):
    """pre-commit runs ``entry + args + file names``; the hook's own args end the options."""
    import shlex

    _pre_commit()
    import yaml

    hook = {h["id"]: h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())}["gclint"]
    _hostile_names(tmp_path)
    names = ["--config=cfg.gcode", "--output=good.gcode", "cfg.gcode", "good.gcode"]
    command = [sys.executable, "-m", "gclint", *shlex.split(hook["entry"])[1:], *hook.get("args", []), *names]
    env = dict(os.environ, PRE_COMMIT="1")
    env.pop("GCLINT_CACHE_DIR", None)
    proc = subprocess.run(command, cwd=tmp_path, capture_output=True, env=env, timeout=120)
    output = proc.stdout.decode() + proc.stderr.decode()
    # (exit 2: cfg.gcode, a 'key = value' file, is not G-code and is said so; nothing was read as an option)
    assert proc.returncode == 2 and "--config=cfg.gcode:2:" in output and "SC001" in output, output
    assert "cfg.gcode: a 'key = value' configuration file" in output, output
    assert (tmp_path / "good.gcode").read_text() == GOOD, "a file name was read as --output"
    # user args that forget to end the options: refused (the hook fails), never a pass
    command = [sys.executable, "-m", "gclint", *shlex.split(hook["entry"])[1:], "--printer", "30m", *names]
    proc = subprocess.run(command, cwd=tmp_path, capture_output=True, env=env, timeout=120)
    assert proc.returncode == 2 and b"'--'" in proc.stderr, proc.stderr
    assert (tmp_path / "good.gcode").read_text() == GOOD


def test_file_names_are_never_options_through_real_pre_commit(tmp_path, hook_repo, pre_commit_home):
    _pre_commit()
    repo = _jobs_repo(tmp_path, hook_repo)
    _hostile_names(repo)
    _git("add", "-A", cwd=repo)
    proc = _run(repo, pre_commit_home)
    output = proc.stdout.decode() + proc.stderr.decode()
    assert proc.returncode == 1 and "SC001" in output and "--config=cfg.gcode" in output, output
    assert (repo / "good.gcode").read_text() == GOOD
    # args given by the user, ended with "--" as the README says
    src, rev = hook_repo
    (repo / ".pre-commit-config.yaml").write_text(
        f"repos:\n  - repo: {src.as_posix()}\n    rev: {rev}\n    hooks:\n      - id: gclint\n"
        "        args: [--printer, 30m, --]\n"
    )
    proc = _run(repo, pre_commit_home)
    output = proc.stdout.decode() + proc.stderr.decode()
    assert proc.returncode == 1 and "SC001" in output, output
    assert (repo / "good.gcode").read_text() == GOOD


def test_the_hooks_take_every_file_a_walk_takes():
    # (one list of job extensions: gclint.runner; the hooks' and the README's file patterns follow it)
    import re as _re

    from gclint.runner import GCODE_EXTENSIONS, PACKAGE_EXTENSIONS

    root = Path(__file__).resolve().parent.parent
    for text in ((root / ".pre-commit-hooks.yaml").read_text(), (root / "README.md").read_text()):
        patterns = _re.findall(r"files: '([^']+)'", text)
        assert patterns
        for pattern in patterns:
            for extension in GCODE_EXTENSIONS + PACKAGE_EXTENSIONS:
                assert _re.search(pattern, f"jobs/part{extension}"), (pattern, extension)


def test_a_hook_whose_only_file_looks_like_an_option_still_needs_the_double_dash(tmp_path):
    # args [--printer, 30m] with no "--", and the one file committed named "--output=ok.gcode": it was read as
    # --output, the folder checked instead and a report written into ok.gcode; now refused
    env = dict(os.environ, PRE_COMMIT="1")
    env.pop("GCLINT_CACHE_DIR", None)
    (tmp_path / "--output=ok.gcode").write_text("M792 ; SHELL C:\\x.exe\n")
    command = [sys.executable, "-m", "gclint", "check", "--force-exclude", "--printer", "30m", "--output=ok.gcode"]
    proc = subprocess.run(command, cwd=tmp_path, capture_output=True, env=env, timeout=120)
    assert proc.returncode == 2 and b"'--'" in proc.stderr, proc.stderr
    assert not (tmp_path / "ok.gcode").exists()
