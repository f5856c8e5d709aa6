"""Hypothesis strategies for G-code: lines of every dialect, valid and garbage, and whole files as bytes.

Importing this module registers the settings profiles and loads the one named by ``GCLINT_HYPOTHESIS``:

* ``default``: 200 examples per property (the normal test run stays fast);
* ``ci``: 1,000 examples;
* ``thorough``: 10,000 examples (``GCLINT_HYPOTHESIS=thorough python -m pytest tests/test_properties.py``).

Deadlines are off: the first lark parse of a session builds the grammar, and a loaded CI machine is slow.
"""

from __future__ import annotations

import os

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

_COMMON = dict(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.register_profile("default", max_examples=200, **_COMMON)
settings.register_profile("ci", max_examples=1000, **_COMMON)
settings.register_profile("thorough", max_examples=10_000, **_COMMON)
settings.load_profile(os.environ.get("GCLINT_HYPOTHESIS", "default"))

DIALECTS = ("hyrel", "hyrel-v4", "marlin", "reprap", "machinekit", "carvera")
PRINTERS = ("30m", "esr", "ehr", "16a", "16a-dual")
ENDINGS = ("\n", "\r\n", "\r")

# -- pieces --------------------------------------------------------------------------------------------------

_digits = st.text(alphabet="0123456789", min_size=1, max_size=6)


@st.composite
def numbers(draw) -> str:
    """A valid G-code number: optional sign, digits with at most one dot (``-.5``, ``10.``, ``007``)."""
    sign = draw(st.sampled_from(["", "", "-", "+"]))
    if draw(st.integers(0, 60)) == 0:  # valid but absurd: no int() or float() on it may raise
        return sign + "9" * draw(st.integers(300, 5000))
    shape = draw(st.integers(0, 3))
    if shape == 0:
        return sign + draw(_digits)
    if shape == 1:
        return sign + draw(_digits) + "." + draw(st.text(alphabet="0123456789", max_size=5))
    if shape == 2:
        return sign + "." + draw(_digits)
    return sign + draw(st.sampled_from(["0", "1", "10", "200", "0.4", "255", "1.75"]))


def bad_numbers() -> st.SearchStrategy[str]:
    """Values that are not G-code numbers, or are numbers no float can hold."""
    return st.one_of(
        st.sampled_from(
            ["1e309", "NaN", "nan", "inf", "--1", "1.2.3", "-", ".", "+-0", "1e5", "0x", "0xZZ", "1:2:", "::"]
        ),
        st.integers(300, 6000).map(lambda n: "9" * n),
        st.text(alphabet="0123456789.-+eE", min_size=1, max_size=12),
    )


def word(letters: str = "XYZEFSPIJKRHLTCDUOABQW", value=None) -> st.SearchStrategy[str]:
    """A letter and a number, with the spaces real files have (``X10``, ``x 10``, ``Y-.5``)."""
    return st.builds(
        lambda letter, gap, number: letter + gap + number,
        st.sampled_from(list(letters + letters.lower())),
        st.sampled_from(["", "", "", " "]),
        value if value is not None else numbers(),
    )


def comments() -> st.SearchStrategy[str]:
    return st.one_of(
        st.sampled_from(
            [
                ";",
                "; comment",
                ";TYPE:WALL-OUTER",
                ";LAYER:12",
                " (note)",
                "(MSG, hello)",
                "; noqa: HY003",
                "; gclint: disable=DL",
                "; gclint: enable",
                "(unclosed",
                ";;(;)",
            ]
        ),
        st.text(alphabet=st.characters(blacklist_characters="\r\n", blacklist_categories=("Cs",)), max_size=30).map(
            lambda t: "; " + t
        ),
        st.text(alphabet=st.characters(blacklist_characters="\r\n)", blacklist_categories=("Cs",)), max_size=20).map(
            lambda t: "(" + t + ")"
        ),
    )


@st.composite
def command_line(draw, codes: list[str], letters: str = "XYZEFSPT") -> str:
    """A code from ``codes`` with up to five parameter words, an optional N number and comment."""
    code = draw(st.sampled_from(codes))
    params = draw(st.lists(word(letters), max_size=5))
    seps = [draw(st.sampled_from([" ", " ", "", "\t", "  "])) for _ in params]
    line = code + "".join(s + p for s, p in zip(seps, params, strict=True))
    if draw(st.integers(0, 9)) == 0:
        line = f"N{draw(st.integers(0, 99999))} " + line
    if draw(st.booleans()):
        line += draw(st.sampled_from([" ", ""])) + draw(comments())
    return draw(st.sampled_from(["", "", "", " ", "/"])) + line


def checksummed(line: str) -> str:
    """``line`` with a correct RepRap ``*checksum``."""
    value = 0
    for byte in line.encode("utf-8", "surrogateescape"):
        value ^= byte
    return f"{line}*{value}"


# -- dialect lines ---------------------------------------------------------------------------------------------

_MOTION = ["G0", "G1", "G01", "g1", "G2", "G3", "G4", "G28", "G90", "G91", "G92", "G20", "G21"]

_HYREL = [
    "M104",
    "M109",
    "M140",
    "M190",
    "M191",
    "M106",
    "M107",
    "M221",
    "M229",
    "M6",
    "M660",
    "M620",
    "M621",
    "M700",
    "M703",
    "M721",
    "M722",
    "M756",
    "M3",
    "M5",
    "M30",
    "M0",
    "G81",
    "G10",
    "G54",
    "T0",
    "T1",
    "T12",
    "T40",
]
_HYREL_SPECIAL = [
    "M229 E1 D1",
    "M229 E1 D0",
    "M109 T40 S200",
    "M109 T0 S200 H5 L10",
    "M6 T12 O2 Z1.5",
    "M703 T14 S12",
    "M792 ; SAY done ; BEEP",
    "M0 ; PIC C:\\mr_ed.png",
    "M660 H1 Z0.2",
    "G1 X10 H1",
    "M106 C255",
    "M106 S50",
]
_MARLIN = [
    "M82",
    "M83",
    "M104",
    "M109",
    "M140",
    "M190",
    "M106",
    "M107",
    "M84",
    "M204",
    "M205",
    "M201",
    "M203",
    "M220",
    "M221",
    "M900",
    "G29",
    "G10",
    "G11",
    "T0",
    "T1",
    "M600",
]
_MARLIN_SPECIAL = [
    "M117 Printing...",
    "M118 E1 hello",
    'M862.3 P "MK3S"',
    "M115 U3.11.0",
    "M23 file.gco",
    "M24",
    "SET_FAN_SPEED FAN=part SPEED=0.5",
    "EXCLUDE_OBJECT_DEFINE NAME=a",
    "M486 S1",
    "M708 A0x0b X5",
    "G0X0Y0S12000M3",
    "M109 R215",
    "T?",
    "M555 P2",
    "; printhost_apikey = ",
    ";FLAVOR:Marlin",
]
_REPRAP = ["M563", "M568", "G10", "M584", "M350", "M92", "M906", "M574", "M558", "M98", "T-1", "T0", "M116"]
_REPRAP_SPECIAL = [
    'M98 P"homeall.g"',
    "if {move.axes[0].homed}",
    "elif true",
    "else",
    "var x = 1",
    "set var.x = {var.x + 1}",
    "while iterations < 3",
    'echo "hello"',
    'abort "no"',
    "G1 X{move.axes[0].max - 5} F6000",
    "M584 E0.1:0.2",
    "G10 P0 R200 S210",
    'M587 S"net" P"pw"',
    "global g = 2",
    'M550 P"printer"',
]
_MACHINEKIT = [
    "G0",
    "G1",
    "G2",
    "G3",
    "G4",
    "G17",
    "G40",
    "G43",
    "G49",
    "G54",
    "G64",
    "G80",
    "G81",
    "M3",
    "M5",
    "M6",
    "M7",
    "M9",
    "M30",
    "M68",
    "M66",
]
_MACHINEKIT_SPECIAL = [
    "o100 if [#1 GT 2]",
    "o100 endif",
    "o<sub> call [1] [2]",
    "#<_x> = 2",
    "#1 = [#2 * 3]",
    "G1 X[#1+2] Y#<_x>",
    "(MSG, hello)",
    "%",
    "G4 P1",
    "O1000",
    "G1 X[SIN[30]] F[#<feed>]",
    "#[#501+100] = 0",
    "M68 E0 Q[#1]",
]
_CARVERA = ["G0", "G1", "G2", "G3", "G28", "G38.2", "M3", "M5", "M6", "M321", "M322", "M801", "M802", "M98", "M30"]
_CARVERA_SPECIAL = [
    "M1000",
    "M1000 ls /sd",
    "M98.1 L2 {gcodes/test.cnc}",
    "M98 P1001 L4",
    "#154",
    "G0X0Y0S12000M3",
    "M6 T3",
    "M32 gcodes/test.cnc",
    "M460 X25 L3",
]

_BY_DIALECT = {
    "hyrel": (_MOTION + _HYREL, _HYREL_SPECIAL, "XYZEFSPTHLUCDRO"),
    "hyrel-v4": (_MOTION + _HYREL, _HYREL_SPECIAL, "XYZEFSPTHLUCDRO"),
    "marlin": (_MOTION + _MARLIN, _MARLIN_SPECIAL, "XYZEFSPTR"),
    "reprap": (_MOTION + _REPRAP, _REPRAP_SPECIAL, "XYZEFSPTRHDIJK"),
    "machinekit": (_MACHINEKIT, _MACHINEKIT_SPECIAL, "XYZABCFSPQRIJKEDHL"),
    "carvera": (_CARVERA, _CARVERA_SPECIAL, "XYZABCFSPIJKRL"),
}


def dialect_line(dialect: str) -> st.SearchStrategy[str]:
    """A plausible line of ``dialect``: its commands with parameters, its special shapes, comments."""
    codes, special, letters = _BY_DIALECT[dialect]
    return st.one_of(
        command_line(codes, letters),
        st.sampled_from(special),
        comments(),
        st.sampled_from(["", " ", "\t"]),
        st.lists(word(letters), min_size=1, max_size=4).map(" ".join),  # implicit motion: X10 Y20
        command_line(codes, letters).map(checksummed),
    )


def garbage_line() -> st.SearchStrategy[str]:
    """Lines that are not G-code: random text from the G-code alphabet and beyond, undecodable bytes
    (as surrogates), broken numbers, unbalanced brackets, stray delimiters."""
    alphabet = st.one_of(
        st.sampled_from(list('GMTNXYZEFS0123456789.-+ \t;()[]{}#<>=*"%/:!?@^$_oOxbB')),
        st.characters(blacklist_characters="\r\n", blacklist_categories=("Cs",)),
        st.characters(min_codepoint=0xDC80, max_codepoint=0xDCFF),  # surrogateescape'd bytes
    )
    return st.one_of(
        st.text(alphabet=alphabet, max_size=80),
        st.builds(lambda c, v: c + v, st.sampled_from(["G1 X", "M104 S", "T", "N", "G", "X", "M"]), bad_numbers()),
        st.builds(
            lambda n, c: c * n, st.integers(1, 300), st.sampled_from(["(", "[", "{", '"', "#", "*", ";", "X", "O"])
        ),
        st.sampled_from(["G1 X1 )", "G1 X[1", "M117", "*", "N", "N10", "N10 *5", "G", "M", "if", "o", "#<", "{", "]"]),
    )


def any_line(dialect: str | None = None) -> st.SearchStrategy[str]:
    """A line of ``dialect`` (or of any dialect), sometimes garbage."""
    good = st.sampled_from(DIALECTS).flatmap(dialect_line) if dialect is None else dialect_line(dialect)
    return st.one_of(good, good, good, garbage_line())


# -- files -----------------------------------------------------------------------------------------------------


@st.composite
def gcode_text(draw, dialect: str | None = None, max_lines: int = 20) -> str:
    """A file's text: lines joined by random line endings (mixed within a file sometimes), with or without a
    final newline, sometimes with a header that names a dialect."""
    lines = draw(st.lists(any_line(dialect), max_size=max_lines))
    header = draw(
        st.sampled_from(
            [
                "",
                "",
                ";FLAVOR:Marlin",
                "; gclint: dialect=hyrel",
                "; generated by Repetrel",
                "; gcode_flavor = reprapfirmware",
                "M6 T0 O1",
                "M6 T12 O2",
            ]
        )
    )
    if header:
        lines.insert(0, header)
    if draw(st.integers(0, 4)) == 0:  # mixed endings
        endings = draw(st.lists(st.sampled_from(ENDINGS), min_size=len(lines), max_size=len(lines)))
    else:
        endings = [draw(st.sampled_from(ENDINGS))] * len(lines)
    if lines and draw(st.booleans()):
        endings[-1] = ""  # no final newline
    return "".join(line + ending for line, ending in zip(lines, endings, strict=True))


@st.composite
def gcode_bytes(draw, dialect: str | None = None) -> bytes:
    """A file's bytes: UTF-8 (sometimes with a BOM), latin-1 comments, stray undecodable bytes."""
    text = draw(gcode_text(dialect))
    data = text.encode("utf-8", "surrogateescape")
    if draw(st.integers(0, 4)) == 0:
        data = data.replace(b"; comment", "; caf\xe9 \xb0C".encode("latin-1"))
    if draw(st.integers(0, 5)) == 0:
        data += draw(st.binary(max_size=20)).replace(b"\x00", b"")
    if draw(st.integers(0, 4)) == 0:
        data = b"\xef\xbb\xbf" + data
    return data


def options_dicts() -> st.SearchStrategy[dict]:
    """Random ``Options`` keyword arguments: dialects, printers, loaded heads, selections."""
    return st.fixed_dictionaries(
        {},
        optional={
            "dialect": st.sampled_from(DIALECTS + ("auto", "hyrel-v5", "rrf")),
            "printer": st.sampled_from(PRINTERS),
            "loaded": st.frozensets(st.integers(0, 19), max_size=5),
            "select": st.sampled_from([["ALL"], ["SX"], ["HY", "SC"], ["DL"], ["ALL"]]),
            "ignore": st.sampled_from([[], ["HY0"], ["SX002"]]),
            "spindle_max_rpm": st.sampled_from([None, 12000.0, 24000.0]),
            "tool_map": st.sampled_from([{}, {0: 2, 1: 3}]),
        },
    )
