"""Run one benchmark task in this (fresh) process and print JSON: seconds, lines, peak RSS in MB.

Usage: python bench/_measure.py TASK PATH...   (TASK: regex, gcodeparser, check, check-hyrel, translate)
Each task is run in its own process so that peak memory is the task's own.
"""

from __future__ import annotations

import json
import os
import re
import resource
import sys
import time

_WORD = re.compile(r"([A-Za-z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")


def files_of(paths: list[str]) -> list[str]:
    out = []
    for p in paths:
        if os.path.isdir(p):
            for d, _, fs in os.walk(p):
                out.extend(
                    os.path.join(d, f) for f in sorted(fs) if f.lower().endswith((".gcode", ".gco", ".g", ".nc"))
                )
        else:
            out.append(p)
    return sorted(out)


def regex_baseline(files: list[str]) -> int:
    """A bare tokenizer: per line drop comments, find letter+number words, convert to float."""
    n = 0
    for path in files:
        with open(path, "rb") as fh:
            for raw in fh:
                line = raw.decode("utf-8", "surrogateescape")
                i = line.find(";")
                if i >= 0:
                    line = line[:i]
                for _letter, value in _WORD.findall(line):
                    float(value)
                n += 1
    return n


def gcodeparser_baseline(files: list[str]) -> int:
    from gcodeparser import parse_gcode_lines

    n = 0
    for path in files:
        with open(path, encoding="utf-8", errors="surrogateescape") as fh:
            text = fh.read()
        try:
            for _line in parse_gcode_lines(text):
                pass
        except ValueError:
            # gcodeparser 0.3 raises on some real files (e.g. "M203 80", "T?"): parse those line by line,
            # skipping the lines it cannot read, so that every file counts.
            for raw in text.splitlines():
                try:
                    for _line in parse_gcode_lines(raw):
                        pass
                except ValueError:
                    pass
        n += text.count("\n") + (0 if text.endswith("\n") or not text else 1)
    return n


def gclint_check(files: list[str], dialect: str) -> int:
    from gclint.engine import Linter, Options

    linter = Linter(Options(dialect=dialect))
    n = 0
    for path in files:
        n += linter.check_path(path).lines
    return n


def gclint_translate(files: list[str], target: str) -> int:
    from gclint import dialects
    from gclint.context import infer
    from gclint.syntax.source import Source
    from gclint.translate import TranslationResult, translate_source, translator_for

    n = 0
    for path in files:
        source = Source.open(path)
        src = dialects.get(infer(source.head_text(), path, complete=source.head_is_whole).dialect)
        translator = translator_for(src, dialects.get(target))
        result = TranslationResult(path, src.name, target)
        with open(os.devnull, "wb") as out:
            for text in translate_source(source, translator, result):
                out.write(source.encode(text))
        n += result.lines_in
    return n


def main() -> None:
    task, paths = sys.argv[1], sys.argv[2:]
    files = files_of(paths)
    start = time.perf_counter()
    if task == "regex":
        lines = regex_baseline(files)
    elif task == "gcodeparser":
        lines = gcodeparser_baseline(files)
    elif task == "check":
        lines = gclint_check(files, "auto")
    elif task == "check-hyrel":
        lines = gclint_check(files, "hyrel")
    elif task == "translate":
        lines = gclint_translate(files, "hyrel")
    else:
        raise SystemExit(f"unknown task {task}")
    seconds = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(json.dumps({"task": task, "seconds": seconds, "lines": lines, "peak_mb": peak}))


if __name__ == "__main__":
    main()
