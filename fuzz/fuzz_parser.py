"""atheris fuzz target for the parser and the streaming reader.

For any bytes: ``Source`` reads them or refuses them with ``SourceError`` (one line); every line parses
without raising (fast path, then the grammar); the fast path, when it accepts a line, gives the grammar's
tree; rendering the tree gives back the line; writing the lines back gives back the bytes.

    python fuzz/fuzz_parser.py -max_total_time=300 fuzz/corpus_parser   (or: python scripts/fuzz.py)
"""

from __future__ import annotations

import io
import sys

import _common  # noqa: F401  (sys.path)
import atheris

with atheris.instrument_imports():
    from gclint.syntax.fastpath import parse_fast
    from gclint.syntax.nodes import Line
    from gclint.syntax.parse import parse_line, parse_slow
    from gclint.syntax.source import Source, SourceError

STATS = _common.Stats("parser")


def TestOneInput(data: bytes) -> None:
    STATS.tick()
    try:
        check(data)
    except SourceError as exc:  # refused (binary, broken UTF-16): one line naming the file
        message = str(exc)
        assert message.startswith("fuzz.gcode: ") and "\n" not in message, message


def check(data: bytes) -> None:
    source = Source(io.BytesIO(data), "fuzz.gcode")
    out = [source.bom]
    compared = 0
    for raw, ending in source.lines():
        parsed = parse_line(raw)
        line = Line(1, raw, ending, parsed)
        assert line.render() == raw + ending, (raw, line.render())
        if compared < 16 and len(raw) <= 1000:  # the grammar is slow: compare the first lines of each input
            compared += 1
            fast = parse_fast(raw)
            if fast is not None:
                slow = parse_slow(raw)
                assert fast == slow, (raw, fast, slow)
        for issue in parsed.issues:
            assert "\n" not in issue.message
        out.append(source.encode(line.render()))
    assert b"".join(out) == data


def main() -> None:
    atheris.Setup(sys.argv, TestOneInput)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
