"""The labelled set for dialect detection (issue 24, item 4): the corpus labels and generated variants.

``corpus_labels()`` reads ``tests/data/corpus_labels.tsv`` (one row per corpus file, labelled by reading
the file as a domain expert would: see the comment block at its top).  ``cases()`` builds the variants
that must keep their label, in memory (nothing of the corpus is copied into the repository):

- ``stripped``: each Hyrel job (corpus and hand-written) with every comment removed;
- ``marlin-habit``: each Hyrel job with one Marlin habit added (a bare ``G28``, ``M109 T1 R215``,
  ``M106 S255``, a retract ``G1 E-0.5 F1800``), one habit per variant;
- ``wrong-version``: a v4 job with one ``W0`` on an M109, a v5 job with one v4 address (``M104 T100 S0``,
  ``M190 T0 S60``): the version stays;
- ``hyrel-comment``: Marlin slicer jobs with a Hyrel-looking comment added (``; for Hyrel 30M``,
  ``; Repetrel``): still Marlin, same firmware;
- ``translated``: corpus jobs run through gclint's translator to hyrel: they read as hyrel v5;
- ``issue``: the examples of issue 24's "Must hold" section;
- ``handwritten``: jobs written for this set in the styles of the Hyrel pages (v5 addressing, M6 T# O#,
  M660/H offsets, the EHR header, the 16A's second yoke, spindle, laser, UV pen, clone squads) and a few
  Marlin, RepRapFirmware, LinuxCNC, Carvera and GRBL ones.

Detection is asked with no dialect or printer given, as the pre-commit hook runs it:
``gclint.context.infer_source(Source.from_text(text, name), name)``.

An expected value may list alternatives (``ehr|16a``): any of them is right.  ``judge`` compares a
``Context`` with a label and returns what differs; the test and bench/bench_detection.py share it.
"""

from __future__ import annotations

import csv
import re
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

from tests.conftest import CORPUS

LABELS = Path(__file__).resolve().parent / "data" / "corpus_labels.tsv"
DIALECTS = ("hyrel", "marlin", "reprap", "machinekit", "carvera", "generic")
FLAVORS = ("prusa-buddy", "prusa-mk3", "bambu", "klipper", "fablin", "reprap-2015")
PRINTERS = ("30m", "esr", "ehr", "16a", "16a-dual")
NOT_GCODE = "-"


@dataclass(frozen=True)
class Label:
    """What a file is: dialect (``hyrel`` for both versions), firmware flavour, Hyrel version, Hyrel model.
    Empty flavour/version/printer: not checked.  ``certain``: a careful reader has no doubt."""

    dialect: str
    flavor: str = ""
    version: str = ""
    printer: str = ""
    certain: bool = True
    why: str = ""

    def __post_init__(self) -> None:
        for name, value, allowed in (
            ("dialect", self.dialect, DIALECTS),
            ("flavor", self.flavor, FLAVORS),
            ("version", self.version, ("4", "5")),
            ("printer", self.printer, PRINTERS),
        ):
            for option in value.split("|") if value else ():
                if option not in allowed:
                    raise ValueError(f"{name} {option!r} is not one of {allowed}")
        if self.version and "hyrel" not in self.dialect.split("|"):
            raise ValueError("a version is a Hyrel file's")

    def describe(self) -> str:
        text = self.dialect
        if self.flavor:
            text += f" ({self.flavor})"
        if self.version:
            text += f" v{self.version}"
        if self.printer:
            text += f", printer {self.printer}"
        return text


@dataclass(frozen=True)
class CorpusFile:
    path: str  # relative to the corpus
    label: Label


@dataclass(frozen=True)
class Case:
    """A variant or hand-written job: ``make()`` gives its text; ``name`` is the file name detection is
    told (the extension is evidence too)."""

    id: str
    kind: str
    name: str
    label: Label
    make: Callable[[], str] = field(compare=False, repr=False)
    needs_corpus: bool = False


# -- the corpus labels ----------------------------------------------------------------------------


@cache
def corpus_labels() -> tuple[CorpusFile, ...]:
    """Every row of tests/data/corpus_labels.tsv, files that are not G-code (dialect ``-``) left out."""
    rows = []
    with LABELS.open(encoding="utf-8", newline="") as fh:
        lines = (line for line in fh if not line.startswith("#"))
        for row in csv.DictReader(lines, delimiter="\t", quoting=csv.QUOTE_NONE):
            if row["dialect"] == NOT_GCODE:
                continue
            if row["certain"] not in ("yes", "no"):
                raise ValueError(f"{row['path']}: certain must be yes or no")
            label = Label(
                row["dialect"], row["flavor"], row["version"], row["printer"], row["certain"] == "yes", row["why"]
            )
            rows.append(CorpusFile(row["path"], label))
    return tuple(rows)


@cache
def all_label_rows() -> tuple[dict[str, str], ...]:
    """Every row of the TSV as written (not-G-code rows included)."""
    with LABELS.open(encoding="utf-8", newline="") as fh:
        lines = (line for line in fh if not line.startswith("#"))
        return tuple(csv.DictReader(lines, delimiter="\t", quoting=csv.QUOTE_NONE))


def corpus_text(path: str) -> str:
    return (CORPUS / path).read_bytes().decode("utf-8", "surrogateescape")


# -- judging a reading ----------------------------------------------------------------------------


def _fits(expected: str, got: str | None) -> bool:
    return got is not None and got in expected.split("|")


def got_of(ctx) -> dict[str, str]:
    """What a ``Context`` says, in the label's terms (``hyrel`` for both versions)."""
    dialect = "hyrel" if ctx.dialect in ("hyrel", "hyrel-v4") else ctx.dialect
    return {
        "dialect": dialect,
        "flavor": ctx.flavor or "",
        "version": str(ctx.firmware) if ctx.firmware is not None else "",
        "printer": ctx.printer or "",
    }


def judge(ctx, label: Label) -> dict[str, tuple[str, str]]:
    """The labelled fields ``ctx`` gets wrong: {field: (expected, got)}.  The dialect is always checked;
    flavour, version and printer when labelled."""
    got = got_of(ctx)
    wrong = {}
    for name in ("dialect", "flavor", "version", "printer"):
        expected = getattr(label, name)
        if expected and not _fits(expected, got[name]):
            wrong[name] = (expected, got[name] or "-")
    return wrong


def reading_of(ctx) -> str:
    """A context as one short text: ``hyrel v4, printer 30m (weak)``."""
    text = ctx.label()
    return f"{text} (weak)" if ctx.weak else text


# -- building variants ----------------------------------------------------------------------------

_PAREN = re.compile(r"\([^)\n]*\)")


def strip_comments(text: str) -> str:
    """``text`` with every ``;`` and ``(...)`` comment removed, and the lines left empty dropped."""
    out = []
    for line in text.splitlines():
        code = _PAREN.sub("", line.split(";", 1)[0]).rstrip()
        if code.strip():
            out.append(code)
    return "\n".join(out) + "\n"


def _code(line: str) -> str:
    return line.split(";", 1)[0].strip()


def _index(lines: list[str], pattern: str, start: int = 0) -> int | None:
    rx = re.compile(pattern, re.IGNORECASE)
    for i in range(start, len(lines)):
        if rx.match(_code(lines[i])):
            return i
    return None


def insert(text: str, new: str, *, after: str | None = None, before: str | None = None, last: bool = False) -> str:
    """``text`` with the line ``new`` after the first line whose code matches ``after`` (else before the
    first matching ``before``; ``last``: before the last match), else at the top."""
    lines = text.splitlines(keepends=True)
    ending = "\r\n" if lines and lines[0].endswith("\r\n") else "\n"
    at = 0
    if after is not None and (i := _index(lines, after)) is not None:
        at = i + 1
    elif before is not None:
        if last:
            found = [i for i in range(len(lines)) if re.match(before, _code(lines[i]), re.IGNORECASE)]
            at = found[-1] if found else len(lines)
        elif (i := _index(lines, before)) is not None:
            at = i
    if at > 0 and not lines[at - 1].endswith(("\n", "\r")):
        lines[at - 1] += ending
    lines.insert(at, new + ending)
    return "".join(lines)


def add_to_first(text: str, code: str, word: str) -> str:
    """``text`` with ``word`` added to the first ``code`` command (before its comment)."""
    lines = text.splitlines(keepends=True)
    i = _index(lines, rf"{code}\b")
    if i is None:
        raise ValueError(f"no {code} line to change")
    line = lines[i]
    body = line.rstrip("\r\n")
    ending = line[len(body) :]
    cut = body.find(";")
    head, tail = (body, "") if cut < 0 else (body[:cut].rstrip(), " " + body[cut:])
    lines[i] = f"{head} {word}{tail}{ending}"
    return "".join(lines)


MOVE = r"G0*[01]\b"
EXTRUDING_MOVE = r"G0*1\b.*\bE"

# (id, the line, where it goes): each Marlin habit alone in an otherwise native Hyrel job
MARLIN_HABITS: tuple[tuple[str, Callable[[str], str]], ...] = (
    ("bare-G28", lambda t: insert(t, "G28", before=MOVE)),
    ("M109-T1-R215", lambda t: insert(t, "M109 T1 R215", after=r"M10[49]\b", before=MOVE)),
    ("M106-S255", lambda t: insert(t, "M106 S255", before=r"G0*1\b")),
    ("retract-E-0.5", lambda t: insert(t, "G1 E-0.5 F1800", after=EXTRUDING_MOVE, before=r"M30\b", last=True)),
)
V4_WRONG_LINES: tuple[tuple[str, Callable[[str], str]], ...] = (
    ("W0-on-M109", lambda t: add_to_first(t, "M109", "W0")),
)
V5_WRONG_LINES: tuple[tuple[str, Callable[[str], str]], ...] = (
    ("M104-T100", lambda t: insert(t, "M104 T100 S0", before=r"M30\b", last=True)),
    ("M190-T0", lambda t: insert(t, "M190 T0 S60", after=r"M1[49]0\b", before=MOVE)),
)
HYREL_COMMENTS = (("for-Hyrel-30M", "; for Hyrel 30M"), ("Repetrel", "; Repetrel"))
# v5 jobs whose own addresses say little about the version (no address, or one that fits both numberings):
# a line of v4 numbering is then as good as all the evidence there is, so they get no wrong-version variant
_FEW_V5_ADDRESSES = {"v5-minimal-native", "v5-co2-laser-T21", "v5-16a-lathe"}

# Marlin jobs a Hyrel-looking comment must not turn (slicer output; not the settings dump, the list of
# commands, or the Cura file of comments only)
_NOT_SLICER_JOBS = {
    "marlin/marlin-M503-dump_CR10-S_config.gcode",
    "marlin/mgcodedetector_valid_marlin-gcodes.gcode",
    "marlin/displaylayerprogress/cura-4.2.1_tiny.gcode",
}

# Jobs run through the translator to hyrel: (corpus path, source dialect)
TRANSLATED = (
    ("marlin/cura-4.10.0_kreistest.gcode", "marlin"),
    ("marlin/cura-4.13.1_octoprint-autoprint_test_heating.gcode", "marlin"),
    ("marlin/displaylayerprogress/cura-lulzbot-3.6.9_LTAZ6A_cube.gcode", "marlin"),
    ("marlin/kisslicer-1.1.0.5_thinbox.gcode", "marlin"),
    ("marlin/prusaslicer-2.5.0_MK3SMMU2S_full_m73.gcode", "marlin"),
    ("marlin/prusaslicer-2.8.1_mini_cube.gcode", "marlin"),
    ("reprap/e3d-toolchanger/rrf3.x/gcodes/toolchange_test.gcode", "reprap"),
    ("reprap/e3d-toolchanger/rrf3.x/gcodes/ToolChanger - Calibration.gcode", "reprap"),
    ("reprap/caribou-duet/gcodes/Hollow_Pyramid-PLA-52min.gcode", "reprap"),
    (
        "machinekit/machinekit-cnc/configs/ARM/BeagleBone/BeBoPr-Bridge/subroutines/fan_and_wait_on_temp_test.ngc",
        "machinekit",
    ),
    ("linuxcnc/linuxcnc/nc_files/comp311.ngc", "machinekit"),
    ("linuxcnc/linuxcnc/tests/test-active-states.ngc", "machinekit"),
    ("carvera/CarveraController/Tests/laser-test-air.nc", "carvera"),
    ("carvera/CarveraController/LED/ABS-Base.nc", "carvera"),
    ("carvera/Carvera_Community_Firmware/TEST_M491.1ToolBreak.cnc", "carvera"),
)


def translate_to_hyrel(text: str, source: str, name: str) -> str:
    """``text`` (a ``source`` job) as ``gclint translate --from SOURCE --to hyrel`` writes it."""
    from gclint import dialects
    from gclint.syntax.source import Source
    from gclint.translate import TranslationResult, translate_source, translator_for
    from gclint.translate.options import TranslateOptions

    translator = translator_for(dialects.get(source), dialects.get("hyrel"), TranslateOptions())
    result = TranslationResult(name, source, "hyrel")
    return "".join(translate_source(Source.from_text(text, name), translator, result))


def _stem(path: str) -> str:
    return path.rsplit("/", 1)[-1]


def _with_suffix(name: str, suffix: str) -> str:
    stem, dot, _ = name.rpartition(".")
    return f"{stem}{suffix}" if dot else f"{name}{suffix}"


# -- hand-written jobs ----------------------------------------------------------------------------


@dataclass(frozen=True)
class Written:
    id: str
    name: str
    label: Label
    text: str
    hyrel_job: bool = False  # also varied (stripped, Marlin habits, wrong-version line)


def _job(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.strip("\n").splitlines()) + "\n"


ISSUE = (
    Written(
        "hyrel-job-with-marlin-habits",
        "habits.gcode",
        Label(
            "hyrel",
            version="5",
            why="M229 E0 D0, M756 S0.3 (Hyrel only); G28, M109 T1 R215, M106 T1 S255, E-0.5 are habits",
        ),
        _job("""
M229 E0 D0
M756 S0.3
G28
M109 T1 R215
T1
M106 T1 S255
G0 X20 Y20 Z0.3 F3000
G1 X80 Y20 F1200 E1
G1 X80 Y80 E1
G1 E-0.5 F1800
G0 X20 Y80
G1 X20 Y20 F1200 E1
M30
"""),
    ),
    Written(
        "klipper-temperature-script",
        "temperature.gcode",
        Label("marlin|reprap", why="M105 (temperature report): Marlin and RRF have it, Hyrel does not"),
        _job("""
M104 S100
M105
M140 S60
M109 S100
M105
"""),
    ),
    Written(
        "fifth-slot-T4-not-30m",
        "t4.gcode",
        Label(
            "hyrel",
            version="5",
            printer="ehr|16a|16a-dual",
            why="M109 T4 / T4: a fifth slot (no 30M or ESR); E1 markers on every move and M30: a native Hyrel print",
        ),
        _job("""
M109 T4 S200
T4
G0 X20 Y20 Z0.3 F3000
G1 X80 Y20 F1200 E1
G1 X80 Y80 E1
G1 X20 Y80 E1
G1 X20 Y20 E1
M30
"""),
    ),
    Written(
        "v5-job-with-one-M190-T0",
        "bed.gcode",
        Label("hyrel", version="5", why="M6 T0 O1, M140/M104 T24 and T0 heads: v5; one M190 T0 (v4's all devices)"),
        _job("""
M6 T0 O1 X0 Y0 Z0
M721 S10000 E100 P-15 T0
M722 S10000 E100 P20 T0
M221 S1.0 T0 P77 W0.5 Z0.3
M140 T24 S60
M190 T0 S60
M109 T0 S215
G21
G90
G28 X0 Y0
T0
G0 X20 Y20 Z0.3 F3000
M756 S0.3
G1 X80 Y20 F1200 E1
G1 X80 Y80 E1
G1 X20 Y80 E1
G1 X20 Y20 E1
M104 T0 S0
M140 T24 S0
M30
"""),
    ),
    Written(
        "grbl-job",
        "grbl.gcode",
        Label("generic", why="$H homing (GRBL system command)"),
        _job("""
$H
M3 S1000
G1 X10 F500
M5
M2
"""),
    ),
    Written(
        "plain-native-hyrel-job-with-one-retract",
        "native.gcode",
        Label("hyrel", version="5", why="M221 T0 P W Z flow, M756 per layer, E1 markers; one G1 E-0.5"),
        _job("""
M221 S1.0 T0 P77 W0.5 Z0.3
M104 T0 S215
M109 T0 S215
T0
G0 X20 Y20 Z0.3 F3000
M756 S0.3
G1 X80 Y20 F1200 E1
G1 X80 Y80 E1
G1 X20 Y80 E1
G1 X20 Y20 E1
G1 E-0.5 F1800
G0 Z0.6
M756 S0.3
G1 X80 Y20 F1200 E1
G1 X80 Y80 E1
G1 X20 Y80 E1
G1 X20 Y20 E1
M104 T0 S0
M30
"""),
    ),
)

HANDWRITTEN = (
    Written(
        "v5-30m-two-heads",
        "two_heads.gcode",
        Label("hyrel", version="5", why="Repetrel v5 header: M6 T1 O2 / M6 T2 O3, M721/M722/M221/M728 T1/T2, M140 T24"),
        _job("""
; Repetrel v5: MK1-250 in the second slot (T1), SDS-05 in the third (T2)
M6 T1 O2 X0 Y0 Z0
M721 S10000 E100 P-15 T1
M722 S10000 E100 P20 T1
M221 S1.0 T1 P77 W0.5 Z0.3
M728 T1 S0
M6 T2 O3 X0 Y0 Z0
M721 S10000 E160 P-100 T2
M722 S10000 E200 P100 T2
M221 S1.0 T2 P81.0 W1.6 Z0.3
M728 T2 S0
G21                 ; mm
G90                 ; absolute
G28 X0 Y0           ; home X and Y
M106 C255           ; fans in 0-255
M140 T24 S60        ; bed 1
M104 T1 S215
M104 T2 S30
M190 T24 S60
M109 T1 S215
M109 T2 S30
T1
G0 X20 Y20 Z0.3 F3000
M756 S0.3
G1 X80 Y20 F1200 E1
G1 X80 Y80 E1
G1 X20 Y80 E1
G1 X20 Y20 E1
M106 T1 S128
T2
G0 X30 Y30 Z0.6 F3000
M756 S0.3
G1 X70 Y30 F600 E1
G1 X70 Y70 E1
G1 X30 Y70 E1
G1 X30 Y30 E1
M107 T1
M104 T40 S0         ; every device off
M140 T46 S0         ; every bed off
G91
G0 Z10
G90
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-ehr-header-m660-after-G28-Z0",
        "ehr.gcode",
        Label(
            "hyrel",
            version="5",
            printer="ehr",
            why="EHR header: G28 Z0 then M660 H1/H5 Z, G1 ... H1; heads T0 and T4 (fifth slot)",
        ),
        _job("""
; Hyrel header for an Engine HR: home Z first, then the tool heights
G21
G90
G28 Z0              ; the EHR needs Z homed for M660
G28 X0 Y0
M660 H1 Z31.5       ; tool height, slot 1
M660 H5 Z29.8       ; tool height, slot 5
M6 T0 O1 X0 Y0
M6 T4 O5 X-42.0 Y0.5
M721 S8000 E60 P-10 T0
M722 S8000 E60 P10 T0
M221 S1.0 T0 P1230 W0.41 Z0.2
M221 S1.0 T4 P77 W0.5 Z0.2
M140 T24 S40
M109 T0 S25
M109 T4 S210 R3
T0
G1 Z0.2 F300 H1     ; first move applies the height
G1 X20 Y20 F900 E1
G1 X40 Y20 E1
G1 X40 Y40 E1
G1 X20 Y40 E1
T4
G1 Z0.2 F300 H5
G1 X60 Y20 F900 E1
G1 X80 Y20 E1
G1 X80 Y40 E1
M104 T40 S0
M140 T24 S0
G0 Z20
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-16a-dual-yoke",
        "dual_yoke.gcode",
        Label(
            "hyrel",
            version="5",
            printer="16a-dual",
            why="M6 T0 O1 and M6 T7 O8 (second yoke, T5-T9), M109 T7, T7 tool change, M104 T42 (yoke 2)",
        ),
        _job("""
; Hydra 16A dual yoke: paste head in yoke 1 slot 1 (T0), thermoplastic in yoke 2 slot 3 (T7)
M6 T0 O1 X0 Y0 Z0
M721 S10000 E100 P-15 T0
M722 S10000 E100 P20 T0
M221 S1.0 T0 P530 W0.84 Z0.4
M6 T7 O8 X203.5 Y0.2 Z0.0
M721 S10000 E100 P-15 T7
M722 S10000 E100 P20 T7
M221 S1.0 T7 P77 W0.5 Z0.4
G21
G90
G28 X0 Y0
M140 T24 S55
M190 T24 S55
M109 T0 S25
M109 T7 S215
T0
G0 X20 Y20 Z0.4 F3000
M756 S0.4
G1 X80 Y20 F900 E1
G1 X80 Y80 E1
G1 X20 Y80 E1
T7
G0 X20 Y20 Z0.8 F3000
M756 S0.4
G1 X80 Y20 F1200 E1
G1 X80 Y80 E1
G1 X20 Y80 E1
M104 T41 S0         ; yoke 1 heads off
M104 T42 S0         ; yoke 2 heads off
M140 T46 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-16a-dual-yoke-T5-T9",
        "yoke2_only.gcode",
        Label(
            "hyrel",
            version="5",
            printer="16a-dual",
            why="heads declared at T5, T6 and T9 (second yoke) with M6 T# O#, tool changes T5/T6/T9",
        ),
        _job("""
M6 T5 O6 X0 Y0 Z0
M6 T6 O7 X25.4 Y0 Z0
M6 T9 O10 X101.6 Y0 Z0
M221 S1.0 T5 P77 W0.5 Z0.3
M221 S1.0 T6 P77 W0.5 Z0.3
M221 S1.0 T9 P77 W0.5 Z0.3
M104 T5 S210
M104 T6 S210
M104 T9 S230
M140 T24 S60
M109 T5 S210
M109 T6 S210
M109 T9 S230
T5
G0 X10 Y10 Z0.3 F3000
M756 S0.3
G1 X60 Y10 F1200 E1
T6
G1 X60 Y60 F1200 E1
T9
G1 X10 Y60 F1200 E1
M104 T42 S0
M140 T24 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-spindle-T20-drilling",
        "spindle.gcode",
        Label(
            "hyrel",
            version="5",
            why="3-phase spindle T20 (M3 T20 S percent), G81 T20 I P Q pecking after M660 H1 set and applied",
        ),
        _job("""
; v5 milling with the 3-phase spindle (T20)
G21
G90
G28 Z0
G28 X0 Y0
M660 H1 Z52.4       ; spindle tool length
M6 T20 O1 X0 Y0 Z0
T20
G0 X10 Y10 Z5 F2000
G1 Z5 F300 H1       ; apply the tool length
M3 T20 S60          ; spindle at 60 %
G4 S2
G1 Z-0.5 F100
G1 X60 F300
G1 Y60
G1 X10
G1 Y10
G0 Z5
G81 T20 X20 Y20 I3 P1 Q-1 Z-3 F100
G81 T20 X40 Y20 I3 P1 Q-1 Z-3 F100
M5 T20
G0 Z20
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-co2-laser-T21",
        "laser.gcode",
        Label("hyrel", version="5", why="M620 T21 E1 / M621 P40 / T21 (v5 CO2 laser) / emitting G1 E1 / M620 T21 E0"),
        _job("""
G21
G90
G28 X0 Y0
G0 X100 Y100 F1000
M620 T21 E1         ; enable the CO2 laser
M621 P40            ; 40 % on emitting moves
T21
G1 X120 Y100 F600 E1
G1 X120 Y120 E1
G1 X120 Y130
G1 X140 Y130 E1
G1 X140 Y100 E1
M620 T21 E0         ; laser off before the end
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-uv-pen-W0-M116",
        "uv_cure.gcode",
        Label("hyrel", version="5", why="M109 T0 S37 W0 then M116 (v5 only), M620 T2 E1 / M623 UV pen"),
        _job("""
; bio-ink in slot 1 (T0), UV pen in slot 3 (T2)
M6 T0 O1 X0 Y0 Z0
M6 T2 O3 X-40.0 Y0 Z0
M721 S10000 E40 P-20 T0
M722 S10000 E40 P20 T0
M221 S1.0 T0 P530 W0.26 Z0.2
M109 T0 S37 W0      ; set, do not wait here
M140 T24 S37
M116                ; now wait for all of them
T0
G0 X30 Y30 Z0.2 F2000
M756 S0.2
G1 X60 Y30 F300 E1
G1 X60 Y60 E1
G1 X30 Y60 E1
G1 X30 Y30 E1
M620 T2 E1
T2
G0 X45 Y45 Z5 F2000
M623 P80 D5000      ; 5 s exposure
M620 T2 E0
M104 T0 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-clone-squad",
        "clones.gcode",
        Label("hyrel", version="5", why="M702 T0 S30 / M703 T1 S30 / M703 T2 S30 clone squad, T30 (v5 virtual head)"),
        _job("""
M6 T0 O1 X0 Y0 Z0
M6 T1 O2 X50.8 Y0 Z0
M6 T2 O3 X101.6 Y0 Z0
M221 S1.0 T0 P77 W0.5 Z0.3
M702 T0 S30         ; squad 30 takes T0's flow settings
M703 T1 S30
M703 T2 S30
M109 T0 S210
M109 T1 S210
M109 T2 S210
T30
G0 X10 Y10 Z0.3 F3000
M756 S0.3
G1 X40 Y10 F1200 E1
G1 X40 Y40 E1
G1 X10 Y40 E1
G1 X10 Y10 E1
M704 T2 S30
M104 T47 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-bed-and-chamber-windows",
        "windows.gcode",
        Label("hyrel", version="5", why="M140 T24, M141 T25, M190 T24 S H window, M109 T0 S L U window"),
        _job("""
M6 T0 O1 X0 Y0 Z0
M221 S1.0 T0 P62 W0.4 Z0.25
M140 T24 S90
M141 T25 S50
M190 T24 S90 H88    ; go on once above 88 C
M109 T0 S250 L5 U5  ; within -5/+5 of 250 C
T0
G0 X20 Y20 Z0.25 F3000
M756 S0.25
G1 X60 Y20 F1500 E1
G1 X60 Y60 E1
G1 X20 Y60 E1
M104 T0 S0
M140 T46 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-five-slots",
        "five_slots.gcode",
        Label(
            "hyrel",
            version="5",
            printer="ehr|16a",
            why="heads declared in all five slots T0-T4 of one yoke (no 30M/ESR, no second yoke)",
        ),
        _job("""
M6 T0 O1 X0 Y0 Z0
M6 T1 O2 X25.4 Y0 Z0
M6 T2 O3 X50.8 Y0 Z0
M6 T3 O4 X76.2 Y0 Z0
M6 T4 O5 X101.6 Y0 Z0
M221 S1.0 T0 P77 W0.5 Z0.3
M221 S1.0 T4 P77 W0.5 Z0.3
M109 T0 S205
M109 T4 S205
T0
G0 X10 Y10 Z0.3 F3000
M756 S0.3
G1 X50 Y10 F1200 E1
T1
G1 X50 Y20 F1200 E1
T2
G1 X10 Y20 F1200 E1
T3
G1 X10 Y30 F1200 E1
T4
G1 X50 Y50 F1200 E1
M104 T41 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-16a-lathe",
        "lathe.gcode",
        Label("hyrel", version="5", printer="16a|16a-dual", why="M253 lathe (Hydra 16A only), A axis, M6 T0 O1"),
        _job("""
; printing onto a rotating mandrel on the 16A lathe
M6 T0 O1 X0 Y0 Z0
M221 S1.0 T0 P77 W0.5 Z0.3
M109 T0 S200
T0
G28 X0 Y0
M253 S40            ; lathe on, clockwise
G0 X10 Y0 Z12 F2000
G1 X120 A720 F600 E1
G1 X10 A1440 E1
M255                ; lathe off
M104 T0 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v4-standard-header-30m-esr",
        "header_v4.gcode",
        Label(
            "hyrel",
            version="4",
            printer="30m|esr",
            why="Hyrel v4 standard header for a 30M/ESR: M109 T12 (v4 head 2), M104 T100, M140 T90, M620 T100",
        ),
        _job("""
; Hyrel header for a 30M/ESR, heated head in the second slot (T1 / T12)
M772 S1             ; metrics
M627 X0 Y0 Z0 J-500 K5
M107
M106 C255
G53
G21
G91
G0 Z10
G90
G28 X0 Y0
M229 E1 D1          ; E values (volumetric)
M190 S60
M109 T12 S215
T1
G0 X20 Y20 Z0.3 F3000
G1 X80 Y20 F1200 E0.52
G1 X80 Y80 E1.04
G1 X20 Y80 E1.56
G1 X20 Y20 E2.08
; Hyrel footer
M107 T100           ; fans off
M620 T100 E0        ; lasers off
M104 T100 S0        ; heads off
M140 T90 S0         ; beds off
M5
G91
G0 Z10
G90
G0 Y0
G0 X0
M84
G53
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v4-16a-dual-yoke",
        "dual_v4.gcode",
        Label(
            "hyrel",
            version="4",
            printer="16a-dual",
            why="v4 addresses: M6 T11 O1 and M6 T23 O8 (yoke 2 device), M109 T23, T7 tool change, M140 T91",
        ),
        _job("""
M6 T11 O1 X0 Y0 Z0
M6 T23 O8 X203.5 Y0 Z0
M221 S1.0 T11 P77 W0.5 Z0.3
M221 S1.0 T23 P77 W0.5 Z0.3
M721 S10000 E100 P-15 T23
M722 S10000 E100 P20 T23
M140 T91 S60
M109 T11 S210
M109 T23 S215
T0
G0 X20 Y20 Z0.3 F3000
G1 X80 Y20 F1200 E1
T7
G1 X80 Y80 F1200 E1
M104 T100 S0
M140 T90 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-esr-header",
        "esr.gcode",
        Label(
            "hyrel", version="5", printer="esr", why="header comment names the Engine SR; M671 danger lights (30M/ESR)"
        ),
        _job("""
; Hyrel Engine SR (ESR), v5 addressing
M671 S100           ; danger lights on
M6 T0 O1 X0 Y0 Z0
M6 T3 O4 X76.2 Y0 Z0
M221 S1.0 T0 P77 W0.5 Z0.3
M221 S1.0 T3 P77 W0.5 Z0.3
M140 T24 S60
M109 T0 S210
M109 T3 S210
T0
G0 X20 Y20 Z0.3 F3000
M756 S0.3
G1 X80 Y20 F1200 E1
T3
G1 X80 Y80 F1200 E1
M104 T41 S0
M671 S0
M30
"""),
        hyrel_job=True,
    ),
    Written(
        "v5-minimal-native",
        "minimal.gcode",
        Label("hyrel", version="5", why="M756 layer heights and E1 markers only (native Hyrel flow)"),
        _job("""
T0
G0 X20 Y20 Z0.2 F3000
M756 S0.2
G1 X60 Y20 F900 E1
G1 X60 Y60 E1
G0 Z0.4
M756 S0.2
G1 X20 Y60 F900 E1
G1 X20 Y20 E1
M30
"""),
        hyrel_job=True,
    ),
    # -- other dialects --------------------------------------------------------------------------
    Written(
        "marlin-start-and-end",
        "marlin.gcode",
        Label("marlin", why="M190/M109 S, bare G28, G29 + M420 S1, M900 K, cumulative E amounts, M84"),
        _job("""
M140 S60
M104 S210
M190 S60
M109 S210
G28                 ; home all axes
G29                 ; probe the bed
M420 S1             ; mesh on
M900 K0.05          ; linear advance
G92 E0
G1 Z0.3 F3000
G1 X10 Y20 E8.5 F1500
G1 X180 Y20 E16.42
G1 E15.62 F2100     ; retract
G0 X180 Y40 F9000
G1 E16.42 F2100
G1 X10 Y40 E24.34 F1500
M107
M104 S0
M140 S0
G28 X0
M84
"""),
    ),
    Written(
        "marlin-klipper-macros",
        "klipper.gcode",
        Label(
            "marlin",
            flavor="klipper",
            why="PRINT_START BED=60 EXTRUDER=210 / PRINT_END Klipper macros, SET_PRESSURE_ADVANCE",
        ),
        _job("""
PRINT_START BED=60 EXTRUDER=210
SET_PRESSURE_ADVANCE ADVANCE=0.04
G90
M83
G1 Z0.2 F3000
G1 X10 Y10 F9000
G1 X100 Y10 E4.2 F1800
G1 X100 Y100 E4.2
G1 E-0.8 F2400
PRINT_END
"""),
    ),
    Written(
        "marlin-prusa-mk4-checks",
        "mk4.gcode",
        Label("marlin", flavor="prusa-buddy", why='M862.3 P "MK4S", M862.1 P0.4, M555 (Prusa Buddy firmware)'),
        _job("""
M862.1 P0.4         ; nozzle check
M862.3 P "MK4S"     ; printer model check
M115 U6.1.3
M555 X80 Y80 W100 H100
M140 S60
M104 S170
G28
M109 S215
G92 E0
G1 X10 Y-4 Z0.2 E8 F1000
"""),
    ),
    Written(
        "reprap-tool-config",
        "config.g",
        Label("reprap", why="M563 tool definition, G10 P tool offsets and temperatures, M568, T-1"),
        _job("""
; tools
M563 P0 S"Extruder" D0 H1 F0   ; define tool 0
G10 P0 X0 Y0 Z0                ; tool 0 offsets
G10 P0 R0 S0                   ; standby and active temperatures
M568 P0 S210 R160
M563 P1 S"Second" D1 H2 F0
G10 P1 X-19.5 Y0 Z-0.2
T-1
"""),
    ),
    Written(
        "reprap-meta-macro",
        "probe.g",
        Label("reprap", why="RRF 3 meta commands (var, if, echo, abort) and {object-model expressions}"),
        _job("""
var probes = 3
if !move.axes[2].homed
  abort "home Z first"
while iterations < var.probes
  G30 S-1
  echo "probe", iterations, move.axes[2].machinePosition
G1 Z{move.axes[2].max - 5} F600
"""),
    ),
    Written(
        "reprap-three-line-macro",
        "lift.g",
        Label("reprap", certain=False, why="3 lines every dialect has (G91, G1 Z5, G90): an RRF macro by name only"),
        _job("""
G91
G1 Z5 F600
G90
"""),
    ),
    Written(
        "linuxcnc-program",
        "pocket.ngc",
        Label("machinekit", why="o<sub> subroutine, #<named> params, [expressions], G64 P Q, G90.1 absolute IJ"),
        _job("""
(pocket with a subroutine)
G21 G17 G90 G64 P0.01 Q0.01
#<depth> = -1.5
o<circle> sub
  G0 X[#1 + #2] Y0
  G1 Z#<depth> F120
  G90.1
  G2 X[#1 + #2] Y0 I#1 J0 F300
  G91.1
  G0 Z5
o<circle> endsub
T1 M6
M3 S12000
o<circle> call [20] [5]
M5
M2
"""),
    ),
    Written(
        "machinekit-fdm-job",
        "print.ngc",
        Label("machinekit", why="Machinekit FDM remaps: M104 P0 S, M106 P1 I1, G22/G23 retract, A-axis extrusion"),
        _job("""
M104 P0 S210
M140 S60
M190 S60
M109 P0 S210
M106 P1 I1 S255
G21 G90
G0 X10 Y10 Z0.3 F6000
G1 X60 Y10 A2.1 F1800
G1 X60 Y60 A4.2
G22
G0 X10 Y60
G23
G1 X10 Y10 A6.3 F1800
M104 P0 S0
M2
"""),
    ),
    Written(
        "carvera-laser",
        "engrave.nc",
        Label("carvera", why="M321 / M322 laser mode (Carvera), power as S0.x on G1"),
        _job("""
G90 G21
M321                ; laser mode
G0 X10 Y10
G1 X60 Y10 F1200 S0.4
G1 X60 Y60 S0.4
G0 X10 Y60
G1 X10 Y10 S0.2
M322                ; leave laser mode
G28
M30
"""),
    ),
    Written(
        "carvera-atc-probe",
        "facing.cnc",
        Label("carvera", why="M490.1/M490.2 tool clamp, M491.1 tool-break check, M370 levelling data (Carvera)"),
        _job("""
G90 G94 G17 G21
M370                ; clear the levelling data
T1 M6
M491.1 H0.1         ; tool-break check
S12000 M3
G54
G0 X0 Y0 Z5
G1 Z-0.5 F300
G1 X100 F1200
G1 Y20
G1 X0
M5
M490.2              ; release
M490.1              ; clamp
G28
M30
"""),
    ),
    Written(
        "grbl-laser-with-settings",
        "laser_grbl.gcode",
        Label("generic", why="$32=1 (GRBL laser mode setting), $H, M4 dynamic laser power"),
        _job("""
$32=1
$H
G21 G90
M4 S0
G0 X10 Y10
G1 X60 F1000 S800
G1 Y60
G1 X10
G1 Y10
M5
M2
"""),
    ),
)

WRITTEN = ISSUE + HANDWRITTEN


# -- the cases ------------------------------------------------------------------------------------


def _corpus_hyrel_jobs() -> list[CorpusFile]:
    return [f for f in corpus_labels() if f.label.dialect == "hyrel" and f.label.certain]


def _varied(label: Label, why: str) -> Label:
    return Label(label.dialect, label.flavor, label.version, label.printer, label.certain, why)


def cases() -> list[Case]:
    """Every variant and hand-written job, with ids that say what it is."""
    out: list[Case] = []
    # Hyrel jobs to vary: (id, file name, label, text maker, from the corpus)
    hyrel: list[tuple[str, str, Label, Callable[[], str], bool]] = [
        (f.path, _stem(f.path), f.label, (lambda p=f.path: corpus_text(p)), True) for f in _corpus_hyrel_jobs()
    ]
    hyrel += [(w.id, w.name, w.label, (lambda t=w.text: t), False) for w in HANDWRITTEN if w.hyrel_job]

    for ident, name, label, text, corpus in hyrel:
        out.append(
            Case(
                f"stripped:{ident}",
                "stripped",
                name,
                _varied(label, "comments stripped"),
                lambda t=text: strip_comments(t()),
                corpus,
            )
        )
    for ident, name, label, text, corpus in hyrel:
        for habit, add in MARLIN_HABITS:
            out.append(
                Case(
                    f"marlin-habit:{habit}:{ident}",
                    "marlin-habit",
                    name,
                    _varied(label, f"one Marlin habit: {habit}"),
                    lambda t=text, a=add: a(t()),
                    corpus,
                )
            )
    for ident, name, label, text, corpus in hyrel:
        if ident in _FEW_V5_ADDRESSES:
            continue
        wrong = V4_WRONG_LINES if label.version == "4" else V5_WRONG_LINES
        for what, add in wrong:
            out.append(
                Case(
                    f"wrong-version:{what}:{ident}",
                    "wrong-version",
                    name,
                    _varied(label, f"one line of the other version: {what}"),
                    lambda t=text, a=add: a(t()),
                    corpus,
                )
            )
    for f in corpus_labels():
        if f.label.dialect != "marlin" or not f.label.certain or not f.path.startswith("marlin/"):
            continue
        if f.path in _NOT_SLICER_JOBS:
            continue
        for what, comment in HYREL_COMMENTS:
            out.append(
                Case(
                    f"hyrel-comment:{what}:{f.path}",
                    "hyrel-comment",
                    _stem(f.path),
                    _varied(f.label, f"Hyrel-looking comment {comment!r} on top"),
                    lambda p=f.path, c=comment: f"{c}\n{corpus_text(p)}",
                    True,
                )
            )
    for path, source in TRANSLATED:
        name = _with_suffix(_stem(path), ".hyrel.gcode")
        out.append(
            Case(
                f"translated:{source}:{path}",
                "translated",
                name,
                Label("hyrel", version="5", why=f"gclint translate --from {source} --to hyrel"),
                lambda p=path, s=source, n=name: translate_to_hyrel(corpus_text(p), s, n),
                True,
            )
        )
    for kind, written in (("issue", ISSUE), ("handwritten", HANDWRITTEN)):
        for w in written:
            out.append(Case(f"{kind}:{w.id}", kind, w.name, w.label, lambda t=w.text: t))
    ids = [c.id for c in out]
    assert len(ids) == len(set(ids)), "case ids must be unique"
    return out


def detect_text(text: str, name: str):
    """The context detection gives ``text`` told it is the file ``name`` (nothing else given)."""
    from gclint.context import infer_source
    from gclint.syntax.source import Source

    source = Source.from_text(text, name)
    try:
        return infer_source(source, name)
    finally:
        source.close()


def detect_file(path: Path, name: str):
    """The context of a file on disk, as ``gclint check`` reads it (its head, and its tail)."""
    from gclint.context import infer_source
    from gclint.syntax.source import Source

    source = Source.open(str(path))
    try:
        return infer_source(source, name)
    finally:
        source.close()


def iter_kinds(items: list[Case]) -> Iterator[str]:
    return iter(dict.fromkeys(c.kind for c in items))
