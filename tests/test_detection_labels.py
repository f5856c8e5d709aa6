"""The labelled set (issue 24, item 4): every corpus file and every variant read as a person would.

Detection runs as the pre-commit hook runs it, with no dialect, firmware or printer given
(``gclint.context.infer_source``).  A file or case labelled ``certain`` must get its dialect right, and its
flavour, Hyrel version and printer model where they are labelled; one a careful reader could take for
several dialects must be right or say it is unsure (``Context.weak``).

The labels come from reading the files (tests/data/corpus_labels.tsv, tests/detection_cases.py), not from
what gclint says: many of these fail until detection is rewritten as a scored choice (issue 24, item 3).
``python bench/bench_detection.py`` prints the accuracy and every misreading.
"""

from __future__ import annotations

import pytest

from tests.conftest import CORPUS, needs_corpus
from tests.detection_cases import (
    LABELS,
    NOT_GCODE,
    Label,
    all_label_rows,
    cases,
    corpus_labels,
    detect_file,
    detect_text,
    judge,
    reading_of,
)

CORPUS_FILES = corpus_labels()
CASES = cases()


def _verdict(ctx, label: Label) -> str | None:
    """Why ``ctx`` fails ``label`` (None: it passes)."""
    wrong = judge(ctx, label)
    if not wrong:
        return None
    if not label.certain and ctx.weak:
        return None  # a file that could be several: unsure is an acceptable answer
    said = "; ".join(f"{name}: expected {want}, got {got}" for name, (want, got) in wrong.items())
    unsure = "" if label.certain else " (labelled uncertain, but the reading does not say it is unsure)"
    return f"read as {reading_of(ctx)}: {said}{unsure}\n  evidence: {ctx.why()}\n  label: {label.why}"


@needs_corpus
def test_every_corpus_file_is_labelled_once() -> None:
    rows = all_label_rows()
    paths = [row["path"] for row in rows]
    assert len(paths) == len(set(paths)), "a file labelled twice"
    on_disk = {
        str(p.relative_to(CORPUS))
        for p in CORPUS.rglob("*")
        if p.is_file() and p.name not in ("README.md", "provenance.jsonl", "licenses.json")
    }
    assert set(paths) == on_disk, (
        f"{LABELS.name} and the corpus differ: unlabelled {sorted(on_disk - set(paths))[:10]}, "
        f"gone {sorted(set(paths) - on_disk)[:10]}"
    )
    for row in rows:
        assert row["why"], f"{row['path']}: say why"
        if row["dialect"] == NOT_GCODE:
            assert not (row["flavor"] or row["version"] or row["printer"]), row["path"]


@needs_corpus
@pytest.mark.parametrize("item", CORPUS_FILES, ids=[f.path for f in CORPUS_FILES])
def test_corpus_file_reads_as_labelled(item) -> None:
    ctx = detect_file(CORPUS / item.path, item.path)
    problem = _verdict(ctx, item.label)
    if problem is not None:
        pytest.fail(f"{item.path} {problem}", pytrace=False)


_MARKS = {True: [needs_corpus], False: []}


@pytest.mark.parametrize("case", [pytest.param(c, id=c.id, marks=_MARKS[c.needs_corpus]) for c in CASES])
def test_case_keeps_its_label(case) -> None:
    ctx = detect_text(case.make(), case.name)
    problem = _verdict(ctx, case.label)
    if problem is not None:
        pytest.fail(f"{case.id} {problem}", pytrace=False)
