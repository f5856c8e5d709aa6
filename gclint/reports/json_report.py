"""``--format json``: one JSON array of findings (path, line, column, code, severity, message, fix...)."""

from __future__ import annotations

import json
from typing import TextIO

from gclint.engine import FileResult


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    findings = [f.to_dict() for r in results for f in r.findings]
    json.dump(findings, out, indent=2, ensure_ascii=False)
    out.write("\n")
