"""The diff of a translation: translate a job in memory, then compare the source with the output, the
differences explained by the translation's own TR findings."""

from __future__ import annotations

from gclint.dialects.base import Dialect
from gclint.simulate import DiffResult, Explanations, Mapping, diff_sources
from gclint.syntax.source import Source


def explanations_from(result) -> Explanations:
    """The warning-level TR findings of a ``TranslationResult``, by aspect."""
    return Explanations([(code, aspects, list(lines)) for (code, aspects), lines in result.occurrences.items()])


def translate_text(path: str | Source, source: Dialect, target: Dialect, options) -> tuple[str, object]:
    """Translate ``path`` (or an open ``Source``) in memory: (output text, TranslationResult)."""
    from gclint.translate import TranslationResult, translate_source, translator_for

    translator = translator_for(source, target, options)
    src = Source.open(path) if isinstance(path, str) else path
    try:
        result = TranslationResult(src.display, source.name, target.name)
        text = "".join(translate_source(src, translator, result))
    finally:
        src.close()
    return text, result


def diff_translation(path: str, source: Dialect, target: Dialect, options) -> tuple[DiffResult, object]:
    """Translate ``path`` and diff the source with the output: (DiffResult, TranslationResult)."""
    text, result = translate_text(path, source, target, options)
    src = Source.open(path)
    try:
        diff = diff_sources(
            src,
            Source.from_text(text, "<translation>"),
            source,
            target,
            Mapping.from_options(options),
            explanations_from(result),
        )
    finally:
        src.close()
    return diff, result
