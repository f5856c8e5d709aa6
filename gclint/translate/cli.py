"""``gclint translate``: read INPUT, translate, write OUTPUT atomically, report TR findings on stderr."""

from __future__ import annotations

import sys

from gclint.dialects.base import Dialect
from gclint.io import AtomicWriter, OutputError
from gclint.rules.base import Severity
from gclint.syntax.source import Source, SourceError
from gclint.translate.engine import TranslationResult, UnsupportedPair, translate_source
from gclint.translate.pairs import translator_for


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
        _say(f"gclint: {exc}")
        return 2
    except ValueError as exc:
        _say(f"gclint: {exc}")
        return 2
    try:
        src = Source.open(input_path)
    except SourceError as exc:
        _say(f"gclint: {exc}")
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
        _say(f"gclint: {exc}")
        return 2
    except OutputError as exc:
        _say(f"gclint: {exc}")
        return 2
    _report(result, unsupported)
    if _refused(result, unsupported):
        return 1
    return 0


def _say(text: str) -> None:
    """One line on standard error (no click here: gclint/translate is library code)."""
    print(text, file=sys.stderr)


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
    from gclint.reports.common import message  # masks secrets quoted from the file

    for f in result.findings:
        _say(f"{f.path}:{f.line}:{f.column}: {f.code} {message(f)}")
    if unsupported == "error" and _refused(result, unsupported):
        _say(
            f"gclint: {result.path}: not translated: {len(result.findings)} construct(s) cannot be translated "
            "exactly (--unsupported error)"
        )
