"""Output formats.  Each module renders the same list of ``FileResult`` objects; ``FORMATS`` maps a
``--format`` name to its writer ``write(results, out, context)``."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TextIO

from gclint.engine import FileResult


@dataclass
class ReportContext:
    """What a report may need besides the findings."""

    tool_version: str = ""
    statistics: bool = False
    show_fixes: bool = True
    color: bool = False
    rules: dict = field(default_factory=dict)  # code -> rule class, for formats that describe rules
    fixed: int | None = None  # with --fix: how many findings were fixed
    group: bool = True  # text, full, grouped: one code's findings in a file after the first few as one line
    # what the configuration switches off or excludes, and what a found one asked in vain (every format says
    # it: gclint.settings.configuration_notes)
    configuration: list[str] = field(default_factory=list)


Writer = Callable[[list[FileResult], TextIO, ReportContext], None]


def formats() -> dict[str, Writer]:
    from gclint.reports import github, html, json_report, junit, sarif, text

    return {
        "text": text.write,
        "concise": text.write,
        "full": text.write_full,
        "grouped": text.write_grouped,
        "json": json_report.write,
        "sarif": sarif.write,
        "github": github.write,
        "junit": junit.write,
        "html": html.write,
    }


def reports(statistics: bool = False) -> dict[str, type]:
    """The ``Report`` class of each format (``gclint.reports.stream``): written file by file.  With
    ``statistics``, the ``--statistics`` report of the formats that have one (text formats and json)."""
    from gclint.reports import github, html, json_report, junit, sarif, text

    if statistics:  # the table (text) in every format that allows --statistics, JSON with json
        return {name: text.StatisticsReport for name in ("text", "concise", "full", "grouped", "github")} | {
            "json": json_report.JsonStatisticsReport
        }
    return {
        "text": text.TextReport,
        "concise": text.TextReport,
        "full": text.FullReport,
        "grouped": text.GroupedReport,
        "json": json_report.JsonReport,
        "sarif": sarif.SarifReport,
        "github": github.GithubReport,
        "junit": junit.JunitReport,
        "html": html.HtmlReport,
    }


# Formats read by programs: no progress bar, nothing but the report on stdout.
MACHINE_FORMATS = frozenset({"json", "sarif", "github", "junit", "html"})
