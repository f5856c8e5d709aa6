"""``--format github``: GitHub Actions workflow commands, one annotation per finding.

    ::error file=jobs/part.gcode,line=12,col=5,endColumn=9,title=HY003::M109 addressed to a group

Escaping follows the Actions toolkit (``@actions/core`` command.ts): in the message ``%``, CR and LF
become ``%25``, ``%0D``, ``%0A``; in property values ``:`` and ``,`` become ``%3A`` and ``%2C`` as well.
So file text can never end the command early or start a new one on its own line.
"""

from __future__ import annotations

from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import human
from gclint.reports.stream import Report
from gclint.rules.base import Severity

COMMANDS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


def escape_data(text: str) -> str:
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(text: str) -> str:
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _command(kind: str, properties: dict[str, object], text: str) -> str:
    props = ",".join(f"{key}={escape_property(str(value))}" for key, value in properties.items())
    return f"::{kind} {props}::{escape_data(text)}" if props else f"::{kind}::{escape_data(text)}"


class GithubReport(Report):
    def __init__(self, out: TextIO, ctx) -> None:
        super().__init__(out, ctx)
        for note in ctx.configuration:  # first: what the configuration switches off or excludes
            out.write(_command("warning", {"title": "gclint configuration"}, human(note)) + "\n")

    def write_file(self, r: FileResult) -> None:
        out = self.out
        # (line breaks kept for escape_property to write as %0A, as GitHub reads them back)
        path = human(r.path, keep_line_breaks=True).replace("\t", "\\x09")
        if r.error:
            out.write(_command("error", {"file": path, "title": "gclint"}, human(r.error)) + "\n")
        for f in r.findings:
            props: dict[str, object] = {"file": path, "line": f.line, "col": f.column}
            if f.end_column is not None and f.end_column > f.column:
                props["endColumn"] = f.end_column
            props["title"] = f.code
            shown = human(f.message, keep_line_breaks=True)  # escape_data encodes line breaks as %0A
            text = f"{shown} ({f.name})" if f.name else shown
            out.write(_command(COMMANDS[f.severity], props, text) + "\n")


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    GithubReport.write(results, out, ctx)
