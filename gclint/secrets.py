"""Find and mask secrets in G-code text: API keys, passwords and tokens that slicers or people leave in jobs.

PrusaSlicer and its forks append their whole configuration to the job as comments, which has included
``; printhost_apikey = ...`` and ``; printhost_password = ...`` (OctoPrint File Check has a
``leaked_api_key`` check for exactly this: OctoPrint documentation, File Check); hand-edited start G-code carries URLs
with ``user:password@host`` and tokens pasted from a browser.  A job file travels (print farms, git, shared
folders), so such a secret is leaked to everyone who gets the job.

``find(text)`` returns the spans of the secret *values*; ``mask(text)`` replaces each value with ``*`` of the
same length (so columns and carets in reports stay aligned) and keeps the key name, so a report still says
what leaked: ``; printhost_apikey = ********************************``.  Every output that prints file
text (rule messages, ``Finding.source``, report source lines) should go through ``mask``.

All patterns are bounded (possessive where giving characters back could only fail again) or anchored on a
literal, so that a 1 MB adversarial line is scanned in linear time; a cheap test of hint substrings skips
the patterns for ordinary comments (``;TYPE:WALL-OUTER``).

Besides comments, three G-code commands carry a secret by design: RepRapFirmware ``M587 S"network"
P"password"`` (and ``M589`` for the access point) stores a WiFi password, ``M551 P"password"`` the
machine's password.  Their ``P`` value is masked however it is written: ``"..."``, ``'...'``, unquoted
(``M551 Psecret``) or with an unterminated quote (to the end of the line).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

__all__ = ["Secret", "find", "mask", "mask_quoted", "has_secret", "MASK_CHAR"]

MASK_CHAR = "*"


@dataclass(frozen=True, slots=True)
class Secret:
    """A secret value at ``text[start:end]``; ``kind`` says what it looks like (for messages)."""

    start: int
    end: int
    kind: str


# Key names whose value is a secret.  "key" alone is not enough ("printhost_authorization_type = key").
_KEYWORDS = re.compile(
    r"(?i)api[_-]?key|apikey|api[_-]?token|access[_-]?token|auth[_-]?token|refresh[_-]?token"
    r"|client[_-]?secret|private[_-]?key|secret|password|passwd|passphrase|pwd|token"
)
# After a keyword: the rest of the key name, an optional closing quote, "=" or ":", then the value: quoted,
# or else the rest of the line (a password may hold spaces: "; printhost_password = my secret phrase"; the
# whole value is masked, never only its first word).  Blank runs are possessive (linear on any line).  The
# key name has no "." so that a file name ("secret.gcode: permission denied") is not a key.
# (blanks: any space but a line break, and the invisible format characters a job may hide the "=" with)
_BLANKS = r"(?:[^\S\r\n]|[\u00ad\u200b-\u200f\u2060-\u2064\ufeff])*+"
_AFTER_KEYWORD = re.compile(
    rf"""[A-Za-z0-9_-]{{0,40}}+["']?{_BLANKS}[=:]{_BLANKS}"""
    r"""(?:"([^"\r\n]{1,512})"|'([^'\r\n]{1,512})'|([^\s][^\r\n]*+))"""
)
_URL_CREDENTIALS = re.compile(r"(?i)\b[a-z][a-z0-9+.-]{0,20}://[^\s/@:;\"'<>]{1,256}:([^\s/@;\"'<>]{1,256})@")
_BEARER = re.compile(r"(?i)\bbearer[ \t]{1,8}+([A-Za-z0-9._~+/=-]{8,512}+)")
_TOKENS = re.compile(
    r"(?<![A-Za-z0-9])(?:"  # ("_" may come before: "x_ghp_...")
    r"gh[pousr]_[A-Za-z0-9]{30,255}+"  # GitHub tokens (36 characters today; GitHub may change the length)
    r"|github_pat_[A-Za-z0-9_]{22,255}+"
    r"|AKIA[0-9A-Z]{16}"  # AWS access key id
    r"|xox[baprs]-[A-Za-z0-9-]{10,200}+"  # Slack
    r"|glpat-[A-Za-z0-9_-]{20,64}+"  # GitLab
    r"|sk-[A-Za-z0-9_-]{20,200}+"  # OpenAI-style secret keys
    r"|eyJ[A-Za-z0-9_-]{8,2048}\.eyJ[A-Za-z0-9_-]{8,2048}\.[A-Za-z0-9_-]{8,2048}"  # JSON web tokens
    r")(?![A-Za-z0-9_-])"
)
# OctoPrint API keys are 32 upper-case hex digits (uuid4().hex.upper()).
_HEX_KEY = re.compile(r"(?<![0-9A-Za-z_-])(?=[0-9A-F]{0,31}[A-F])(?=[0-9A-F]{0,31}[0-9])[0-9A-F]{32}(?![0-9A-Za-z_-])")
_PRIVATE_KEY = re.compile(r"-----BEGIN [A-Z ]{0,40}PRIVATE KEY-----")
# Docker's config.json ("auths": {"registry": {"auth": "<base64 of user:password>"}}) and "auth = ..."
# settings: "auth" alone as the key name ("printhost_authorization_type = key" is not one).
_AUTH = re.compile(
    r"""(?i)(?<![A-Za-z0-9])auth["']?[ \t]*+[=:][ \t]*+(?:"([^"\r\n]{1,2048}+)"|'([^'\r\n]{1,2048}+)'|([^\s,;"'}][^\s,;}]{0,2047}+))"""
)
# RepRapFirmware commands whose P is a password: M551 (the machine's), M587 (a WiFi network's), M589 (the
# access point's).  Their words are read one by one (a P inside another word's quoted string is not the P).
# Marlin's password feature: M511 P<passcode> unlocks the machine, M512 P<old> S<new> sets the passcode
# (https://github.com/MarlinFirmware/Marlin/blob/bugfix-2.1.x/Marlin/src/gcode/feature/password/M510-M512.cpp).
# RepRapFirmware's M586.4 configures its MQTT client: U the user name, K the password (MqttClient.cpp Configure).
_PASSWORD_CODE = re.compile(r"(?i)(?<![A-Za-z0-9])M0{0,4}+(551|58[79]|51[12]|586\.4)(?![\d.])")
_PASSWORD_KIND = {
    "551": "password",
    "587": "WiFi password",
    "589": "WiFi password",
    "511": "Marlin passcode",
    "512": "Marlin passcode",
    "586.4": "MQTT password",
}
# (the words that hold one; P for the others: M587's enterprise form puts a private key's password in Q,
# WiFiInterface.cpp)
_PASSWORD_LETTERS = {"512": "PpSs", "586.4": "Kk", "587": "PpQq"}
# One word: a letter, then a value "..." (RepRapFirmware writes a quote inside as ""), '...', either with
# its closing quote missing (the value runs to the end of the line), or unquoted (to a blank or ";").
_WORD = re.compile(r"""[ \t]*+([A-Za-z])[ \t]*+("(?:[^"\r\n]|"")*+"?|'[^'\r\n]*+'?|[^\s;"']*+)""")
_WORDS_READ = 16

_HEX_RUN = re.compile(r"[0-9A-F]{32}")


def _hinted(text: str) -> bool:
    """Whether any pattern could match (the common case, ";TYPE:Perimeter", stops here).  A chain of
    substring tests: several times faster than one case-insensitive regex or a loop."""
    t = text.lower()
    return _words_hinted(t) or _codes_hinted(t)


def _words_hinted(t: str) -> bool:
    """``_hinted``'s tests (of the lowered text) but for the password codes'."""
    return (
        "key" in t
        or "pass" in t
        or "secret" in t
        or "token" in t
        or "pwd" in t
        or "bearer" in t
        or "://" in t
        or "ghp_" in t  # (GitHub tokens: gh[pousr]_ and github_pat_; not "gh" alone: ";HEIGHT:0.2")
        or "gho_" in t
        or "ghu_" in t
        or "ghs_" in t
        or "ghr_" in t
        or "github_pat_" in t
        or "akia" in t
        or "xox" in t
        or "glpat-" in t
        or "sk-" in t
        or "eyj" in t
        or "auth" in t
    )


def _codes_hinted(t: str) -> bool:
    """``_hinted``'s tests (of the lowered text) for the password codes (``_command_passwords``)."""
    return (
        "587" in t  # (M587, M589, M551: not "58" alone, a common digit pair)
        or "589" in t
        or "551" in t
        or "m51" in t  # (Marlin's M511/M512 passcodes)
        or "586" in t  # (RepRapFirmware's M586.4 MQTT password)
    )


def may_hold(text: str) -> bool:
    """Whether ``text`` may hold a secret (``find`` finds none in a text for which this is False).

    Where only a password code's digits hint at one (Cura's ``; LINE_WIDTH: 0.551177``, thousands of lines
    a job), the code itself is looked for: in ASCII text each of ``find``'s other patterns holds one of the
    other hints.  (Not outside ASCII: there ignoring case matches more than ``lower()`` shows, "ſecret" is
    a keyword.)  True of lines joined by line breaks when true of one of them (``Rule.comment_hint``)."""
    if len(text) >= 32 and _HEX_RUN.search(text) is not None:
        return True
    t = text.lower()
    if _words_hinted(t):
        return True
    return _codes_hinted(t) and (not text.isascii() or _PASSWORD_CODE.search(text) is not None)


# Values that are placeholders, not secrets: "; printhost_password = " has none, "= none", "= ***".
_PLACEHOLDERS = frozenset(
    {
        "none",
        "null",
        "nil",
        "false",
        "true",
        "no",
        "yes",
        "0",
        "1",
        "-",
        "''",
        '""',
        "n/a",
        "password",
        "passwd",
        "secret",
        "changeme",
        "apikey",
        "api_key",
        "token",
        "your_password",
        "yourpassword",
        "your_api_key",
        "your-api-key",
        "your_token",
    }
)


def _placeholder(value: str) -> bool:
    v = value.strip().lower()
    if not v or v in _PLACEHOLDERS:
        return True
    if len(set(v)) == 1 and v[0] in "*x.#?-_":
        return True  # "****", "xxxx": already masked
    return (v[0], v[-1]) in (("<", ">"), ("{", "}"), ("[", "]"), ("%", "%")) or v.startswith("$")


def _kind(keyword: str) -> str:
    keyword = keyword.lower()
    if "pass" in keyword or keyword == "pwd":
        return "password"
    if "token" in keyword:
        return "token"
    if "key" in keyword:
        return "API key"
    return "secret"


def find(text: str) -> list[Secret]:
    """The secrets in ``text``, in order, not overlapping."""
    found: list[Secret] = []
    if len(text) >= 32 and _HEX_RUN.search(text):
        for hex_key in _HEX_KEY.finditer(text):
            found.append(Secret(hex_key.start(), hex_key.end(), "API key"))
    if _hinted(text):
        if "PRIVATE KEY-----" in text:
            for key in _PRIVATE_KEY.finditer(text):
                found.append(Secret(key.end(), len(text), "private key"))
        pos = 0
        while True:
            k = _KEYWORDS.search(text, pos)
            if k is None:
                break
            m = _AFTER_KEYWORD.match(text, k.end())
            if m is None:
                pos = k.end()
                continue
            group = 1 if m.group(1) is not None else 2 if m.group(2) is not None else 3
            value = m.group(group)
            end = m.start(group) + len(value.rstrip(" \t"))
            if not _placeholder(value):
                found.append(Secret(m.start(group), end, _kind(k.group(0))))
            pos = m.end()
        if "://" in text and "@" in text:
            for m in _URL_CREDENTIALS.finditer(text):
                if not _placeholder(m.group(1)):
                    found.append(Secret(m.start(1), m.end(1), "password in a URL"))
        for m in _BEARER.finditer(text):
            found.append(Secret(m.start(1), m.end(1), "bearer token"))
        for m in _TOKENS.finditer(text):
            found.append(Secret(m.start(), m.end(), "access token"))
        if "auth" in text.lower():
            for m in _AUTH.finditer(text):
                group = m.lastindex or 3
                if not _placeholder(m.group(group)):
                    found.append(Secret(m.start(group), m.end(group), "credentials"))
        if "51" in text or "586" in text or "587" in text or "589" in text:  # (M551, M511, M512; M586.4, M587, M589)
            found.extend(_command_passwords(text))
    if len(found) <= 1:
        return found
    found.sort(key=lambda s: (s.start, -s.end))
    merged: list[Secret] = []
    for s in found:
        if merged and s.start < merged[-1].end:
            last = merged[-1]
            if s.end > last.end:
                merged[-1] = Secret(last.start, s.end, last.kind)
            continue
        merged.append(s)
    return merged


def _command_passwords(text: str) -> list[Secret]:
    """The ``P`` values of ``M551``/``M587``/``M589``/``M511``, and ``P`` and ``S`` of ``M512``, in ``text`` (in a
    comment too: a copy is as secret)."""
    found = []
    pos = 0
    while (m := _PASSWORD_CODE.search(text, pos)) is not None:
        pos = m.end()  # (the next code is looked for after these words: "M551 P\"M551 P\"..." is linear)
        for _ in range(_WORDS_READ):
            word = _WORD.match(text, pos)
            if word is None or word.end() == pos:
                break  # a comment, a checksum, the end of the line
            pos = word.end()
            if word.group(1) not in _PASSWORD_LETTERS.get(m.group(1), "Pp"):
                continue
            value, start = word.group(2), word.start(2)
            if value[:1] in ("'", '"'):
                closed = len(value) > 1 and value[-1] == value[0]
                value, start = value[1 : -1 if closed else None], start + 1
            if value and not _placeholder(value):  # (every P: a repeated one may be the one used)
                found.append(Secret(start, start + len(value), _PASSWORD_KIND[m.group(1)]))
    return found


def has_secret(text: str) -> bool:
    """True when ``text`` holds at least one secret."""
    return bool(find(text))


def mask(text: str) -> str:
    """``text`` with every secret value replaced by ``*`` (same length); text without secrets is returned
    as is, so calling it on every line of a report is cheap (short texts are remembered: messages repeat)."""
    if len(text) <= _REMEMBERED:
        return _mask_remembered(text)
    return _mask(text)


def _mask(text: str) -> str:
    if not text:
        return text
    secrets = find(text)
    if not secrets:
        return text
    parts: list[str] = []
    pos = 0
    for s in secrets:
        parts.append(text[pos : s.start])
        parts.append(MASK_CHAR * (s.end - s.start))
        pos = s.end
    parts.append(text[pos:])
    return "".join(parts)


_REMEMBERED = 512  # (the longest text whose masked form is remembered: 4,096 of them at most)
_mask_remembered = lru_cache(maxsize=4096)(_mask)


def mask_quoted(text: str, line: str) -> str:
    """``text``, a message about ``line``, with its own secrets masked and every secret value of ``line``
    it quotes: a message may quote a word without what makes it a secret ("P"pass1234" is repeated in
    M587" has no M587 before the P)."""
    for value in _values_remembered(line) if len(line) <= _REMEMBERED else _values(line):
        text = text.replace(value, MASK_CHAR * len(value))
    return mask(text)


def _values(line: str) -> tuple[str, ...]:
    """The secret values of ``line``, longest first."""
    return tuple(sorted({line[s.start : s.end] for s in find(line)}, key=len, reverse=True)) if line else ()


_values_remembered = lru_cache(maxsize=4096)(_values)
