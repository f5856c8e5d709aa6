"""Sources anyone can check (issue 29): nothing in the repository cites a file outside it, and every rule,
dialect and firmware inventory names a public source that docs/sources.md describes.

What counts as a citation of an outside file: a path into the workplace's research notes or seed copies
(``research/...``, ``seeds/...``, the notes and the page copies by file name), the design notes ``DESIGN.md``, or any
``../shared`` path other than the test corpus.  The corpus is data, not a citation: tests and benchmarks read it in
place (``../shared/corpus``, ``$GCLINT_CORPUS``), and code that builds a path to the shared folder from
``tests.conftest`` (``SHARED / ...``, ``SEEDS / ...``, or the file names of the page copies in a test that imports
``SEEDS``) reads test data there, which a clone without that folder skips.  Everything else must cite the public page or
repository itself (docs/sources.md).
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from gclint.dialects import all_dialects
from gclint.firmware import all_firmware
from gclint.rules.base import all_rules

ROOT = Path(__file__).resolve().parent.parent
SOURCES_DOC = ROOT / "docs" / "sources.md"

# A citation of a file outside the repository (the notes are named without their folder too).
OUTSIDE = re.compile(
    r"\.\./shared(?!/corpus)"  # the shared folder, but for the corpus
    r"|/work/shared/(?!corpus)"
    r"|(?<![\w.-])(?:research|seeds)/[\w.-]+"  # research/dialects.md, seeds/carvera-mcodes.md ...
    r"|\bDESIGN\.md\b"
    r"|(?<![\w/-])(?:hyrel_v4|firmware_codes|dialects|anchors)\.md\b"
    r"|" + r"(?<![\w-])(?:carvera-mcodes\.md|machinekit-fdm-mcodes\.md|reprap-gcode-2015\.txt|hyrel-[\w-]+\.wiki\.txt)"
)
# The local copies of public pages by their file names: data for a test that reads them in place (it imports
# SEEDS from tests.conftest), a citation anywhere else.
SEED_COPY = re.compile(r"carvera-mcodes|machinekit-fdm-mcodes|reprap-gcode-2015|\.wiki\.txt")
READS_SEEDS = re.compile(r"conftest import[^\n]*\bSEEDS\b")
# Code that builds a path into the shared folder reads test data there (see the module docstring).
DATA_PATH = re.compile(r"\b(?:SHARED|SEEDS|SHARED_SEEDS)\s*/")
SKIP_SUFFIXES = {".png", ".jpg", ".gif", ".ico", ".pdf", ".gz", ".zip", ".whl", ".pyc"}


def _repository_files() -> list[Path]:
    """The files of the checkout: git's list when there is one, else every file but the usual build folders."""
    try:
        out = subprocess.run(
            ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
            cwd=ROOT,
            capture_output=True,
            check=True,
        ).stdout
        names = [n for n in out.decode("utf-8", "surrogateescape").split("\0") if n]
        return [ROOT / n for n in names if (ROOT / n).is_file()]
    except (OSError, subprocess.CalledProcessError):
        skip = {".git", ".venv", "venv", "build", "dist", "node_modules", "__pycache__", ".pytest_cache"}
        return [p for p in ROOT.rglob("*") if p.is_file() and not skip & set(p.relative_to(ROOT).parts)]


def _outside_citations(text: str) -> list[tuple[int, str]]:
    found = []
    reads_seeds = READS_SEEDS.search(text) is not None
    for n, line in enumerate(text.splitlines(), 1):
        if DATA_PATH.search(line):
            continue
        for m in OUTSIDE.finditer(line):
            if not (reads_seeds and SEED_COPY.search(m.group(0))):
                found.append((n, m.group(0)))
    return found


def test_the_pattern_finds_the_citations_it_is_meant_to_find():
    cited = [
        "from ../shared/seeds/hyrel-gcode-reference.wiki.txt",
        "(research/dialects.md 1.1 G53)",
        "see seeds/carvera-mcodes.md",
        "Exit codes (DESIGN.md)",
        "(hyrel_v4.md: medium)",
        "firmware_codes.md section 8",
        "/work/shared/research/anchors.md",
        '"M30 | End of the program" (carvera-mcodes.md)',
        "the Gcode page (hyrel-gcode-reference.wiki.txt)",
    ]
    for line in cited:
        assert _outside_citations(line), line
    allowed = [
        "the corpus tests read ../shared/corpus in place",
        "CORPUS = SHARED / 'corpus'",
        'RESEARCH = SHARED / "research" / "firmware_codes.md"',
        "docs/sources.md, docs/translation.md",
        "Marlin/src/gcode/gcode.cpp",
        "github.com/Carvera-Community/docs, firmware/supported-commands/mcodes/README.md",
        "from .conftest import SEEDS\nPAGES = {'gcode': 'hyrel-gcode-reference.wiki.txt'}",
    ]
    for text in allowed:
        assert not _outside_citations(text), text


def test_nothing_in_the_repository_cites_a_file_outside_it():
    this = Path(__file__).resolve()
    problems = []
    for path in _repository_files():
        if path.resolve() == this or path.suffix.lower() in SKIP_SUFFIXES:
            continue
        try:
            text = path.read_text(encoding="utf-8")
        except (UnicodeDecodeError, OSError):
            continue  # binary data
        for n, what in _outside_citations(text):
            problems.append(f"{path.relative_to(ROOT)}:{n}: {what}")
    assert not problems, (
        "cite the public page or repository (docs/sources.md) instead of a file outside the repository:\n"
        + "\n".join(problems)
    )


# -- every rule, dialect and inventory names a source that docs/sources.md describes ----------------------------


def _cited_as() -> list[str]:
    """The short names docs/sources.md gives each source ("Cited as: ..." lines and the inventories' table)."""
    names: list[str] = []
    in_table = False
    for line in SOURCES_DOC.read_text(encoding="utf-8").splitlines():
        m = re.search(r"Cited as: (.*)$", line)
        if m:
            names += re.findall(r'"([^"]+)"', m.group(1))
        if line.startswith("|") and "Cited as" in line:
            in_table = True
            continue
        if in_table:
            if not line.startswith("|"):
                in_table = False
            else:
                names += re.findall(r'"([^"]+)"', line.rstrip(" |").rsplit("|", 1)[-1])
    return names


# A rule may rest on gclint's own design: then it cites the file of this repository that states it.
_IN_REPOSITORY = re.compile(r"grammar\.lark|docs/[\w-]+\.md|gclint/[\w/*.]+|\bREADME\b")


def _names_a_source(text: str, names: list[str]) -> bool:
    if any(name in text for name in names):
        return True
    for ref in _IN_REPOSITORY.findall(text):
        ref = ref.rstrip(".,;)")
        if ref == "README" or ref == "grammar.lark" or list(ROOT.glob(ref)):
            return True
    return False


def test_sources_doc_gives_names_and_addresses():
    names = _cited_as()
    assert len(names) >= 20, names
    text = SOURCES_DOC.read_text(encoding="utf-8")
    for needed in ("hyrel3d.com/wiki", "marlinfw.org", "docs.duet3d.com", "linuxcnc.org/docs", "Carvera-Community"):
        assert needed in text
    assert "confidence" in text.lower() and "medium" in text  # the uncertain v4 -> v5 entries say so


@pytest.mark.parametrize("code", sorted(all_rules()))
def test_every_rule_names_its_public_source(code):
    rule = all_rules()[code]
    assert rule.source.strip(), f"{code}: no source (Rule.source names the public source and section)"
    assert _names_a_source(rule.source, _cited_as()), (
        f"{code}: its source {rule.source!r} names none of the sources in docs/sources.md "
        "(use a name from a 'Cited as' line, or add the source there)"
    )


@pytest.mark.parametrize("dialect", [d for d in all_dialects() if d.name != "generic"], ids=lambda d: d.name)
def test_every_dialect_names_its_public_sources_with_addresses(dialect):
    assert dialect.sources, f"{dialect.name}: no sources"
    names = _cited_as()
    for source in dialect.sources:
        assert _names_a_source(source, names), f"{dialect.name}: {source!r} is not in docs/sources.md"
        assert re.search(r"https?://|github\.com/", source), f"{dialect.name}: {source!r} gives no address"


@pytest.mark.parametrize("fw", all_firmware(), ids=lambda f: f.name)
def test_every_firmware_inventory_names_its_source_with_an_address(fw):
    assert _names_a_source(fw.source, _cited_as()), f"{fw.name}: {fw.source!r} is not in docs/sources.md"
    assert re.search(r"https?://|github\.com/", fw.source), f"{fw.name}: {fw.source!r} gives no address"
