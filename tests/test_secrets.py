"""gclint.secrets: what the masking finds (most cases are in test_security*.py, through the outputs)."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st


def test_blanks_a_job_may_hide_the_equals_sign_with() -> None:
    """NBSP or a zero-width space around "=" hid the password from SC006 and from every mask."""
    from gclint.secrets import mask

    for text in ("; printhost_password\u00a0=\u00a0ZQXnb1 ZQXnb2", "; printhost_password\u200b= ZQXzw3"):
        assert "ZQX" not in mask(text), text


_PIECES = [
    "M551 P",
    'M0587 S"net" P',
    "m589 P'",
    "M511 P",
    "M0512 S",
    "M586.4 K",
    "M5510 P",
    "; LINE_WIDTH: 0.551177",
    "; flush_volumes_matrix = 0,587,589",
    "586",
    "m51",
    "hunter2",
    '"x y"',
    " ",
    ";",
    "\n",
    "X1.551",
    "pass",
    "word = ",
    "ſ",
    "K",
    "0",
    "ABCDEF0123456789ABCDEF0123456789",
]


@given(st.lists(st.sampled_from(_PIECES), max_size=10))
def test_may_hold_is_true_wherever_find_finds_a_secret(pieces) -> None:
    # (may_hold looks for the password codes themselves where only their digits hint at one: Cura writes
    # thousands of "; LINE_WIDTH: 0.551177" lines)
    from gclint.secrets import find, may_hold

    text = "".join(pieces)
    if find(text):
        assert may_hold(text), text
    lines = text.split("\n")
    if any(may_hold(line) for line in lines):  # (a comment hint: true of the lines joined when true of one)
        assert may_hold("\n".join(lines)), text


def test_the_digits_of_a_password_code_alone_hold_no_secret() -> None:
    from gclint.secrets import may_hold

    assert not may_hold("; LINE_WIDTH: 0.551177") and not may_hold("G1 X5.587 Y1.589")
    assert may_hold("M551 Phunter2") and may_hold("; m0587 P") and may_hold("M586.4")
    assert may_hold("; \u017fecret 551")  # (outside ASCII: no shortcut)
