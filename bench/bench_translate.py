"""Time ``gclint check`` against ``gclint translate --from marlin --to hyrel`` on ../shared/corpus/marlin.

Both run in this process, one after the other, over the same files (read from disk each time); the
translation's output is written to /dev/null through the same encoder the CLI uses.  Prints both times
and the ratio translate / check (the goal: at most 2).

    python bench/bench_translate.py [FOLDER] [--dialect marlin] [--flow evalues|native] [--repeat N]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from gclint import dialects  # noqa: E402
from gclint.engine import Linter, Options  # noqa: E402
from gclint.syntax.source import Source  # noqa: E402
from gclint.translate import TranslationResult, translate_source, translator_for  # noqa: E402
from gclint.translate.options import TranslateOptions  # noqa: E402

EXTENSIONS = (".gcode", ".gco", ".g", ".nc", ".ngc", ".cnc", ".tap")


def job_files(folder: Path) -> list[str]:
    out = []
    for root, _, names in os.walk(folder):
        for name in sorted(names):
            if name.lower().endswith(EXTENSIONS):
                out.append(os.path.join(root, name))
    return sorted(out)


def time_check(paths: list[str], dialect: str) -> tuple[float, int]:
    linter = Linter(Options(dialect=dialect))
    lines = 0
    start = time.perf_counter()
    for path in paths:
        lines += linter.check_path(path).lines
    return time.perf_counter() - start, lines


def time_translate(paths: list[str], dialect: str, flow: str) -> tuple[float, int, int]:
    source = dialects.get(dialect)
    target = dialects.get("hyrel")
    changed = 0
    out_bytes = 0
    start = time.perf_counter()
    with open(os.devnull, "wb") as sink:
        for path in paths:
            options = TranslateOptions()
            options.flow = flow
            translator = translator_for(source, target, options)
            src = Source.open(path)
            result = TranslationResult(path, source.name, target.name)
            for text in translate_source(src, translator, result):
                data = src.encode(text)
                out_bytes += len(data)
                sink.write(data)
            changed += result.lines_changed
    return time.perf_counter() - start, changed, out_bytes


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", default=str(ROOT.parent / "shared" / "corpus" / "marlin"))
    parser.add_argument("--dialect", default="marlin")
    parser.add_argument("--flow", default="evalues", choices=("evalues", "native"))
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    paths = job_files(Path(args.folder))
    if not paths:
        print(f"no G-code files under {args.folder}", file=sys.stderr)
        return 2
    best_check = best_translate = float("inf")
    for _ in range(args.repeat):
        check_time, lines = time_check(paths, args.dialect)
        translate_time, changed, out_bytes = time_translate(paths, args.dialect, args.flow)
        best_check = min(best_check, check_time)
        best_translate = min(best_translate, translate_time)
    print(f"{len(paths)} files, {lines:,} lines ({args.folder})")
    print(f"check     --dialect {args.dialect}: {best_check:7.2f} s  ({lines / best_check:,.0f} lines/s)")
    print(
        f"translate --from {args.dialect} --to hyrel --flow {args.flow}: {best_translate:7.2f} s  "
        f"({lines / best_translate:,.0f} lines/s; {changed:,} lines changed, {out_bytes:,} bytes out)"
    )
    print(f"ratio translate / check: {best_translate / best_check:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
