"""Configuration a change adds cannot switch the gate off (issue 25).

A ``.gclint.toml``, ``gclint.toml`` or ``pyproject.toml [tool.gclint]`` found by walking up from the files
travels with them: before, ``jobs/.gclint.toml`` with ``ignore = ["SC"]`` (or ``select``, ``severity``,
``per-file-ignores``, ``exclude = ["**"]``) let ``M792 ; SHELL C:\\x.exe`` pass with 0 SARIF results and no
word in any format, ``-q`` dropping the one note there was.  Such a file may tune the SX, DL and HY rules;
only the command line or ``--config`` reaches the SC rules; and whatever configuration excludes or switches
off, every format says."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from gclint.options import Options
from gclint.trust import guard, selected

from .conftest import run_cli

JOB = "M792 ; SHELL C:\\x.exe\nG1 X1 X2 F600\n"  # SC001, and SX002 (a rule a configuration may switch off)

ATTEMPTS = {
    "ignore": 'ignore = ["SC"]\n',
    "ignore-all": 'ignore = ["ALL"]\n',
    "select": 'select = ["SX", "DL", "HY"]\n',
    "severity": 'severity = { SC = "info", SC001 = "info" }\n',
    "per-file-ignores": 'per-file-ignores = { "*.gcode" = ["ALL"] }\n',
    "exclude": 'exclude = ["**"]\n',
    "extend-exclude": 'extend-exclude = ["*.gcode"]\n',
}


def _jobs(tmp_path: Path, config: str, name: str = ".gclint.toml") -> Path:
    jobs = tmp_path / "jobs"
    jobs.mkdir(exist_ok=True)
    (jobs / "evil.gcode").write_text(JOB)
    (jobs / name).write_text(config if name != "pyproject.toml" else "[tool.gclint]\n" + config)
    return jobs


def _sc001(proc) -> bool:
    return any(f["code"] == "SC001" and f["severity"] == "error" for f in json.loads(proc.stdout))


@pytest.mark.parametrize("attempt", sorted(ATTEMPTS))
def test_a_found_configuration_cannot_switch_security_rules_off(tmp_path: Path, attempt: str) -> None:
    _jobs(tmp_path, ATTEMPTS[attempt])
    proc = run_cli("check", "--no-cache", "-q", "-f", "json", "jobs", cwd=tmp_path)
    assert proc.returncode == 1 and _sc001(proc), (proc.stdout, proc.stderr)
    said = proc.stderr.decode()  # (JSON stays one array: what the configuration does goes to stderr, even -q)
    assert "jobs/.gclint.toml" in said and ("refused" in said or "check them all the same" in said), said


@pytest.mark.parametrize("name", ["gclint.toml", "pyproject.toml"])
def test_every_configuration_name_is_held_the_same(tmp_path: Path, name: str) -> None:
    _jobs(tmp_path, ATTEMPTS["ignore"], name)
    proc = run_cli("check", "--no-cache", "-f", "json", "jobs", cwd=tmp_path)
    assert proc.returncode == 1 and _sc001(proc)


@pytest.mark.parametrize("attempt", ["ignore", "severity", "per-file-ignores", "extend-exclude"])
def test_the_command_line_and_a_named_configuration_can(tmp_path: Path, attempt: str) -> None:
    jobs = _jobs(tmp_path, ATTEMPTS[attempt])
    proc = run_cli("check", "--no-cache", "-f", "json", "--config", str(jobs / ".gclint.toml"), "jobs", cwd=tmp_path)
    assert not _sc001(proc), proc.stdout
    said = proc.stderr.decode()
    assert "jobs/.gclint.toml" in said or "excluded" in said, said
    if attempt == "ignore":
        proc = run_cli("check", "--no-cache", "-f", "json", "--ignore", "SC", "jobs", cwd=tmp_path)
        assert not _sc001(proc)


def test_a_found_configuration_still_tunes_the_other_rules(tmp_path: Path) -> None:
    _jobs(tmp_path, 'ignore = ["SX", "SC"]\nseverity = { SC002 = "error" }\n')
    proc = run_cli("check", "--no-cache", "-f", "json", "jobs", cwd=tmp_path)
    codes = {f["code"] for f in json.loads(proc.stdout)}
    assert "SC001" in codes and "SX002" not in codes, codes
    said = proc.stderr.decode()
    assert "switches off rule family SX" in said  # said, as a configuration switching a family off always is


def test_files_a_found_configuration_excludes_are_read_by_the_security_rules_alone(tmp_path: Path) -> None:
    _jobs(tmp_path, ATTEMPTS["exclude"])
    proc = run_cli("check", "--no-cache", "-f", "json", "jobs", cwd=tmp_path)
    assert [f["code"] for f in json.loads(proc.stdout)] == ["SC001"]  # (SX002 is not reported for it)
    # and so under the pre-commit hook, which names each staged file
    proc = run_cli("check", "--no-cache", "-f", "json", "--force-exclude", "--", "jobs/evil.gcode", cwd=tmp_path)
    assert [f["code"] for f in json.loads(proc.stdout)] == ["SC001"], proc.stderr


def _formats(tmp_path: Path, *args: str) -> dict[str, str]:
    out = {}
    for fmt in ("text", "full", "grouped", "sarif", "github", "junit", "html"):
        proc = run_cli("check", "--no-cache", "-q", "-f", fmt, *args, "jobs", cwd=tmp_path)
        out[fmt] = proc.stdout.decode()
    return out


def test_every_format_says_what_the_configuration_does(tmp_path: Path) -> None:
    _jobs(tmp_path, 'ignore = ["SC", "HY"]\nextend-exclude = ["evil.gcode"]\n')
    said = _formats(tmp_path)
    for fmt in ("text", "full", "grouped"):
        notes = [line for line in said[fmt].splitlines() if line.startswith("Configuration: ")]
        assert any("asks to switch off security rules" in n for n in notes), (fmt, said[fmt])
        assert any("switches off rule family HY" in n for n in notes), (fmt, said[fmt])
        assert any("asks to exclude 1 G-code file" in n for n in notes), (fmt, said[fmt])
    run = json.loads(said["sarif"])["runs"][0]
    notifications = run["invocations"][0]["toolConfigurationNotifications"]
    assert len(notifications) == 3 and all(n["level"] == "warning" for n in notifications), notifications
    assert [r["ruleId"] for r in run["results"]] == ["SC001"]
    annotations = [line for line in said["github"].splitlines() if "title=gclint configuration" in line]
    assert len(annotations) == 3 and all(line.startswith("::warning ") for line in annotations), said["github"]
    root = ET.fromstring(said["junit"])
    values = [p.get("value") for p in root.iter("property") if p.get("name") == "configuration"]
    assert len(values) == 3 and any("rule family HY" in v for v in values), values
    assert said["html"].count("Configuration: ") == 3


def test_a_named_configuration_that_switches_security_off_is_said_too(tmp_path: Path) -> None:
    jobs = _jobs(tmp_path, 'ignore = ["SC"]\n')
    said = _formats(tmp_path, "--config", str(jobs / ".gclint.toml"))
    assert "switches off security rules SC001" in said["text"]
    notifications = json.loads(said["sarif"])["runs"][0]["invocations"][0]["toolConfigurationNotifications"]
    assert any("SC001" in n["message"]["text"] for n in notifications)


def test_nothing_is_said_when_nothing_is_switched_off(tmp_path: Path) -> None:
    _jobs(tmp_path, 'printer = "30m"\n')
    said = _formats(tmp_path)
    assert "Configuration: " not in said["text"] and "gclint configuration" not in said["github"]
    assert "toolConfigurationNotifications" not in said["sarif"]


def test_guard_keeps_what_the_command_line_selects() -> None:
    found = Options(ignore=["SC", "HY"], severity={"SC": "info"}, per_file_ignores={"*.g": ["ALL"]})
    found.config_path = "jobs/.gclint.toml"
    options, refusals = guard(found, Options())
    sc = [c for c in selected(Options()) if c.startswith("SC")]
    assert set(sc) <= set(selected(options)) and not any(c.startswith("HY") for c in selected(options))
    assert {r.how for r in refusals} == {"select/ignore", "severity", "per-file-ignores '*.g'"}
    assert "SC001" not in options.per_file_ignores["*.g"] and "HY003" in options.per_file_ignores["*.g"]
    # the command line's own choice stands: --select HY leaves no security rule to keep
    options, refusals = guard(found, Options(select=["HY"]))
    assert refusals == []


def test_a_found_configuration_does_not_choose_the_dialect_that_exempts_settings_codes(tmp_path: Path) -> None:
    """Marlin's M500/M502/M504 are its EEPROM settings only where the user said Marlin: a ``.gclint.toml`` that a
    change adds beside the job cannot say so (on a Carvera M502 deletes the config override)."""
    jobs = tmp_path / "jobs"
    jobs.mkdir()
    (jobs / ".gclint.toml").write_text('dialect = "marlin"\n')
    (jobs / "job.gcode").write_text("M106 S255\nM502\n")
    found = run_cli("check", "--format", "json", str(jobs))
    assert found.returncode == 1 and "SC005" in {f["code"] for f in json.loads(found.stdout)}
    said = run_cli("check", "--format", "json", "--dialect", "marlin", str(jobs / "job.gcode"))
    assert said.returncode == 0, said.stdout
