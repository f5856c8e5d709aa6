"""The grammar, the typed tree, the fast path and the streaming reader."""

from __future__ import annotations

import io

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gclint.syntax.fastpath import parse_fast
from gclint.syntax.nodes import (
    ASSIGNMENT,
    EXPRESSION,
    EXTENDED,
    FLAG,
    GCODE,
    IMPLICIT,
    LIST,
    META,
    OWORD,
    PARAMETER,
    QUERY,
    STRING,
    TEXT,
    Line,
    normalize_code,
    to_number,
)
from gclint.syntax.parse import parse_line, parse_slow
from gclint.syntax.source import Source, SourceError, split_lines


def parse(raw: str):
    return parse_slow(raw)


def roundtrip(raw: str) -> None:
    for parsed in (parse_slow(raw), parse_line(raw)):
        line = Line(1, raw, "", parsed)
        assert line.render() == raw
        assert all(type(n).__name__ != "Unparsed" for n in line.elements()) or parsed.kind == "error"


# -- the grammar: every construct grammar.lark reads ------------------------------------------------------


@pytest.mark.parametrize(
    "raw,codes",
    [
        ("G1 X10 Y-2.5 E.5 F1800", ["G1"]),
        ("/G1 X1", ["G1"]),  # block delete
        ("N10 G1 X1", ["G1"]),  # line number
        ("G2.1 I15 J20 P1.2 E1", ["G2.1"]),  # decimal codes
        ('M862.3 P "MK3S"', ["M862.3"]),  # decimal code, spaced quoted string
        ("G1 X-.5 Y10. Z+1", ["G1"]),  # signed, leading-dot, trailing-dot numbers
        ("G0 X -5 Y 0 Z 0 F 200", ["G0"]),  # spaces inside words
        ("g1 x10 y20", ["G1"]),  # lowercase
        ("G0X0Y0S12000M3", ["G0", "M3"]),  # no spaces, two commands
        ("T2M6", ["T2", "M6"]),
        ("G1 X1 ; a ; b", ["G1"]),  # several ; comments
        ("G1 (a) X1 (b) ; c", ["G1"]),  # ( ) comments
        ("N3 T0*57", ["T0"]),  # checksum
        ("M117 Hello World!", ["M117"]),  # free text
        ("M118 E1 Yello World!", ["M118"]),
        ("G1 X{var.x + 1} Y[#1 * 2]", ["G1"]),  # {..} and [..] expressions
        ("o100 if [#1 GT 2]", ["O"]),  # O-words
        ("#<x> = [#1 * 2]", ["#"]),  # parameters
        ("if { result != 0 }", ["if"]),  # RRF meta
        ("var tZ = { exists(param.Z) ? param.Z : 1 }", ["var"]),
        ("SET_FAN_SPEED FAN=part SPEED=0.5", ["SET_FAN_SPEED"]),  # Klipper
        ("%", []),  # program delimiter
        ("G91 G81 R.1 Z-.5 ^60 L6 F10", ["G91", "G81"]),  # LinuxCNC polar words
        ("#1211 = FUP[#1201 / #1114]", ["#"]),  # functions
        ("M307 H1 R4.446 K0.738:0.000", ["M307"]),  # RRF drive lists
        ("M708 A0x0b X5", ["M708"]),  # Prusa hex register
        ("g0x2", ["G0"]),  # compact CNC: G0 X2, not a hex code
        ("g53g0x1 y0", ["G53", "G0"]),
        ("T?", ["T?"]),  # Prusa MMU query
        # a G/M word that cannot be a code (sign, more than 3 digits after the point) is a parameter
        ("M900 K0.02 M0.125481", ["M900"]),  # PrusaSlicer/BambuStudio
        ("G1 X1 M-1", ["G1"]),
        ("G1 X1 M0.5", ["G1", "M0.5"]),  # (could be a sub-code: a command)
        ("G28.140 D0 M0.0001", ["G28.14"]),
        # ... and so is a letter the command takes by the firmware sources (BambuStudio profiles, Prusa-Firmware-Buddy)
        ("M900 L1000.0 M1.0", ["M900"]),  # Bambu: not M900 then an M1 stop
        ("M1006 A0 B0 L0 C0 D0 M100 E0 F0 N0", ["M1006"]),
        ("M970 Q1 A7 B30 C80 H15 K0 M20 O3", ["M970"]),
        ("M959 KM G1", ["M959"]),  # Prusa Buddy
        ("G80 M5", ["G80", "M5"]),  # CNC: two commands
        ("G91 G1 Z5 G90", ["G91", "G1", "G90"]),
        ("M3 S1000 M8", ["M3", "M8"]),
    ],
)
def test_grammar_accepts(raw, codes):
    parsed = parse(raw)
    assert parsed.kind != "error", parsed.issues
    assert not [i for i in parsed.issues if i.code == "SX001"], parsed.issues
    assert [c.code for c in parsed.commands] == codes
    roundtrip(raw)


def test_word_kinds_and_values():
    cmd = parse('G1 X10 Y"a" Z[#1] A#2 E1:2 B T?').commands
    kinds = {w.letter: w.kind for w in cmd[0].words}
    assert kinds == {"X": "number", "Y": STRING, "Z": EXPRESSION, "A": PARAMETER, "E": LIST, "B": FLAG, "T": QUERY}
    g1 = cmd[0]
    assert g1.get("X") == 10.0 and g1.raw("Y") == '"a"' and g1.params["B"] is None
    assert parse("T?").commands[0].word.kind == QUERY


def test_command_kinds():
    assert parse("M117 hi").commands[0].kind == TEXT
    assert parse("SET_X A=1").commands[0].kind == EXTENDED
    assert parse("echo hi").commands[0].kind == META
    assert parse("o1 sub").commands[0].kind == OWORD
    assert parse("#1=2").commands[0].kind == ASSIGNMENT
    assert parse("X10 Y20").commands[0].kind == IMPLICIT
    assert parse("G1 X1").commands[0].kind == GCODE


def test_text_command_reads_plain_words_as_parameters():
    m486 = parse("M486 S3").commands[0]
    assert m486.kind == TEXT and m486.get("S") == 3
    assert parse("M115 U3.11.0").commands[0].params == {}


@pytest.mark.parametrize(
    "raw,code",
    [
        ("G1 X10 Y20 )", "SX001"),
        ("G1 X1 X2", "SX002"),
        ("G0 X10 (clamp", "SX005"),
        ("G1 X1.2.3", "SX006"),
        ("G1 X--1", "SX006"),
        ("G1 X\u0661\u0660 Y5", "SX006"),  # Arabic-Indic digits: Python reads them as numbers, no firmware does
        ("M109 T0 S\u0662\u0660\u0660", "SX006"),
        ("G1 0.200 F10000", "SX007"),
        ("G1 X1 *12 Y2", "SX001"),  # checksum not at the end
        ("M", "SX001"),
    ],
)
def test_syntax_issues(raw, code):
    assert code in {i.code for i in parse(raw).issues}
    assert code in {i.code for i in parse_line(raw).issues}
    roundtrip(raw)


def test_codes_are_normalised():
    assert normalize_code("g", "01") == "G1"
    assert normalize_code("M", "862.30") == "M862.3"
    assert normalize_code("T", "-1") == "T-1"
    assert normalize_code("G", "1.") == "G1"
    assert normalize_code("G", "9" * 5000).startswith("G9")  # no int() of huge text


def test_numbers():
    assert to_number("-.5") == -0.5
    assert to_number("10.") == 10.0
    assert to_number("1e5") is None  # G-code has no exponents ("1e5" is the words 1 and E5)
    assert to_number("nan") is None and to_number("inf") is None
    assert to_number("9" * 5000) is None  # overflows to inf: not a finite number
    assert to_number("0x0b") == 11.0


# -- the fast path gives the same tree as the grammar -------------------------------------------------------

_num = st.builds(
    lambda sign, whole, dot, frac: sign + whole + dot + frac,
    st.sampled_from(["", "-", "+"]),
    st.sampled_from(["", "0", "1", "12", "007", "300"]),
    st.sampled_from(["", "."]),
    st.sampled_from(["", "5", "25", "000"]),
).filter(lambda s: any(c.isdigit() for c in s))
_letter = st.sampled_from(list("GMTNXYZEFSPIJKRHTgmxyz"))
_sep = st.sampled_from(["", " ", "  ", "\t"])
_word = st.builds(lambda l, s, n: l + s + n, _letter, st.sampled_from(["", "", " "]), _num)
_tail = st.sampled_from(["", " ; comment", ";c", " (note)", "*12", " ; noqa: HY003", "  "])


@st.composite
def gcode_lines(draw):
    words = draw(st.lists(_word, min_size=0, max_size=6))
    seps = [draw(_sep) for _ in words]
    body = "".join(s + w for s, w in zip(seps, words, strict=True))
    return draw(st.sampled_from(["", " ", "/"])) + body + draw(_tail)


@settings(max_examples=1500, deadline=None)
@given(gcode_lines())
def test_fastpath_agrees_with_grammar_on_generated_lines(raw):
    fast = parse_fast(raw)
    slow = parse_slow(raw)
    if fast is not None:
        assert fast == slow, (raw, fast, slow)
    roundtrip(raw)


@pytest.mark.parametrize(
    "raw",
    ["M30", "M30 ", "M30\t; end", "M117", "  M117  ;(x)", "N10 M30", "N10  M030\t; c", "M0810", "M1002", "M23 ;"],
)
def test_a_free_text_code_alone_is_read_by_the_fast_path_as_the_grammar_reads_it(raw):
    fast = parse_fast(raw)
    assert fast is not None and fast.commands[0].kind == TEXT
    assert fast == parse_slow(raw)


@pytest.mark.parametrize("raw", ["M30.0", "M117 Hello", "M486 S1", "M30*12", "m30", "M+30"])
def test_a_free_text_code_with_anything_else_is_left_to_the_grammar(raw):
    assert parse_fast(raw) is None


@settings(max_examples=500, deadline=None)
@given(gcode_lines())
def test_a_word_asked_for_before_the_others_are_built_is_the_same_word(raw):
    # (Command.param builds one word of a fast-path command, not all of them)
    lazy, built = parse_fast(raw), parse_slow(raw)
    if lazy is None:
        return
    for mine, theirs in zip(lazy.commands, built.commands, strict=True):
        for letter in "XYZEFSTPGM":
            word, expected = mine.param(letter), theirs.param(letter)
            assert word == expected
            if word is not None:
                assert (word.column, word.end_column) == (expected.column, expected.end_column)


@settings(max_examples=500, deadline=None)
@given(st.text(alphabet=st.characters(blacklist_categories=("Cs",), blacklist_characters="\r\n"), max_size=60))
def test_any_text_parses_without_raising_and_roundtrips(raw):
    parsed = parse_line(raw)
    assert Line(1, raw, "\n", parsed).render() == raw + "\n"


# -- the streaming reader ----------------------------------------------------------------------------------


def _lines(data: bytes) -> list[tuple[str, str]]:
    return list(Source(io.BytesIO(data), "t").lines())


@pytest.mark.parametrize(
    "data",
    [
        b"G1 X1\nG1 X2\n",
        b"G1 X1\r\nG1 X2\r\n",
        b"G1 X1\rG1 X2\r",
        b"G1 X1\nG1 X2\r\nG1 X3\rG1 X4",  # mixed, no final newline
        b"\xef\xbb\xbfG1 X1\n",  # UTF-8 BOM
        b"G1 X1 ; caf\xe9 latin-1\n",  # not UTF-8
        b"",
        b"   \n\n",
        "G1 X1 ; üñí\n".encode("utf-16"),  # UTF-16 with BOM
    ],
)
def test_source_roundtrip(data):
    source = Source(io.BytesIO(data), "t")
    out = [source.bom]
    for raw, ending in source.lines():
        out.append(source.encode(Line(1, raw, ending, parse_line(raw)).render()))
    assert b"".join(out) == data


def test_source_streams_in_chunks(monkeypatch):
    import gclint.syntax.source as src

    monkeypatch.setattr(src, "CHUNK", 7)
    monkeypatch.setattr(src, "HEAD", 5)
    data = b"G1 X1\r\nG1 X22\rG1 X333\nG1 X4444\r\n" * 5
    source = src.Source(io.BytesIO(data), "t")
    assert "".join(r + e for r, e in source.lines()).encode() == data


def test_crlf_split_across_chunks(monkeypatch):
    import gclint.syntax.source as src

    monkeypatch.setattr(src, "CHUNK", 6)
    monkeypatch.setattr(src, "HEAD", 6)
    data = b"G1 X1\r\nG1\r\n"
    assert src.Source(io.BytesIO(data), "t").lines().__next__() == ("G1 X1", "\r\n")
    assert list(src.Source(io.BytesIO(data), "t").lines()) == [("G1 X1", "\r\n"), ("G1", "\r\n")]


def test_split_lines():
    assert split_lines("a\nb\n") == [("a", "\n"), ("b", "\n")]
    assert split_lines("a\r\nb\rc\n") == [("a", "\r\n"), ("b", "\r"), ("c", "\n")]


@pytest.mark.parametrize(
    "data,what",
    [
        (b"GCDE\x01\x00\x00\x00", "binary G-code"),
        (b"\x89PNG\r\n\x1a\n", "PNG"),
        (b"\x00\x01\x02\x03" * 100, "binary data"),
    ],
)
def test_binary_is_refused(data, what):
    with pytest.raises(SourceError, match=what):
        Source(io.BytesIO(data), "t.gcode")


def test_missing_file_message():
    with pytest.raises(SourceError, match="no such file"):
        Source.open("/nonexistent/x.gcode")
