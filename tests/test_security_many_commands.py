"""Issue 25: many commands on one line.  ``M0 `` 33,000 times on one line took about 60 s: each M0 made the
security rules read the rest of the line again (and ``gclint explain`` and the editor's hover did the same).
The rules now read each code's text once per line, and Smoothieware's split of a line is read for at most
SEGMENT_LIMIT commands, with one finding for the rest.  These tests count the characters read, not seconds
(bench/bench_many_commands.py measures the time).
"""

from __future__ import annotations

import pytest

from gclint import dialects, secrets
from gclint.engine import Linter, Options
from gclint.explain import explain_text, jobflow
from gclint.rules.security import actions, views

LINE = "M0 " * 5_000  # (15,000 characters: 5,000 commands that each read the rest of the line made 37 million)


@pytest.fixture
def characters_read(monkeypatch):
    """The characters the SHELL and action readers are handed, in total."""
    read = {"chars": 0}

    def counting(function):
        def wrapper(text, *args, **kwargs):
            read["chars"] += len(text)
            return function(text, *args, **kwargs)

        return wrapper

    monkeypatch.setattr(actions, "shell_offsets", counting(actions.shell_offsets))
    monkeypatch.setattr(actions, "host_actions", counting(actions.host_actions))
    return read


def test_the_security_rules_read_a_line_of_commands_once(characters_read):
    Linter(Options(select=["SC"])).check_text(LINE + "\n", "job.gcode")
    assert characters_read["chars"] <= 4 * len(LINE), characters_read


def test_a_line_of_m792_with_shell_at_its_end_is_reported_once():
    found = Linter(Options(select=["SC"])).check_text("M792 " * 5_000 + "; SHELL C:\\x.exe\n", "job.gcode").findings
    assert [f.code for f in found] == ["SC001"], found


@pytest.fixture
def explain_reads(monkeypatch):
    """The characters explain hands the secret finder and the SHELL reader, in total (every line searched)."""
    read = {"chars": 0}

    def counting(function):
        def wrapper(text):
            read["chars"] += len(text)
            return function(text)

        return wrapper

    monkeypatch.setattr(secrets, "find", counting(secrets.find))
    monkeypatch.setattr(secrets, "may_hold", lambda text: True)
    monkeypatch.setattr(jobflow, "shell_offsets", counting(jobflow.shell_offsets))
    cached = getattr(jobflow, "_actions", None)
    if cached is not None:
        cached.cache_clear()
    return read


def test_explain_reads_the_line_once(explain_reads):
    line = LINE + "; SAY hello"  # (a line no other test explains)
    out = explain_text(line, dialects.get("hyrel"))
    assert len(out) == 5_000 and all(e.masked() is e for e in out)  # (masked once, by the walk)
    assert explain_reads["chars"] <= 3 * len(line), explain_reads


def test_the_hover_reads_the_line_once(explain_reads):
    analysis = pytest.importorskip("gclint.server.analysis")
    from gclint.server.text import Snapshot

    line = LINE + "; BEEP"
    target = analysis.explain_at(Snapshot(line + "\n"), 0, len(LINE) - 2, dialects.get("hyrel"))
    assert target is not None and target.explanation.code == "M0"
    assert explain_reads["chars"] <= 3 * len(line), explain_reads


SEGMENT_LIMIT = getattr(views, "SEGMENT_LIMIT", 1_000)


def _line_of(count: int) -> str:
    return "G4 " + "".join(f"M30 /f{i}.gco " for i in range(count))


def test_smoothieware_commands_past_the_limit_are_one_finding():
    text, more = views._views(_line_of(SEGMENT_LIMIT + 5))
    assert more and len([view for view in text if view[0] == views.SMOOTHIE_VIEW]) == SEGMENT_LIMIT
    found = Linter(Options(select=["SC"])).check_text(_line_of(SEGMENT_LIMIT + 5) + "\n", "job.gcode").findings
    cut = [f for f in found if "commands after its first" in f.message]
    assert cut and all(f.severity.label == "error" for f in cut), [f.message for f in found]
    assert sorted(f.code for f in cut) == sorted({f.code for f in cut}) and "SC005" in {f.code for f in cut}
    found = Linter(Options(select=["SC005"])).check_text(_line_of(SEGMENT_LIMIT + 5) + "\n", "job.gcode").findings
    assert [f.line for f in found if "commands after its first" in f.message] == [1]  # (one per rule selected)


def test_repeated_commands_are_read_once_and_count_once():
    assert views._views("G4 " + "M30 /a.gco " * (SEGMENT_LIMIT + 5))[1] is False
    found = Linter(Options(select=["SC"])).check_text(_line_of(SEGMENT_LIMIT - 1) + "\n", "job.gcode").findings
    assert not [f for f in found if "commands after its first" in f.message]
    assert found and {f.code for f in found} == {"SC005"}


def test_many_shell_actions_on_one_line_are_ten_findings_and_one_for_the_rest():
    # (each SHELL was read to the end of the line: quadratic on a line of 95,000; now ten, then one finding)
    from gclint.engine import Linter, Options

    text = "M792 " + "; SHELL x " * 2000 + "\n"
    found = [f for f in Linter(Options(select=["SC001"])).check_text(text, "a.gcode").findings]
    assert len(found) == 10, [f.message for f in found]
    assert sum("1991 more SHELL actions follow on this line" in f.message for f in found) == 1
