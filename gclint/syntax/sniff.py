"""Recognise text files that are clearly not G-code (scripts, INI configuration, Org documents), so that
``gclint check`` says so in one line instead of reporting every line as a parse error.

Conservative on purpose: a G-code program never starts with a shebang, an INI section header, an Org
heading, a run of ``key = value`` lines, an ANTLR ``grammar Name;`` or a TAP plan followed by ``ok`` lines,
so none of these tests can refuse a real job.
"""

from __future__ import annotations

import re

from gclint.syntax.source import NotGcode, Source

_INI_SECTION = re.compile(r"\[[A-Za-z_][^\]\r\n]*\]\s*")
# Other files that share G-code's extensions: ANTLR grammars (.g), Test Anything Protocol output (.tap)
_ANTLR = re.compile(r"(?:(?:lexer|parser|tree)\s+)?grammar\s+[A-Za-z_]\w*\s*;")
_TAP = re.compile(r"TAP version \d+|1\.\.\d+(?:\s*#.*)?")
_KEY_VALUE = re.compile(r"[A-Za-z_][A-Za-z0-9_.]*\s*=\s*")
_ORG_HEADING = re.compile(r"\*+ \S")


def not_gcode_reason(head: str) -> str | None:
    """Why the text beginning with ``head`` is not G-code, or None when it may be G-code."""
    if head.startswith("#!"):
        first = head.split("\n", 1)[0].strip()
        return f"a script ({first[:40]}), not G-code"
    lines = [line.strip() for line in head.splitlines()[:200]]
    content = [line for line in lines if line]
    if not content:
        return None
    if _ORG_HEADING.match(content[0]):
        return "an Org-mode document, not G-code"
    code = [line for line in content if not line.startswith(("#", ";"))][:40]
    if not code:
        return None
    if _ANTLR.match(code[0]):
        return "an ANTLR grammar (.g), not G-code"
    if _TAP.fullmatch(code[0]) and any(line.startswith(("ok ", "not ok ")) for line in code[1:]):
        return "Test Anything Protocol output (.tap), not G-code"
    if _INI_SECTION.fullmatch(code[0]):
        return f"an INI configuration file (section {code[0]}), not G-code"
    pairs = sum(1 for line in code if _KEY_VALUE.match(line))
    # (no G-code line starts with a name and '=': Klipper's "NAME KEY=VALUE" has a blank after the name,
    # RRF's "var x = 1" too; a short file is refused only when every line is a pair)
    if pairs == len(code) or (len(code) >= 3 and pairs >= 0.9 * len(code)):
        return "a 'key = value' configuration file (slicer or printer profile), not G-code"
    return None


def refuse_non_gcode(source: Source) -> None:
    """Raise ``NotGcode`` (one line for the user) when the file is not G-code by content: what ``gclint
    check`` refuses (``not_gcode_reason``: scripts, configuration files...), and text with control characters, which
    G-code never has but random or binary data without NUL bytes does (about one byte in ten)."""
    head = source.head_text(8192)
    reason = not_gcode_reason(head)
    if reason is None:
        controls = sum(1 for ch in head if ch < " " and ch not in "\t\n\r\f\v" or ch == "\x7f")
        if controls >= 16 and controls * 100 > len(head):
            reason = "binary data (control characters), not a G-code text file"
    if reason is not None:
        raise NotGcode(f"{source.display}: {reason}")
