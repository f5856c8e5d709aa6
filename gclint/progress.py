"""A progress bar on stderr for long checks on a terminal.

    checking [############··············]  12/40 files  31.2/98.0 MB  0:04 left 0:09

It appears only when stderr is a terminal and the run is long (many files, or many megabytes), never
for the machine formats (their readers want stdout clean and stderr quiet), and it erases itself before
the report is printed.  A background tick keeps the elapsed time moving while one big file is checked.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TextIO

from gclint.engine import FileResult

MANY_FILES = 20
MANY_BYTES = 20 * 1024 * 1024
TICK = 0.25


def wanted(requested: bool | None, fmt: str, files: list[str], stream: TextIO | None = None) -> bool:
    """Whether to show a bar: ``--progress``/``--no-progress`` decide, else a long run on a terminal.

    Never for the machine formats, and never when stderr is not a terminal (CI logs, pipes, editors).
    """
    from gclint.reports import MACHINE_FORMATS

    stream = stream if stream is not None else sys.stderr
    if requested is False or fmt in MACHINE_FORMATS:
        return False
    try:
        tty = stream.isatty()
    except (AttributeError, ValueError):
        tty = False
    if not tty or os.environ.get("TERM") == "dumb":
        return False
    if requested:
        return True
    return len(files) >= MANY_FILES or total_bytes(files) >= MANY_BYTES


def total_bytes(files: list[str]) -> int:
    total = 0
    for path in files:
        if path == "-":
            continue
        try:
            total += os.path.getsize(path)
        except OSError:
            pass
    return total


def _size(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB"):
        if n < 1000 or unit == "GB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1000
    return f"{n:.1f} GB"


def _clock(seconds: float) -> str:
    seconds = int(seconds)
    return (
        f"{seconds // 60}:{seconds % 60:02d}"
        if seconds < 3600
        else f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"
    )


class ProgressBar:
    """``bar = ProgressBar(files); runner.run(..., progress=bar.advance); bar.close()`` (or ``with``)."""

    def __init__(self, files: list[str], stream: TextIO | None = None, width: int | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.sizes = {path: (os.path.getsize(path) if path != "-" and os.path.isfile(path) else 0) for path in files}
        self.total_files = len(files)
        self.total = sum(self.sizes.values())
        self.done_files = 0
        self.done = 0
        self.start = time.monotonic()
        self.width = width
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._shown = 0
        self._thread = threading.Thread(target=self._tick, name="gclint-progress", daemon=True)
        self._thread.start()

    def __enter__(self) -> ProgressBar:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def advance(self, result: FileResult) -> None:
        """The runner's callback: one more file finished."""
        with self._lock:
            self.done_files += 1
            self.done += self.sizes.get(result.path, 0)
        self._draw()

    def line(self) -> str:
        elapsed = time.monotonic() - self.start
        share = (
            self.done / self.total if self.total else (self.done_files / self.total_files if self.total_files else 1.0)
        )
        columns = self.width or _columns(self.stream)
        text = f" {self.done_files}/{self.total_files} files"
        if self.total:
            text += f"  {_size(self.done)}/{_size(self.total)}"
        text += f"  {_clock(elapsed)}"
        if 0.1 <= share < 1 and elapsed > 1:  # earlier guesses swing too much to help
            text += f" left {_clock(elapsed / share - elapsed)}"
        bar_width = max(10, min(40, columns - len(text) - len("checking [] ") - 1))
        filled = int(bar_width * min(1.0, share))
        return f"checking [{'#' * filled}{'·' * (bar_width - filled)}]{text}"[: max(20, columns - 1)]

    def _draw(self) -> None:
        with self._lock:
            if self._stop.is_set():
                return
            text = self.line()
            pad = " " * max(0, self._shown - len(text))
            try:
                self.stream.write("\r" + text + pad)
                self.stream.flush()
            except (OSError, ValueError):
                self._stop.set()
                return
            self._shown = len(text)

    def _tick(self) -> None:
        while not self._stop.wait(TICK):
            self._draw()

    @contextmanager
    def above(self) -> Iterator[None]:
        """``with bar.above(): print(...)``: the bar is erased while something else is written to the
        terminal (a report written as files are checked, an error), and drawn again below it at the next tick."""
        with self._lock:
            self._erase()
            yield

    def _erase(self) -> None:
        # (under the lock) blank the bar's line and go back to its start
        try:
            if self._shown:
                self.stream.write("\r" + " " * self._shown + "\r")
                self.stream.flush()
        except (OSError, ValueError):
            pass
        self._shown = 0

    def close(self) -> None:
        """Stop ticking and erase the bar, so the report starts on a clean line."""
        with self._lock:
            if self._stop.is_set() and not self._shown:
                return
            self._stop.set()
            self._erase()
        if self._thread is not threading.current_thread():
            self._thread.join(timeout=1)


def _columns(stream: TextIO) -> int:
    try:
        columns = os.get_terminal_size(stream.fileno()).columns
    except (AttributeError, OSError, ValueError):
        return 80
    return columns if columns > 0 else 80  # a terminal that does not say its size
