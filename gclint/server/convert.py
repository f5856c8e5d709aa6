"""gclint's results in the protocol's terms: findings -> diagnostics, fixes -> text edits, a ``noqa``
comment -> a text edit, ``explain`` output -> hover text.

Pure functions returning the protocol's JSON objects as dicts (no server, no client), so each conversion
is tested on its own.  gclint lines and columns are 1-based characters; the protocol's are 0-based, in the code
units of the negotiated position encoding (``Geometry`` does that arithmetic for one version of the text).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Sequence

from gclint.noqa import INLINE_UNSUPPRESSIBLE, noqa_insertion, text_code
from gclint.ruledocs import rule_url
from gclint.rules.base import Edit, Finding, Fix, Severity
from gclint.server.analysis import HoverTarget
from gclint.server.text import UTF16, Snapshot, char_to_units

SOURCE = "gclint"
FIX_ALL_KIND = "source.fixAll.gclint"
QUICK_FIX = "quickfix"
# DiagnosticSeverity: 1 error, 2 warning, 3 information, 4 hint
SEVERITIES = {Severity.ERROR: 1, Severity.WARNING: 2, Severity.INFO: 3}
PLAINTEXT = "plaintext"
MARKDOWN = "markdown"

# The protocol's objects, as JSON has them.
Position = dict
Range = dict
TextEdit = dict
Diagnostic = dict
CodeAction = dict


def position(line: int, character: int) -> Position:
    return {"line": line, "character": character}


def range_(start: Position, end: Position) -> Range:
    return {"start": start, "end": end}


class Geometry:
    """Positions in one version of a document's text, in the client's units.

    A UTF-8 byte order mark at the start of the text is not part of gclint's first line (its reader
    removes it) but is a character for the editor: columns of line 1 move by one."""

    def __init__(self, snapshot: Snapshot, encoding: str = UTF16) -> None:
        self.snapshot = snapshot
        self.encoding = encoding
        self._bom = snapshot.text.startswith("\ufeff")

    def line_index(self, line: int) -> int:
        """The 0-based line of a gclint line number (clamped to the text)."""
        return max(0, min(line - 1, self.snapshot.line_count - 1))

    def char_index(self, line: int, column: int) -> int:
        """The 0-based character index of gclint's ``column`` on ``line`` (clamped to the line)."""
        index = self.line_index(line)
        text = self.snapshot.line(index)
        if line - 1 > index:  # past the last line (an end-of-file finding): the end of the text
            return len(text)
        shift = 1 if index == 0 and self._bom else 0
        return max(0, min(column - 1 + shift, len(text)))

    def position(self, line: int, column: int) -> Position:
        index = self.line_index(line)
        return position(index, char_to_units(self.snapshot.line(index), self.char_index(line, column), self.encoding))

    def line_end(self, line: int) -> Position:
        index = self.line_index(line)
        text = self.snapshot.line(index)
        return position(index, char_to_units(text, len(text), self.encoding))

    def span(self, line: int, start: int, end: int) -> Range:
        """The range of gclint columns ``start``..``end`` (1-based, end exclusive) on ``line``."""
        return range_(self.position(line, start), self.position(line, max(start, end)))


def finding_range(f: Finding, geo: Geometry) -> Range:
    """Where a finding is: its columns when the rule gave an end, else the word (the run of
    non-blank characters) that starts at its column."""
    if f.end_column is not None and f.end_column > f.column:
        return geo.span(f.line, f.column, f.end_column)
    index = geo.line_index(f.line)
    text = geo.snapshot.line(index)
    start = geo.char_index(f.line, f.column)
    end = start
    limit = min(len(text), start + 200)
    while end < limit and not text[end].isspace():
        end += 1
    units = char_to_units
    return range_(position(index, units(text, start, geo.encoding)), position(index, units(text, end, geo.encoding)))


def to_diagnostic(f: Finding, geo: Geometry) -> Diagnostic:
    out: Diagnostic = {
        "range": finding_range(f, geo),
        "severity": SEVERITIES.get(f.severity, 2),
        "code": f.code,
        "source": SOURCE,
        "message": f.message,
    }
    url = rule_url(f.code)
    if url:
        out["codeDescription"] = {"href": url}
    return out


def diagnostics(findings: Iterable[Finding], geo: Geometry, limit: int | None = None) -> list[Diagnostic]:
    out: list[Diagnostic] = []
    for f in findings:
        if limit is not None and len(out) >= limit:
            break
        out.append(to_diagnostic(f, geo))
    return out


# -- edits -----------------------------------------------------------------------------------------------


def _text_edit(e: Edit, geo: Geometry) -> TextEdit:
    return {"range": geo.span(e.line, e.start, e.end), "newText": e.text}


def fix_edits(fix: Fix, geo: Geometry) -> list[TextEdit]:
    """One fix's edits, as the protocol's text edits (in an order the protocol accepts: no overlaps)."""
    return [_text_edit(e, geo) for e in _without_overlaps(fix.edits)]


def _without_overlaps(edits: Iterable[Edit]) -> list[Edit]:
    """The edits ``gclint check --fix`` would make (per line, later columns first; an edit that overlaps
    one already taken is dropped), in the order the protocol applies them: two insertions at one place
    come out in the order ``--fix`` leaves them in the text."""
    by_line: dict[int, list[Edit]] = {}
    for e in edits:
        by_line.setdefault(e.line, []).append(e)
    out: list[Edit] = []
    for line in sorted(by_line):
        kept: list[Edit] = []
        last_start = 1 << 62
        for e in sorted(by_line[line], key=lambda e: e.start, reverse=True):
            if e.end > last_start:
                continue
            kept.append(e)
            last_start = e.start
        out.extend(reversed(kept))
    return out


def fix_all_edits(findings: Sequence[Finding], geo: Geometry) -> list[TextEdit]:
    """The edits of every safe fix, as ``gclint check --fix`` applies them (none when the file does not
    parse: a fix is never applied to a file with SX001 findings)."""
    if any(f.code == "SX001" for f in findings):
        return []
    edits = [e for f in findings if f.fix is not None and f.fix.safe for e in f.fix.edits]
    return [_text_edit(e, geo) for e in _without_overlaps(edits)]


def noqa_offered(finding: Finding, geo: Geometry) -> bool:
    """Whether "suppress with noqa" is offered for ``finding``: never for a security finding (a job cannot
    silence those: the comment would do nothing) nor on a pause or action line, whose comment is what the
    printer says or does (``M792 ; SHELL ...``: a noqa there changes the command)."""
    if finding.code.startswith(INLINE_UNSUPPRESSIBLE):
        return False
    return text_code(geo.snapshot.line(geo.line_index(finding.line))) is None


def noqa_edit(geo: Geometry, line: int, code: str) -> TextEdit:
    """The edit that suppresses ``code`` on ``line`` (1-based), as ``check --add-noqa`` writes it
    (gclint.noqa: first in the line's ``noqa: ...`` list, else `` ; noqa: CODE`` at the end)."""
    index = geo.line_index(line)
    text = geo.snapshot.line(index)
    start, end, new_text = noqa_insertion(text, [code])
    first = position(index, char_to_units(text, start, geo.encoding))
    last = position(index, char_to_units(text, end, geo.encoding))
    return {"range": range_(first, last), "newText": new_text}


# -- code actions ----------------------------------------------------------------------------------------


def kind_wanted(kind: str, only: Sequence[str] | None) -> bool:
    """Whether a code action of ``kind`` answers a request limited to ``only`` (kinds are hierarchical:
    ``source.fixAll`` covers ``source.fixAll.gclint``)."""
    if not only:
        return True
    return any(kind == o or kind.startswith(o + ".") for o in only)


def code_actions(
    uri: str,
    findings: Sequence[Finding],
    geo: Geometry,
    first_line: int,
    last_line: int,
    only: Sequence[str] | None = None,
    version: int | None = None,
    fix_all: Sequence[Finding] | None = None,
) -> list[CodeAction]:
    """Quick fixes for the findings on lines ``first_line``..``last_line`` (0-based, as in the request):
    each fix, "suppress with noqa" per code and line, and "fix all safe" for the file."""

    def workspace_edit(edits: list[TextEdit]) -> dict:
        if version is None:
            return {"changes": {uri: edits}}
        return {"documentChanges": [{"textDocument": {"uri": uri, "version": version}, "edits": edits}]}

    quick = QUICK_FIX
    out: list[CodeAction] = []
    here = [f for f in findings if first_line <= geo.line_index(f.line) <= last_line]
    if kind_wanted(quick, only):
        for f in here:
            if f.fix is not None:
                title = f"{f.code}: {f.fix.message}" + ("" if f.fix.safe else " (unsafe fix)")
                out.append(
                    {
                        "title": title,
                        "kind": quick,
                        "diagnostics": [to_diagnostic(f, geo)],
                        "edit": workspace_edit(fix_edits(f.fix, geo)),
                        "isPreferred": f.fix.safe,
                    }
                )
        seen: set[tuple[int, str]] = set()
        for f in here:
            key = (geo.line_index(f.line), f.code)
            if key in seen:
                continue
            seen.add(key)
            if not noqa_offered(f, geo):
                continue
            out.append(
                {
                    "title": f"{f.code}: suppress on this line (; noqa: {f.code})",
                    "kind": quick,
                    "diagnostics": [to_diagnostic(g, geo) for g in here if g.code == f.code and g.line == f.line],
                    "edit": workspace_edit([noqa_edit(geo, f.line, f.code)]),
                }
            )
    kept = list(findings) if fix_all is None else list(fix_all)  # (fix_all: what --fix keeps, gclint.fixes)
    safe = sum(1 for f in kept if f.fix is not None and f.fix.safe)
    all_edits = fix_all_edits(kept, geo) if safe else []
    if all_edits:
        title = f"Fix all safe gclint problems in this file ({safe})"
        if kind_wanted(quick, only) and any(f.fix is not None and f.fix.safe for f in here) and safe > 1:
            out.append({"title": title, "kind": quick, "edit": workspace_edit(all_edits)})
        if kind_wanted(FIX_ALL_KIND, only):
            out.append({"title": title, "kind": FIX_ALL_KIND, "edit": workspace_edit(all_edits)})
    return out


# -- hover -----------------------------------------------------------------------------------------------

# Only what would change the text mid-line (emphasis, code, links, HTML, tables): escaping more shows as
# backslashes in clients that display the markdown source (Neovim's hover window).
_MD_SPECIAL = re.compile(r"([\\`*_<\[\]~|])")


def _md(text: str) -> str:
    return _MD_SPECIAL.sub(r"\\\1", text)


def _code_span(text: str) -> str:
    fence = "``" if "`" in text else "`"
    return f"{fence} {text} {fence}" if fence == "``" else f"`{text}`"


def hover_text(target: HoverTarget, markdown: bool, dialect_reason: str = "") -> str:
    """The ``gclint explain`` text of the hovered command (plain text, as the command line prints it)
    or the same as markdown with the hovered word in bold."""
    exp = target.explanation
    about = f"dialect: {target.dialect.name} ({target.dialect.title})"
    if dialect_reason:
        about += f", {dialect_reason}"
    if not markdown:
        return f"{exp.render()}\n\n{about}"
    head = f"**{_md(exp.code)}** {_md(exp.title)}" if exp.code else f"**{_md(exp.title)}**"
    lines = [head, ""]
    for item in exp.items:
        if item.word:
            text = _md(item.text)
            if target.word is not None and item.word == target.word:
                text = f"**{text}**"
            lines.append(f"- {_code_span(item.word)} {text}")
        elif item.warning:
            lines.append(f"- warning: {_md(item.text)}")
        else:
            lines.append(f"- note: {_md(item.text)}")
    lines += ["", f"*{_md(about)}*"]
    return "\n".join(lines)


def hover(target: HoverTarget, geo: Geometry, line: int, markdown: bool, dialect_reason: str = "") -> dict:
    """The hover for ``target`` found on ``line`` (1-based)."""
    contents = {"kind": MARKDOWN if markdown else PLAINTEXT, "value": hover_text(target, markdown, dialect_reason)}
    index = geo.line_index(line)
    text = geo.snapshot.line(index)
    start = char_to_units(text, target.start - 1, geo.encoding)
    end = char_to_units(text, target.end - 1, geo.encoding)
    return {"contents": contents, "range": range_(position(index, start), position(index, end))}
