"""The HTML report in a real headless Chromium: it renders with no console error, its script runs, the
toolpath plot is there (one SVG path per head and kind of move, markers on the flagged lines), and file
text that looks like markup stays text.

Needs Debian's ``chromium`` (``apt-get install chromium``).  Outside CI the test is skipped when no
Chromium is installed; in CI (``CI`` set) it fails instead, because .ci/run installs it.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from tests.conftest import CORPUS, corpus_available, run_cli

BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")


def chromium() -> str:
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    if os.environ.get("CI"):
        pytest.fail("Chromium is not installed, but CI must run this test (.ci/run installs Debian's chromium)")
    pytest.skip("Chromium is not installed (apt-get install chromium); CI installs it and runs this test")


def render(page: Path, profile: Path) -> tuple[str, str]:
    """Load ``page`` headless; returns the DOM after scripts ran and Chromium's log (console included)."""
    cmd = [
        chromium(),
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        f"--user-data-dir={profile}",
        "--enable-logging=stderr",
        "--v=0",
        "--virtual-time-budget=3000",
        "--dump-dom",
        page.as_uri(),
    ]
    proc = subprocess.run(cmd, capture_output=True, timeout=180)
    assert proc.returncode == 0, proc.stderr.decode("utf-8", "replace")[-2000:]
    return proc.stdout.decode("utf-8", "replace"), proc.stderr.decode("utf-8", "replace")


def console(log: str) -> list[str]:
    return [line for line in log.splitlines() if ":CONSOLE" in line]


JOB = (
    "; gclint: dialect=hyrel\n"
    "; <script>document.title='pwned'</script> </svg><b>bold</b>\n"
    "; printhost_apikey = 0123456789abcdef\n"
    "M6 T0 O1 X0 Y0 Z0\nM6 T1 O2 X0 Y0 Z0\n"
    "T0\nG28 X0 Y0\nG1 X10 Y10 E1 F1200\nG1 X40 Y10 E1\nG1 X40 Y40 E1\nG1 X10 X12 Y40 E1\n"  # SX002 on line 11
    "T1\nG0 X60 Y10\nG1 X90 Y10 E1\nG1 X90 Y40 E1 ; <img src=x onerror=alert(1)>\nM9999\nG1 X60 Y40 E1\n"
)


def test_html_report_renders_in_chromium(tmp_path: Path):
    job = tmp_path / "two heads.gcode"
    job.write_text(JOB)
    page = tmp_path / "report.html"
    proc = run_cli("check", "--no-cache", str(job), "--format", "html", "--output", str(page))
    assert proc.returncode == 1, proc.stderr
    dom, log = render(page, tmp_path / "profile")

    messages = console(log)
    assert any("gclint report ready: 1 plot(s)" in m for m in messages), log[-2000:]
    bad = [m for m in messages if re.search(r"Uncaught|Error|Refused|violat", m)]
    assert not bad, bad
    assert 'data-ready="1"' in dom  # the page's script ran to the end under its CSP

    svg = re.search(r'<svg class="plot".*?</svg>', dom, re.S)
    assert svg, "no toolpath plot in the rendered page"
    heads = re.findall(r'<g class="head" data-head="([^"]+)">', svg.group())
    assert heads == ["head T0 (yoke 1, position 1)", "head T1 (yoke 1, position 2)"]
    work = re.findall(r'<path class="work" stroke="[^"]+" d="(M[^"]+)"', svg.group())
    assert len(work) == 2 and all(d.count("L") >= 2 for d in work)
    assert '<path class="travel"' in svg.group()
    markers = re.findall(r'<circle class="marker m-(\w+)" data-line="(\d+)"', svg.group())
    assert ("error", "11") in markers and ("error", "16") in markers

    assert "pwned" not in dom.split("<body", 1)[0]  # the comment's script never ran
    assert "&lt;script&gt;" in dom or "&lt;script>" in dom or "<script>document.title" not in dom
    assert "<img src=" not in dom and "<b>bold</b>" not in dom
    assert "0123456789abcdef" not in dom


@pytest.mark.skipif(not corpus_available(), reason="corpus not found")
def test_html_report_of_a_big_corpus_job_renders(tmp_path: Path):
    job = CORPUS / "marlin" / "prusaslicer-2.6.1_benchy.gcode"
    page = tmp_path / "benchy.html"
    proc = run_cli("check", "--no-cache", str(job), "--format", "html", "--output", str(page), "--exit-zero")
    assert proc.returncode == 0, proc.stderr
    assert page.stat().st_size < 3_000_000  # the plot is sampled, not every move
    dom, log = render(page, tmp_path / "profile")
    assert any("gclint report ready: 1 plot(s)" in m for m in console(log))
    assert not [m for m in console(log) if re.search(r"Uncaught|Error|Refused", m)]
    d = re.search(r'<path class="work" stroke="[^"]+" d="(M[^"]+)"', dom)
    assert d and d.group(1).count("L") > 1000
