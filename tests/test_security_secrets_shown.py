"""Issue 25: ``gclint explain -d reprap -e 'M551 Phunter2'`` and the editor's hover listed the password letter
by letter (an unquoted password is read as words: P, h, u, n, t, e, r2), and SX002 named the letters a password
repeats.  From a password on, explain and hover now show the rest of the command as one masked item, and SX002
does not name the letter.
"""

from __future__ import annotations

import json
import re

import pytest
from click.testing import CliRunner

from gclint import dialects
from gclint.cli import main
from gclint.engine import Linter, Options
from gclint.explain import explain_text


def _explain(*args: str) -> str:
    result = CliRunner().invoke(main, ["explain", *args])
    assert result.exit_code == 0, result.output
    return result.stdout


def test_explain_does_not_spell_out_a_password():
    out = _explain("-d", "reprap", "-e", "M551 Phunter2")
    assert "hunter2" not in out
    for letter in "HUNTER":
        assert f"{letter} value" not in out, out
    assert "R value: 2" not in out and "** r2" not in out and "** h " not in out, out
    payload = json.loads(_explain("-f", "json", "-d", "reprap", "-e", "M551 Phunter2"))
    assert [item["word"] for item in payload["commands"][0]["items"]] == ["P", "***"], payload


@pytest.mark.parametrize(
    "line, shown, hidden",
    [
        ('M587 S"home" P"pass word" X1 Y2', ['S"home"'], ["X1", "Y2", "pass", "word"]),
        ("M551 Pletmein S1", ["P"], ["S1", "letmein"]),
        ('M589 S"ap" Psecret99', ['S"ap"', "P"], ["secret99", "ecret99"]),
    ],
)
def test_the_rest_of_the_command_is_masked(line, shown, hidden):
    [exp] = explain_text(line, dialects.get("reprap"))
    words = [item.word for item in exp.items if item.word]
    assert words[: len(shown)] == shown and words[len(shown) :] == ["***"], words
    text = exp.render()
    for part in hidden:
        assert part not in text, (part, text)


def test_other_commands_of_the_line_are_explained():
    first, second = explain_text("G1 X5 M551 Phunter2", dialects.get("reprap"))
    assert [item.word for item in first.items if item.word] == ["X5"]
    assert [item.word for item in second.items if item.word] == ["P", "***"]


def test_hover_does_not_spell_out_a_password():
    analysis = pytest.importorskip("gclint.server.analysis")
    convert = pytest.importorskip("gclint.server.convert")
    from gclint.server.text import Snapshot

    for column in (1, 7, 9):  # on M551, on the password's first letter, inside it
        target = analysis.explain_at(Snapshot("G28\nM551 Phunter2\n"), 1, column, dialects.get("reprap"))
        assert target is not None
        for markdown in (True, False):
            text = convert.hover_text(target, markdown)
            assert "hunter2" not in text and "H value" not in text and "R value" not in text, text


@pytest.mark.parametrize(
    "line",
    [
        "M551 Pletmein",  # e repeated in the password
        'M587 S"home" Pssecret',  # s repeated in the password, and S as the network's word
        "M551 Pab A1",  # a: once in the password, once as a word after it
    ],
)
def test_sx002_does_not_name_a_letter_of_a_password(line):
    found = Linter(Options(dialect="reprap")).check_text(line + "\n", "job.gcode").findings
    repeated = [f for f in found if f.code == "SX002"]
    assert repeated, found
    for finding in repeated:
        assert "not named" in finding.message, finding.message
        assert re.search(r"\b[A-Za-z]\b (?:is repeated|appears more than once)", finding.message) is None


def test_sx002_still_names_letters_outside_a_password():
    found = Linter(Options(dialect="reprap")).check_text("G1 X1 X2 ; password = hunter2\n", "job.gcode").findings
    assert [f.message for f in found if f.code == "SX002"] == ["X appears more than once in G1"]
