"""Mutation test of ``gclint diff`` (issue 27): every job of tests/mutations.py translated by gclint, the output
edited once per mutant; prints the kill rate per kind of meaning-changing edit, the false alarms per kind of
meaning-preserving edit, and each survivor and false alarm.

    python bench/bench_mutations.py [--per-kind N] [--fast] [--job SUBSTRING]

Goal (issue 27): at least 98 % of the meaning-changing edits killed (reported as a difference no finding
explains, or one the edited line's own finding explains), no difference at all after a meaning-preserving
edit; the unedited translations have no unexplained difference.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests.mutations import FAST, JOBS, judge, mutants, prepare  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--per-kind", type=int, default=3, help="edits of each kind per job (default 3)")
    parser.add_argument("--fast", action="store_true", help="the jobs of the CI test only")
    parser.add_argument("--job", default="", help="only jobs whose name contains this")
    args = parser.parse_args()
    jobs = [j for j in (FAST if args.fast else JOBS) if args.job in j.name]
    start = time.perf_counter()
    changing: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    keeping: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    survivors, alarms, dirty, undone = [], [], [], []
    used = 0
    for job in jobs:
        prepared = prepare(job)
        if prepared.unexplained:
            dirty.append((job, prepared.unexplained))
        count = 0
        for mutant in mutants(prepared.translation, prepared.cnc, args.per_kind):
            verdict = judge(prepared, mutant)
            count += 1
            table = keeping if mutant.preserving else changing
            row = table[mutant.kind]
            row[0] += 1
            if mutant.preserving:
                if verdict.new:
                    row[1] += 1
                    alarms.append(verdict)
            elif verdict.killed:
                row[1] += 1
            elif verdict.undoes:
                row[0] -= 1
                undone.append(verdict)
            else:
                survivors.append(verdict)
        used += count > 0
        print(f"{job.name}: {count} edits", flush=True)
    total = sum(r[0] for r in changing.values())
    killed = sum(r[1] for r in changing.values())
    print(f"\nmeaning-changing edits: {total} over {used} jobs; killed {killed} ({100 * killed / max(total, 1):.1f} %)")
    for kind, (n, k) in sorted(changing.items()):
        print(f"  {kind:28} {k:4}/{n:<4} {100 * k / max(n, 1):6.1f} %")
    total_keep = sum(r[0] for r in keeping.values())
    false = sum(r[1] for r in keeping.values())
    print(f"meaning-preserving edits: {total_keep}; false alarms {false}")
    for kind, (n, k) in sorted(keeping.items()):
        print(f"  {kind:28} {k:4}/{n:<4} false alarms")
    for job, diffs in dirty:
        print(f"\nunedited translation with unexplained differences: {job.name}")
        for d in diffs[:5]:
            print(f"  {d.source_line}: {d.aspect}: {d.source} -> {d.output}")
    print(f"edits that took the output back to the source's meaning (not counted): {len(undone)}")
    for title, verdicts in (("survivors", survivors), ("false alarms", alarms), ("taken back", undone)):
        if verdicts:
            print(f"\n{title}:")
        for v in verdicts:
            m = v.mutant
            print(f"  {v.job.name} output line {m.line + 1}: {m.kind}: {m.what}")
            for d in v.new[:3] or [f"no longer: {g.aspect} {g.source} -> {g.output}" for g in v.gone[:2]]:
                if isinstance(d, str):
                    print(f"      {d}")
                    continue
                why = f"explained by {d.explained_by[0]} at {d.explained_by[1]}" if d.explained_by else "unexplained"
                print(f"      {d.aspect} at source {d.source_line}: {d.source} -> {d.output} ({why})")
    print(f"\n{time.perf_counter() - start:.1f} s")
    return 0 if killed >= 0.98 * total and not false and not dirty else 1


if __name__ == "__main__":
    sys.exit(main())
