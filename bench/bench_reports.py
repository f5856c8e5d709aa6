"""Benchmark: peak memory of whole ``gclint check`` runs whose size is in the findings, the suppression
comments or the job summary rather than in one line (the attacker review's cases A, B and C).

    python bench/bench_reports.py [CASE ...] [--scale F]     (CASE: many, noqa, disable, setpoints; default all)

Each case writes its input to a temporary folder, then runs ``python -m gclint check --no-cache`` in a
child process measured by ``/usr/bin/time -f %M`` (peak resident memory, KiB) and prints MB, seconds and
the exit code.  The goal (docs/security.md): memory stays under 100 MB whatever the input, and does not
grow with the number of files, findings or suppression comments.

* many: 60 files of 25,000 lines, each line with several findings and a secret (1.2 million findings
  kept: 20,000 a file), every report format (``-j 1``; github also ``-j 2``).
* noqa: a job of N lines each with ``; noqa: HY001`` (300k, 600k, 1.2M lines: flat or linear?).
* disable: N ``gclint: disable`` / ``enable`` pairs.
* setpoints: the HTML report of a job with 1.5 million distinct Z heights and set-points (the job summary
  and the plot must stay bounded).

Not a test: the figures depend on the machine.  ``--scale 0.1`` runs smaller inputs for a quick look.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def measure(args: list[str], cwd: str) -> dict:
    """Run ``gclint ARGS`` in a child process; peak RSS (MB), seconds, exit code, last stderr line."""
    cmd = ["/usr/bin/time", "-f", "PEAK %M", sys.executable, "-m", "gclint", *args]
    start = time.perf_counter()
    proc = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, errors="replace")
    seconds = time.perf_counter() - start
    lines = proc.stderr.splitlines()
    peak = next((int(line.split()[1]) for line in reversed(lines) if line.startswith("PEAK ")), 0)
    last = next((line for line in reversed(lines) if not line.startswith("PEAK ")), "")
    return {"peak_mb": peak / 1024, "seconds": seconds, "exit": proc.returncode, "stderr": last[-160:]}


def show(label: str, r: dict) -> None:
    print(f"{label:<58} {r['peak_mb']:8.1f} MB  {r['seconds']:7.1f} s  exit {r['exit']}  {r['stderr']}", flush=True)


def many(folder: str, scale: float) -> None:
    files = max(2, int(60 * scale))
    jobs = os.path.join(folder, "many")
    os.makedirs(jobs, exist_ok=True)
    text = "G28 X0 Y0\n" + "M109 T40 S200 ; password=hunter2 hunter3\n" * 25000 + "M30\n"
    for i in range(files):
        with open(os.path.join(jobs, f"j{i:02}.gcode"), "w") as fh:
            fh.write(text)
    for fmt, jobs_n in (("text", 1), ("json", 1), ("sarif", 1), ("junit", 1), ("html", 1), ("github", 2)):
        out = os.path.join(folder, f"many.{fmt}")
        r = measure(["check", "--no-cache", "-j", str(jobs_n), "-f", fmt, "-o", out, "many"], folder)
        size = os.path.getsize(out) / 1e6 if os.path.exists(out) else 0.0
        show(f"many: {files} files x 25k lines, -f {fmt} -j {jobs_n} ({size:.0f} MB report)", r)
        if os.path.exists(out):
            os.unlink(out)
    r = measure(["check", "--no-cache", "-j", "1", "--statistics", "many"], folder)
    show(f"many: {files} files, --statistics", r)


def noqa(folder: str, scale: float) -> None:
    for n in (300_000, 600_000, 1_200_000):
        n = int(n * scale)
        path = os.path.join(folder, "db.gcode")
        with open(path, "w") as fh:
            fh.write("G28 X0 Y0\n" + "G1 X1 F100 ; noqa: HY001\n" * n + "M30\n")
        show(
            f"noqa: {n:,} lines with '; noqa: HY001', -f json",
            measure(["check", "--no-cache", "-f", "json", path], folder),
        )
        os.unlink(path)


def disable(folder: str, scale: float) -> None:
    n = int(400_000 * scale)
    path = os.path.join(folder, "pairs.gcode")
    with open(path, "w") as fh:
        fh.write("G28 X0 Y0\n" + "; gclint: disable=HY001\nG1 X1 F100\n; gclint: enable=HY001\n" * n + "M30\n")
    show(f"disable: {n:,} disable/enable pairs, -f json", measure(["check", "--no-cache", "-f", "json", path], folder))
    os.unlink(path)


def setpoints(folder: str, scale: float) -> None:
    n = int(1_500_000 * scale)
    path = os.path.join(folder, "zs2.gcode")
    with open(path, "w") as fh:
        fh.write("G28 X0 Y0\n")
        for i in range(n):
            fh.write(f"G1 Z{i // 1000}.{i % 1000:03d} E1 F100\nM104 T0 S{i // 10}.{i % 10}\n")
        fh.write("M30\n")
    out = os.path.join(folder, "o.html")
    r = measure(["check", "--no-cache", "-f", "html", "-o", out, path], folder)
    size = os.path.getsize(out) / 1e6 if os.path.exists(out) else 0.0
    show(f"setpoints: {n:,} distinct Z and set-points, -f html ({size:.1f} MB page)", r)
    os.unlink(path)


CASES = {"many": many, "noqa": noqa, "disable": disable, "setpoints": setpoints}


def main(argv: list[str]) -> None:
    scale = 1.0
    if "--scale" in argv:
        i = argv.index("--scale")
        scale = float(argv[i + 1])
        del argv[i : i + 2]
    chosen = [a for a in argv if a in CASES] or list(CASES)
    with tempfile.TemporaryDirectory(prefix="gclint-bench-") as folder:
        for name in chosen:
            CASES[name](folder, scale)


if __name__ == "__main__":
    main(sys.argv[1:])
