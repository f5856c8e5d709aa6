"""``--format json``: one JSON array of findings (path, line, column, code, severity, message, fix...).

One finding per line: readable, and written by the C encoder (``indent`` would select the slow pure
Python one, which took most of the time of a cached re-run over the corpus).
"""

from __future__ import annotations

import json
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import json_safe, mask
from gclint.reports.stream import Report


class JsonReport(Report):
    """The array is written element by element, as each file is checked."""

    def __init__(self, out: TextIO, ctx) -> None:
        super().__init__(out, ctx)
        self._encode = json.JSONEncoder(ensure_ascii=False).encode
        self._started = False

    def write_file(self, r: FileResult) -> None:
        encode, out = self._encode, self.out
        for f in r.findings:
            out.write(",\n  " if self._started else "[\n  ")
            self._started = True
            out.write(json_safe(encode(_masked(f.to_dict()))))

    def close(self) -> None:
        self.out.write("\n]\n" if self._started else "[]\n")


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    JsonReport.write(results, out, ctx)


class JsonStatisticsReport(Report):
    """``--statistics --format json``: one JSON array of per-code counts (as ruff)."""

    def close(self) -> None:
        json.dump(self.tally.statistics(), self.out, ensure_ascii=False, indent=2)
        self.out.write("\n")


def write_statistics(results: list[FileResult], out: TextIO, ctx) -> None:
    JsonStatisticsReport.write(results, out, ctx)


def _masked(data: dict) -> dict:
    data["message"] = mask(data["message"])  # messages may quote file text
    return data
