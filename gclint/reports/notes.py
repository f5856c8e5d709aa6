"""Notes for people about how files were read (the way ruff prints warnings on stderr): a file read on weak
or conflicting evidence gets a note; files where nothing told the dialect share one note (read as
``hyrel``, the first target); ``-v`` gives the decision for every file."""

from __future__ import annotations

from gclint.context.model import NONE, WEAK
from gclint.engine import FileResult

MAX_NOTES = 20  # more weak files than this: the rest are counted (-v lists every file)


def context_notes(results: list[FileResult], verbose: bool = False) -> list[str]:
    """The note lines (without the ``note:`` prefix's colour) for ``results``, in file order."""
    lines: list[str] = []
    defaulted: list[str] = []
    weak: list[str] = []
    for r in results:
        c = r.context
        if r.profile and r.error is None:  # (a slicer profile: what its check filled in, and how it read)
            lines.extend(f"{r.path}: {note}" for note in r.notes)
            if verbose and c is not None:
                lines.append(f"{r.path}: its custom G-code was checked as {c.label()}: {r.dialect_reason}")
            continue
        if r.error is not None or c is None:
            continue
        if verbose:
            lines.append(f"{r.path}: checked as {c.label()}: {c.why()}")
            if c.candidates:  # the scored choice (gclint.context.score): every reading's score, best first
                lines.append(f"{r.path}: {c.scores_text()}")
        elif c.strength == "none" and not c.conflict:
            defaulted.append((r.path, c))
        elif c.weak:
            how = " on weak evidence" if c.strength in (WEAK, NONE) else ""
            weak.append(f"{r.path}: checked as {c.label()}{how}: {c.why()}")
    if verbose:
        return lines
    lines.extend(weak[:MAX_NOTES])
    if len(weak) > MAX_NOTES:
        more = len(weak) - MAX_NOTES
        lines.append(f"{more} more file{'s were' if more != 1 else ' was'} read on weak evidence (-v lists every file)")
    # (each group names what its files were checked as, as the "Checked as" line does: the version and the
    # printer too, which a file's addresses may tell when nothing tells its dialect)
    groups: dict[str, list[str]] = {}
    for path, c in defaulted:
        groups.setdefault(c.dialect_label() + _printer_part(c), []).append(path)
    for label, paths in groups.items():
        shown = ", ".join(paths[:3]) + (f" and {len(paths) - 3} more" if len(paths) > 3 else "")
        files = "1 file" if len(paths) == 1 else f"{len(paths)} files"
        lines.append(
            f"nothing in {files} tells the dialect ({shown}): checked as {label}; "
            "set --dialect, dialect = ... in gclint.toml or '; gclint: dialect=NAME' in the file"
        )
    return lines


def _printer_part(c) -> str:
    """``, the first target`` and, when the job tells the printer, which one."""
    text = ", the first target"
    if c.printer is not None and c.printer_origin == "content":
        text += f" (printer {c.printer}, from the job)"
    return text
