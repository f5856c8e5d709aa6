"""The editor set-ups of docs/editors.md, run as documented: the Neovim configuration in Neovim itself
(headless: file types, the server it starts, diagnostics, hover, a code action applied, an edit checked
again), and the VS Code extension built with the documented commands (npm, then vsce).

They need programs from outside Python: Debian's ``neovim`` (12 ships 0.7.2, the oldest Neovim the
configuration supports) and ``npm`` with the npm registry.  .ci/run installs what is missing; under CI
(``CI`` set) a missing program or an unreachable registry fails the test, elsewhere it skips with the
reason.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from tests.conftest import ROOT

EDITORS_DOC = ROOT / "docs" / "editors.md"
NEOVIM_CONFIG = ROOT / "editors" / "neovim" / "gclint.lua"
SMOKE_TEST = ROOT / "editors" / "neovim" / "smoke_test.lua"
VSCODE = ROOT / "editors" / "vscode"


def _missing(what: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what} (CI: .ci/run installs it)")
    pytest.skip(what)


def _section(heading: str) -> str:
    text = EDITORS_DOC.read_text(encoding="utf-8")
    start = text.index(f"\n## {heading}\n")
    end = text.find("\n## ", start + 1)
    return text[start : end if end >= 0 else None]


def _blocks(section: str, language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", section, re.S)


def _bin_dir() -> str:
    """Where this Python's ``gclint`` command is (the virtualenv's bin folder)."""
    return str(Path(sys.executable).parent)


def test_the_documented_neovim_configuration_is_the_tested_file():
    assert _blocks(_section("Neovim"), "lua")[0] == NEOVIM_CONFIG.read_text(encoding="utf-8")


def test_the_documented_neovim_configuration_works_headless(tmp_path):
    nvim = shutil.which("nvim")
    if nvim is None:
        _missing("Neovim is not installed (Debian: apt-get install neovim)")
    if shutil.which("gclint", path=_bin_dir()) is None:
        pytest.skip(f"no gclint command beside {sys.executable} (install the package: pip install -e .)")
    env = dict(os.environ)
    env["PATH"] = _bin_dir() + os.pathsep + env.get("PATH", "")
    for name in ("CONFIG", "DATA", "STATE", "CACHE"):  # nothing of the user's Neovim is read or written
        env[f"XDG_{name}_HOME"] = str(tmp_path / name.lower())
    env.pop("GCLINT_CACHE_DIR", None)
    proc = subprocess.run(
        [nvim, "--headless", "-u", str(NEOVIM_CONFIG), "-i", "NONE", "-c", f"luafile {SMOKE_TEST}"],
        capture_output=True,
        text=True,
        timeout=180,
        env=env,
        cwd=str(tmp_path),
    )
    said = proc.stdout + proc.stderr
    assert proc.returncode == 0 and "FAIL" not in said, said
    for step in ("file types", "started gclint server", "diagnostics", "hover", "code action applied", "checked again"):
        assert step in said, said


def _npm_offline(proc: subprocess.CompletedProcess) -> bool:
    said = proc.stdout + proc.stderr
    return any(s in said for s in ("ENOTFOUND", "EAI_AGAIN", "ECONNREFUSED", "ETIMEDOUT", "ENETUNREACH", "network"))


def test_the_vscode_extension_builds_with_the_documented_commands(tmp_path):
    npm = shutil.which("npm")
    if npm is None or shutil.which("npx") is None:
        _missing("npm is not installed (Debian: apt-get install nodejs npm)")
    [block] = _blocks(_section("VS Code"), "sh")
    commands = [line.split("#")[0].strip() for line in block.splitlines()]
    commands = [c for c in commands if c]
    assert commands[0] == "cd editors/vscode" and commands[-1].startswith("code --install-extension ")
    build = commands[1:-1]
    assert build == ["npm install", "npx @vscode/vsce package"], build
    folder = tmp_path / "vscode"
    shutil.copytree(VSCODE, folder, ignore=shutil.ignore_patterns("node_modules", "*.vsix"))
    env = dict(os.environ)
    env.setdefault("npm_config_update_notifier", "false")
    for command in build:
        proc = subprocess.run(
            command.split(),
            cwd=folder,
            capture_output=True,
            text=True,
            timeout=900,
            env=env,
            stdin=subprocess.DEVNULL,  # (vsce asks nothing: a question would end the build)
        )
        if proc.returncode != 0 and command == "npm install" and _npm_offline(proc) and not os.environ.get("CI"):
            pytest.skip(f"the npm registry cannot be reached: {proc.stderr.strip()[-300:]}")
        assert proc.returncode == 0, f"{command}:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    package = folder / commands[-1].split()[-1]
    assert package.is_file(), sorted(p.name for p in folder.iterdir())
    with zipfile.ZipFile(package) as vsix:
        names = set(vsix.namelist())
    for needed in ("extension/package.json", "extension/extension.js", "extension/language-configuration.json"):
        assert needed in names
    assert "extension/node_modules/vscode-languageclient/package.json" in names  # the runtime dependency
    assert not any(n.startswith("extension/node_modules/@vscode/vsce/") for n in names)  # not the build tool
