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
        elif c.strength == "none" and not c.conflict:
            defaulted.append(r.path)
        elif c.weak:
            how = " on weak evidence" if c.strength in (WEAK, NONE) else ""
            weak.append(f"{r.path}: checked as {c.label()}{how}: {c.why()}")
    if verbose:
        return lines
    lines.extend(weak[:MAX_NOTES])
    if len(weak) > MAX_NOTES:
        more = len(weak) - MAX_NOTES
        lines.append(f"{more} more file{'s were' if more != 1 else ' was'} read on weak evidence (-v lists every file)")
    if defaulted:
        shown = ", ".join(defaulted[:3]) + (f" and {len(defaulted) - 3} more" if len(defaulted) > 3 else "")
        files = "1 file" if len(defaulted) == 1 else f"{len(defaulted)} files"
        lines.append(
            f"nothing in {files} tells the dialect ({shown}): checked as hyrel v5, the first target; "
            "set --dialect, dialect = ... in gclint.toml or '; gclint: dialect=NAME' in the file"
        )
    return lines
