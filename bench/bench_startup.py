"""Benchmark: the CPU time of a one-file check (what every pre-commit run and editor start pays).

    python bench/bench_startup.py [JOB]      (default: examples/hyrel_job.gcode)

Runs ``gclint check --no-cache JOB`` in a fresh process ROUNDS times, interleaved with a bare ``python -c pass``
(the interpreter's own start) in the same run, and reports each one's fastest CPU time (user + system, from
``getrusage`` of the children) and the difference: gclint's own cost.  The goal (issue 29) is a check within
0.15 s of CPU.  Then the modules that take longest to import (``python -X importtime``).  Not a test.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROUNDS = int(os.environ.get("BENCH_ROUNDS", "15"))


def cpu(argv: list[str]) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    job = sys.argv[1] if len(sys.argv) > 1 else str(HERE.parent / "examples" / "hyrel_job.gcode")
    tasks = {
        "python -c pass": [sys.executable, "-c", "pass"],
        "gclint --version": [sys.executable, "-m", "gclint", "--version"],
        "gclint check (one file)": [sys.executable, "-m", "gclint", "check", "--no-cache", job],
    }
    best = dict.fromkeys(tasks, float("inf"))
    for _ in range(ROUNDS):
        for name, argv in tasks.items():
            best[name] = min(best[name], cpu(argv))
    base = best["python -c pass"]
    for name, seconds in best.items():
        print(f"{name:28} {seconds:6.3f} s CPU   ({seconds - base:+.3f} s over the bare interpreter)")
    goal = best["gclint check (one file)"]
    print(f"goal: a one-file check within 0.150 s CPU: {'met' if goal <= 0.150 else 'not met'} ({goal:.3f} s)")
    out = subprocess.run(
        [sys.executable, "-X", "importtime", "-m", "gclint", "check", "--no-cache", job],
        capture_output=True,
        text=True,
        check=False,
    ).stderr
    rows = []
    for line in out.splitlines():
        if line.startswith("import time:") and "|" in line:
            self_us, _total, name = (part.strip() for part in line[len("import time:") :].split("|", 2))
            if self_us.isdigit():
                rows.append((int(self_us), name))
    print("slowest imports (self time):")
    for self_us, name in sorted(rows, reverse=True)[:12]:
        print(f"  {self_us / 1000:6.1f} ms  {name}")


if __name__ == "__main__":
    main()
