"""The default report: one line per finding, ``path:line:col: CODE message``."""

from __future__ import annotations

from collections import Counter
from dataclasses import replace
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import Elided, grouped, human, message


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    for result in results:
        path = human(result.path)
        for f in grouped(result.findings, ctx.group):
            if isinstance(f, Elided):
                out.write(f"{path}: {f}\n")
                continue
            out.write(f"{path}:{f.line}:{f.column}: {f.code}{_mark(f, ctx)} {message(f)}\n")
    write_summary(results, out, ctx)


def _mark(f, ctx) -> str:
    """`` [error]`` and, for a safe fix, `` [*]``: what follows the code in the human formats."""
    fixable = " [*]" if (f.fix is not None and f.fix.safe and ctx.show_fixes) else ""
    return f" [{f.severity.label}]{fixable}"


def _fixable(f, ctx) -> bool:
    return f.fix is not None and f.fix.safe and ctx.show_fixes


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
            if _fixable(f, ctx):
                fixable += 1
    if ctx.statistics:
        write_statistics(results, out)
        for note in ctx.suppressions:
            out.write(f"{'-':>7}  {human(note)}\n")
    n = sum(total.values())
    parts = [f"{total[k]} {k}{'s' if total[k] != 1 else ''}" for k in ("error", "warning", "info") if total[k]]
    files = f" in {files_with} file{'s' if files_with != 1 else ''}" if n else ""
    if ctx.fixed is not None and (ctx.fixed or n):  # --fix: ruff's "Found 3 errors (2 fixed, 1 remaining)."
        found = n + ctx.fixed
        # the file count is of the remaining findings (the fixed ones may be in other files)
        remaining = f"{n} remaining: {', '.join(parts)}{files}" if n else "0 remaining"
        out.write(f"Found {found} finding{'s' if found != 1 else ''} ({ctx.fixed} fixed, {remaining}).\n")
    elif n:
        out.write(f"Found {n} finding{'s' if n != 1 else ''} ({', '.join(parts)}){files}.\n")
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
    if n and fixable and ctx.fixed is None:
        out.write(f"[*] {fixable} fixable with --fix.\n")
    checked_as = read_as_line(results)
    if checked_as:
        out.write(checked_as + "\n")


def read_as_line(results: list[FileResult]) -> str:
    """``Checked as hyrel v5, printer 30m (assumed).`` or, for a mix, each label with its file count."""
    labels = Counter(r.read_as for r in results if r.error is None and r.read_as)
    if not labels:
        return ""
    if len(labels) == 1:
        return f"Checked as {next(iter(labels))}."
    parts = [f"{label} ({n} file{'s' if n != 1 else ''})" for label, n in labels.most_common()]
    return "Checked as: " + "; ".join(parts) + "."


def statistics(results: list[FileResult]) -> list[dict]:
    """Counts per code, most frequent first (``ruff --statistics``): code, name, severity, count,
    fixable (how many have a safe fix), first (where the first one is)."""
    rows: dict[str, dict] = {}
    for result in results:
        for f in result.findings:
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
            if f.fix is not None and f.fix.safe:
                row["fixable"] += 1
    return sorted(rows.values(), key=lambda r: (-r["count"], r["code"]))


def write_statistics(results: list[FileResult], out: TextIO) -> None:
    """The statistics table (``--statistics``), ``[*]`` on codes with safe fixes."""
    rows = statistics(results)
    name_width = max((len(row["name"]) for row in rows), default=0)
    for row in rows:
        mark = " [*]" if row["fixable"] else ""
        level = f"[{row['severity']}]"
        out.write(
            f"{row['count']:>7}  {row['code']}{mark:<4} {row['name']:<{name_width}}  {level:<9}  "
            f"first at {human(row['first'])}\n"
        )


def write_statistics_report(results: list[FileResult], out: TextIO, ctx) -> None:
    """``--statistics`` in the human formats: the table and the totals, not every finding."""
    write_summary(results, out, replace(ctx, statistics=True))


def write_full(results: list[FileResult], out: TextIO, ctx) -> None:
    """``--format full``: each finding with its source line and a caret under the columns it covers."""
    from gclint.reports.common import source_line

    for result in results:
        path = human(result.path)
        for f in grouped(result.findings, ctx.group):
            if isinstance(f, Elided):
                out.write(f"{path}: {f}\n\n")
                continue
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
        for f in grouped(result.findings, ctx.group):
            if isinstance(f, Elided):
                out.write(f"  {'':<{width}} {f}\n")
                continue
            where = f"{f.line}:{f.column}"
            out.write(f"  {where:<{width}} {f.code}{_mark(f, ctx)} {message(f)}\n")
        out.write("\n")
    write_summary(results, out, ctx)
