"""``--format junit``: JUnit XML, as Jenkins, GitLab, Azure DevOps and most CI servers read test results.

One ``<testsuite>`` per file; each finding is a ``<testcase>`` with a ``<failure>`` (type = the rule code,
message = the finding, text = the location and the line with secrets masked); a clean file is one
passing test case; a file that could not be read is a test case with an ``<error>``.  ElementTree
escapes ``& < > "``; characters XML 1.0 cannot carry at all (controls, undecodable bytes) are shown as
``\\xNN`` first.
"""

from __future__ import annotations

import socket
import xml.etree.ElementTree as ET
from datetime import UTC, datetime
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import message, printable, source_line


def build(results: list[FileResult], ctx) -> ET.Element:
    timestamp = datetime.now(UTC).replace(microsecond=0).strftime("%Y-%m-%dT%H:%M:%S")
    hostname = printable(socket.gethostname() or "localhost")
    suites = ET.Element("testsuites", name="gclint")
    total_tests = total_failures = total_errors = 0
    for index, r in enumerate(results):
        path = printable(r.path)
        suite = ET.SubElement(
            suites, "testsuite", name=path, id=str(index), hostname=hostname, timestamp=timestamp, time="0", skipped="0"
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
                    ET.SubElement(
                        props, "property", name="printer_assumed", value=str(r.context.printer_assumed).lower()
                    )
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
        total_tests += tests
        total_failures += failures
        total_errors += errors
    suites.set("tests", str(total_tests))
    suites.set("failures", str(total_failures))
    suites.set("errors", str(total_errors))
    suites.set("time", "0")
    return suites


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    root = build(results, ctx)
    ET.indent(root)
    out.write('<?xml version="1.0" encoding="UTF-8"?>\n')
    out.write(ET.tostring(root, encoding="unicode"))
    out.write("\n")
