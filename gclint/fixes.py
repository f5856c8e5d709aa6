"""Apply fixes the way ruff does: a safe fix never changes what a valid line means, and a fix never makes
a file worse.

* Fixes come from the findings of one check (``--fix``: the safe ones; ``--unsafe-fixes``: all).
* Never in a file that does not parse (SX001).
* The fixed text is checked again, in the same context, before anything is written: a fix after which a
  finding appears that was not there before is taken back (with every fix when the new finding cannot be
  tied to one line), and the file is checked again; what was taken back is reported.
* The file is written only if its bytes are still the ones that were checked (a file that changed since
  it was read is not fixed), through a temporary file renamed over it (a failure leaves it untouched).
* ``write=False`` (``--diff``) writes nothing and returns the diff instead.  The diff is for people: its
  lines are shown as the text format shows file text (``gclint.textsafe.human``: secrets masked, control
  and invisible characters escaped), so it is not a patch to apply.
"""

from __future__ import annotations

import os
import tempfile
from collections import Counter
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace
from typing import BinaryIO

from gclint.engine import FileResult, Linter
from gclint.io import AtomicWriter, OutputError
from gclint.noqa import INLINE_UNSUPPRESSIBLE, text_code, with_noqa
from gclint.rules.base import Edit, Finding, Fix
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source, SourceError
from gclint.textsafe import human, human_path

_ROUNDS = 4  # checks of the fixed text at most (each round takes back at least one fix)


@dataclass
class FixOutcome:
    """What fixing one file did."""

    result: FileResult  # the findings of the file as it is now (fixed or not)
    fixed: int = 0  # findings whose fix was applied
    applied: list[Finding] = field(default_factory=list)  # those findings (for --show-fixes)
    reverted: list[str] = field(default_factory=list)  # fixes taken back, and why
    diff: str = ""  # with write=False: the changes as a unified diff
    error: str | None = None


@dataclass
class FixPlan:
    """The fixes that can be applied safely, found by checking the fixed text again."""

    fixes: list[Finding] = field(default_factory=list)  # findings whose fix is kept
    reverted: list[str] = field(default_factory=list)  # fixes taken back, and why
    checked: FileResult | None = None  # the check of the text with ``fixes`` applied
    digest: str | None = None  # hash of the original bytes, as read for that check


def plan_fixes(result: FileResult, linter: Linter, read: Callable[[], Source], *, unsafe: bool = False) -> FixPlan:
    """Which of ``result``'s fixes to apply: the safe ones (all with ``unsafe``), minus those after which
    a finding appears that was not there.  ``read`` opens the text ``result`` was made from."""
    plan = FixPlan()
    if result.error is not None or any(f.code == "SX001" for f in result.findings):
        return plan
    chosen = [f for f in result.findings if f.fix is not None and (f.fix.safe or unsafe)]
    before = {(f.line, f.code) for f in result.findings}
    counts = Counter(f.code for f in result.findings)
    for _ in range(_ROUNDS):
        if not chosen:
            return plan
        edits = _edits(chosen)
        plan.checked, plan.digest = _check_fixed(read(), result.path, edits, linter)
        # New findings: a rule now reports more than before (a finding that only moved, as the same
        # mismatch reported at another line once the numbers are right, is not new).
        grown = {code for code, n in Counter(f.code for f in plan.checked.findings).items() if n > counts[code]}
        new = [f for f in plan.checked.findings if f.code in grown and (f.line, f.code) not in before]
        if not new:
            plan.fixes = chosen
            return plan
        lines = {n.line for n in new}
        blamed = [f for f in chosen if any(e.line in lines for e in f.fix.edits)]  # type: ignore[union-attr]
        if not blamed:
            blamed = chosen  # a new finding away from every edited line: no fix can be trusted
        for f in blamed:
            caused = next((n for n in new if any(e.line == n.line for e in f.fix.edits)), new[0])  # type: ignore[union-attr]
            plan.reverted.append(
                f"{f.path}:{f.line}: {f.code} fix not applied: in the fixed text, {caused.code} would report "
                f"line {caused.line} ({caused.message})"
            )
        chosen = [f for f in chosen if f not in blamed]
    return plan  # still not clean after every round: nothing is applied


def settle(result: FileResult, linter: Linter, read: Callable[[], Source]) -> FileResult:
    """``result`` with the marks a report shows matching what ``--fix`` does: a safe fix that the check of
    the fixed text would take back is shown as unsafe (its edit is still offered, as --unsafe-fixes would
    try it), so "[*] N fixable" counts only the fixes --fix applies.  A file that cannot be read again is
    left as it is."""
    safe = [f for f in result.findings if f.fix is not None and f.fix.safe]
    if not safe:
        return result
    try:
        kept = {id(f) for f in plan_fixes(result, linter, read).fixes}
    except (OSError, SourceError, OutputError):
        return result
    if len(kept) == len(safe):
        return result
    findings = [
        f if f.fix is None or not f.fix.safe or id(f) in kept else replace(f, fix=replace(f.fix, safe=False))
        for f in result.findings
    ]
    return replace(result, findings=findings)


def fix_file(result: FileResult, linter: Linter, *, unsafe: bool = False, write: bool = True) -> FixOutcome:
    """Apply the fixes of ``result`` (the check of ``result.path`` by ``linter``) to the file."""
    outcome = FixOutcome(result)
    if not any(f.fix is not None and (f.fix.safe or unsafe) for f in result.findings):
        return outcome
    if write and (why := read_only(result.path)) is not None:
        outcome.reverted.append(why)
        return outcome
    if result.digest is None:
        outcome.error = f"{result.path}: not fixed: the file was not read to the end"
        return outcome
    try:
        plan = plan_fixes(result, linter, lambda: Source.open(result.path, digest=True), unsafe=unsafe)
    except (OSError, SourceError, OutputError) as exc:
        outcome.error = f"{result.path}: not fixed: {exc}"
        return outcome
    if plan.digest is not None and plan.digest != result.digest:
        outcome.error = f"{result.path}: not fixed: the file changed since it was checked; check it again"
        return outcome
    outcome.reverted = plan.reverted
    if not plan.fixes:
        return outcome
    try:
        if write:
            _write(result.path, _edits(plan.fixes), result.digest)
        else:
            outcome.diff = "".join(_diff(result.path, _edits(plan.fixes)))
    except (OSError, SourceError, OutputError) as exc:
        outcome.error = str(exc) if str(exc).startswith(result.path) else f"{result.path}: not fixed: {exc}"
        return outcome
    outcome.fixed, outcome.applied = len(plan.fixes), plan.fixes
    outcome.result = plan.checked  # type: ignore[assignment]
    return outcome


def add_noqa(result: FileResult) -> FixOutcome:
    """``check --add-noqa``: a ``; noqa: CODES`` on every line with findings (an archive of old jobs keeps
    its findings as they are and new ones stand out, as ruff's --add-noqa), written as --fix writes:
    atomically, and only if the file is still what was checked.

    A line whose comment a pause or action code reads as its text (M0, M1, M792 and the codes translated
    to M0) cannot take a noqa (it would change what the printer says or does): it is put between a
    ``; gclint: disable=CODES`` line and a ``; gclint: enable=CODES`` line instead, and a finding after
    the last line gets a ``; gclint: disable=CODES`` line at the end.  Security findings (SC) cannot be
    silenced by the job: ``reverted`` names each such line and why."""
    outcome = FixOutcome(result)
    by_line: dict[int, list[str]] = {}
    security: dict[int, list[str]] = {}
    for f in result.findings:
        into = security if f.code.startswith(INLINE_UNSUPPRESSIBLE) else by_line
        if f.code not in into.setdefault(f.line, []):
            into[f.line].append(f.code)
    for line, kept in sorted(security.items()):
        outcome.reverted.append(
            f"{result.path}:{line}: {', '.join(kept)} not marked: a job cannot silence its own security"
            " findings (--ignore on the command line or a configuration named by --config can)"
        )
    if not by_line or result.error is not None:
        return outcome
    if (why := read_only(result.path)) is not None:
        outcome.reverted.append(why)
        return outcome
    if result.digest is None:
        outcome.error = f"{result.path}: no noqa added: the file was not read to the end"
        return outcome
    try:
        source = Source.open(result.path, digest=True)
        with AtomicWriter(result.path, follow_links=True) as out:
            out.write(source.bom)
            number = 0
            usual = "\n"  # (the file's line ending, for the lines written here)
            for chunk in source.chunks():
                for raw, ending in chunk:
                    number += 1
                    if number == 1 and ending:
                        usual = ending
                    codes = by_line.get(number)
                    if codes and (action := text_code(raw)):
                        listed = ",".join(codes)
                        outcome.reverted.append(
                            f"{result.path}:{number}: {', '.join(codes)} marked by '; gclint: disable=' and"
                            f" 'enable=' lines around it: its comment is the text of {action}, which a noqa"
                            " would change"
                        )
                        out.write(source.encode(f"; gclint: disable={listed}{usual}{raw}{ending or usual}"))
                        out.write(source.encode(f"; gclint: enable={listed}{ending}"))
                        continue
                    out.write(source.encode((with_noqa(raw, codes) if codes else raw) + ending))
            after = sorted({code for line, codes in by_line.items() if line > number for code in codes})
            if after:  # (findings about the end of the job, after its last line)
                out.write(
                    source.encode(
                        ("" if not number or ending else usual) + f"; gclint: disable={','.join(after)}{usual}"
                    )
                )
            if source.sha256 != result.digest:
                out.discard()
                raise OutputError(f"{result.path}: no noqa added: the file changed since it was checked")
    except (OSError, SourceError, OutputError) as exc:
        outcome.error = str(exc)
        return outcome
    outcome.fixed = len(by_line)
    return outcome


def read_only(path: str) -> str | None:
    """Why ``path`` must not be rewritten when it is read-only (its mode has no write bit, or this user
    may not write it), else None.  A rewrite renames a new file over the old one, which the folder's
    permission allows whatever the file's: a job someone made read-only is reported and left as it is."""
    try:
        st = os.stat(path)
    except OSError:
        return None  # (the write itself says what is wrong)
    if not st.st_mode & 0o222 or not os.access(path, os.W_OK):
        return f"{path}: read-only: not rewritten (make it writable to fix it)"
    return None


def fix_stream(
    result: FileResult, linter: Linter, read: Callable[[], Source], out: BinaryIO, *, unsafe: bool = False
) -> FixOutcome:
    """``--fix -``: write the text ``read`` opens, fixed, to ``out`` (the text unchanged when no fix
    can be applied), as editors use it."""
    outcome = FixOutcome(result)
    plan = plan_fixes(result, linter, read, unsafe=unsafe)
    outcome.reverted = plan.reverted
    edits = _edits(plan.fixes)
    source = read()
    out.write(source.bom)
    for _, _, text, ending in _fixed_lines(source, edits):
        out.write(source.encode(text + ending))
    if plan.fixes:
        outcome.fixed, outcome.applied = len(plan.fixes), plan.fixes
        outcome.result = plan.checked  # type: ignore[assignment]
    return outcome


def _edits(findings: list[Finding]) -> dict[int, list[Edit]]:
    edits: dict[int, list[Edit]] = {}
    for f in findings:
        for e in f.fix.edits:  # type: ignore[union-attr]
            edits.setdefault(e.line, []).append(e)
    return edits


def _fixed_lines(source: Source, edits: dict[int, list[Edit]]) -> Iterator[tuple[int, str, str, str]]:
    """(line number, original text, fixed text, ending) for every line of ``source``."""
    number = 0
    for chunk in source.chunks():
        for raw, ending in chunk:
            number += 1
            line_edits = edits.get(number)
            yield number, raw, (_with_checksum(raw, _edit(raw, line_edits)) if line_edits else raw), ending


def _with_checksum(raw: str, text: str) -> str:
    """``text`` (``raw`` fixed) with its ``*`` checksum recomputed when ``raw``'s was right: a fix must not turn a
    good line into one the printer rejects (SX004), whatever rules are selected.  A wrong checksum is left
    as it is (it may mark a line damaged in transfer; recomputing it would bless the damage)."""
    from gclint.rules.syntax import compute_checksum

    old = parse_line(raw).checksum
    if old is None or old.value != compute_checksum(raw[: old.column - 1]):
        return text
    new = parse_line(text).checksum
    if new is None:
        return text
    right = compute_checksum(text[: new.column - 1])
    if new.value == right:
        return text
    return f"{text[: new.column - 1]}*{right}{text[new.end_column - 1 :]}"


def _check_fixed(
    source: Source, path: str, edits: dict[int, list[Edit]], linter: Linter
) -> tuple[FileResult, str | None]:
    """Check the fixed text (in a temporary file, named as the real one) and hash the original's bytes."""
    with tempfile.TemporaryFile() as scratch:
        scratch.write(source.bom)
        for _, _, text, ending in _fixed_lines(source, edits):
            scratch.write(source.encode(text + ending))
        scratch.seek(0)
        checked = linter.check_source(Source(scratch, path))
    return checked, source.sha256


def _write(path: str, edits: dict[int, list[Edit]], digest: str) -> None:
    source = Source.open(path, digest=True)
    with AtomicWriter(path, follow_links=True) as out:  # in place: the job a link names
        out.write(source.bom)
        for _, _, text, ending in _fixed_lines(source, edits):
            out.write(source.encode(text + ending))
        if source.sha256 != digest:  # changed while being fixed: keep what is there
            out.discard()
            raise OutputError(f"{path}: not fixed: the file changed while it was being fixed")


def _diff(path: str, edits: dict[int, list[Edit]], context: int = 3) -> Iterator[str]:
    """A unified diff of the fixes (lines change in place: never added or removed)."""
    ranges: list[list[int]] = []  # [first, last] line of each hunk, changes with their context merged
    for number in sorted(edits):
        first, last = max(1, number - context), number + context
        if ranges and first <= ranges[-1][1] + 1:
            ranges[-1][1] = last
        else:
            ranges.append([first, last])
    shown = human_path(path)
    yield f"--- {shown}\n+++ {shown} (fixed)\n"
    index, lines = 0, []
    for number, raw, text, ending in _fixed_lines(Source.open(path), edits):
        first, last = ranges[index]
        if number < first:
            continue
        lines.append((raw, text, ending))
        if number == last:
            yield from _hunk(first, lines)
            index, lines = index + 1, []
            if index == len(ranges):
                return
    if lines:  # the file ended inside the last hunk's context
        yield from _hunk(ranges[index][0], lines)


# What a unified diff (diff -u, git diff) writes after a last line that has no line break: every line of the
# diff ends with one, so without this mark the diff would say the file ends with a line break it does not have.
_NO_NEWLINE = "\\ No newline at end of file\n"


def _hunk(start: int, lines: list[tuple[str, str, str]]) -> Iterator[str]:
    yield f"@@ -{start},{len(lines)} +{start},{len(lines)} @@\n"
    for raw, text, ending in lines:
        mark = "" if ending else _NO_NEWLINE
        if raw == text:
            yield f" {human(raw)}\n{mark}"
        else:
            yield f"-{human(raw)}\n{mark}+{human(text)}\n{mark}"


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


__all__ = ["add_noqa", "fix_file", "fix_stream", "plan_fixes", "FixOutcome", "FixPlan", "Fix"]
