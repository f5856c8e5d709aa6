"""Benchmark: many commands on one line (issue 25).  ``M0 `` 33,000 times on one line once took about 60 s:
each M0 (and M792) made the security rules read the rest of the line again, and ``gclint explain`` and the
editor's hover did the same per command.  For N commands (default 8,000, 16,000 and 32,000), in this process,
best of 3:

* ``check``: the Linter on the line, and on the same bytes with a line break after each command (the
  baseline: what the same commands cost across lines), every rule on, dialect auto;
* ``server``: the language server's check of the document (gclint.server.analysis.check_text) and its hover
  on the last command of the line (explain_at: the explanation of every command of the line);
* ``explain``: ``gclint explain``'s walk over the line.

For each it prints the seconds and the ratio one line / across lines (about 1 when the time per command does
not depend on where the command is; it grew with N when it was quadratic), and the ratio of consecutive N
(2.0 is linear).

    python bench/bench_many_commands.py [N ...] [--command "M0 "]

Not a test: the machine is shared, compare ratios.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from gclint import dialects  # noqa: E402
from gclint.engine import Linter, Options  # noqa: E402
from gclint.explain import explain_text  # noqa: E402


def best(task, rounds: int = 3) -> float:
    times = []
    for _ in range(rounds):
        start = time.perf_counter()
        task()
        times.append(time.perf_counter() - start)
    return min(times)


def tasks(text: str) -> dict[str, object]:
    out = {
        "check": lambda: Linter(Options()).check_text(text, "job.gcode"),
        "explain": lambda: explain_text(text, dialects.get("hyrel")),
    }
    try:
        from gclint.server.analysis import check_text, explain_at
        from gclint.server.text import Snapshot
    except ImportError:  # (the server extra is not installed)
        return out
    out["server check"] = lambda: check_text(text, "job.gcode", Options())
    last = text.rstrip("\n").split("\n")
    out["server hover"] = lambda: explain_at(Snapshot(text), len(last) - 1, len(last[-1]) - 2, dialects.get("hyrel"))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("counts", nargs="*", type=int, default=[8_000, 16_000, 32_000])
    parser.add_argument("--command", default="M0 ", help='the command repeated (default "M0 ")')
    args = parser.parse_args()
    previous: dict[str, float] = {}
    print(f"{'task':<14} {'commands':>9} {'one line':>10} {'across lines':>13} {'ratio':>6} {'vs prev':>7}")
    for count in args.counts:
        one = args.command * count + "\n"
        across = (args.command.rstrip() + "\n") * count
        one_tasks, across_tasks = tasks(one), tasks(across)
        for name, task in one_tasks.items():
            seconds = best(task)
            baseline = best(across_tasks[name])
            growth = f"{seconds / previous[name]:6.2f}x" if name in previous else ""
            previous[name] = seconds
            print(f"{name:<14} {count:>9,} {seconds:>9.3f}s {baseline:>12.3f}s {seconds / baseline:>5.2f}x {growth:>7}")


if __name__ == "__main__":
    main()
