"""``gclint diff SOURCE OUTPUT --from D --to D``: where two jobs differ in meaning.

Both files are simulated, each in its own dialect, and compared at their working moves and at the end
(compare.py).  With ``explain`` (the default) SOURCE is also translated in memory with the same settings,
and each difference is marked with the TR finding that explains it; when OUTPUT is not that translation
(edited since, or translated otherwise), a difference is explained only where the translation has the very
same one (compare.Explanations.reference).  Exit code: 0 no difference (or,
with ``fail_on="unexplained"``, none unexplained), 1 differences, 2 a usage error or a file that could
not be read.  No click here: gclint/cli.py parses the options.
"""

from __future__ import annotations

import json
import sys

from gclint.dialects.base import Dialect
from gclint.simulate import DiffResult, Explanations, Mapping, diff_sources
from gclint.syntax.sniff import refuse_non_gcode
from gclint.syntax.source import Source, SourceError
from gclint.textsafe import human, human_path
from gclint.translate.cli import source_reading
from gclint.translate.pairs import is_target


def run_diff(
    source_path: str,
    output_path: str,
    source: Dialect,
    target: Dialect,
    *,
    fmt: str = "text",
    explain: bool = True,
    fail_on: str = "any",
    printer: str | None = None,
    tool_map: dict[int, int] | None = None,
    config_file: str | None = None,
    flow: str | None = None,
    settings: dict[str, str] | None = None,
) -> int:
    from gclint.translate.options import TranslateOptions

    try:
        options = TranslateOptions.build(
            source_path,
            printer=printer,
            tool_map=tool_map,
            config_file=config_file,
            flow=flow,
            settings=settings,
        )
    except ValueError as exc:
        _say(f"gclint: {exc}")
        return 2
    if not is_target(target) or source is target:
        # the same dialect on both sides would compare a job with itself; from Hyrel, only to the other version
        _say(
            f"gclint: diff compares a job with its Hyrel translation; translating {source.name} to {target.name} "
            "is not supported (targets: hyrel, hyrel-v4)"
        )
        return 2
    explanations: Explanations | None = None
    mapping = Mapping.from_options(options)
    try:
        opener = _opener(source_path)
        first = opener()
        try:  # (read with the firmware the job says it was written for, as translate and check read it)
            source = source_reading(first, source_path, source)
        finally:
            first.close()
        translation: str | None = None
        if explain and source.name != target.name:
            explanations, translation = _explanations(opener(), source, target, options)
        if translation is not None and explanations is not None and _text(output_path) != translation:
            # not the translator's own output: a finding explains only a difference that output has too
            first = opener()
            try:
                own = diff_sources(first, Source.from_text(translation), source, target, mapping, explanations)
            finally:
                first.close()
            explanations = Explanations(explanations.entries, reference=own.differences)
        first = opener()
        try:
            refuse_non_gcode(first)
            second = Source.open(output_path)
            try:
                refuse_non_gcode(second)
                result = diff_sources(first, second, source, target, mapping, explanations)
            finally:
                second.close()
        finally:
            first.close()
    except SourceError as exc:
        _say(f"gclint: {exc}")
        return 2
    except ValueError as exc:
        _say(f"gclint: {exc}")
        return 2
    if fmt == "json":
        _print_json(result, source_path, output_path, explanations is not None)
    else:
        _print_text(result, source_path, output_path, explanations is not None)
    if fail_on == "unexplained":
        return 1 if result.unexplained() else 0
    return 1 if result.differences else 0


def _opener(path: str):
    """A function that opens SOURCE afresh (it is read twice: translated, then simulated); standard input
    is read once, into memory."""
    if path != "-":
        return lambda: Source.open(path)
    first = Source.open(path)
    try:
        data = first.bom + b"".join(
            first.encode("".join(raw + ending for raw, ending in chunk)) for chunk in first.chunks()
        )
    finally:
        first.close()
    return lambda: Source.from_bytes(data, first.display)


def _explanations(src: Source, source: Dialect, target: Dialect, options) -> tuple[Explanations, str | None]:
    """The findings of translating SOURCE with the same settings, and the translation (None: it failed)."""
    from gclint.simulate.translation import explanations_from, translate_text

    try:
        refuse_non_gcode(src)
        text, result = translate_text(src, source, target, options)
    except SourceError:
        raise
    except Exception as exc:  # the translator's own problem must not hide the diff
        _say(f"gclint: {src.display}: could not translate it to explain the differences: {type(exc).__name__}")
        return Explanations(), None
    return explanations_from(result), text


def _text(path: str) -> str:
    """OUTPUT's text as the translator would have written it (its lines and their endings)."""
    output = Source.open(path)
    try:
        return "".join(raw + ending for chunk in output.chunks() for raw, ending in chunk)
    finally:
        output.close()


def _say(text: str) -> None:
    print(text, file=sys.stderr)


def _print_text(result: DiffResult, source_path: str, output_path: str, explained: bool) -> None:
    out = sys.stdout
    source_path, output_path = human_path(source_path), human_path(output_path)
    for d in result.differences:
        where = f"{source_path}:{d.source_line or '-'}: {output_path}:{d.output_line or '-'}:"
        count = f" ({d.count} working moves)" if d.count > 1 else ""
        line = f"{where} {d.aspect}: {d.source} -> {d.output}{count}"
        if explained:
            line += (
                f" [explained by {d.explained_by[0]} at {source_path}:{d.explained_by[1]}]"
                if d.explained_by
                else " [unexplained]"
            )
        out.write(human(line) + "\n")
    total = len(result.differences)
    summary = f"{total} difference{'s' if total != 1 else ''} over {result.pairs} matched working moves"
    if explained:
        summary += f" ({len(result.unexplained())} unexplained)"
    out.write(summary + ".\n")
    for note in result.notes:
        out.write(f"note: {human(note)}\n")


def _print_json(result: DiffResult, source_path: str, output_path: str, explained: bool) -> None:
    data = {
        "source": source_path,
        "output": output_path,
        "matched_moves": result.pairs,
        "differences": [d.to_dict() for d in result.differences],
        "unexplained": len(result.unexplained()) if explained else None,
        "notes": result.notes,
    }
    json.dump(data, sys.stdout, indent=2, ensure_ascii=False)
    sys.stdout.write("\n")
