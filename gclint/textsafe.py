"""Text that is safe to show: secrets masked, undecodable bytes and control characters escaped.

One place for what every output does to file text (it may hold credentials, terminal escape sequences,
bidirectional overrides, characters XML cannot carry, undecodable bytes kept as lone surrogates):

* ``clean``: undecodable bytes as ``\\xNN`` (any encoder can write the text);
* ``printable``: also control characters except tab and line feed, and the invisible format characters
  (XML, multi-line fields: a JUnit viewer shows them as a browser does, U+202E reversing what follows);
* ``human``: secrets masked and every control, line break and invisible format character (Unicode
  category Cf: bidirectional overrides, soft hyphen, zero-width spaces) escaped, for a line a person reads
  (text, full, grouped, github, html, explain, the --diff, error lines and notes, reports);
* ``json_safe``: encoded JSON with the characters a terminal acts on written as ``\\uNNNN``.

``human`` is idempotent, so text escaped once (an error message) can go through it again.  ``human_path``
is ``human`` for a file name: a tab is escaped too (it would shift what the name shows).
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


# The invisible format characters (Unicode category Cf, as of Unicode 15.1): bidirectional overrides and
# isolates (they reorder what a terminal or a browser shows), the soft hyphen, zero-width spaces and joiners,
# the BOM, tag characters (they hide text).  Escaped in every human output, as the parser's messages
# (SX001, Python's repr) already do.  A test checks this against unicodedata.
_FORMAT_CHARACTERS = (
    "\u00ad\u0600-\u0605\u061c\u06dd\u070f\u0890\u0891\u08e2\u180e\u200b-\u200f\u202a-\u202e\u2060-\u2064"
    "\u2066-\u206f\ufeff\ufff9-\ufffb\U000110bd\U000110cd\U00013430-\U0001343f\U0001bca0-\U0001bca3"
    "\U0001d173-\U0001d17a\U000e0001\U000e0020-\U000e007f"
)
FORMAT_CHARACTERS = re.compile(f"[{_FORMAT_CHARACTERS}]")  # (also read by the SC rules' firmware views)
# C0 controls except tab and line feed, DEL, C1 controls (they would drive a terminal or break XML), and the
# format characters, line and paragraph separators (they reorder or split what a viewer shows).
_CONTROLS = re.compile(f"[\x00-\x08\x0b-\x1f\x7f-\x9f\u2028\u2029{_FORMAT_CHARACTERS}\ufffe\uffff]")


def printable(text: str) -> str:
    """``clean(text)`` with control and invisible format characters shown as ``\\xNN``/``\\uNNNN`` (safe on
    a terminal, in XML 1.0 and in a viewer that applies bidirectional overrides); line feeds stay."""
    text = clean(text)
    if _CONTROLS.search(text):
        text = _CONTROLS.sub(_escape, text)
    return text


# For text shown on a terminal as one line: the controls above plus line breaks (a file name with a newline
# would forge a line of its own), the line and paragraph separators (they split what a terminal or a browser
# shows) and the format characters.  Tabs stay.
_HUMAN = re.compile(f"[\x00-\x08\x0a-\x1f\x7f-\x9f\u2028\u2029{_FORMAT_CHARACTERS}\ufffe\uffff]")
_HUMAN_LINES = re.compile(f"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f\u2028\u2029{_FORMAT_CHARACTERS}\ufffe\uffff]")
# In JSON text (a machine format) such characters are written as \u escapes: the same data, nothing raw.
_JSON_UNSAFE = re.compile(f"[\x7f-\x9f\u2028\u2029{_FORMAT_CHARACTERS}]")


def human(text: str, *, keep_line_breaks: bool = False) -> str:
    """``text`` for a line of human output (text, full, grouped, github, html, explain, --diff, error
    lines, the postprocess report): secrets masked, undecodable bytes, every control character and every
    invisible format character shown as ``\\xNN``/``\\uNNNN``, never raw.  ``keep_line_breaks`` for a format that encodes them itself
    (GitHub workflow commands write them as ``%0A``)."""
    text = clean(text)
    pattern = _HUMAN_LINES if keep_line_breaks else _HUMAN
    if pattern.search(text):
        text = pattern.sub(_escape, text)
    return mask(text)  # after escaping: a value runs to the end of the line, past an escaped line break


def _escape(m: re.Match) -> str:
    code = ord(m.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def _json_escape(m: re.Match) -> str:
    code = ord(m.group())
    if code < 0x10000:
        return f"\\u{code:04x}"
    code -= 0x10000  # JSON writes a character beyond the BMP as a surrogate pair
    return f"\\u{0xD800 + (code >> 10):04x}\\u{0xDC00 + (code & 0x3FF):04x}"


def json_safe(text: str) -> str:
    """Encoded JSON with the characters a terminal would act on written as ``\\uNNNN`` (still valid JSON)."""
    if _JSON_UNSAFE.search(text):
        text = _JSON_UNSAFE.sub(_json_escape, text)
    return text


def human_path(path: str) -> str:
    """A file name for human output: ``human``, and its tabs written as ``\\x09`` too."""
    return human(path).replace("\t", "\\x09")


class HumanStream:
    """A text stream that writes what it is given through ``human`` (line breaks kept): for a stream of
    error lines written by code that does not escape them itself (``gclint diff``)."""

    def __init__(self, stream) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        self._stream.write(human(text, keep_line_breaks=True))
        return len(text)

    def flush(self) -> None:
        self._stream.flush()
