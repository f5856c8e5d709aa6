"""The Hyrel printer model a job was written for, decided by the weight of all its lines.

Each model (gclint.machine.profiles) is scored on what the job uses:

* every line it cannot explain costs it ``LINE_MISFIT`` (weighted as gclint.context.version weighs a use
  repeated on many lines): a head position it lacks (a T command, a T variable, a declared head ``M6 T# O#``,
  a second yoke's group address), an A or B axis ("Hyrel model 16A and EHR printers may be expanded to
  five", Hyrel wiki, Gcode page, "G0 Rapid Move"), the lathe ("M253 Turn On Lathe (CW)": 16A only), an aux
  port it does not have ("Controlling Aux Devices": M671 "30M/ESR only", M676 "16A only"...);
* among the models that explain a line, the one with fewer choices explains it better (an Occam factor,
  once per distinct head position and per distinct model-specific aux port: a job that uses the danger
  lights and nothing a 30M has besides reads as an ESR, whose aux ports are fewer);
* ``M660`` after ``G28 Z0`` is the EHR's header ("By default, this is ONLY used on the EHR", "You MUST have a
  G28 Z0 in your header to run this M660 on the EHR": Gcode page, "M660 Assign Tool Height Offset"): an
  ``M660`` with no ``G28 Z0`` before it tells nothing (an EHR job would be missing its G28 Z0: HY005);
* a comment that names a model (``; job for our 30M``, ``; Hyrel Engine SR``) is the job's own word for its
  printer: a named model is read whatever the lines say (among several named, the best), and the lines it
  cannot explain are the job's mistakes, which the HY rules report and the reasons name.

So a lone line that disagrees with the rest does not flip the model: it is reported by the HY rules that
rest on the model (HY007, HY042, HY041, HY043).  Where nothing tells, the model is the default, ``30m``;
among equals the simplest model (``MODEL_ORDER``).
"""

from __future__ import annotations

import math
from functools import cache

from gclint.context.content import ContentReading, Seen
from gclint.context.model import CONTENT, DEFAULT
from gclint.dialects.addressing import HEAD, fits, resolve_v4_command, resolve_v4_variable, resolve_v5
from gclint.dialects.base import HeadScan
from gclint.machine.profiles import PROFILES, a_model

MODEL_ORDER = ("30m", "esr", "ehr", "16a", "16a-dual")  # the simplest model that fits the job wins ties
LINE_MISFIT = 4.0
EHR_HEADER = 3.0
NAMED = 2.0
_TIE = 0.05  # the prior: each step along MODEL_ORDER costs this much


# ("Hydra 16A, single yoke": the comment names the one-yoke 16A; words within 40 characters, a bounded search)
_ONE_YOKE = r"(?im)^[^\n;(]*+[;(][^\n]*?(?:\b16A\b[^\n]{0,40}?\b(?:single|one|1)[- ]?yokes?\b|\b(?:single|one|1)[- ]?yokes?\b[^\n]{0,40}?\b16A\b)"


def weight(lines: int) -> float:
    """How much a use on ``lines`` lines weighs: 1 for one line, one more for each doubling."""
    return 1.0 + math.log2(max(1, lines))


@cache
def _specific_aux() -> dict[str, frozenset[str]]:
    """Each model's aux ports that not every model has (the ones that tell models apart)."""
    common = frozenset.intersection(*(p.aux_codes for p in PROFILES.values()))
    return {name: p.aux_codes - common for name, p in PROFILES.items()}


class _Scores:
    def __init__(self) -> None:
        self.total = {name: -i * _TIE for i, name in enumerate(MODEL_ORDER)}
        self.told = dict.fromkeys(MODEL_ORDER, 0.0)  # what the job says (no Occam factor, no prior)
        self.misfits: dict[str, list[tuple[float, int, str]]] = {n: [] for n in MODEL_ORDER}
        self.evidence: list[tuple[dict[str, float], int, str]] = []

    def misfit(self, lacks, seen: Seen, lines: int, what: str) -> None:
        cost = LINE_MISFIT * weight(lines)
        hit = {}
        for name in MODEL_ORDER:
            if lacks(PROFILES[name]):
                self.total[name] -= cost
                self.told[name] -= cost
                self.misfits[name].append((cost, seen.line, f"{seen}: {what}"))
                hit[name] = -cost
        if hit and len(hit) < len(MODEL_ORDER):
            self.evidence.append((hit, seen.line, f"{seen}: {what}"))

    def favour(self, points: dict[str, float], line: int, text: str = "", told: bool = True) -> None:
        """Add ``points``; ``told``: what the job says (else an Occam factor); ``text``: a reason to show."""
        for name, value in points.items():
            self.total[name] += value
            if told:
                self.told[name] += value
        if text:
            self.evidence.append((points, line, text))


def decide(
    reading: ContentReading, scan: HeadScan | None, firmware: int, printer: str | None, printer_origin: str
) -> tuple[str, str, tuple[str, ...], tuple[str, ...]]:
    """(model, origin, reasons, the models the job fits equally well: the first is the model)."""
    if printer is not None:
        return printer, printer_origin, (), (printer,)
    s = _Scores()
    _positions(reading, firmware, s)
    counts = reading.counts
    if reading.rotary_axes is not None:
        s.misfit(lambda p: "A" not in p.axes, reading.rotary_axes, counts.get(("axis",), 1), "uses an A/B axis")
    if reading.lathe is not None:
        s.misfit(lambda p: not p.lathe, reading.lathe, counts.get(("lathe",), 1), "runs the lathe")
    # Bed2 (v5 T25, v4 T92): "our Hydra models have room to have a second hotbed" (Gcode page, Controlling
    # Temperature); the pages give the other models none
    bed2 = 25 if firmware == 5 else 92
    second = [seen for (_, letter, n), seen in reading.addresses.items() if letter == "T" and n == bed2]
    if second:
        first = min(second, key=lambda seen: seen.line)
        s.misfit(lambda p: not p.second_bed, first, len(second), "uses the second bed (Bed2), which only the Hydra has")
    specific = _specific_aux()
    for code, seen in reading.aux_codes.items():
        owners = [n for n in MODEL_ORDER if code in specific[n]]
        if not owners:
            continue  # (a port every model has)
        s.misfit(
            lambda p, code=code: code not in p.aux_codes,
            seen,
            counts.get(("aux", code), 1),
            f"{code} exists on some models only",
        )
        s.favour({n: math.log(1 / len(specific[n])) for n in owners}, seen.line)  # (Occam: fewer ports)
    ehr = reading.m660_after_z_home
    if ehr is not None:
        points = {n: EHR_HEADER for n in MODEL_ORDER if PROFILES[n].needs_z_home_for_m660}
        s.favour(points, ehr.line, f"{ehr} after G28 Z0: the EHR header (M660 is ONLY used on the EHR)")
    named: list[str] = []  # the models a comment names: the job's own word for its printer
    if scan is not None:
        found: dict[str, str] = {}
        for name in MODEL_ORDER:
            pattern = PROFILES[name].named
            # (anchored at the line start: one attempt a line, so a line of 100,000 "(" costs linear time)
            text = scan.found(rf"(?im)^[^\n;(]*+[;(][^\n]*?(?:{pattern})") if pattern else None
            if text is not None:  # (shown from the comment on: the match starts at the line's start)
                found[name] = text[min(i for i in (text.find(";"), text.find("("), len(text)) if i >= 0) :]
        if "16a-dual" in found:  # ("16A dual" names the dual-yoke 16A, not the single-yoke one as well)
            found.pop("16a", None)
        elif "16a" in found and scan.found(_ONE_YOKE) is None:
            found["16a-dual"] = found["16a"]  # ("Hydra 16A" names the model, one yoke or two: the lines tell which)
        for name, text in found.items():
            named.append(name)
            s.favour({name: NAMED}, 0, f"the comment '{text.replace(': ', ' - ')}' names it")
    if not s.evidence:
        return MODEL_ORDER[0], DEFAULT, (), (MODEL_ORDER[0],)
    best = max(named or MODEL_ORDER, key=lambda n: s.total[n])
    runner = max((n for n in MODEL_ORDER if n != best), key=lambda n: s.total[n])
    fitting = tuple(
        sorted(
            (n for n in MODEL_ORDER if not s.misfits[n] and s.told[n] >= s.told[best] - 1e-9),
            key=lambda n: -s.total[n],
        )
    )
    if best not in fitting:
        fitting = (best,)
    ranked = sorted(
        (-(pts.get(best, 0.0) - pts.get(runner, 0.0)), line or 1 << 40, text)
        for pts, line, text in s.evidence
        if pts.get(best, 0.0) - pts.get(runner, 0.0) > 0
    )
    reasons = tuple(dict.fromkeys(text for _, _, text in ranked))[:2]
    if not reasons:  # (everything the job says fits several models: the simplest is read)
        reasons = tuple(dict.fromkeys(text for _, _, text in sorted(s.evidence, key=lambda e: e[1] or 1 << 40)))[:1]
    if s.misfits[best]:
        n = len(s.misfits[best])
        worst = max(s.misfits[best])[2]
        uses = f"{n} use{'s' if n != 1 else ''}"
        them = "them" if n != 1 else "it"
        if named and s.total[best] < max(s.total.values()):  # (the lines alone would read another model)
            disagree = (
                f"{uses} {a_model(best)} lacks ({worst}): the comment's model is kept and the HY rules report {them}"
            )
        else:
            disagree = f"{uses} no model fits with the rest ({worst}): the HY rules report {them}"
        reasons = (*reasons[:1], disagree)
    return best, CONTENT, reasons, fitting


def _positions(reading: ContentReading, firmware: int, s: _Scores) -> None:
    """The head positions the job uses: declared heads, T variables and T commands that name a head, and a
    second yoke's group address (v5 T42, v4 T20)."""
    resolve = resolve_v4_variable if firmware == 4 else resolve_v5
    resolve_command = resolve_v4_command if firmware == 4 else resolve_v5
    counts = reading.counts
    used: set[int] = set()

    def head(position: int, seen: Seen, lines: int, what: str) -> None:
        used.add(position)
        s.misfit(lambda p: position not in p.positions, seen, lines, what)

    for (code, letter, number), seen in reading.addresses.items():
        if letter != "T" or (code == "M6" and number in reading.declarations):
            continue  # (a declared head is counted as a declaration)
        address = resolve(number)
        if not fits(code, address):
            continue  # (a head's number on a bed code is HY046's mistake, no head the job uses)
        lines = counts.get(("T", code, letter, number), 1)
        if address.kind == HEAD and address.position is not None and address.position < 10:
            head(address.position, seen, lines, f"names the head T{address.position}")
        elif number == (20 if firmware == 4 else 42):
            s.misfit(lambda p: p.max_position < 9, seen, lines, "addresses a second yoke's heads")
    for number, seen in reading.tool_commands.items():
        address = resolve_command(number)
        if address.kind == HEAD and address.position is not None and address.position < 10:
            head(address.position, seen, counts.get(("tool", number), 1), f"focuses the head T{address.position}")
    for number, seen in reading.declarations.items():
        address = resolve(number)
        if address.kind == HEAD and address.position is not None and address.position < 10:
            head(address.position, seen, counts.get(("decl", number), 1), f"declares a head at T{address.position}")
    for position in used:  # the Occam factor: among the models with that slot, the fewer slots the better
        s.favour(
            {n: math.log(1 / len(PROFILES[n].positions)) for n in MODEL_ORDER if position in PROFILES[n].positions},
            0,
            told=False,
        )


__all__ = ["MODEL_ORDER", "decide"]
