"""Read G-code bytes as lines, streaming, so that writing the lines back gives the same bytes.

* Line endings (LF, CRLF, CR, mixed) are kept per line; a missing final newline is an empty ending.
* A UTF-8 byte order mark is kept aside and written back; UTF-16 (with a BOM) is decoded and re-encoded.
* Bytes that are not UTF-8 (latin-1 comments, stray binary) decode with ``surrogateescape`` and encode
  back unchanged.
* Binary files (``.bgcode``, images, archives) are refused with a ``SourceError`` naming the problem.

The file is read in chunks of ``CHUNK`` bytes; memory does not grow with the file's length (only with
its longest line).
"""

from __future__ import annotations

import codecs
import hashlib
import io
import re
import sys
from collections.abc import Iterator
from itertools import repeat
from typing import BinaryIO

CHUNK = 1 << 20
HEAD = 1 << 16
UTF8_BOM = b"\xef\xbb\xbf"
_LINES = re.compile(r"([^\r\n]*)(\r\n|\r|\n)")


class SourceError(Exception):
    """A file that cannot be read as G-code; the message is one line for the user."""


class Source:
    """A G-code file (or stdin) opened for streaming.

    ``display`` is the name used in findings; ``encoding`` is ``"utf-8"`` (with surrogateescape) or the
    UTF-16 variant found; ``bom`` is the byte order mark to write back (may be empty).
    """

    def __init__(self, stream: BinaryIO, display: str, *, close: bool = False) -> None:
        self.display = display
        self._stream = stream
        self._close = close
        try:
            head = stream.read(HEAD)
        except OSError as exc:
            raise SourceError(f"{display}: cannot read: {exc.strerror or exc}") from None
        self._head_eof = len(head) < HEAD
        self.bom = b""
        self.encoding = "utf-8"
        if head.startswith(UTF8_BOM):
            self.bom = UTF8_BOM
            head = head[3:]
        elif head.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
            self.bom = head[:2]
            self.encoding = "utf-16-le" if head.startswith(codecs.BOM_UTF16_LE) else "utf-16-be"
            head = head[2:]
        else:
            _refuse_binary(head, display)
        self._head = head
        self._consumed = False
        self._hash = hashlib.blake2b(digest_size=16)  # of the bytes read, as read (BOM included)
        self._hash.update(self.bom)
        self._hash.update(head)
        self._complete = False

    @classmethod
    def open(cls, path: str) -> Source:
        """Open a file path (``-`` for standard input)."""
        if path == "-":
            return cls(sys.stdin.buffer, "-")
        try:
            stream = open(path, "rb")  # noqa: SIM115 - closed by Source.close / iteration end
        except FileNotFoundError:
            raise SourceError(f"{path}: no such file") from None
        except IsADirectoryError:
            raise SourceError(f"{path}: is a folder, not a file") from None
        except PermissionError:
            raise SourceError(f"{path}: permission denied") from None
        except OSError as exc:
            raise SourceError(f"{path}: cannot open: {exc.strerror or exc}") from None
        try:
            return cls(stream, path, close=True)
        except BaseException:
            stream.close()
            raise

    @classmethod
    def from_bytes(cls, data: bytes, display: str = "<bytes>") -> Source:
        return cls(io.BytesIO(data), display)

    @classmethod
    def from_text(cls, text: str, display: str = "<text>") -> Source:
        return cls.from_bytes(text.encode("utf-8", "surrogateescape"), display)

    @property
    def head_is_whole(self) -> bool:
        """True when the head read at opening is the whole file."""
        return self._head_eof

    def head_text(self, limit: int = HEAD) -> str:
        """The beginning of the file as text (for dialect detection); does not consume the stream."""
        data = self._head[:limit]
        if self.encoding == "utf-8":
            return data.decode("utf-8", "surrogateescape")
        return data[: len(data) // 2 * 2].decode(self.encoding, "replace")

    def tail_text(self, limit: int = HEAD) -> str:
        """The end of the file as text, from its first whole line: where slicers write their settings
        (PrusaSlicer's ``; printer_model = MK4S``).  Empty when the head is the whole file (read that),
        when the stream cannot seek (a pipe) or is not UTF-8.  Does not consume the stream."""
        if self._head_eof or self._consumed or self.encoding != "utf-8":
            return ""
        stream = self._stream
        try:
            if not stream.seekable():
                return ""
            here = stream.tell()
            end = stream.seek(0, io.SEEK_END)
            start = max(here, end - limit)
            stream.seek(start)
            data = stream.read(end - start)
            stream.seek(here)
        except (OSError, ValueError):
            return ""
        newline = data.find(b"\n")
        return data[newline + 1 :].decode("utf-8", "surrogateescape") if newline >= 0 else ""

    @property
    def digest(self) -> str | None:
        """A hash of every byte of the file, once it has been read to the end (else None): what was
        checked, for ``--fix`` to see that the file has not changed since."""
        return self._hash.hexdigest() if self._complete else None

    def encode(self, text: str) -> bytes:
        """Encode output text so that unchanged text gives back the original bytes."""
        if self.encoding == "utf-8":
            return text.encode("utf-8", "surrogateescape")
        return text.encode(self.encoding, "surrogatepass")

    def close(self) -> None:
        if self._close:
            self._stream.close()

    # -- iteration ---------------------------------------------------------------------------------------

    def chunks(self) -> Iterator[list[tuple[str, str]]]:
        """Yield lists of ``(text, ending)`` pairs, in file order, a chunk of the file at a time."""
        if self._consumed:
            raise RuntimeError("a Source can be read once")
        self._consumed = True
        try:
            if self.encoding == "utf-8":
                yield from self._utf8_chunks()
            else:
                yield from self._decoded_chunks()
        except OSError as exc:
            raise SourceError(f"{self.display}: read failed: {exc.strerror or exc}") from None
        finally:
            self.close()

    def lines(self) -> Iterator[tuple[str, str]]:
        """Yield ``(text, ending)`` for every line."""
        for chunk in self.chunks():
            yield from chunk

    def _utf8_chunks(self) -> Iterator[list[tuple[str, str]]]:
        buffer = self._head
        read = self._stream.read
        eof = self._head_eof
        while True:
            if not eof:
                more = read(CHUNK)
                if more:
                    self._hash.update(more)
                    buffer += more
                else:
                    eof = True
            cut = _last_line_end(buffer, eof)
            if cut:
                yield split_lines(buffer[:cut].decode("utf-8", "surrogateescape"))
                buffer = buffer[cut:]
            if eof:
                self._complete = True
                if buffer:
                    yield [(buffer.decode("utf-8", "surrogateescape"), "")]
                return

    def _decoded_chunks(self) -> Iterator[list[tuple[str, str]]]:
        decoder = codecs.getincrementaldecoder(self.encoding)("surrogatepass")
        data = self._head
        pending = ""
        while True:
            final = not data
            try:
                pending += decoder.decode(data, final=final)
            except UnicodeDecodeError:  # an odd number of bytes: cut short, or not UTF-16 at all
                raise SourceError(
                    f"{self.display}: starts with a UTF-16 byte order mark but is not valid UTF-16 text"
                ) from None
            cut = max(pending.rfind("\n"), pending.rfind("\r"))
            if cut >= 0 and (final or cut < len(pending) - 1 or pending[cut] == "\n"):
                yield split_lines(pending[: cut + 1])
                pending = pending[cut + 1 :]
            if final:
                self._complete = True
                if pending:
                    yield [(pending, "")]
                return
            data = self._stream.read(CHUNK)
            self._hash.update(data)


def _last_line_end(buffer: bytes, eof: bool) -> int:
    """Length of the longest prefix of ``buffer`` that ends with a complete line ending."""
    lf = buffer.rfind(b"\n")
    cr = buffer.rfind(b"\r")
    if cr > lf:
        if cr == len(buffer) - 1 and not eof:
            # A CR at the very end may be the first half of a CRLF split across reads.
            return lf + 1 if lf >= 0 else 0
        return cr + 1
    return lf + 1


def split_lines(text: str) -> list[tuple[str, str]]:
    """Split text that ends with a line ending into ``(line, ending)`` pairs."""
    if "\r" not in text:
        parts = text.split("\n")
        parts.pop()  # text ends with "\n"
        return list(zip(parts, repeat("\n", len(parts)), strict=True))  # pairs built in C
    if "\n" not in text:
        parts = text.split("\r")
        parts.pop()
        return list(zip(parts, repeat("\r", len(parts)), strict=True))
    crlf = text.count("\r\n")
    if crlf == text.count("\r") == text.count("\n"):
        parts = text.split("\r\n")
        parts.pop()
        return list(zip(parts, repeat("\r\n", len(parts)), strict=True))
    return _LINES.findall(text)


_BINARY_MAGIC = {
    b"GCDE": "binary G-code (.bgcode); export ASCII G-code or convert it first",
    b"PK\x03\x04": "a ZIP archive (3MF project?), not G-code",
    b"\x89PNG": "a PNG image, not G-code",
    b"\xff\xd8\xff": "a JPEG image, not G-code",
    b"%PDF": "a PDF document, not G-code",
    b"\x7fELF": "an executable, not G-code",
    b"\x1f\x8b": "a gzip archive, not G-code",
}


def _refuse_binary(head: bytes, display: str) -> None:
    for magic, what in _BINARY_MAGIC.items():
        if head.startswith(magic):
            raise SourceError(f"{display}: {what}")
    sample = head[:8192]
    if b"\x00" in sample:
        nul = sample.count(b"\x00")
        controls = sum(1 for b in sample if b < 9 or 13 < b < 32)
        if nul > 1 or controls > len(sample) // 10:
            raise SourceError(f"{display}: binary data (NUL bytes), not a G-code text file")
