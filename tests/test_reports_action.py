"""The composite GitHub Action (action.yml): its shell steps run for real, in order, the way the Actions
runner runs them (inputs and step outputs passed through ``env``, ``GITHUB_OUTPUT`` and ``GITHUB_PATH``
files).  The ``uses:`` steps (setup-python, upload-sarif) belong to GitHub and are skipped.  The install
step pip-installs a copy of this repository into a fresh virtualenv (needs PyPI for the dependencies).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from tests.conftest import ROOT

GOOD = "; gclint: dialect=marlin\nG28\nG1 X10 Y10 E1 F1200\n"
BAD = "; gclint: dialect=marlin\nG28\nG1 X10 X20 Y10 E1 F1200\nM9999\n"
EXPR = re.compile(r"\$\{\{\s*(.*?)\s*\}\}")
# What the runner says about the action being run (a test value: where a workflow would have fetched it)
GITHUB_CONTEXT = {
    "github.action_repository": "example-owner/gclint",
    "github.action_ref": "v0.1.0",
    "github.server_url": "https://github.com",
}


def _yaml():
    try:
        import yaml
    except ImportError:
        if os.environ.get("CI"):
            pytest.fail("PyYAML is needed (it comes with pre-commit, in the test extras)")
        pytest.skip("PyYAML is not installed")
    return yaml


@pytest.fixture(scope="module")
def action_copy(tmp_path_factory) -> Path:
    """This repository's files (tracked and new, as git lists them), copied where the runner would put them."""
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    target = tmp_path_factory.mktemp("action") / "gclint"
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT,
        capture_output=True,
        check=True,
    ).stdout.decode()
    for name in filter(None, listed.split("\0")):
        if (ROOT / name).is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, target / name)
    return target


@pytest.fixture(scope="module")
def runner_temp(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("runner-temp")


def run_action(action: Path, workspace: Path, runner_temp: Path, **inputs: str) -> dict:
    """Run the action's bash steps; returns {"steps": {id: outputs}, "log": text, "failed": step name or None}."""
    spec = _yaml().safe_load((action / "action.yml").read_text())
    values = {
        name: str(inputs.get(name.replace("-", "_"), meta.get("default", ""))) for name, meta in spec["inputs"].items()
    }
    values.update({k.replace("_", "-"): v for k, v in inputs.items()})
    outputs: dict[str, dict[str, str]] = {}
    path_file = runner_temp / "github_path"
    path_file.touch()
    log = []
    failed = None
    for step in spec["runs"]["steps"]:
        if "uses" in step:
            continue
        if step["name"] == "Install gclint" and (runner_temp / "gclint-venv" / "bin" / "gclint").exists():
            # installed by an earlier test of this module: the runner's PATH keeps it
            path_file.write_text(str(runner_temp / "gclint-venv" / "bin") + "\n")
            continue

        def evaluate(match: re.Match) -> str:
            expr = match.group(1)
            if expr.startswith("inputs."):
                return values[expr[len("inputs.") :]]
            if expr == "github.action_path":
                return str(action)
            if expr in GITHUB_CONTEXT:
                return GITHUB_CONTEXT[expr]
            m = re.fullmatch(r"steps\.([\w-]+)\.outputs\.([\w-]+)", expr)
            if m:
                return outputs.get(m.group(1), {}).get(m.group(2), "")
            raise AssertionError(f"expression not handled by the test: {expr}")

        condition = step.get("if")
        if condition and "inputs.python-version" in condition:
            continue
        output_file = runner_temp / f"output-{len(log)}"
        output_file.write_text("")
        env = {k: v for k, v in os.environ.items() if not k.startswith(("GITHUB_", "GCLINT_"))}
        env.update({k: EXPR.sub(evaluate, str(v)) for k, v in step.get("env", {}).items()})
        extra_path = [p for p in path_file.read_text().splitlines() if p]
        env.update(
            RUNNER_TEMP=str(runner_temp),
            GITHUB_OUTPUT=str(output_file),
            GITHUB_PATH=str(path_file),
            PATH=os.pathsep.join([*extra_path, env.get("PATH", "")]),
        )
        assert step["shell"] == "bash"
        proc = subprocess.run(
            ["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", step["run"]],
            cwd=workspace,
            env=env,
            capture_output=True,
            timeout=900,
        )
        log.append(f"== {step['name']} (exit {proc.returncode})\n{proc.stdout.decode()}{proc.stderr.decode()}")
        if "id" in step:
            outputs[step["id"]] = dict(
                line.split("=", 1) for line in output_file.read_text().splitlines() if "=" in line
            )
        if proc.returncode != 0:
            failed = step["name"]
            break
    return {"steps": outputs, "log": "\n".join(log), "failed": failed}


def test_action_fails_the_job_on_errors_and_writes_sarif(tmp_path, action_copy, runner_temp):
    workspace = tmp_path / "repo"
    (workspace / "jobs").mkdir(parents=True)
    (workspace / "jobs" / "good.gcode").write_text(GOOD)
    (workspace / "jobs" / "bad.gcode").write_text(BAD)
    result = run_action(action_copy, workspace, runner_temp, paths="jobs")
    assert result["failed"] == "Gate on findings", result["log"]
    check = result["steps"]["check"]
    assert check["errors"] == "1" and check["warnings"] == "1" and check["sarif-file"] == "gclint.sarif"
    log = json.loads((workspace / "gclint.sarif").read_text())
    assert {r["ruleId"] for r in log["runs"][0]["results"]} == {"SX002", "DL001"}
    uri = log["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]
    assert uri == "jobs/bad.gcode"  # relative to the repository root, as code scanning expects
    assert "::error file=jobs/bad.gcode,line=3," in result["log"]  # annotations
    assert "::error title=gclint::1 error(s), 1 warning(s), 0 info in G-code (fail-on: warning)" in result["log"]
    # the rules' help links: the rule reference in the action's repository, at the ref the workflow uses
    for rule in log["runs"][0]["tool"]["driver"]["rules"]:
        assert (
            rule["helpUri"] == f"https://github.com/example-owner/gclint/blob/v0.1.0/docs/rules.md#{rule['id'].lower()}"
        )


def test_an_installed_gclint_links_its_own_rule_reference(tmp_path, action_copy, runner_temp):
    """Installed from a copy (not editable), the package carries docs/rules.md (setup.py copies it), and
    the links of SARIF (helpUri) and of the language server point to that copy."""
    workspace = tmp_path / "repo"
    workspace.mkdir()
    (workspace / "bad.gcode").write_text(BAD)
    run_action(action_copy, workspace, runner_temp, upload_sarif="false")  # (installs the copy)
    gclint = runner_temp / "gclint-venv" / "bin" / "gclint"
    env = {k: v for k, v in os.environ.items() if not k.startswith(("GCLINT_", "PYTHONPATH"))}
    proc = subprocess.run(
        [str(gclint), "check", "-f", "sarif", "--no-cache", "bad.gcode"], cwd=workspace, env=env, capture_output=True
    )
    assert proc.returncode == 1, proc.stderr
    rules = json.loads(proc.stdout)["runs"][0]["tool"]["driver"]["rules"]
    python = runner_temp / "gclint-venv" / "bin" / "python"
    for rule in rules:
        uri = rule["helpUri"]
        assert uri.startswith("file://") and uri.endswith("/site-packages/gclint/_docs/rules.md#" + rule["id"].lower())
        where = subprocess.run(
            [
                str(python),
                "-c",
                "import sys, urllib.parse, urllib.request as u; print(u.url2pathname(urllib.parse.urlparse(sys.argv[1]).path))",
                uri,
            ],
            capture_output=True,
            text=True,
            env=env,
        ).stdout.strip()
        text = Path(where).read_text(encoding="utf-8")
        assert f"### {rule['id']}" in text  # the heading the anchor names


def test_action_passes_clean_jobs_and_honours_fail_on(tmp_path, action_copy, runner_temp):
    workspace = tmp_path / "repo"
    workspace.mkdir()
    (workspace / "good.gcode").write_text(GOOD)
    clean = run_action(action_copy, workspace, runner_temp, annotations="false")
    assert clean["failed"] is None, clean["log"]
    assert clean["steps"]["check"]["errors"] == "0"

    (workspace / "warn.gcode").write_text("; gclint: dialect=marlin\nM9999\n")
    relaxed = run_action(action_copy, workspace, runner_temp, fail_on="error")
    assert relaxed["failed"] is None, relaxed["log"]
    report_only = run_action(action_copy, workspace, runner_temp, fail_on="never")
    assert report_only["failed"] is None, report_only["log"]
    strict = run_action(action_copy, workspace, runner_temp)  # the default, as gclint check's: warning
    assert strict["failed"] == "Gate on findings"
    assert "(fail-on: warning)" in strict["log"]
    bad = run_action(action_copy, workspace, runner_temp, fail_on="sometimes")
    assert bad["failed"] == "Gate on findings" and "fail-on must be error, warning, info or never" in bad["log"]


def test_action_reports_unreadable_files(tmp_path, action_copy, runner_temp):
    workspace = tmp_path / "repo"
    workspace.mkdir()
    (workspace / "job.gcode").write_bytes(b"GCDE\x01\x00binary")
    result = run_action(action_copy, workspace, runner_temp)
    assert result["failed"] == "Gate on findings"
    assert "could not be read" in result["log"] or "could not check" in result["log"]
