"""A job that is not G-code by its content: the security rules read it anyway, and the check fails.

A file named on the command line, or found in a folder under a G-code extension, is a job as far as a
printer is concerned: nothing in a firmware looks at the first line (``#!/bin/sh``, ``[section]``,
``key = value``, an Org heading) or at a NetCDF magic number before running the rest.  Marlin,
RepRapFirmware and Smoothieware read a file from the SD card line by line, as C's ``fgets`` does, into a
C string: a line's text ends at its first NUL byte and the next line starts after the next line feed.

So a file the check refuses as "not G-code" is read here the same way (each line cut at its first NUL),
by the SC rules alone, and the result carries an error (exit 2): the gate never passes a file it did not
read as G-code.  The user's own command line or ``--config`` can exclude such files (a NetCDF ``.nc``).
"""

from __future__ import annotations

import os
import stat

from gclint import bgcode
from gclint.engine import FileResult, Linter
from gclint.syntax.source import CHUNK, UTF8_BOM, ByteStream, Source, SourceError

_DECODED_BOMS = (b"\xff\xfe", b"\xfe\xff", b"\x00\x00\xfe\xff")  # UTF-16/32: Source decodes these itself
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)


class CutAtNul:
    """A byte stream read as ``fgets`` into a C string sees it: each line up to its first NUL byte, then
    its line feed.  ``prefix`` comes first (a UTF-8 byte order mark, so that ``Source`` reads the bytes
    as text instead of refusing a binary head: the rules must see what a firmware sees)."""

    def __init__(self, raw, prefix: bytes = b"") -> None:
        self._raw = raw
        self._pending = bytearray(prefix)
        self._dropping = False  # past a NUL: the rest of the line is not part of the string
        self._eof = False

    def read(self, size: int = -1) -> bytes:
        while (size is None or size < 0 or len(self._pending) < size) and not self._eof:
            block = self._raw.read(CHUNK)
            if not block:
                self._eof = True
                break
            self._cut(block)
        if size is None or size < 0:
            size = len(self._pending)
        out = bytes(self._pending[:size])
        del self._pending[:size]
        return out

    def _cut(self, data: bytes) -> None:
        start, end = 0, len(data)
        while start < end:
            newline = data.find(b"\n", start)
            stop = end if newline < 0 else newline
            if not self._dropping:
                nul = data.find(b"\0", start, stop)
                self._pending += data[start : stop if nul < 0 else nul]
                self._dropping = nul >= 0
            if newline < 0:
                return
            self._pending += b"\n"
            self._dropping = False
            start = newline + 1

    def close(self) -> None:
        self._raw.close()


def scan(path: str, linter: Linter, reason: str) -> FileResult:
    """The SC findings of the regular file ``path`` read as a firmware reads it, with an error saying it
    is not G-code (``reason``, one line naming the file).  ``linter`` checks the security rules only."""
    error = (
        f"{reason}: only the security rules read it, as a firmware would; exclude it on the command line or"
        " with --config if it is not a job"
    )
    try:
        fd = os.open(path, os.O_RDONLY | _NONBLOCK)  # (a pipe swapped in must not block the run)
    except OSError:
        return FileResult(path, error=reason, not_gcode=True)
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):  # a pipe or device was read once already: not again
            os.close(fd)
            return FileResult(path, error=reason, not_gcode=True)
        raw = os.fdopen(fd, "rb")
    except OSError:
        os.close(fd)
        return FileResult(path, error=reason, not_gcode=True)
    try:
        head = raw.read(4)
        raw.seek(0)
        if head == bgcode.MAGIC:  # (a firmware reads a binary G-code file by its blocks, never as text)
            return _scan_bgcode(path, raw, linter, error)
        stream: ByteStream = raw
        if not head.startswith(_DECODED_BOMS):
            stream = CutAtNul(raw, b"" if head.startswith(UTF8_BOM) else UTF8_BOM)
        source = Source(stream, path, close=True, cut_long_lines=True)
        result = linter.check_source(source, sniff=False)
    except SourceError as exc:
        raw.close()
        return FileResult(path, error=f"{reason}; {exc}", not_gcode=True)
    result.error = error if result.error is None else f"{error}; {result.error}"
    result.not_gcode = True
    return result


def _scan_bgcode(path: str, raw, linter: Linter, error: str) -> FileResult:
    """The SC findings of the G-code blocks of a binary G-code file that gclint can decode (``gclint.bgcode``),
    with an error naming the blocks it could not read."""
    try:
        data = raw.read(bgcode.MAX_FILE + 1)
    finally:
        raw.close()
    try:
        text, unread = bgcode.decode(data[: bgcode.MAX_FILE])
    except ValueError:
        text, unread = b"", 1
    if unread or len(data) > bgcode.MAX_FILE:
        count = max(unread, 1)
        blocks = "1 G-code block is" if count == 1 else f"{count} G-code blocks are"
        error += f"; {blocks} compressed or encoded in a way gclint cannot read (heatshrink, MeatPack)"
    try:
        result = linter.check_source(Source.from_bytes(text, path, cut_long_lines=True), sniff=False)
    except SourceError as exc:
        return FileResult(path, error=f"{error}; {exc}", not_gcode=True)
    result.error = error if result.error is None else f"{error}; {result.error}"
    result.not_gcode = True
    return result
