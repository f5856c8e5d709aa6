"""Every example on the Hyrel pages passes gclint's checks (issue "Hyrel rules", done means 1).

The example command lines are read in place from stored copies of the pages (``conftest.SEEDS``, in the workplace's
shared folder; a clone without it skips): the Gcode page (https://hyrel3d.com/wiki/index.php/Gcode), T_v5
(https://hyrel3d.com/wiki/index.php/T_v5) and the hidden-codes page (Sekret!, docs/sources.md): every indented block
under an "Example", "Usage", "Here are examples", "A sample
of code ..." or "Before/After editing" heading, i.e. every indented block except the parameter lists
("Parameters"), the M773 sample output and the report listings of the hidden-codes page.  Each block is
checked as one file (its lines run in sequence, as in the laser and spiral examples) with every rule
on, dialect hyrel, and head T0 loaded.

The page writes placeholders; they are made concrete the way the page decodes them:
* ``T#`` -> ``T0`` (the loaded head), ``T24`` on the bed/chamber codes M140/M141/M190/M191
  ("T# is the target bed"); ``S#`` (T_v5, M702-M704) -> ``S30`` (a squad in 30-39);
* ``Xn``, ``Sn`` ... in Usage lines -> ``X1``, ``S1`` (``X0`` on G28: "X0 ensures that the X axis is
  homed"; ``S200`` for M104/M109 head temperatures, ``S60`` for beds); ``M719 P.1 Xn Yn Zn Ln`` is
  decoded by the page as X1 Y1 Z1 L1, the same substitution;
* ``[v5+]`` (the wiki's orange v5-only marker) is dropped; ``[ SAY | PIC | ... ]`` (M0/M792 Usage, a list
  of alternatives) becomes its first alternative, ``; SAY sample message``; ``... (the rest of your
  lasering job)`` is prose and skipped; the M660 Usage line's trailing "(see [[#G1_Working_Move]] for
  other details" is a wiki cross-reference, not G-code, and is cut.

The printer is the dual-yoke 16A (ten heads, A/B axes, the lathe, its aux ports) unless the section
limits the code to other models ("(30M/ESR only)", "(older 30Ms only)": the 30M).  Where the page states
a precondition for an example, the precondition is put before it (not counted as an example line):
G81 runs after "an M660 offset must be set and applied BEFORE THIS COMMAND" and the spindle "is turned
on with an M3 or M4 before this command".
"""

from __future__ import annotations

import re

import pytest

from gclint.engine import Linter, Options
from gclint.rules.base import Severity

from .conftest import SEEDS as SHARED_SEEDS

SEEDS = SHARED_SEEDS
PAGES = {
    "gcode": "hyrel-gcode-reference.wiki.txt",
    "t_v5": "hyrel-T_v5-addressing.wiki.txt",
    "hidden": "hyrel-hidden-codes.wiki.txt",
}
# Indented blocks that are not G-code: parameter lists, sample output, report listings.
NOT_EXAMPLES = re.compile(r"^(\[v5\+\] )?Parameters$|^Sample Output$|^In addition to info|^M797 I1 reports|^Old style:")
BED_CODES = ("M140", "M141", "M190", "M191")
# Model limits named in the section text -> the printer that has the code.
MODEL_LIMITS = (
    ("(30M/ESR only)", "30m"),
    ("(older 30Ms only)", "30m"),
    ("(30M/16A only)", "16a-dual"),
    ("(16A only)", "16a-dual"),
    ("(16A with CO_2 lasers only)", "16a-dual"),
    ("Only available on Hydra 16A models", "16a-dual"),
)
DEFAULT_PRINTER = "16a-dual"
# Preconditions the page states for an example (section -> lines put before the block).
PRECONDITIONS = {
    "G81 Peck Drilling": [
        "M660 H1 Z30 ; 'an M660 offset must be set and applied BEFORE THIS COMMAND'",
        "G1 Z10 F600 H1",
        "M3 T0 S75 ; 'the spindle tool is turned on with an M3 or M4 before this command'",
    ],
}

# Example lines that the page itself says are wrong, with the page's words: (page, seed line) -> codes.
WRONG_BY_THE_PAGE = {
    # The Usage lines list every parameter of the wait, but the next sentence says "Please use EITHER (H
    # and/or C) OR (L and/or U) OR (R) with your M109 command" and "You can use Hn or Ln, but not both.
    # You can use Cn or Un, but not both." -- the template as a command is exactly what HY002 reports.
    ("gcode", 1161): {"HY002"},  # M109 T# Sn Hn Cn Ln Un Rn [v5+] W0
    ("gcode", 1336): {"HY002"},  # M190 T# Sn Hn Cn Ln Un Rn
    ("gcode", 1426): {"HY002"},  # M191 T# Sn Hn Cn Ln Un Rn
}


def example_blocks():
    """(page, section, heading, section text, [(seed line number, text)]) for every example block."""
    for page, name in PAGES.items():
        text = (SEEDS / name).read_text(encoding="utf-8")
        sections: dict[str, list[str]] = {}
        found = []
        section = heading = ""
        block: list[tuple[int, str]] = []
        for number, line in enumerate(text.split("\n"), 1):
            sections.setdefault(section, []).append(line)
            if not line.strip():
                continue  # blank lines do not end a block (the laser example has them)
            if line.startswith(" "):
                block.append((number, line.strip()))
                continue
            if block:
                found.append((section, heading, block))
                block = []
            if line.startswith("="):
                section = line.strip("= ").strip()
            heading = line.strip()
        if block:
            found.append((section, heading, block))
        for section, heading, lines in found:
            if not NOT_EXAMPLES.search(heading):
                yield page, section, heading, "\n".join(sections.get(section, [])), lines


def concrete(line: str) -> str:
    """The page's example line with its placeholders made concrete (see the module docstring)."""
    line = line.replace("[v5+] ", "").replace("[v5+]", "")
    line = re.sub(r"\s*\(see \[\[.*$", "", line)
    code = line.split()[0] if line.split() else ""
    line = line.replace("T#", "T24" if code in BED_CODES else "T0").replace("S#", "S30")
    line = line.replace("[ SAY | PIC | VID | SEND | BEEP | SHELL ]", "; SAY sample message")

    def value(m: re.Match) -> str:
        letter = m.group(1)
        if code == "G28":
            return letter + "0"
        if letter == "S" and code in ("M104", "M109"):
            return "S200"
        if letter == "S" and code in BED_CODES:
            return "S60"
        return letter + "1"

    return re.sub(r"(?<![A-Za-z;(])([A-Z])n\b", value, line)


def printer_for(section_text: str) -> str:
    for words, printer in MODEL_LIMITS:
        if words in section_text:
            return printer
    return DEFAULT_PRINTER


def check_blocks():
    """Check every block; returns (example lines, command lines, {(page, seed line): {codes}} of errors,
    the findings of every level as text for messages)."""
    linters: dict[str, Linter] = {}
    lines_checked = commands_checked = 0
    errors: dict[tuple[str, int], set[str]] = {}
    details: list[str] = []
    for page, section, _heading, section_text, block in example_blocks():
        printer = printer_for(section_text)
        linter = linters.get(printer)
        if linter is None:
            linter = linters[printer] = Linter(
                Options(dialect="hyrel", printer=printer, loaded=frozenset({0}), select=["ALL"])
            )
        pre = PRECONDITIONS.get(section, [])
        rows = [(number, concrete(text)) for number, text in block if not text.startswith("...")]
        source = "\n".join([*pre, *(text for _, text in rows)]) + "\n"
        result = linter.check_text(source, f"{page}:{block[0][0]}")
        lines_checked += len(rows)
        commands_checked += sum(1 for _, text in rows if text and text[0] not in ";(")
        for f in result.findings:
            index = f.line - 1 - len(pre)
            if index < 0:
                details.append(f"precondition of {section}: {f.code} {f.message}")
                continue
            number, text = rows[index]
            if f.severity == Severity.ERROR:
                errors.setdefault((page, number), set()).add(f.code)
            details.append(f"{page}:{number} {text!r}: {f.code} {f.severity.label} {f.message}")
    return lines_checked, commands_checked, errors, details


@pytest.fixture(scope="module")
def checked():
    if not SEEDS.is_dir():
        pytest.skip(f"seed pages not found at {SEEDS}")
    return check_blocks()


def test_every_example_line_is_collected(checked):
    lines, commands, _, _ = checked
    # 288 lines in the example/usage blocks of the three seed pages, 282 of them with a command (the
    # others are comment lines such as "(followed by)"); the seeds are fixed, so the counts are exact.
    assert (lines, commands) == (288, 282), (lines, commands)
    print(f"\n{lines} example lines checked ({commands} with commands)")


def test_no_error_unless_the_page_says_the_example_is_wrong(checked):
    _, _, errors, details = checked
    unexpected = {key: codes - WRONG_BY_THE_PAGE.get(key, set()) for key, codes in errors.items()}
    unexpected = {key: codes for key, codes in unexpected.items() if codes}
    assert not unexpected, "\n".join(d for d in details if " error " in d)


def test_the_wrong_examples_are_reported(checked):
    _, _, errors, _ = checked
    for key, codes in WRONG_BY_THE_PAGE.items():
        assert codes <= errors.get(key, set()), key


def test_page_examples_with_their_real_addresses():
    """A few page examples with the addresses the T_v5 page gives (no placeholder)."""
    linter = Linter(Options(dialect="hyrel", printer="16a-dual"))
    text = (
        "\n".join(
            [
                "M6 T1 O2 X0 Y0 Z0",  # T_v5, Two Heads Loaded
                "M6 T2 O3 X0 Y0 Z0",
                "T1",  # Explicit Mode: "force focus with a T command ... before your first print move"
                "M109 T1 S240 L10 U5",  # M109 Example 4
                "M190 T24 S60 H55",  # M190 Example 3, bed 1
                "M702 T1 S30",  # T_v5 M702
                "M703 T2 S30",
                "G1 X50 Y75 E1 F1800",
                "M704 T2 S30",
                "M30",
            ]
        )
        + "\n"
    )
    findings = [f for f in linter.check_text(text).findings if f.severity >= Severity.WARNING]
    assert findings == [], findings
