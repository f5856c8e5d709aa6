"""Hyrel firmware v4 or v5, decided by the weight of every address the file uses, never by one line.

Each use of an address (a T variable inside an M-code, an ``M703``/``M704`` S, a ``T`` command) is read in
both numberings (gclint.dialects.addressing: the T_v5 page's "Chart of Addresses"; for v4 the T_v4
page and the Hyrel v4 firmware source, docs/sources.md) and scored under each:

* natural: the number names a device the command addresses (a head on ``M104``, a bed on ``M140``): 0;
* a mistake: a device the command does not address (a bed code on a head address, a wait on a group or a
  clone squad: HY046, HY003): ``MISTAKE``;
* impossible: a number no device has in that numbering (v4's ``T100`` in v5, v5's ``T24`` as a v4 tool
  number): ``IMPOSSIBLE``; a v5 head of a third or fourth yoke, which no Hyrel model has: ``NO_MODEL``.

``W0`` and ``M116`` exist from v5 ("[v5+]", Hyrel wiki, Gcode page, "M109 Wait for Temp (Head)" and "M116
Wait for Temps (v5+)"): under v4 each is a mistake HY027 reports, weighed as two addresses, not decisive
alone.  Each number counts once (``score``).  v5, the current firmware, is the prior: it is read where the
evidence ties.
"""

from __future__ import annotations

import math

from gclint.context.content import ContentReading
from gclint.context.model import CONTENT, DEFAULT
from gclint.dialects.addressing import (
    AUX,
    BED,
    GROUP,
    HEAD,
    RESERVED,
    VIRTUAL,
    Address,
    fits,
    resolve_v4_command,
    resolve_v4_variable,
    resolve_v5,
)

# A number read wrong costs the same whatever the way (no address at all in that numbering, an address of T_v5's
# chart no model has, a device the command does not address): one misreading each, as the old rule of one vote
# per number had it; W0 and M116 under v4 weigh as much, so they decide nothing alone against a v4 number
IMPOSSIBLE = 2.0
NO_MODEL = 2.0
MISTAKE = 2.0
V5_ONLY = 2.0
_WAITS = frozenset({"M109", "M190", "M191"})
_YOKES = 10  # v5 heads T0-T9: yokes 1 and 2, the most any model has (T_v5, "Using the T with the 16A (Dual Yoke)")


def _variable_cost(code: str, address: Address, v5: bool) -> float:
    if address.kind == RESERVED:
        return IMPOSSIBLE
    if v5 and address.kind == HEAD and address.number >= _YOKES:
        return NO_MODEL
    if not fits(code, address):
        return MISTAKE
    if code in _WAITS and address.kind in (GROUP, VIRTUAL):
        return MISTAKE  # a wait on a group never ends (HY003)
    return 0.0


def _command_cost(address: Address, v5: bool) -> float:
    if address.kind == RESERVED:
        return IMPOSSIBLE
    if v5 and address.kind == HEAD and address.number >= _YOKES:
        return NO_MODEL
    if address.kind in (BED, GROUP, AUX):
        return MISTAKE  # a T command focuses a head, the laser or the spindle (HY047)
    return 0.0


def _squad_cost(number: int, v5: bool) -> float:
    # M702-M704 S: v5 a squad T30-T39 or a head to copy (T_v5, "M702 Establish Clone Squad"); v4 an alias
    # (Hyrel v4 firmware source, Hydra4/src/MCode.c M702-M704)
    if v5:
        return 0.0 if 30 <= number <= 39 or 0 <= number < _YOKES else MISTAKE
    return 0.0 if resolve_v4_variable(number).kind == HEAD else MISTAKE


def score(reading: ContentReading) -> tuple[dict[int, float], list[tuple[float, int, str]]]:
    """The address evidence for each version (no prior) and each number: (v4 score - v5 score, line, text).

    Each number counts once, as the average of its uses' costs weighted by the lines that use each (one number
    written wrong on three commands is one misunderstanding, and a head number that is right on six commands
    and wrong on one, ``M190 T0`` in a v5 job, is mostly right), and weighs more the more lines use it, with
    diminishing returns.  A line that is another firmware's habit (``M109 T1 R215``: Marlin's extruder index)
    is not read for addresses (gclint.context.content)."""
    totals = {4: 0.0, 5: 0.0}
    numbers: dict[tuple[str, int], list] = {}  # ("T" variable / "S" squad / "tool" command, n) -> uses
    counts = reading.counts
    for (code, letter, number), seen in reading.addresses.items():
        lines = counts.get(("T", code, letter, number), 1)
        if letter == "S":
            cost4, cost5 = _squad_cost(number, False), _squad_cost(number, True)
        else:
            cost4 = _variable_cost(code, resolve_v4_variable(number), False)
            cost5 = _variable_cost(code, resolve_v5(number), True)
        texts = (f"T{number} is a v4 device address", f"T{number} fits v5")
        numbers.setdefault((letter, number), []).append((seen, cost4, cost5, lines, texts))
    for number, seen in reading.tool_commands.items():
        lines = counts.get(("tool", number), 1)
        cost4 = _command_cost(resolve_v4_command(number), False)
        cost5 = _command_cost(resolve_v5(number), True)
        numbers.setdefault(("tool", number), []).append(
            (seen, cost4, cost5, lines, ("a v4 tool number", "a v5 address"))
        )
    for fact, what, key in (
        (reading.m116, "M116 exists from v5", "M116"),
        (reading.waits_w0, "W0 exists from v5", "W0"),
    ):
        if fact is not None:
            numbers[(what, 0)] = [(fact, V5_ONLY, 0.0, counts.get((key,), 1), ("", what))]
    uses: list[tuple[float, int, str]] = []
    for found in numbers.values():
        lines = sum(use[3] for use in found)
        cost4 = sum(use[1] * use[3] for use in found) / lines
        cost5 = sum(use[2] * use[3] for use in found) / lines
        if cost4 == cost5:
            continue
        w = 1.0 + 0.5 * math.log2(lines)
        cost4, cost5 = cost4 * w, cost5 * w
        totals[4] -= cost4
        totals[5] -= cost5
        # shown: the use that tells the versions apart most
        seen, c4, c5, _, (what4, what5) = max(found, key=lambda use: abs(use[1] - use[2]))
        uses.append((cost5 - cost4, seen.line, f"{seen}: {what4 if c4 < c5 else what5}"))
    return totals, uses


def decide(reading: ContentReading, explicit: int | None, origin: str) -> tuple[int, str, tuple[str, ...], int | None]:
    """(firmware, origin, reasons, what the addresses say) for a Hyrel file.  ``explicit``: the version the
    user named (4 or 5), else None; ``origin``: where an explicit version came from."""
    totals, uses = score(reading)
    evidence = 4 if totals[4] > totals[5] else 5 if totals[5] > totals[4] else None
    if explicit is not None:
        return explicit, origin, (), evidence
    firmware = evidence or 5
    sign = 1.0 if firmware == 4 else -1.0
    ranked = sorted(((-sign * lead, line or 1 << 40, text) for lead, line, text in uses if sign * lead > 0))
    reasons = tuple(dict.fromkeys(text for _, _, text in ranked))[:3]
    against = sorted(((sign * lead, line or 1 << 40, text) for lead, line, text in uses if sign * lead < 0))
    if against:
        n = len(against)
        reasons += (f"{n} address{'es' if n != 1 else ''} read as v{9 - firmware} ({against[0][2]})",)
    return firmware, CONTENT if evidence is not None else DEFAULT, reasons, evidence


__all__ = ["decide", "score"]
