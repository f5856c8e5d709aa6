"""atheris fuzz target for the checker: ``Linter.check_source`` on any bytes, with options taken from the
first bytes (dialect, printer, loaded heads, all rules), must never raise, never hit an internal error in a
rule, and produce well-formed findings with secrets masked in SC findings.

    python fuzz/fuzz_check.py -max_total_time=300 fuzz/corpus_check   (or: python scripts/fuzz.py)
"""

from __future__ import annotations

import io
import sys

import _common  # noqa: F401  (sys.path)
import atheris

with atheris.instrument_imports():
    from gclint import secrets
    from gclint.engine import Linter, Options
    from gclint.syntax.source import Source, SourceError

DIALECTS = ("auto", "hyrel", "hyrel-v4", "marlin", "reprap", "machinekit", "carvera")
PRINTERS = ("30m", "esr", "ehr", "16a", "16a-dual")
LINTERS: dict[tuple, Linter] = {}
STATS = _common.Stats("check")


def _linter(key: tuple) -> Linter:
    linter = LINTERS.get(key)
    if linter is None:
        dialect, printer, loaded = key
        linter = LINTERS[key] = Linter(Options(dialect=dialect, printer=printer, loaded=loaded, select=["ALL"]))
    return linter


def TestOneInput(data: bytes) -> None:
    STATS.tick()
    fdp = atheris.FuzzedDataProvider(data)
    dialect = DIALECTS[fdp.ConsumeIntInRange(0, len(DIALECTS) - 1)]
    printer = PRINTERS[fdp.ConsumeIntInRange(0, len(PRINTERS) - 1)]
    mask = fdp.ConsumeIntInRange(0, (1 << 20) - 1)
    loaded = None if mask & 1 else frozenset(i for i in range(20) if mask >> (i + 1) & 1)
    payload = fdp.ConsumeBytes(fdp.remaining_bytes())
    try:
        source = Source(io.BytesIO(payload), "fuzz.gcode")
    except SourceError:
        return
    result = _linter((dialect, printer, loaded)).check_source(source)
    if result.error is not None:  # refused (not G-code, broken UTF-16), never a rule's internal error
        assert "\n" not in result.error and "internal error" not in result.error, result.error
    for f in result.findings:
        assert len(f.code) == 5 and f.line >= 1 and f.column >= 1 and "\n" not in f.message, f
        if f.code.startswith("SC") and f.source is not None:
            assert secrets.mask(f.source) == f.source, f


def main() -> None:
    atheris.Setup(sys.argv, TestOneInput)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
