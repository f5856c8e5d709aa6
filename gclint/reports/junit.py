"""``--format junit``: JUnit XML, as Jenkins, GitLab, Azure DevOps and most CI servers read test results.

One ``<testsuite>`` per file; each finding is a ``<testcase>`` with a ``<failure>`` (type = the rule code,
message = the finding, text = the location and the line with secrets masked); a clean file is one
passing test case; a file that could not be read is a test case with an ``<error>``.  What the
configuration switches off or excludes comes first, as the properties of a suite of its own (``gclint
configuration``).  ElementTree escapes ``& < > "``; characters XML 1.0 cannot carry at all (controls,
undecodable bytes) and the invisible format characters (U+202E) are shown as ``\\xNN``/``\\uNNNN`` first.
"""

from __future__ import annotations

import socket
import xml.etree.ElementTree as ET
from datetime import UTC, datetime
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import message, printable, source_line
from gclint.reports.stream import Report, Spool


def _suite(index: int, r: FileResult, timestamp: str, hostname: str) -> tuple[ET.Element, int, int, int]:
    """One file's ``<testsuite>`` and its numbers of tests, failures and errors."""
    path = printable(r.path)
    suite = ET.Element(
        "testsuite", name=path, id=str(index), hostname=hostname, timestamp=timestamp, time="0", skipped="0"
    )
    tests = failures = errors = 0
    if r.dialect:
        props = ET.SubElement(suite, "properties")
        ET.SubElement(props, "property", name="dialect", value=r.dialect)
        ET.SubElement(props, "property", name="read_as", value=printable(r.read_as))
        ET.SubElement(props, "property", name="dialect_reason", value=printable(r.dialect_reason))
        if r.context is not None:
            ET.SubElement(props, "property", name="evidence", value=r.context.strength)
            if r.context.printer is not None:
                ET.SubElement(props, "property", name="printer_assumed", value=str(r.context.printer_assumed).lower())
                ET.SubElement(props, "property", name="printer_from", value=r.context.printer_from)
        ET.SubElement(props, "property", name="lines", value=str(r.lines))
    if r.error:
        case = ET.SubElement(suite, "testcase", name="read", classname=path, file=path, time="0")
        error = ET.SubElement(case, "error", type="read-error", message=printable(r.error))
        error.text = printable(r.error)
        tests, errors = 1, 1
    elif not r.findings:
        ET.SubElement(suite, "testcase", name="gclint", classname=path, file=path, time="0")
        tests = 1
    for f in r.findings:
        text = message(f)
        case = ET.SubElement(
            suite,
            "testcase",
            name=f"{f.code} at line {f.line}, column {f.column}",
            classname=path,
            file=path,
            line=str(f.line),
            time="0",
        )
        failure = ET.SubElement(case, "failure", type=f.code, message=text)
        body = [f"{path}:{f.line}:{f.column}: {f.code} [{f.severity.label}] {text}"]
        line = source_line(f)
        if line is not None:
            body.append(f"{f.line:>6} | {line}")
        if f.fix is not None:
            body.append(f"fix ({'safe' if f.fix.safe else 'unsafe'}): {printable(f.fix.message)}")
        failure.text = "\n".join(body)
        tests += 1
        failures += 1
    suite.set("tests", str(tests))
    suite.set("failures", str(failures))
    suite.set("errors", str(errors))
    return suite, tests, failures, errors


def _configuration_suite(notes: list[str], timestamp: str, hostname: str) -> ET.Element:
    """What the configuration switches off or excludes: a property each, and one passing test case whose
    output lists them (CI servers that show no properties show that)."""
    suite = ET.Element(
        "testsuite", name="gclint configuration", id="configuration", hostname=hostname, timestamp=timestamp
    )
    suite.set("time", "0")
    suite.set("skipped", "0")
    props = ET.SubElement(suite, "properties")
    for note in notes:
        ET.SubElement(props, "property", name="configuration", value=printable(note))
    case = ET.SubElement(suite, "testcase", name="configuration", classname="gclint", time="0")
    ET.SubElement(case, "system-out").text = "\n".join(printable(note) for note in notes)
    for key, value in (("tests", "1"), ("failures", "0"), ("errors", "0")):
        suite.set(key, value)
    return suite


def _stamp() -> tuple[str, str]:
    timestamp = datetime.now(UTC).replace(microsecond=0).strftime("%Y-%m-%dT%H:%M:%S")
    return timestamp, printable(socket.gethostname() or "localhost")


def build(results: list[FileResult], ctx) -> ET.Element:
    """The whole document as one tree (for tests and programs; ``write`` streams it)."""
    timestamp, hostname = _stamp()
    suites = ET.Element("testsuites", name="gclint")
    totals = [0, 0, 0]
    if ctx.configuration:
        suites.append(_configuration_suite(ctx.configuration, timestamp, hostname))
        totals[0] += 1
    for index, r in enumerate(results):
        suite, *numbers = _suite(index, r, timestamp, hostname)
        suites.append(suite)
        totals = [a + b for a, b in zip(totals, numbers, strict=True)]
    _set_totals(suites, *totals)
    return suites


def _set_totals(suites: ET.Element, tests: int, failures: int, errors: int) -> None:
    suites.set("tests", str(tests))
    suites.set("failures", str(failures))
    suites.set("errors", str(errors))
    suites.set("time", "0")


class JunitReport(Report):
    """Each file's ``<testsuite>`` is serialized as soon as it is checked, into a temporary file; the root
    element (whose attributes are the totals) is written at the end, around them."""

    def __init__(self, out: TextIO, ctx) -> None:
        super().__init__(out, ctx)
        self._stamp = _stamp()
        self._spool = Spool()
        self._index = 0
        self._totals = [0, 0, 0]
        if ctx.configuration:
            suite = _configuration_suite(ctx.configuration, *self._stamp)
            ET.indent(suite, level=1)
            self._spool.write("\n  " + ET.tostring(suite, encoding="unicode"))
            self._totals[0] += 1

    def write_file(self, r: FileResult) -> None:
        suite, *numbers = _suite(self._index, r, *self._stamp)
        self._index += 1
        self._totals = [a + b for a, b in zip(self._totals, numbers, strict=True)]
        ET.indent(suite, level=1)
        self._spool.write("\n  " + ET.tostring(suite, encoding="unicode"))

    def close(self) -> None:
        out = self.out
        root = ET.Element("testsuites", name="gclint")
        _set_totals(root, *self._totals)
        out.write('<?xml version="1.0" encoding="UTF-8"?>\n')
        if self._spool.empty:
            out.write(ET.tostring(root, encoding="unicode"))
        else:
            head = ET.tostring(root, encoding="unicode")
            out.write(head[: -len(" />")] + ">")
            self._spool.copy_to(out)
            out.write("\n</testsuites>")
        out.write("\n")
        self._spool.close()


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    JunitReport.write(results, out, ctx)
