"""Writing translated lines.

A source line the translator does not touch is written as it was read (``raw + ending``: byte for byte,
the lossless tree guarantees ``line.render()`` gives the same text).  A changed line is the source text
with the changed commands' spans replaced, so its comments, N number and line ending stay; a ``*``
checksum is recomputed over the new text.  Lines the translator adds (header, footer, a command that
becomes two) are plain text without N or checksum.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from gclint.rules.syntax import compute_checksum
from gclint.syntax.nodes import Command, Line

LINE_LIMIT = 100  # "Note that all lines will be truncated at 100 characters." (Hyrel Gcode page, M0)


def fit_line(text: str) -> tuple[list[str], str]:
    """Lines of at most 100 characters for ``text`` and what was done: "wrapped" (the comment on lines of
    its own, before the command), "cut" (an M0/M792 message, which must stay on its line), or "long"
    (the command itself is longer; left as it is)."""
    from gclint.syntax.parse import parse_line

    parsed = parse_line(text)
    comments = parsed.comments
    if not comments:
        return [text], "long"
    start = comments[0].column - 1
    command = text[:start].rstrip()
    if command and _ACTION_CODE.match(command):
        return [text[:LINE_LIMIT]], "cut"
    wrapped = []
    for comment in comments:
        if comment.style == "(":
            body, opening, closing = comment.text[1:-1].strip(), "(", ")"
        else:
            body, opening, closing = comment.text[1:].strip(), ";", ""
        room = LINE_LIMIT - len(opening) - len(closing) - 1
        words = body.split(" ")
        current = ""
        for word in words:
            while len(word) > room:  # a word longer than a line
                if current:
                    wrapped.append(current)
                    current = ""
                wrapped.append(word[:room])
                word = word[room:]
            if current and len(current) + 1 + len(word) > room:
                wrapped.append(current)
                current = word
            else:
                current = f"{current} {word}" if current else word
        if current or not wrapped:
            wrapped.append(current)
    lines = [f"{opening} {chunk}{closing}".rstrip() if opening == ";" else f"({chunk})" for chunk in wrapped]
    if not command:
        return lines, "wrapped"
    if len(command) > LINE_LIMIT:
        return [*lines, command], "long"
    return [*lines, command], "wrapped"


def fmt(value: float, places: int = 4) -> str:
    """A number as G-code text: at most ``places`` decimals, no trailing zeros, no ``-0``."""
    text = f"{value:.{places}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    if text in ("-0", ""):
        return "0"
    return text


def command_text(code: str, *words: str | None) -> str:
    """``command_text("M109", "T0", "S200")`` -> ``"M109 T0 S200"`` (None words are skipped)."""
    return " ".join([code, *(w for w in words if w)])


def rewrite(
    cmd: Command,
    *,
    code: str | None = None,
    drop: str = "",
    values: Mapping[str, str | None] | None = None,
    add: tuple[str, ...] = (),
    first: tuple[str, ...] = (),
    rename: dict[str, str] | None = None,
) -> str:
    """The text of ``cmd`` with changes: another ``code``, letters in ``drop`` removed, letters renamed
    (``{"A": "E"}``), the values of ``values`` replaced (None removes the word), words ``first`` put right
    after the code and ``add`` at the end.  Words that do not change keep their source text (``X10.000``
    stays ``X10.000``)."""
    values = values or {}
    parts = [code if code is not None else _code_text(cmd), *first]
    params = cmd.params
    for letter, value in params.items():  # in source order; a repeated letter keeps its first value
        if letter in drop:
            continue
        if rename and letter in rename:
            letter = rename[letter]
        if letter in values:
            value = values[letter]
            if value is None:
                continue
        parts.append(letter if value is None else letter + value)
    renamed = set(rename.values()) if rename else set()
    for letter, new in values.items():
        if new is not None and letter not in params and letter not in renamed:
            parts.append(letter + new)
    parts.extend(add)
    return " ".join(p for p in parts if p)


def _code_text(cmd: Command) -> str:
    return cmd.code or ""


class LineEdit:
    """What the translator does to one source line: replaced or removed commands, lines to insert
    before and after, notes for ``--annotate``."""

    __slots__ = ("line", "replaced", "before", "after", "notes", "changed", "dropped", "strip_comments", "order")

    def __init__(self, line: Line) -> None:
        self.line = line
        self.replaced: dict[int, str] = {}  # command index -> new text ("" removes the command)
        self.before: list[str] = []
        self.after: list[str] = []
        self.notes: list[str] = []
        self.changed = False  # the source line itself changes (not only insertions around it)
        self.dropped = False  # the whole line goes (a line that could not be parsed)
        self.strip_comments = False  # the line's comments go (they would be Hyrel host actions)
        # the order the source machine runs the line's commands in, when not as written (LinuxCNC's order of
        # execution): the commands are written one a line in that order, as Hyrel runs them as written
        self.order: tuple[int, ...] | None = None

    def render(self, annotate: bool, default_ending: str) -> list[str]:
        """The output lines, endings included."""
        line = self.line
        ending = line.ending
        several = len(line.parsed.commands) > 1  # one command a line, as the Hyrel pages show
        if not annotate and not self.before and not self.after and not self.dropped and not self.strip_comments:
            # the common case (one command rewritten in place): no list juggling
            main = (
                _apply(line, self.replaced, ending or default_ending, self.order)
                if self.replaced or several
                else line.raw
            )
            if main is None:
                return []
            return [main, ending]
        glue = ending or default_ending
        out: list[str] = [text + glue for text in self.before]
        if self.dropped:
            main = None
        elif self.strip_comments:
            main = _commands_only(line, self.replaced, self.order)
        elif self.replaced or several:
            main = _apply(line, self.replaced, glue, self.order)
        else:
            main = line.raw
        if main == line.raw and not self.before and not self.after:
            self.changed = False  # the new text is the old text
        if annotate and self.changed:
            note = "; ".join(self.notes) if self.notes else f"was '{_quote(line.raw)}'"
            if main is None:
                main = f"; gclint: dropped '{_quote(line.raw)}' ({note})"
            elif _ACTION_CODE.match(main):
                # on Hyrel the text after M0/M792 is a list of host actions: the note goes on a line of its own
                out.append(f"; gclint: {note}{glue}")
            else:
                main = f"{main} ; gclint: {note}" if main.strip() else f"; gclint: {note}"
        if main is not None:
            out.append(main + (glue if self.after else ending))
        for i, text in enumerate(self.after):
            last = i == len(self.after) - 1
            out.append(text + (ending if last else glue))
        if main is None and not self.after and out and not ending:
            # the dropped line was the last one and had no line ending: keep the file's missing final newline
            out[-1] = out[-1][: len(out[-1]) - len(glue)]
        return out


def _one_per_line(line: Line, replaced: dict[int, str], glue: str, order: tuple[int, ...] | None = None) -> str:
    """A changed line with several commands, one command a line (in ``order``, else as written): the first
    keeps the N number (and a recomputed checksum), the last the comments."""
    parsed = line.parsed
    raw = line.raw
    texts = []
    for index in order if order is not None else range(len(parsed.commands)):
        cmd = parsed.commands[index]
        text = replaced.get(index)
        if text is None:
            start, end = _span(cmd, line)
            text = raw[start:end]
            for comment in parsed.comments:
                text = text.replace(comment.text, "")
            text = " ".join(text.split())
        if text:
            texts.append(text)
    first = parsed.commands[0]
    prefix = raw[: first.column - 1]
    if parsed.checksum is not None:
        prefix = prefix[: parsed.checksum.column - 1] if parsed.checksum.column <= first.column else prefix
    texts[0] = prefix + texts[0]
    if parsed.checksum is not None:
        texts[0] = f"{texts[0]}*{compute_checksum(texts[0])}"
    if parsed.comments:
        texts[-1] += " " + " ".join(c.text for c in parsed.comments)
    return glue.join(texts)


def _commands_only(line: Line, replaced: dict[int, str], order: tuple[int, ...] | None = None) -> str | None:
    """The line's commands (replaced or as written), without its comments, N number and checksum."""
    texts = []
    commands = line.parsed.commands
    for index in order if order is not None else range(len(commands)):
        cmd = commands[index]
        text = replaced.get(index)
        if text is None:
            start, end = _span(cmd, line)
            text = line.raw[start:end]
            for comment in line.parsed.comments:  # a comment between the command's words
                text = text.replace(comment.text, "")
            text = " ".join(text.split())
        if text:
            texts.append(text)
    return " ".join(texts) or None


_ACTION_CODE = re.compile(r"[ \t]*(?:[Nn]\d+[ \t]*)?[Mm]0*(?:0|792)(?![\d.])")


def _quote(text: str) -> str:
    return text.strip().replace("'", '"')


def _span(cmd: Command, line: Line) -> tuple[int, int]:
    """0-based [start, end) of a command's source text."""
    parsed = line.parsed
    if len(parsed.commands) == 1 and not parsed.extra and all(c.style == ";" for c in parsed.comments):
        # one command: it runs to the comment, the checksum or the end of the line (no words to build)
        raw = line.raw
        end = len(raw)
        if parsed.comments:
            end = parsed.comments[0].column - 1
        if parsed.checksum is not None and parsed.checksum.column - 1 < end:
            end = parsed.checksum.column - 1
        while end > cmd.column and raw[end - 1] in " \t":
            end -= 1
        return cmd.column - 1, end
    end = cmd.column
    for node in cmd.nodes():
        if node.end_column > end:
            end = node.end_column
    return cmd.column - 1, end - 1


def _apply(line: Line, replaced: dict[int, str], glue: str = "\n", order: tuple[int, ...] | None = None) -> str | None:
    """The line's text with commands replaced; None when nothing but an N number and whitespace is left.
    When more than one command is left, each gets a line of its own (joined with ``glue``): the Hyrel
    pages show one command per line."""
    parsed = line.parsed
    raw = line.raw
    checksum = parsed.checksum
    commands = parsed.commands
    if len(commands) > 1 and sum(1 for i in range(len(commands)) if replaced.get(i, True)) > 1:
        return _one_per_line(line, replaced, glue, order)
    if len(commands) == 1 and checksum is None and not parsed.extra:
        text = replaced.get(0)
        if text and all(c.style == ";" for c in parsed.comments):
            start, end = _span(commands[0], line)
            return raw[:start] + text + raw[end:]
    tail = ""
    if checksum is not None:
        tail = raw[checksum.end_column - 1 :]
        raw = raw[: checksum.column - 1]
    comments = parsed.comments
    for index in sorted(replaced, key=lambda i: commands[i].column, reverse=True):
        cmd = commands[index]
        start, end = _span(cmd, line)
        text = replaced[index]
        inside = [c.text for c in comments if start < c.column - 1 < end]
        if inside:  # a comment between the command's words (G1 X1 (c) Y2): keep it after the command
            text = " ".join([text, *inside]) if text else " ".join(inside)
        if text:
            raw = raw[:start] + text + raw[end:]
        else:
            before = raw[:start]
            after = raw[end:]
            stripped = before.rstrip(" \t")
            if stripped:
                raw = stripped + (after if after[:1] in ("", " ", "\t", ";", "(", "*") else " " + after)
            else:
                raw = before + after.lstrip(" \t")
    if all(replaced.get(i) == "" for i in range(len(commands))):
        # nothing left to run: keep the comments (without the N number and checksum), else no line
        return " ".join(c.text for c in comments) or None
    if checksum is not None:
        return f"{raw}*{compute_checksum(raw)}{tail}"
    return raw
