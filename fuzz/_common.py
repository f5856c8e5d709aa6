"""Shared set-up of the fuzz targets: a seed corpus of real-looking lines and a statistics counter."""

from __future__ import annotations

import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))  # run from a checkout without installing

SEED_LINES = [
    b"G1 X10.5 Y-3 E0.12345 F1800",
    b"g1x10y20",
    b"N10 G1 X1*57",
    b"M109 T0 S200 H5 L10",
    b"M229 E1 D1",
    b"M792 ; SAY hi ; SHELL C:\\x.exe",
    b"M0 ; PIC C:\\a.png",
    b"M1000 rm /sd/x",
    b'M98 P"homeall.g"',
    b"M98.1 L2 {gcodes/test.cnc}",
    b"o100 if [#1 GT 2]",
    b"#<_x> = [#1 * 2]",
    b"G1 X[SIN[30]] Y#<_x>",
    b"if {move.axes[0].homed}",
    b"var x = 1",
    b"SET_FAN_SPEED FAN=part SPEED=0.5",
    b"M117 Hello (world)",
    b'M862.3 P "MK3S"',
    b"M708 A0x0b X5",
    b"; printhost_apikey = 0123456789ABCDEF0123456789ABCDEF",
    b"(unclosed",
    b"%",
    b"/G0 X1",
    b"G1 X--1",
    b"T-1",
    b"T?",
    b"M584 E0.1:0.2",
    b'M587 S"n" P"pw"',
]


class Stats:
    """Counts inputs and prints a line every few seconds (atheris prints its own statistics too)."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.count = 0
        self.start = time.monotonic()
        self.last = self.start

    def tick(self) -> None:
        self.count += 1
        now = time.monotonic()
        if now - self.last > 30:
            self.last = now
            rate = self.count / (now - self.start)
            print(
                f"[{self.name}] {self.count} inputs in {now - self.start:.0f} s ({rate:.0f}/s)",
                file=sys.stderr,
                flush=True,
            )


def write_seeds(folder: str) -> None:
    """Seed inputs: each seed line alone, with endings, and a few small files mixing them."""
    os.makedirs(folder, exist_ok=True)
    seeds = list(SEED_LINES)
    seeds.append(b"\r\n".join(SEED_LINES) + b"\r\n")
    seeds.append(b"\xef\xbb\xbf" + b"\n".join(SEED_LINES))
    seeds.append(b"\r".join(SEED_LINES[:10]))
    seeds.append("\n".join(s.decode("latin-1") for s in SEED_LINES[:8]).encode("utf-16"))
    for i, seed in enumerate(seeds):
        with open(os.path.join(folder, f"seed-{i:03d}"), "wb") as fh:
            fh.write(seed)


if __name__ == "__main__":
    write_seeds(sys.argv[1])
