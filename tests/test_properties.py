"""Property tests: the parser, the reader, the translator and the checker on generated G-code of every dialect,
valid and garbage.  Example counts come from the settings profile (tests/strategies.py: 200 by default,
``GCLINT_HYPOTHESIS=ci`` 1,000, ``thorough`` 10,000).

* parsing never raises, and printing the tree gives back the line (``Line.render``);
* the fast path gives the grammar's tree whenever it accepts a line;
* bytes -> ``Source`` -> lines -> bytes is the identity (endings, BOM, latin-1, undecodable bytes, UTF-16);
* translating a file to its own dialect is the identity;
* translated output parses (for the dialect pairs the translator supports);
* checking never raises and never hits an internal error in a rule, whatever the options;
* ``secrets.mask`` keeps lengths, is idempotent and hides every generated secret.
"""

from __future__ import annotations

import codecs
import io
import re

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from gclint import dialects, secrets
from gclint.engine import Linter, Options
from gclint.rules.base import Severity
from gclint.syntax.fastpath import parse_fast
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line, parse_slow
from gclint.syntax.source import Source, SourceError
from gclint.translate import TranslationResult, UnsupportedPair, translate_source, translator_for

from .strategies import DIALECTS, any_line, dialect_line, gcode_bytes, gcode_text, options_dicts

# -- parsing ---------------------------------------------------------------------------------------------------


@given(any_line())
def test_parsing_never_raises_and_render_gives_back_the_line(raw):
    for parsed in (parse_line(raw), parse_slow(raw)):
        for ending in ("\n", "\r\n", "\r", ""):
            assert Line(7, raw, ending, parsed).render() == raw + ending
        for issue in parsed.issues:
            assert issue.code[:2] == "SX" and issue.column >= 1 and "\n" not in issue.message


@given(st.sampled_from(DIALECTS).flatmap(dialect_line))
def test_fast_path_agrees_with_the_grammar(raw):
    fast = parse_fast(raw)
    if fast is not None:
        assert fast == parse_slow(raw), raw


# -- reading bytes ---------------------------------------------------------------------------------------------


def _roundtrip(data: bytes) -> bytes:
    source = Source(io.BytesIO(data), "t.gcode")
    out = [source.bom]
    for number, (raw, ending) in enumerate(source.lines(), 1):
        out.append(source.encode(Line(number, raw, ending, parse_line(raw)).render()))
    return b"".join(out)


@given(gcode_bytes())
def test_bytes_roundtrip_through_source(data):
    try:
        assert _roundtrip(data) == data
    except SourceError as exc:  # refused as binary: one line naming the file
        assert str(exc).startswith("t.gcode: ") and "\n" not in str(exc)


@given(gcode_text(), st.sampled_from(["utf-16-le", "utf-16-be"]))
@example("\x0000\n", "utf-16-le")
def test_utf16_roundtrip_through_source(text, encoding):
    bom = codecs.BOM_UTF16_LE if encoding == "utf-16-le" else codecs.BOM_UTF16_BE
    data = bom + text.encode(encoding, "surrogatepass")
    if data.startswith(codecs.BOM_UTF32_LE):  # (a UTF-16-LE text starting with NUL: UTF-32's mark, refused)
        with pytest.raises(SourceError, match=r"^t\.gcode: .*UTF-32"):
            _roundtrip(data)
        return
    assert _roundtrip(data) == data


@given(st.binary(max_size=300))
def test_any_bytes_read_or_refused_cleanly(data):
    try:
        assert _roundtrip(data) == data
    except SourceError as exc:
        assert "\n" not in str(exc)


# -- translation -----------------------------------------------------------------------------------------------


def _translate(data: bytes, source: str, target: str) -> tuple[bytes, TranslationResult]:
    src = Source(io.BytesIO(data), "t.gcode")
    translator = translator_for(dialects.get(source), dialects.get(target))
    result = TranslationResult("t.gcode", source, target)
    out = [src.bom]
    for text in translate_source(src, translator, result):
        out.append(src.encode(text))
    return b"".join(out), result


@given(data=st.data())
def test_translating_to_the_same_dialect_is_the_identity(data):
    dialect = data.draw(st.sampled_from(DIALECTS))
    payload = data.draw(gcode_bytes(dialect))
    try:
        out, _ = _translate(payload, dialect, dialect)
    except SourceError:
        return
    assert out == payload


def _supported_pairs() -> list[tuple[str, str]]:
    pairs = []
    for source in DIALECTS:
        for target in DIALECTS:
            if source == target:
                continue
            try:
                translator_for(dialects.get(source), dialects.get(target))
            except UnsupportedPair:
                continue
            except Exception:  # noqa: BLE001 - a broken translator must fail its test below, not the collection
                pass
            pairs.append((source, target))
    return pairs


_PAIRS = _supported_pairs()


def _sx001_lines(data: bytes) -> int:
    # (the lines as gclint.syntax.source cuts them, without its refusal of binary-looking files: a short
    # output such as "; \x00" is refused, and its lines are what is counted here)
    text = data.decode("utf-8", "surrogateescape")
    lines = re.split(r"\r\n?|\n", text)
    return sum(1 for raw in lines if any(i.code == "SX001" for i in parse_line(raw).issues))


@pytest.mark.skipif(not _PAIRS, reason="no dialect pair is translatable yet (gclint.translate.pairs)")
@given(data=st.data())
def test_translated_output_parses(data):
    source, target = data.draw(st.sampled_from(_PAIRS), label="pair")
    text = data.draw(gcode_text(source), label="text")
    payload = text.encode("utf-8", "surrogateescape")
    try:
        out, result = _translate(payload, source, target)
    except SourceError:
        return
    # Lines the grammar reads in the input must stay readable: no new parse errors in the output.
    assert _sx001_lines(out) <= _sx001_lines(payload), out.decode("utf-8", "replace")
    for f in result.findings:
        assert f.code.startswith("TR") and "\n" not in f.message


# -- checking --------------------------------------------------------------------------------------------------


def _assert_sane(result, text_lines: int | None = None) -> None:
    assert result.error is None or "\n" not in result.error
    assert result.error is None or "internal error" not in result.error, result.error
    for f in result.findings:
        assert len(f.code) == 5 and f.code[:2].isalpha() and f.code[2:].isdigit()
        assert isinstance(f.severity, Severity)
        assert f.line >= 1 and f.column >= 1, f
        if text_lines is not None:
            assert f.line <= max(text_lines, 1), f
        assert "\n" not in f.message
        if f.code.startswith("SC"):
            assert f.source is None or secrets.mask(f.source) == f.source  # already masked


@given(gcode_text(), options_dicts())
def test_check_never_raises(text, options):
    result = Linter(Options(**options)).check_text(text, "t.gcode")
    _assert_sane(result, result.lines)


@given(gcode_bytes(), options_dicts())
def test_check_bytes_never_raises(data, options):
    linter = Linter(Options(**options))
    try:
        source = Source(io.BytesIO(data), "t.gcode")
    except SourceError:
        return
    _assert_sane(linter.check_source(source))


# -- secrets ---------------------------------------------------------------------------------------------------

_secret_values = st.text(
    alphabet="abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.", min_size=8, max_size=40
)
_templates = st.sampled_from(
    [
        "; printhost_apikey = {}",
        "; printhost_password = {}",
        "; octoprint_apikey={}",
        "(password: {})",
        "; upload to http://pi:{}@octopi.local/api",
        "; Authorization: Bearer {}",
        'M587 S"net" P"{}"',
        '; "api_key": "{}"',
    ]
)


@given(
    _templates,
    _secret_values.filter(lambda v: v.strip("-_.") and not secrets._placeholder(v)),
    st.text(max_size=20),
)
def test_mask_hides_generated_secrets(template, value, noise):
    text = noise.replace("\n", " ") + " " + template.format(value)
    masked = secrets.mask(text)
    assert len(masked) == len(text)
    assert value not in masked[len(noise) + 1 :], (text, masked)


@given(st.one_of(any_line(), st.text(max_size=200)))
def test_mask_is_idempotent_and_keeps_length(text):
    masked = secrets.mask(text)
    assert len(masked) == len(text)
    assert secrets.mask(masked) == masked
