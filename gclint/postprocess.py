"""``gclint postprocess``: the slicer post-processing step (PrusaSlicer, SuperSlicer, OrcaSlicer, Bambu
Studio; Simplify3D with ``"[output_filepath]"``).

The contract (PrusaSlicer source, src/libslic3r/GCode/PostProcessor.cpp): the slicer runs ``$SHELL -c "<configured line>
'<path>'"`` with every setting exported as ``SLIC3R_<KEY>``; the G-code path comes last and is often a temporary copy
(``<temp>.gcode.pp``); the script must change that file in place; a non-zero exit stops the export and PrusaSlicer shows
the captured stderr.  So gclint:

1. reads the source flavour from ``SLIC3R_GCODE_FLAVOR`` (else the file's header),
2. translates the file to ``--to`` (if given and different), writing a temporary file and renaming it
   over the original (a failure never leaves a half-written job),
3. checks the result in the target dialect,
4. prints the findings on stderr and writes them to a report beside the final output
   (``<output>.gclint.txt``; the final name comes from ``SLIC3R_PP_OUTPUT_NAME``),
5. exits 1 when ``--fail-on`` is met (the slicer then stops the export), else 0.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TextIO

from gclint import __version__, dialects
from gclint.context import infer_source
from gclint.dialects.base import Dialect
from gclint.engine import FileResult, Linter, Options
from gclint.io import AtomicWriter, OutputError
from gclint.rules.base import Finding, Severity
from gclint.syntax.source import Source, SourceError

FAIL_ON = {"error": Severity.ERROR, "warning": Severity.WARNING, "info": Severity.INFO, "never": None}
STDERR_LIMIT = 30  # findings printed on stderr (the slicer's dialog); the report has them all


@dataclass
class Outcome:
    """What one post-processing run did."""

    path: str
    display: str
    source_dialect: str
    source_reason: str
    target_dialect: str
    translated: bool = False
    translation_note: str = ""  # why nothing was translated, when --to was asked for
    translation_findings: list[Finding] = field(default_factory=list)
    result: FileResult | None = None
    report_path: str | None = None
    report_error: str | None = None
    error: str | None = None  # the file could not be read or written (exit 2)

    @property
    def findings(self) -> list[Finding]:
        out = list(self.translation_findings)
        if self.result is not None:
            out.extend(self.result.findings)
        return sorted(out, key=Finding.sort_key)

    def worst(self) -> Severity | None:
        return max((f.severity for f in self.findings), default=None)

    def exit_code(self, fail_on: str, untranslatable_fails: bool) -> int:
        if self.error:
            return 2
        threshold = FAIL_ON[fail_on]
        if threshold is None:
            return 0
        if self.translation_note and untranslatable_fails:
            return 1
        worst = self.worst()
        return 1 if worst is not None and worst >= threshold else 0


def output_name(path: str, environ: Mapping[str, str] | None = None) -> str:
    """The name of the file the user will get: ``SLIC3R_PP_OUTPUT_NAME`` when the slicer gives it.

    For the ``File`` host it is the final full path; for print hosts it is the name on the host.
    Without it (Simplify3D, a manual run) the path itself, minus PrusaSlicer's temporary ``.pp``.
    """
    env = os.environ if environ is None else environ
    name = env.get("SLIC3R_PP_OUTPUT_NAME", "").strip()
    if name:
        return name
    return path[:-3] if path.endswith(".pp") else path


def report_path_for(path: str, environ: Mapping[str, str] | None = None) -> str:
    """Where the report goes: beside the final output when that folder exists, else beside ``path``."""
    final = output_name(path, environ)
    folder = os.path.dirname(final)
    if os.path.isabs(final) and folder and os.path.isdir(folder):
        return final + ".gclint.txt"
    return os.path.join(os.path.dirname(os.path.abspath(path)), os.path.basename(final) + ".gclint.txt")


def source_dialect(source: Source, path: str, env_flavor: str | None, explicit: str | None) -> tuple[Dialect, str]:
    """The dialect the slicer wrote: ``--from``, else what the content says (gclint.context), with the
    slicer's flavour (``SLIC3R_GCODE_FLAVOR``) as header evidence that loses to clear content."""
    if explicit and explicit != "auto":
        return dialects.get(explicit), "--from"
    context = infer_source(source, path, env_flavor=env_flavor or None)
    return dialects.reading(context.dialect, context.flavor), context.why()


def run(
    path: str,
    *,
    to: str | None = None,
    source: str | None = None,
    printer: str | None = None,
    loaded: frozenset[int] | None = None,
    report: str | None = None,
    environ: dict[str, str] | None = None,
) -> Outcome:
    """Translate (when ``to`` differs from the source) and check ``path`` in place."""
    env = os.environ if environ is None else environ
    display = os.path.basename(output_name(path, env))
    try:
        src = Source.open(path)
    except SourceError as exc:
        return Outcome(path, display, "", "", to or "", error=str(exc))
    try:
        dialect, reason = source_dialect(src, path, env.get("SLIC3R_GCODE_FLAVOR"), source)
    except dialects.UnknownDialect as exc:
        src.close()
        return Outcome(path, display, "", "", to or "", error=str(exc))
    target = dialects.get(to) if to else dialect
    outcome = Outcome(path, display, dialect.name, reason, target.name)
    if target.name != dialect.name:
        _translate(src, dialect, target, outcome, printer)
    else:
        src.close()
    check_dialect = target if outcome.translated or target.name == dialect.name else dialect
    options = Options(dialect=check_dialect.name, env_flavor=None)
    if printer:
        options = replace(options, printer=printer)
    if loaded is not None:
        options = replace(options, loaded=loaded)
    try:
        with open(path, "rb") as stream:
            outcome.result = Linter(options).check_source(Source(stream, display))
    except (OSError, SourceError) as exc:
        outcome.error = f"{path}: cannot read: {exc}"
        return outcome
    if outcome.result.error:
        outcome.error = outcome.result.error
    outcome.report_path = report or report_path_for(path, env)
    return outcome


def _translate(src: Source, dialect: Dialect, target: Dialect, outcome: Outcome, printer: str | None) -> None:
    from gclint.translate import TranslationResult, UnsupportedPair, translate_source, translator_for
    from gclint.translate.options import TranslateOptions

    try:
        options = TranslateOptions.build(outcome.path, printer=printer, unsupported="warn")
        translator = translator_for(dialect, target, options)
    except (UnsupportedPair, ValueError) as exc:
        src.close()
        outcome.translation_note = (
            f"{exc}: the file was left as {dialect.name} and checked as {dialect.name}; "
            f"it is NOT ready for a {target.name} printer"
        )
        return
    result = TranslationResult(outcome.display, dialect.name, target.name)
    try:
        with AtomicWriter(outcome.path, keep_mode_of=outcome.path, follow_links=True) as out:
            out.write(src.bom)
            for text in translate_source(src, translator, result):
                out.write(src.encode(text))
    except (SourceError, OutputError) as exc:
        outcome.error = str(exc)
        return
    for f in result.findings:
        f.path = outcome.display
    outcome.translation_findings = list(result.findings)
    outcome.translated = True


def write_report(outcome: Outcome, out: TextIO, fail_on: str, limit: int | None = None) -> None:
    """The text report: what was done, then ``name:line:col: CODE message`` per finding."""
    from gclint.reports.common import human, message
    from gclint.textsafe import human_path

    out.write(f"gclint {__version__} postprocess: {human_path(outcome.display)}\n")
    if outcome.error:
        out.write(f"error: {human(outcome.error)}\n")
        return
    out.write(f"source dialect: {outcome.source_dialect} ({human(outcome.source_reason)})\n")
    if outcome.translated:
        out.write(
            f"translated to: {outcome.target_dialect} (TR findings name lines of the job as the slicer wrote it;"
            " the others, lines of the translated job now in the file)\n"
        )
    elif outcome.translation_note:
        out.write(f"not translated: {human(outcome.translation_note)}\n")
    findings = outcome.findings
    shown = findings if limit is None else findings[:limit]
    for f in shown:
        out.write(f"{human_path(f.path)}:{f.line}:{f.column}: {f.code} [{f.severity.label}] {message(f)}\n")
    if limit is not None and len(findings) > limit:
        out.write(f"... and {len(findings) - limit} more")
        out.write(f" (see {human_path(outcome.report_path)})\n" if outcome.report_path else "\n")
    counts = {k: 0 for k in ("error", "warning", "info")}
    for f in findings:
        counts[f.severity.label] += 1
    if findings:
        parts = ", ".join(_count(counts[k], k) for k in ("error", "warning", "info") if counts[k])
        out.write(f"{_count(len(findings), 'finding')}: {parts}\n")
    else:
        out.write("no findings\n")
    threshold = FAIL_ON[fail_on]
    worst = outcome.worst()
    if threshold is not None and (outcome.translation_note or (worst is not None and worst >= threshold)):
        out.write(f"export stopped by gclint (--fail-on {fail_on})\n")


def save_report(outcome: Outcome, fail_on: str) -> None:
    """Write the report file (atomically, never through a link planted where it goes)."""
    from gclint.io import write_text

    if not outcome.report_path:
        return
    try:
        write_text(outcome.report_path, lambda out: write_report(outcome, out, fail_on))
    except OutputError as exc:
        outcome.report_error = f"{exc} (the report was not written)"


def main(
    path: str,
    *,
    to: str | None,
    fail_on: str,
    source: str | None = None,
    printer: str | None = None,
    loaded: frozenset[int] | None = None,
    report: str | None = None,
    no_report: bool = False,
    stderr: TextIO | None = None,
) -> int:
    """Run the step, print on stderr, write the report; returns the exit code."""
    err = stderr if stderr is not None else sys.stderr
    outcome = run(path, to=to, source=source, printer=printer, loaded=loaded, report=report)
    if no_report:
        outcome.report_path = None
    from gclint.textsafe import human, human_path

    if outcome.error:
        err.write(f"gclint: {human(outcome.error)}\n")
        return 2
    save_report(outcome, fail_on)
    write_report(outcome, err, fail_on, limit=STDERR_LIMIT)
    if outcome.report_error:
        err.write(f"gclint: {human(outcome.report_error)}\n")
    elif outcome.report_path:
        err.write(f"report: {human_path(outcome.report_path)}\n")
    return outcome.exit_code(fail_on, untranslatable_fails=True)


def _count(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"
