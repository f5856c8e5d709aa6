"""``gclint check --show-settings``: what each file would be checked as, and the settings that apply to it
(the configuration file found for it, the rule selection, suppressions), without checking it."""

from __future__ import annotations

import sys

from gclint.config import ConfigError
from gclint.engine import Linter, Options
from gclint.syntax.source import Source, SourceError


def show(files: list[str], overrides: dict, config_file: str | None, stdin_name: str = "-") -> str:
    from gclint import runner
    from gclint.reports.common import printable

    out: list[str] = []
    for path in files:
        name = stdin_name if path == "-" else path
        out.append(printable(name))
        try:
            options = runner.options_for(path, Options(), overrides, config_file)
        except ConfigError as exc:
            out.append(f"  error: {printable(str(exc))}")
            continue
        try:
            source = Source(sys.stdin.buffer, name) if path == "-" else Source.open(path)
        except SourceError as exc:
            out.append(f"  error: {printable(str(exc))}")
            continue
        linter = Linter(options)
        try:
            context = linter.context_of(source)
        finally:
            source.close()
        out.append(f"  configuration: {printable(options.config_path) if options.config_path else 'none found'}")
        out.append(f"  checked as: {context.label()} ({context.strength} evidence)")
        out.append(f"  dialect: {context.dialect}, {printable(context.why())}")
        if context.printer is not None:
            how = {"option": "--printer", "configuration": "the configuration"}.get(context.printer_origin)
            told = how or ("read from the job" if context.printer_origin == "content" else "the default")
            out.append(f"  printer: {context.printer} ({told})")
            loaded = options.loaded
            heads = ", ".join(f"T{h}" for h in sorted(loaded)) if loaded is not None else None
            out.append(
                f"  loaded heads: {heads + ' (--loaded or configuration)' if heads else 'from the job (M6 T# O...)'}"
            )
        if options.extend_known_codes:
            out.append(f"  extend-known-codes: {', '.join(options.extend_known_codes)}")
        selected = sorted(cls.code for cls in linter.rule_classes)
        out.append(f"  rules selected: {len(selected)} ({_families(selected)})")
        if options.select is not None:
            out.append(f"  select: {', '.join(options.select)}")
        if options.ignore:
            out.append(f"  ignore: {', '.join(options.ignore)}")
        matching = linter.per_file_ignores(name)
        if matching:
            out.append(f"  per-file-ignores: {', '.join(matching)}")
    return "\n".join(out) + "\n"


def _families(codes: list[str]) -> str:
    counts: dict[str, int] = {}
    for code in codes:
        counts[code[:2]] = counts.get(code[:2], 0) + 1
    return ", ".join(f"{family} {n}" for family, n in counts.items())
