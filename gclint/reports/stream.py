"""Reports written file by file, so that a run's memory does not grow with its number of files.

``gclint check`` hands each file's result to a ``Report`` as soon as it is checked (``add``) and drops its
findings; what the end of a report needs (totals per severity, counts per code for ``--statistics``, the
exit code, what the files were read as) is kept in a ``Tally``, a few numbers per code and per file.
Formats that can be written in order write each file's part at once (text, github, JSON as an array
written element by element); formats whose head needs the totals (JUnit's ``tests=``, SARIF's rule table,
the HTML page's totals) spool the per-file parts to a temporary file and write the head, then the parts,
at the end.  Every format's ``write(results, out, ctx)`` is the same ``Report`` fed a list.
"""

from __future__ import annotations

import shutil
import tempfile
from collections import Counter
from typing import TextIO

from gclint.engine import FileResult
from gclint.rules.base import Severity


class Tally:
    """Counts over every finding of a run (exact: nothing here is capped)."""

    def __init__(self) -> None:
        self.files = 0  # results added (checked files and paths that could not be checked)
        self.unread = 0  # of those, the ones with an error
        self.files_with = 0  # files with at least one finding
        self.severity: Counter = Counter()  # label -> findings
        self.fixable = 0  # findings with a safe fix
        self.worst: Severity | None = None
        self.rows: dict[str, dict] = {}  # code -> statistics row (see ``statistics``)
        self.code_files: Counter = Counter()  # code -> files with a finding of it
        self.labels: Counter = Counter()  # what files were checked as -> files

    def add(self, result: FileResult) -> None:
        self.files += 1
        if result.error is not None:
            self.unread += 1
        elif result.read_as:
            self.labels[result.read_as] += 1
        if result.findings:
            self.files_with += 1
        rows = self.rows
        codes: set[str] = set()
        for f in result.findings:
            self.severity[f.severity.label] += 1
            safe = f.fix is not None and f.fix.safe
            if safe:
                self.fixable += 1
            if self.worst is None or f.severity > self.worst:
                self.worst = f.severity
            row = rows.get(f.code)
            if row is None:
                row = rows[f.code] = {
                    "code": f.code,
                    "name": f.name,
                    "severity": f.severity.label,
                    "count": 0,
                    "fixable": 0,
                    "first": f"{f.path}:{f.line}",
                }
            row["count"] += 1
            if safe:
                row["fixable"] += 1
            codes.add(f.code)
        for code in codes:
            self.code_files[code] += 1

    @classmethod
    def of(cls, results: list[FileResult]) -> Tally:
        tally = cls()
        for r in results:
            tally.add(r)
        return tally

    @property
    def total(self) -> int:
        return sum(self.severity.values())

    def totals(self) -> dict[str, int]:
        return {k: self.severity[k] for k in ("error", "warning", "info")}

    def statistics(self) -> list[dict]:
        """Counts per code, most frequent first (``ruff --statistics``)."""
        return sorted((dict(r) for r in self.rows.values()), key=lambda r: (-r["count"], r["code"]))


class Report:
    """A report written file by file: ``add`` each result in order, then ``close``."""

    def __init__(self, out: TextIO, ctx) -> None:
        self.out = out
        self.ctx = ctx
        self.tally = Tally()

    def add(self, result: FileResult) -> None:
        self.tally.add(result)
        self.write_file(result)

    def write_file(self, result: FileResult) -> None:  # the file's part of the report
        pass

    def close(self) -> None:  # what ends the report
        pass

    @classmethod
    def write(cls, results: list[FileResult], out: TextIO, ctx) -> None:
        report = cls(out, ctx)
        for r in results:
            report.add(r)
        report.close()


class Spool:
    """Text kept in a temporary file (not in memory) until it is copied out."""

    def __init__(self) -> None:
        self._file = tempfile.TemporaryFile("w+", encoding="utf-8", errors="surrogatepass", newline="")  # noqa: SIM115
        self.empty = True

    def write(self, text: str) -> None:
        if text:
            self.empty = False
            self._file.write(text)

    def lines(self):
        self._file.flush()
        self._file.seek(0)
        yield from self._file

    def copy_to(self, out: TextIO) -> None:
        self._file.flush()
        self._file.seek(0)
        shutil.copyfileobj(self._file, out, 1 << 16)

    def close(self) -> None:
        self._file.close()
