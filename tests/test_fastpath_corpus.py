"""The fast path and the lark grammar agree on every line of the corpus (each distinct line once;
two processes).  About 1.4 million distinct lines: this is the slowest test of the suite."""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor

from gclint.syntax.fastpath import parse_fast
from gclint.syntax.parse import parse_slow
from gclint.syntax.source import Source, SourceError

from .conftest import CORPUS, needs_corpus

pytestmark = needs_corpus


def _compare(lines: list[str]) -> tuple[int, list[str]]:
    fast_count = 0
    disagree = []
    for raw in lines:
        fast = parse_fast(raw)
        if fast is None:
            continue
        fast_count += 1
        if fast != parse_slow(raw):
            disagree.append(raw)
    return fast_count, disagree


def test_fastpath_agrees_with_grammar_on_every_corpus_line():
    distinct: set[str] = set()
    total = 0
    for path in sorted(p for p in CORPUS.rglob("*") if p.is_file()):
        try:
            source = Source.open(str(path))
        except SourceError:
            continue
        for raw, _ in source.lines():
            distinct.add(raw)
            total += 1
    lines = sorted(distinct)
    chunks = [lines[i : i + 25000] for i in range(0, len(lines), 25000)]
    with ProcessPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(_compare, chunks))
    fast_lines = sum(r[0] for r in results)
    disagree = [raw for r in results for raw in r[1]]
    assert not disagree, disagree[:20]
    assert total > 2_000_000 and fast_lines > 0.9 * len(lines)
