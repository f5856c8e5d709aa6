"""``gclint translate``: read INPUT, translate, write OUTPUT atomically, report TR findings on stderr."""

from __future__ import annotations

import sys

import click

from gclint.dialects.base import Dialect
from gclint.io import AtomicWriter, OutputError
from gclint.rules.base import Severity
from gclint.syntax.source import Source, SourceError
from gclint.translate.engine import TranslationResult, UnsupportedPair, translate_source, translator_for


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
    from gclint.translate.options import TranslateOptions

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
        translator = translator_for(source, target, options)
    except UnsupportedPair as exc:
        _error(exc)
        return 2
    except ValueError as exc:
        _error(exc)
        return 2
    try:
        src = Source.open(input_path)
    except SourceError as exc:
        _error(exc)
        return 2
    result = TranslationResult(src.display, source.name, target.name)
    target_path = output if output not in (None, "-") else None
    try:
        if target_path is None:
            data = _collect(src, translator, result)
            if _refused(result, unsupported):
                _report(result, unsupported)
                return 1
            sys.stdout.flush()
            sys.stdout.buffer.write(data)
            sys.stdout.buffer.flush()
        else:
            with AtomicWriter(target_path, keep_mode_of=input_path if input_path != "-" else None) as out:
                out.write(src.bom)
                for text in translate_source(src, translator, result):
                    out.write(src.encode(text))
                if _refused(result, unsupported):
                    out.discard()
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

    click.echo(f"gclint: {human(str(exc))}", err=True)


def _collect(src: Source, translator, result: TranslationResult) -> bytes:
    parts = [src.bom]
    for text in translate_source(src, translator, result):
        parts.append(src.encode(text))
    return b"".join(parts)


def _refused(result: TranslationResult, unsupported: str) -> bool:
    return unsupported == "error" and any(f.severity >= Severity.WARNING for f in result.findings)


def _report(result: TranslationResult, unsupported: str) -> None:
    if unsupported == "ignore":
        return
    from gclint.reports.common import human, message  # masks secrets, escapes file text

    for f in result.findings:
        click.echo(f"{human(f.path)}:{f.line}:{f.column}: {f.code} {message(f)}", err=True)
    if unsupported == "error" and _refused(result, unsupported):
        click.echo(
            f"gclint: {human(result.path)}: not translated: {len(result.findings)} construct(s) cannot be translated "
            "exactly (--unsupported error)",
            err=True,
        )
