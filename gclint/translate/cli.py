"""``gclint translate``: read INPUT, translate, write OUTPUT atomically, report TR findings on stderr."""

from __future__ import annotations

import shutil
import sys
import tempfile

from gclint.dialects.base import Dialect
from gclint.io import AtomicWriter, OutputError
from gclint.rules.base import Severity
from gclint.syntax.sniff import refuse_non_gcode
from gclint.syntax.source import CHUNK, Source, SourceError
from gclint.translate.engine import TranslationResult, UnsupportedPair, translate_source
from gclint.translate.pairs import translator_for


def source_reading(src: Source, path: str, source: Dialect) -> Dialect:
    """``source`` as the job is read: with the firmware the job says it was written for (its flavour: Bambu's
    arcs, Machinekit FDM's G28), as ``gclint check`` reads it."""
    from gclint import dialects
    from gclint.context import infer_source

    flavor = infer_source(src, path, dialect=source.name).flavor
    return dialects.reading(source.name, flavor)


def run_translate(
    input_path: str,
    source: Dialect,
    target: Dialect,
    *,
    output: str | None,
    unsupported: str = "warn",
    annotate: bool = False,
    printer: str | None = None,
    tool_map: dict[int, int] | None = None,
    config_file: str | None = None,
    flow: str | None = None,
    settings: dict[str, str] | None = None,
) -> int:
    """Translate one file; returns the exit code."""
    from gclint.translate.options import ToolMapClash, TranslateOptions

    try:
        options = TranslateOptions.build(
            input_path,
            printer=printer,
            tool_map=tool_map,
            annotate=annotate,
            unsupported=unsupported,
            config_file=config_file,
            flow=flow,
            settings=settings,
        )
    except ValueError as exc:
        _error(exc)
        return 2
    try:
        src = Source.open(input_path)
        try:
            refuse_non_gcode(src)  # as ``gclint check`` refuses it (one line, exit 2)
        except SourceError:
            src.close()
            raise
        source = source_reading(src, input_path, source)
    except SourceError as exc:
        _error(exc)
        return 2
    try:
        translator = translator_for(source, target, options)
    except (UnsupportedPair, ValueError) as exc:
        src.close()
        _error(exc)
        return 2
    result = TranslationResult(src.display, source.name, target.name)
    target_path = output if output not in (None, "-") else None
    try:
        if target_path is None:
            with _collect(src, translator, result) as data:
                if _refused(result, unsupported):
                    _report(result, unsupported)
                    return 1
                sys.stdout.flush()
                shutil.copyfileobj(data, sys.stdout.buffer, CHUNK)
                sys.stdout.buffer.flush()
        else:
            in_place = target_path == input_path
            keep = input_path if input_path != "-" else None
            with AtomicWriter(target_path, keep_mode_of=keep, follow_links=in_place) as out:
                out.write(src.bom)
                for text in translate_source(src, translator, result):
                    out.write(src.encode(text))
                if _refused(result, unsupported):
                    out.discard()
    except ToolMapClash as exc:  # two tools of the job on one head: nothing written
        _error(exc)
        return 2
    except SourceError as exc:
        _error(exc)
        return 2
    except OutputError as exc:
        _error(exc)
        return 2
    _report(result, unsupported)
    if _refused(result, unsupported):
        return 1
    return 0


def _error(exc: Exception) -> None:
    from gclint.textsafe import human  # file names and file text: no control character reaches stderr

    _say(f"gclint: {human(str(exc))}")


def _say(text: str) -> None:
    """One line on standard error (no click here: gclint/translate is library code)."""
    print(text, file=sys.stderr)


def _collect(src: Source, translator, result: TranslationResult) -> tempfile.SpooledTemporaryFile:
    """The whole translation, held in memory up to 8 MiB and in a temporary file beyond: nothing reaches
    standard output before the input was read to its end (an unreadable line or --unsupported error
    would otherwise leave half a job there), and memory does not grow with the job."""
    spool = tempfile.SpooledTemporaryFile(max_size=8 << 20)  # noqa: SIM115 (returned open)
    try:
        spool.write(src.bom)
        for text in translate_source(src, translator, result):
            spool.write(src.encode(text))
        spool.seek(0)
    except BaseException:
        spool.close()
        raise
    return spool


def _refused(result: TranslationResult, unsupported: str) -> bool:
    if result.refused:  # the output would make the host run a program (HostActionGuard): never written
        return True
    return unsupported == "error" and any(f.severity >= Severity.WARNING for f in result.findings)


def _report(result: TranslationResult, unsupported: str) -> None:
    if unsupported == "ignore" and not result.refused:
        return
    from gclint.reports.common import message  # masks secrets, escapes file text
    from gclint.textsafe import human_path

    for f in result.findings:
        if unsupported != "ignore" or f.severity >= Severity.ERROR:
            _say(f"{human_path(f.path)}:{f.line}:{f.column}: {f.code} {message(f)}")
    if result.refused:
        _say(
            f"gclint: {human_path(result.path)}: not translated: the output would make the host computer run a program"
        )
    elif unsupported == "error" and _refused(result, unsupported):
        _say(
            f"gclint: {human_path(result.path)}: not translated: {len(result.findings)} construct(s) cannot be translated "
            "exactly (--unsupported error)"
        )
