"""Read G-code bytes as lines, streaming, so that writing the lines back gives the same bytes.

* Line endings (LF, CRLF, CR, mixed) are kept per line; a missing final newline is an empty ending.
* A UTF-8 byte order mark is kept aside and written back; UTF-16 (with a BOM) is decoded and re-encoded.
* Bytes that are not UTF-8 (latin-1 comments, stray binary) decode with ``surrogateescape`` and encode
  back unchanged.
* Binary files (``.bgcode``, images, archives) are refused with a ``SourceError`` naming the problem.

The file is read in chunks of ``CHUNK`` bytes; memory does not grow with the file's length, and time is
linear in it.  A line is held whole up to ``LINE_LIMIT`` bytes (characters for UTF-16/32): a longer one
(a 256 MiB line of junk, a sparse file of NULs) is refused with a ``SourceError`` naming its line, unless
the reader asked for ``cut_long_lines`` (checking, not rewriting): then the line comes as an ``Overlong``
text, its first ``LINE_LIMIT`` characters plus its real ``length``, and the rest is skipped while
streaming.  Writers (translate, --fix) never set it, so they never write a file they could not read whole.

``Source.open(path, digest=True)`` hashes the bytes as they are read: ``source.sha256`` is the SHA-256 of
exactly the bytes that were checked (the result cache's key), or None when the file is not a regular file
or was not read to its end.
"""

from __future__ import annotations

import codecs
import hashlib
import io
import os
import re
import stat
import sys
from collections.abc import Iterator
from itertools import repeat
from operator import itemgetter
from typing import BinaryIO, Protocol, Self, runtime_checkable

CHUNK = 1 << 20
HEAD = 1 << 16
LINE_LIMIT = 4 << 20  # bytes (characters for UTF-16/32) of one line held in memory
UTF8_BOM = b"\xef\xbb\xbf"
# (BOM, codec), UTF-32 first: its little-endian BOM starts with UTF-16's.
_DECODED_BOMS = (
    (codecs.BOM_UTF32_LE, "utf-32-le"),
    (codecs.BOM_UTF32_BE, "utf-32-be"),
    (codecs.BOM_UTF16_LE, "utf-16-le"),
    (codecs.BOM_UTF16_BE, "utf-16-be"),
)
_LINES = re.compile(r"([^\r\n]*)(\r\n|\r|\n)")
_TEXT = itemgetter(0)


class ByteView:
    """The lines of a UTF-16/32 file as a firmware that reads bytes sees them (``fgets``: lines end at a
    ``\n`` byte, text at the first NUL).  Plain UTF-16 text gives nothing there (a NUL follows or precedes
    every ASCII character), but a file can be made to read as a harmless comment when decoded and as
    commands when read as bytes: the engine checks these lines with the security rules too.

    Only lines of two characters or more are kept; a file whose byte view holds more than ``LIMIT``
    characters is refused (no UTF-16 G-code looks like that)."""

    LIMIT = 16 << 20

    def __init__(self, display: str) -> None:
        self.display = display
        self.lines: list[tuple[int, str]] = []  # (byte-view line number, text)
        self._pending = b""
        self._number = 0
        self._size = 0

    def feed(self, data: bytes, final: bool) -> None:
        pending = self._pending + data if self._pending else data
        parts = pending.split(b"\n")
        self._pending = b"" if final else parts.pop()
        if len(self._pending) > LINE_LIMIT:  # a line is read up to its first NUL: keep no more than that
            self._pending = self._pending[: self._pending.find(b"\0") + 1 or LINE_LIMIT]
        for part in parts:
            self._number += 1
            text = part.split(b"\0", 1)[0].strip(b" \t\r")
            if len(text) < 2:
                continue
            self._size += len(text)
            if self._size > self.LIMIT:
                raise SourceError(
                    f"{self.display}: its bytes, read without the byte order mark, are other text than the "
                    "decoded file (a file that reads two ways); not checked"
                )
            self.lines.append((self._number, text.decode("utf-8", "surrogateescape")))


def stdin() -> BinaryIO:
    """Standard input's bytes; a closed standard input (``gclint check - <&-``) is a SourceError."""
    if sys.stdin is None or getattr(sys.stdin, "buffer", None) is None:
        raise SourceError("-: standard input is closed")
    return sys.stdin.buffer


class SourceError(Exception):
    """A file that cannot be read as G-code; the message is one line for the user."""


class NotGcode(SourceError):
    """A file that is something else (an image, an archive, a script, NetCDF data): a folder walk skips it
    with a note; named on the command line, it is an error."""


class Overlong(str):
    """The first ``LINE_LIMIT`` characters of a longer line; ``length`` is the length of the whole line (bytes,
    or characters in UTF-16/32).  Only produced for readers that asked for ``cut_long_lines``."""

    length: int

    def __new__(cls, text: str, length: int) -> Overlong:
        obj = super().__new__(cls, text)
        obj.length = length
        return obj


class ByteStream(Protocol):
    """What ``Source`` reads: a binary file, standard input, or a wrapper (``notgcode.CutAtNul``)."""

    def read(self, size: int = -1, /) -> bytes: ...

    def close(self) -> None: ...


@runtime_checkable
class _Seekable(Protocol):
    """A stream whose end can be read before its middle (``Source.tail_text``)."""

    def seekable(self) -> bool: ...

    def tell(self) -> int: ...

    def seek(self, offset: int, whence: int = 0, /) -> int: ...

    def read(self, size: int = -1, /) -> bytes: ...


class _Hashing:
    """A byte stream that hashes what is read from it (the cache key is the hash of the bytes checked)."""

    def __init__(self, stream: BinaryIO) -> None:
        self._stream = stream
        self._sha = hashlib.sha256()
        self.eof = False

    def read(self, size: int = -1) -> bytes:
        data = self._stream.read(size)
        self._sha.update(data)
        if not data or (size is not None and 0 <= len(data) < size):
            self.eof = True  # a buffered read returns less than asked only at the end
        return data

    def hexdigest(self) -> str:
        return self._sha.hexdigest()

    def close(self) -> None:
        self._stream.close()


class Source:
    """A G-code file (or stdin) opened for streaming.

    ``display`` is the name used in findings; ``encoding`` is ``"utf-8"`` (with surrogateescape) or the
    UTF-16 variant found; ``bom`` is the byte order mark to write back (may be empty).
    """

    def __init__(self, stream: ByteStream, display: str, *, close: bool = False, cut_long_lines: bool = False) -> None:
        self.display = display
        self._stream = stream
        self._close = close
        self.cut_long_lines = cut_long_lines
        self.lines_read = 0
        self._hashing: _Hashing | None = stream if isinstance(stream, _Hashing) else None
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
        else:
            for bom, encoding in _DECODED_BOMS:
                if head.startswith(bom):
                    self.bom, self.encoding = bom, encoding
                    head = head[len(bom) :]
                    break
            else:
                _refuse_binary(head, display)
        self._head = head
        self._consumed = False
        # For a UTF-16/32 file: the lines a reader that ignores the byte order mark sees (ByteView)
        self.byte_view: ByteView | None = None

    @property
    def sha256(self) -> str | None:
        """The SHA-256 of every byte read, once the whole file was read (``Source.open(path, digest=True)``
        on a regular file); None otherwise."""
        if self._hashing is None or not self._hashing.eof:
            return None
        return self._hashing.hexdigest()

    @classmethod
    def open(cls, path: str, *, digest: bool = False, cut_long_lines: bool = False) -> Self:
        """Open a file path (``-`` for standard input).  With ``digest``, a regular file is hashed as it is
        read (``sha256``); pipes and devices are read once as a stream and never hashed."""
        if path == "-":
            return cls(stdin(), "-", cut_long_lines=cut_long_lines)
        try:
            file: BinaryIO = open(path, "rb")  # noqa: SIM115 - closed by Source.close / iteration end
        except FileNotFoundError:
            raise SourceError(f"{path}: no such file") from None
        except IsADirectoryError:
            raise SourceError(f"{path}: is a folder, not a file") from None
        except PermissionError:
            raise SourceError(f"{path}: permission denied") from None
        except OSError as exc:
            raise SourceError(f"{path}: cannot open: {exc.strerror or exc}") from None
        try:
            hashed = digest and stat.S_ISREG(os.fstat(file.fileno()).st_mode)
            return cls(_Hashing(file) if hashed else file, path, close=True, cut_long_lines=cut_long_lines)
        except OSError as exc:
            file.close()
            raise SourceError(f"{path}: cannot read: {exc.strerror or exc}") from None
        except BaseException:
            file.close()
            raise

    @classmethod
    def from_bytes(cls, data: bytes, display: str = "<bytes>", *, cut_long_lines: bool = False) -> Self:
        return cls(io.BytesIO(data), display, cut_long_lines=cut_long_lines)

    @classmethod
    def from_text(cls, text: str, display: str = "<text>", *, cut_long_lines: bool = False) -> Self:
        return cls.from_bytes(text.encode("utf-8", "surrogateescape"), display, cut_long_lines=cut_long_lines)

    @property
    def head_is_whole(self) -> bool:
        """True when the head read at opening is the whole file."""
        return self._head_eof

    def head_text(self, limit: int = HEAD) -> str:
        """The beginning of the file as text (for dialect detection); does not consume the stream.  A
        ``limit`` beyond what was read at opening reads on (kept for the iteration, which starts from it)."""
        if limit > len(self._head) and not self._head_eof and not self._consumed:
            wanted = limit - len(self._head)
            try:
                more = self._stream.read(wanted)
            except OSError as exc:
                raise SourceError(f"{self.display}: cannot read: {exc.strerror or exc}") from None
            self._head += more
            self._head_eof = len(more) < wanted
        data = self._head[:limit]
        if self.encoding == "utf-8":
            return data.decode("utf-8", "surrogateescape")
        unit = 4 if "32" in self.encoding else 2
        return data[: len(data) // unit * unit].decode(self.encoding, "replace")

    def tail_text(self, limit: int = HEAD) -> str | None:
        """The end of a regular file beyond the head (whole lines), as text, or None (the head is the
        whole file, or the stream cannot seek: standard input, a pipe).  Does not move the stream, and
        what it reads is not hashed (``sha256`` stays the hash of the bytes checked, in order)."""
        if self._head_eof or self._consumed:
            return None
        stream = self._stream._stream if isinstance(self._stream, _Hashing) else self._stream
        if not isinstance(stream, _Seekable):
            return None
        try:
            if not stream.seekable():
                return None
            here = stream.tell()
            end = stream.seek(0, io.SEEK_END)
            start = max(here, end - limit)
            # (one byte before: whether the tail starts a line; the head stops at a byte count, mid-line)
            stream.seek(start - 1 if start > 0 else 0)
            data = stream.read(end - start + (1 if start > 0 else 0))
            stream.seek(here)
        except (OSError, ValueError, AttributeError):
            return None
        if start > 0:
            before, data = data[:1], data[1:]
            if before not in (b"\n", b"\r"):  # begins mid-line: keep whole lines only
                cut = max(data.find(b"\n"), data.find(b"\r"))
                data = data[cut + 1 :] if cut >= 0 else b""
        if self.encoding == "utf-8":
            return data.decode("utf-8", "surrogateescape")
        unit = 4 if "32" in self.encoding else 2
        return data[: len(data) // unit * unit].decode(self.encoding, "replace")

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
        for block in self.blocks():
            yield split_lines(block) if isinstance(block, str) else block

    def blocks(self) -> Iterator[str | list[tuple[str, str]]]:
        """The chunks of ``chunks()``, each either a list of ``(text, ending)`` pairs or, most often, the
        chunk's text: whole lines, each with its ending, which ``split_lines`` turns into those pairs.
        For readers that scan the text before (or instead of) cutting it into lines (the engine's runs
        of plain moves)."""
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

    def _utf8_chunks(self) -> Iterator[str | list[tuple[str, str]]]:
        read = self._stream.read

        def pieces() -> Iterator[bytes]:
            yield self._head
            if self._head_eof:
                return
            while True:
                more = read(CHUNK)
                if not more:
                    return
                yield more

        def decode(data: bytes) -> str:
            return data.decode("utf-8", "surrogateescape")

        yield from self._lines(pieces(), b"", b"\n", b"\r", decode)

    def _decoded_chunks(self) -> Iterator[str | list[tuple[str, str]]]:
        decoder = codecs.getincrementaldecoder(self.encoding)("surrogatepass")
        view = self.byte_view = ByteView(self.display)

        def pieces() -> Iterator[str]:
            data = self._head
            final = self._head_eof
            while True:
                view.feed(data, final)
                try:
                    text = decoder.decode(data, final=final)
                except UnicodeDecodeError:  # a byte count that does not fit the encoding, or not that encoding
                    name = self.encoding.split("-le")[0].split("-be")[0].upper()
                    raise SourceError(
                        f"{self.display}: starts with a {name} byte order mark but is not valid {name} text"
                    ) from None
                if text:
                    yield text
                if final:
                    return
                data = self._stream.read(CHUNK)
                final = not data

        yield from self._lines(pieces(), "", "\n", "\r", lambda text: text)

    def _lines(self, pieces: Iterator, empty, lf, cr, decode) -> Iterator[str | list[tuple[str, str]]]:
        """Cut ``pieces`` (bytes or text) into blocks of whole lines (see ``blocks``).  Every piece is searched for line endings once and a
        partial line is carried over only up to ``LINE_LIMIT``: time is linear, memory bounded."""
        pending = empty
        eof = False
        while True:
            more = next(pieces, None)
            if more is None:
                eof = True
            else:
                pending = pending + more if pending else more
            cut = _last_line_end(pending, eof, lf, cr)
            if cut:
                text = decode(pending[:cut])
                if cut > LINE_LIMIT:  # (only then can a line be longer than the limit)
                    lines = split_lines(text)
                    if max(map(len, map(_TEXT, lines))) > LINE_LIMIT:
                        self._limit(lines, empty)
                    self.lines_read += len(lines)
                    yield lines
                else:
                    self.lines_read += count_lines(text)
                    yield text
                pending = pending[cut:]
            if eof:
                if pending:
                    self.lines_read += 1
                    yield [(decode(pending), "")]
                return
            if len(pending) - (pending[-1:] == cr) > LINE_LIMIT:  # (a CR at the end may be its ending)
                pending = yield from self._long_line(pending, pieces, empty, lf, cr, decode)

    def _limit(self, lines: list[tuple[str, str]], empty) -> None:
        """Refuse (or cut) the lines longer than ``LINE_LIMIT`` that arrived whole within one read."""
        for index, (text, ending) in enumerate(lines):
            if len(text) > LINE_LIMIT:
                if not self.cut_long_lines:
                    self._refuse(self.lines_read + index + 1)
                length = len(text.encode("utf-8", "surrogateescape")) if isinstance(empty, bytes) else len(text)
                lines[index] = (Overlong(text[:LINE_LIMIT], length), ending)

    def _refuse(self, number: int) -> None:
        raise SourceError(
            f"{self.display}: line {number} is longer than {LINE_LIMIT:,} bytes; gclint does not read or"
            " rewrite files with such lines"
        )

    def _long_line(self, pending, pieces: Iterator, empty, lf, cr, decode):
        """A line longer than ``LINE_LIMIT``: refused, or (``cut_long_lines``) its beginning and length,
        the rest skipped as it streams by.  Returns what follows the line's ending."""
        if not self.cut_long_lines:
            self._refuse(self.lines_read + 1)
        prefix = decode(pending[:LINE_LIMIT])
        length = LINE_LIMIT
        data = pending[LINE_LIMIT:]
        rest = None
        while rest is None:
            i = _first_line_end(data, lf, cr)
            if i < 0:
                length += len(data)
                more = next(pieces, None)
                if more is None:
                    ending, rest = "", empty
                else:
                    data = more
                continue
            length += i
            if data[i : i + 1] == lf:
                ending, rest = "\n", data[i + 1 :]
            elif i + 1 < len(data):
                ending, rest = ("\r\n", data[i + 2 :]) if data[i + 1 : i + 2] == lf else ("\r", data[i + 1 :])
            else:  # a CR that ends this piece: the next one tells CR from CRLF
                more = next(pieces, None)
                if more is not None and more[:1] == lf:
                    ending, rest = "\r\n", more[1:]
                else:
                    ending, rest = "\r", more if more is not None else empty
        self.lines_read += 1
        yield [(Overlong(prefix, length), ending)]
        return rest


def _first_line_end(data, lf, cr) -> int:
    """Index of the first LF or CR in ``data`` (bytes or text), -1 when it has none."""
    a = data.find(lf)
    b = data.find(cr)
    if a < 0:
        return b
    if b < 0:
        return a
    return min(a, b)


def _last_line_end(buffer, eof: bool, lf=b"\n", cr=b"\r") -> int:
    """Length of the longest prefix of ``buffer`` (bytes or text) that ends with a complete line ending."""
    lf_at = buffer.rfind(lf)
    cr_at = buffer.rfind(cr)
    if cr_at > lf_at:
        if cr_at == len(buffer) - 1 and not eof:
            # A CR at the very end may be the first half of a CRLF split across reads: cut before it.
            return max(lf_at, buffer.rfind(cr, 0, cr_at)) + 1
        return cr_at + 1
    return lf_at + 1


def line_slices(text: str, start: int, end: int, size: int = 1 << 16) -> Iterator[tuple[int, int]]:
    """``text[start:end]``, whole lines, as spans of about ``size`` characters that end after a line
    ending: a reader that makes an object per line holds a few thousand at a time, not a chunk's worth
    (a megabyte of empty lines is a million lines)."""
    while end - start > size:
        cut = text.find("\n", start + size, end) + 1 or text.find("\r", start + size, end) + 1  # (no LF: CR)
        if not cut or cut >= end:
            break
        yield start, cut
        start = cut
    yield start, end


def count_lines(text: str) -> int:
    """How many lines ``split_lines(text)`` gives (CR LF, CR and LF each end a line)."""
    lf = text.count("\n")
    cr = text.count("\r")
    return lf + cr - text.count("\r\n") if cr else lf


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
    b"xgcode 1.0": "a FlashForge .gx job (a binary header and thumbnail before its G-code); export plain G-code",
    b"PK\x03\x04": "a ZIP archive (3MF project?), not G-code",
    b"\x89PNG": "a PNG image, not G-code",
    b"\xff\xd8\xff": "a JPEG image, not G-code",
    b"%PDF": "a PDF document, not G-code",
    b"\x7fELF": "an executable, not G-code",
    b"\x1f\x8b": "a gzip archive, not G-code",
    b"CDF\x01": "NetCDF data (.nc), not G-code",
    b"CDF\x02": "NetCDF data (.nc), not G-code",
    b"\x89HDF\r\n\x1a\n": "HDF5 / NetCDF-4 data (.nc), not G-code",
}


def _refuse_binary(head: bytes, display: str) -> None:
    for magic, what in _BINARY_MAGIC.items():
        if head.startswith(magic):
            raise NotGcode(f"{display}: {what}")
    sample = head[:8192]
    if b"\x00" in sample:
        nul = sample.count(b"\x00")
        controls = sum(1 for b in sample if b < 9 or 13 < b < 32)
        if nul > 1 or controls > len(sample) // 10:
            raise NotGcode(f"{display}: binary data (NUL bytes), not a G-code text file")
