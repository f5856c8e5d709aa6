"""Benchmark: gclint check --jobs 1 against a bare regex tokenizer and gcodeparser, in the same run.

    python bench/bench_check.py [PATH ...]      (default: ../shared/corpus/marlin)

Each task runs in a fresh process, ROUNDS times, interleaved, and the fastest round counts (the machine
is shared and noisy: compare ratios measured in the same run, not absolute speeds across runs).  Prints
lines/s, the ratio to the regex baseline, and peak memory.  Not a test.

``BENCH_COMPILED_PYTHON=/path/to/python`` adds the same checks run by another interpreter that has a
compiled build of gclint installed (setup.py no longer offers one: the mypyc build failed type checks).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT = HERE.parent.parent / "shared" / "corpus" / "marlin"
ROUNDS = int(os.environ.get("BENCH_ROUNDS", "3"))
TASKS = ["regex", "gcodeparser", "check", "check-hyrel"]


COMPILED = os.environ.get("BENCH_COMPILED_PYTHON")


def measure(task: str, paths: list[str]) -> dict:
    python = sys.executable
    if task.endswith(" (mypyc)"):
        python, task = COMPILED, task[: -len(" (mypyc)")]
    out = subprocess.run([python, str(HERE / "_measure.py"), task, *paths], check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def available_tasks() -> list[str]:
    tasks = list(TASKS)
    try:
        import gcodeparser  # noqa: F401
    except ImportError:
        tasks.remove("gcodeparser")
        print("(gcodeparser not installed: pip install gcodeparser, or pip install -e '.[bench]')")
    if COMPILED:
        tasks += ["check (mypyc)", "check-hyrel (mypyc)"]
    return tasks


def run(tasks: list[str], paths: list[str], rounds: int = ROUNDS) -> dict[str, dict]:
    """The fastest of ``rounds`` interleaved rounds of each task (a fresh process each)."""
    best: dict[str, dict] = {}
    for _ in range(rounds):
        for task in tasks:
            r = measure(task, paths)
            if task not in best or r["seconds"] < best[task]["seconds"]:
                best[task] = r
    return best


def speed(result: dict) -> float:
    return result["lines"] / result["seconds"]


def main() -> None:
    paths = sys.argv[1:] or [str(DEFAULT)]
    tasks = available_tasks()
    best = run(tasks, paths)
    base = speed(best["regex"])
    print(f"{'task':<22}{'lines':>12}{'seconds':>10}{'lines/s':>12}{'vs regex':>10}{'peak MB':>10}")
    for task in tasks:
        r = best[task]
        print(
            f"{task:<22}{r['lines']:>12,}{r['seconds']:>10.2f}{speed(r):>12,.0f}{speed(r) / base:>9.2f}x{r['peak_mb']:>10.0f}"
        )
    if "gcodeparser" in best:
        gp = speed(best["gcodeparser"])
        for task in [t for t in tasks if t.startswith("check")]:
            print(f"{task:<22} vs gcodeparser: {speed(best[task]) / gp:.2f}x")


if __name__ == "__main__":
    main()
