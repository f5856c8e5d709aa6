"""The G-code text of a Prusa binary G-code file (``.bgcode``), as far as gclint can decode it.

The format (libbgcode's specification, https://github.com/prusa3d/libbgcode/blob/main/doc/specifications.md):
a file header ("GCDE", version: u32, checksum type: u16, 1 for CRC32), then blocks, each a header (type: u16,
compression: u16, uncompressed size: u32, and compressed size: u32 when compressed), its parameters (2 bytes
for metadata and G-code blocks: the encoding; 6 for a thumbnail), its data and, with CRC32, a 4-byte checksum.
Block type 1 holds G-code.  Compression 0 is none and 1 is deflate (zlib); 2 and 3 are heatshrink, and
encodings 1 and 2 are MeatPack, which gclint does not decode.

A firmware reads a ``.bgcode`` by its blocks, never as text: so the security rules read the G-code of the
blocks decoded here (``gclint.notgcode``), not the compressed bytes, and the check names the blocks it could
not read (the file stays an error, exit 2).
"""

from __future__ import annotations

import struct
import zlib

MAGIC = b"GCDE"
GCODE_BLOCK = 1
THUMBNAIL_BLOCK = 5
_MAX_BLOCK = 64 << 20  # (a block bigger than this, stored or inflated, is a broken or hostile file)
MAX_FILE = 64 << 20  # (the most of a file read, so memory stays bounded: a bigger one is an error for the rest)


def decode(data: bytes) -> tuple[bytes, int]:
    """The text of the G-code blocks of ``data`` that gclint can decode, joined, and how many G-code blocks
    it could not (compressed with heatshrink, encoded with MeatPack, or cut short).  ``ValueError`` when
    ``data`` is not a binary G-code file."""
    if not data.startswith(MAGIC) or len(data) < 10:
        raise ValueError("not a binary G-code file")
    (checksum_type,) = struct.unpack_from("<H", data, 8)
    checksum = 4 if checksum_type == 1 else 0
    pos, texts, unread = 10, [], 0
    while pos + 8 <= len(data):
        kind, compression, size = struct.unpack_from("<HHI", data, pos)
        pos += 8
        stored = size
        if compression:
            if pos + 4 > len(data):
                break
            (stored,) = struct.unpack_from("<I", data, pos)
            pos += 4
        parameters = 6 if kind == THUMBNAIL_BLOCK else 2
        if stored > _MAX_BLOCK or size > _MAX_BLOCK or pos + parameters + stored > len(data):
            unread += kind == GCODE_BLOCK
            break
        (encoding,) = struct.unpack_from("<H", data, pos)
        body = data[pos + parameters : pos + parameters + stored]
        pos += parameters + stored + checksum
        if kind != GCODE_BLOCK:
            continue
        if encoding != 0 or compression not in (0, 1):
            unread += 1
            continue
        try:
            # (inflated to the size its header gives at most: a small block cannot inflate into gigabytes)
            texts.append(zlib.decompressobj().decompress(body, size) if compression == 1 else body)
        except zlib.error:
            unread += 1
    return b"".join(texts), unread
