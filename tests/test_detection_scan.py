"""``--dialect auto`` tests each header pattern once per file and skips patterns whose required text is
absent (dialects/base.py HeadScan): the answers must be those of a plain search, on every corpus file."""

from __future__ import annotations

import re

from hypothesis import given
from hypothesis import strategies as st

from gclint import dialects
from gclint.dialects.base import HeadScan, _plan
from gclint.syntax.source import Source, SourceError
from tests.conftest import CORPUS, needs_corpus

PATTERNS = sorted({p for d in dialects.all_dialects() for p, _ in d.detection.patterns})


def _plain(pattern: str, head: str) -> bool:
    return re.search(pattern, head, re.MULTILINE) is not None


def test_the_texts_every_match_contains():
    assert _plan("a|b")[1] == ()  # (one character: not worth a test)
    assert _plan("repetrel|hyrel")[1] == ("repetrel", "hyrel")
    assert _plan(r"x(?:ab|cd)")[1] == ("ab", "cd")
    assert _plan("x[|]y")[1] == ("x|y",) and _plan(r"xy\|z")[1] == ("xy|z",)
    assert _plan(r"(?i)^[;(].*\bskeinforge\b[^\n]*")[1:] == (("skeinforge",), True)
    assert _plan(r"(?i)^[;(].*\b(?:RepRapFirmware|RRF|Duet ?[23W]\w*)\b")[1] == ("RepRapFirmware", "RRF", "Duet")
    assert _plan(r"^;\s*FLAVOR:\s*RepRap\s*\(RepRap\)")[1] == ("(RepRap)",)  # (the longest)
    assert _plan(r"^M229\b|^; hand")[1] == ("M229", "; hand")
    assert _plan(r"(?:ab)?cdx")[1] == ("cdx",) and _plan(r"ab*")[1] == ()  # (optional parts are not needed)
    assert _plan(r"Ab(?i:xyz)")[1] == ("Ab",)  # (a part that ignores case in one that does not: not used)


@given(
    st.lists(
        st.sampled_from(
            [
                "M229",
                "m229",
                " M6 T12 O1",
                "; Repetrel",
                "HYREL",
                "G1 X1 A2",
                "M8",
                "M82",
                "; FLAVOR:Marlin",
                ";flavor: reprap",
                "o100 sub",
                "echo hi",
                "\n",
                " ",
                "\r",
                "carvera",
                "G22",
                "M104 P1 S200",
                ";gcode_flavor = marlin2",
            ]
        ),
        max_size=12,
    )
)
def test_same_answers_on_generated_heads(parts):
    head = "".join(parts)
    scan = HeadScan(head)
    for pattern in PATTERNS:
        assert scan.matches(pattern) == _plain(pattern, head), pattern


@needs_corpus
def test_same_answers_on_the_corpus():
    checked = 0
    for path in sorted(p for p in CORPUS.rglob("*") if p.is_file()):
        try:
            source = Source.open(str(path))
        except SourceError:
            continue
        head = source.head_text()
        source.close()
        scan = HeadScan(head)
        for pattern in PATTERNS:
            assert scan.matches(pattern) == _plain(pattern, head), (path, pattern)
        checked += 1
    assert checked > 500
