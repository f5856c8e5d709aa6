"""Notes for people about how files were read (the way ruff prints warnings on stderr), summarised once per
run: the files read on weak or conflicting evidence share one note (one file: its reasons; more: how many,
as what, the first few names), and so do the files where nothing told the dialect (read as ``hyrel``,
gclint's default, with how to choose another); ``-v`` gives the decision, its reasons and every reading's score for every file."""

from __future__ import annotations

from gclint.context.model import NONE, WEAK, Context
from gclint.engine import FileResult

NAMED = 3  # files named in a summary note (-v lists every file)


def context_notes(results: list[FileResult], verbose: bool = False) -> list[str]:
    """The note lines (without the ``note:`` prefix's colour) for ``results``, in file order."""
    lines: list[str] = []
    defaulted: list[tuple[str, Context]] = []
    weak: list[tuple[str, str, str]] = []  # (path, checked as, why)
    conflicting = False
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
        evidence = "weak or conflicting evidence" if conflicting else "weak evidence"
        lines.append(
            f"{len(weak)} files were read on {evidence} ({read_as}: {_named(p for p, _, _ in weak)}); -v gives each file's reasons"
        )
    # (each group names what its files were checked as, as the "Checked as" line does: the version and the
    # printer too, which a file's addresses may tell when nothing tells its dialect)
    groups: dict[str, list[str]] = {}
    for path, context in defaulted:
        groups.setdefault(context.dialect_label() + _printer_part(context), []).append(path)
    for label, paths in groups.items():
        files = "1 file" if len(paths) == 1 else f"{len(paths)} files"
        lines.append(
            f"nothing in {files} tells the dialect ({_named(paths)}): checked as {label}, as gclint checks "
            "every file that does not say which firmware it is for; for another, give --dialect NAME (marlin, "
            "reprap, machinekit, carvera, generic), dialect = NAME in gclint.toml or '; gclint: dialect=NAME' "
            "in the file"
        )
    return lines


def _named(paths) -> str:
    paths = list(paths)
    return ", ".join(paths[:NAMED]) + (f" and {len(paths) - NAMED} more" if len(paths) > NAMED else "")


def _printer_part(c) -> str:
    """When the job tells the printer: which one."""
    if c.printer is not None and c.printer_origin == "content":
        return f" (printer {c.printer}, from the job)"
    return ""
