"""``--format html``: one self-contained page (no external files, no network) from a jinja2 template.

For each file: a summary (dialect and why, lines, counts), the findings with their source lines (secrets
masked), and an inline SVG plot of the XY toolpath per head with the flagged lines marked.  A page is for
people: file text on it is shown as on a terminal (``human``: secrets masked, control and invisible format
characters escaped).  The
template is rendered with autoescaping on, so file text is always text, never markup; the page's only
script carries a per-report nonce that its Content-Security-Policy requires.
"""

from __future__ import annotations

import math
import secrets as _random
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import TextIO

from gclint.engine import FileResult
from gclint.reports.common import codes_in, human, message, rule_docs, source_line, totals
from gclint.reports.toolpath import Toolpath, read_toolpath

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


# Findings listed per file: a page that a browser can open, and memory that stays bounded (the machine
# formats list them all).
HTML_FINDINGS = 2000


def _file_view(index: int, result: FileResult, plot_budget: int) -> FileView:
    findings = []
    for f in result.findings[:HTML_FINDINGS]:
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
        path=human(result.path),
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
        omitted=max(0, len(result.findings) - HTML_FINDINGS),
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


def render(results: list[FileResult], ctx, plot_budget: int = 6000) -> str:
    from jinja2 import Environment, PackageLoader, StrictUndefined

    env = Environment(
        loader=PackageLoader("gclint.reports", "templates"),
        autoescape=True,  # every file text is data, never markup (html, attributes, svg titles)
        undefined=StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    template = env.get_template("report.html.j2")
    files = [_file_view(i, r, plot_budget) for i, r in enumerate(results)]
    docs = rule_docs(codes_in(results))
    counts: dict[str, list[int]] = {}  # code -> [findings, files]
    for r in results:
        for code in {f.code for f in r.findings}:
            counts.setdefault(code, [0, 0])[1] += 1
        for f in r.findings:
            counts.setdefault(f.code, [0, 0])[0] += 1
    for code, doc in docs.items():
        doc = dict(doc)
        doc["count"], doc["files"] = counts.get(code, [0, 0])
        docs[code] = doc
    return template.render(
        version=ctx.tool_version,
        generated=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
        files=files,
        totals=totals(results),
        unreadable=sum(1 for r in results if r.error),
        rules=[docs[c] for c in sorted(docs)],
        nonce=_random.token_urlsafe(16),
        severity_colors=SEVERITY_COLORS,
    )


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    out.write(render(results, ctx))
