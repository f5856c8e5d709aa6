"""``--format sarif``: SARIF 2.1.0 (OASIS), the format GitHub code scanning and most CI dashboards read.

One run; ``tool.driver.rules`` describes every rule that produced a result (summary, explanation with
examples as help text, ``helpUri``, default level); each result points at ``path:line:column`` with the
line (secrets masked) as its snippet.  Files that could not be read become tool execution
notifications, and the invocation is then marked unsuccessful (what the security rules still found in a
file that is not G-code is listed as results too).  What the configuration switches off or excludes is a
tool configuration notification (``ReportContext.configuration``).
"""

from __future__ import annotations

import hashlib
import io
import json
import os
from pathlib import PurePosixPath, PureWindowsPath
from typing import Any, TextIO
from urllib.parse import quote

from gclint.engine import FileResult
from gclint.reports.common import clean, mask, message, rule_docs, source_line
from gclint.reports.stream import Report, Spool
from gclint.ruledocs import rule_url
from gclint.rules.base import Finding, Severity, project_url

SCHEMA = "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
LEVELS = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
_DOC_LEVELS = {"error": "error", "warning": "warning", "info": "note"}


def artifact_uri(path: str) -> tuple[str, str | None]:
    """A SARIF ``uri`` (and ``uriBaseId``) for a path as gclint printed it.

    Relative paths stay relative to the folder gclint ran in (``%SRCROOT%``), which is what GitHub code
    scanning expects when gclint runs at the repository root; absolute paths become ``file://`` URIs.
    """
    if path == "-" or not path:
        return "stdin", None
    windows = PureWindowsPath(path)
    if windows.drive and windows.is_absolute():
        return "file:///" + quote(_raw(windows.as_posix()), safe="/:"), None
    posix = path.replace(os.sep, "/") if os.sep != "/" else path
    if posix.startswith("/"):
        return "file://" + quote(_raw(posix), safe="/"), None
    parts = [p for p in PurePosixPath(posix).parts if p != "."]
    return quote(_raw("/".join(parts)), safe="/"), "%SRCROOT%"


def _raw(path: str) -> bytes:
    """The file name's bytes (a Latin-1 name that is not UTF-8 is kept as it is on disk, percent-encoded)."""
    return path.encode("utf-8", "surrogateescape")


def _rule_descriptor(code: str, doc: dict | None, name: str | None) -> dict:
    if doc is None:  # a code with no registered rule (e.g. a plugin that is gone): describe it briefly
        name = name or code
        return {"id": code, "name": name, "shortDescription": {"text": name}}
    help_parts = [doc["summary"]]
    if doc["explanation"]:
        help_parts += ["", doc["explanation"]]
    markdown = list(help_parts)
    if doc["example_bad"]:
        help_parts += ["", "Bad:", doc["example_bad"]]
        markdown += ["", "Bad:", "", "```gcode", doc["example_bad"], "```"]
    if doc["example_good"]:
        help_parts += ["", "Good:", doc["example_good"]]
        markdown += ["", "Good:", "", "```gcode", doc["example_good"], "```"]
    descriptor: dict[str, Any] = {
        "id": code,
        "name": _pascal(doc["name"]) if doc["name"] else code,
        "shortDescription": {"text": doc["summary"] or code},
        "fullDescription": {"text": doc["explanation"] or doc["summary"] or code},
        "help": {"text": "\n".join(help_parts), "markdown": "\n".join(markdown)},
        "defaultConfiguration": {"level": _DOC_LEVELS.get(doc["severity"], "warning")},
        "properties": {"tags": [code[:2], *doc["applies_to"]], "kebab-name": doc["name"]},
    }
    if doc["source"]:
        descriptor["properties"]["source"] = doc["source"]
    if url := rule_url(code):  # (gclint.ruledocs: a published address, else the installed rules.md)
        descriptor["helpUri"] = url
    return descriptor


def _pascal(kebab: str) -> str:
    # SARIF names are conventionally identifiers; keep the kebab-case name in properties
    return "".join(p[:1].upper() + p[1:] for p in kebab.replace("_", "-").split("-") if p)


def _fingerprint(f: Finding) -> str:
    # Stable across runs and insertions above the line: the code, the file and the line's text.
    # masked: a hash of a line that holds a short password could be reversed by trying passwords
    text = mask(f.source) if f.source is not None else str(f.line)
    data = "\0".join((f.code, f.path, text.strip())).encode("utf-8", "surrogateescape")
    return hashlib.sha256(data).hexdigest()[:32]


_RESULTS = "\x00results\x00"  # where the spooled results go in the document


class SarifReport(Report):
    """Each result is serialized as soon as its file is checked, into a temporary file (one line each);
    the rule table (which codes occur, each result's ``ruleIndex``) needs them all, so the document is
    written at the end: its head, then the spooled results, indented as ``json.dump(indent=2)`` does."""

    def __init__(self, out: TextIO, ctx) -> None:
        super().__init__(out, ctx)
        self._spool = Spool()
        self._encode = json.JSONEncoder(ensure_ascii=False).encode
        self.artifacts: list[dict] = []
        self._artifact_index: dict[str, int] = {}
        self.notifications: list[dict] = []

    def write_file(self, r: FileResult) -> None:
        uri, base = artifact_uri(r.path)
        if r.error:
            self.notifications.append(
                {
                    "level": "error",
                    "message": {"text": clean(r.error)},
                    "locations": [{"physicalLocation": {"artifactLocation": _location(uri, base)}}],
                }
            )
            if not r.findings:
                return
        if r.path not in self._artifact_index:
            self._artifact_index[r.path] = len(self.artifacts)
            artifact: dict = {"location": _location(uri, base), "sourceLanguage": "gcode"}
            if r.dialect:
                artifact["properties"] = {
                    "dialect": r.dialect,
                    "readAs": r.read_as,
                    "dialectReason": clean(r.dialect_reason),
                    "lines": r.lines,
                    **_context_properties(r),
                }
            self.artifacts.append(artifact)
        for f in r.findings:
            region: dict = {"startLine": max(1, f.line), "startColumn": max(1, f.column)}
            if f.end_column is not None and f.end_column > f.column:
                region["endColumn"] = f.end_column
            snippet = source_line(f)
            if snippet is not None:
                region["snippet"] = {"text": snippet}
            location = _location(uri, base)
            location["index"] = self._artifact_index[r.path]
            result: dict = {
                "ruleId": f.code,
                "level": LEVELS[f.severity],
                "message": {"text": message(f)},
                "locations": [{"physicalLocation": {"artifactLocation": location, "region": region}}],
                "partialFingerprints": {"gclint/v1": _fingerprint(f)},
            }
            if f.fix is not None:
                result["properties"] = {"fix": f.fix.message, "fixApplicability": "safe" if f.fix.safe else "unsafe"}
            self._spool.write(self._encode(result) + "\n")

    def close(self) -> None:
        codes = sorted(self.tally.rows)
        docs = rule_docs(set(codes))
        rules = [_rule_descriptor(code, docs.get(code), self.tally.rows[code]["name"]) for code in codes]
        index = {code: i for i, code in enumerate(codes)}
        artifacts, notifications = self.artifacts, self.notifications
        invocation: dict = {"executionSuccessful": not notifications}
        if notifications:
            invocation["toolExecutionNotifications"] = notifications
        if self.ctx.configuration:
            invocation["toolConfigurationNotifications"] = [
                {"level": "warning", "message": {"text": clean(note)}, "descriptor": {"id": "gclint/configuration"}}
                for note in self.ctx.configuration
            ]
        run: dict = {
            "tool": {
                "driver": {
                    "name": "gclint",
                    "version": self.ctx.tool_version or "0",
                    "semanticVersion": self.ctx.tool_version or "0.0.0",
                    **({"informationUri": home} if (home := project_url("homepage", "repository", "source")) else {}),
                    "rules": rules,
                }
            },
            "invocations": [invocation],
            "artifacts": artifacts,
            "results": _RESULTS,
            "columnKind": "unicodeCodePoints",
        }
        if any(a["location"].get("uriBaseId") for a in artifacts):
            run["originalUriBaseIds"] = {"%SRCROOT%": {"description": {"text": "The folder gclint ran in."}}}
        document = json.dumps({"$schema": SCHEMA, "version": "2.1.0", "runs": [run]}, indent=2, ensure_ascii=False)
        head, tail = document.split(json.dumps(_RESULTS, ensure_ascii=False), 1)
        out = self.out
        out.write(head)
        if self._spool.empty:
            out.write("[]")
        else:
            out.write("[")
            separator = "\n"
            for line in self._spool.lines():
                data = json.loads(line)
                result = {"ruleId": data["ruleId"], "ruleIndex": index[data["ruleId"]], **data}
                text = json.dumps(result, indent=2, ensure_ascii=False).replace("\n", "\n        ")
                out.write(separator + "        " + text)
                separator = ",\n"
            out.write("\n      ]")
        out.write(tail)
        out.write("\n")
        self._spool.close()


def build(results: list[FileResult], ctx) -> dict:
    """The SARIF log as a dict (``write`` streams it)."""
    out = io.StringIO()
    SarifReport.write(results, out, ctx)
    return json.loads(out.getvalue())


def _location(uri: str, base: str | None) -> dict:
    out = {"uri": uri}
    if base:
        out["uriBaseId"] = base
    return out


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    SarifReport.write(results, out, ctx)


def _context_properties(r) -> dict:
    """How the file's dialect, Hyrel firmware version and printer model were decided (gclint.context)."""
    c = r.context
    if c is None:
        return {}
    out: dict = {"decidedBy": c.origin, "evidence": c.strength, "weakEvidence": c.weak}
    if c.conflict:
        out["conflict"] = clean(c.conflict)
    if c.firmware is not None:
        out["firmware"] = c.firmware
    if c.flavor is not None:
        out["flavor"] = c.flavor
    if c.printer is not None:
        out["printer"] = c.printer
        out["printerAssumed"] = c.printer_assumed  # nobody said: read from the job or the default
        out["printerFrom"] = c.printer_from
    return out
