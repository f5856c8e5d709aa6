"""Every report format is registered everywhere a format is named (CONTRIBUTING.md, "Adding a report format"):
a writer (``formats()``) and a file-by-file ``Report`` (``reports()``) under the same name, a line in
``--format``'s help, and a row in the format tables of README.md and docs/entry-points.md.  What every format
must do with the findings (the same findings, secrets masked, file text escaped, written file by file) is
checked by the tests that go over ``formats()``: tests/test_security.py, test_secrets_review.py,
test_run_bounds.py, test_bad_input.py, test_cache.py.
"""

from __future__ import annotations

import re

import pytest
from click.testing import CliRunner

from gclint.cli.app import main
from gclint.reports import MACHINE_FORMATS, formats, reports

from .conftest import ROOT

ALIASES = {"concise": "text"}  # names documented on their format's row


def test_every_writer_has_its_report() -> None:
    assert sorted(formats()) == sorted(reports()), "formats() and reports() must name the same formats"
    assert set(formats()) >= MACHINE_FORMATS


def _help() -> str:
    result = CliRunner().invoke(main, ["check", "--help"], terminal_width=200)
    assert result.exit_code == 0, result.output
    return " ".join(result.output.split())


@pytest.mark.parametrize("name", sorted(set(formats()) - set(ALIASES)))
def test_every_format_is_documented(name: str) -> None:
    assert re.search(rf"\b{name}\b", _help()), f"--format's help does not name {name} (gclint/cli/check.py)"
    for doc in ("README.md", "docs/entry-points.md"):
        text = (ROOT / doc).read_text(encoding="utf-8")
        assert re.search(rf"^\| `{name}`", text, re.MULTILINE), f"{doc}: no row for the {name} format"
