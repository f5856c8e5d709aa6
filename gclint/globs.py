"""Path patterns as ruff reads them: ``*`` and ``?`` stay within one folder, ``**`` crosses folders,
``[...]`` is a character class; a pattern with no ``/`` also matches a file's name alone
(``*.nc``, ``calibration.gcode``).  Paths are compared with ``/`` separators, relative to the folder of
the configuration file that names the pattern."""

from __future__ import annotations

import os
import re
from functools import lru_cache


@lru_cache(maxsize=512)
def compile_glob(pattern: str) -> re.Pattern[str]:
    """The regular expression for ``pattern`` (matched against a whole ``/``-separated path)."""
    out: list[str] = []
    i, n = 0, len(pattern)
    while i < n:
        c = pattern[i]
        if c == "*":
            if pattern.startswith("**", i):
                i += 2
                if pattern.startswith("/", i):  # "**/": any number of folders, none included
                    out.append("(?:.*/)?")
                    i += 1
                else:
                    out.append(".*")
                continue
            out.append("[^/]*")
        elif c == "?":
            out.append("[^/]")
        elif c == "[":
            end = pattern.find("]", i + 2 if pattern.startswith("[!", i) or pattern.startswith("[]", i) else i + 1)
            if end < 0:
                out.append(re.escape(c))
            else:
                body = pattern[i + 1 : end].replace("\\", "\\\\")
                if body.startswith("!"):
                    body = "^" + body[1:]
                out.append(f"[{body}]")
                i = end
        else:
            out.append(re.escape(c))
        i += 1
    return re.compile("".join(out))


def matches(pattern: str, path: str) -> bool:
    """Whether ``path`` (``/``-separated, relative) matches ``pattern``; a pattern with no ``/`` also
    matches the last part of the path."""
    pattern = pattern.strip()
    if pattern.startswith("./"):
        pattern = pattern[2:]
    rx = compile_glob(pattern.rstrip("/"))
    if rx.fullmatch(path):
        return True
    return "/" not in pattern.rstrip("/") and rx.fullmatch(path.rsplit("/", 1)[-1]) is not None


def relative(path: str, base: str) -> str:
    """``path`` relative to the folder ``base``, with ``/`` separators (``..`` parts when outside)."""
    try:
        rel = os.path.relpath(os.path.abspath(path), os.path.abspath(base))
    except ValueError:  # another drive (Windows)
        rel = os.path.abspath(path)
    return rel.replace(os.sep, "/")
