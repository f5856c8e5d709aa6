"""Assemble parsed pieces (words, comments, checksum...) into a ``ParsedLine``.

Both the lark parser and the fast path produce a flat, ordered list of pieces and hand it here, so the
grouping of words into commands, and the syntax issues found on the way, are defined once.
"""

from __future__ import annotations

import re

from gclint.syntax.nodes import (
    ASSIGNMENT,
    GCODE,
    IMPLICIT,
    NUMBER,
    STRING,
    TEXT,
    BlockDelete,
    Checksum,
    Command,
    Comment,
    Issue,
    Node,
    ParsedLine,
    Stray,
    Text,
    Word,
    is_number,
    normalize_code,
)

# Codes whose argument is free text (see TEXT_CODE in grammar.lark).
TEXT_CODES = frozenset(
    ["M16", "M23", "M28", "M30", "M32", "M33", "M37", "M98", "M115", "M117", "M118", "M486"]
    + ["M552", "M553", "M554", "M624", "M928", "M1002"]
    + [f"M81{i}" for i in range(10)]
)

# A text argument made only of words (M486 S1, M98 P100 L2, M98 P"homez.g") is read as parameters.
_NUM = r"[-+]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)"  # unambiguous: no backtracking blow-up (see fastpath._NUM)
_TEXT_WORDS = re.compile(rf'(?:[ \t]*[A-Za-z][ \t]*(?:{_NUM}|"(?:[^"]|"")*"))+[ \t]*')
_TEXT_WORD = re.compile(rf'([A-Za-z])[ \t]*({_NUM}|"(?:[^"]|"")*")')

# Syntax issue codes (the SX rules in gclint/rules/syntax.py describe them).
PARSE_ERROR = "SX001"
DUPLICATE_WORD = "SX002"
BAD_CHECKSUM_PLACE = "SX001"
UNCLOSED_COMMENT = "SX005"
BAD_NUMBER = "SX006"
STRAY_VALUE = "SX007"


class TextCommand:
    """Piece: a free-text command (``M117 Hello``): its code word and its text."""

    __slots__ = ("word", "text")

    def __init__(self, word: Word, text: Text | None) -> None:
        self.word = word
        self.text = text


class Assignment:
    """Piece: a LinuxCNC parameter assignment (``#1 = 5``)."""

    __slots__ = ("text", "target", "value")

    def __init__(self, text: Text, target: str, value: str) -> None:
        self.text = text
        self.target = target
        self.value = value


MAX_DIGITS = 30  # per side of the decimal point; the fast path's patterns use the same bound

# The exponent of a number in exponent notation ("F1.875e+06", as some generators print floats): an E word
# straight after a number, "e" with an integer (signed, or after an upper-case letter: "g1x10e1" is a compact
# line in lower case), or "E" with a signed integer of two digits or more (as printf's %E writes it; "X10E-2"
# in a line without blanks is a compact E word).
_EXPONENT_LOWER = re.compile(r"[-+]?[0-9]{1,4}")
_EXPONENT_UPPER = re.compile(r"[-+][0-9]{2,4}")

# An IPv4 address after M80/M81: the argument OctoPrint's smart-plug plugins read ("M81 192.168.1.84" switches
# the printer's plug off), never sent to the firmware
_IPV4 = re.compile(r"\d{1,3}(?:\.\d{1,3}){3}")


def _exponent_of(previous: Word | None, piece: Word) -> str | None:
    """The number written in exponent notation when the E word ``piece`` is the exponent of the word
    ``previous`` (written straight after it), else None.  G-code numbers have no exponent: the grammar reads
    the E as a word of its own, and this names the number the author may have meant."""
    if previous is None or piece.letter != "E" or piece.value is None or previous.value is None:
        return None
    if previous.kind != NUMBER or previous.letter in "GMTN" or previous.column + len(previous.text) != piece.column:
        return None
    lower = piece.text[:1] == "e"
    if not (_EXPONENT_LOWER if lower else _EXPONENT_UPPER).fullmatch(piece.value) or not is_number(previous.value):
        return None
    if lower and piece.value[0] not in "+-" and not previous.text[:1].isupper():
        return None  # ("g1x10e1": a compact line in lower case, whose e1 is an E word)
    return f"{previous.text[:1]}{previous.value}{piece.text[:1]}{piece.value}"


def written_out(number: str) -> str:
    """The number of an exponent notation written plainly: ``F1.875e+06`` -> ``F1875000``."""
    from decimal import Decimal, InvalidOperation

    try:
        plain = format(Decimal(number[1:]), "f")
    except InvalidOperation:  # pragma: no cover - _exponent_of gives numbers only
        return number
    return number[0] + (plain.rstrip("0").rstrip(".") if "." in plain else plain)


def exponents(cmd: Command) -> list[tuple[Word, Word, str]]:
    """The numbers of ``cmd`` written in exponent notation: (the word the number starts, the E word the grammar
    reads its exponent as, the number as written, ``F1.875e+06``).  What such a number means depends on the
    firmware (RepRapFirmware reads ``C7.06e-8`` as one number), so the rules of a dialect say whether to report
    it (HY067 on Hyrel, whose pages do not say)."""
    words = cmd.words
    code_word = cmd.word
    if isinstance(code_word, Word):  # (not a Name: SET_FAN_SPEED or o100 is no number)
        words = (code_word, *words)
    found = []
    for previous, word in zip(words, words[1:], strict=False):
        number = _exponent_of(previous, word)
        if number is not None:
            found.append((previous, word, number))
    return found


def _too_long(value: str) -> bool:
    whole, _, frac = value.lstrip("+-").partition(".")
    return len(whole) > MAX_DIGITS or len(frac) > MAX_DIGITS


def code_of(word: Word) -> str:
    """The normalised command code of a G/M/T word."""
    if word.kind == NUMBER and word.value is not None and is_number(word.value):
        return normalize_code(word.letter, word.value)
    return word.letter + (word.value or "")


# Commands that take G or M as a parameter letter, by the firmware sources (Prusa-Firmware-Buddy @ 818d812f
# and the BambuStudio machine profiles; docs/sources.md, Firmware inventories): Bambu
# "M900 K0.02 M1.0", "M1006 A0 B0 L0 C0 D0 M100", "M970 Q1 A7 ... M20", "M983.1 M1", "G151 P M",
# "G383 O0 M2 T140", "M9711 M E Z...", "M9712 E M"; Prusa Buddy "M863 M L P E R", "M959 ... G ... K M",
# "M960 ... G ... M", "M46 M".  (Prusa MK3's "G80 ... M" is left out: in a CNC program "G80 M5" is two
# commands.)
LETTER_PARAMETERS = {
    "M900": "M",
    "M1006": "M",
    "M970": "M",
    "M983.1": "M",
    "G151": "M",
    "G383": "M",
    "M9711": "M",
    "M9712": "M",
    "M863": "M",
    "M959": "GM",
    "M960": "GM",
    "M46": "M",
}
# A code's number: no sign, and at most three digits after the point (the longest sub-codes any
# inventory lists are three digits: Bambu's G28.140).  "M0.125481" cannot be a code.
_CODE_NUMBER = re.compile(r"[0-9]+(?:\.[0-9]{0,3})?")


def _parameter_of(current: Command | None, piece: Word) -> bool:
    """Whether the G or M word ``piece`` is a parameter of the command ``current`` rather than a command."""
    if current is None or current.kind != GCODE or piece.letter not in "GM" or piece.value is None:
        return False
    if piece.letter in LETTER_PARAMETERS.get(current.code, ""):  # type: ignore[arg-type]
        return True
    return piece.kind == NUMBER and not _CODE_NUMBER.fullmatch(piece.value)


def assemble(
    pieces: list,
    block_delete: BlockDelete | None = None,
    line_number: Word | None = None,
) -> ParsedLine:
    """Group ``pieces`` (in source order) into commands and collect syntax issues."""
    commands: list[Command] = []
    comments: list[Comment] = []
    extra: list[Node] = []
    issues: list[Issue] = []
    checksum: Checksum | None = None
    current: Command | None = None
    current_words: list[Word] = []
    previous_word: Word | None = None  # the word just before (for exponent notation)
    exponents: dict[tuple[int, str], str] = {}  # (command, letter) -> the number in exponent notation its word ends

    def close() -> None:
        nonlocal current, current_words
        if current is not None:
            current._words = tuple(current_words)
            commands.append(current)
        current = None
        current_words = []

    for piece in pieces:
        if checksum is not None and not isinstance(piece, Comment):
            issues.append(Issue(PARSE_ERROR, checksum.column, "the checksum must be at the end of the line"))
            extra.append(checksum)  # kept in the tree (lossless), but not the line's checksum
            checksum = None
        if isinstance(piece, Word):
            letter = piece.letter
            exponent = _exponent_of(previous_word, piece)  # (named in the message of a repeated E)
            previous_word = piece
            if piece.kind == NUMBER and piece.value is not None:
                if not is_number(piece.value):
                    issues.append(Issue(BAD_NUMBER, piece.column, f"{letter} value {piece.value!r} is not a number"))
                elif _too_long(piece.value):
                    issues.append(
                        Issue(
                            BAD_NUMBER,
                            piece.column,
                            f"{letter} value has {len(piece.value)} characters: no firmware reads a number this long",
                        )
                    )
            # G and M words start a command; so does a T that starts the line or follows another T
            # command (T2M6, T1 T2).  A G, M or T with no value after a command is a flag parameter
            # (Bambu "M620 M", Marlin "M20 T", RepRapFirmware "T T{expr}"), and so is a G or M word
            # after a command when it cannot be a code or the command takes that letter (see below).
            if letter in "GMT" and (piece.value is not None or current is None) and not _parameter_of(current, piece):
                starts = (
                    letter != "T"
                    or current is None
                    or (
                        current.kind == GCODE and current.code[0] == "T" and current.word.value is not None  # type: ignore[index, union-attr]
                    )
                )
            else:
                starts = False
            if starts:
                close()
                if piece.value is None and letter != "T":
                    issues.append(Issue(PARSE_ERROR, piece.column, f"{letter} needs a number"))
                current = Command(code_of(piece), GCODE, piece.column, {}, word=piece)
                continue
            if current is None or current.kind not in (GCODE, IMPLICIT):
                close()
                current = Command(None, IMPLICIT, piece.column, {})
            if letter in current.params:
                where = current.code or "this block"
                first_exponent = exponents.get((id(current), letter))
                if first_exponent is not None or exponent is not None:
                    # (one of the two is the exponent of a number in exponent notation)
                    issues.append(
                        Issue(
                            DUPLICATE_WORD,
                            piece.column,
                            f"{letter} appears more than once in {where}: the E of "
                            f"{first_exponent or exponent} is read as an E word of its own",
                        )
                    )
                elif current.params[letter] == piece.value:
                    # The same value twice is redundant, not ambiguous: every firmware gets the same value.
                    issues.append(
                        Issue(DUPLICATE_WORD, piece.column, f"{piece.text.strip()} is repeated in {where}", "warning")
                    )
                else:
                    issues.append(Issue(DUPLICATE_WORD, piece.column, f"{letter} appears more than once in {where}"))
            else:
                current.params[letter] = piece.value
                if exponent is not None:
                    exponents[(id(current), letter)] = exponent
            current_words.append(piece)
            continue
        previous_word = None
        if isinstance(piece, Comment):
            comments.append(piece)
            if not piece.closed:
                issues.append(Issue(UNCLOSED_COMMENT, piece.column, "comment opened with '(' is never closed"))
        elif isinstance(piece, Checksum):
            checksum = piece
            if piece.value is None:
                issues.append(Issue(PARSE_ERROR, piece.column, "checksum '*' is not followed by a number"))
        elif isinstance(piece, TextCommand):
            close()
            words = _text_words(piece.text)
            params: dict[str, str | None] = {}
            for w in words:
                params.setdefault(w.letter, w.value)
            commands.append(
                Command(
                    code_of(piece.word), TEXT, piece.word.column, params, word=piece.word, words=words, args=piece.text
                )
            )
        elif isinstance(piece, Assignment):
            close()
            commands.append(
                Command(
                    "#",
                    ASSIGNMENT,
                    piece.text.column,
                    {"target": piece.target, "value": piece.value},
                    words=(),
                    args=piece.text,
                )
            )
        elif isinstance(piece, Stray):
            extra.append(piece)
            if not (current is not None and current.code in ("M80", "M81") and _IPV4.fullmatch(piece.text.strip())):
                issues.append(
                    Issue(STRAY_VALUE, piece.column, f"value {piece.text!r} has no word letter and is ignored")
                )
            # (else OctoPrint's smart-plug plugins' "M81 192.168.1.84": the host switches that plug off)
        else:  # pragma: no cover - a new piece type must be handled above
            raise TypeError(f"unknown piece {piece!r}")
    close()
    if commands or line_number is not None or block_delete is not None or checksum is not None or extra:
        kind = "code"
    elif comments:
        kind = "comment"
    else:
        kind = "blank"
    return ParsedLine(
        commands=tuple(commands),
        comments=tuple(comments),
        line_number=line_number,
        checksum=checksum,
        block_delete=block_delete,
        issues=tuple(issues),
        extra=tuple(extra),
        kind=kind,
    )


def _text_words(text: Text | None) -> tuple[Word, ...]:
    """The words of a free-text argument when it consists of words only, else ()."""
    if text is None or not _TEXT_WORDS.fullmatch(text.text):
        return ()
    base = text.column
    return tuple(
        Word(
            m.group(1).upper(),
            m.group(2),
            STRING if m.group(2).startswith('"') else NUMBER,
            m.group(0),
            base + m.start(),
        )
        for m in _TEXT_WORD.finditer(text.text)
    )
