"""Benchmark the whole-run features in one run: --jobs 2 against --jobs 1 on the corpus, a cached
second run against the first, and translate against check on the marlin folder.

    python bench/bench_scale.py [CORPUS]        (default: ../shared/corpus)

Each measurement is the wall time of a real ``gclint`` command (a fresh process), best of ROUNDS.
Peak memory on a 5-million-line job: bench/bench_memory.py.  Single-file speed: bench/bench_check.py.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT = HERE.parent.parent / "shared" / "corpus"
ROUNDS = int(os.environ.get("BENCH_ROUNDS", "2"))


# As installed for a user: Python keeps the compiled bytecode of gclint's modules (some sandboxes set
# PYTHONDONTWRITEBYTECODE, which makes every command compile gclint's source again, about 0.2 s).
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def gclint(*args: str) -> float:
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "gclint", *args], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV
    )
    return time.perf_counter() - start


def best(fn, rounds: int = ROUNDS) -> float:
    return min(fn() for _ in range(rounds))


def run(corpus: Path) -> dict[str, float]:
    """Wall times (s): ``jobs1``, ``jobs2`` (the corpus), ``cold`` and ``warm`` (cache), and ``check`` and
    ``translate`` (the marlin folder, file by file), printed as they are measured."""
    out: dict[str, float] = {}
    common = ["--exit-zero", "--format", "json", "-o", os.devnull]
    gclint("rules")  # warm-up: writes the bytecode if it is missing
    j1 = out["jobs1"] = best(lambda: gclint("check", str(corpus), "--jobs", "1", "--no-cache", *common))
    j2 = out["jobs2"] = best(lambda: gclint("check", str(corpus), "--jobs", "2", "--no-cache", *common))
    print(f"check corpus --jobs 1: {j1:7.2f} s")
    print(f"check corpus --jobs 2: {j2:7.2f} s   speed-up {j1 / j2:.2f}x")

    firsts, seconds = [], []
    for _ in range(ROUNDS):
        with tempfile.TemporaryDirectory() as cache:
            firsts.append(gclint("check", str(corpus), "--cache-dir", cache, *common))
            seconds.append(gclint("check", str(corpus), "--cache-dir", cache, *common))
    cold, warm = out["cold"], out["warm"] = min(firsts), min(seconds)
    print(f"check corpus, cold cache: {cold:7.2f} s")
    print(f"check corpus, warm cache: {warm:7.2f} s   speed-up {cold / warm:.1f}x")

    marlin = corpus / "marlin"
    if marlin.is_dir():
        files = sorted(p for p in marlin.rglob("*.gcode"))

        def translate_all() -> float:
            total = 0.0
            with tempfile.TemporaryDirectory() as out:
                for i, f in enumerate(files):
                    total += gclint(
                        "translate", "--from", "marlin", "--to", "hyrel", str(f), "-o", os.path.join(out, f"{i}.gcode")
                    )
            return total

        def check_all() -> float:
            return sum(gclint("check", str(f), "--dialect", "marlin", "--no-cache", *common) for f in files)

        c = out["check"] = best(check_all)
        t = out["translate"] = best(translate_all)
        print(f"marlin folder, file by file: check {c:.2f} s, translate to hyrel {t:.2f} s   ratio {t / c:.2f}")
    return out


def main() -> None:
    run(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT)


if __name__ == "__main__":
    main()
