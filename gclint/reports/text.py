"""The default report: one line per finding, ``path:line:col: CODE message``."""

from __future__ import annotations

from dataclasses import replace
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import Elided, grouped, human, message
from gclint.reports.stream import Report, Tally
from gclint.textsafe import human_path


class TextReport(Report):
    """``--format text`` (and ``concise``): one line per finding, then the totals."""

    def write_file(self, result: FileResult) -> None:
        out, ctx = self.out, self.ctx
        path = human_path(result.path)
        for f in grouped(result.findings, ctx.group):
            if isinstance(f, Elided):
                out.write(f"{path}: {f}\n")
                continue
            out.write(f"{path}:{f.line}:{f.column}: {f.code}{_mark(f, ctx)} {message(f)}\n")

    def close(self) -> None:
        write_summary(self.tally, self.out, self.ctx)


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    TextReport.write(results, out, ctx)


def _mark(f, ctx) -> str:
    """`` [error]`` and, for a safe fix, `` [*]``: what follows the code in the human formats."""
    fixable = " [*]" if (f.fix is not None and f.fix.safe and ctx.show_fixes) else ""
    return f" [{f.severity.label}]{fixable}"


def write_summary(results: list[FileResult] | Tally, out: TextIO, ctx) -> None:
    """Statistics (with --statistics), then the totals line shared by the text formats."""
    tally = results if isinstance(results, Tally) else Tally.of(results)
    total = tally.severity
    fixable = tally.fixable if ctx.show_fixes else 0
    files_with = tally.files_with
    if ctx.statistics:
        write_statistics(tally, out)
    n = tally.total
    parts = [f"{total[k]} {k}{'s' if total[k] != 1 else ''}" for k in ("error", "warning", "info") if total[k]]
    files = f" in {files_with} file{'s' if files_with != 1 else ''}" if n else ""
    if ctx.fixed is not None and (ctx.fixed or n):  # --fix: ruff's "Found 3 errors (2 fixed, 1 remaining)."
        found = max(ctx.found or 0, n + ctx.fixed)
        # the file count is of the remaining findings (the fixed ones may be in other files)
        remaining = f"{n} remaining: {', '.join(parts)}{files}" if n else "0 remaining"
        gone = found - n - ctx.fixed  # findings that ended with a fix made elsewhere (a head renumbered)
        also = f", {gone} more ended by those fixes" if gone else ""
        out.write(f"Found {found} finding{'s' if found != 1 else ''} ({ctx.fixed} fixed{also}, {remaining}).\n")
    elif n:
        out.write(f"Found {n} finding{'s' if n != 1 else ''} ({', '.join(parts)}){files}.\n")
    elif tally.unread:
        # never "All checks passed" when something was not checked (an unreadable file or folder)
        unread = tally.unread
        checked = tally.files - unread
        out.write(
            f"No findings in the {checked} file{'s' if checked != 1 else ''} checked; {unread} "
            f"{'paths' if unread != 1 else 'path'} could not be checked (see above).\n"
        )
    elif tally.files:
        out.write("All checks passed.\n")
    if n and fixable and ctx.fixed is None:
        out.write(f"[*] {fixable} fixable with --fix.\n")
    checked_as = read_as_line(tally)
    if checked_as:
        out.write(checked_as + "\n")
    for note in ctx.configuration:  # (never left out: -q drops notes on stderr, not these)
        out.write(f"Configuration: {human(note)}\n")


def read_as_line(results: list[FileResult] | Tally) -> str:
    """``Checked as hyrel v5, printer 30m (assumed).`` or, for a mix, each label with its file count."""
    labels = results.labels if isinstance(results, Tally) else Tally.of(results).labels
    if not labels:
        return ""
    if len(labels) == 1:
        return f"Checked as {next(iter(labels))}."
    parts = [f"{label} ({n} file{'s' if n != 1 else ''})" for label, n in labels.most_common()]
    return "Checked as: " + "; ".join(parts) + "."


def statistics(results: list[FileResult] | Tally) -> list[dict]:
    """Counts per code, most frequent first (``ruff --statistics``): code, name, severity, count,
    fixable (how many have a safe fix), first (where the first one is)."""
    return (results if isinstance(results, Tally) else Tally.of(results)).statistics()


def write_statistics(results: list[FileResult] | Tally, out: TextIO) -> None:
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


class StatisticsReport(Report):
    """``--statistics`` in the human formats: the table and the totals, not every finding."""

    def close(self) -> None:
        write_summary(self.tally, self.out, replace(self.ctx, statistics=True))


def write_statistics_report(results: list[FileResult], out: TextIO, ctx) -> None:
    StatisticsReport.write(results, out, ctx)


class FullReport(Report):
    """``--format full``: each finding with its source line and a caret under the columns it covers."""

    def write_file(self, result: FileResult) -> None:
        from gclint.reports.common import source_line

        out, ctx = self.out, self.ctx
        path = human_path(result.path)
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

    def close(self) -> None:
        write_summary(self.tally, self.out, self.ctx)


def write_full(results: list[FileResult], out: TextIO, ctx) -> None:
    FullReport.write(results, out, ctx)


class GroupedReport(Report):
    """``--format grouped``: findings under their file's name, like ``ruff --output-format grouped``."""

    def write_file(self, result: FileResult) -> None:
        if not result.findings:
            return
        out, ctx = self.out, self.ctx
        out.write(f"{human_path(result.path)}:\n")
        width = max(len(f"{f.line}:{f.column}") for f in result.findings)
        for f in grouped(result.findings, ctx.group):
            if isinstance(f, Elided):
                out.write(f"  {'':<{width}} {f}\n")
                continue
            where = f"{f.line}:{f.column}"
            out.write(f"  {where:<{width}} {f.code}{_mark(f, ctx)} {message(f)}\n")
        out.write("\n")

    def close(self) -> None:
        write_summary(self.tally, self.out, self.ctx)


def write_grouped(results: list[FileResult], out: TextIO, ctx) -> None:
    GroupedReport.write(results, out, ctx)
