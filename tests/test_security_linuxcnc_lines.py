"""Issue 25 (found by a stranger's attack): LinuxCNC reads lines as C's fgets does, so only a line feed ends a line
(src/emc/rs274ngc/interp_read.cc read_text); interp_internal.cc close_and_downcase drops a carriage return outside
a comment and keeps one inside, where convert_comment steps over it as white space.  And a subroutine defined
inside a block that may not run (an ``if``, a loop, another subroutine) is not defined above a call."""

from __future__ import annotations

import pytest

from gclint.engine import Linter, Options


def _found(text: str, dialect: str = "machinekit") -> list[tuple[int, str]]:
    result = Linter(Options(dialect=dialect, select=["SC"])).check_text(text, "job.ngc")
    return [(f.line, f.code) for f in result.findings]


@pytest.mark.parametrize("dialect", ["machinekit", "marlin", "hyrel", "auto"])
@pytest.mark.parametrize(
    "text,expected",
    [
        ("G0 X0\n(\rlogopen,/home/cnc/.bashrc)\nM2\n", [(3, "SC005")]),
        ("G0 X0\n(\r\rLOGOPEN,/x)\nM2\n", [(4, "SC005")]),
        ("G0 X0\n( \rpy,import os)\nM2\n", [(3, "SC001")]),
        ("G0 X0\no<evil>\rcall\nM2\n", [(3, "SC004")]),
        ("G0 X0\no\r<evil> call\nM2\n", [(3, "SC004")]),
        ("G0 X0\no100\rcall\nM2\n", [(3, "SC004")]),
        ("G0 X0\n(\rLOGOPEN,/x)", [(3, "SC005")]),  # (no line feed at the end of the file)
        ("G0 X0\n(\rLOGOPEN,/x)\r", [(3, "SC005")]),  # (the file ends in the carriage return)
    ],
)
def test_a_bare_carriage_return_does_not_end_a_linuxcnc_line(text, expected, dialect):
    # (every dialect: a job that a LinuxCNC or Machinekit controller runs can claim any flavour)
    assert _found(text, dialect) == expected


def test_crlf_and_plain_comments_stay_quiet():
    assert _found("G0 X0\r\n(a comment)\r\nG1 X1\r\nM2\r\n") == []
    assert _found("G0 X0\r(a comment)\rG1 X1\rM2\r") == []  # (a classic Mac file: one long line for LinuxCNC)
    # a carriage return inside a comment is white space only at its start: "(a\rLOGOPEN,x)" is a plain comment
    assert _found("G0 X0\n(a\rLOGOPEN,/x)\nM2\n") == []


@pytest.mark.parametrize(
    "text",
    [
        "o1 if [0]\no<evil> sub\nG0 X1\no<evil> endsub\no1 endif\no<evil> call\nM2\n",
        "o<outer> sub\no<evil> sub\nG0 X1\no<evil> endsub\no<outer> endsub\no<evil> call\nM2\n",
        "o2 while [#1 LT 0]\no<evil> sub\no<evil> endsub\no2 endwhile\no<evil> call\nM2\n",
        "o3 do\no<evil> sub\no<evil> endsub\no3 while [0]\no<evil> call\nM2\n",
        "o1 if [0]\nO100\nG0 X1\nM99\no1 endif\nM98 P100\nM2\n",
        "O200\no<evil> sub\no<evil> endsub\nM99\no<evil> call\nM2\n",  # (inside a Fanuc-style subprogram)
    ],
)
def test_a_subroutine_defined_inside_a_block_is_not_defined_above_the_call(text):
    assert [code for _, code in _found(text)] == ["SC004"], _found(text)


@pytest.mark.parametrize(
    "text",
    [
        "o<prime> sub\nG0 Z5\no<prime> endsub\no<prime> call\nM2\n",
        "o1 if [1]\nG0 X1\no1 endif\no<prime> sub\no<prime> endsub\no<prime> call\nM2\n",
        "o3 do\nG0 X1\no3 while [0]\no<prime> sub\no<prime> endsub\no<prime> call\nM2\n",
        "o<Prime> sub\no<Prime> endsub\no<PRIME> call\nM2\n",
    ],
)
def test_a_subroutine_defined_at_the_top_level_above_the_call_is_quiet(text):
    assert _found(text) == []
