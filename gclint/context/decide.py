"""What a file is: its dialect (and firmware flavour), Hyrel firmware version and printer model.

What the user said wins (docs/architecture.md, "What a file is checked as"): ``--dialect``/``--printer``/``--flavor``,
the configuration, then a ``; gclint: dialect=NAME`` line; an explicit dialect is never second-guessed.
Otherwise the file is read once (gclint.context.content) and every candidate reading is scored on how well
it explains it (gclint.context.score: a code a candidate lacks nearly rules it out, a habit costs a little,
a code only one dialect has is strong evidence, the header and the extension are weak, Hyrel is the
prior); the best reading wins (gclint.context.choose), and a close second makes the decision weak.  For a
Hyrel file the version (gclint.context.version) and the model (gclint.context.printer) are decided the same
way, by the weight of all the lines.
"""

from __future__ import annotations

import re

from gclint import dialects, firmware
from gclint.context import printer as printer_model
from gclint.context import version as hyrel_version
from gclint.context.candidates import flavor_candidates
from gclint.context.choose import Decision, decide
from gclint.context.content import ContentReading, read_content
from gclint.context.header import SLICER_FLAVORS, slicer_flavor
from gclint.context.model import CONFIGURATION, DIRECTIVE, EXPLICIT, OPTION, Context
from gclint.context.score import rank
from gclint.dialects.base import HeadScan

DIRECTIVE_LINE = re.compile(r"(?im)^[^\n]*[;(]\s*gclint:\s*dialect\s*=\s*([^\s;)]+)")


def infer(
    head: str,
    path: str = "",
    *,
    dialect: str = "auto",
    dialect_origin: str = OPTION,
    printer: str | None = None,
    printer_origin: str = OPTION,
    flavor: str | None = None,
    flavor_origin: str = OPTION,
    env_flavor: str | None = None,
    complete: bool = True,
    tail: str | None = None,
    machine_codes: tuple[str, ...] = (),
) -> Context:
    """The context of the file whose beginning is ``head`` (``complete``: the whole file; ``tail``: the
    end of a longer file, whole lines; the flavour reads it too).

    ``dialect`` is a dialect name or ``auto``; ``printer`` a model name or None (infer it); ``flavor`` the
    firmware the user declared (``klipper``; None: read it from the file), which also says the dialect when
    nobody else does.  The ``*_origin`` arguments say where an explicit value came from (``option`` or
    ``configuration``).  ``machine_codes`` are the codes the machine's own INI beside the job defines
    (LinuxCNC's ``REMAP=``, gclint.machine.linuxcnc_ini): known codes of the dialects that read such an INI, and
    evidence for them.
    """
    declared = firmware.get(flavor) if flavor is not None else None
    told = (f"--flavor {flavor}" if flavor_origin == OPTION else f"flavor = {flavor} in the configuration",)
    scan = HeadScan(head)
    tail_scan = HeadScan(tail) if tail else None
    reading: ContentReading | None = None

    def content() -> ContentReading:
        nonlocal reading
        if reading is None:
            reading = read_content(head, complete, tail)
        return reading

    directive, unknown = _directive(scan)
    notes = (f"'; gclint: dialect={unknown}' names no dialect: ignored",) if unknown else ()
    decision: Decision | None = None
    reasons: tuple[str, ...]
    if dialect != "auto":  # the user's word beats the file's: a job does not choose how the gate reads it
        name, origin, reasons, strength, conflict = dialects.get(dialect).name, dialect_origin, (), EXPLICIT, ""
        if directive is not None and directive != name:
            told_by = "--dialect" if dialect_origin == OPTION else "dialect in the configuration"
            conflict = f"its '; gclint: dialect={directive}' line is ignored: {told_by} says {name}"
    elif directive is not None:
        name, origin, reasons, strength, conflict = directive, DIRECTIVE, (), EXPLICIT, ""
    elif declared is not None:  # the firmware's files are its dialect's
        name, origin, reasons, strength, conflict = declared.dialect, flavor_origin, told, EXPLICIT, ""
    else:
        decision = decide(rank(content(), scan, tail_scan, path, env_flavor, machine_codes=machine_codes))
        name, origin, reasons = decision.dialect, decision.origin, decision.reasons
        strength, conflict = decision.strength, decision.conflict
    if notes:  # a directive that names nothing is shown, as weak evidence is
        conflict = "; ".join((*notes, conflict)) if conflict else notes[0]
    if declared is not None and declared.dialect != name:
        ignored = f"{told[0]} is a firmware for {declared.dialect} files, and this one is read as {name}: ignored"
        conflict = f"{conflict}; {ignored}" if conflict else ignored
    candidates = decision.candidates if decision is not None else ()
    candidate_reasons = decision.candidate_reasons if decision is not None else ()
    chosen = dialects.get(name)
    if chosen.extras.get("firmware") is None:  # (no version and no printer model to decide)
        found: str | None
        flavor_reasons: tuple[str, ...]
        if declared is not None and declared.dialect == name:
            found, flavor_reasons = declared.name, told
        elif decision is not None:
            found, flavor_reasons = decision.flavor, decision.flavor_reasons
        else:
            found, flavor_reasons = _flavor(content(), scan, tail_scan, path, env_flavor, name)
        return Context(
            name,
            origin,
            strength,
            reasons,
            conflict,
            flavor=found,
            flavor_reasons=flavor_reasons,
            candidates=candidates,
            candidate_reasons=candidate_reasons,
        )

    # Hyrel: v4 or v5 (a variant of the dialect: its ``firmware``), then the model
    base = dialects.get(chosen.variant_of) if chosen.variant_of else chosen
    versions = {d.extras["firmware"]: d.name for d in dialects.all_dialects() if d is base or d.variant_of == base.name}
    stated = chosen.extras["firmware"]  # (the version a Hyrel dialect reads: 4 or 5)
    explicit = (
        stated
        if isinstance(stated, int) and (origin in (OPTION, CONFIGURATION, DIRECTIVE) or chosen is not base)
        else None
    )
    number, firmware_origin, firmware_reasons, evidence = hyrel_version.decide(content(), explicit, origin)
    name = versions.get(number, name)
    model, model_origin, model_reasons, fitting = printer_model.decide(content(), scan, number, printer, printer_origin)
    return Context(
        name,
        origin,
        strength,
        reasons,
        conflict,
        firmware=number,
        firmware_origin=firmware_origin,
        firmware_reasons=firmware_reasons,
        version_evidence=evidence,
        printer=model,
        printer_origin=model_origin,
        printer_reasons=model_reasons,
        printer_candidates=fitting,
        candidates=candidates,
        candidate_reasons=candidate_reasons,
    )


def _flavor(
    reading: ContentReading, scan: HeadScan, tail: HeadScan | None, path: str, env_flavor: str | None, dialect: str
) -> tuple[str | None, tuple[str, ...]]:
    """The firmware flavour of a file whose dialect was given: the best of that dialect's readings."""
    pool = flavor_candidates(dialect)
    if len(pool) < 2:
        return None, ()
    decision = decide(rank(reading, scan, tail, path, env_flavor, pool))
    return decision.flavor, decision.flavor_reasons


_FAR = 1 << 20  # how far to read when the head is mostly comments (a slicer's thumbnail images)


def infer_source(source, path: str | None = None, **options) -> Context:
    """The context of a ``gclint.syntax.source.Source`` (not consumed): its head, read on past comment
    blocks such as thumbnails, and the tail of a regular file (slicers' end code, Hyrel's footer)."""
    head = source.head_text()
    limit = len(head)
    while not source.head_is_whole and limit < _FAR and _mostly_comments(head):
        limit = min(_FAR, limit * 4)  # past the comment block, in steps (thumbnails are 10 KB to 1 MB)
        head = source.head_text(limit)
    return infer(
        head,
        source.display if path is None else path,
        complete=source.head_is_whole,
        tail=source.tail_text(),
        **options,
    )


def _mostly_comments(text: str) -> bool:
    comments = sum(len(line) for line in text.splitlines() if line.lstrip()[:1] in (";", "("))
    return comments > 0.75 * len(text)


def _directive(scan: HeadScan) -> tuple[str | None, str | None]:
    """(the dialect a ``; gclint: dialect=NAME`` line names, the name when it names none)."""
    if "gclint" not in scan.lowered:
        return None, None
    m = DIRECTIVE_LINE.search(scan.head)
    if m is None:
        return None, None
    try:
        return dialects.get(m.group(1)).name, None
    except dialects.UnknownDialect:
        return None, m.group(1)[:40]


def scores(
    head: str, path: str = "", env_flavor: str | None = None, complete: bool = True, tail: str | None = None
) -> dict[str, dict]:
    """Every candidate reading's score and the evidence for and against it (for ``gclint check -v`` and
    tests): ``{key: {"score": float, "evidence": [(points, text), ...]}}``, best first."""
    ranking = rank(
        read_content(head, complete, tail), HeadScan(head), HeadScan(tail) if tail else None, path, env_flavor
    )
    out = {}
    for key, value in sorted(ranking.scores().items(), key=lambda kv: -kv[1]):
        evidence = [(round(i.deltas[key], 2), i.text) for i in ranking.items if i.deltas.get(key)]
        out[key] = {"score": round(value, 2), "evidence": evidence}
    return out


__all__ = ["infer", "infer_source", "slicer_flavor", "scores", "SLICER_FLAVORS"]
