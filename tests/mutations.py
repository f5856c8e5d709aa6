"""Mutation testing of ``gclint diff`` (issue 27): real corpus jobs are translated by gclint, then the OUTPUT is
edited once.  An edit that changes what the printer does must show as a difference that no finding of the
translation explains (the diff "kills" it); an edit that changes nothing (a comment, spaces, a line number,
another spelling of a number, a line's commands on lines of their own) must change nothing the diff reports.

Shared by tests/test_diff_mutations.py (a few jobs, in CI) and bench/bench_mutations.py (every job below; the
kill rate per kind of edit).

Where an edit is made is chosen by a small reading of the Hyrel output of its own (``Scan``), written for
this purpose only and much simpler than gclint/simulate: an edit is made only where it changes something a
later working move (a move that prints or cuts) runs with, or the end of the job (a wait for a temperature
the head was not waited to yet, a fan value other than the one in force, the one M30).  So a survivor is a
miss of the diff, not an edit without effect.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field

from gclint import dialects
from gclint.simulate import Explanations, Mapping, diff_sources
from gclint.simulate.compare import Difference
from gclint.simulate.translation import explanations_from
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source
from gclint.translate import TranslationResult, translate_source, translator_for
from gclint.translate.options import TranslateOptions

from .conftest import CORPUS

# -- the jobs -----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Job:
    """A corpus job as the mutation test reads it: a sample of its lines (its first ``head`` and last ``tail``),
    translated from ``dialect`` with ``settings``.  ``to_machinekit``: a Marlin job first turned into a
    Machinekit one by the rules of Machinekit's own filter (corpus: machinekit-cnc/scripts/gcode-to-ngc)."""

    path: str
    dialect: str
    settings: tuple[tuple[str, str], ...] = ()
    head: int = 2500
    tail: int = 600
    to_machinekit: bool = False

    @property
    def name(self) -> str:
        extra = ",".join(f"{k}={v}" for k, v in self.settings)
        kind = "machinekit (gcode-to-ngc)" if self.to_machinekit else self.dialect
        return f"{self.path} [{kind}{', ' + extra if extra else ''}]"

    def options(self) -> TranslateOptions:
        options = TranslateOptions()
        for key, value in self.settings:
            options.set(key, value)
        return options


EXPLICIT = (("retract", "explicit"),)
NATIVE = (("flow", "native"),)
JOBS = [
    Job("marlin/prusaslicer-2.6.1_benchy.gcode", "marlin", EXPLICIT),
    Job("marlin/displaylayerprogress/cura-lulzbot-3.6.9_LTAZ6A_cube.gcode", "marlin"),
    Job("marlin/prusaslicer-2.5.0_MK3SMMU2S_full_m73.gcode", "marlin", EXPLICIT),
    Job("marlin/bambustudio-01.07.06.92_xmas_pud_plate_1.gcode", "marlin"),
    Job("marlin/kisslicer-1.1.0.5_motor_mount.gcode", "marlin", NATIVE),
    Job("marlin/prusaslicer-2.7.4_screw.gcode", "marlin", NATIVE + EXPLICIT),
    Job("marlin/mgcodedetector_valid_marlin-gcodes.gcode", "marlin"),
    Job("reprap/caribou-duet/gcodes/Hollow_Pyramid-PLA-52min.gcode", "reprap", EXPLICIT),
    Job("reprap/caribou-duet/gcodes/Hollow_Pyramid-PLA-52min.gcode", "reprap", NATIVE, head=1500, tail=300),
    Job("linuxcnc/linuxcnc/nc_files/g76.ngc", "machinekit"),
    Job("linuxcnc/linuxcnc/nc_files/mmount.ngc", "machinekit", (("spindle-max-rpm", "12000"),)),
    Job("linuxcnc/linuxcnc/tests/interp/inside-corners/test.ngc", "machinekit"),
    Job("carvera/CarveraController/Tests/board-test.nc", "carvera"),
    Job("carvera/CarveraController/LED/ABS-Base.nc", "carvera", (("spindle-max-rpm", "15000"),), head=1500, tail=300),
    Job("carvera/CarveraController/Laser/AudreyHepburnSmall.nc", "carvera", head=800, tail=200),
    Job("hyrel/unidentified_idx23496765178__slot_template_v4.gcode", "hyrel-v4"),
    Job("hyrel/Zmmyslony_Vector_Slicer_GCode__diagonal_1x0.5cm.gcode", "hyrel-v4"),
    Job("other/mach3_plasma.gcode", "marlin"),
    Job("marlin/displaylayerprogress/cura-3.5.0_usbcap.gcode", "machinekit", EXPLICIT, 1500, 300, to_machinekit=True),
    Job("marlin/prusaslicer-2.6.1_benchy.gcode", "machinekit", NATIVE, head=1500, tail=300, to_machinekit=True),
]
# the fast subset (tests/test_diff_mutations.py): one job of each kind of source, small samples
FAST = [
    Job("marlin/prusaslicer-2.6.1_benchy.gcode", "marlin", EXPLICIT, head=700, tail=150),
    Job("marlin/kisslicer-1.1.0.5_motor_mount.gcode", "marlin", NATIVE, head=600, tail=150),
    Job("marlin/mgcodedetector_valid_marlin-gcodes.gcode", "marlin"),
    Job("linuxcnc/linuxcnc/nc_files/g76.ngc", "machinekit"),
    Job("carvera/CarveraController/Tests/board-test.nc", "carvera"),
    Job("hyrel/unidentified_idx23496765178__slot_template_v4.gcode", "hyrel-v4"),
    Job("marlin/prusaslicer-2.6.1_benchy.gcode", "machinekit", NATIVE, head=500, tail=100, to_machinekit=True),
]


def sample(job: Job) -> str:
    """The job's text as the test reads it (its head and tail when long; Machinekit form when asked)."""
    src = Source.open(str(CORPUS / job.path))
    try:
        lines = [raw + ending for chunk in src.chunks() for raw, ending in chunk]
    finally:
        src.close()
    if len(lines) > job.head + job.tail:
        lines = lines[: job.head] + lines[-job.tail :]
    text = "".join(lines)
    return gcode_to_ngc(text) if job.to_machinekit else text


_MOTION_WITH_E = re.compile(r"^(\s*[Gg]0*(?:[0-3]|28|92)(?![\d.])[^;(]*?)[Ee]([-+]?[\d.])")
_SETS_WITH_S = re.compile(r"^(\s*[Mm]0*(?:104|106|109|140|141|190|191)(?![\d.])[^;(]*?)[Ss]([\d.])")
_DWELL_MS = re.compile(r"^(\s*[Gg]0*4[ \t]+[Pp])(\d+)(?![\d.])")
_RETRACT = re.compile(r"^(\s*)[Gg]1([01])(?![\d.])")


def gcode_to_ngc(text: str) -> str:
    """A RepRap job in Machinekit's FDM dialect, as Machinekit's filter writes it (gcode-to-ngc, in the corpus):
    E becomes A on G0-G3, G28 and G92; G4 P milliseconds become seconds; G10/G11 become G22/G23; the S of
    M104/M106/M109/M140/M141/M190/M191 becomes P; M82 lines are emptied; M2 ends the program."""
    out = []
    for line in text.splitlines(keepends=True):
        body = line.rstrip("\r\n")
        ending = line[len(body) :]
        body = _MOTION_WITH_E.sub(r"\1A\2", body)
        body = _SETS_WITH_S.sub(r"\1P\2", body)
        body = _DWELL_MS.sub(lambda m: m.group(1) + f"{int(m.group(2)) / 1000:g}", body)
        body = _RETRACT.sub(lambda m: m.group(1) + ("G22" if m.group(2) == "0" else "G23"), body)
        if re.match(r"^\s*[Mm]0*82(?![\d.])", body):
            body = ""
        out.append(body + ending)
    return "".join(out) + "M2 ; end of program\n"


# -- the translation, with where each output line comes from ---------------------------------------------------


@dataclass
class Translation:
    job: Job
    source: str
    text: str
    result: TranslationResult
    origin: list[int]  # per output line (0-based): the source line it was written for (0: header or footer)

    def lines(self) -> list[str]:
        return self.text.splitlines(keepends=True)


def translate(job: Job, source: str | None = None) -> Translation:
    """Translate the job's sample, line by line through the translator (no plain-move route), so that each
    output line is known to come from one source line; the text is checked against ``translate_source``."""
    source = sample(job) if source is None else source
    src, dst = dialects.get(job.dialect), dialects.get("hyrel")
    translator = translator_for(src, dst, job.options())
    result = TranslationResult(job.path, src.name, dst.name)
    reader = Source.from_text(source, job.path)
    translator.read_job(reader)  # (as translate_source does: the job's settings, then its lines)
    pieces: list[tuple[int, str]] = [(0, "".join(translator.start(result)))]
    mark = translator.mark()  # (the line saying what the output is, with the first line's ending)
    number = 0
    for chunk in reader.chunks():
        for raw, ending in chunk:
            number += 1
            if mark is not None:
                pieces.append((0, mark + (ending or "\n")))
                mark = None
            pieces.append(
                (number, "".join(translator.translate_line(Line(number, raw, ending, parse_line(raw)), result)))
            )
    result.lines_in = number
    pieces.append((0, "".join(translator.finish(result))))
    text = "".join(p for _, p in pieces)
    check = TranslationResult(job.path, src.name, dst.name)
    assert text == "".join(
        translate_source(Source.from_text(source, job.path), translator_for(src, dst, job.options()), check)
    )
    starts, lines_of = [], []
    at = 0
    for number, piece in pieces:
        starts.append(at)
        lines_of.append(number)
        at += len(piece)
    origin = []
    at = 0
    for line in text.splitlines(keepends=True):
        origin.append(lines_of[bisect_right(starts, at) - 1] if starts else 0)
        at += len(line)
    return Translation(job, source, text, check, origin)


# -- a small reading of the Hyrel output (where an edit changes something) ---------------------------------

_WORD = re.compile(r"([A-Za-z])[ \t]*([-+]?(?:\d+\.?\d*|\.\d+))?")
_PAREN = re.compile(r"\([^)]*\)")


@dataclass
class Cmd:
    code: str
    params: dict[str, float | None]
    start: int  # columns of the command's words in the line
    end: int
    words: list[tuple[str, str | None, int, int]] = field(default_factory=list)  # (letter, value text, start, end)


def commands(line: str) -> list[Cmd]:
    """The commands of one line: each starts at a G or M word (a T word first on the line is a tool command)."""
    code = line.rstrip("\r\n").split(";", 1)[0]
    code = _PAREN.sub(lambda m: " " * len(m.group()), code)
    out: list[Cmd] = []
    for m in _WORD.finditer(code):
        letter, value = m.group(1).upper(), m.group(2)
        if letter == "N" and not out:
            continue
        if letter in "GM" or (letter == "T" and not out):
            number = value or ""
            if "." not in number and number.lstrip("+-").isdigit():
                number = str(int(number))
            out.append(Cmd(letter + number, {}, m.start(), m.end()))
        elif out:
            out[-1].params[letter] = float(value) if value not in (None, "", ".", "-", "+") else None
            out[-1].words.append((letter, value, m.start(2) if value else m.end(), m.end()))
            out[-1].end = m.end()
    return out


_HEADS = range(0, 20)
_DEFAULTS = {"fan": 0.0, "flow": 1.0, "temp": 0.0, "bed": 0.0, "aux": 0.0, "emit": False}
_AXES = "XYZAB"


class Scan:
    """The Hyrel output line by line: what each line sets (``sets[i]``: key -> value after the line) and which
    lines are working moves (``working[i]``: the focused head, or None).  A key names one thing a working move
    runs with or the job ends with: ("temp", head), ("wait", head), ("fan", head), ("flow", head), ("height",
    head), ("width", head), ("bed", address), ("bedwait", address), ("spindle", head), ("laser",), ("emit",
    head), ("aux", port), ("focus",), ("evalues",), ("emode",), ("absolute",), ("epos",), ("wcs",),
    ("offset", head)."""

    def __init__(self, lines: list[str], cnc: bool) -> None:
        self.lines = lines
        self.cmds = [commands(line) for line in lines]
        self.cnc = cnc
        state: dict = {("focus",): None, ("evalues",): False, ("emode",): "abs", ("absolute",): True}
        state[("epos",)] = 0.0
        pos = [None] * 5
        self.sets: list[dict] = []
        self.before: list[dict] = []
        self.working: list[int | None | bool] = []
        self.focus: list[int | None] = []
        for cmds in self.cmds:
            self.before.append(dict(state))
            sets: dict = {}
            work: int | None | bool = False
            for cmd in cmds:
                w = self._apply(cmd, state, sets, pos)
                if w:
                    work = state[("focus",)]
            self.sets.append(sets)
            self.working.append(work)
            self.focus.append(state[("focus",)])
        self.after = state

    def _targets(self, cmd: Cmd, state: dict) -> list:
        t = cmd.params.get("T")
        if t is None:
            return [state[("focus",)]]
        return [int(t)]

    def _apply(self, cmd: Cmd, state: dict, sets: dict, pos: list) -> bool:
        code, p = cmd.code, cmd.params

        def put(key, value):
            state[key] = value
            sets[key] = value

        if code[0] == "T" and code[1:].isdigit():
            put(("focus",), int(code[1:]))
        elif code in ("M104", "M109"):
            for h in self._targets(cmd, state):
                if p.get("S") is not None:
                    put(("temp", h), p["S"])
                if code == "M109" and p.get("W") != 0:
                    put(("wait", h), (state.get(("temp", h)), "R" in p))
        elif code in ("M140", "M190", "M141", "M191"):  # (beds and chambers: T24 unless T says)
            a = int(p["T"]) if p.get("T") is not None else 24
            if p.get("S") is not None:
                put(("bed", a), p["S"])
            if code in ("M190", "M191"):
                put(("bedwait", a), state.get(("bed", a)))
        elif code == "M106":
            if p.get("C") is not None:
                put(("fanrange",), p["C"])
            if p.get("S") is not None:
                for h in self._targets(cmd, state):
                    put(("fan", h), p["S"] / (state.get(("fanrange",)) or 100.0))
        elif code == "M107":
            for h in self._targets(cmd, state):
                put(("fan", h), 0.0)
        elif code == "M221":
            for h in self._targets(cmd, state):
                for letter, key in (("S", "flow"), ("W", "width"), ("Z", "height")):
                    if p.get(letter) is not None:
                        put((key, h), p[letter])
        elif code == "M756":
            if p.get("S") is not None:
                for h in _HEADS:
                    put(("height", h), p["S"])
        elif code in ("M3", "M4"):
            for h in self._targets(cmd, state):
                put(("spindle", h), None if p.get("S") == 0 else (code, p.get("S")))
        elif code == "M5":
            for h in self._targets(cmd, state):
                put(("spindle", h), None)
        elif code == "M620":
            for h in self._targets(cmd, state):
                put(("emit", h), p.get("E") == 1)
        elif code == "M621":
            put(("laser",), p.get("P"))
        elif code in ("M7", "M8", "M679", "M685"):
            put(("aux", code), 100.0 if p.get("S") is None else p["S"])
        elif code == "M9":
            put(("aux", "M7"), 0.0)
            put(("aux", "M8"), 0.0)
        elif code == "M229":
            put(("evalues",), p.get("E") == 1)
        elif code in ("M82", "M83"):
            put(("emode",), "abs" if code == "M82" else "rel")
        elif code in ("G90", "G91"):
            put(("absolute",), code == "G90")
        elif code in ("G54", "G55", "G56", "G57", "G58", "G59", "G53"):
            put(("wcs",), code)
        elif code == "M6" and "O" in p:
            for h in self._targets(cmd, state):
                put(("offset", h), tuple(p.get(a) or 0.0 for a in "XYZ"))
        elif code == "G92":
            if p.get("E") is not None:
                put(("epos",), p["E"])
            for i, a in enumerate(_AXES):
                if a in p:
                    put(("shift", a), (p[a], pos[i]))
        elif code == "M30":
            put(("ended",), True)
            state[("evalues",)] = False
        elif code in ("G0", "G1", "G2", "G3"):
            moved = False
            for i, a in enumerate(_AXES):
                v = p.get(a)
                if v is None:
                    continue
                new = v if state[("absolute",)] else (pos[i] or 0.0) + v
                moved = moved or new != pos[i] or not state[("absolute",)]
                pos[i] = new
            e = p.get("E")
            if code == "G0":
                return False
            extrudes = False
            if e is not None:
                if not state[("evalues",)] or code in ("G2", "G3"):
                    extrudes = True
                elif state[("emode",)] == "abs":
                    extrudes = e - (state[("epos",)] or 0.0) > 1e-9
                    put(("epos",), e)
                else:
                    extrudes = e > 1e-9
            spinning = any(v for k, v in state.items() if k[0] == "spindle")
            emitting = any(v for k, v in state.items() if k[0] == "emit")
            return moved and (extrudes or ((self.cnc or spinning) and not emitting) or (emitting and e is not None))
        return False

    # -- questions -------------------------------------------------------------------------------------------

    def changes(self, i: int, key) -> bool:
        """Whether line ``i`` sets ``key`` to another value than the one in force (a fan is off, a head's
        flow 1 and a heater off until set)."""
        default = _DEFAULTS.get(key[0])
        before = self.before[i].get(key, default)
        return key in self.sets[i] and self.sets[i][key] != (default if before is None else before)

    def matters(self, i: int, key, head=None, end: bool = True) -> bool:
        """Whether what line ``i`` sets in ``key`` is seen: a later working move (on ``head``, when given; one
        with E for the E mode and position) before another line sets ``key``, or the end of the job (``end``:
        the key is part of what is left on)."""
        extruding = key[0] in ("emode", "epos")
        for j in range(i + 1, len(self.lines)):
            w = self.working[j]
            seen = w is not False and (head is None or w == head)
            if seen and (not extruding or any("E" in c.params for c in self.cmds[j])):
                return True
            if key in self.sets[j]:
                return False
        return end and ("ended",) not in self.sets[i]

    def effective(self, i: int, key, head=None, end: bool = True) -> bool:
        return self.changes(i, key) and self.matters(i, key, head, end)


# -- the edits ---------------------------------------------------------------------------------------------


@dataclass
class Mutant:
    kind: str
    preserving: bool
    line: int  # output line (0-based) edited
    lines: list[str]  # the whole edited output
    what: str  # the edit, for the report

    def text(self) -> str:
        return "".join(self.lines)


def _replace(lines: list[str], i: int, new: str | list[str]) -> list[str]:
    out = list(lines)
    out[i : i + 1] = [new] if isinstance(new, str) else new
    return out


def _ending(line: str) -> str:
    return line[len(line.rstrip("\r\n")) :] or "\n"


def _single(scan: Scan, i: int, codes: tuple[str, ...]) -> Cmd | None:
    cmds = scan.cmds[i]
    return cmds[0] if len(cmds) == 1 and cmds[0].code in codes else None


def _edit_word(line: str, cmd: Cmd, letter: str, change) -> str | None:
    for lt, value, start, end in cmd.words:
        if lt == letter and value:
            new = change(float(value))
            if new is None:
                return None
            return line[:start] + _fmt(new) + line[end:]
    return None


def _fmt(v: float) -> str:
    return f"{v:.4f}".rstrip("0").rstrip(".") if v != int(v) else str(int(v))


def _spread(items: list, n: int) -> list:
    """At most ``n`` of ``items``, spread over the job (the first, the last, evenly between)."""
    if len(items) <= n:
        return items
    if n == 1:
        return [items[0]]
    return [items[round(k * (len(items) - 1) / (n - 1))] for k in range(n)]


def mutants(translation: Translation, cnc: bool, per_kind: int = 3) -> Iterator[Mutant]:
    lines = translation.lines()
    scan = Scan(lines, cnc)
    found: dict[str, list[Mutant]] = {}

    def add(kind: str, i: int, new, what: str, preserving: bool = False) -> None:
        found.setdefault(kind, []).append(Mutant(kind, preserving, i, _replace(lines, i, new), what))

    for i, cmds in enumerate(scan.cmds):
        if len(cmds) != 1:
            continue
        cmd = cmds[0]
        code, p = cmd.code, cmd.params
        line = lines[i]
        heads = scan._targets(cmd, scan.before[i])
        h = heads[0] if heads else None
        drop = f"drop {line.strip()!r}"
        # -- drops and number changes, where the line changes what is seen later
        if code == "M30" and i == max(k for k, c in enumerate(scan.cmds) if c and c[0].code == "M30"):
            add("drop M30", i, [], drop)
        elif code in ("M721", "M722") and p.get("I") == 1:
            add(f"drop {code} I1", i, [], drop)
        elif code in ("M104", "M109"):
            eff_temp = scan.effective(i, ("temp", h), h)
            if code == "M109":
                wait = scan.sets[i].get(("wait", h))
                before = scan.before[i].get(("wait", h))
                fresh = (
                    before is None
                    or (wait and wait[0] is not None and (before[0] or 0) < wait[0])
                    or (wait and wait[1])
                )
                if fresh and scan.matters(i, ("wait", h), h, end=False):
                    add("drop M109", i, [], drop)
                    add(
                        "change temperature", i, _edit_word(line, cmd, "S", lambda v: v + 15 if v > 0 else None), "S+15"
                    )
            elif eff_temp:
                add("drop M104", i, [], drop)
                if p.get("S"):
                    add("change temperature", i, _edit_word(line, cmd, "S", lambda v: v + 15), "S+15")
        elif code in ("M140", "M190"):
            a = int(p["T"]) if p.get("T") is not None else 24
            if code == "M190":
                before = scan.before[i].get(("bedwait", a))
                if before != scan.sets[i].get(("bedwait", a)) and scan.matters(i, ("bedwait", a), end=False):
                    add("drop M190", i, [], drop)
            elif scan.effective(i, ("bed", a)):
                add("drop M140", i, [], drop)
                if p.get("S"):
                    add("change temperature", i, _edit_word(line, cmd, "S", lambda v: v + 10), "S+10")
        elif code in ("M106", "M107"):
            if scan.effective(i, ("fan", h), h):
                add(f"drop {code}", i, [], drop)
                if code == "M106" and p.get("S"):
                    add("change fan", i, _edit_word(line, cmd, "S", lambda v: round(v / 2) or None), "S/2")
        elif code[0] == "T" and code[1:].isdigit():
            if scan.effective(i, ("focus",), end=False):
                add("drop T#", i, [], drop)
        elif code in ("M3", "M4", "M5"):
            if scan.effective(i, ("spindle", h), h):
                add(f"drop {code}", i, [], drop)
                if code != "M5":
                    other = "M4" if code == "M3" else "M3"
                    add("swap M3/M4", i, line[: cmd.start] + other + line[cmd.start + len(code) :], f"{code}->{other}")
                    if (p.get("S") or 0) >= 0.4:  # (the diff compares percents to 0.1 point)
                        add("change spindle speed", i, _edit_word(line, cmd, "S", lambda v: v / 2), "S/2")
        elif code == "M756":
            if scan.effective(i, ("height", h if h is not None else 0), end=False) or any(
                scan.effective(i, ("height", k), k, end=False) for k in set(scan.focus) if k is not None
            ):
                add("drop M756", i, [], drop)
                add("change layer height", i, _edit_word(line, cmd, "S", lambda v: v * 1.5), "S*1.5")
        elif code == "M221":
            if any(scan.effective(i, (k, h), h, end=False) for k in ("flow", "width", "height")):
                add("drop M221", i, [], drop)
                if p.get("S"):
                    add("change flow", i, _edit_word(line, cmd, "S", lambda v: v * 1.1), "S*1.1")
                if p.get("Z"):
                    add("change layer height", i, _edit_word(line, cmd, "Z", lambda v: v * 1.5), "Z*1.5")
        elif code == "G4":
            if (p.get("S") or 0) >= 0.01 or (p.get("P") or 0) >= 10:  # (Hyrel: P ms, S s; a dwell of 10 ms or more)
                add("drop G4", i, [], drop)
                letter = "S" if p.get("S") else "P"
                add("change dwell", i, _edit_word(line, cmd, letter, lambda v: v * 2), f"{letter}*2")
        elif code == "G92":
            b = scan.before[i]
            if (
                p.get("E") is not None
                and b[("evalues",)]
                and b[("emode",)] == "abs"
                and p["E"] != b[("epos",)]
                and scan.matters(i, ("epos",), end=False)
            ):
                add("drop G92", i, [], drop)
        elif code == "M0":
            add("drop M0", i, [], drop)
        elif code in ("M620", "M621"):
            key = ("emit", h) if code == "M620" else ("laser",)
            if scan.effective(i, key, end=code == "M620"):
                add(f"drop {code}", i, [], drop)
                if code == "M621" and p.get("P"):
                    add("change laser power", i, _edit_word(line, cmd, "P", lambda v: v / 2), "P/2")
        elif code in ("M7", "M8", "M9"):
            port = "M7" if code == "M9" else code
            if scan.effective(i, ("aux", port)):
                add(f"drop {code}", i, [], drop)
        elif code == "M229":
            if scan.effective(i, ("evalues",), end=False):
                add("drop M229", i, [], drop)
        elif code in ("M82", "M83"):
            if scan.effective(i, ("emode",), end=False) and scan.before[i][("evalues",)]:
                add("drop M82/M83", i, [], drop)
        elif code in ("G90", "G91"):
            if scan.effective(i, ("absolute",), end=False):
                add("drop G90/G91", i, [], drop)
        elif code in ("G54", "G55", "G56", "G57", "G58", "G59"):
            if scan.effective(i, ("wcs",), end=False):
                add("drop G54-G59", i, [], drop)
        elif code == "M6" and "O" in p and any(p.get(a) for a in "XYZ"):
            invoked = any(c and c[0].code == f"T{h}" for c in scan.cmds[i + 1 :])  # (a T invokes the offsets)
            if invoked:
                add("drop M6", i, [], drop)
        # -- moves: numbers, order
        if scan.working[i] is not False and code in ("G1", "G2", "G3"):
            if p.get("F") and scan.before[i].get(("evalues",)) is not None:
                add("change feed", i, _edit_word(line, cmd, "F", lambda v: v * 1.5), "F*1.5")
            if p.get("E") is not None and scan.before[i][("evalues",)] and code == "G1":
                if scan.before[i][("emode",)] == "rel":
                    add("change E", i, _edit_word(line, cmd, "E", lambda v: v * 1.5), "E*1.5")
                else:
                    prev = scan.before[i][("epos",)] or 0.0
                    add("change E", i, _edit_word(line, cmd, "E", lambda v, p=prev: v + (v - p) * 0.5 + 0.01), "E+")
            for letter in "XYZ":
                if p.get(letter) is not None and code == "G1":
                    add("change coordinate", i, _edit_word(line, cmd, letter, lambda v: v + 1.0), f"{letter}+1")
                    break
            j = i + 1
            next_move = j < len(lines) and scan.working[j] is not False and len(scan.cmds[j]) == 1
            if next_move and scan.cmds[j][0].code == "G1" and code == "G1" and lines[j].strip() != line.strip():
                swapped = lines[:i] + [lines[j], line] + lines[j + 1 :]
                found.setdefault("reorder two moves", []).append(
                    Mutant("reorder two moves", False, i, swapped, "swapped with the next move")
                )
        # a state line right before a working move it changes: the move runs with the old state
        if i + 1 < len(lines) and scan.working[i + 1] is not False:
            w = scan.working[i + 1]
            keys = [k for k in scan.sets[i] if scan.changes(i, k) and (len(k) == 1 or k[1] == w or k[0] in ("bed",))]
            keys = [k for k in keys if k[0] in ("temp", "fan", "flow", "height", "spindle", "laser", "bed", "focus")]
            if keys and code not in ("G0", "G1", "G2", "G3", "G92"):
                new = lines[:i] + [lines[i + 1], line] + lines[i + 2 :]
                found.setdefault("reorder state and move", []).append(
                    Mutant("reorder state and move", False, i, new, f"{line.strip()!r} after the next move")
                )
    # -- edits that keep the meaning
    commands_at = [i for i, c in enumerate(scan.cmds) if c]
    for i in _spread(commands_at, 6):
        line = lines[i]
        body = line.rstrip("\r\n")
        code = scan.cmds[i][0].code
        if code in ("M0", "M1", "M792", "M30"):
            continue
        add("comment line", i, ["; a comment added\n", line], "a comment line before", True)
        add("trailing comment", i, body + " ; note" + _ending(line), "a comment after", True)
        add("spaces", i, "  " + re.sub(r" ", "  ", body) + " \t" + _ending(line), "more spaces", True)
        add("line number", i, f"N{i + 1} " + line, f"N{i + 1} before", True)
    moves = [i for i, c in enumerate(scan.cmds) if c and c[0].code in ("G0", "G1") and len(c[0].words) >= 2]
    for i in _spread(moves, 8):
        line, cmd = lines[i], scan.cmds[i][0]
        spelled = line
        for letter, value, start, end in reversed(cmd.words):
            if value and letter in "XYZEFS":
                v = value
                if "." not in v:
                    v = v + ".000"
                elif v.startswith("0."):
                    v = v[1:]
                elif v.startswith("-0."):
                    v = "-" + v[2:]
                else:
                    v = v + "0"
                spelled = spelled[:start] + v + spelled[end:]
        if spelled != line:
            add("number spelling", i, spelled, "numbers spelled otherwise", True)
        words = [line[s - 1 : e] if line[s - 1 : s].isalpha() else line[s:e] for _, _, s, e in cmd.words]
        if len(words) >= 2:
            head = line[: cmd.start] + cmd.code
            tail = line[cmd.end :]
            add("word order", i, head + " " + " ".join(reversed(words)) + tail, "words in another order", True)
    multi = [i for i, c in enumerate(scan.cmds) if len(c) > 1]
    for i in _spread(multi, 6):
        line = lines[i]
        body, ending = line.rstrip("\r\n"), _ending(line)
        parts = [body[c.start : c.end].strip() for c in scan.cmds[i]]
        add("split a line", i, [part + ending for part in parts], "one command a line", True)
    pairs = [
        i
        for i in range(len(lines) - 1)
        if len(scan.cmds[i]) == 1
        and len(scan.cmds[i + 1]) == 1
        and {scan.cmds[i][0].code, scan.cmds[i + 1][0].code} <= {"M104", "M140", "M106", "M107", "M221"}
        and scan.cmds[i][0].code != scan.cmds[i + 1][0].code
    ]
    for i in _spread(pairs, 4):
        new = lines[:i] + [lines[i + 1], lines[i]] + lines[i + 2 :]
        found.setdefault("swap independent settings", []).append(
            Mutant("swap independent settings", True, i, new, "two settings of different devices swapped")
        )
        a, b = lines[i].rstrip("\r\n").split(";")[0].strip(), lines[i + 1].rstrip("\r\n").split(";")[0].strip()
        joined = lines[:i] + [f"{a} {b}" + _ending(lines[i + 1])] + lines[i + 2 :]
        found.setdefault("join two lines", []).append(
            Mutant("join two lines", True, i, joined, "two settings on one line (run in order)")
        )
    for items in found.values():
        items = [m for m in items if m.lines is not None and None not in m.lines]
        yield from _spread(items, per_kind if not items or not items[0].preserving else max(per_kind, 4))


# -- running and judging --------------------------------------------------------------------------------------


def _key(d: Difference) -> tuple:
    return (d.aspect, d.source_line, d.source, d.output, d.count, getattr(d, "trail", 0))


@dataclass
class Verdict:
    mutant: Mutant
    new: list[Difference]  # differences the unedited translation does not have
    killed: bool  # (meaning-changing) reported: a new difference no finding explains, or one the edited line's does
    job: Job
    # differences of the unedited translation this output no longer has: with no new one, the edit took the
    # output back to the source's meaning in what the diff compares (it removed what the translator added)
    gone: list[Difference] = field(default_factory=list)

    source_line: int = 0  # the source line the edited output line was written for (0: header or footer)

    @property
    def undoes(self) -> bool:
        """The edit removed only differences the translator made on the edited line's source line and said so
        there (an approximation it reported): the output has the source's meaning again in what the diff
        compares."""
        return (
            not self.killed
            and not self.new
            and bool(self.gone)
            and all(d.explained_by is not None and d.explained_by[1] == self.source_line for d in self.gone)
        )


@dataclass
class Prepared:
    job: Job
    translation: Translation
    baseline: list[Difference]
    unexplained: list[Difference]  # of the unedited translation (must be none)
    cnc: bool


def prepare(job: Job) -> Prepared:
    translation = translate(job)
    src, dst = dialects.get(job.dialect), dialects.get("hyrel")
    diff = _diff(job, translation, translation.text, explanations_from(translation.result))
    from gclint.simulate import is_cnc

    return Prepared(job, translation, diff.differences, diff.unexplained(), is_cnc(src) or is_cnc(dst))


def _diff(job: Job, translation: Translation, output: str, explanations: Explanations):
    src, dst = dialects.get(job.dialect), dialects.get("hyrel")
    return diff_sources(
        Source.from_text(translation.source, "source"),
        Source.from_text(output, "output"),
        src,
        dst,
        Mapping.from_options(job.options()),
        explanations,
    )


def explanations_for(prepared: Prepared) -> Explanations:
    """The translation's findings, and (where the diff takes it) the unedited translation's own differences:
    only a difference the translator's output has too is explained by a finding."""
    explanations = explanations_from(prepared.translation.result)
    if hasattr(explanations, "reference"):
        explanations.reference = prepared.baseline
    return explanations


def judge(prepared: Prepared, mutant: Mutant) -> Verdict:
    diff = _diff(prepared.job, prepared.translation, mutant.text(), explanations_for(prepared))
    base = Counter(_key(d) for d in prepared.baseline)
    new = []
    for d in diff.differences:
        k = _key(d)
        if base[k]:
            base[k] -= 1
        else:
            new.append(d)
    gone = [d for d in prepared.baseline if base[_key(d)] > 0]
    origin = prepared.translation.origin
    source_line = origin[mutant.line] if mutant.line < len(origin) else 0
    killed = any(d.explained_by is None or (source_line and d.explained_by[1] == source_line) for d in new)
    return Verdict(mutant, new, killed, prepared.job, gone, source_line)


def run(jobs: list[Job], per_kind: int = 3) -> Iterator[tuple[Prepared, Verdict]]:
    for job in jobs:
        prepared = prepare(job)
        for mutant in mutants(prepared.translation, prepared.cnc, per_kind):
            yield prepared, judge(prepared, mutant)
