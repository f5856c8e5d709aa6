"""Text that is safe to show: secrets masked, undecodable bytes and control characters escaped.

One place for what every output does to file text (it may hold credentials, terminal escape sequences,
bidirectional overrides, characters XML cannot carry, undecodable bytes kept as lone surrogates):

* ``clean``: undecodable bytes as ``\\xNN`` (any encoder can write the text);
* ``printable``: also control characters except tab and line feed (XML, multi-line fields);
* ``human``: secrets masked and every control, line break and bidirectional character escaped, for a
  line a person reads on a terminal (text, full, grouped, github, explain, error lines, reports);
* ``json_safe``: encoded JSON with the characters a terminal acts on written as ``\\uNNNN``.

``human`` is idempotent, so text escaped once (an error message) can go through it again.
"""

from __future__ import annotations

import re

from gclint.secrets import mask

_SURROGATES = re.compile("[\ud800-\udfff]")


def clean(text: str) -> str:
    """Undecodable bytes (lone surrogates) shown as ``\\xNN``, so any encoder can write the text."""
    if not _SURROGATES.search(text):
        return text
    return _SURROGATES.sub(
        lambda m: f"\\x{ord(m.group()) - 0xDC00:02x}" if ord(m.group()) >= 0xDC80 else "\ufffd", text
    )


# C0 controls except tab, DEL, C1 controls: they would drive a terminal (ESC sequences) or break XML.
_CONTROLS = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\ufffe\uffff]")


def printable(text: str) -> str:
    """``clean(text)`` with control characters shown as ``\\xNN`` (safe on a terminal and in XML 1.0)."""
    text = clean(text)
    if _CONTROLS.search(text):
        text = _CONTROLS.sub(lambda m: f"\\x{ord(m.group()):02x}", text)
    return text


# For text shown on a terminal as one line: the controls above plus line breaks (a file name with a newline
# would forge a line of its own) and the invisible bidirectional and line-separator characters (they
# reorder or split what a terminal or a browser shows).  Tabs stay.
_HUMAN = re.compile("[\x00-\x08\x0a-\x1f\x7f-\x9f\u061c\u200e\u200f\u2028-\u202e\u2066-\u2069\ufffe\uffff]")
_HUMAN_LINES = re.compile(
    "[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f\u061c\u200e\u200f\u2028-\u202e\u2066-\u2069\ufffe\uffff]"
)
# In JSON text (a machine format) such characters are written as \u escapes: the same data, nothing raw.
_JSON_UNSAFE = re.compile("[\x7f-\x9f\u061c\u200e\u200f\u2028-\u202e\u2066-\u2069]")


def human(text: str, *, keep_line_breaks: bool = False) -> str:
    """``text`` for a line of human output (text, full, grouped, github, explain, error lines, the
    postprocess report): secrets masked, undecodable bytes and every control character shown as
    ``\\xNN``/``\\uNNNN``, never raw.  ``keep_line_breaks`` for a format that encodes them itself
    (GitHub workflow commands write them as ``%0A``)."""
    text = clean(text)
    pattern = _HUMAN_LINES if keep_line_breaks else _HUMAN
    if pattern.search(text):
        text = pattern.sub(_escape, text)
    return mask(text)  # after escaping: a value runs to the end of the line, past an escaped line break


def _escape(m: re.Match) -> str:
    code = ord(m.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def json_safe(text: str) -> str:
    """Encoded JSON with the characters a terminal would act on written as ``\\uNNNN`` (still valid JSON)."""
    if _JSON_UNSAFE.search(text):
        text = _JSON_UNSAFE.sub(lambda m: f"\\u{ord(m.group()):04x}", text)
    return text
