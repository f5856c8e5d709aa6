"""Hostile jobs from a second attacker review that passed the gate with exit 0; each case failed before the fix.

1. Characters a firmware edits before it parses the line: Marlin's backspaces (src/gcode/queue.cpp
   ``process_stream_char``), Klipper's ``line.strip()`` and ``upper()`` (U+017F to S, U+00A0 and U+3000
   trimmed), other control characters (erased or dropped): the SC rules read each firmware's view of the
   line and report on the line as written, naming the view.
2. Lines the grammar refuses are read the same way, so a job that switches SX001 off hides nothing.
3. Smoothieware/Carvera runs every G and M of a line (Smoothieware source, GcodeDispatch.cpp): each dangerous
   command after the first is reported.
4. M928 (SD logging into a named file), M997/M936 (firmware update), M505 (system folder): SC005.
5. SHELL with fillers (tatweel, braille blank, Hangul filler) or letters of other scripts (Cyrillic ЅНЕLL,
   small capitals ꜱʜᴇʟʟ) after M0/M792: SC001, and the translator's guard reads it the same way.
"""

from __future__ import annotations

import json

import pytest

from gclint.engine import Linter, Options
from gclint.rules.security import action_shell_column, firmware_views, shell_offsets
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line

from .conftest import run_cli


def _findings(text: str, dialect: str = "auto", path: str = "job.gcode") -> list:
    return [
        f for f in Linter(Options(dialect=dialect, select=["SC"])).check_text(text, path).findings if f.code[:2] == "SC"
    ]


def _check(tmp_path, name: str, data: bytes, *options: str):
    job = tmp_path / name
    job.write_bytes(data)
    proc = run_cli("check", "--no-cache", "-f", "json", *options, "--", str(job))
    return proc, json.loads(proc.stdout or b"[]")


# -- 1. characters a firmware edits ---------------------------------------------------------------------------


def test_marlin_backspaces_hide_a_command(tmp_path):
    data = (
        b";FLAVOR:Marlin\nG28\nM117 hello"
        + b"\x08" * 10
        + b"M30 /config.gco\nM117 hi"
        + b"\x08" * 7
        + b"M928 auto0.g\nM84\n"
    )
    proc, found = _check(tmp_path, "r1.gcode", data)
    assert proc.returncode == 1, proc.stderr
    by_line = {(f["line"], f["code"]) for f in found}
    assert {(3, "SC005"), (4, "SC005")} <= by_line, found
    line3 = next(f for f in found if f["line"] == 3)
    assert "read as Marlin reads backspaces" in line3["message"] and '"/config.gco"' in line3["message"]


def test_marlin_reading_follows_queue_cpp():
    views = dict((how, text) for how, text, _ in firmware_views("M17\x08\x0828 auto0.g ; x\x08"))
    marlin = [text for how, text in views.items() if how.startswith("read as Marlin")]
    assert marlin == ["M28 auto0.g "]  # (a backspace after ";" is not read: the comment is not queued)
    # a backslash takes the next character as it is: an escaped backspace still erases (process_stream_char)
    assert [t for h, t, _ in firmware_views("M3\\\x080 x") if h.startswith("read as Marlin")] == ["M0 x"]


@pytest.mark.parametrize(
    "line, code",
    [
        ("M17\x08\x0828 auto0.g", "SC005"),  # Marlin: M28 auto0.g
        ("M3\x070 /config.gco", "SC005"),  # a firmware that drops the bell reads M30 /config.gco
        ("M17\x7f\x7f28 x.g", "SC005"),  # DEL erasing like a backspace
        (";\x08M30 /x.gco", "SC005"),  # a reader that erases before it cuts the comment
        ("M117 x\x08\x08\x08\x08\x08\x08M0 ; SHELL calc.exe", "SC001"),
    ],
)
def test_control_characters_are_read_as_a_firmware_may(line, code):
    assert code in {f.code for f in _findings(f"G28\n{line}\nM84\n")}, line


def test_klipper_reading_and_lines_that_do_not_parse(tmp_path):
    text = (
        "; gcode_flavor = klipper\nG28\n; gclint: disable=SX001\nRUN_\u017fHELL_COMMAND CMD=evil\n"
        "\u00a0save_config\n\u3000sdcard_print_file FILENAME=x.gcode\nM84\n"
    )
    proc, found = _check(tmp_path, "r2.gcode", text.encode(), "--fail-on", "warning")
    assert proc.returncode == 1, proc.stderr
    codes = {(f["line"], f["code"]) for f in found}
    assert {(4, "SC001"), (5, "SC005"), (6, "SC004")} <= codes, found
    # the job's own configuration switching SX001 off changes nothing either
    (tmp_path / "gclint.toml").write_text('ignore = ["SX001"]\n')
    proc, found = _check(tmp_path, "r2.gcode", text.encode(), "--fail-on", "warning")
    assert proc.returncode == 1 and {(4, "SC001"), (5, "SC005"), (6, "SC004")} <= {
        (f["line"], f["code"]) for f in found
    }


@pytest.mark.parametrize(
    "line, code",
    [
        ("\u00a0M792 ; SHELL C:\\x.exe", "SC001"),  # Hyrel, a leading no-break space
        ("RUN_SHELL_COMMAND\u00a0CMD=x", "SC001"),  # a Klipper name starting a line the grammar refuses
        ("G4 P0 M1000 rm /sd/config.txt", "SC003"),  # Carvera: the M1000 after G4
        ("M17\b\b28 auto0.g", "SC005"),
        ("\u2003M30 /sys/config.g", "SC005"),
    ],
)
def test_lines_the_grammar_refuses_are_read(line, code):
    for dialect in ("auto", "marlin", "hyrel", "carvera", "reprap"):
        assert code in {f.code for f in _findings(f"G28\n{line}\nM84\n", dialect)}, (line, dialect)


def test_job_level_suppression_hides_nothing(tmp_path):
    data = "G28\n; gclint: disable=SX SC\n(gclint: disable=SX001)\n\u00a0M792 ; SHELL C:\\x.exe ; noqa\nM30\n"
    proc, found = _check(tmp_path, "s.gcode", data.encode())
    assert proc.returncode == 1 and any(f["code"] == "SC001" for f in found), (proc.stdout, proc.stderr)


def test_views_of_ordinary_lines():
    assert firmware_views("G1 X10 Y10 E0.5") == []
    assert firmware_views("M117 Printing G-code M30") == []  # M117 takes the rest of the line on Smoothieware
    assert firmware_views("; Grüße, Straße") == []  # only a comment
    assert _findings("M117 Grüße \u00a0\nG1 X1 ; ſhell\nM104 S200 T0\n; Привет\nM84\n") == []


# -- 3. several commands on one line --------------------------------------------------------------------------


def test_every_command_of_a_line_is_read(tmp_path):
    data = b"G28\nG0 X0 M502\nG0 X0 M500\nG0 X0 M504 x\nG0 X0 M98 P1234\nM2\n"
    proc, found = _check(tmp_path, "r3.nc", data, "--dialect", "carvera")
    assert proc.returncode == 1, proc.stderr
    assert {(f["line"], f["code"]) for f in found} == {(2, "SC005"), (3, "SC005"), (4, "SC005"), (5, "SC004")}
    assert all("Smoothieware" in f["message"] for f in found)
    m502 = next(f for f in found if f["line"] == 2)
    assert m502["column"] > 6  # on the M502, not on the G0


def test_every_dangerous_command_of_a_line_is_reported():
    found = _findings("G28\nG0 X0 M502 M30 /config.gco\nM2\n", "carvera")
    messages = [f.message for f in found]
    assert any("M502" in m for m in messages) and any("/config.gco" in m for m in messages), messages


def test_dialect_exemptions_hold_in_every_view():
    assert _findings("G28\nG0 X0 M500\nM84\n", "marlin") == []  # Marlin's M500 is the EEPROM
    # a subprogram of the same file, defined above the call (else LinuxCNC looks for the file 1234.ngc first)
    assert _findings("o1234 sub\nG0 X1\no1234 endsub\nG0 X0 M98 P1234\nM2\n", "machinekit") == []


# -- 4. firmware and logging files ----------------------------------------------------------------------------


def test_firmware_update_logging_and_system_folder(tmp_path):
    proc, found = _check(tmp_path, "r7.gcode", b";FLAVOR:Marlin\nG28\nM928 auto0.g\nM997\nM84\n")
    assert proc.returncode == 1 and {(3, "SC005"), (4, "SC005")} <= {(f["line"], f["code"]) for f in found}
    proc, found = _check(tmp_path, "r8.g", b'; gclint: dialect=reprap\nG28\nM505 P"evil"\nM997 S0\n')
    assert proc.returncode == 1 and {(3, "SC005"), (4, "SC005")} <= {(f["line"], f["code"]) for f in found}
    assert {f.code for f in _findings("G28\nM936\nM84\n")} == {"SC005"}
    assert _findings("G28\nM928\nM84\n") == []  # no file named


# -- 5. SHELL lookalikes --------------------------------------------------------------------------------------

LOOKALIKES = [
    "SH\u0640ELL",  # Arabic tatweel
    "SH\u2800ELL",  # braille blank
    "S\u3164HELL",  # Hangul filler
    "SHE\u07faLL",  # NKo lajanyalan
    "\u0405\u041d\u0415LL",  # Cyrillic
    "\u0455\u04bb\u0435\u04cf\u04cf",  # Cyrillic small letters
    "\u0405\u0397\u0395LL",  # Cyrillic S, Greek Eta and Epsilon
    "\ua731\u029c\u1d07\u029f\u029f",  # small capitals
    "\U0001d412\U0001d407\U0001d404\U0001d40b\U0001d40b",  # mathematical bold
    "\uff33\uff28\uff25\uff2c\uff2c",  # full-width
]


@pytest.mark.parametrize("word", LOOKALIKES)
def test_shell_lookalikes(tmp_path, word):
    assert shell_offsets(f" ; {word} C:\\x.exe") == [3]
    line = f"M792 ; {word} C:\\x.exe"
    assert action_shell_column(Line(2, line, "\n", parse_line(line))) == 8  # the translator's guard
    proc, found = _check(tmp_path, "r6.gcode", f"G28 X0 Y0\n{line}\nM30\n".encode())
    assert proc.returncode == 1 and [f["code"] for f in found if f["code"].startswith("SC")] == ["SC001"], found


def test_shell_lookalikes_are_not_read_into_words():
    assert shell_offsets(" ; Sheila changes the filament") == []
    assert shell_offsets(" ; shelf") == []


def test_translator_guard_reads_firmware_views():
    for line in ("\u00a0M792 ; SHELL C:\\x.exe", "M117 x\x08\x08\x08\x08\x08\x08M0 ; SHELL x"):
        assert action_shell_column(Line(1, line, "\n", parse_line(line))) is not None, line


def test_translator_guard_passes_lines_an_action_hides_in():
    """The guard's quick filter lets through lines where M0/M792 shows only after a firmware edits the line
    (backspaces), so the translation is refused."""
    from gclint.translate.engine import HostActionGuard, TranslationResult

    for text in ("G1 X1\nM17\x08\x080 ; SHELL x\n", "\u00a0M792 ; SHELL C:\\x.exe\n"):
        result = TranslationResult("job.gcode", "marlin", "hyrel")
        HostActionGuard(result).check(text)
        assert result.refused, text


def test_an_invisible_format_character_before_the_code_hides_nothing(tmp_path):
    """A BOM or zero-width space mid-file (files joined with cat) turned the line into SX001 only, which the
    job switched off."""
    job = tmp_path / "z.gcode"
    job.write_text("; gclint: disable=SX001\nG28 X0 Y0\n\ufeffM792 ; SHELL C:\\x.exe\n\u200bM30 /config.gco\nM30\n")
    proc = run_cli("check", "--no-cache", str(job))
    out = proc.stdout.decode()
    assert proc.returncode == 1 and "3:9: SC001" in out and "4:1: SC005" in out, out  # (3:9: the SHELL itself)
    assert "invisible format characters" in out


def test_a_console_line_behind_a_control_character_is_read(tmp_path):
    """ "\\x01rm /sd/config.txt": a firmware that drops control characters runs a console command (SC003),
    and the job had switched off SX001, the only finding left."""
    job = tmp_path / "d1.nc"
    job.write_bytes(b"; gclint: disable=SX001\nG28 X0 Y0\n\x01rm /sd/config.txt\n\x7fplay /sd/gcodes/evil.cnc\nM30\n")
    proc = run_cli("check", "--no-cache", str(job))
    out = proc.stdout.decode()
    assert proc.returncode == 1 and "3:1: SC003" in out and "4:1: SC003" in out, out
