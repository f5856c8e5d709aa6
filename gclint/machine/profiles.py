"""Hyrel printer models: head positions, axes and the aux devices each one has.

Sources: T_v5 "Using the T with the ESR and 30M / EHR and 16A / 16A (Dual Yoke)" for head positions;
Gcode page "G0 Rapid Move" note ("All Hyrel printers have built-in support for three axes. Hyrel model
16A and EHR printers may be expanded to five") for A/B; "Controlling Aux Devices" for which model has
which port (M671 30M/ESR only, M676 16A only, ...); "M253 Turn On Lathe" (16A only); "M660" (EHR needs
G28 Z0); "Controlling Temperature" for the second bed ("our Hydra models have room to have a second
hotbed": the 16A; the pages give the other models none).
"""

from __future__ import annotations

from dataclasses import dataclass


def a_model(name: str) -> str:
    """A model's name with its article ("an esr", "an ehr": E is read "ee"; "a 30m", "a 16a")."""
    return ("an " if name[:1] in "aeiou8" else "a ") + name


@dataclass(frozen=True)
class PrinterProfile:
    name: str
    title: str
    positions: tuple[int, ...]  # v5 head addresses with a tool slot
    axes: str  # axes the model can have
    aux_codes: frozenset[str]  # model-specific aux port codes it has (M670-M689)
    lathe: bool = False
    needs_z_home_for_m660: bool = False
    named: str = ""  # how a comment names the model (gclint.context.printer)
    second_bed: bool = False  # room for Bed2 (T25): "our Hydra models have room to have a second hotbed"

    @property
    def max_position(self) -> int:
        return max(self.positions)

    @property
    def a(self) -> str:
        """The name with its article, as read aloud: "an esr", "an ehr", "a 30m", "a 16a"."""
        return a_model(self.name)

    def describe_positions(self) -> str:
        return f"T0-T{self.max_position}"


_ALWAYS = frozenset({"M670", "M672", "M673", "M689"})

PROFILES: dict[str, PrinterProfile] = {
    p.name: p
    for p in (
        PrinterProfile(
            "30m",
            "System 30M (one yoke, four tool slots T0-T3)",
            (0, 1, 2, 3),
            "XYZ",
            _ALWAYS | {"M671", "M675", "M677", "M679"},
            # (a bare name only as written, upper case: "1h 30m 5s" and "cure time 30m" are times)
            named=r"\b(?:System|Hydra|Hyrel) ?30M\b|(?-i:(?<!\dh )(?<!\dh)\b30M\b(?! ?\d+ ?s\b))",
        ),
        PrinterProfile(
            "esr",
            "Engine SR (one yoke, four tool slots T0-T3)",
            (0, 1, 2, 3),
            "XYZ",
            _ALWAYS | {"M671", "M679"},
            named=r"\bEngine ?SR\b|(?-i:\bESR\b)",
        ),
        PrinterProfile(
            "ehr",
            "Engine HR (one yoke, five tool slots T0-T4; A/B optional)",
            (0, 1, 2, 3, 4),
            "XYZAB",
            _ALWAYS,
            needs_z_home_for_m660=True,
            named=r"\bEngine ?HR\b|(?-i:\bEHR\b)",
        ),
        PrinterProfile(
            "16a",
            "Hydra 16A, single yoke (T0-T4; A/B optional; lathe)",
            (0, 1, 2, 3, 4),
            "XYZAB",
            _ALWAYS | {"M675", "M676", "M678", "M684", "M685"},
            lathe=True,
            # ("Hydra 16A" alone names the 16A, one yoke or two: "one extra yoke gives a 16A a total of ten
            # positions", T_v5 Overall; gclint.context.printer reads it as either)
            named=r"\bHydra ?16A\b|(?-i:\b16A\b)",
            second_bed=True,
        ),
        PrinterProfile(
            "16a-dual",
            "Hydra 16A, dual yoke (T0-T9; A/B optional; lathe)",
            tuple(range(10)),
            "XYZAB",
            _ALWAYS | {"M675", "M676", "M678", "M684", "M685"},
            lathe=True,
            # ("16A dual", "dual-yoke Hydra 16A", "Hydra 16A, two yokes": T_v5 "16A (Dual Yoke)", "Current
            # dual-yoke Hydra 16A units")
            # (the words within 40 characters of each other: a bounded search, linear on any line)
            named=r"\b(?:Hydra ?)?16A\b[^\n]{0,40}?\b(?:dual|two[- ]yokes?|2[- ]yokes?)\b|\b(?:dual|two)[- ]?yokes?\b[^\n]{0,40}?\b16A\b",
            second_bed=True,
        ),
    )
}

DEFAULT_PROFILE = "30m"


class UnknownPrinter(ValueError):
    pass


def get_profile(name: str) -> PrinterProfile:
    key = name.strip().lower().replace("_", "-")
    key = {"16a-single": "16a", "hydra16a": "16a", "16a-2": "16a-dual", "16a2": "16a-dual", "system30m": "30m"}.get(
        key, key
    )
    profile = PROFILES.get(key)
    if profile is None:
        raise UnknownPrinter(f"unknown printer {name!r} (known: {', '.join(PROFILES)})")
    return profile
