"""Hostile jobs from a second attacker review that passed the gate with exit 0; each case failed before the fix.

1. Characters a firmware edits before it parses the line: Marlin's backspaces (src/gcode/queue.cpp
   ``process_stream_char``), Klipper's ``line.strip()`` and ``upper()`` (U+017F to S, U+00A0 and U+3000
   trimmed), other control characters (erased or dropped): the SC rules read each firmware's view of the
   line and report on the line as written, naming the view.
2. Lines the grammar refuses are read the same way, so a job that switches SX001 off hides nothing.
3. Smoothieware/Carvera runs every G and M of a line (research/firmware_codes.md section 8): each dangerous
   command after the first is reported.
4. M928 (SD logging into a named file), M997/M936 (firmware update), M505 (system folder): SC005.
5. SHELL with fillers (tatweel, braille blank, Hangul filler) or letters of other scripts (Cyrillic ЅНЕLL,
   small capitals ꜱʜᴇʟʟ) after M0/M792: SC001, and the translator's guard reads it the same way.
"""

from __future__ import annotations

import json

from gclint.engine import Linter, Options

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


# -- 4. firmware and logging files ----------------------------------------------------------------------------


def test_firmware_update_logging_and_system_folder(tmp_path):
    proc, found = _check(tmp_path, "r7.gcode", b";FLAVOR:Marlin\nG28\nM928 auto0.g\nM997\nM84\n")
    assert proc.returncode == 1 and {(3, "SC005"), (4, "SC005")} <= {(f["line"], f["code"]) for f in found}
    proc, found = _check(tmp_path, "r8.g", b'; gclint: dialect=reprap\nG28\nM505 P"evil"\nM997 S0\n')
    assert proc.returncode == 1 and {(3, "SC005"), (4, "SC005")} <= {(f["line"], f["code"]) for f in found}
    assert {f.code for f in _findings("G28\nM936\nM84\n")} == {"SC005"}
    assert _findings("G28\nM928\nM84\n") == []  # no file named
