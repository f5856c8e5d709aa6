"""``--format html``: one self-contained page (no external files, no network) from a jinja2 template.

For each file: what it was checked as, its job summary (``gclint summary``) beside an explorable toolpath,
and the findings with their source lines (secrets masked).  ``gclint summary --format html`` writes the same
page without findings (``SummaryPage``).

The toolpath (``toolpath.py``: per layer and per head, sampled) goes to the page as compact JSON in an
attribute of its figure; the page's script (``templates/page.js``, plain JavaScript, no library) draws it on a
canvas: zoom and pan, a layer slider with the layers below faded, per-head colours, travel on or off, the view
fitted to the part, markers on the flagged lines linked both ways with their findings.

A page is for people: file text on it is shown as on a terminal (``human``: secrets masked, control and
invisible format characters escaped).  The template is rendered with autoescaping on, so file text is always
text, never markup (the JSON too: it is an attribute's value); the page's only script carries a per-report
nonce that its Content-Security-Policy requires.
"""

from __future__ import annotations

import io
import json
import math
import re
import secrets as _random
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import TextIO

from markupsafe import Markup

from gclint.engine import FileResult
from gclint.reports.common import human, message, rule_docs, source_line
from gclint.reports.stream import Report, Spool
from gclint.reports.toolpath import BUDGET, Toolpath, read_toolpath
from gclint.textsafe import human_path

PALETTE = ("#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#bcbd22", "#7f7f7f", "#e377c2", "#ff7f0e")
SEVERITY_COLORS = {"error": "#d62728", "warning": "#e6a700", "info": "#4a90d9"}
SEVERITIES = ("error", "warning", "info")
# Coordinates go to the page as whole numbers of this many mm (finer for a job of kilometres: at most
# STEPS steps across it), each point as the step from the one before: a compact JSON.
UNIT = 0.01
STEPS = 1 << 24


@dataclass
class PlotHead:
    label: str
    color: str
    moves: int
    working_moves: int


@dataclass
class Plot:
    """The toolpath viewer's data (``data``: the JSON the page's script draws) and what the page says of it."""

    data: str
    layers: int
    heads: list[PlotHead]
    bounds: tuple[float, float, float, float]  # every move, mm
    fit: tuple[float, float, float, float]  # the part (the bulk of the working moves), mm
    label: str  # the top layer's name, as the slider starts
    note: str
    marked: frozenset[int] = frozenset()  # flagged lines with a marker on the plot


def build_plot(toolpath: Toolpath, result: FileResult | None = None) -> Plot | None:
    """The viewer's data: per layer, each head's sampled moves as whole-number steps and runs of travel and
    work; the flagged lines' markers; the box of the part and of everything."""
    bounds = toolpath.bounds()
    fit = toolpath.fit()
    if bounds is None or fit is None:
        return None
    min_x, min_y, max_x, max_y = bounds
    span = max(max_x - min_x, max_y - min_y)
    if not all(math.isfinite(v) for v in (*bounds, *fit, span)):
        return None  # coordinates beyond what a float can scale (X999...9): no plot, the findings still show
    unit = max(UNIT, span / STEPS)
    scale = 1 / unit

    def qx(x: float) -> int:
        return round((x - min_x) * scale)

    def qy(y: float) -> int:
        return round((y - min_y) * scale)

    heads = list(toolpath.heads)
    head_index = {key: i for i, key in enumerate(heads)}
    layers = []
    for layer in toolpath.layers:
        paths = []
        for head, stroke in layer.strokes.items():
            if len(stroke) < 2:
                continue
            ix = [round((x - min_x) * scale) for x in stroke.xs]
            iy = [round((y - min_y) * scale) for y in stroke.ys]
            steps = [0] * (2 * len(ix))
            steps[0::2] = [b - a for a, b in zip([0, *ix], ix, strict=False)]
            steps[1::2] = [b - a for a, b in zip([0, *iy], iy, strict=False)]
            paths.append([head_index[head], steps, _runs(stroke.work)])
        z = [layer.z_low, layer.z_high] if layer.z_low <= layer.z_high else None
        layers.append({"z": z, "p": paths})
    by_line: dict[int, list] = {}
    if result is not None:
        for f in result.findings:
            by_line.setdefault(f.line, []).append(f)
    markers = []
    marked = set()
    for m in toolpath.markers:
        found = by_line.get(m.line, [])
        if not found:
            continue
        worst = max(found, key=lambda f: f.severity)
        markers.append([qx(m.x), qy(m.y), m.layer or 0, m.line, SEVERITIES.index(worst.severity.label)])
        marked.add(m.line)
    plot_heads = [
        PlotHead(h.label, PALETTE[i % len(PALETTE)], h.moves, h.working_moves)
        for i, h in enumerate(toolpath.heads.values())
    ]
    data = {
        "unit": unit,
        "origin": [min_x, min_y],
        "heads": [{"name": h.label, "color": h.color} for h in plot_heads],
        "layers": layers,
        "byMarkers": toolpath.by_markers,
        "fit": [qx(fit[0]), qy(fit[1]), qx(fit[2]), qy(fit[3])],
        "all": [0, 0, qx(max_x), qy(max_y)],
        "markers": markers,
        "severities": list(SEVERITIES),
        "colors": [SEVERITY_COLORS[s] for s in SEVERITIES],
    }
    notes = []
    if toolpath.by_markers:
        notes.append("layers as the slicer marks them")
    else:
        notes.append("layers: the heights the job works at, lowest first")
    if toolpath.merged > 1 and toolpath.by_markers:
        notes.append(f"a big job: {toolpath.merged} of the slicer's layers are drawn as one")
    elif toolpath.merged > 1:
        notes.append(f"a big job: the heights within {toolpath.merged / 1000:g} mm are drawn as one layer")
    if toolpath.sampled:
        notes.append(f"a big job: one move in up to {toolpath.stride} is drawn")
    notes.append("arcs are drawn as chords")
    return Plot(
        data=json.dumps(data, separators=(",", ":"), allow_nan=False),
        layers=len(layers),
        heads=plot_heads,
        bounds=bounds,
        fit=fit,
        label=layer_label(toolpath, len(layers) - 1),
        note="; ".join(notes),
        marked=frozenset(marked),
    )


def layer_label(toolpath: Toolpath, index: int) -> str:
    """How the slider names a layer (the page's script says the same: ``toolpath.js``)."""
    if not toolpath.layers:
        return "no layers"
    layer = toolpath.layers[index]
    text = f"layer {index + 1} of {len(toolpath.layers)}"
    if layer.z_low <= layer.z_high:
        low, high = f"{layer.z_low:.2f}".rstrip("0").rstrip("."), f"{layer.z_high:.2f}".rstrip("0").rstrip(".")
        text += f", Z {low} mm" if low == high else f", Z {low} to {high} mm"
    return text


def _runs(work: bytearray) -> list[int]:
    """The strokes of a path as alternate counts: travel, work, travel, ... (point i's flag is the stroke that
    ends there; point 0 starts the path)."""
    runs = [m.end() - m.start() for m in _RUN.finditer(work, 1)]
    return [0, *runs] if len(work) > 1 and work[1] else runs


_RUN = re.compile(rb"\x00+|\x01+")


@dataclass
class FileView:
    """One job's section: the check report's (``counts`` and findings) or the summary page's (no findings)."""

    path: str
    anchor: str
    read_as: str
    dialect_reason: str
    weak: bool
    lines: int
    plot: Plot | None
    plot_error: str | None
    counts: dict[str, int] | None = None  # findings per severity (None: a summary page, nothing checked)
    findings: list[dict] = field(default_factory=list)
    error: str | None = None  # why the file could not be checked (or read)
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
    plot, plot_error = None, None
    if result.error is None:
        plot, plot_error = _plot(result.path, result.dialect, result, plot_budget)
    return FileView(
        path=human_path(result.path),
        anchor=f"file-{index}",
        read_as=human(result.read_as),
        dialect_reason=human(result.dialect_reason),
        weak=result.context is not None and result.context.weak,
        lines=result.lines,
        plot=plot,
        plot_error=plot_error,
        counts=result.counts(),
        findings=findings,
        error=human(result.error) if result.error is not None else None,
        omitted=len(result.findings) - len(findings),
        summary=_summary(result),
    )


def _plot(path: str, dialect: str | None, result: FileResult | None, budget: int) -> tuple[Plot | None, str | None]:
    """The job's toolpath for the viewer, or why there is none."""
    flagged = {f.line for f in result.findings} if result is not None else set()
    toolpath = read_toolpath(path, dialect, flagged, budget=budget)
    if toolpath.error:
        return None, human(toolpath.error)
    plot = build_plot(toolpath, result)
    return plot, None if plot is not None else "no XY moves in this file"


def _summary(result: FileResult) -> list[str]:
    """The job summary beside the toolpath (the file read once more, in the context it was checked in)."""
    if result.error is not None or result.context is None or result.path == "-":
        return []
    from gclint.summary import summarize
    from gclint.syntax.source import Source, SourceError

    try:
        source = Source.open(result.path, cut_long_lines=True)
        return summary_facts(summarize(source, result.context))
    except (OSError, SourceError, ValueError):
        return []


def summary_facts(summary) -> list[str]:
    """A ``JobSummary`` as ``gclint summary`` says it, one fact a line (its first line, the job's name and
    what it was read as, is the section's head)."""
    from gclint.summary import render as render_summary

    return [human(line.strip()) for line in render_summary(summary).splitlines()[1:]]


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
        autoescape=True,  # every file text is data, never markup (html, attributes, the toolpath JSON)
        undefined=StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
    )


class HtmlReport(Report):
    """Each file's section is rendered as soon as the file is checked, into a temporary file; the page
    (whose head holds the totals and a link to every file) is written at the end around the sections."""

    plot_budget = BUDGET

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
            script=page_script(),
        )
        head, tail = page.split(marker, 1)
        tail = tail[1:] if tail.startswith("\n") else tail  # each section ends its own line
        self.out.write(head)
        self._spool.copy_to(self.out)
        self.out.write(tail)
        self._spool.close()


def render(results: list[FileResult], ctx, plot_budget: int = BUDGET) -> str:
    out = io.StringIO()
    report = HtmlReport(out, ctx)
    report.plot_budget = plot_budget
    for r in results:
        report.add(r)
    report.close()
    return out.getvalue()


def write(results: list[FileResult], out: TextIO, ctx) -> None:
    HtmlReport.write(results, out, ctx)


def page_script() -> Markup:
    """The page's one script (``page.js``: the findings' filters and the toolpath viewer), run under the
    page's nonce.  Template text, not a value: jinja never escapes it, and it holds no file text."""
    from importlib.resources import files

    return Markup(files("gclint.reports").joinpath("templates", "page.js").read_text(encoding="utf-8"))


class SummaryPage:
    """``gclint summary --format html``: the report's page with a section per job, its summary beside its
    toolpath (nothing is checked, so no findings).  Each section is written as soon as its job is read."""

    def __init__(self, out: TextIO, version: str, paths: list[str], plot_budget: int = BUDGET) -> None:
        self.out = out
        self.plot_budget = plot_budget
        self._env = _environment()
        self._section = self._env.get_template("file.html.j2")
        self._count = 0
        nonce = _random.token_urlsafe(16)
        marker = f"<!-- gclint sections {nonce} -->"
        page = self._env.get_template("summary.html.j2").render(
            version=version,
            generated=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
            files=[NavItem(f"file-{i}", human_path(p), 0) for i, p in enumerate(paths)],
            sections=Markup(marker),
            nonce=nonce,
            severity_colors=SEVERITY_COLORS,
            script=page_script(),
        )
        head, tail = page.split(marker, 1)
        self._tail = tail[1:] if tail.startswith("\n") else tail
        out.write(head)

    def add(self, summary, dialect: str | None, reason: str = "", weak: bool = False) -> None:
        """One job: its ``JobSummary`` and the dialect it was read in (its toolpath is read in that too)."""
        if summary.error:
            plot, plot_error = None, None
        else:
            plot, plot_error = _plot(summary.path, dialect, None, self.plot_budget)
        view = FileView(
            path=human_path(summary.path),
            anchor=f"file-{self._count}",
            read_as=human(summary.read_as),
            dialect_reason=human(reason),
            weak=weak,
            lines=summary.lines,
            plot=plot,
            plot_error=plot_error,
            error=human(summary.error) if summary.error else None,
            summary=[] if summary.error else summary_facts(summary),
        )
        self._count += 1
        self.out.write(self._section.render(f=view, severity_colors=SEVERITY_COLORS) + "\n")

    def close(self) -> None:
        self.out.write(self._tail)
