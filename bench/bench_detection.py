"""How well detection reads the labelled set (issue 24, item 4), and what it costs.

    python bench/bench_detection.py [--json] [--rounds N] [--no-timing]

Reads tests/data/corpus_labels.tsv (every corpus file, labelled by reading it) and the variants and
hand-written jobs of tests/detection_cases.py, runs detection on each as the pre-commit hook does (no
dialect or printer given: ``gclint.context.infer_source``), and prints

- accuracy per label: per dialect (all files, the certain ones, and the uncertain ones that are right or
  say they are unsure), per firmware flavour, per Hyrel version, per printer model, and per kind of variant;
- every misreading: the file or case, what it is, what detection said, and the context's reasons;
- the time detection takes against parsing the same heads (the text detection reads: the head, read on
  past comment blocks, and the tail), fastest of ``--rounds`` (the machine is shared and noisy).

``--json`` prints one JSON object instead (the same numbers and lists).  Not a test:
tests/test_detection_labels.py is the gate.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from gclint.context import decide  # noqa: E402
from gclint.syntax import parse as parse_mod  # noqa: E402
from gclint.syntax.source import Source, SourceError  # noqa: E402
from tests.conftest import CORPUS, corpus_available  # noqa: E402
from tests.detection_cases import (  # noqa: E402
    cases,
    corpus_labels,
    detect_file,
    detect_text,
    got_of,
    judge,
    reading_of,
)

FIELDS = ("dialect", "flavor", "version", "printer")


class Tally:
    """right / total per key."""

    def __init__(self) -> None:
        self.right: dict[str, int] = defaultdict(int)
        self.total: dict[str, int] = defaultdict(int)

    def add(self, key: str, ok: bool) -> None:
        self.total[key] += 1
        self.right[key] += ok

    def rows(self) -> list[dict]:
        return [
            {"label": k, "right": self.right[k], "total": n, "accuracy": round(self.right[k] / n, 4)}
            for k, n in sorted(self.total.items())
        ]


def evaluate(items) -> dict:
    """Run detection on every (id, kind, label, detect) item; tally and collect the misreadings."""
    per = {name: Tally() for name in FIELDS}
    certain, uncertain, kinds = Tally(), Tally(), Tally()
    misreadings = []
    for ident, kind, label, detect in items:
        try:
            ctx = detect()
        except SourceError as exc:  # (a labelled G-code file that cannot be read is a misreading too)
            misreadings.append(
                {
                    "id": ident,
                    "kind": kind,
                    "expected": label.describe(),
                    "got": f"error: {exc}",
                    "certain": label.certain,
                    "weak": None,
                    "wrong": {},
                    "reasons": "",
                }
            )
            continue
        wrong = judge(ctx, label)
        for name in FIELDS:
            expected = getattr(label, name)
            if expected:
                per[name].add(expected, name not in wrong)
        (certain if label.certain else uncertain).add(
            label.dialect, "dialect" not in wrong or not label.certain and ctx.weak
        )
        passes = not wrong or (not label.certain and ctx.weak)
        kinds.add(kind, passes)
        if wrong:
            misreadings.append(
                {
                    "id": ident,
                    "kind": kind,
                    "expected": label.describe(),
                    "got": reading_of(ctx),
                    "got_fields": got_of(ctx),
                    "certain": label.certain,
                    "weak": ctx.weak,
                    "passes": passes,
                    "wrong": {k: list(v) for k, v in wrong.items()},
                    "reasons": ctx.why(),
                }
            )
    return {
        "accuracy": {name: per[name].rows() for name in FIELDS},
        "dialect_certain": certain.rows(),
        "dialect_uncertain_right_or_unsure": uncertain.rows(),
        "pass_rate_by_kind": kinds.rows(),
        "misreadings": misreadings,
    }


def corpus_items():
    for f in corpus_labels():
        yield f.path, "corpus", f.label, (lambda p=f.path: detect_file(CORPUS / p, p))


def case_items(with_corpus: bool):
    for c in cases():
        if c.needs_corpus and not with_corpus:
            continue
        text = c.make()  # (built outside the timing: translation and reading the corpus are not detection)
        yield c.id, c.kind, c.label, (lambda t=text, n=c.name: detect_text(t, n))


# -- timing ---------------------------------------------------------------------------------------


def _heads(path: Path) -> tuple[str, str | None]:
    """The text detection reads of ``path``: its head (read on past comment blocks, as infer_source
    does) and its tail."""
    source = Source.open(str(path))
    try:
        head = source.head_text()
        limit = len(head)
        while not source.head_is_whole and limit < decide._FAR and decide._mostly_comments(head):
            limit = min(decide._FAR, limit * 4)
            head = source.head_text(limit)
        return head, source.tail_text()
    finally:
        source.close()


def _parse_heads(paths: list[Path]) -> int:
    n = 0
    for path in paths:
        head, tail = _heads(path)
        for text in (head, tail or ""):
            for line in text.splitlines():
                parse_mod.parse_line(line)
                n += 1
    return n


def _detect_all(paths: list[Path]) -> None:
    for path in paths:
        detect_file(path, str(path))


def timing(rounds: int) -> dict:
    """Detection of every labelled corpus file against parsing the lines it reads (both from disk, the
    parser's cache emptied before each run: detection parses with the same cached parser)."""
    paths = [CORPUS / f.path for f in corpus_labels()]
    best = {"detect": float("inf"), "parse": float("inf")}
    lines = 0
    for _ in range(rounds):
        for name, run in (("parse", _parse_heads), ("detect", _detect_all)):
            parse_mod._CACHE.clear()
            start = time.perf_counter()
            result = run(paths)
            best[name] = min(best[name], time.perf_counter() - start)
            if name == "parse":
                lines = result
    return {
        "files": len(paths),
        "lines_in_heads": lines,
        "detect_seconds": round(best["detect"], 4),
        "parse_seconds": round(best["parse"], 4),
        "ratio_detect_to_parse": round(best["detect"] / best["parse"], 3) if best["parse"] else None,
    }


# -- output ---------------------------------------------------------------------------------------


def _table(title: str, rows: list[dict]) -> None:
    if not rows:
        return
    print(title)
    for r in rows:
        print(f"  {r['label']:<22}{r['right']:>5} / {r['total']:<5}{100 * r['accuracy']:6.1f} %")


def _print(result: dict) -> None:
    for part in ("corpus", "cases"):
        if part not in result:
            continue
        r = result[part]
        print(f"== {part} ==")
        for name in FIELDS:
            _table(f"{name} (right / labelled)", r["accuracy"][name])
        _table("dialect, files labelled certain", r["dialect_certain"])
        _table("dialect, files labelled uncertain: right, or read as unsure", r["dialect_uncertain_right_or_unsure"])
        _table("pass (the test's verdict) by kind", r["pass_rate_by_kind"])
        print()
    for part in ("corpus", "cases"):
        if part not in result:
            continue
        wrong = result[part]["misreadings"]
        print(
            f"== misreadings: {part} ({len(wrong)}; '*' marks those the test lets pass: uncertain and read as unsure) =="
        )
        for m in wrong:
            star = "*" if m.get("passes") else " "
            print(f"{star} {m['id']}")
            print(f"    expected {m['expected']}{'' if m['certain'] else ' (uncertain)'}; got {m['got']}")
            print(f"    reasons: {m['reasons']}")
        print()
    if "timing" in result:
        t = result["timing"]
        print("== timing (fastest round) ==")
        print(
            f"  {t['files']} files, {t['lines_in_heads']:,} lines in the heads: detection {t['detect_seconds']:.3f} s, "
            f"parsing the same heads {t['parse_seconds']:.3f} s, ratio {t['ratio_detect_to_parse']}"
        )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--rounds", type=int, default=3, help="timing rounds (the fastest counts)")
    ap.add_argument("--no-timing", action="store_true", help="skip the timing")
    args = ap.parse_args(argv)
    result: dict = {}
    with_corpus = corpus_available()
    if with_corpus:
        result["corpus"] = evaluate(corpus_items())
    else:
        print(f"(corpus not found at {CORPUS}: the hand-written cases only)", file=sys.stderr)
    result["cases"] = evaluate(case_items(with_corpus))
    if with_corpus and not args.no_timing:
        result["timing"] = timing(args.rounds)
    if args.json:
        json.dump(result, sys.stdout, indent=1)
        print()
    else:
        _print(result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
