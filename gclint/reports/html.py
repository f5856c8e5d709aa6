"""``--format html``: one self-contained page (no external files, no network) from a jinja2 template.

For each file: a summary (dialect and why, lines, counts), the findings with their source lines (secrets
masked), and an inline SVG plot of the XY toolpath per head with the flagged lines marked.  A page is for
people: file text on it is shown as on a terminal (``human``: secrets masked, control and invisible format
characters escaped).  The
template is rendered with autoescaping on, so file text is always text, never markup; the page's only
script carries a per-report nonce that its Content-Security-Policy requires.
"""

from __future__ import annotations

import io
import math
import secrets as _random
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import TextIO

from markupsafe import Markup

from gclint.engine import FileResult
from gclint.reports.common import human, message, rule_docs, source_line
from gclint.reports.stream import Report, Spool
from gclint.reports.toolpath import Toolpath, read_toolpath
from gclint.textsafe import human_path

PLOT_WIDTH = 640
PLOT_HEIGHT = 480
PLOT_MARGIN = 12
PALETTE = ("#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#bcbd22", "#7f7f7f", "#e377c2", "#ff7f0e")
SEVERITY_COLORS = {"error": "#d62728", "warning": "#e6a700", "info": "#4a90d9"}


@dataclass
class PlotHead:
    label: str
    color: str
    work: str  # SVG path data of the working (printing, cutting) strokes
    travel: str  # SVG path data of the travel moves
    moves: int
    working_moves: int
    stride: int


@dataclass
class PlotMarker:
    x: float
    y: float
    line: int
    severity: str
    title: str


@dataclass
class Plot:
    width: int
    height: int
    heads: list[PlotHead] = field(default_factory=list)
    markers: list[PlotMarker] = field(default_factory=list)
    note: str = ""
    bounds: tuple[float, float, float, float] | None = None


def build_plot(toolpath: Toolpath, result: FileResult) -> Plot | None:
    """Scale the toolpath into the plot box (Y up, aspect kept) as SVG path data per head."""
    bounds = toolpath.bounds()
    if bounds is None:
        return None
    min_x, min_y, max_x, max_y = bounds
    span_x = max(max_x - min_x, 1e-9)
    span_y = max(max_y - min_y, 1e-9)
    if not all(math.isfinite(v) for v in (*bounds, span_x, span_y)):
        return None  # coordinates beyond what a float can scale (X999...9): no plot, the findings still show
    inner_w, inner_h = PLOT_WIDTH - 2 * PLOT_MARGIN, PLOT_HEIGHT - 2 * PLOT_MARGIN
    scale = min(inner_w / span_x, inner_h / span_y)
    if max_x == min_x and max_y == min_y:
        scale = 1.0
    width = int(round(span_x * scale)) + 2 * PLOT_MARGIN
    height = int(round(span_y * scale)) + 2 * PLOT_MARGIN

    def sx(x: float) -> float:
        return round(PLOT_MARGIN + (x - min_x) * scale, 1)

    def sy(y: float) -> float:
        return round(PLOT_MARGIN + (max_y - y) * scale, 1)

    plot = Plot(width=max(width, 2 * PLOT_MARGIN + 1), height=max(height, 2 * PLOT_MARGIN + 1), bounds=bounds)
    for i, head in enumerate(toolpath.heads.values()):
        work: list[str] = []
        travel: list[str] = []
        previous: tuple[float, float] | None = None
        for x, y, working in head.points:
            point = (sx(x), sy(y))
            if previous is not None and point != previous:
                segment = f"M{previous[0]} {previous[1]}L{point[0]} {point[1]}"
                (work if working else travel).append(segment)
            previous = point
        plot.heads.append(
            PlotHead(
                label=head.label,
                color=PALETTE[i % len(PALETTE)],
                work=_join(work),
                travel=_join(travel),
                moves=head.moves,
                working_moves=head.working_moves,
                stride=head.stride,
            )
        )
    by_line: dict[int, list] = {}
    for f in result.findings:
        by_line.setdefault(f.line, []).append(f)
    for m in toolpath.markers:
        found = by_line.get(m.line, [])
        if not found:
            continue
        worst = max(found, key=lambda f: f.severity)
        title = f"line {m.line}: " + "; ".join(f"{f.code} {message(f)}" for f in found)
        plot.markers.append(PlotMarker(sx(m.x), sy(m.y), m.line, worst.severity.label, title))
    notes = []
    if toolpath.sampled:
        strides = sorted({h.stride for h in toolpath.heads.values()})
        notes.append(f"big job: one move in {strides[-1]} is drawn")
    notes.append("arcs are drawn as chords")
    plot.note = "; ".join(notes)
    return plot


def _join(segments: list[str]) -> str:
    # Consecutive segments that continue each other share their point: "M a L b" + "M b L c" -> "M a L b L c".
    out: list[str] = []
    last_end = None
    for seg in segments:
        start, end = seg[1:].split("L")
        if start == last_end:
            out.append("L" + end)
        else:
            out.append(seg)
        last_end = end
    return "".join(out)


@dataclass
class FileView:
    path: str
    anchor: str
    result: FileResult
    counts: dict[str, int]
    findings: list[dict]
    plot: Plot | None
    plot_error: str | None
    dialect_reason: str
    read_as: str
    weak: bool
    error: str | None = None  # why the file could not be checked
    omitted: int = 0  # findings not listed on the page (see HTML_FINDINGS)
    summary: list[str] = field(default_factory=list)  # the job summary (gclint summary), one fact a line


# Findings listed per file, and in all: a page that a browser can open, and memory that stays bounded (the
# machine formats list them all).
HTML_FINDINGS = 2000
HTML_TOTAL_FINDINGS = 20_000


def _file_view(index: int, result: FileResult, plot_budget: int, limit: int = HTML_FINDINGS) -> FileView:
    findings = []
    for f in result.findings[: max(0, limit)]:
        line = source_line(f)
        start = max(0, f.column - 1)
        end = f.end_column - 1 if f.end_column is not None and f.end_column > f.column else start + 1
        findings.append(
            {
                "line": f.line,
                "column": f.column,
                "code": f.code,
                "name": f.name,
                "severity": f.severity.label,
                "message": message(f),
                "fix": human(f.fix.message) if f.fix is not None else None,
                "fix_safe": f.fix.safe if f.fix is not None else None,
                # the line in three parts so the template can highlight the columns the finding covers
                "before": line[:start] if line is not None else None,
                "focus": line[start:end] if line is not None else None,
                "after": line[end:] if line is not None else None,
            }
        )
    plot = None
    plot_error = None
    if result.error is None:
        toolpath = read_toolpath(result.path, result.dialect, {f.line for f in result.findings}, budget=plot_budget)
        plot_error = human(toolpath.error) if toolpath.error else None
        plot = build_plot(toolpath, result) if toolpath.error is None else None
        if plot is None and plot_error is None:
            plot_error = "no XY moves in this file"
    return FileView(
        path=human_path(result.path),
        anchor=f"file-{index}",
        result=result,
        counts=result.counts(),
        findings=findings,
        plot=plot,
        plot_error=plot_error,
        dialect_reason=human(result.dialect_reason),
        read_as=human(result.read_as),
        error=human(result.error) if result.error is not None else None,
        weak=result.context is not None and result.context.weak,
        omitted=len(result.findings) - len(findings),
        summary=_summary(result),
    )


def _summary(result: FileResult) -> list[str]:
    """The job summary beside the toolpath (the file read once more, in the context it was checked in)."""
    if result.error is not None or result.context is None or result.path == "-":
        return []
    from gclint.summary import render as render_summary
    from gclint.summary import summarize
    from gclint.syntax.source import Source, SourceError

    try:
        source = Source.open(result.path, cut_long_lines=True)
        facts = render_summary(summarize(source, result.context)).splitlines()[1:]
    except (OSError, SourceError, ValueError):
        return []
    return [human(line.strip()) for line in facts]


@dataclass
class NavItem:
    """What the page's head keeps of a file: its link and how many of its findings are listed."""

    anchor: str
    path: str
    listed: int


def _environment():
    from jinja2 import Environment, PackageLoader, StrictUndefined

    return Environment(
        loader=PackageLoader("gclint.reports", "templates"),
        autoescape=True,  # every file text is data, never markup (html, attributes, svg titles)
        undefined=StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )


class HtmlReport(Report):
    """Each file's section is rendered as soon as the file is checked, into a temporary file; the page
    (whose head holds the totals and a link to every file) is written at the end around the sections."""

    plot_budget = 6000

    def __init__(self, out: TextIO, ctx) -> None:
        super().__init__(out, ctx)
        self._env = _environment()
        self._section = self._env.get_template("file.html.j2")
        self._spool = Spool()
        self._nav: list[NavItem] = []
        self._listed = 0

    def write_file(self, r: FileResult) -> None:
        limit = min(HTML_FINDINGS, HTML_TOTAL_FINDINGS - self._listed)
        view = _file_view(len(self._nav), r, self.plot_budget, limit)
        self._listed += len(view.findings)
        self._nav.append(NavItem(view.anchor, view.path, len(view.findings)))
        self._spool.write(self._section.render(f=view, severity_colors=SEVERITY_COLORS) + "\n")

    def close(self) -> None:
        tally = self.tally
        docs = rule_docs(set(tally.rows))
        for code, doc in docs.items():
            doc = dict(doc)
            doc["count"] = tally.rows[code]["count"] if code in tally.rows else 0
            doc["files"] = tally.code_files[code]
            docs[code] = doc
        nonce = _random.token_urlsafe(16)
        marker = f"<!-- gclint sections {nonce} -->"
        page = self._env.get_template("report.html.j2").render(
            version=self.ctx.tool_version,
            generated=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
            files=self._nav,
            sections=Markup(marker),
            totals=tally.totals(),
            unreadable=tally.unread,
            configuration=[human(note) for note in self.ctx.configuration],
            rules=[docs[c] for c in sorted(docs)],
            nonce=nonce,
            severity_colors=SEVERITY_COLORS,
        )
        head, tail = page.split(marker, 1)
        tail = tail[1:] if tail.startswith("\n") else tail  # each section ends its own line
        self.out.write(head)
        self._spool.copy_to(self.out)
        self.out.write(tail)
        self._spool.close()


def render(results: list[FileResult], ctx, plot_budget: int = 6000) -> str:
    out = io.StringIO()
    report = HtmlReport(out, ctx)
    report.plot_budget = plot_budget
    for r in results:
        report.add(r)
    report.close()
    return out.getvalue()


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    HtmlReport.write(results, out, ctx)
