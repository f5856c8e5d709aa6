"""Every translation source is complete (CONTRIBUTING.md, "Adding a translation source"): its translator
defines every handler its tables name, ``gclint diff`` has a reader (simulator) for its jobs, it has a table
of translation tests, and docs/translation.md has its section.  A source registered in
``gclint.translate.pairs.TO_HYREL`` without one of these fails here, naming what is missing, instead of with
an internal error on the first job that uses the missing piece.
"""

from __future__ import annotations

import re

import pytest

from gclint.dialects import get
from gclint.simulate import _SIMULATORS
from gclint.translate.pairs import TO_HYREL

from .conftest import ROOT
from .test_dialect_facts import FACTS

# The test file holding a source's table of translations (tests/test_translate_tables.py holds the helpers and
# the Marlin and RepRapFirmware rows); default tests/test_translate_<source>.py.
TABLES = {"marlin": "test_translate_tables.py", "reprap": "test_translate_tables.py"}


def _handlers(cls: type) -> dict[str, str]:
    """code -> method name, as HyrelTranslator.__init__ merges the tables (the subclass's rows last)."""
    out: dict[str, str] = {}
    for klass in reversed(cls.__mro__):
        out.update(vars(klass).get("HANDLERS", {}))
    return out


@pytest.mark.parametrize("source", sorted(TO_HYREL))
def test_every_handler_the_tables_name_is_defined(source: str) -> None:
    cls = TO_HYREL[source]
    missing = sorted(
        {f"{code} -> {name}" for code, name in _handlers(cls).items() if not callable(getattr(cls, name, None))}
    )
    assert not missing, (
        f"{cls.__name__} ({source}) names handlers it does not define: {missing} (a CncTranslator source "
        "defines spindle and tool_change itself: see machinekit.py, carvera.py)"
    )


@pytest.mark.parametrize("source", sorted(TO_HYREL))
def test_every_source_has_a_reader_for_the_diff(source: str) -> None:
    dialect = get(source)
    assert (dialect.variant_of or dialect.name) in _SIMULATORS, (
        f"{source}: no simulator in gclint/simulate/__init__.py _SIMULATORS: gclint diff would read its jobs "
        "as a machine with no devices (fdm.py and cnc.py have the readers to build on)"
    )
    assert source in FACTS, f"{source}: no row in tests/test_dialect_facts.py"


@pytest.mark.parametrize("source", sorted(TO_HYREL))
def test_every_source_has_its_tests_and_docs(source: str) -> None:
    table = ROOT / "tests" / TABLES.get(source, f"test_translate_{source}.py")
    assert table.is_file(), f"{source}: no table of translations ({table.relative_to(ROOT)}, Row(...) as the others)"
    module = TO_HYREL[source].__module__.rsplit(".", 1)[-1]
    docs = (ROOT / "docs" / "translation.md").read_text(encoding="utf-8")
    sections = re.findall(r"^### .*-> Hyrel \((.*)\)$", docs, re.MULTILINE)
    assert any(
        f"{module}.py" in s for s in sections
    ), f"{source}: docs/translation.md has no '### ... -> Hyrel (`gclint/translate/{module}.py`)' section"
