"""The default report: one line per finding, ``path:line:col: CODE message``."""

from __future__ import annotations

from collections import Counter
from typing import TextIO

from gclint.engine import FileResult


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    total = Counter()
    fixable = 0
    files_with = 0
    for result in results:
        if result.findings:
            files_with += 1
        for f in result.findings:
            mark = " [*]" if (f.fix is not None and f.fix.safe and ctx.show_fixes) else ""
            out.write(f"{f.path}:{f.line}:{f.column}: {f.code}{mark} {f.message}\n")
            total[f.severity.label] += 1
            if mark:
                fixable += 1
    if ctx.statistics:
        write_statistics(results, out)
    n = sum(total.values())
    if n:
        parts = [f"{total[k]} {k}{'s' if total[k] != 1 else ''}" for k in ("error", "warning", "info") if total[k]]
        out.write(f"Found {n} finding{'s' if n != 1 else ''} ({', '.join(parts)}) in {files_with} file{'s' if files_with != 1 else ''}.\n")
        if fixable:
            out.write(f"[*] {fixable} fixable with --fix.\n")
    elif any(r.error is None for r in results):
        out.write("All checks passed.\n")


def write_statistics(results: list[FileResult], out: TextIO) -> None:
    """Counts per code, most frequent first, like ``ruff --statistics``."""
    counts: Counter = Counter()
    names: dict[str, tuple[str, str]] = {}
    first: dict[str, str] = {}
    for result in results:
        for f in result.findings:
            counts[f.code] += 1
            names[f.code] = (f.name, f.severity.label)
            first.setdefault(f.code, f"{f.path}:{f.line}")
    for code, n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])):
        name, severity = names[code]
        out.write(f"{n:>7}  {code}  {name:<32} [{severity}]  first at {first[code]}\n")
