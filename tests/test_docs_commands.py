"""The documentation works when copied (issue 28): no placeholders where a command or an address should
be, commands that run without an activated virtual environment, output shown as the tool prints it, and
no build the project does not have."""

from __future__ import annotations

import re

import pytest

from tests.conftest import ROOT, run_cli

DOCS = [
    ROOT / "README.md",
    ROOT / "CONTRIBUTING.md",
    ROOT / "docs" / "editors.md",
    ROOT / "docs" / "entry-points.md",
    ROOT / "docs" / "ci.md",
    ROOT / "editors" / "vscode" / "README.md",
    ROOT / ".pre-commit-hooks.yaml",
    ROOT / "action.yml",
]


def _code(text: str) -> list[str]:
    """The commands people copy: code blocks, indented blocks and inline code."""
    blocks = re.findall(r"```[a-z]*\n(.*?)```", text, re.S)
    indented = re.findall(r"(?m)^    (\S.*)$", text)
    inline = re.findall(r"`([^`\n]+)`", text)
    return blocks + indented + inline


@pytest.mark.parametrize("path", DOCS, ids=lambda p: p.name)
def test_no_placeholders(path):
    text = path.read_text(encoding="utf-8")
    for placeholder in ("<owner>", "<tag", "<release tag", "<commit", "@<"):
        assert placeholder not in text, f"{path.name}: {placeholder}"


@pytest.mark.parametrize("path", DOCS, ids=lambda p: p.name)
def test_python_commands_name_the_virtual_environment(path):
    """`python ...` fails on Debian outside an activated virtual environment (there is only python3)."""
    for code in _code(path.read_text(encoding="utf-8")):
        for line in code.splitlines():
            assert not re.match(r"\s*(\$ )?(python|pip) ", line), f"{path.name}: {line}"


def test_the_mypyc_build_is_not_offered():
    """It failed mypy's type checks (setup.py says why it was removed)."""
    for path in [*DOCS, ROOT / "setup.py"]:
        text = path.read_text(encoding="utf-8")
        assert "GCLINT_USE_MYPYC" not in text, path.name


def test_the_readme_shows_sx002_as_the_tool_prints_it(tmp_path):
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    [block] = [
        b for b in re.findall(r"```text\n(.*?)```", readme, re.S) if b.startswith("$ gclint check part.gcode -f full")
    ]
    shown = block.splitlines()[1:]
    line6 = next(line for line in shown if line.startswith(" 6 | "))[len(" 6 | ") :]
    (tmp_path / "part.gcode").write_text(f"; gclint: dialect=marlin\nG28\nG90\nM82\nG92 E0\n{line6}\n")
    proc = run_cli("check", "part.gcode", "-f", "full", "--no-cache", cwd=tmp_path)
    printed = proc.stdout.decode().splitlines()
    assert printed[: len(shown)] == shown, proc.stdout.decode()


def test_the_readme_states_when_its_test_time_was_measured():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    said = re.search(r"The run took ([^.]*?) on (\d{4}-\d{2}-\d{2})", readme)
    assert said, "the README's test time says when it was measured"
