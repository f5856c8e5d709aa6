"""The translation reviewer's findings (review 27: A-F) and the explain/translate/diff items of the stranger review
of issue 24 (1.4, 1.5, 1.6, 1.9, sections 2 and 3), each as it must read now.  Facts from the LinuxCNC documentation
(https://linuxcnc.org/docs/html/gcode/overview.html, g-code.html, m-code.html) and the Carvera M-code table."""

from __future__ import annotations

import pytest

from gclint import dialects
from gclint.explain import explain_text
from gclint.syntax.parse import parse_line
from gclint.translate.words import has_expression

from .test_translate_tables import translate


def explained(text: str, dialect: str) -> str:
    return "\n".join(e.render() for e in explain_text(text, dialects.get(dialect)))


def codes_on(result, line: int) -> list[str]:
    return sorted(f.code for f in result.findings if f.line == line)


# -- A: an expression that starts with a function name is a computed value ----------------------------------------


@pytest.mark.parametrize(
    "line",
    [
        "G0 XSIN[30] Y1",
        "G0 X ABS[-4]",
        "G0 X EXISTS[#<_foo>]",
        "G0 X ATAN[1]/[2]",
        "G0 X-ROUND[2.5]",
        "G0 Y FIX[2.8]",
        "G0 Y FUP[2.8]",
        "G0 Y SQRT[4]",
        "G0 Y LN[4]",
        "G0 Y EXP[1]",
        "G0 Y ACOS[0]",
        "G0 Y ASIN[1]",
        "G0 Y COS[0]",
        "G0 Y TAN[45]",
        "G1 X cos[0] F100",
    ],
)
def test_a_function_value_is_untranslatable_and_explained_as_computed(line: str) -> None:
    out, result = translate("machinekit", f"G21 G90\nG0 X0 Y0 Z1\n{line}\nM2\n")
    assert line not in out
    assert "TR005" in codes_on(result, 3)
    text = explained(line, "machinekit")
    assert "a value computed when the line runs" in text and "(to X" not in text.replace(" (to X0", "")


def test_what_counts_as_a_computed_value() -> None:
    assert has_expression(parse_line("G0 X EXISTS[#<_foo>]").commands[0])
    assert not has_expression(parse_line('M118 S"a #1 b"').commands[0])
    assert not has_expression(parse_line("G1 X-2.5 Y.5").commands[0])
