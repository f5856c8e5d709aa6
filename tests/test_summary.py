"""Issue 14: ``gclint summary`` (and the summary in the HTML report), checked against counts made by hand."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from gclint.summary import summarize_path
from tests.conftest import CORPUS, needs_corpus, run_cli

HAND = """\
; gclint: dialect=hyrel
M6 T0 O1 X0 Y0 Z0
M6 T1 O2 X20 Y0 Z0
M140 S60
M109 T0 S215
M104 T1 S200
G21
G90
G28 X0 Y0
M229 E1 D1
T0
G1 Z0.3 F600
G1 X10 Y0 E1 F1200
G1 X10 Y10 E2
G1 Z0.6 F600
G1 X0 Y10 E3 F1200
T1
G1 X0 Y0 E4
G4 P2000
M30
"""


def test_a_hand_written_job(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(HAND)
    s = summarize_path(str(job))
    heads = {h.head: h for h in s.heads}
    assert heads["T0"].set_points == [215] and heads["T0"].waits == [215] and heads["T0"].printing_moves == 3
    assert heads["T1"].set_points == [200] and heads["T1"].waits == [] and heads["T1"].printing_moves == 1
    assert heads["T0"].extruded_mm == pytest.approx(3) and heads["T1"].extruded_mm == pytest.approx(1)
    assert s.devices == {"bed": [60]} and s.waited_devices == {}
    assert s.flow.startswith("native then E values")
    assert s.layers == 2 and s.z_range == (0.3, 0.6)
    assert s.x_range == (0, 10) and s.y_range == (0, 10) and s.feed_range == (1200, 1200)
    assert s.printing_mm == pytest.approx(40)
    # by hand: 40 mm at 1200 mm/min = 2 s; the Z move 0.3 -> 0.6 at 600 = 0.03 s (the first Z move starts
    # where Z is unknown: not counted); G4 P2000 = 2 s
    assert s.time_s == pytest.approx(2 + 0.03 + 2, abs=0.005)


@needs_corpus
def test_a_prusaslicer_job_against_its_own_counts() -> None:
    path = CORPUS / "marlin" / "prusaslicer-2.6.1_benchy.gcode"
    text = path.read_text(errors="replace")
    s = summarize_path(str(path))
    layers = len(re.findall(r"^;LAYER_CHANGE", text, re.M))  # the slicer's own layer marks (160)
    assert s.layers == layers + 1  # + the start purge line at Z 0.2, below the first layer
    assert s.z_range[1] == float(re.findall(r"^;Z:([\d.]+)", text, re.M)[-1])
    used = float(re.search(r"^; filament used \[mm\] = ([\d.]+)", text, re.M).group(1))
    [head] = s.heads
    assert head.extruded_mm == pytest.approx(used, rel=0.002)  # net E: retractions taken back
    assert s.bed == (0, 0, 180, 180) and s.outside_bed  # the purge line runs at Y -2, off the bed


def test_cli_text_and_json(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(HAND)
    out = run_cli("summary", str(job)).stdout.decode()
    assert "T0: set-points 215 °C; waits for 215; 3 printing moves; 3.0 mm of filament" in out
    assert "layers: 2, Z 0.3 to 0.6 mm" in out and "estimated time: 0 min 04 s" in out
    data = json.loads(run_cli("summary", "-f", "json", str(job)).stdout)
    assert data[0]["layers"] == 2 and data[0]["read_as"].startswith("hyrel v5")
    assert run_cli("summary", str(tmp_path / "missing.gcode")).returncode == 2


def test_html_report_has_the_summary_and_counts_in_words(tmp_path: Path) -> None:
    job = tmp_path / "job.gcode"
    job.write_text(HAND.replace("M109 T0 S215", "M109 T40 S215"))
    html = run_cli("check", "-f", "html", str(job)).stdout.decode()
    assert "Job summary" in html and "layers: 2, Z 0.3 to 0.6 mm" in html
    assert "1 error<" in html and "1 errors" not in html
    assert re.search(r"1 finding in 1 file", html)
