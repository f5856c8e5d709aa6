"""What the dialect's code table says: titles, parameter meanings and readings, the words no decoder
reads, codes the dialect does not have.  Every dialect is explained from its table through these; the
topic modules add only what depends on numbers or on the job so far."""

from __future__ import annotations

from collections.abc import Iterable

from gclint.dialects.base import Code, Dialect
from gclint.explain.model import Explanation, Item
from gclint.syntax.nodes import Command, Word

# Letter meanings used when a code's table says nothing about a letter.
GENERIC = {
    "X": "X",
    "Y": "Y",
    "Z": "Z",
    "A": "A axis",
    "B": "B axis",
    "C": "C axis",
    "E": "extruder",
    "F": "feed rate, mm/min",
    "S": "S value",
    "P": "P value",
    "T": "tool",
    "I": "I value",
    "J": "J value",
    "K": "K value",
    "R": "R value",
    "H": "H value",
    "D": "D value",
    "L": "L value",
    "Q": "Q value",
}


def title(dialect: Dialect, code: str, spec: Code | None) -> str:
    if spec is not None and spec.summary:
        return spec.summary
    if spec is not None or dialect.knows(code):
        return f"a {dialect.name} command"
    return f"not a code of {dialect.title}"


def generic(dialect: Dialect, exp: Explanation, cmd: Command, spec: Code | None, skip: Iterable[str] = ()) -> None:
    """Each word not in ``skip``, with its meaning from the table; the required letters left out."""
    skip = set(skip)
    for word in cmd.words:
        if word.letter in skip:
            continue
        meaning = spec.meaning(word.letter) if spec is not None else None
        text = word.text.strip()
        if spec is not None and spec.params is not None and spec.param(word.letter) is None:
            exp.items.append(
                Item(text, f"{cmd.code} takes no {word.letter} in {dialect.name}: ignored or rejected", True)
            )
            continue
        param = spec.param(word.letter) if spec is not None else None
        if param is not None and param.forbidden:
            exp.items.append(Item(text, param.meaning, True))
            continue
        value = word.value if word.value is not None else ""
        if meaning is None:
            meaning = GENERIC.get(word.letter, f"{word.letter} value")
        exp.add(text, f"{meaning}: {value}" if value else f"{meaning} (no value)")
    if spec is not None and spec.params:
        for letter, param in spec.params.items():
            if param.required and letter not in cmd.params:
                exp.warn(f"{letter} is required ({param.meaning})")


def unknown(dialect: Dialect, exp: Explanation, cmd: Command) -> None:
    """A code the dialect does not have: what the firmware does with it, and the words as letters."""
    exp.warn(dialect.unknown_note.format(code=cmd.code, title=dialect.title))
    for word in cmd.words:
        exp.add(word.text.strip(), GENERIC.get(word.letter, f"{word.letter} value"))


def read(exp: Explanation, cmd: Command, spec: Code | None, letter: str) -> Word | None:
    """The word ``letter`` of ``cmd``, added with the table's reading of it (``Param.says``/``values``)."""
    word = cmd.param(letter)
    if word is not None:
        exp.add(word.text.strip(), reading(spec, letter, word.value))
    return word


def read_or_absent(exp: Explanation, cmd: Command, spec: Code | None, letter: str) -> Word | None:
    """``read``, or a note of what happens without the word (``Param.absent``)."""
    word = read(exp, cmd, spec, letter)
    if word is None:
        exp.note(absent(spec, letter))
    return word


def reading(spec: Code | None, letter: str, value: str | None) -> str:
    """The table's reading of ``letter`` written with ``value``."""
    return spec.params[letter].reading(value)  # type: ignore[union-attr,index]


def absent(spec: Code | None, letter: str) -> str:
    """What the table says happens when ``letter`` is not written."""
    return spec.params[letter].absent  # type: ignore[union-attr,index]


def does(exp: Explanation, spec: Code | None) -> None:
    """Note what the command does (``Code.does``)."""
    for text in spec.does if spec is not None else ():
        exp.note(text)


def notes(exp: Explanation, spec: Code | None) -> None:
    """Note what else the table says about the command (``Code.notes``)."""
    for text in spec.notes if spec is not None else ():
        exp.note(text)
