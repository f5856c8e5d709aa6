"""Path patterns (issue 25): ``exclude``/``per-file-ignores`` globs and ``.gitignore`` lines match in steps
bounded by name length x pattern length, with git's meaning (``**``, anchoring, negation, folders only,
character classes), and a pattern that cannot be read is one error line when the configuration is read."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from gclint import globs
from gclint.gitignore import GitIgnore

from .conftest import run_cli

HOSTILE = "*a*a*a*a*a*a*a*a*a*a*a*ac"


def _steps(monkeypatch) -> list[int]:
    """Counts the character comparisons the matcher makes."""
    count = [0]
    one = globs._one

    def counted(token, c):
        count[0] += 1
        return one(token, c)

    monkeypatch.setattr(globs, "_one", counted)
    return count


@pytest.mark.parametrize("length", [40, 60, 400])
def test_a_backtracking_pattern_is_matched_in_bounded_steps(monkeypatch, length: int) -> None:
    steps = _steps(monkeypatch)
    name = "a" * length + ".gcode"
    assert not globs.matches(HOSTILE, name)
    assert not globs.matches("**/" + HOSTILE, "x/" + name)
    assert not GitIgnore.from_lines([HOSTILE, "/deep/" + HOSTILE]).decide(name, False)
    # (four matches, each within the bound; most names are refused on the pattern's ends with no step at all)
    assert steps[0] <= 4 * len(name) * len(HOSTILE), steps


def test_folders_are_matched_in_bounded_steps_too(monkeypatch) -> None:
    steps = _steps(monkeypatch)
    path = "/".join(["a" * 10] * 300) + "/job.gcode"
    pattern = "**/a*a*a*a*/**/a*a*a*a*c/**/*.gcode"
    assert not globs.matches(pattern, path)
    assert steps[0] <= len(path) * len(pattern), steps


def test_the_hostile_pattern_through_the_command_line(tmp_path: Path) -> None:
    """The reproducer: a .gitignore line and an extend-exclude pattern over 40- and 60-character names took
    minutes (the timeout is a guard against a hang, not a measure: bench/bench_walk.py measures)."""
    if shutil.which("git"):
        subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    (tmp_path / ".gitignore").write_text(HOSTILE + "\n")
    for n in (40, 60):
        (tmp_path / ("a" * n + ".gcode")).write_text("M792 ; SHELL C:\\x.exe\n")
    proc = run_cli("check", "--no-cache", "-f", "json", "--extend-exclude", HOSTILE, ".", cwd=tmp_path, timeout=60)
    assert proc.returncode == 1 and len(json.loads(proc.stdout)) == 2, proc.stderr


@pytest.mark.parametrize(
    ("pattern", "path", "expected"),
    [
        ("*.gcode", "jobs/a.gcode", True),  # no "/": the name alone
        ("jobs/*.gcode", "jobs/a.gcode", True),
        ("jobs/*.gcode", "jobs/deep/a.gcode", False),  # "*" stays within a folder
        ("jobs/**/*.gcode", "jobs/deep/er/a.gcode", True),
        ("jobs/**/*.gcode", "jobs/a.gcode", True),  # "**/" may be no folder at all
        ("archive/**", "archive/old/a.gcode", True),
        ("archive/**", "archive", False),  # what is inside, not the folder itself
        ("**", "any/thing", True),
        ("j?bs/[a-c].gcode", "jobs/b.gcode", True),
        ("jobs/[!a-c].gcode", "jobs/b.gcode", False),
        ("jobs/[!a].gcode", "jobs//.gcode", False),  # a class never matches "/"
        ("a\\*b", "a*b", True),  # an escaped star is a star
        ("a\\*b", "axb", False),
        ("./calibration", "calibration", True),
    ],
)
def test_ruff_style_globs(pattern: str, path: str, expected: bool) -> None:
    assert globs.matches(pattern, path) is expected


def _ignored(lines: list[str], path: str, is_dir: bool = False) -> bool | None:
    return GitIgnore.from_lines(lines).decide(path, is_dir)


def test_gitignore_semantics() -> None:
    assert _ignored(["*.tmp.gcode"], "deep/x.tmp.gcode")  # no "/": at any depth
    assert _ignored(["/top.gcode"], "sub/top.gcode") is None  # a leading "/" anchors
    assert _ignored(["build/"], "build", is_dir=True) and _ignored(["build/"], "build") is None  # folders only
    assert _ignored(["*.gcode", "!keep.gcode"], "keep.gcode") is False  # negation, the last pattern wins
    assert _ignored(["\\!x.gcode"], "!x.gcode") and _ignored(["\\#x.gcode"], "#x.gcode")
    assert _ignored(["# a comment", "", "x.gcode   "], "x.gcode")  # trailing blanks dropped
    assert _ignored(["x.gcode\\ "], "x.gcode ") and _ignored(["x.gcode\\ "], "x.gcode") is None
    assert _ignored(["[[:digit:]]*.gcode"], "7.gcode") and _ignored(["[[:digit:]]*.gcode"], "a.gcode") is None
    assert _ignored(["a/**/b.gcode"], "a/x/y/b.gcode") and _ignored(["a/**/b.gcode"], "a/b.gcode")
    assert _ignored(["?//"], "g", is_dir=True) is None  # one trailing slash is dropped: "?/" is anchored
    # a line git cannot read matches nothing (the checkout's file, not the user's: no error)
    assert _ignored(["[z-a]", "[abc"], "b") is None


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_gitignore_decisions_agree_with_git(tmp_path: Path) -> None:
    """The same tree through git check-ignore and through gclint, parent folders included."""
    from gclint.excludes import Excluder

    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    lines = ["*.tmp", "build/", "/top/*", "!/top/keep.gcode", "deep/**/x.gcode", "[ab]?.gcode", "!ab.gcode"]
    (tmp_path / ".gitignore").write_text("\n".join(lines) + "\n")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / ".gitignore").write_text("!c.tmp\nlocal.gcode\n")
    files = [
        "a.tmp", "sub/c.tmp", "sub/local.gcode", "local.gcode", "build/a.gcode", "sub/build/b.gcode",
        "top/a.gcode", "top/keep.gcode", "sub/top/a.gcode", "deep/x.gcode", "deep/1/2/x.gcode", "ax.gcode",
        "ab.gcode", "cx.gcode",
    ]  # fmt: skip
    for name in files:
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text("G28\n")
    done = subprocess.run(
        ["git", "-C", str(tmp_path), "check-ignore", "--no-index", "--stdin"],
        input="\n".join(files) + "\n",
        capture_output=True,
        text=True,
    )
    by_git = set(done.stdout.split())
    excluder = Excluder()
    by_gclint = {name for name in files if excluder._gitignored(str(tmp_path / name), False)}
    assert by_gclint == by_git


@pytest.mark.parametrize("pattern", ["[z-a]", "jobs/[abc", "[[:nope:]].gcode"])
def test_a_pattern_that_cannot_be_read_is_one_error_line(tmp_path: Path, pattern: str) -> None:
    (tmp_path / "a.gcode").write_text("G28\n")
    for key in ("exclude", "extend-exclude"):
        (tmp_path / "gclint.toml").write_text(f"{key} = [{json.dumps(pattern)}]\n")
        proc = run_cli("check", "--no-cache", ".", cwd=tmp_path)
        lines = proc.stderr.decode().splitlines()
        assert proc.returncode == 2 and len(lines) == 1, lines
        assert "gclint.toml" in lines[0] and key in lines[0] and "not a valid path pattern" in lines[0], lines
        assert "internal error" not in lines[0]
    (tmp_path / "gclint.toml").write_text(f'per-file-ignores = {{ {json.dumps(pattern)} = ["HY"] }}\n')
    proc = run_cli("check", "--no-cache", ".", cwd=tmp_path)
    assert proc.returncode == 2 and b"per-file-ignores" in proc.stderr and b"internal error" not in proc.stderr
    (tmp_path / "gclint.toml").unlink()
    proc = run_cli("check", "--no-cache", "--extend-exclude", pattern, ".", cwd=tmp_path)
    lines = proc.stderr.decode().splitlines()
    assert proc.returncode == 2 and len(lines) == 1 and "--extend-exclude" in lines[0], lines


def test_the_reversed_range_is_named() -> None:
    with pytest.raises(globs.GlobError, match="the range z-a is reversed"):
        globs.check("[z-a]")


def test_pathspec_is_no_longer_a_dependency() -> None:
    from tests.conftest import ROOT

    assert "pathspec" not in (ROOT / "pyproject.toml").read_text()


@given(st.text("ab*?", max_size=8), st.text("ab", max_size=10))
def test_the_shortcuts_answer_as_the_general_loop(pattern: str, name: str) -> None:
    part = globs.Part(pattern)
    assert part.match(name) == globs._match_tokens(part.tokens, name), (pattern, name)


def test_many_backtracking_patterns_against_long_names_are_refused_on_their_ends() -> None:
    # the eighth attack: 3,000 ".gitignore" lines "*a*a...*ac<i>" against 100 names of 200 "a"s took a minute
    ignore = GitIgnore.from_lines(["*a" * 40 + f"c{i}" for i in range(3000)])
    names = ["a" * 200 + f"{i}.gcode" for i in range(20)]
    assert not any(ignore.decide(name, False) for name in names)
    assert globs.matches("*a*b*c", "xxaxxbxxc") and not globs.matches("*a*b*c", "xxbxxaxxc")
