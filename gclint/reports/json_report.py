"""``--format json``: one JSON array of findings (path, line, column, code, severity, message, fix...).

One finding per line: readable, and written by the C encoder (``indent`` would select the slow pure
Python one, which took most of the time of a cached re-run over the corpus).
"""

from __future__ import annotations

import json
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import json_safe, mask


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    encode = json.JSONEncoder(ensure_ascii=False).encode
    findings = [json_safe(encode(_masked(f.to_dict()))) for r in results for f in r.findings]
    if not findings:
        out.write("[]\n")
        return
    out.write("[\n  ")
    out.write(",\n  ".join(findings))
    out.write("\n]\n")


def write_statistics(results: list[FileResult], out: TextIO, ctx) -> None:
    """``--statistics --format json``: one JSON array of per-code counts (as ruff)."""
    from gclint.reports.text import statistics

    json.dump(statistics(results), out, ensure_ascii=False, indent=2)
    out.write("\n")


def _masked(data: dict) -> dict:
    data["message"] = mask(data["message"])  # messages may quote file text
    return data
