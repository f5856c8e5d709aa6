"""atheris fuzz target for the result cache and the reporters (issue 12).

Two modes, chosen by the first byte:

* a job: the bytes are written to a file and checked twice through a ``ResultCache``; the second run
  must give exactly the first run's result (the cache never changes an answer), and every report format
  must render it: machine formats parse, human formats carry no raw control character, no secret
  that the masking finds in the job reaches any output;
* a cache entry: the bytes are signed with this user's key (the strongest attacker: a valid signature)
  and stored as the job's entry; reading it must never raise, and whatever it yields must render.

    python fuzz/fuzz_reports.py -max_total_time=300 fuzz/corpus_reports     (or: fuzz/run.sh 120 reports)

``one_input`` does not need atheris; tests/test_fuzz_targets.py runs it on seeds and random bytes.
"""

from __future__ import annotations

import io
import json
import os
import sys
import tempfile
import xml.etree.ElementTree as ET

import _common  # noqa: F401  (sys.path)

from gclint import runner
from gclint.cache import ResultCache
from gclint.engine import Options
from gclint.reports import ReportContext, formats

HUMAN = ("text", "concise", "full", "grouped", "github")
RAW = ("\x1b", "\x07", "\x00", "\x9b", "\u202e")
DIALECTS = ("auto", "hyrel", "marlin", "reprap", "machinekit", "carvera")
_WORK_DIR = tempfile.TemporaryDirectory(prefix="gclint-fuzz-reports-")  # (removed at exit)
_WORK = _WORK_DIR.name
JOB = os.path.join(_WORK, "fuzz.gcode")
CACHE = ResultCache(os.path.join(_WORK, "cache"), root=os.path.join(_WORK, "user"))
STATS = _common.Stats("reports")


def _key(results) -> list:
    return [(r.path, r.error, [(f.line, f.column, f.code, f.severity, f.message) for f in r.findings]) for r in results]


def render_all(results) -> None:
    for name, writer in formats().items():
        out = io.StringIO()
        writer(results, out, ReportContext(tool_version="0", statistics=True))
        text = out.getvalue()
        if name in ("json", "sarif"):
            json.loads(text)
        elif name == "junit":
            ET.fromstring(text.split("\n", 1)[1])
        elif name in HUMAN:
            assert not any(c in text for c in RAW), (name, text[:400])


def one_input(data: bytes) -> None:
    if not data:
        return
    mode, dialect, payload = data[0] % 2, DIALECTS[data[0] // 2 % len(DIALECTS)], data[1:]
    options = Options(dialect=dialect)
    with open(JOB, "wb") as fh:
        fh.write(payload if mode == 0 else b"G1 X1 X2\nM792 ; SHELL x.exe\n")
    if mode == 0:
        first = runner.run([JOB], Options(), {"dialect": dialect}, cache=CACHE)
        second = runner.run([JOB], Options(), {"dialect": dialect}, cache=CACHE)
        assert _key(second) == _key(first), "the cache changed an answer"
        render_all(second)
        return
    settings = CACHE.settings_key(options.cache_key(), ["SX002"])
    entry = CACHE._entry(JOB)
    os.makedirs(entry.parent, mode=0o700, exist_ok=True)
    try:
        with open(entry, "wb") as fh:
            fh.write(CACHE._sign(payload))
    except OSError:
        return
    result = CACHE.get(JOB, settings)  # must never raise
    if result is not None:
        render_all([result])


def TestOneInput(data: bytes) -> None:  # noqa: N802  (atheris' name)
    STATS.tick()
    one_input(data)


def main() -> None:
    import atheris

    atheris.instrument_all()
    atheris.Setup(sys.argv, TestOneInput)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
