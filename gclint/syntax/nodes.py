"""The typed, lossless syntax tree of one G-code line.

Every character of a line belongs to exactly one node; ``Line.render()`` joins the nodes back into the
exact source text.  Nodes are immutable by convention and shared between identical lines (the parser
caches parse results by line text), so rules must never modify them.

Columns are 1-based character offsets into the decoded line.  Undecodable bytes are kept as lone
surrogates (``surrogateescape``), so re-encoding a rendered line gives back the original bytes.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

# Word kinds.
NUMBER = "number"  # X10.5, G1, T-1
FLAG = "flag"  # the X in "G28 X Y": a letter with no value
STRING = "string"  # P"MK3S"
EXPRESSION = "expression"  # X[#1+2] (LinuxCNC), X{var.x} (RepRapFirmware)
PARAMETER = "parameter"  # X#1, X#<name>
LIST = "list"  # E1:2:3 (RepRapFirmware drive lists)
QUERY = "query"  # T? (Prusa MMU: ask the user which filament)

# Command kinds.
GCODE = "gcode"  # G/M/T commands and their parameter words
IMPLICIT = "implicit"  # words with no G/M/T on the line: modal motion such as "X10 Y20"
TEXT = "text"  # commands whose argument is free text: M117 Hello
EXTENDED = "extended"  # Klipper: SET_FAN_SPEED FAN=x SPEED=1
META = "meta"  # RepRapFirmware meta commands (if, var, echo...), Smoothieware echo
OWORD = "oword"  # LinuxCNC O-words: o100 if [#1 GT 2]
ASSIGNMENT = "assignment"  # LinuxCNC parameter assignment: #1 = 5
PERCENT = "percent"  # % program delimiter
HOST = "host"  # OctoPrint's @ commands: @pause, @BEDLEVELVISUALIZER (run by the host, never sent to the printer)

# Every letter a word can have (grammar.lark: A-Z in either case, read as upper case, and LinuxCNC's @ ^ $).
WORD_LETTERS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZ@^$")

_STRICT_NUMBER = re.compile(r"[-+]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)|0x[0-9A-Fa-f]+")  # unambiguous: linear time
# A number as the fast path reads it (gclint.syntax.fastpath).  Unambiguous ("\d+\.?\d*" can split a run of
# digits many ways: exponential backtracking on a long line of words that ends in junk), at most 30 digits
# before and after the point: longer numbers are reported (SX006) by the grammar path.
FAST_NUMBER = r"[-+]?(?:[0-9]{1,30}(?:\.[0-9]{0,30})?|\.[0-9]{1,30})"
FAST_WORD = re.compile(rf"([A-Za-z])[ \t]*({FAST_NUMBER})")  # a letter and a number: group 1, group 2


class Node:
    """Base of all nodes: a piece of source text at a column."""

    __slots__ = ("text", "column")

    def __init__(self, text: str, column: int) -> None:
        self.text = text
        self.column = column

    @property
    def end_column(self) -> int:
        """Column just past the node."""
        return self.column + len(self.text)

    def __eq__(self, other: object) -> bool:
        return type(self) is type(other) and self.text == other.text and self.column == other.column

    def __hash__(self) -> int:
        return hash((type(self).__name__, self.text, self.column))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.text!r}, col={self.column})"


class Whitespace(Node):
    """Spaces and tabs between other nodes."""

    __slots__ = ()


class Text(Node):
    """Raw text: the argument of M117, a Klipper command's arguments, a meta command's body."""

    __slots__ = ()


class Name(Node):
    """The name of a command that is not a letter-and-number word: ``SET_FAN_SPEED``, ``if``, ``o100``."""

    __slots__ = ()


class Stray(Node):
    """A value with no word letter, such as the ``0.200`` in ``G1 0.200 F10000`` (firmware ignores it)."""

    __slots__ = ()


class Unparsed(Node):
    """Text the grammar could not parse (reported as SX001)."""

    __slots__ = ()


class Word(Node):
    """A letter with its value: ``X10.5``, ``G1``, ``P"MK3S"``, ``X[#1+2]`` or a bare flag ``X``.

    ``text`` is the exact source (spaces inside the word included); ``value`` is the exact source of the
    value alone (``None`` for a flag).
    """

    __slots__ = ("letter", "value", "kind")

    def __init__(self, letter: str, value: str | None, kind: str, text: str, column: int) -> None:
        self.text = text
        self.column = column
        self.letter = letter
        self.value = value
        self.kind = kind

    @property
    def number(self) -> float | None:
        """The value as a float, or None when it is not a plain, valid number."""
        if self.kind != NUMBER or self.value is None:
            return None
        return to_number(self.value)

    @property
    def is_valid_number(self) -> bool:
        return self.kind == NUMBER and self.value is not None and is_number(self.value)

    def __eq__(self, other: object) -> bool:
        return (
            type(other) is Word
            and self.text == other.text
            and self.column == other.column
            and self.letter == other.letter
            and self.value == other.value
            and self.kind == other.kind
        )

    def __hash__(self) -> int:
        return hash((self.letter, self.text, self.column))

    def __repr__(self) -> str:
        return f"Word({self.text!r}, col={self.column}, kind={self.kind})"


class Comment(Node):
    """A comment: ``; text``, ``(text)`` or (Klipper/test harness) ``# text``.

    ``style`` is the opening character; ``body`` is the text inside the delimiters.
    """

    __slots__ = ("style",)

    def __init__(self, text: str, column: int, style: str) -> None:
        self.text = text
        self.column = column
        self.style = style

    @property
    def body(self) -> str:
        if self.style == "(":
            return self.text[1:-1] if self.text.endswith(")") else self.text[1:]
        return self.text[1:]

    @property
    def closed(self) -> bool:
        return self.style != "(" or self.text.endswith(")")

    def __eq__(self, other: object) -> bool:
        return (
            type(other) is Comment
            and self.text == other.text
            and self.column == other.column
            and self.style == other.style
        )

    def __hash__(self) -> int:
        return hash((self.text, self.column))


class Checksum(Node):
    """The ``*nn`` checksum at the end of a line (RepRap host protocol)."""

    __slots__ = ()

    @property
    def value(self) -> int | None:
        digits = self.text[1:].strip()
        if not digits.isdigit() or len(digits) > 6:
            return None
        return int(digits)


class BlockDelete(Node):
    """The ``/`` block-delete mark at the start of a line."""

    __slots__ = ()


class Issue:
    """A syntax problem found while parsing; the SX rules turn these into findings."""

    __slots__ = ("code", "column", "message", "severity")

    def __init__(self, code: str, column: int, message: str, severity: str | None = None) -> None:
        self.code = code
        self.column = column
        self.message = message
        self.severity = severity  # None: the rule's default severity

    def __eq__(self, other: object) -> bool:
        return (
            type(other) is Issue
            and self.code == other.code
            and self.column == other.column
            and self.message == other.message
            and self.severity == other.severity
        )

    def __hash__(self) -> int:
        return hash((self.code, self.column, self.message))

    def __repr__(self) -> str:
        return f"Issue({self.code}, col={self.column}, {self.message!r})"


def _fast_word(m: re.Match[str]) -> Word:
    """The word a match of ``FAST_WORD`` in a fast-path command's source is."""
    return Word(m.group(1).upper(), m.group(2), NUMBER, m.group(0), m.start() + 1)


class Command:
    """One command on a line: its code (``G1``, ``M109``, ``T3``, ``G2.1``, ``SET_FAN_SPEED``, ``if``)
    and its parameter words.

    ``code`` is normalised (upper-case letter, no leading zeros, no trailing ``.0``) so that ``g01``
    and ``G1`` dispatch alike; ``word`` keeps the exact source of the code.  ``params`` maps each
    parameter letter to the source text of its value (first occurrence; ``None`` for a flag).
    Parameter words are built on first use for lines read by the fast path.
    """

    __slots__ = ("code", "kind", "column", "params", "args", "_word", "_words", "_src", "_span")

    def __init__(
        self,
        code: str | None,
        kind: str,
        column: int,
        params: dict[str, str | None],
        word: Node | None = None,
        words: tuple[Word, ...] | None = None,
        args: Text | None = None,
        src: str | None = None,
        span: tuple[int, int] | None = None,
    ) -> None:
        self.code = code
        self.kind = kind
        self.column = column
        self.params = params
        self.args = args
        self._word = word
        self._words = words
        self._src = src
        self._span = span

    # -- parameter access -------------------------------------------------------------------------

    def has(self, letter: str) -> bool:
        return letter in self.params

    def get(self, letter: str, default: float | None = None) -> float | None:
        """The value of parameter ``letter`` as a number (``default`` when absent or not a number)."""
        value = self.params.get(letter)
        if value is None:
            return default
        number = to_number(value)
        return default if number is None else number

    def raw(self, letter: str) -> str | None:
        """The exact source text of the value of ``letter`` (``None`` when absent or a flag)."""
        return self.params.get(letter)

    def param(self, letter: str) -> Word | None:
        """The parameter word for ``letter`` (first occurrence), with its column."""
        if self._words is None and self._src is not None:  # (one word built, not all: a rule's report)
            start, end = self._span  # type: ignore[misc]
            words = FAST_WORD.finditer(self._src, start, end)
            next(words, None)  # (the code word)
            for m in words:
                if m.group(1).upper() == letter:
                    return _fast_word(m)
            return None
        for w in self.words:
            if w.letter == letter:
                return w
        return None

    @property
    def letter(self) -> str:
        return self.code[0] if self.code else ""

    @property
    def number(self) -> str:
        """The numeric part of a G/M/T code as text (``"2.1"`` for ``G2.1``)."""
        return self.code[1:] if self.code and self.kind == GCODE else ""

    @property
    def word(self) -> Node | None:
        """The code word itself (``G1`` in ``G1 X10``), a ``Name`` for Klipper, meta and O-word
        commands; None for implicit commands and assignments."""
        if self._words is None and self._src is not None:
            self._materialize()
        return self._word

    @property
    def words(self) -> tuple[Word, ...]:
        """The parameter words, in source order (duplicates included)."""
        if self._words is None:
            if self._src is None:
                return ()
            self._materialize()
        return self._words  # type: ignore[return-value]

    def _materialize(self) -> None:
        """Build the code word and parameter words the fast path's canonical tier left unbuilt."""
        start, end = self._span  # type: ignore[misc]
        words = [_fast_word(m) for m in FAST_WORD.finditer(self._src, start, end)]  # type: ignore[arg-type]
        if self.kind == GCODE and words:
            self._word, self._words = words[0], tuple(words[1:])
        else:  # pragma: no cover - only G/M/T commands are left unbuilt
            self._word, self._words = None, tuple(words)

    def nodes(self) -> Iterator[Node]:
        """The nodes that make up the command's source (a text command's words lie inside its args)."""
        if self.word is not None:
            yield self.word
        if self.kind != TEXT:
            yield from self.words
        if self.args is not None:
            yield self.args

    def __eq__(self, other: object) -> bool:
        return (
            type(other) is Command
            and self.code == other.code
            and self.kind == other.kind
            and self.column == other.column
            and self.params == other.params
            and self.word == other.word
            and self.words == other.words
            and self.args == other.args
        )

    def __hash__(self) -> int:
        return hash((self.code, self.column))

    def __repr__(self) -> str:
        return f"Command({self.code!r}, kind={self.kind}, col={self.column}, params={self.params})"


class ParsedLine:
    """What the parser found on one line of text (without its line ending).

    Shared between identical lines; ``Line`` adds the line number and ending.
    """

    __slots__ = (
        "commands",
        "comments",
        "line_number",
        "checksum",
        "block_delete",
        "issues",
        "extra",
        "kind",
        "special",
    )

    def __init__(
        self,
        commands: tuple[Command, ...] = (),
        comments: tuple[Comment, ...] = (),
        line_number: Word | None = None,
        checksum: Checksum | None = None,
        block_delete: BlockDelete | None = None,
        issues: tuple[Issue, ...] = (),
        extra: tuple[Node, ...] = (),
        kind: str = "code",
    ) -> None:
        self.commands = commands
        self.comments = comments
        self.line_number = line_number
        self.checksum = checksum
        self.block_delete = block_delete
        self.issues = issues
        self.extra = extra  # stray values, unparsed text, oword arguments: nodes outside commands
        self.kind = kind  # "blank", "comment", "code", "percent", "error"
        # True when the line has anything besides commands (the engine skips a few checks otherwise)
        self.special = bool(comments) or bool(issues) or line_number is not None or checksum is not None

    def nodes(self) -> list[Node]:
        """All non-whitespace nodes, in column order."""
        out: list[Node] = []
        if self.block_delete is not None:
            out.append(self.block_delete)
        if self.line_number is not None:
            out.append(self.line_number)
        for cmd in self.commands:
            out.extend(cmd.nodes())
        out.extend(self.comments)
        out.extend(self.extra)
        if self.checksum is not None:
            out.append(self.checksum)
        out.sort(key=_column)
        return out

    def __eq__(self, other: object) -> bool:
        return (
            type(other) is ParsedLine
            and self.kind == other.kind
            and self.commands == other.commands
            and self.comments == other.comments
            and self.line_number == other.line_number
            and self.checksum == other.checksum
            and self.block_delete == other.block_delete
            and self.issues == other.issues
            and self.extra == other.extra
        )

    def __hash__(self) -> int:
        return hash((self.kind, self.commands))

    def __repr__(self) -> str:
        return (
            f"ParsedLine(kind={self.kind}, commands={list(self.commands)}, comments={list(self.comments)},"
            f" n={self.line_number}, cs={self.checksum}, issues={list(self.issues)}, extra={list(self.extra)})"
        )


def _column(node: Node) -> int:
    return node.column


class Line:
    """One line of a G-code file: its number (1-based), its text, its ending and its parse."""

    __slots__ = ("number", "raw", "ending", "parsed")

    def __init__(self, number: int, raw: str, ending: str, parsed: ParsedLine) -> None:
        self.number = number
        self.raw = raw
        self.ending = ending
        self.parsed = parsed

    @property
    def commands(self) -> tuple[Command, ...]:
        return self.parsed.commands

    @property
    def comments(self) -> tuple[Comment, ...]:
        return self.parsed.comments

    @property
    def issues(self) -> tuple[Issue, ...]:
        return self.parsed.issues

    @property
    def kind(self) -> str:
        return self.parsed.kind

    @property
    def comment_text(self) -> str:
        """The bodies of all comments on the line, joined by spaces."""
        return " ".join(c.body for c in self.parsed.comments)

    def elements(self) -> list[Node]:
        """Every node of the line, whitespace included, in order: joining their texts gives ``raw``."""
        out: list[Node] = []
        pos = 1
        raw = self.raw
        for node in self.parsed.nodes():
            if node.column > pos:
                out.append(_gap(raw[pos - 1 : node.column - 1], pos))
            out.append(node)
            pos = node.end_column
        if pos <= len(raw):
            out.append(_gap(raw[pos - 1 :], pos))
        return out

    def render(self) -> str:
        """The line's source text rebuilt from its nodes, line ending included."""
        return "".join(n.text for n in self.elements()) + self.ending

    def __repr__(self) -> str:
        return f"Line({self.number}, {self.raw!r})"


def _gap(text: str, column: int) -> Node:
    if text.strip(" \t") == "":
        return Whitespace(text, column)
    return Unparsed(text, column)


# -- numbers ------------------------------------------------------------------------------------------


def is_number(text: str) -> bool:
    """True when ``text`` is a G-code number: optional sign, digits with at most one dot."""
    return _STRICT_NUMBER.fullmatch(text) is not None


def to_number(text: str) -> float | None:
    """Convert a G-code number; None when it is not a valid, finite number."""
    try:
        value = float(text)
    except ValueError:
        if text[:2] == "0x" and _STRICT_NUMBER.fullmatch(text) and len(text) < 20:
            return float(int(text, 16))
        return None
    if value != value or value in (float("inf"), float("-inf")):
        return None
    if not _STRICT_NUMBER.fullmatch(text):
        return None
    return value


def normalize_code(letter: str, number: str) -> str:
    """``("g", "01")`` -> ``"G1"``; ``("M", "862.30")`` -> ``"M862.3"``; ``("T", "-1")`` -> ``"T-1"``.

    Works on the text only, so a 5000-digit code cannot raise.
    """
    sign = ""
    if number[:1] in "+-":
        sign = "-" if number[0] == "-" else ""
        number = number[1:]
    whole, _, frac = number.partition(".")
    whole = whole.lstrip("0") or "0"
    frac = frac.rstrip("0")
    return letter.upper() + sign + whole + ("." + frac if frac else "")
