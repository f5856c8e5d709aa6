"""Security: the SC rules on hostile G-code of every dialect, secrets masked in every output, the HTML report
escapes file text, and the configuration is data (it cannot run code; a bad one is one line and exit 2)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from gclint import secrets
from gclint.engine import Linter, Options
from gclint.reports import formats

from .conftest import run_cli
from .strategies import DIALECTS

# -- the rules, line by line ------------------------------------------------------------------------------------

HOSTILE = [
    # (line, expected SC codes)
    ("M792 ; SHELL C:\\program.exe", {"SC001"}),
    ("M0 ; SAY Hello Wilbur ; SHELL C:\\Windows\\System32\\cmd.exe /c del *.*", {"SC001"}),
    ("M0 SHELL C:\\program.exe", {"SC001"}),  # no ";": the grammar refuses the line, the rule still reads it
    ("N10 M792 ; shell calc.exe", {"SC001"}),
    ("M0 (SHELL evil.exe)", {"SC001"}),
    ("RUN_SHELL_COMMAND CMD=backup_cfg PARAMS=now", {"SC001"}),
    ("M0 ; PIC C:\\mr_ed.png", {"SC002"}),
    ("M792 ; VID C:\\sample.mp4 ; BEEP", {"SC002"}),
    ("M792 ; PIC a.png ; SHELL b.exe", {"SC001", "SC002"}),
    ("M1000 rm /sd/config.txt", {"SC003"}),
    ("M1000 config-set sd spindle.max_rpm 30000", {"SC003"}),
    ('M98 P"0:/macros/prime.g"', {"SC004"}),
    ("M98 Phomez.g", {"SC004"}),
    ("M98.1 L2 {gcodes/test.cnc}", {"SC004"}),
    ("M98 P1001", {"SC004"}),  # a Carvera runs gcodes/macros/1001.cnc (a LinuxCNC subprogram: not reported there)
    ("M32 !/models/part.gco#", {"SC004"}),
    ("M23 part2.gco", {"SC004"}),
    ("M30 old_job.gco", {"SC005"}),
    ('M30 "0:/sys/config.g"', {"SC005"}),
    ("M28 /sys/config.g", {"SC005"}),
    ('M471 S"/sys/config.g" T"/sys/config.bak"', {"SC005"}),
    ("; printhost_apikey = 4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19", {"SC006"}),
    ("; printhost_password = hunter2hunter2", {"SC006"}),
    ("; octoprint_apikey = s3cr3t-key-value", {"SC006"}),
    ("; upload http://pi:raspberry@octopi.local/api/files", {"SC006"}),
    ("; Authorization: Bearer abcdEFGH1234ijkl5678", {"SC006"}),
    ('M587 S"workshop" P"wifi-pass-123"', {"SC006", "SC007"}),
    ('M587 S"net" P""', {"SC007"}),  # (no secret, but the printer joins the job's network)
    ("M117 token=abcdef123456", {"SC006"}),
    ("G1 X1 )( ; password=abc123xyz", {"SC006"}),  # a line the grammar refuses: its comment is still read
    ("; ghp_" + "a1B2" * 9, {"SC006"}),
    ("; AKIAABCDEFGHIJKLMNOP", {"SC006"}),
]

HARMLESS = [
    "M0",
    "M0 ; Load the blue filament",
    "M792 ; SAY done ; BEEP ; SEND layer",
    "M1000",
    "M24",
    "M30",
    "M30 ; end",
    "M30 (done)",
    "; printhost_apikey = ",
    "; printhost_password = ",
    "; printhost_authorization_type = key",
    "; print_host = http://octopi.local",
    "; password: ****",
    ";TYPE:WALL-OUTER",
    "; thumbnail begin 16x16 1234",
    "; iVBORw0KGgoAAAANSUhEUgAAABAAAAAQCAYAAAAf8/9hAAAAAXNSR0IArs4c6QAAAARnQU1BAACxjwv8YQUAAAAJcEhZcwAADsMAAA7D",
    "; bbl_use_printhost = 0",
    "(The percent sign (%) after M30 is a special stop code.)",
    "G1 X10 Y10 F3000",
    "; md5 5d41402abc4b2a76b9719d911017c592",
]


def _sc(text: str, dialect: str = "auto") -> list:
    return [f for f in Linter(Options(dialect=dialect, select=["SC"])).check_text(text, "job.gcode").findings]


@pytest.mark.parametrize("line,codes", HOSTILE, ids=[h[0][:40] for h in HOSTILE])
def test_hostile_lines(line: str, codes: set[str]) -> None:
    found = _sc(line + "\n")
    assert {f.code for f in found} == codes, [(f.code, f.message) for f in found]


@pytest.mark.parametrize("line", HARMLESS)
def test_harmless_lines(line: str) -> None:
    assert _sc(line + "\n") == []


@pytest.mark.parametrize("dialect", DIALECTS)
def test_every_dialect_is_checked(dialect: str) -> None:
    text = "M792 ; SHELL evil.exe\nM1000 rm x\nM30 old.gco\n; printhost_apikey = 4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19\n"
    assert sorted(f.code for f in _sc(text, dialect)) == ["SC001", "SC003", "SC005", "SC006"]


def test_findings_point_at_the_action() -> None:
    [f] = _sc("M0 ; SAY hi ; SHELL C:\\x.exe\n")
    assert f.line == 1 and f.column == len("M0 ; SAY hi ; ") + 1
    assert '"C:\\x.exe"' in f.message


# -- a job never silences its own SC findings (issue 12, item 5) ---------------------------------------------------

SELF_SILENCED = [
    "M792 ; SHELL C:\\x.exe ; noqa: SC001",
    "M792 ; SHELL C:\\x.exe ; noqa",
    "M792 ; SHELL C:\\x.exe ; NOQA: SC",
    "M792 (SHELL x.exe) (noqa: SC001)",
    "M792 ; SHELL C:\\tools\\noqa.exe",
    "; gclint: disable=SC\nM792 ; SHELL C:\\x.exe",
    "; gclint: disable=SC001\nM792 ; SHELL C:\\x.exe",
    "; gclint: disable\nM792 ; SHELL C:\\x.exe",
    "(gclint: disable=SC)\nM0 ; SHELL C:\\x.exe",
]


@pytest.mark.parametrize("text", SELF_SILENCED)
def test_a_job_cannot_silence_its_own_security_findings(text: str) -> None:
    assert "SC001" in {f.code for f in _sc(text + "\n")}


def test_noqa_does_not_silence_a_security_finding() -> None:
    # Before issue 12 a job could write "; noqa: SC004" after its own macro call; SC findings are now
    # suppressed only from the configuration or the command line.
    assert [f.code for f in _sc('M98 P"homeall.g" ; noqa: SC004\n')] == ["SC004"]


def test_noqa_inside_a_path_is_not_a_suppression() -> None:
    # "noqa" must start a comment (or follow a ";"): a path or a word that merely contains it is text.
    text = "G1 X1 X2 ; C:\\tools\\noqa.exe\nG1 X1 X2 ; see noqa.txt\nG1 X1 X2 ; noqa: SX002\n"
    findings = Linter(Options(dialect="marlin")).check_text(text, "job.gcode").findings
    assert [(f.line, f.code) for f in findings if f.code == "SX002"] == [(1, "SX002"), (2, "SX002")]


def test_security_findings_are_suppressed_from_the_command_line_and_configuration(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text("; gclint: dialect=hyrel\n; gclint: disable=SC\nM792 ; SHELL C:\\x.exe ; noqa: SC001\n")
    proc = run_cli("check", "--no-cache", "--format", "json", str(job))
    assert proc.returncode == 1 and [f["code"] for f in json.loads(proc.stdout)] == ["SC001"]
    proc = run_cli("check", "--no-cache", "--format", "json", "--ignore", "SC001", str(job))
    assert proc.returncode == 0 and json.loads(proc.stdout) == []
    config = tmp_path / "gclint.toml"
    config.write_text('per-file-ignores = { "job.gcode" = ["SC"] }\n')
    # found beside the job, the configuration cannot (issue 25): the user names it with --config
    proc = run_cli("check", "--no-cache", "--format", "json", str(job))
    assert proc.returncode == 1 and [f["code"] for f in json.loads(proc.stdout)] == ["SC001"]
    proc = run_cli("check", "--no-cache", "--format", "json", "--config", str(config), str(job))
    assert proc.returncode == 0 and json.loads(proc.stdout) == []
    # ... and such a suppression is visible: a note on stderr, in --statistics and in --show-settings
    stderr = proc.stderr.decode()
    assert "SC" in stderr and "gclint.toml" in stderr, stderr
    proc = run_cli("check", "--no-cache", "--statistics", "--config", str(config), str(job))
    assert "SC001" in proc.stdout.decode() and "gclint.toml" in proc.stdout.decode(), proc.stdout
    proc = run_cli("check", "--show-settings", "--config", str(config), str(job))
    shown = proc.stdout.decode()
    assert proc.returncode == 0 and "gclint.toml" in shown and "SC001" in shown and "job.gcode" in shown, shown


def test_postprocess_stops_a_job_that_silences_itself(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text("; gclint: disable=SC\nG28\nM792 ; SHELL C:\\tools\\noqa.exe ; noqa: SC001\n")
    proc = run_cli("postprocess", "--fail-on", "error", str(job))
    assert proc.returncode == 1, proc.stderr
    assert "SC001" in proc.stderr.decode()


# -- secrets -----------------------------------------------------------------------------------------------------

SECRET_VALUES = [
    "4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19",
    "hunter2hunter2",
    "raspberry",
    "abcdEFGH1234ijkl5678",
    "wifi-pass-123",
]
SECRET_JOB = (
    "; gclint: dialect=marlin\n"
    "; printhost_apikey = 4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19\n"
    "; printhost_password = hunter2hunter2\n"
    "M117 http://pi:raspberry@octopi.local/\n"
    "; Authorization: Bearer abcdEFGH1234ijkl5678\n"
    'M587 S"workshop" P"wifi-pass-123"\n'
    # A finding of another rule on a line that holds a secret: its source line must be masked too.
    "M104 S200 S210 ; password=hunter2hunter2\n"
    "G1 X1 )( ; printhost_apikey = 4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19\n"
)


def test_sc_findings_are_masked_in_message_and_source() -> None:
    findings = Linter(Options(dialect="marlin")).check_text(SECRET_JOB, "job.gcode").findings
    sc = [f for f in findings if f.code == "SC006"]
    assert len(sc) == 7, [(f.line, f.message) for f in sc]
    for f in sc:
        for value in SECRET_VALUES:
            assert value not in f.message and value not in (f.source or ""), f
        assert "*" in f.source


def test_mask_keeps_the_key_and_the_length() -> None:
    line = "; printhost_apikey = 4F1C2B7A9D8E4C3B8A7F6E5D4C3B2A19"
    assert secrets.mask(line) == "; printhost_apikey = " + "*" * 32
    assert secrets.mask("G1 X10 Y10") == "G1 X10 Y10"
    assert secrets.mask("http://user:pw1234@host/x") == "http://user:******@host/x"


@pytest.mark.parametrize("fmt", sorted(formats()))
def test_no_output_format_shows_a_secret(tmp_path: Path, fmt: str) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(SECRET_JOB)
    out = tmp_path / f"report.{fmt}"
    proc = run_cli("check", "--format", fmt, "--output", str(out), str(job))
    assert proc.returncode == 1, proc.stderr
    text = out.read_text(encoding="utf-8", errors="replace") + proc.stderr.decode("utf-8", "replace")
    for value in SECRET_VALUES:
        assert value not in text, f"{fmt}: {value} shown"


def test_postprocess_report_shows_no_secret(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(SECRET_JOB)
    report = tmp_path / "job.gcode.gclint.txt"
    proc = run_cli("postprocess", "--fail-on", "never", "--report", str(report), str(job))
    assert proc.returncode == 0, proc.stderr
    text = proc.stderr.decode() + report.read_text()
    for value in SECRET_VALUES:
        assert value not in text


# -- the HTML report escapes file text ----------------------------------------------------------------------------

needs_html = pytest.mark.skipif("html" not in formats(), reason="the html report format does not exist yet")

SCRIPT_JOB = (
    "; <script>alert('comment')</script>\n"
    "M117 <img src=x onerror=alert('m117')>\n"
    "G1 X1 Y1 </pre><script>alert('parse')</script>\n"
    "M104 S200 S210 ; \"><svg onload=alert('attr')>\n"
    "M0 ; SHELL <script>alert('sc')</script>\n"
)


@needs_html
def test_html_report_escapes_file_text(tmp_path: Path) -> None:
    job = tmp_path / "x<b>y.gcode"  # file names are file text too
    job.write_text(SCRIPT_JOB)
    out = tmp_path / "report.html"
    proc = run_cli("check", "--format", "html", "--output", str(out), str(job))
    assert proc.returncode == 1, proc.stderr
    html = out.read_text(encoding="utf-8")
    for raw in ("<script>alert", "<img src=x", "<svg onload", "x<b>y", "onerror=alert('m117')>"):
        assert raw not in html, f"unescaped file text: {raw}"
    assert "&lt;script&gt;alert" in html or "&#60;script&#62;alert" in html, "the comment should be shown, escaped"


# -- configuration is data ---------------------------------------------------------------------------------------

BAD_CONFIGS = {
    "code in a string": ("dialect = \"__import__('os').system('touch PWNED')\"\n", "unknown dialect"),
    "python file content": ("import os\nos.system('touch PWNED')\n", "invalid TOML"),
    "plugins key": ('plugins = ["os:system"]\n', "unknown option 'plugins'"),
    "wrong type": ("select = 5\n", "'select'"),
    "bad printer": ('printer = "zz"\n', "unknown printer"),
    "bad heads": ("loaded = {a = 1}\n", "'loaded'"),
    "bad rpm": ('spindle-max-rpm = "fast"\n', "'spindle-max-rpm'"),
    "invalid TOML": ("ignore = [\n", "invalid TOML"),
    "deeply nested": ("dialect = " + "[" * 50_000 + "]" * 50_000 + "\n", "invalid TOML"),
    "binary": (bytes(range(256)), "invalid TOML"),
    # values are validated, not only typed (issue 12, item 10)
    "nan rpm": ("spindle-max-rpm = nan\n", "'spindle-max-rpm'"),
    "inf rpm": ("spindle-max-rpm = inf\n", "'spindle-max-rpm'"),
    "negative rpm": ("spindle-max-rpm = -5\n", "'spindle-max-rpm'"),
    "absurd rpm": ("spindle-max-rpm = 1e300\n", "'spindle-max-rpm'"),
    "boolean rpm": ("spindle-max-rpm = true\n", "'spindle-max-rpm'"),
    "unicode digit head": ('loaded = ["T\u0661"]\n', "'loaded'"),
    "superscript tool map": ('tool-map = { 0 = "T\u00b2" }\n', "'tool-map'"),
    "huge tool index": ('tool-map = { 0 = "T' + "9" * 5000 + '" }\n', "'tool-map'"),
}


@pytest.mark.parametrize("name", BAD_CONFIGS)
def test_bad_configuration_is_one_line_exit_2_and_runs_nothing(tmp_path: Path, name: str) -> None:
    content, message = BAD_CONFIGS[name]
    config = tmp_path / "gclint.toml"
    config.write_bytes(content if isinstance(content, bytes) else content.encode())
    job = tmp_path / "job.gcode"
    job.write_text("G28\n")
    proc = run_cli("check", str(job), cwd=tmp_path)
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "Traceback" not in stderr, stderr
    lines = [line for line in stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and "gclint.toml" in lines[0] and message in lines[0], lines
    assert not (tmp_path / "PWNED").exists() and not Path("PWNED").exists()


def test_pyproject_section_is_data_too(tmp_path: Path) -> None:
    (tmp_path / "pyproject.toml").write_text(
        '[tool.gclint]\nselect = ["SC"]\n[tool.gclint.hooks]\nbefore = "rm -rf /"\n'
    )
    job = tmp_path / "job.gcode"
    job.write_text("G28\n")
    proc = run_cli("check", str(job), cwd=tmp_path)
    assert proc.returncode == 2 and "unknown option 'hooks'" in proc.stderr.decode()


def test_bad_configuration_for_translate_names_the_file(tmp_path: Path) -> None:
    (tmp_path / "gclint.toml").write_text('spindle-max-rpm = "fast"\n')
    job = tmp_path / "job.gcode"
    job.write_text("G28\n")
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", str(job), cwd=tmp_path)
    assert proc.returncode == 2 and "gclint.toml" in proc.stderr.decode()


def test_configuration_is_read_with_tomllib_only() -> None:
    import inspect

    import gclint.config as config

    source = inspect.getsource(config)
    for forbidden in ("eval(", "exec(", "import_module", "__import__", "yaml", "pickle", "runpy"):
        assert forbidden not in source, forbidden
    assert "tomllib" in source


def test_json_report_of_security_findings(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text("M792 ; SHELL C:\\evil.exe\n")
    proc = run_cli("check", "--format", "json", str(job))
    [finding] = [f for f in json.loads(proc.stdout) if f["code"].startswith("SC")]
    assert finding["code"] == "SC001" and finding["severity"] == "error" and finding["name"] == "host-runs-program"
    assert proc.returncode == 1
    assert os.path.basename(finding["path"]) == "job.gcode"


# -- whole values masked everywhere (issue 12, item 7) --------------------------------------------------------------

MULTIWORD = "correct horse battery staple"
MORE_SECRETS = (
    "; gclint: dialect=hyrel\n"
    f"; printhost_password = {MULTIWORD}\n"
    "; printhost_apikey =            FarAwayKey987654321\n"
    "M0 ; SAY the password=Sesame0pen4me is on the wall\n"
    "M117 token=abc123def456 ghi789\n"
    "M104 S200 S210 ; password: trailing words here\n"
)
MORE_VALUES = [
    "horse",
    "battery",
    "staple",
    "FarAwayKey987654321",
    "Sesame0pen4me",
    "abc123def456",
    "ghi789",
    "trailing",
]


@pytest.mark.parametrize(
    "line,value",
    [
        (f"; printhost_password = {MULTIWORD}", MULTIWORD),
        ("; printhost_apikey =            FarAwayKey987654321", "FarAwayKey987654321"),
        ("; password          =   spaced out value  ", "spaced out value"),
        ('; password = "unterminated quote and more', '"unterminated quote and more'),
    ],
)
def test_secrets_are_masked_whole(line: str, value: str) -> None:
    masked = secrets.mask(line)
    assert value not in masked and not any(w in masked for w in value.split() if len(w) > 3), masked
    assert len(masked) == len(line)


@pytest.mark.parametrize("fmt", sorted(formats()))
def test_no_output_format_shows_any_word_of_a_secret(tmp_path: Path, fmt: str) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(MORE_SECRETS)
    out = tmp_path / f"report.{fmt}"
    proc = run_cli("check", "--no-cache", "--select", "ALL", "--format", fmt, "--output", str(out), str(job))
    assert proc.returncode == 1, proc.stderr
    text = out.read_text(encoding="utf-8", errors="replace") + proc.stderr.decode("utf-8", "replace")
    for value in MORE_VALUES:
        assert value not in text, f"{fmt}: {value} shown"


def test_explain_and_postprocess_mask_secrets(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(MORE_SECRETS + 'M587 S"net" P"wifi secret words"\n')
    shown = ""
    for fmt in ("text", "json"):
        proc = run_cli("explain", "--all-lines", "--format", fmt, str(job))
        assert proc.returncode == 0, proc.stderr
        shown += proc.stdout.decode()
    proc = run_cli("explain", "-e", 'M587 S"net" P"wifi secret words"', "-d", "reprap")
    shown += proc.stdout.decode()
    report = tmp_path / "report.txt"
    proc = run_cli("postprocess", "--fail-on", "never", "--report", str(report), str(job))
    shown += proc.stderr.decode() + report.read_text()
    for value in [*MORE_VALUES, "wifi secret words"]:
        assert value not in shown, value


# -- control characters never reach a terminal (issue 12, item 6) ---------------------------------------------------

ESC_JOB = (
    "; gclint: dialect=hyrel\n"
    "M117 \x1b[2J\x1b[1;1Hall good\x07\n"
    "M792 ; SHELL C:\\x.exe \x1b[8mhidden\x1b[0m\u202e\n"
    "G1 X1 X2 ; \x1b]0;title\x07 \x9b31m\n"
)
RAW_CONTROLS = ("\x1b", "\x07", "\x9b", "\u202e")


def _no_controls(text: str, where: str) -> None:
    for c in RAW_CONTROLS:
        assert c not in text, f"{where}: raw {c!r} in output"
    assert "\r" not in text, where


@pytest.mark.parametrize("fmt", ["text", "full", "grouped", "github", "concise"])
def test_human_formats_escape_control_characters(tmp_path: Path, fmt: str) -> None:
    job = tmp_path / "job\x1b[2K\nx.gcode"
    job.write_bytes(ESC_JOB.encode())
    proc = run_cli("check", "--no-cache", "--format", fmt, "--statistics", str(job))
    assert proc.returncode == 1, proc.stderr
    out = proc.stdout.decode() + proc.stderr.decode()
    _no_controls(out, fmt)
    assert "SC001" in out
    assert all(line.count(".gcode") <= 1 for line in out.splitlines()), "a newline in the file name split a line"
    tabbed = tmp_path / "t\tab.gcode"  # a tab in a file name is escaped too (it shifts what the name shows)
    tabbed.write_bytes(ESC_JOB.encode())
    shown = run_cli("check", "--no-cache", "--format", fmt, str(tabbed)).stdout.decode()
    assert "t\\x09ab.gcode" in shown and "t\tab" not in shown


def test_error_lines_explain_and_postprocess_escape_control_characters(tmp_path: Path) -> None:
    script = tmp_path / "run\x1b[31m.gcode"
    script.write_bytes(b"#!/bin/sh \x1b[2J\x1b]0;pwned\x07\nrm -rf /\n")
    proc = run_cli("check", "--no-cache", str(script))
    assert proc.returncode == 2
    _no_controls(proc.stderr.decode(), "#! refusal")
    proc = run_cli("translate", "--from", "marlin", "--to", "hyrel", str(tmp_path / "missing\x1b[2J.gcode"))
    assert proc.returncode == 2
    _no_controls(proc.stderr.decode(), "translate error")
    job = tmp_path / "job.gcode"
    job.write_bytes(ESC_JOB.encode())
    for args in (("explain", str(job)), ("explain", "-e", "M117 \x1b[2Jhi"), ("explain", "--format", "json", str(job))):
        proc = run_cli(*args)
        assert proc.returncode == 0, proc.stderr
        _no_controls(proc.stdout.decode(), " ".join(args[:2]))
    report = tmp_path / "report.txt"
    proc = run_cli("postprocess", "--fail-on", "error", "--report", str(report), str(job))
    assert proc.returncode == 1
    _no_controls(proc.stderr.decode() + report.read_text(), "postprocess")


def test_nan_rpm_never_reaches_the_output(tmp_path: Path) -> None:
    (tmp_path / "gclint.toml").write_text("spindle-max-rpm = nan\n")
    job = tmp_path / "job.gcode"
    job.write_text("G21\nM3 S12000\nG1 X1 F100\nM5\n")
    proc = run_cli("translate", "--from", "carvera", "--to", "hyrel", str(job), cwd=tmp_path)
    assert proc.returncode == 2 and b"nan" not in proc.stdout.lower(), proc.stdout
    lines = [line for line in proc.stderr.decode().splitlines() if line.strip()]
    assert len(lines) == 1 and "gclint.toml" in lines[0] and "spindle-max-rpm" in lines[0], lines


def test_show_settings_with_a_broken_configuration_is_one_line(tmp_path: Path) -> None:
    (tmp_path / "gclint.toml").write_text("x = [\n")
    job = tmp_path / "job.gcode"
    job.write_text("G28\n")
    proc = run_cli("check", "--show-settings", str(job))
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "internal error" not in stderr and "gclint.toml" in stderr, stderr


def test_sarif_fingerprints_are_not_hashes_of_secrets(tmp_path: Path) -> None:
    import hashlib

    job = tmp_path / "job.gcode"
    line = "M104 S200 S210 ; password=hunter2"
    job.write_text(line + "\n")
    proc = run_cli("check", "--no-cache", "--format", "sarif", str(job))
    results = json.loads(proc.stdout)["runs"][0]["results"]
    prints = {r["partialFingerprints"]["gclint/v1"] for r in results}
    for code in {r["ruleId"] for r in results}:
        raw = "\0".join((code, str(job), line)).encode()
        assert hashlib.sha256(raw).hexdigest()[:32] not in prints


def test_github_annotations_encode_a_line_break_in_a_file_name(tmp_path: Path) -> None:
    """GitHub reads %0A back as the line break, so the annotation finds its file (a raw \\x0a would not)."""
    job = tmp_path / "a\nb.gcode"
    job.write_bytes(ESC_JOB.encode())
    out = run_cli("check", "--no-cache", "--format", "github", str(job)).stdout.decode()
    assert "file=" in out and "a%0Ab.gcode" in out and "\\x0a" not in out
