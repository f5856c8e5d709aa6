"""Benchmark: hostile line lengths (issue 12, item 8).  Time and peak memory of ``gclint check`` on

* a job whose second line is one huge line of N MiB (default 32, 64, 128, 256), written on the fly (the
  generator never holds it); the time must grow linearly: the ratios of consecutive sizes are printed
  (2.0 is linear; the quadratic reader of before gave 2.5, 2.9, 3.4);
* a line of a million ``X1`` words (3 MB): memory (it once made a million findings and 1.1 GB);
* a 2 GiB sparse file (a G-code header, then 2 GiB of NUL bytes as one line), unless --no-sparse.

    python bench/bench_long_line.py [MIB ...] [--no-sparse]

Each run is a fresh ``python -m gclint check --jobs 1 --no-cache`` child whose peak resident memory is read
with ``resource.getrusage(RUSAGE_CHILDREN)``.  Not a test: the machine is shared, compare ratios.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

MEASURE = r"""
import json, resource, subprocess, sys, time
start = time.perf_counter()
proc = subprocess.run([sys.executable, "-m", "gclint", "check", "--jobs", "1", "--no-cache", "--format", "json",
                       sys.argv[1]], capture_output=True)
seconds = time.perf_counter() - start
findings = json.loads(proc.stdout) if proc.stdout.strip().startswith(b"[") else []
print(json.dumps({"exit": proc.returncode, "seconds": seconds,
                  "peak_mb": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024,
                  "findings": len(findings), "codes": sorted({f["code"] for f in findings}),
                  "stderr": proc.stderr.decode(errors="replace")[-300:]}))
"""


def measure(path: str) -> dict:
    out = subprocess.run([sys.executable, "-c", MEASURE, path], capture_output=True, check=True, text=True)
    return json.loads(out.stdout)


def huge_line(folder: str, mib: int) -> str:
    path = os.path.join(folder, f"line-{mib}MiB.gcode")
    block = b"9" * (1 << 20)
    with open(path, "wb") as fh:
        fh.write(b"G28\nG1 X1 Y")
        for _ in range(mib):
            fh.write(block)
        fh.write(b"\nM30\n")
    return path


def word_line(folder: str, words: int = 1_000_000) -> str:
    path = os.path.join(folder, "million-words.gcode")
    with open(path, "wb") as fh:
        fh.write(b"G28\nG1" + b" X1" * words + b"\nG1 X1 X1\n")
    return path


def sparse(folder: str, size: int = 2 << 30, text: int = 0) -> str:
    """``size`` bytes: a G-code header, ``text`` more bytes of G-code lines, then NUL bytes (a hole) as one line."""
    path = os.path.join(folder, f"sparse-{text}.gcode")
    with open(path, "wb") as fh:
        fh.write(b"; gclint: dialect=hyrel\nG28\nG1 X10 Y10\n")
        fh.write(b"G1 X10 Y10 F1800\n" * (text // 17))
        fh.truncate(size)
    return path


def main(argv: list[str]) -> None:
    sizes = [int(a) for a in argv if a.isdigit()] or [32, 64, 128, 256]
    with tempfile.TemporaryDirectory(prefix="gclint-bench-") as folder:
        tiny = os.path.join(folder, "tiny.gcode")
        with open(tiny, "wb") as fh:
            fh.write(b"G28\nG1 X1 Y1\nM30\n")
        start_up = min(measure(tiny)["seconds"] for _ in range(3))
        print(f"start-up (a 3-line job): {start_up:.2f} s; 'net' below is the time minus start-up")
        rows = []
        for mib in sizes:
            path = huge_line(folder, mib)
            r = min((measure(path) for _ in range(3)), key=lambda r: r["seconds"])
            os.unlink(path)
            r["net"] = max(r["seconds"] - start_up, 1e-3)
            rows.append((mib, r))
            print(
                f"{mib:>5} MiB line: {r['seconds']:6.2f} s (net {r['net']:.2f} s, {mib / r['net']:.0f} MiB/s)  "
                f"peak {r['peak_mb']:6.1f} MB  exit {r['exit']}  {r['findings']} findings {r['codes']}",
                flush=True,
            )
        for (a, ra), (b, rb) in zip(rows, rows[1:], strict=False):
            print(f"  net time {b}/{a} MiB: {rb['net'] / ra['net']:.2f}x (linear: {b / a:.1f}x)")
        path = word_line(folder)
        r = measure(path)
        print(f"million-word line: {r['seconds']:.2f} s  peak {r['peak_mb']:.1f} MB  {r['findings']} findings")
        if "--no-sparse" not in argv:
            path = sparse(folder)
            r = measure(path)
            print(f"2 GiB sparse file: {r['seconds']:.2f} s  peak {r['peak_mb']:.1f} MB  exit {r['exit']} (binary)")
            os.unlink(path)
            # the same after 100 kB of G-code: the NUL bytes are past the binary test, read as one 2 GiB line
            path = sparse(folder, text=100_000)
            r = measure(path)
            print(
                f"2 GiB sparse file after 100 kB of G-code: {r['seconds']:.2f} s  peak {r['peak_mb']:.1f} MB  "
                f"exit {r['exit']}  {r['codes']}"
            )


if __name__ == "__main__":
    main(sys.argv[1:])
