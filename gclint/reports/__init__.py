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
    found: int | None = None  # with --fix: how many findings there were before (fixing one may end others)
    group: bool = True  # text, full, grouped: one code's findings in a file after the first few as one line
    # what the configuration switches off or excludes, and what a found one asked in vain (every format says
    # it: gclint.settings.configuration_notes)
    configuration: list[str] = field(default_factory=list)


Writer = Callable[[list[FileResult], TextIO, ReportContext], None]


# The formats: ``--format`` name -> (module in gclint.reports, its writer of a whole list, its file-by-file
# ``Report`` class).  One registry; a format's module is imported only when it is used (html brings jinja2).
FORMATS: dict[str, tuple[str, str, str]] = {
    "text": ("text", "write", "TextReport"),
    "concise": ("text", "write", "TextReport"),
    "full": ("text", "write_full", "FullReport"),
    "grouped": ("text", "write_grouped", "GroupedReport"),
    "json": ("json_report", "write", "JsonReport"),
    "sarif": ("sarif", "write", "SarifReport"),
    "github": ("github", "write", "GithubReport"),
    "junit": ("junit", "write", "JunitReport"),
    "html": ("html", "write", "HtmlReport"),
}
# The formats that have a --statistics report: the table (text) in the text formats and github, JSON with json.
_STATISTICS = {name: ("text", "StatisticsReport") for name in ("text", "concise", "full", "grouped", "github")} | {
    "json": ("json_report", "JsonStatisticsReport")
}


def _load(module: str, name: str):
    from importlib import import_module

    return getattr(import_module(f"gclint.reports.{module}"), name)


def writer(fmt: str) -> Writer:
    """The writer of format ``fmt`` (a name in ``FORMATS``)."""
    module, name, _ = FORMATS[fmt]
    return _load(module, name)


def report_class(fmt: str, statistics: bool = False) -> type | None:
    """The ``Report`` class of format ``fmt`` (``gclint.reports.stream``): written file by file.  With
    ``statistics``, its ``--statistics`` report, None when the format has none."""
    if statistics:
        found = _STATISTICS.get(fmt)
        return _load(*found) if found is not None else None
    module, _, name = FORMATS[fmt]
    return _load(module, name)


def formats() -> dict[str, Writer]:
    """Every format's writer (imports every format's module: for tools that list them all)."""
    return {fmt: writer(fmt) for fmt in FORMATS}


def reports(statistics: bool = False) -> dict[str, type]:
    """The ``Report`` class of each format (with ``statistics``, of those that have a --statistics report)."""
    names = _STATISTICS if statistics else FORMATS
    return {fmt: cls for fmt in names if (cls := report_class(fmt, statistics)) is not None}


# Formats read by programs: no progress bar, nothing but the report on stdout.
MACHINE_FORMATS = frozenset({"json", "sarif", "github", "junit", "html"})
