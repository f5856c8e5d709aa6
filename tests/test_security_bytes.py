"""Issue 25: bytes that are not UTF-8 hid SHELL.  ``M792 ; SH<0xAD>ELL C:\\x.exe`` (a Windows-1252 soft hyphen),
``SH<0x8A>ELL`` and a CESU-8 surrogate got an info only.  Repetrel is a Windows program: the SC rules read a
line with undecodable bytes as a reader that drops them may, and a line that is not ASCII as Windows-1252.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from gclint.cli import main
from gclint.engine import Linter, Options
from gclint.rules.security import firmware_views


def _check(tmp_path, data: bytes, name: str = "job.gcode") -> tuple[int, list[dict]]:
    job = tmp_path / name
    job.write_bytes(data)
    result = CliRunner().invoke(main, ["check", "--no-cache", "-f", "json", "--", str(job)])
    return result.exit_code, json.loads(result.stdout or "[]")


@pytest.mark.parametrize(
    "hidden",
    [
        b"SH\xadELL",  # the reproducer: a Windows-1252 soft hyphen
        b"SH\x8aELL",  # a byte a reader may drop (or read as the C1 control U+008A, as Latin-1 does)
        b"SH\xed\xa0\x80ELL",  # CESU-8: a surrogate encoded as UTF-8 bytes
        b"S\xffHELL",
    ],
)
def test_undecodable_bytes_do_not_hide_shell(tmp_path, hidden):
    code, found = _check(tmp_path, b"M792 ; " + hidden + b" C:\\x.exe\n")
    assert code == 1 and [f["code"] for f in found if f["code"].startswith("SC")] == ["SC001"], found


def test_a_utf8_letter_that_windows_1252_reads_as_e_and_a_soft_hyphen(tmp_path):
    """U+02ED is the bytes CB AD: Windows-1252 reads them as "Ë" and a soft hyphen, so SH\\u02edLL is SHELL."""
    code, found = _check(tmp_path, "M792 ; SH\u02edLL C:\\x.exe\n".encode())
    assert code == 1, found
    [shell] = [f for f in found if f["code"] == "SC001"]
    assert shell["message"].startswith("read as Windows-1252"), shell


def test_the_windows_1252_view():
    from gclint.rules.security.views import WINDOWS_1252_VIEW

    line = "M792 ; SH\udcadELL C:\\x.exe"  # (0xAD, undecodable as UTF-8: syntax/source.py surrogateescape)
    views = {how: text for how, text, _ in firmware_views(line)}
    assert views[WINDOWS_1252_VIEW] == "M792 ; SH\u00adELL C:\\x.exe"
    # the five bytes Python's cp1252 leaves undefined are Windows' C1 controls
    assert {how: text for how, text, _ in firmware_views("M0 ; \udc81\udc8d")}[WINDOWS_1252_VIEW] == "M0 ; \x81\x8d"
    assert WINDOWS_1252_VIEW not in {how for how, _, _ in firmware_views("; caf\udce9 cr\u00e8me")}  # no code


def test_an_undecodable_byte_inside_a_code_is_dropped_as_a_reader_may(tmp_path):
    code, found = _check(tmp_path, b"G28\nM3\xad0 /sys/config.g\nM84\n")
    assert code == 1 and (2, "SC005") in {(f["line"], f["code"]) for f in found}, found


@pytest.mark.parametrize(
    "text",
    [
        b"M117 Temp\xe9rature\nM84\n",  # Latin-1 text
        b"; caf\xe9 cr\xe8me\nG1 X1 ; \xe9t\xe9\nM0 ; SAY Gr\xfc\xdfe\n",
        "M117 Grüße, 温度\nM0 ; SAY Straße\n".encode(),
    ],
)
def test_ordinary_text_that_is_not_ascii_stays_quiet(text):
    found = Linter(Options(select=["SC"])).check_text(text.decode("utf-8", "surrogateescape"), "job.gcode").findings
    assert found == []
