"""Plain moves a translator keeps unchanged skip the tree (translate_source + ``plain_route``).

The route must change nothing but speed: the same output bytes and the same TR findings as the general
route, for every corpus job of every source dialect, both flows, and for generated jobs.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from gclint import dialects
from gclint.syntax.source import Source
from gclint.translate import TranslationResult, Translator, translate_source, translator_for
from gclint.translate.options import TranslateOptions
from tests.strategies import any_line, numbers
from tests.test_translate_corpus import FOLDERS, jobs

from .conftest import corpus_job, needs_corpus

PAIRS = [("marlin", "hyrel"), ("reprap", "hyrel"), ("machinekit", "hyrel"), ("carvera", "hyrel"), ("marlin", "marlin")]


def _translate(source: Source, src: str, dst: str, flow: str, plain: bool) -> tuple[str, list]:
    options = TranslateOptions()
    options.flow = flow
    translator = translator_for(dialects.get(src), dialects.get(dst), options)
    if not plain:
        translator.plain_route = lambda: None  # type: ignore[method-assign]
    result = TranslationResult("<t>", src, dst)
    text = "".join(translate_source(source, translator, result))
    findings = [(f.line, f.column, f.code, f.message) for f in result.findings]
    return text, findings + [("changed", result.lines_changed)]


def _same_text(text: str, src: str, dst: str, flow: str) -> None:
    fast = _translate(Source.from_text(text, "<t>"), src, dst, flow, True)
    slow = _translate(Source.from_text(text, "<t>"), src, dst, flow, False)
    assert fast == slow


def test_the_route_is_offered_where_it_applies():
    def route(src: str, dst: str):
        return translator_for(dialects.get(src), dialects.get(dst), TranslateOptions()).plain_route()

    assert route("marlin", "hyrel") is not None
    assert route("reprap", "hyrel") is not None
    assert route("marlin", "marlin") is not None  # the identity keeps every line
    assert route("machinekit", "hyrel") is None  # A is the extruder there
    assert route("carvera", "hyrel") is None  # E is one of its extra letters (laser moves)
    assert Translator.plain_route is not None


@st.composite
def _move(draw) -> str:
    letters = draw(st.lists(st.sampled_from("FXYZEF"), max_size=6))
    return draw(st.sampled_from(["G0", "G1"])) + "".join(f" {letter}{draw(numbers())}" for letter in letters)


@given(
    st.lists(
        st.one_of(
            _move(),
            _move(),
            _move(),
            st.sampled_from(
                ["G91", "G90", "M82", "M83", "G92 E0", "M84", "G28", "G20", "G21", "M30", "T1", "M104 S200"]
            ),
            any_line("marlin").filter(lambda line: "\x00" not in line),
        ),
        max_size=40,
    ),
    st.sampled_from(["evalues", "native"]),
    st.sampled_from(["\n", "\r\n"]),
)
def test_same_on_generated_jobs(lines, flow, ending):
    text = ending.join(lines) + (ending if lines and len(lines) % 2 else "")
    for src in ("marlin", "reprap"):
        _same_text(text, src, "hyrel", flow)


@needs_corpus
@pytest.mark.parametrize("folder", FOLDERS)
@pytest.mark.parametrize("flow", ["evalues", "native"])
def test_same_on_the_corpus(folder, flow):
    paths = jobs(folder)
    assert paths
    for path in paths:
        job = corpus_job(path)  # (a big job's head and tail; every line with GCLINT_SLOW=1)
        fast = _translate(Source.open(job), folder, "hyrel", flow, True)
        slow = _translate(Source.open(job), folder, "hyrel", flow, False)
        assert fast == slow, path
