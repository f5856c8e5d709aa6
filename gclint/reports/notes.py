"""Notes for people about how files were read (the way ruff prints warnings on stderr), summarised once per
run: the files read on weak or conflicting evidence share one note (one file: its reasons; more: how many,
as what, the first few names), and so do the files where nothing told the dialect (read as ``hyrel``,
the first target); ``-v`` gives the decision and its reasons for every file."""

from __future__ import annotations

from gclint.context.model import NONE, WEAK
from gclint.engine import FileResult

NAMED = 3  # files named in a summary note (-v lists every file)


def context_notes(results: list[FileResult], verbose: bool = False) -> list[str]:
    """The note lines (without the ``note:`` prefix's colour) for ``results``, in file order."""
    lines: list[str] = []
    defaulted: list[str] = []
    weak: list[tuple[str, str, str]] = []  # (path, checked as, why)
    conflicting = False
    for r in results:
        c = r.context
        if r.error is not None or c is None:
            continue
        if verbose:
            lines.append(f"{r.path}: checked as {c.label()}: {c.why()}")
        elif c.strength == "none" and not c.conflict:
            defaulted.append(r.path)
        elif c.weak:
            how = " on weak evidence" if c.strength in (WEAK, NONE) else ""
            conflicting = conflicting or not how
            weak.append((r.path, f"{c.label()}{how}", c.why()))
    if verbose:
        return lines
    if len(weak) == 1:
        path, label, why = weak[0]
        lines.append(f"{path}: checked as {label}: {why}")
    elif weak:
        kinds: dict[str, int] = {}
        for _, label, _ in weak:
            name = label.removesuffix(" on weak evidence")
            kinds[name] = kinds.get(name, 0) + 1
        read_as = ", ".join(f"{name} {n}" for name, n in sorted(kinds.items(), key=lambda kv: (-kv[1], kv[0])))
        shown = ", ".join(path for path, _, _ in weak[:NAMED]) + (
            f" and {len(weak) - NAMED} more" if len(weak) > NAMED else ""
        )
        evidence = "weak or conflicting evidence" if conflicting else "weak evidence"
        lines.append(f"{len(weak)} files were read on {evidence} ({read_as}: {shown}); -v gives each file's reasons")
    if defaulted:
        shown = ", ".join(defaulted[:NAMED]) + (f" and {len(defaulted) - NAMED} more" if len(defaulted) > NAMED else "")
        files = "1 file" if len(defaulted) == 1 else f"{len(defaulted)} files"
        lines.append(
            f"nothing in {files} tells the dialect ({shown}): checked as hyrel v5, the first target; "
            "set --dialect, dialect = ... in gclint.toml or '; gclint: dialect=NAME' in the file"
        )
    return lines
