"""Benchmark: folder walks that a hostile checkout makes expensive (issue 25).

* Path patterns: ``*a*a*a*a*a*a*a*a*a*a*a*ac`` against ``aaa....gcode`` names of 40 to 640 characters, with
  ``gclint.globs`` (exclude patterns) and ``gclint.gitignore`` (.gitignore lines), each against ``*.gcode``
  on the same names in the same run.  A regular expression built from such a pattern (pathspec, the former
  ``compile_glob``) took minutes at 40-60 characters; the matcher is bounded by name length x pattern
  length, so each doubling of the name should cost about 2x.
* The same through the command line: a repository whose ``.gitignore`` and ``extend-exclude`` hold the
  pattern, 200 jobs with 60-character names, against the same walk with ``*.tmp`` instead.
* Deep folders: ``gclint check`` over a tree N folders deep with a job in every folder (N = 375, 750,
  1,500), against the same number of jobs in one folder.  Before, 1,500 levels took 103 s.  Ratios of
  consecutive depths: 2.0 is linear in the number of folders (the system's own path lookups grow with
  the depth of each path, so a little more is expected).

    python bench/bench_walk.py [--depths 375,750,1500]

Not a test: the machine is shared; compare ratios within one run.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

HOSTILE = "*a*a*a*a*a*a*a*a*a*a*a*ac"
JOB = "; gclint: dialect=marlin\nG28\nG1 X1 Y1 F600\n"


def _best(func, repeat: int = 5) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        func()
        best = min(best, time.perf_counter() - start)
    return best


def patterns() -> None:
    from gclint import globs
    from gclint.gitignore import GitIgnore

    hostile, plain = GitIgnore.from_lines([HOSTILE]), GitIgnore.from_lines(["*.tmp"])
    print("pattern matching, 2,000 names each (ms); hostile / *.gcode in the same run")
    previous = None
    for n in (40, 80, 160, 320, 640):
        names = [f"{'a' * n}{i}.gcode" for i in range(2000)]
        slow = _best(lambda names=names: [globs.matches(HOSTILE, x) for x in names])
        base = _best(lambda names=names: [globs.matches("*.gcode", x) for x in names])
        ignored = _best(lambda names=names: [hostile.decide(x, False) for x in names])
        unignored = _best(lambda names=names: [plain.decide(x, False) for x in names])
        step = f", x{slow / previous:.2f} for twice the name" if previous else ""
        previous = slow
        print(
            f"  {n:>4} chars: exclude {slow * 1e3:7.1f} ({slow / base:5.1f}x *.gcode{step}); "
            f".gitignore {ignored * 1e3:7.1f} ({ignored / unignored:5.1f}x *.tmp)"
        )


def _gclint(*args: str, cwd: str) -> float:
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "gclint", "check", "-q", "--no-cache", "--jobs", "1", *args],
        cwd=cwd,
        capture_output=True,
        check=False,
    )
    return time.perf_counter() - start


def checkout(folder: str) -> None:
    subprocess.run(["git", "init", "-q", folder], check=True)
    jobs = os.path.join(folder, "jobs")
    os.mkdir(jobs)
    for i in range(200):
        with open(os.path.join(jobs, f"{'a' * 60}{i}.gcode"), "w") as fh:
            fh.write(JOB)
    timings = {}
    for name, pattern in (("*.tmp", "*.tmp"), ("hostile", HOSTILE)):
        with open(os.path.join(folder, ".gitignore"), "w") as fh:
            fh.write(pattern + "\n")
        timings[name] = _gclint("--extend-exclude", pattern, "jobs", cwd=folder)
    ratio = timings["hostile"] / timings["*.tmp"]
    print(
        f"checkout of 200 jobs, .gitignore and --extend-exclude {HOSTILE}: {timings['hostile']:.2f} s"
        f" ({ratio:.2f}x the same with *.tmp)"
    )


def deep(folder: str, depths: list[int]) -> None:
    print("deep folders: a job in every folder, N folders deep (s), against N jobs in one folder")
    previous = None
    for n in depths:
        tree = os.path.join(folder, f"deep{n}")
        flat = os.path.join(folder, f"flat{n}")
        os.makedirs(flat)
        path = tree
        for i in range(n):
            os.mkdir(path)
            with open(os.path.join(path, "a.gcode"), "w") as fh:
                fh.write(JOB)
            with open(os.path.join(flat, f"a{i}.gcode"), "w") as fh:
                fh.write(JOB)
            path = os.path.join(path, "d")
        nested = _gclint(os.path.basename(tree), cwd=folder)
        one = _gclint(os.path.basename(flat), cwd=folder)
        step = f", x{nested / previous:.2f} for twice the depth" if previous else ""
        previous = nested
        print(f"  {n:>5} deep: {nested:6.2f} s ({nested / one:.2f}x {n} jobs in one folder: {one:.2f} s{step})")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--depths", default="375,750,1500")
    args = parser.parse_args()
    patterns()
    folder = tempfile.mkdtemp(prefix="gclint-bench-walk-")
    try:
        checkout(os.path.join(folder, "repo"))
        deep(folder, [int(d) for d in args.depths.split(",")])
    finally:  # (shutil.rmtree recurses once per folder: past Python's limit at 1,500)
        subprocess.run(["rm", "-rf", "--", folder], check=False)


if __name__ == "__main__":
    main()
