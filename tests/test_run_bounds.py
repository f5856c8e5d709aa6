"""A run's memory does not grow with its number of files, findings or suppression comments (the attacker
review's cases A and B): results come one by one and each file's part of the report is written at once
(formats whose head needs totals spool the parts to a temporary file); only counts stay.  Suppression
comments are kept as arrays, and suppressed findings take no place under the per-file bound.

Structural checks only; the memory itself is measured in bench/bench_reports.py.
"""

from __future__ import annotations

import io
import json
import xml.etree.ElementTree as ET
from pathlib import Path

from gclint import runner
from gclint.engine import FileResult, Options
from gclint.reports import ReportContext, formats, reports
from gclint.reports.stream import Tally

from .conftest import run_cli

JOB = "; gclint: dialect=hyrel\nG28\nM109 T40 S200 ; password=hunter2\nG1 X1 X2 F100\nM30\n"


def _results(tmp_path: Path, n: int = 4) -> list[FileResult]:
    paths = []
    for i in range(n):
        p = tmp_path / f"j{i}.gcode"
        p.write_text(JOB if i % 2 == 0 else JOB.replace("M109 T40", "M104 T0"))
        paths.append(str(p))
    missing = str(tmp_path / "missing.gcode")
    return runner.run([*paths, missing], Options(), {})


# -- A: results one by one, reports file by file --------------------------------------------------------------


def test_results_come_one_by_one_with_a_bounded_look_ahead(tmp_path: Path, monkeypatch) -> None:
    checked: list[str] = []
    real = runner.check_file

    def counting(path, options):
        checked.append(path)
        return real(path, options)

    monkeypatch.setattr(runner, "check_file", counting)
    files = []
    for i in range(40):
        p = tmp_path / f"j{i:02}.gcode"
        p.write_text(JOB)
        files.append(str(p))
    stream = runner.results(files, Options(), {}, jobs=1)
    first = next(stream)
    assert first.path == files[0] and len(checked) == 1  # nothing checked ahead in one process
    rest = list(stream)
    assert [r.path for r in [first, *rest]] == files and len(checked) == 40


def test_every_format_written_file_by_file_is_what_it_was(tmp_path: Path) -> None:
    """Each writer is its Report fed the list; a Report fed one result at a time gives the same text."""
    results = _results(tmp_path)
    ctx = ReportContext(tool_version="1.0")
    for name, report_class in reports().items():
        whole = io.StringIO()
        formats()[name](results, whole, ctx)
        parts = io.StringIO()
        report = report_class(parts, ctx)
        for r in results:
            report.add(r)
        report.close()
        if name == "html":  # a new nonce and time on every page
            sections = '<section class="file" id="file-'
            assert parts.getvalue().count(sections) == whole.getvalue().count(sections) == len(results)
        else:
            assert parts.getvalue() == whole.getvalue(), name


def test_sarif_written_from_its_spool_is_valid_and_indexed(tmp_path: Path) -> None:
    results = _results(tmp_path)
    out = io.StringIO()
    formats()["sarif"](results, out, ReportContext(tool_version="1.0"))
    log = json.loads(out.getvalue())
    run = log["runs"][0]
    rules = run["tool"]["driver"]["rules"]
    assert [r["id"] for r in rules] == sorted(r["id"] for r in rules)
    assert run["results"] and all(rules[x["ruleIndex"]]["id"] == x["ruleId"] for x in run["results"])
    assert len(run["results"]) == Tally.of(results).total
    assert run["invocations"][0]["executionSuccessful"] is False  # the missing file
    assert "hunter2" not in out.getvalue()


def test_junit_totals_come_before_the_suites_written_one_by_one(tmp_path: Path) -> None:
    results = _results(tmp_path)
    out = io.StringIO()
    formats()["junit"](results, out, ReportContext())
    root = ET.fromstring(out.getvalue().split("\n", 1)[1])
    suites = root.findall("testsuite")
    assert len(suites) == len(results)
    assert int(root.get("failures")) == sum(int(s.get("failures")) for s in suites) == Tally.of(results).total
    assert int(root.get("errors")) == 1


def test_the_html_page_lists_a_bounded_number_of_findings_in_all(tmp_path: Path, monkeypatch) -> None:
    from gclint.reports import html

    monkeypatch.setattr(html, "HTML_TOTAL_FINDINGS", 5)
    results = _results(tmp_path)
    total = Tally.of(results).total
    page = html.render(results, ReportContext())
    assert page.count('<tr class="f-') == 5 and total > 5
    counts = Tally.of(results).totals()
    assert f"{counts['error']} error" in page and f"{counts['warning']} warning" in page


def test_a_report_file_is_written_whole_and_the_run_counts_exactly(tmp_path: Path) -> None:
    for i in range(3):
        (tmp_path / f"j{i}.gcode").write_text(JOB)
    for fmt in ("json", "sarif", "junit", "html", "github", "text"):
        out = tmp_path / f"report.{fmt}"
        proc = run_cli(
            "check",
            "--no-cache",
            "-j",
            "2",
            "-f",
            fmt,
            "-o",
            str(out),
            "--",
            *sorted(str(p) for p in tmp_path.glob("j*.gcode")),
        )
        assert proc.returncode == 1, (fmt, proc.stderr)
        assert out.exists() and not list(tmp_path.glob(".gclint-*")), fmt
    findings = json.loads((tmp_path / "report.json").read_text())
    proc = run_cli("check", "--no-cache", "-f", "json", "--statistics", str(tmp_path))
    assert sum(row["count"] for row in json.loads(proc.stdout)) == len(findings)


def test_a_report_that_cannot_be_written_is_said_before_checking(tmp_path: Path) -> None:
    (tmp_path / "j.gcode").write_text(JOB)
    link = tmp_path / "report.json"
    link.symlink_to(tmp_path / "elsewhere.json")
    proc = run_cli("check", "--no-cache", "-f", "json", "-o", str(link), str(tmp_path / "j.gcode"))
    assert proc.returncode == 2 and b"the report was not written" in proc.stderr


def test_batches_sent_to_workers_hold_a_few_small_files_or_one_big_one(tmp_path: Path) -> None:
    small = tmp_path / "small.gcode"
    small.write_text(JOB)
    big = tmp_path / "big.gcode"
    big.write_text("G1 X1 F100\n" * (runner.BATCH_BYTES // 11 + 10))
    items = [runner._Item(i, str(p), task=(str(p), Options())) for i, p in enumerate([small, small, big, small, big])]
    batches = [[item.index for item in batch] for batch in runner._batches(iter(items), 16)]
    assert batches == [[0, 1], [2], [3], [4]]


def test_many_files_in_worker_processes_come_back_in_order(tmp_path: Path) -> None:
    files = []
    for i in range(30):
        p = tmp_path / f"j{i:02}.gcode"
        p.write_text(JOB if i % 3 else JOB + "G1 X1 X2\n")
        files.append(str(p))
    one = [(r.path, len(r.findings)) for r in runner.results(files, Options(), {}, jobs=1)]
    two = [(r.path, len(r.findings)) for r in runner.results(files, Options(), {}, jobs=2)]
    assert one == two and [p for p, _ in one] == files
