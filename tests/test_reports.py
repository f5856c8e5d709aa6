"""The report formats, all fed the same findings: SARIF (validated against the official 2.1.0 schema),
GitHub workflow commands, JUnit XML (read back by junitparser, the library CI result publishers use),
full and grouped text, HTML structure and escaping, the toolpath sampler, the progress bar on a real
pseudo-terminal, and docs/rules.md being up to date."""

from __future__ import annotations

import json
import os
import pty
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from gclint.engine import FileResult
from gclint.reports import ReportContext, github
from gclint.reports.toolpath import read_toolpath
from gclint.rules.base import Finding, Severity
from tests.conftest import CORPUS, FIXTURES, ROOT, needs_corpus, run_cli

SECRET = "0123456789abcdef"
BAD = (
    "; gclint: dialect=marlin\n"
    f"; printhost_apikey = {SECRET}\n"
    "G28\n"
    "G1 X10 Y10 E1 F1200\n"
    'G1 X1 <b>&amp;"%,:\n'  # SX001: a message that quotes file text with markup and command characters
    "G1 X20 X30 Y20 E2 ; <img src=x onerror=alert(1)>\n"  # SX002
    "M9999 ; \x1b[31mred\n"  # DL001 (warning) with a terminal escape in the line
    "G1 X5 Y5 E3\n"
)
GOOD = "; gclint: dialect=marlin\nG28\nG1 X10 Y10 E1 F1200\nG1 X20 Y20 E2\n"


@pytest.fixture
def jobs(tmp_path: Path) -> dict[str, Path]:
    bad = tmp_path / "bad job.gcode"
    bad.write_bytes(BAD.encode() + b"; latin-1 \xe9\xff\n")
    good = tmp_path / "good.gcode"
    good.write_text(GOOD)
    return {"bad": bad, "good": good, "missing": tmp_path / "missing.gcode", "dir": tmp_path}


def check(*args: str, cwd: Path | None = None, env: dict | None = None) -> subprocess.CompletedProcess:
    return run_cli("check", "--no-cache", *args, cwd=cwd, env=env)


# -- SARIF ---------------------------------------------------------------------------------------------


def need(module: str):
    """Import a test dependency: skip without it on a developer machine, fail in CI (.ci/run installs it)."""
    try:
        return __import__(module)
    except ImportError:
        if os.environ.get("CI"):
            pytest.fail(f"{module} is not installed; it belongs in the test extras")
        pytest.skip(f"{module} is not installed")


def sarif_validator():
    jsonschema = need("jsonschema")
    schema = json.loads((FIXTURES / "sarif-schema-2.1.0.json").read_text(encoding="utf-8"))
    return jsonschema.Draft4Validator(schema)


def test_sarif_validates_against_the_official_schema(jobs):
    proc = check("bad job.gcode", "good.gcode", "missing.gcode", "--format", "sarif", cwd=jobs["dir"])
    assert proc.returncode == 2, proc.stderr  # the missing file
    log = json.loads(proc.stdout)
    errors = sorted(sarif_validator().iter_errors(log), key=str)
    assert not errors, "\n".join(str(e) for e in errors[:3])
    run = log["runs"][0]
    rules = {r["id"]: r for r in run["tool"]["driver"]["rules"]}
    assert {"SX001", "SX002", "DL001"} <= set(rules)
    for rule in rules.values():
        # no address is published: the rule reference of this install (gclint.ruledocs), at the rule's heading
        assert rule["helpUri"].startswith("file://") and rule["helpUri"].endswith("/rules.md#" + rule["id"].lower())
        assert rule["help"]["text"] and rule["shortDescription"]["text"]
    published = check(
        "bad job.gcode", "--format", "sarif", cwd=jobs["dir"], env={"GCLINT_DOCS_URL": "https://x.example/rules.md"}
    )
    for rule in json.loads(published.stdout)["runs"][0]["tool"]["driver"]["rules"]:
        assert rule["helpUri"] == "https://x.example/rules.md#" + rule["id"].lower()  # the heading's anchor
    results = run["results"]
    by_rule = {r["ruleId"]: r for r in results}
    sx002 = by_rule["SX002"]
    assert sx002["level"] == "error" and by_rule["DL001"]["level"] == "warning"
    region = sx002["locations"][0]["physicalLocation"]["region"]
    assert region["startLine"] == 6 and region["startColumn"] >= 1
    assert sx002["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "bad%20job.gcode"
    assert rules[sx002["ruleId"]] is run["tool"]["driver"]["rules"][sx002["ruleIndex"]]
    text = json.dumps(log)
    assert SECRET not in text  # snippets and messages are masked
    assert not run["invocations"][0]["executionSuccessful"]
    assert "missing.gcode" in run["invocations"][0]["toolExecutionNotifications"][0]["message"]["text"]


def test_sarif_of_a_clean_run_is_valid_and_empty(jobs):
    proc = check(str(jobs["good"]), "--format", "sarif")
    assert proc.returncode == 0, proc.stderr
    log = json.loads(proc.stdout)
    assert not list(sarif_validator().iter_errors(log))
    assert log["runs"][0]["results"] == [] and log["runs"][0]["invocations"][0]["executionSuccessful"]


@needs_corpus
def test_sarif_on_corpus_files_is_valid():
    files = [CORPUS / "hyrel" / "unidentified_idx23519466326__shape1_v4.gcode", CORPUS / "other"]
    proc = check(*map(str, files), "--format", "sarif", "--exit-zero")
    log = json.loads(proc.stdout)
    assert not list(sarif_validator().iter_errors(log))


# -- GitHub --------------------------------------------------------------------------------------------


def test_github_escaping_follows_the_actions_toolkit():
    assert github.escape_data("50% done\r\nnext") == "50%25 done%0D%0Anext"
    assert github.escape_property("a:b,c%\n") == "a%3Ab%2Cc%25%0A"
    finding = Finding(
        "dir,1/a:b.gcode", 3, 4, "HY003", Severity.ERROR, "line one\n::error::injected 100%", "name", end_column=9
    )
    out = _render(github.write, [FileResult("dir,1/a:b.gcode", [finding])])
    assert out == (
        "::error file=dir%2C1/a%3Ab.gcode,line=3,col=4,endColumn=9,title=HY003::line one%0A::error::injected 100%25 (name)\n"
    )
    assert out.count("\n") == 1  # file text can never start a second command


def test_github_format_from_the_cli(jobs):
    proc = check("bad job.gcode", "--format", "github", cwd=jobs["dir"])
    assert proc.returncode == 1
    lines = proc.stdout.decode().splitlines()
    assert all(line.startswith(("::error ", "::warning ", "::notice ")) for line in lines)
    assert any(line.startswith("::error file=bad job.gcode,line=6,col=") and "title=SX002::" in line for line in lines)
    assert any(line.startswith("::warning file=bad job.gcode,line=7,") for line in lines)
    sx001 = next(line for line in lines if "title=SX001" in line)
    assert "%25" in sx001 and "\x1b" not in proc.stdout.decode()


# -- JUnit ---------------------------------------------------------------------------------------------


def test_junit_structure_and_escaping(jobs):
    proc = check("bad job.gcode", "good.gcode", "missing.gcode", "--format", "junit", cwd=jobs["dir"])
    assert proc.returncode == 2
    root = ET.fromstring(proc.stdout)  # well-formed XML despite <, &, quotes, ESC and latin-1 bytes
    assert root.tag == "testsuites"
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    assert set(suites) == {"bad job.gcode", "good.gcode", "missing.gcode"}
    bad = suites["bad job.gcode"]
    failures = bad.findall("testcase/failure")
    assert int(bad.get("failures")) == len(failures) == int(bad.get("tests")) >= 3
    assert {f.get("type") for f in failures} >= {"SX001", "SX002", "DL001"}
    sx001 = next(f for f in failures if f.get("type") == "SX001")
    assert '<b>&amp;"%' in sx001.get("message")  # round-trips as text, not markup
    assert SECRET not in proc.stdout.decode()
    good = suites["good.gcode"]
    assert good.get("failures") == "0" and len(good.findall("testcase")) == 1
    assert suites["missing.gcode"].find("testcase/error") is not None
    total = sum(int(s.get("tests")) for s in suites.values())
    assert root.get("tests") == str(total)


def test_junit_is_read_by_junitparser(jobs, tmp_path):
    junitparser = need("junitparser")
    out = tmp_path / "report.xml"
    check(str(jobs["bad"]), str(jobs["good"]), "--format", "junit", "--output", str(out))
    xml = junitparser.JUnitXml.fromfile(str(out))
    suites = list(xml)
    assert len(suites) == 2
    bad = suites[0]
    cases = list(bad)
    assert bad.failures == len(cases) >= 3
    assert all(not case.is_passed for case in cases)
    assert any(r.type == "SX002" for case in cases for r in case.result)
    assert list(suites[1])[0].is_passed


def test_junit_writes_no_bidirectional_control_raw(tmp_path):
    """Issue 25: a file name with U+202E (RIGHT-TO-LEFT OVERRIDE) reached the JUnit report raw, so a viewer
    showed the name, and what followed it, reversed."""
    name = "job\u202egcode.txt.gcode"
    (tmp_path / name).write_text("; gclint: dialect=marlin\nM9999\n")
    proc = check(name, "--format", "junit", cwd=tmp_path)
    text = proc.stdout.decode()
    assert "\u202e" not in text and "job\\u202egcode" in text, text
    assert ET.fromstring(proc.stdout).find("testsuite").get("name") == "job\\u202egcode.txt.gcode"


def test_configuration_notes_are_valid_sarif_and_junit(tmp_path):
    """What the configuration switches off goes in every report: as SARIF tool configuration notifications
    (valid against the schema) and as a JUnit suite's properties (read back by junitparser); a file that is not
    G-code is a notification and its security findings are results."""
    junitparser = need("junitparser")
    (tmp_path / ".gclint.toml").write_text('ignore = ["SC", "HY"]\n')
    (tmp_path / "a.nc").write_bytes(b"#!/bin/sh\nM792 ; SHELL C:\\x.exe\n")
    proc = check("a.nc", "--format", "sarif", cwd=tmp_path)
    log = json.loads(proc.stdout)
    errors = sorted(sarif_validator().iter_errors(log), key=str)
    assert not errors, "\n".join(str(e) for e in errors[:3])
    invocation = log["runs"][0]["invocations"][0]
    assert len(invocation["toolConfigurationNotifications"]) == 2 and not invocation["executionSuccessful"]
    assert [r["ruleId"] for r in log["runs"][0]["results"]] == ["SC001"]
    out = tmp_path / "report.xml"
    check("a.nc", "--format", "junit", "--output", str(out), cwd=tmp_path)
    suites = {suite.name: suite for suite in junitparser.JUnitXml.fromfile(str(out))}
    configuration = suites["gclint configuration"]
    assert len([p for p in configuration.properties() if p.name == "configuration"]) == 2
    assert all(case.is_passed for case in configuration)
    assert any(r.type == "SC001" for case in suites["a.nc"] for r in case.result)


# -- text: full and grouped ----------------------------------------------------------------------------


def test_full_format_shows_the_line_and_a_caret(jobs):
    proc = check("bad job.gcode", "--format", "full", cwd=jobs["dir"])
    text = proc.stdout.decode()
    block = text.split("bad job.gcode:6:")[1]
    source_line, caret_line = block.splitlines()[2:4]
    assert source_line.startswith(" 6 | G1 X20 X30")
    column = source_line.index("G1 X20 X30") + len("G1 X20 ")
    assert caret_line.index("^") == column
    unknown = text.split("bad job.gcode:7:1:")[1].splitlines()
    assert unknown[2].startswith(" 7 | M9999") and unknown[3].endswith("| ^^^^^")  # the whole code word
    assert SECRET not in text and "\x1b" not in text and "\\x1b[31m" in text
    assert text.rstrip().splitlines()[-2].startswith("Found ") and text.rstrip().endswith("Checked as marlin.")


def test_grouped_format_groups_by_file(jobs):
    proc = check("bad job.gcode", "good.gcode", "--format", "grouped", cwd=jobs["dir"])
    lines = proc.stdout.decode().splitlines()
    assert lines[0] == "bad job.gcode:"
    assert any(line.startswith("  6:") and "SX002" in line for line in lines)
    assert "good.gcode:" not in lines  # files without findings are not listed


# -- HTML (structure; the browser test is test_html_chromium.py) ----------------------------------------


def toolpath_data(page: str) -> list[dict]:
    """The toolpath viewer's data of each figure on a page (an attribute's value, escaped as text)."""
    import html

    return [
        json.loads(html.unescape(d)) for d in re.findall(r'<figure class="toolpath"[^>]* data-toolpath="([^"]*)"', page)
    ]


def test_html_escapes_file_text_and_plots_the_toolpath(jobs):
    proc = check("bad job.gcode", "good.gcode", "--format", "html", cwd=jobs["dir"])
    page = proc.stdout.decode()
    assert page.startswith("<!DOCTYPE html>")
    assert "<img src=x" not in page and "&lt;img src=x onerror=alert(1)&gt;" in page
    assert "<b>&amp;amp;" not in page and "&lt;b&gt;&amp;amp;&#34;" in page
    assert SECRET not in page
    bad, good = toolpath_data(page)
    assert [h["name"] for h in bad["heads"]] == ["extruder 0"] and len(bad["layers"]) == 1
    assert [6, 0] in [[m[3], m[4]] for m in bad["markers"]]  # line 6, an error (SX002)
    assert '<button type="button" class="goto" data-line="6"' in page  # the finding leads to its marker
    assert good["markers"] == [] and good["layers"][0]["p"]
    assert page.count("<script") == 1  # only the report's own script, with its nonce


def test_html_toolpath_data_decodes_to_the_moves(tmp_path):
    from gclint.reports.html import build_plot

    job = tmp_path / "square.gcode"
    job.write_text(
        "; gclint: dialect=marlin\nG28\nM83\nG1 Z0.2 F600\nG0 X10 Y10\nG1 X20 Y10 E1\nG1 X20 Y20 E1\nG0 X30 Y30\n"
    )
    plot = build_plot(read_toolpath(str(job), "marlin"))
    data = json.loads(plot.data)
    (layer,) = data["layers"]
    head, steps, runs = layer["p"][0]
    points, x, y = [], 0, 0
    for dx, dy in zip(steps[::2], steps[1::2], strict=True):
        x, y = x + dx, y + dy
        points.append((round(data["origin"][0] + x * data["unit"], 3), round(data["origin"][1] + y * data["unit"], 3)))
    # from home (0, 0): a travel to (10, 10), two working strokes, a travel to (30, 30)
    assert points == [(0, 0), (10, 10), (20, 10), (20, 20), (30, 30)] and runs == [1, 2, 1]
    assert plot.fit == (10, 10, 20, 20) and plot.bounds == (0, 0, 30, 30)
    assert plot.label == "layer 1 of 1, Z 0.2 mm"


def test_toolpath_sampling_is_bounded(tmp_path):
    path = tmp_path / "big.gcode"
    with path.open("w") as fh:
        fh.write("; gclint: dialect=marlin\nT0\nG28\n")
        for i in range(60000):
            if i % 6000 == 0:
                fh.write(f"G1 Z{0.2 + i // 6000 * 0.2:.1f}\n")
            fh.write(f"G1 X{i % 200} Y{(i // 200) % 200} E{i}\n")
            if i == 30000:
                fh.write("T1\n")
    toolpath = read_toolpath(str(path), "marlin", {10, 30012}, budget=4000, cap=1000)
    assert set(toolpath.heads) == {"extruder 0", "extruder 1"}  # (each head in the dialect's own terms)
    assert len(toolpath.layers) == 10 and toolpath.points <= 4000 and toolpath.stride > 1
    for layer in toolpath.layers:
        assert layer.working == 6000 or layer.working == 5999  # (every move seen; one in a few kept)
        assert all(len(stroke) <= 1000 for stroke in layer.strokes.values())
    # (every move in XY is drawn; homing is none, nor are the Z moves)
    assert sum(h.moves for h in toolpath.heads.values()) == 60000
    assert [m.line for m in toolpath.markers] == [10, 30012]
    assert toolpath.markers[1].head == "extruder 1" and toolpath.markers[1].layer == 5


def test_toolpath_thinning_never_draws_work_across_a_travel():
    from gclint.reports.toolpath import Stroke

    stroke = Stroke()
    stroke.jump(0, 0)
    for i in range(1, 9):
        stroke.add(i, 0, working=i not in (3, 6))  # travel into points 3 and 6
    stroke.halve()
    assert list(stroke.xs) == [0, 2, 4, 6, 8]
    # 0-2 works (1 and 2 do); 2-4 does not (3 is a travel); 4-6 does not (6); 6-8 works
    assert list(stroke.work)[1:] == [1, 0, 0, 1] and stroke.stride == 2


LAYERED = (
    "; gclint: dialect=marlin\nG28\nM83\n"
    "G1 Z15 F600\nG1 X0 Y-3 E5 F1000\nG1 X60 Y-3 E9\n"  # a purge line printed at Z15, far from the part
    + "".join(
        f"{{marker}}G1 Z{0.2 * k:.1f}\nG0 X100 Y100\n"
        + "".join(f"G1 X{100 + (i % 2) * 10} Y{100 + i / 4} E0.5\n" for i in range(1, 41))
        for k in range(1, 6)
    )
    + "G1 Z30\nG0 X0 Y200\n"  # parking
)


@pytest.mark.parametrize("marker", ["", ";LAYER_CHANGE\n", ";LAYER:{n}\n", "; CHANGE_LAYER\n"])
def test_toolpath_layers_and_the_box_of_the_part(tmp_path, marker):
    """Layers are the slicer's where it marks them, else the heights the job prints at; either way a purge line
    at Z15 and a parking move are no layer of their own, and the part's box leaves them out."""
    job = tmp_path / "layered.gcode"
    job.write_text(LAYERED.replace("{marker}", marker).replace("{n}", "3"))
    toolpath = read_toolpath(str(job), "marlin")
    assert toolpath.by_markers == bool(marker)
    assert [(layer.z_low, layer.z_high) for layer in toolpath.layers] == [(round(0.2 * k, 1),) * 2 for k in range(1, 6)]
    assert toolpath.fit() == (100, 100, 110, 110)
    assert toolpath.bounds() == (0, -3, 110, 200)


def test_toolpath_layer_markers_in_the_settings_are_not_layers(tmp_path):
    job = tmp_path / "settings.gcode"
    job.write_text(
        "; gclint: dialect=marlin\nG28\nM83\nG1 Z0.2\nG1 X1 Y1 E1\nG1 Z0.4\nG1 X2 Y2 E1\n"
        "; layer_gcode = ;LAYER_CHANGE\\n;Z:[layer_z]\n; before_layer_gcode = ;LAYER:[layer_num]\n"
    )
    toolpath = read_toolpath(str(job), "marlin")
    assert not toolpath.by_markers and len(toolpath.layers) == 2


def test_toolpath_of_many_heads_at_many_heights_stays_bounded(tmp_path, monkeypatch):
    from gclint.reports import toolpath as module

    monkeypatch.setattr(module, "MAX_LAYERS", 64)
    monkeypatch.setattr(module, "MAX_STROKES", 128)
    job = tmp_path / "hostile.gcode"
    with job.open("w") as fh:
        fh.write("; gclint: dialect=marlin\nG28\nM83\n")
        for k in range(600):  # 600 heights, a head of ten each
            fh.write(f"T{k % 10}\nG1 Z{0.01 * (k + 1):.2f}\nG1 X1 Y{k % 50} E1\nG1 X2 Y{k % 50} E1\n")
    toolpath = read_toolpath(str(job), "marlin", budget=500, cap=50)
    assert len(toolpath.layers) <= 64 and sum(len(layer.strokes) for layer in toolpath.layers) <= 128
    assert toolpath.points <= 500 and toolpath.merged > 1
    assert sum(layer.working for layer in toolpath.layers) == 1200  # (every working move is in a layer)


def test_summary_as_a_page(tmp_path):
    job = tmp_path / "job <1>.gcode"
    job.write_text(GOOD)
    out = tmp_path / "summary.html"
    proc = run_cli("summary", str(job), "--format", "html", "--output", str(out))
    assert proc.returncode == 0, proc.stderr
    page = out.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>") and "<title>gclint summary: 1 job</title>" in page
    assert "job &lt;1&gt;.gcode" in page and "job <1>" not in page
    assert "Job summary" in page and "Read as" in page and 'class="findings"' not in page
    (data,) = toolpath_data(page)
    assert data["layers"] and data["markers"] == []
    assert page.count("<script") == 1 and "script-src 'nonce-" in page


def test_toolpath_of_stdin_is_not_plotted():
    assert read_toolpath("-", "hyrel").error


# -- progress bar ----------------------------------------------------------------------------------------


def _check_on_a_terminal(args: list[str]) -> tuple[int, str, bytes]:
    master, slave = pty.openpty()
    env = dict(os.environ, TERM="xterm")
    env.pop("GCLINT_CACHE_DIR", None)
    with open(os.devnull, "wb") as devnull:
        proc = subprocess.Popen(
            [sys.executable, "-m", "gclint", "check", "--no-cache", *args],
            stdout=subprocess.PIPE,
            stderr=slave,
            stdin=devnull,
            env=env,
        )
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:
            break
        if not data:
            break
        chunks.append(data)
    out = proc.stdout.read()
    code = proc.wait()
    os.close(master)
    return code, b"".join(chunks).decode("utf-8", "replace"), out


def _many_files(folder: Path, n: int = 25) -> list[str]:
    for i in range(n):
        (folder / f"job{i:02}.gcode").write_text(GOOD)
    return [str(folder)]


def test_progress_bar_on_a_terminal(tmp_path):
    code, err, out = _check_on_a_terminal(_many_files(tmp_path) + ["--jobs", "1"])
    assert code == 0
    assert "checking [" in err and "25/25 files" in err
    assert err.endswith("\r")  # erased before the report
    assert b"All checks passed." in out and b"checking" not in out


def test_no_progress_bar_for_machine_formats_or_pipes(tmp_path):
    paths = _many_files(tmp_path)
    code, err, out = _check_on_a_terminal([*paths, "--format", "json"])
    assert "checking" not in err and json.loads(out) == []
    proc = check(*paths, "--progress")  # stderr is a pipe here: never a bar
    assert b"checking" not in proc.stderr


# -- docs/rules.md ----------------------------------------------------------------------------------------


def test_rules_reference_is_up_to_date():
    proc = subprocess.run([sys.executable, str(ROOT / "scripts" / "gen_rules_doc.py"), "--check"], capture_output=True)
    assert proc.returncode == 0, proc.stderr.decode() + " (run: python scripts/gen_rules_doc.py)"


def _render(writer, results) -> str:
    import io

    out = io.StringIO()
    writer(results, out, ReportContext(tool_version="test"))
    return out.getvalue()
