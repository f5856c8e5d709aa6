"""Benchmark: ``gclint summary`` against ``gclint check`` of the same job, as a user runs them.

    python bench/bench_summary.py [PATH ...]      (default: the corpus's largest job)

Each command runs in a fresh process, ROUNDS times, interleaved; the least CPU time (user + system, the
process and its children) of each counts, since the machine is shared and noisy: compare the ratio, not
absolute times across runs.  Also prints the summary's own parts measured in this process (the reader's
events, the summary without the planner, the whole) for the same job.  Not a test.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
LARGEST = HERE.parent.parent / "shared" / "corpus" / "marlin" / "fabtotum" / "Socket Screwdriver 8 (M5 nuts).gcode"
ROUNDS = int(os.environ.get("BENCH_ROUNDS", "3"))


def cpu_of(args: list[str]) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-m", "gclint", *args], capture_output=True, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def parts(path: str) -> dict[str, float]:
    from gclint.dialects import get
    from gclint.engine import Linter, Options
    from gclint.simulate import simulator_for
    from gclint.summary import summarize_path
    from gclint.syntax.source import Source
    from gclint.timing import planner

    out = {}
    context = Linter(Options()).context_of(Source.open(path))
    start = time.process_time()
    for _ in simulator_for(get(context.dialect)).events(Source.open(path)):
        pass
    out["reader's events"] = time.process_time() - start
    start = time.process_time()
    summarize_path(path)
    out["summary"] = time.process_time() - start
    move = planner.Planner.move
    planner.Planner.move = lambda self, *a, **k: None  # type: ignore[method-assign]
    try:
        start = time.process_time()
        summarize_path(path)
        out["summary without the planner"] = time.process_time() - start
    finally:
        planner.Planner.move = move  # type: ignore[method-assign]
    return out


def main(paths: list[str]) -> None:
    for path in paths or [str(LARGEST)]:
        check, summary = [], []
        for _ in range(ROUNDS):
            check.append(cpu_of(["check", "-q", "--no-cache", "--exit-zero", path]))
            summary.append(cpu_of(["summary", path]))
        startup = min(cpu_of(["rules", "HY001"]) for _ in range(ROUNDS))
        print(f"{path}")
        print(f"  gclint check:   {min(check):.2f} s CPU")
        print(f"  gclint summary: {min(summary):.2f} s CPU  ({min(summary) / min(check):.1f}x check)")
        print(f"  (starting gclint: {startup:.2f} s CPU of each)")
        for name, seconds in parts(path).items():
            print(f"  in process, {name}: {seconds:.2f} s CPU")


if __name__ == "__main__":
    main(sys.argv[1:])
