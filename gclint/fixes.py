"""Apply fixes: rewrite a file with the edits of its findings' fixes, atomically, then check it again.

A fix is never applied to a file that does not parse (SX001 findings), and a fixed file that would not
parse is left untouched (the sqlfluff safety net).
"""

from __future__ import annotations

from gclint.engine import FileResult, Linter
from gclint.io import AtomicWriter, OutputError
from gclint.rules.base import Edit
from gclint.syntax.source import Source, SourceError


def apply_fixes(result: FileResult, unsafe: bool = False, linter: Linter | None = None) -> FileResult:
    """Fix ``result.path`` in place; returns the result of checking the fixed file again with ``linter``
    (pass the linter of the first check, so that its printer, loaded heads and selection apply)."""
    if any(f.code == "SX001" for f in result.findings):
        return result
    edits: dict[int, list[Edit]] = {}
    fixed_codes = []
    for f in result.findings:
        if f.fix is not None and (f.fix.safe or unsafe):
            for e in f.fix.edits:
                edits.setdefault(e.line, []).append(e)
            fixed_codes.append(f.code)
    if not edits:
        return result
    try:
        source = Source.open(result.path)
        with AtomicWriter(result.path, follow_links=True) as out:  # in place: the job a link names
            out.write(source.bom)
            number = 0
            for chunk in source.chunks():
                for raw, ending in chunk:
                    number += 1
                    line_edits = edits.get(number)
                    text = _edit(raw, line_edits) if line_edits else raw
                    out.write(source.encode(text + ending))
    except (SourceError, OutputError) as exc:
        return FileResult(result.path, findings=result.findings, dialect=result.dialect, error=str(exc))
    checker = linter
    if checker is None:
        from gclint.engine import Options

        checker = Linter(Options(dialect=result.dialect or "auto"))
    return checker.check_path(result.path)


def _edit(raw: str, edits: list[Edit]) -> str:
    """Apply non-overlapping edits to one line (later columns first)."""
    text = raw
    last_start = len(raw) + 2
    for e in sorted(edits, key=lambda e: e.start, reverse=True):
        if e.end > last_start:
            continue  # overlapping edit: keep the first one only
        text = text[: e.start - 1] + e.text + text[e.end - 1 :]
        last_start = e.start
    return text
