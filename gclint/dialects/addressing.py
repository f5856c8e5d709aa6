"""Hyrel head addressing: what a T number means in firmware v5 and in v4, and the v4 -> v5 map.

Sources (docs/sources.md): the T_v5 page (https://hyrel3d.com/wiki/index.php/T_v5, "Chart of Addresses"), and
for v4 the T_v4 page and the Hyrel v4 firmware source (github.com/Karl690/HydraSt_407 @ 734de72: Hydra4/main.c
toolNumberMap, Hydra4/common/inc/hyrel.h), with the confidence of each v4 -> v5 entry ("Hyrel v4 addressing").

Everything inside gclint speaks v5 numbers: a physical head is its v5 position index 0-19 (T0-T4 yoke 1,
T5-T9 yoke 2, ...).  v4 files are converted when read (``resolve_v4_*``) and written back with
``V5_TO_V4``.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from gclint.syntax.nodes import Word, is_number, to_number

# Kinds of address.
HEAD = "head"
SPINDLE = "spindle"
LASER = "laser"
AUX = "aux"
BED = "bed"
VIRTUAL = "virtual"  # clone squads T30-T39
GROUP = "group"  # T40-T48: all devices, a yoke, all aux, all beds...
RESERVED = "reserved"  # numbers with no device


@dataclass(frozen=True)
class Address:
    """What one T number designates."""

    number: int  # the number as written in the file
    kind: str
    v5: int | None  # the v5 address (for v4 files: the translated number), None when there is none
    label: str
    certain: bool = True  # False where the v4 -> v5 correspondence is inferred (confidence: medium/low)

    @property
    def position(self) -> int | None:
        """The physical head position (v5 index 0-19), or None for other devices."""
        return self.v5 if self.kind == HEAD else None

    @property
    def is_physical(self) -> bool:
        """True for one real device (a head, the spindle, the laser, an aux port, a bed)."""
        return self.kind in (HEAD, SPINDLE, LASER, AUX, BED)


def yoke_label(position: int) -> str:
    return f"yoke {position // 5 + 1}, position {position % 5 + 1}"


# -- v5 (T_v5 "Chart of Addresses": T commands and T variables share these numbers) -----------------

_V5_SPECIAL = {
    20: (SPINDLE, "3-phase spindle"),
    21: (LASER, "CO2 laser"),
    22: (AUX, "Aux1"),
    23: (AUX, "Aux2"),
    24: (BED, "Bed1 / Chamber1"),
    25: (BED, "Bed2 / Chamber2"),
    40: (GROUP, "all devices"),
    41: (GROUP, "yoke 1, all heads"),
    42: (GROUP, "yoke 2, all heads"),
    43: (GROUP, "yoke 3, all heads"),
    44: (GROUP, "yoke 4, all heads"),
    45: (GROUP, "all aux devices"),
    46: (GROUP, "all beds / chambers"),
    47: (GROUP, "all non-bed / non-chamber devices"),
    48: (GROUP, "all virtual devices (T30-T39)"),
}


# The devices a v5 group address covers (T_v5 "Logical/Vurtual Device Addresses": T40 "ALL DEVICES",
# T41-T44 "Yoke n, all Heads", T45 "All Aux devices", T46 "All Beds / Chambers", T47 "All non-Bed /
# non-Chamber devices", T48 "All Virtual devices (T30-T39)").  A clone squad's heads are job state
# (M702/M703), not data: ``MachineState.squads``.
GROUP_MEMBERS: dict[int, tuple[int, ...]] = {
    40: tuple(range(26)),
    41: tuple(range(0, 5)),
    42: tuple(range(5, 10)),
    43: tuple(range(10, 15)),
    44: tuple(range(15, 20)),
    45: (22, 23),
    46: (24, 25),
    47: tuple(range(24)),
    48: tuple(range(30, 40)),
}


def members(address: int, squads: Mapping[int, Iterable[int]]) -> list[int]:
    """The devices a group or virtual address covers: the T_v5 groups (``GROUP_MEMBERS``) and a clone squad's
    heads (``squads``: job state, M702/M703); a physical address covers itself (an empty list: none known)."""
    found: list[int] = []
    for device in GROUP_MEMBERS.get(address, (address,)):
        if device != address:
            found.append(device)
        if device in squads:
            found.extend(squads[device])
    return found


def wait_fails(address: Address) -> bool:
    """Whether a wait (M109, M190, M191) on ``address`` fails: "this will FAIL (non-fatally) if you address a
    virtual group address; be sure to use an actual physical address" (Hyrel wiki, Gcode page, M109 Wait for
    Temp (Head)).  The temperature is set, the job goes on without waiting."""
    return address.kind in (VIRTUAL, GROUP)


def resolve_v5(number: int) -> Address:
    """The v5 meaning of ``T<number>`` (command or variable)."""
    if 0 <= number <= 19:
        return Address(number, HEAD, number, f"head T{number} ({yoke_label(number)})")
    if number in _V5_SPECIAL:
        kind, label = _V5_SPECIAL[number]
        return Address(number, kind, number, f"{label} (T{number})")
    if 30 <= number <= 39:
        return Address(number, VIRTUAL, number, f"virtual head / clone squad T{number}")
    return Address(number, RESERVED, None, f"T{number} (no device has this address)")


# -- v4 (T_v4 page, Hyrel v4 firmware source; docs/sources.md) --------------------------------------

# T variables inside M-codes are CAN device addresses (hyrel.h, mailbox.c); value: (kind, v5, label, certain)
_V4_VARIABLES: dict[int, tuple[str, int | None, str, bool]] = {
    0: (GROUP, 40, "all devices", True),
    10: (GROUP, 41, "yoke 1, all heads", True),
    # The aux port: tool 10 -> device 16 in toolNumberMap (confidence: high for v4); that it is v5 Aux1 T22 is
    # inferred (confidence: medium): no page says whether v5 Aux1 (T22) is v4 device 16 (docs/sources.md)
    16: (AUX, 22, "aux (yoke 1 aux position)", False),
    20: (GROUP, 42, "yoke 2, all heads", True),
    26: (SPINDLE, 20, "3-phase spindle", True),
    # yokes 3 and 4: in the firmware's tables (confidence: high for v4), but no 3- or 4-yoke machine is
    # documented, so the v5 counterparts are inferred (confidence: medium) and never applied
    30: (GROUP, 43, "yoke 3, all heads", False),
    40: (GROUP, 44, "yoke 4, all heads", False),
    41: (LASER, 21, "CO2 laser", True),
    # groups 50-57 (hyrel.h, hyrel_can.h: high for v4); v5 squads T30-T39 and T48 are their likely
    # counterparts (confidence: medium for 50 -> T48, low for the numbering of 51-57)
    50: (GROUP, 48, "all groups (clone squads)", False),
    90: (GROUP, 46, "all beds", True),
    91: (BED, 24, "hotbed 1", True),
    92: (BED, 25, "hotbed 2", True),
    100: (GROUP, 47, "all heads (non-bed devices)", True),
}
for _i in range(5):
    _V4_VARIABLES[11 + _i] = (HEAD, _i, f"yoke 1, position {_i + 1}", True)
    _V4_VARIABLES[21 + _i] = (HEAD, 5 + _i, f"yoke 2, position {_i + 1}", True)
    _V4_VARIABLES[31 + _i] = (HEAD, 10 + _i, f"yoke 3, position {_i + 1}", False)
for _i in range(1, 8):
    _V4_VARIABLES[50 + _i] = (VIRTUAL, 29 + _i, f"group {50 + _i}", False)
# 42-45 (yoke 4 positions 2-5) exist in the firmware's mailbox list; 41 is the CO2 laser there too.
for _i in range(1, 5):
    _V4_VARIABLES[41 + _i] = (HEAD, 15 + _i, f"yoke 4, position {_i + 1}", False)

# T commands (a line "T3") are tool numbers (Hydra4/main.c toolNumberMap): 0-4 yoke 1, 5-9 yoke 2,
# 10 aux, 11 CO2 laser, 12 spindle, 13/14 hotbeds; 50-57 select a group.
_V4_COMMANDS: dict[int, tuple[str, int | None, str, bool]] = {
    10: (AUX, 22, "aux", False),  # v5 Aux1 inferred, "medium" (as variable 16 above)
    11: (LASER, 21, "CO2 laser", True),
    12: (SPINDLE, 20, "3-phase spindle", True),
    13: (BED, 24, "hotbed 1", True),
    14: (BED, 25, "hotbed 2", True),
    50: (GROUP, 48, "all groups", False),
}
for _i in range(10):
    _V4_COMMANDS[_i] = (HEAD, _i, yoke_label(_i), True)
for _i in range(1, 8):
    _V4_COMMANDS[50 + _i] = (VIRTUAL, 29 + _i, f"group {50 + _i}", False)


def resolve_v4_variable(number: int) -> Address:
    """The meaning of ``T<number>`` as a T variable (inside an M-code) in a v4 file."""
    entry = _V4_VARIABLES.get(number)
    if entry is None:
        return Address(number, RESERVED, None, f"T{number} (no v4 device address)", True)
    kind, v5, label, certain = entry
    return Address(number, kind, v5, f"{label} (v4 T{number})", certain)


def resolve_v4_command(number: int) -> Address:
    """The meaning of a ``T<number>`` command line in a v4 file."""
    entry = _V4_COMMANDS.get(number)
    if entry is None:
        return Address(number, RESERVED, None, f"T{number} (not a v4 tool number)", True)
    kind, v5, label, certain = entry
    return Address(number, kind, v5, f"{label} (v4 T{number})", certain)


# v4 T variables that mean something else (or nothing) in v5: the ones HY008 looks for in a v5 file.
# (T_v5 addresses T10-T19 exist only on three- and four-yoke machines; T90+ do not exist at all.)
V4_STYLE_VARIABLES = frozenset(list(range(10, 17)) + list(range(21, 27)) + [90, 91, 92, 100])

# The certain part of the v4 -> v5 map for T variables (issue 4; docs/sources.md, confidence "high").
V4_TO_V5_VARIABLE: dict[int, int] = {
    n: v5 for n, (kind, v5, label, certain) in _V4_VARIABLES.items() if certain and v5 is not None
}
# And back; v5 numbers with no certain v4 variable are missing (translation reports them).
V5_TO_V4_VARIABLE: dict[int, int] = {v5: n for n, v5 in V4_TO_V5_VARIABLE.items()}

# T commands: v4 and v5 agree on heads 0-9.
V4_TO_V5_COMMAND: dict[int, int] = {
    n: v5 for n, (kind, v5, label, certain) in _V4_COMMANDS.items() if certain and v5 is not None
}
V5_TO_V4_COMMAND: dict[int, int] = {v5: n for n, v5 in V4_TO_V5_COMMAND.items()}

# The inferred part of the map (confidence medium or low: v4 aux 16 / tool 10 -> v5 Aux1 T22,
# yokes 3 and 4, groups): never applied, only named in messages as the likely counterpart.
V4_TO_V5_VARIABLE_INFERRED: dict[int, int] = {
    n: v5 for n, (kind, v5, label, certain) in _V4_VARIABLES.items() if not certain and v5 is not None
}
V5_TO_V4_VARIABLE_INFERRED: dict[int, int] = {v5: n for n, v5 in V4_TO_V5_VARIABLE_INFERRED.items()}
V4_TO_V5_COMMAND_INFERRED: dict[int, int] = {
    n: v5 for n, (kind, v5, label, certain) in _V4_COMMANDS.items() if not certain and v5 is not None
}
V5_TO_V4_COMMAND_INFERRED: dict[int, int] = {v5: n for n, v5 in V4_TO_V5_COMMAND_INFERRED.items()}

# -- which devices a command's T variable can name ---------------------------------------------------

# Read from the Gcode page ("T# is the target head / bed / chamber / tool position" in each section) and
# the T_v5 chart.  Codes not listed take any device.
_HEADS = frozenset({HEAD, VIRTUAL, GROUP})
_FITS: dict[str, frozenset[str]] = {
    **{c: _HEADS for c in "M104 M109 M106 M107 M221 M701 M702 M703 M704 M721 M722 M723 M728 M783".split()},  # noqa: SIM905
    **{c: frozenset({BED, GROUP}) for c in ("M140", "M141", "M190", "M191")},
    "M6": frozenset({HEAD, VIRTUAL, SPINDLE, LASER}),
    "M620": frozenset({HEAD, LASER, GROUP}),
    "M3": frozenset({HEAD, SPINDLE, GROUP}),
    "M4": frozenset({HEAD, SPINDLE, GROUP}),
    "M5": frozenset({HEAD, SPINDLE, GROUP}),
    "G81": frozenset({HEAD, SPINDLE}),
    "G38": frozenset({HEAD}),
}
_ANY_DEVICE = frozenset({HEAD, VIRTUAL, GROUP, SPINDLE, LASER, AUX, BED})


def fits(code: str, address: Address) -> bool:
    """Whether ``code``'s T variable can sensibly name ``address`` (a bed for M140, a head for M104...)."""
    return address.kind != RESERVED and address.kind in _FITS.get(code, _ANY_DEVICE)


# -- renumbering one command between v4 and v5 ---------------------------------------------------------

# M702-M704 S: v5 a squad or the head to copy (T_v5), v4 an alias or a group (Hydra4/src/MCode.c M702-M704)
SQUAD_CODES = frozenset({"M702", "M703", "M704"})


@dataclass(frozen=True)
class Renumbering:
    """One number of a command in the other numbering (``renumberings``)."""

    node: Word  # the Word holding the number (the code word of a T command)
    letter: str  # "T" or "S" (M702-M704)
    number: int
    new: int | None  # None: no certain counterpart (docs/sources.md confidence medium or low, or none)
    tool_command: bool  # a T command line (a tool number) rather than a T variable

    @property
    def changes(self) -> bool:
        return self.new is not None and self.new != self.number

    def text(self) -> str:
        """The word's text with the new number (``T12`` -> ``T1``; spaces inside the word kept)."""
        word = self.node
        text = word.text
        value = text[1:] if self.tool_command else word.value
        if value and text.endswith(value):
            return text[: len(text) - len(value)] + str(self.new)
        return text[:1] + str(self.new)


def address_number(text: str | None) -> int | None:
    """A T (or squad S) value as a whole number >= 0, or None (not a number, a fraction, too long)."""
    if not text or not is_number(text) or len(text) > 12:
        return None
    value = to_number(text)  # (hex such as "0x1" included; float() would raise on it)
    return int(value) if value is not None and value == int(value) and value >= 0 else None


def renumberings(cmd, to_v5: bool = True) -> list[Renumbering]:
    """Every address of ``cmd`` (a parsed Command) in the other numbering, v4 -> v5 (``to_v5``) or back:
    a T command's tool number, every T variable, and M702-M704's S when it names a head.  Only the
    certain part of the map gives a number (V4_TO_V5_VARIABLE, V4_TO_V5_COMMAND and their inverses);
    the rest comes back with ``new=None``.  The translator (gclint/translate/renumber.py) and HY008's fix
    both renumber through this, so they never disagree."""
    code = cmd.code or ""
    out: list[Renumbering] = []
    if code[:1] == "T":
        number = address_number(code[1:])
        if number is not None:
            commands = V4_TO_V5_COMMAND if to_v5 else V5_TO_V4_COMMAND
            out.append(Renumbering(cmd.word, "T", number, commands.get(number), True))
        return out
    variables = V4_TO_V5_VARIABLE if to_v5 else V5_TO_V4_VARIABLE
    for w in cmd.words:
        letter = w.letter
        if not (letter == "T" or (letter == "S" and code in SQUAD_CODES)) or w.value is None:
            continue
        number = address_number(w.value)
        if number is None:
            continue
        new = variables.get(number)
        if new is not None and letter == "S":
            # a squad (v5 30-39 / v4 groups 50-57, correspondence uncertain) or a head to copy
            kind = resolve_v4_variable(number).kind if to_v5 else resolve_v5(number).kind
            new = new if kind == HEAD else None
        out.append(Renumbering(w, letter, number, new, False))
    return out
