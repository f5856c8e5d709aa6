"""What the SC rules share: the code at the start of a line the grammar refused, comments, quoting and the
masking of machine passwords."""

from __future__ import annotations

import re

from gclint.syntax.nodes import Command, Line

# "M792", "N10 M0", "/M98", "m0792": the code at the start of a line the grammar could not parse.
_LEADING_CODE = re.compile(
    r"[ \t]*+(?:/[ \t]*+)?(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?([Mm])[ \t]*+(\d{1,8}+(?:\.\d{1,4}+)?)(?![\d.])"
)
# "RUN_SHELL_COMMAND", "N5 save_config": a Klipper command name at the start of a line the grammar refused.
_LEADING_NAME = re.compile(r"[ \t]*+(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?([A-Za-z_][A-Za-z0-9_]*+)")
_NUMBER = re.compile(r"[-+]?\d+(?:\.\d*)?")


def _code(letter: str, number: str) -> str:
    whole, _, frac = number.partition(".")
    frac = frac.rstrip("0")
    return letter.upper() + (whole.lstrip("0") or "0") + ("." + frac if frac else "")


_PAREN_COMMENT = re.compile(r"\([^)\r\n]*+(?:\)|$)")


def _strip_comment(text: str) -> str:
    """``text`` without its comments (``;`` to the end, ``(...)``): the argument of a command."""
    cut = text.find(";")
    if cut >= 0:
        text = text[:cut]
    if "(" in text:
        text = _PAREN_COMMENT.sub("", text)
    return text.strip(" \t")


def _starts_line(line: Line, cmd: Command | None) -> bool:
    """Marlin and RepRapFirmware run the first command of a line; "(note about M30 ...)" is prose.  (The
    other commands of the line are read in Smoothieware's view of it: ``firmware_views``.)"""
    return cmd is None or line.parsed.commands[0] is cmd


# RepRapFirmware M551 P"password" (RepRapFirmware source @ fc1cd16c, src/GCodes/GCodes2.cpp: M551); an old-style
# unquoted value runs to the end of the command.
_M551 = re.compile(
    r"""(?i)(?<![A-Za-z0-9])M0{0,4}+551(?![\d.])[^;\r\n]{0,300}?(?<![A-Za-z0-9'])P[ \t]{0,4}+("((?:[^"\r\n]|""){0,256}+)"|[^\s;"]{1,256}+)"""
)


def _machine_passwords(text: str) -> list[tuple[int, int]]:
    """The spans of M551 password values in ``text`` (empty values are no secret)."""
    if "551" not in text:
        return []
    out = []
    for m in _M551.finditer(text):
        if m.group(2) is not None:
            if m.group(2):
                out.append((m.start(2), m.end(2)))
        else:
            out.append((m.start(1), m.end(1)))
    return out


def _mask_machine_password(text: str) -> str:
    """``text`` with each M551 password replaced by ``*`` (secrets.mask does not know M551)."""
    spans = _machine_passwords(text)
    for start, end in reversed(spans):
        text = text[:start] + "*" * (end - start) + text[end:]
    return text


def _quote(text: str, limit: int = 80) -> str:
    return '"' + (text[:limit] + "..." if len(text) > limit else text) + '"'


def _excerpt(text: str, limit: int = 60) -> str:
    text = _strip_comment(text)
    if not text:
        return ""
    return f" ({text[:limit]}{'...' if len(text) > limit else ''})"
