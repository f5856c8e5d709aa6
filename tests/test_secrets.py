"""gclint.secrets: what the masking finds (most cases are in test_security*.py, through the outputs)."""

from __future__ import annotations


def test_blanks_a_job_may_hide_the_equals_sign_with() -> None:
    """NBSP or a zero-width space around "=" hid the password from SC006 and from every mask."""
    from gclint.secrets import mask

    for text in ("; printhost_password\u00a0=\u00a0ZQXnb1 ZQXnb2", "; printhost_password\u200b= ZQXzw3"):
        assert "ZQX" not in mask(text), text
