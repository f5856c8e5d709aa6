"""Benchmark the parser choices on the same lines, in one run: lark LALR (tree), lark LALR with
lark-cython, gclint's grammar path (lark + tree building), the fast path, and parse_line (fast path +
cache + fallback), against the bare regex tokenizer.

    python bench/bench_parser.py [FILE]   (default: a 40k-line sample of ../shared/corpus/marlin)
"""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path

from lark import Lark

from gclint.syntax import parse as parse_mod
from gclint.syntax.fastpath import parse_fast
from gclint.syntax.larkparse import GRAMMAR_PATH, parse_with_lark

DEFAULT = (
    Path(__file__).resolve().parent.parent.parent / "shared" / "corpus" / "marlin" / "prusaslicer-2.6.1_benchy.gcode"
)
_WORD = re.compile(r"([A-Za-z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")


def timed(name: str, fn, lines: list[str], base: float | None = None) -> float:
    start = time.perf_counter()
    fn(lines)
    rate = len(lines) / (time.perf_counter() - start)
    ratio = f"{rate / base:6.2f}x regex" if base else ""
    print(f"{name:<34}{rate:>12,.0f} lines/s  {ratio}")
    return rate


def regex(lines):
    for line in lines:
        i = line.find(";")
        for _l, v in _WORD.findall(line if i < 0 else line[:i]):
            float(v)


def main() -> None:
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT
    lines = path.read_text(encoding="utf-8", errors="surrogateescape").splitlines()[:40000]
    grammar = GRAMMAR_PATH.read_text(encoding="utf-8")
    plain = Lark(grammar, parser="lalr", lexer="contextual", maybe_placeholders=False)
    base = timed("regex tokenizer (baseline)", regex, lines)
    timed("lark LALR, tree", lambda ls: [plain.parse(x) for x in ls], lines[:10000], base)
    try:
        import lark_cython

        fast_lark = Lark(
            grammar, parser="lalr", lexer="contextual", maybe_placeholders=False, _plugins=lark_cython.plugins
        )
        timed("lark LALR + lark-cython, tree", lambda ls: [fast_lark.parse(x) for x in ls], lines[:10000], base)
    except ImportError:
        print("lark-cython not installed")
    timed("grammar path (lark + gclint tree)", lambda ls: [parse_with_lark(x) for x in ls], lines[:10000], base)
    timed("fast path only", lambda ls: [parse_fast(x) for x in ls], lines, base)
    parse_mod._CACHE.clear()
    timed("parse_line (fast + cache + lark)", lambda ls: [parse_mod.parse_line(x) for x in ls], lines, base)
    fallback = sum(1 for x in lines if parse_fast(x) is None)
    print(f"lines handed to the grammar: {fallback} of {len(lines)} ({100 * fallback / len(lines):.2f}%)")


if __name__ == "__main__":
    main()
