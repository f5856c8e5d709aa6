"""Third-party rules: loaded only from the ``gclint.rules`` entry point group, and a broken plugin is an error
that names it (exit 2, one line), never a traceback.  A plugin rule that raises while checking is reported
(naming the rule, its module and the file) and the other rules and files go on.

Each test builds a real installed distribution: a module and a ``.dist-info`` folder with
``entry_points.txt`` in a temporary folder put on ``PYTHONPATH`` of the real command line, which is what
``pip install`` leaves in site-packages.
"""

from __future__ import annotations

import json
import sys
import textwrap
from pathlib import Path

import pytest

from .conftest import run_cli

CLEAN = ";FLAVOR:Marlin\nG28\nG1 X10 Y10 F3000\n"  # (a bare G28 alone would be a Hyrel job's HY025)


def install_plugin(root: Path, dist: str, modules: dict[str, str], entry_points: dict[str, dict[str, str]]) -> Path:
    """Write modules and ``<dist>-1.0.dist-info`` under ``root``; returns ``root`` (for PYTHONPATH)."""
    root.mkdir(parents=True, exist_ok=True)
    for name, source in modules.items():
        (root / f"{name}.py").write_text(textwrap.dedent(source))
    info = root / f"{dist.replace('-', '_')}-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 1.0\n")
    lines = []
    for group, entries in entry_points.items():
        lines.append(f"[{group}]")
        lines.extend(f"{k} = {v}" for k, v in entries.items())
    (info / "entry_points.txt").write_text("\n".join(lines) + "\n")
    return root


def run_with(plugins: Path, *args: str, cwd: Path | None = None):
    return run_cli(*args, env={"PYTHONPATH": str(plugins)}, cwd=cwd)


GOOD_RULE = """
    from gclint.rules.base import Rule, Severity, register

    @register
    class NoHomeAll(Rule):
        code = "XX001"
        name = "no-home-all"
        severity = Severity.WARNING
        summary = "G28 without axes"
        explanation = "Example plugin rule."
        example_bad = "G28"
        example_good = "G28 X0"
        codes = ("G28",)

        def check(self, line, cmd):
            if not cmd.params:
                self.report(line, "G28 homes every axis", node=cmd)
"""


def _one_line(stderr: bytes) -> str:
    text = stderr.decode("utf-8", "replace")
    assert "Traceback" not in text, text
    lines = [line for line in text.splitlines() if line.strip()]
    assert len(lines) == 1, lines
    return lines[0]


def test_a_working_plugin_is_loaded(tmp_path: Path) -> None:
    plugins = install_plugin(
        tmp_path / "site",
        "gclint-example",
        {"gclint_example": GOOD_RULE},
        {"gclint.rules": {"example": "gclint_example"}},
    )
    job = tmp_path / "job.gcode"
    job.write_text(CLEAN)
    proc = run_with(plugins, "check", "--format", "json", str(job))
    assert proc.returncode == 1, proc.stderr
    assert [f["code"] for f in json.loads(proc.stdout)] == ["XX001"]
    listed = run_with(plugins, "rules", "XX001")
    assert listed.returncode == 0 and b"no-home-all" in listed.stdout


def test_only_the_gclint_rules_group_is_loaded(tmp_path: Path) -> None:
    plugins = install_plugin(
        tmp_path / "site",
        "not-a-gclint-plugin",
        {"sneaky": GOOD_RULE, "explodes": "raise SystemExit('imported!')\n"},
        {
            "gclint.plugins": {"sneaky": "sneaky"},
            "flake8.extension": {"EXP": "explodes"},
            "gclint_rules": {"x": "explodes"},
        },
    )
    job = tmp_path / "job.gcode"
    job.write_text(CLEAN)
    proc = run_with(plugins, "check", "--format", "json", str(job))
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout) == []


BROKEN = {
    "import error": ({"broken_import": "import this_module_does_not_exist\n"}, "broken_import"),
    "raises at import": ({"broken_raise": "raise RuntimeError('plugin exploded')\n"}, "broken_raise"),
    "syntax error": ({"broken_syntax": "def oops(:\n"}, "broken_syntax"),
    "missing attribute": ({"broken_attr": "X = 1\n"}, "broken_attr:DoesNotExist"),
    "bad rule code": (
        {"broken_code": GOOD_RULE.replace('"XX001"', '"BAD"')},
        "broken_code",
    ),
    "code taken by a built-in rule": (
        {"broken_dup": GOOD_RULE.replace('"XX001"', '"SX001"').replace("    @register\n", "")},
        "broken_dup:NoHomeAll",
    ),
    "system exit at import": ({"broken_exit": "import sys\nsys.exit(3)\n"}, "broken_exit"),
    "not a rule": ({"broken_obj": "def rule():\n    pass\n"}, "broken_obj:rule"),
}


@pytest.mark.parametrize("case", BROKEN, ids=list(BROKEN))
@pytest.mark.parametrize("command", ["check", "rules"])
def test_a_broken_plugin_is_named_and_exits_2(tmp_path: Path, case: str, command: str) -> None:
    modules, value = BROKEN[case]
    plugins = install_plugin(tmp_path / "site", "gclint-broken", modules, {"gclint.rules": {"brokenplugin": value}})
    job = tmp_path / "job.gcode"
    job.write_text(CLEAN)
    args = ("check", str(job)) if command == "check" else ("rules",)
    proc = run_with(plugins, *args)
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    line = _one_line(proc.stderr)
    assert "brokenplugin" in line, line


RAISING_RULE = """
    from gclint.rules.base import Rule, Severity, register

    @register
    class Explodes(Rule):
        code = "XX002"
        name = "explodes"
        severity = Severity.WARNING
        summary = "Raises on files that contain BOOM"
        explanation = "A rule with a bug."
        example_bad = "G1 X1"
        example_good = "G1 X1"
        codes = ("G1",)
        on_comment = True

        def check_comment(self, line, comment):
            if "BOOM" in comment.text:
                raise ZeroDivisionError("rule bug on purpose")
"""


@pytest.mark.parametrize("jobs", ["1", "3"])
def test_a_rule_that_raises_does_not_stop_the_run(tmp_path: Path, jobs: str) -> None:
    plugins = install_plugin(
        tmp_path / "site",
        "gclint-explodes",
        {"gclint_explodes": RAISING_RULE},
        {"gclint.rules": {"explodes": "gclint_explodes"}},
    )
    files = tmp_path / "jobs"
    files.mkdir()
    (files / "a.gcode").write_text("G1 X1 (unclosed\n")
    (files / "b_boom.gcode").write_text("G28\n; BOOM\nG1 X1 (unclosed\nG1 X2 (also unclosed\n")
    (files / "c_binary.gcode").write_bytes(bytes(range(256)) * 8)
    (files / "d.gcode").write_text("G1 X2 (unclosed\n")
    proc = run_with(plugins, "check", "--jobs", jobs, "--dialect", "marlin", "--format", "json", str(files))
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "Traceback" not in stderr, stderr
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert len(lines) == 2, lines
    boom = next(line for line in lines if "b_boom.gcode" in line)
    assert "XX002" in boom and "gclint_explodes" in boom and "line 2" in boom and "ZeroDivisionError" in boom
    assert any("c_binary.gcode" in line and "binary" in line for line in lines)
    findings = json.loads(proc.stdout)
    by_file = {}
    for f in findings:
        by_file.setdefault(Path(f["path"]).name, []).append((f["line"], f["code"]))
    # The other rules still ran on the file with the crash, after the crash too; the other files were checked.
    assert by_file["b_boom.gcode"] == [(3, "SX005"), (4, "SX005")], by_file
    assert by_file["a.gcode"] == [(1, "SX005")] and by_file["d.gcode"] == [(1, "SX005")]


def test_importlib_metadata_is_asked_only_where_a_distribution_may_name_the_group(tmp_path, monkeypatch):
    # (the pre-test that spares a one-file check importing importlib.metadata: never False where a plugin is)
    from gclint.rules.base import _may_declare_plugins

    other = install_plugin(tmp_path / "other", "other-tool", {}, {"console_scripts": {"x": "os:getcwd"}})
    monkeypatch.setattr(sys, "path", [str(other), str(tmp_path / "missing")])
    assert not _may_declare_plugins()
    plugin = install_plugin(tmp_path / "plugin", "gclint-plugin", {}, {"gclint.rules": {"p": "os"}})
    monkeypatch.setattr(sys, "path", [str(other), str(plugin)])
    assert _may_declare_plugins()
    archive = tmp_path / "dists.zip"
    archive.write_bytes(b"PK\x05\x06" + bytes(18))  # (a zip file on the path: importlib.metadata reads it)
    monkeypatch.setattr(sys, "path", [str(other), str(archive)])
    assert _may_declare_plugins()
