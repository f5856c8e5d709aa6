"""The default report: one line per finding, ``path:line:col: CODE message``."""

from __future__ import annotations

from collections import Counter
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import human, message


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    for result in results:
        path = human(result.path)
        for f in result.findings:
            out.write(f"{path}:{f.line}:{f.column}: {f.code}{_mark(f, ctx)} {message(f)}\n")
    write_summary(results, out, ctx)


def _mark(f, ctx) -> str:
    return " [*]" if (f.fix is not None and f.fix.safe and ctx.show_fixes) else ""


def write_summary(results: list[FileResult], out: TextIO, ctx) -> None:
    """Statistics (with --statistics), then the totals line shared by the text formats."""
    total = Counter()
    fixable = 0
    files_with = 0
    for result in results:
        if result.findings:
            files_with += 1
        for f in result.findings:
            total[f.severity.label] += 1
            if _mark(f, ctx):
                fixable += 1
    if ctx.statistics:
        write_statistics(results, out)
        for note in ctx.suppressions:
            out.write(f"{'-':>7}  {human(note)}\n")
    n = sum(total.values())
    if n:
        parts = [f"{total[k]} {k}{'s' if total[k] != 1 else ''}" for k in ("error", "warning", "info") if total[k]]
        out.write(
            f"Found {n} finding{'s' if n != 1 else ''} ({', '.join(parts)}) in {files_with} file{'s' if files_with != 1 else ''}.\n"
        )
        if fixable:
            out.write(f"[*] {fixable} fixable with --fix.\n")
    elif any(r.error is not None for r in results):
        # never "All checks passed" when something was not checked (an unreadable file or folder)
        unread = sum(1 for r in results if r.error is not None)
        checked = len(results) - unread
        out.write(
            f"No findings in the {checked} file{'s' if checked != 1 else ''} checked; {unread} "
            f"{'paths' if unread != 1 else 'path'} could not be checked (see above).\n"
        )
    elif results:
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
            first.setdefault(f.code, f"{human(f.path)}:{f.line}")
    for code, n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])):
        name, severity = names[code]
        out.write(f"{n:>7}  {code}  {name:<32} [{severity}]  first at {first[code]}\n")


def write_full(results: list[FileResult], out: TextIO, ctx) -> None:
    """``--format full``: each finding with its source line and a caret under the columns it covers."""
    from gclint.reports.common import source_line

    for result in results:
        path = human(result.path)
        for f in result.findings:
            out.write(f"{path}:{f.line}:{f.column}: {f.code}{_mark(f, ctx)} {message(f)}\n")
            line = source_line(f)
            if line is not None:
                gutter = " " * len(str(f.line))
                shown = line.expandtabs(4)
                start = len(line[: max(0, f.column - 1)].expandtabs(4))
                end_column = f.end_column if f.end_column is not None and f.end_column > f.column else f.column + 1
                width = max(1, len(line[: end_column - 1].expandtabs(4)) - start)
                out.write(f" {gutter} |\n {f.line} | {shown}\n {gutter} | {' ' * start}{'^' * width}\n")
            if f.fix is not None and ctx.show_fixes:
                fix = human(f.fix.message)
                out.write(f" {' ' * len(str(f.line))} = fix{'' if f.fix.safe else ' (unsafe)'}: {fix}\n")
            out.write("\n")
    write_summary(results, out, ctx)


def write_grouped(results: list[FileResult], out: TextIO, ctx) -> None:
    """``--format grouped``: findings under their file's name, like ``ruff --output-format grouped``."""
    for result in results:
        if not result.findings:
            continue
        out.write(f"{human(result.path)}:\n")
        width = max(len(f"{f.line}:{f.column}") for f in result.findings)
        for f in result.findings:
            where = f"{f.line}:{f.column}"
            out.write(f"  {where:<{width}} {f.code}{_mark(f, ctx)} {message(f)}\n")
        out.write("\n")
    write_summary(results, out, ctx)
