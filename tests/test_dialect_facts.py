"""Every dialect states, in this file, what its machine does with the lines a new dialect most often gets
wrong, with the page that says so; its ``Semantics`` must agree (CONTRIBUTING.md, "Adding a dialect").

A dialect drafted from another one inherits that one's readings silently: a CNC dialect copied from Marlin
read ``G4 P0.5`` as half a millisecond and called its feed moves "printing", with every other test green.
So a dialect without a row here fails, and so does one whose semantics say something else than its row.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import pytest

from gclint.dialects import all_dialects
from gclint.dialects.base import Dialect


@dataclass(frozen=True)
class Facts:
    g4_p: float | None  # seconds one unit of G4 P lasts (0.001: milliseconds; None: P is not a time)
    g4_s: float | None  # seconds one unit of G4 S lasts (None: S is not a time)
    extruder: str | None  # the word that drives the extruder (None: nothing extrudes)
    working: str  # "extrudes" (a working move deposits) or "feeds" (every feed move cuts: CNC)
    tool_select: str  # what T<n> does: "address", "extruder" (changes tool), "prepare" (for the next M6)
    source: str  # where the page says so (docs/sources.md names each)


FACTS = {
    "hyrel": Facts(0.001, 1.0, "E", "extrudes", "address", "Hyrel Gcode page, G4 Timed Pause, G1 Working Move; T_v5"),
    "hyrel-v4": Facts(0.001, 1.0, "E", "extrudes", "address", "as hyrel; T_v4"),
    "marlin": Facts(0.001, 1.0, "E", "extrudes", "extruder", "Marlin G-code reference, G4 and T"),
    "reprap": Facts(0.001, 1.0, "E", "extrudes", "extruder", "Duet G-code dictionary, G4 and T"),
    "machinekit": Facts(
        1.0, None, "A", "feeds", "prepare", "LinuxCNC docs, G4 Dwell (P seconds), T; Machinekit-FDM remap (A axis)"
    ),
    "carvera": Facts(1.0, 1.0, None, "feeds", "prepare", "Carvera G-code table, G4; Smoothieware Robot.cpp G4"),
    "generic": Facts(None, None, "E", "extrudes", "extruder", "gclint's own reading of an unknown dialect"),
}


def _facts(dialect: Dialect) -> Facts:
    s = dialect.semantics
    return Facts(s.dwell.p_seconds, s.dwell.s_seconds, s.extruder, s.working, s.tool_select, "")


def test_every_dialect_states_its_facts() -> None:
    missing = [d.name for d in all_dialects() if d.name not in FACTS]
    assert not missing, (
        f"dialects with no row in tests/test_dialect_facts.py FACTS: {missing}.  Add one with what the "
        "machine's documentation says G4 P and S count, which word extrudes, whether a feed move prints or "
        "cuts, and what T does (CONTRIBUTING.md, 'Adding a dialect')"
    )
    assert not set(FACTS) - {d.name for d in all_dialects()}, "rows for dialects that do not exist"


@pytest.mark.parametrize("dialect", all_dialects(), ids=lambda d: d.name)
def test_the_semantics_say_what_the_row_says(dialect: Dialect) -> None:
    stated = FACTS.get(dialect.name)
    if stated is None:
        pytest.skip("no row (test_every_dialect_states_its_facts fails)")
    actual = _facts(dialect)
    wrong = [
        f"{f.name}: the semantics say {getattr(actual, f.name)!r}, the row ({stated.source}) says "
        f"{getattr(stated, f.name)!r}"
        for f in fields(Facts)
        if f.name != "source" and getattr(actual, f.name) != getattr(stated, f.name)
    ]
    assert not wrong, f"{dialect.name}: " + "; ".join(wrong)


@pytest.mark.parametrize("dialect", [d for d in all_dialects() if d.known], ids=lambda d: d.name)
def test_every_known_dialect_declares_its_own_semantics(dialect: Dialect) -> None:
    default = next(f for f in fields(Dialect) if f.name == "semantics").default_factory()  # type: ignore[misc]
    assert dialect.semantics is not default, (
        f"{dialect.name}: no semantics= (it reads lines as an unknown dialect does): declare a Semantics "
        "(gclint/dialects/semantics.py) with its machine's facts"
    )
    s = dialect.semantics
    assert (s.extruder is None) <= (s.working == "feeds"), f"{dialect.name}: nothing extrudes, yet moves print"
