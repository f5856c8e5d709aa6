"""Output formats.  Each module renders the same list of ``FileResult`` objects; ``FORMATS`` maps a
``--format`` name to its writer ``write(results, out, context)``."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, TextIO

from gclint.engine import FileResult


@dataclass
class ReportContext:
    """What a report may need besides the findings."""

    tool_version: str = ""
    statistics: bool = False
    show_fixes: bool = True
    color: bool = False
    rules: dict = field(default_factory=dict)  # code -> rule class, for formats that describe rules


Writer = Callable[[list[FileResult], TextIO, ReportContext], None]


def formats() -> dict[str, Writer]:
    from gclint.reports import json_report, text

    out: dict[str, Writer] = {
        "text": text.write,
        "concise": text.write,
        "json": json_report.write,
    }
    try:
        from gclint.reports import extra  # formats added by later modules (sarif, github, junit, html...)

        out.update(extra.FORMATS)
    except ImportError:
        pass
    return out
