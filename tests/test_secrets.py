

def test_blanks_a_job_may_hide_the_equals_sign_with() -> None:
    """NBSP or a zero-width space around "=" hid the password from SC006 and from every mask."""
    from gclint.secrets import mask

    for text in ("; printhost_password\u00a0=\u00a0ZQXnb1 ZQXnb2", "; printhost_password\u200b= ZQXzw3"):
        assert "ZQX" not in mask(text), text
