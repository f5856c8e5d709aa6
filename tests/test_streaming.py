"""Checking streams: memory does not grow with the length of the file.

Measured as the peak resident memory of fresh processes checking generated jobs of 50k and 400k lines
fed through a generator-backed stream (the file never exists in full, in memory or on disk).  Eight
times the lines must take about the same memory: what grows is bounded (the parse cache keeps at most
8192 distinct lines).
"""

from __future__ import annotations

import io
import random


class GeneratedJob(io.RawIOBase):
    """A readable binary stream producing a sliced-looking job of ``lines`` lines on the fly."""

    def __init__(self, lines: int, seed: int = 1) -> None:
        self.remaining = lines
        self.rng = random.Random(seed)
        self.buffer = b""

    def readable(self) -> bool:
        return True

    def _more(self) -> bytes:
        out = []
        for _ in range(min(1000, self.remaining)):
            r = self.rng.random()
            if r < 0.8:
                out.append(
                    f"G1 X{self.rng.uniform(0, 200):.3f} Y{self.rng.uniform(0, 200):.3f} E{self.rng.uniform(0, 2):.5f}\n"
                )
            elif r < 0.9:
                out.append(f"G0 X{self.rng.uniform(0, 200):.2f} Y{self.rng.uniform(0, 200):.2f} F9000\n")
            elif r < 0.95:
                out.append(f";TYPE:Perimeter {self.rng.randint(0, 10**6)}\n")
            else:
                out.append(f"G1 Z{self.rng.uniform(0, 50):.2f} F600 ; layer\n")
        self.remaining -= len(out)
        return "".join(out).encode()

    def readinto(self, b) -> int:
        while len(self.buffer) < len(b) and self.remaining > 0:
            self.buffer += self._more()
        n = min(len(b), len(self.buffer))
        b[:n] = self.buffer[:n]
        self.buffer = self.buffer[n:]
        return n


_SCRIPT = """
import io, resource, sys
sys.path.insert(0, {root!r})
from tests.test_streaming import GeneratedJob
from gclint.engine import Linter, Options
from gclint.syntax.source import Source
linter = Linter(Options(dialect="marlin"))
result = linter.check_source(Source(io.BufferedReader(GeneratedJob({lines})), "generated.gcode"))
print(result.lines, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
"""


def peak_rss(lines: int) -> tuple[int, int]:
    """Lines checked and the peak resident memory (KiB) of a fresh process checking a generated job."""
    import subprocess
    import sys
    from pathlib import Path

    root = str(Path(__file__).resolve().parent.parent)
    out = subprocess.run(
        [sys.executable, "-c", _SCRIPT.format(root=root, lines=lines)], capture_output=True, text=True, check=True
    )
    checked, rss = out.stdout.split()
    return int(checked), int(rss)


def test_memory_does_not_grow_with_length():
    small_lines, small = peak_rss(50_000)
    big_lines, big = peak_rss(400_000)
    assert small_lines == 50_000 and big_lines == 400_000
    # Eight times the lines: the peak may drift by allocator noise, not grow with the file.
    assert big < small + 10 * 1024, (small, big)
