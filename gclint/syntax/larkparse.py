"""Parse one line with the lark grammar (gclint/grammar.lark) into a ``ParsedLine``.

This is the reference parser.  It handles every shape the grammar knows; the fast path hands it any
line it does not recognise.  A line the grammar rejects becomes a ``ParsedLine`` of kind ``"error"``
with an SX001 issue: parsing never raises.
"""

from __future__ import annotations

import hashlib
import io
import re
from functools import lru_cache
from pathlib import Path

import lark
from lark import Lark, Token, Tree
from lark.exceptions import LarkError, UnexpectedCharacters, UnexpectedInput

from gclint.secrets import mask
from gclint.syntax.build import PARSE_ERROR, Assignment, TextCommand, assemble
from gclint.syntax.nodes import (
    EXPRESSION,
    EXTENDED,
    FLAG,
    HOST,
    LIST,
    META,
    NUMBER,
    OWORD,
    PARAMETER,
    PERCENT,
    QUERY,
    STRING,
    BlockDelete,
    Checksum,
    Command,
    Comment,
    Issue,
    Name,
    Node,
    ParsedLine,
    Stray,
    Text,
    Unparsed,
    Word,
)

GRAMMAR_PATH = Path(__file__).resolve().parent.parent / "grammar.lark"
# The parse tables lark builds from the grammar (about 40 ms at each start), saved with Lark.save: package
# data written by ``python -m gclint.syntax.larkparse``, read only when their first line names this lark
# version and this grammar (else the grammar is built as before).  tests/test_grammar_tables.py checks
# that they are current and parse as the grammar does.
TABLES_PATH = GRAMMAR_PATH.with_name("grammar.tables")

_KLIPPER_PARAM = re.compile(r"""([A-Za-z_][A-Za-z0-9_]*)=("(?:[^"\\]|\\.)*"|'[^']*'|\S*)""")
_OPTIONS = {"parser": "lalr", "lexer": "contextual", "maybe_placeholders": False}


def tables_key(grammar: str) -> bytes:
    """The first line of the tables made from ``grammar`` by the installed lark."""
    digest = hashlib.sha256(grammar.encode("utf-8")).hexdigest()
    return f"gclint grammar tables: lark {lark.__version__}, grammar sha256 {digest}\n".encode()


def _plugins() -> dict:
    """lark-cython, when installed, about doubles the speed of this fallback parser (measured in
    bench/bench_parser.py); the trees are the same."""
    try:
        import lark_cython
    except ImportError:  # pragma: no cover - optional accelerator
        return {}
    return {"_plugins": lark_cython.plugins}


@lru_cache(maxsize=1)
def parser() -> Lark:
    """The LALR parser for one line (loaded or built once per process)."""
    grammar = GRAMMAR_PATH.read_text(encoding="utf-8")
    try:
        data = TABLES_PATH.read_bytes()
    except OSError:
        data = b""
    key = tables_key(grammar)
    if data.startswith(key):
        try:
            return Lark.__new__(Lark)._load(io.BytesIO(data[len(key) :]), **_plugins())
        except Exception:  # pragma: no cover - tables this lark cannot read: build them
            pass
    return Lark(grammar, **_OPTIONS, **_plugins())


def write_tables() -> Path:
    """Save the parse tables of the grammar (``python -m gclint.syntax.larkparse``)."""
    grammar = GRAMMAR_PATH.read_text(encoding="utf-8")
    out = io.BytesIO()
    Lark(grammar, **_OPTIONS).save(out)  # (without plugins: they are given again when the tables are loaded)
    TABLES_PATH.write_bytes(tables_key(grammar) + out.getvalue())
    return TABLES_PATH


def parse_with_lark(raw: str) -> ParsedLine:
    """Parse ``raw`` (one line, no line ending) with the grammar."""
    try:
        tree = parser().parse(raw)
    except UnexpectedInput as exc:
        return _error_line(raw, exc)
    except (LarkError, RecursionError) as exc:  # pragma: no cover - defensive
        return _error_line(raw, exc)
    return _Builder(raw).build(tree)


def _error_line(raw: str, exc: Exception) -> ParsedLine:
    column = getattr(exc, "column", None)
    if not isinstance(column, int) or column < 1:
        column = 1
    # The message quotes the line, cut short: quoted from the masked line, as a cut secret ("'x' P'hunte")
    # would no longer be recognised as one by the reports (mask keeps lengths, so columns stay).
    shown_line = mask(raw)
    if isinstance(exc, UnexpectedCharacters):
        ch = shown_line[column - 1 : column]
        shown = repr(ch) if ch.isprintable() else f"character {ch.encode('utf-8', 'surrogateescape')!r}"
        message = f"unexpected {shown}"
    elif column > len(raw):
        message = "unexpected end of line"
    else:
        message = f"unexpected {shown_line[column - 1 : column + 9]!r}"
    return ParsedLine(
        extra=(Unparsed(raw, 1),) if raw else (),
        issues=(Issue(PARSE_ERROR, column, f"cannot parse line: {message}"),),
        kind="error",
    )


def _text(tree: Tree | Token) -> str:
    # Iterative: "X[[[[...]]]]" nests as deep as the line is long (a recursive walk hit RecursionError).
    if not isinstance(tree, Tree):
        return str(tree)
    parts: list[str] = []
    stack: list[Tree | Token] = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, Tree):
            stack.extend(reversed(node.children))
        else:
            parts.append(str(node))
    return "".join(parts)


def _first_token(tree: Tree | Token) -> Token:
    while isinstance(tree, Tree):
        tree = tree.children[0]
    return tree


def _token(node: Tree | Token) -> Token:
    """A child the grammar makes a token (a tree there: the grammar and the builder are out of step)."""
    if isinstance(node, Tree):  # pragma: no cover
        raise AssertionError(f"unexpected rule {node.data}")
    return node


def _column(node: Tree | Token) -> int:
    """The column of a token (the grammar's tokens all have one: lark's ``propagate_positions``)."""
    column = _token(node).column
    if column is None:  # pragma: no cover
        raise AssertionError(f"no column for {node!r}")
    return column


def split_letter(text: str) -> tuple[str, str]:
    """``"X -5"`` -> ``("X", "-5")``: the word letter (upper-cased) and the value's source text."""
    return text[0].upper(), text[1:].lstrip(" \t")


def klipper_params(args: str) -> dict[str, str | None]:
    """KEY=VALUE pairs of a Klipper extended command (keys upper-cased, quotes kept)."""
    return {k.upper(): v for k, v in _KLIPPER_PARAM.findall(args)}


class _Builder:
    def __init__(self, raw: str) -> None:
        self.raw = raw

    def build(self, tree: Tree) -> ParsedLine:
        block_delete = None
        line_number = None
        statement = None
        for child in tree.children:
            if not isinstance(child, Tree):
                if child.type == "BLOCK_DELETE":
                    block_delete = BlockDelete(str(child), child.column)
                elif child.type == "LINENO":
                    letter, value = split_letter(str(child))
                    line_number = Word(letter, value, NUMBER, str(child), child.column)
            elif str(child.data) == "host":
                return self.named(child, HOST, None, None)
            else:
                statement = child
        if statement is None or str(statement.data) == "words":
            pieces = self.word_pieces(statement.children if statement is not None else [])
            return assemble(pieces, block_delete, line_number)
        kind = str(statement.data)
        if kind == "percent":
            return self.percent(statement, block_delete, line_number)
        if kind == "meta":
            return self.named(statement, META, block_delete, line_number)
        if kind == "extended":
            return self.named(statement, EXTENDED, block_delete, line_number)
        if kind == "oword":
            return self.oword(statement, block_delete, line_number)
        raise AssertionError(f"unknown statement {kind}")  # pragma: no cover

    # -- ordinary lines -------------------------------------------------------------------------------

    def word_pieces(self, parts: list) -> list:
        pieces: list = []
        for part in parts:
            if not isinstance(part, Tree):
                t = part.type
                if t == "WS":
                    continue
                if t == "STRAY":
                    pieces.append(Stray(str(part), part.column))
                elif t == "CHECKSUM":
                    pieces.append(Checksum(str(part), part.column))
                elif t in ("SEMI_COMMENT", "PAREN_COMMENT", "HASH_COMMENT", "UNCLOSED_COMMENT"):
                    pieces.append(Comment(str(part), part.column, str(part)[0]))
                else:  # pragma: no cover - grammar and builder out of step
                    raise AssertionError(f"unexpected token {t}")
                continue
            data = str(part.data)
            if data == "number_word":
                tok = part.children[0]
                letter, value = split_letter(str(tok))
                kind = LIST if ":" in value else NUMBER
                pieces.append(Word(letter, value, kind, str(tok), _column(tok)))
            elif data == "string_word":
                tok = part.children[0]
                letter, value = split_letter(str(tok))
                pieces.append(Word(letter, value, STRING, str(tok), _column(tok)))
            elif data == "query_word":
                tok = part.children[0]
                pieces.append(Word(str(tok)[0].upper(), "?", QUERY, str(tok), _column(tok)))
            elif data == "flag_word":
                tok = part.children[0]
                pieces.append(Word(str(tok).upper(), None, FLAG, str(tok), _column(tok)))
            elif data == "expr_word":
                tok = part.children[0]
                text = _text(part)
                letter, value = split_letter(text)
                value_kind = EXPRESSION if value.lstrip("+-")[:1] in "[{" else PARAMETER
                pieces.append(Word(letter, value, value_kind, text, _column(tok)))
            elif data == "text_command":
                code_tok = part.children[0]
                letter, value = split_letter(str(code_tok))
                word = Word(letter, value, NUMBER, str(code_tok), _column(code_tok))
                arg = None
                if len(part.children) > 1:
                    arg_tok = part.children[1]
                    arg = Text(str(arg_tok), _column(arg_tok))
                pieces.append(TextCommand(word, arg))
            elif data == "assignment":
                first = _first_token(part)
                text = _text(part)
                target, _, value = text.partition("=")
                pieces.append(Assignment(Text(text, _column(first)), target.strip(), value.strip()))
            else:  # pragma: no cover
                raise AssertionError(f"unexpected rule {data}")
        return pieces

    # -- other statements -----------------------------------------------------------------------------

    def percent(self, tree: Tree, block_delete: BlockDelete | None, line_number: Word | None) -> ParsedLine:
        comments = []
        extra: list[Node] = []
        for child in tree.children:
            if not isinstance(child, Tree) and child.type == "PERCENT":
                extra.append(Text(str(child), child.column))
            elif not isinstance(child, Tree) and child.type != "WS":
                comments.append(Comment(str(child), child.column, str(child)[0]))
        issues = tuple(
            Issue("SX005", c.column, "comment opened with '(' is never closed") for c in comments if not c.closed
        )
        return ParsedLine(
            comments=tuple(comments),
            extra=tuple(extra),
            line_number=line_number,
            block_delete=block_delete,
            issues=issues,
            kind=PERCENT,
        )

    def named(self, tree: Tree, kind: str, block_delete: BlockDelete | None, line_number: Word | None) -> ParsedLine:
        name_tok = tree.children[0]
        args = None
        comments = []
        for child in map(_token, tree.children[1:]):
            if child.type in ("META_REST", "EXT_ARGS", "HOST_ARGS"):
                args = Text(str(child), _column(child))
            else:
                comments.append(Comment(str(child), _column(child), str(child)[0]))
        name = str(name_tok)
        if kind == EXTENDED:
            code = name.upper()
            params = klipper_params(args.text) if args is not None else {}
        else:
            code = name
            params = {}
        command = Command(
            code, kind, _column(name_tok), params, word=Name(name, _column(name_tok)), words=(), args=args
        )
        return ParsedLine(
            commands=(command,),
            comments=tuple(comments),
            line_number=line_number,
            block_delete=block_delete,
            kind="code",
        )

    def oword(self, tree: Tree, block_delete: BlockDelete | None, line_number: Word | None) -> ParsedLine:
        name_tok = tree.children[0]
        name = str(name_tok)
        rest = tree.children[1:]
        if _token(name_tok).type == "OWORD_OPEN":  # O[#2 * 10] call, o#<sub> call
            name += _text(rest[0])
            rest = rest[1:]
        label = name[1:].strip(" \t")
        keyword = ""
        comments: list[Comment] = []
        extra: list[Node] = []
        issues: list[Issue] = []
        for child in rest:
            if not isinstance(child, Tree):
                if child.type == "WS":
                    continue
                if child.type in ("SEMI_COMMENT", "PAREN_COMMENT", "HASH_COMMENT", "UNCLOSED_COMMENT"):
                    comment = Comment(str(child), child.column, str(child)[0])
                    comments.append(comment)
                    if not comment.closed:
                        issues.append(Issue("SX005", child.column, "comment opened with '(' is never closed"))
                    continue
                if child.type == "OKEY" and not keyword:
                    keyword = str(child).lower()
                extra.append(Text(str(child), child.column))
            else:
                extra.append(Text(_text(child), _column(_first_token(child))))
        command = Command(
            "O",
            OWORD,
            _column(name_tok),
            {"label": label, "keyword": keyword},
            word=Name(name, _column(name_tok)),
            words=(),
        )
        return ParsedLine(
            commands=(command,),
            comments=tuple(comments),
            line_number=line_number,
            block_delete=block_delete,
            issues=tuple(issues),
            extra=tuple(extra),
            kind="code",
        )


if __name__ == "__main__":
    print(f"wrote {write_tables()}")
