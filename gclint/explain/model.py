"""What ``gclint explain`` produces: one ``Explanation`` per command, a list of ``Item``s (the words as
written and what each does, notes and warnings), rendered as the Hyrel page renders its examples."""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass, field

DEG = "°C"


@dataclass
class Item:
    """One decoded part of a command: the word as written (empty for notes) and what it does."""

    word: str
    text: str
    warning: bool = False


# What stands for the words of a command from a secret on (``Explanation.masked``).
_HIDDEN = Item("***", "the rest of the command: part of a secret value, not shown")


@dataclass
class Explanation:
    """One command, decoded."""

    line: int
    source: str
    code: str | None
    title: str
    items: list[Item] = field(default_factory=list)
    seconds: float | None = None  # the dwell the command makes (G4), as the dialect counts it
    secrets_masked: bool = field(default=False, repr=False, compare=False)  # (``masked`` has nothing to do)

    def add(self, word: str, text: str) -> None:
        self.items.append(Item(word, text))

    def note(self, text: str) -> None:
        self.items.append(Item("", text))

    def warn(self, text: str) -> None:
        self.items.append(Item("", text, warning=True))

    def masked(self, values: Collection[str] | None = None, hidden: Collection[str] = ()) -> Explanation:
        """A copy with every secret of the source line (a password, a key) masked wherever it is quoted, and
        the words ``hidden`` not shown at all: the words of a command from a password on (an unquoted
        password is read as words, "Phunter2" as P, h, u, n...: ``Explainer.explain_line``).  ``values``:
        the line's secret values, longest first (``secret_values``), when the caller has them."""
        from gclint import secrets

        if self.secrets_masked:
            return self
        if values is None:
            values = secret_values(self.source)
        if not values and not hidden:
            self.secrets_masked = True  # (its source holds none)
            return self

        def hide(text: str) -> str:
            for value in values:
                text = text.replace(value, secrets.MASK_CHAR * len(value))
            return secrets.mask(text)

        items: list[Item] = []
        for item in self.items:
            if item.word and item.word in hidden:
                if not any(i.word == _HIDDEN.word for i in items):  # (one item: not even the words' lengths)
                    items.append(_HIDDEN)
            else:
                items.append(Item(hide(item.word), hide(item.text), warning=item.warning))
        return Explanation(
            self.line, hide(self.source), self.code, hide(self.title), items, self.seconds, secrets_masked=True
        )

    def to_dict(self) -> dict:
        return {
            "line": self.line,
            "source": self.source,
            "code": self.code,
            "title": self.title,
            "items": [{"word": i.word, "text": i.text, "warning": i.warning} for i in self.items],
            **({"dwell_s": self.seconds} if self.seconds is not None else {}),
        }

    def render(self) -> str:
        head = f"* {self.code} ({self.title})" if self.code else f"* ({self.title})"
        lines = [head]
        for item in self.items:
            if item.word:
                lines.append(f"** {item.word} ({item.text})")
            elif item.warning:
                lines.append(f"** warning: {item.text}")
            else:
                lines.append(f"** note: {item.text}")
        return "\n".join(lines)


def secret_values(text: str) -> tuple[str, ...]:
    """The secret values in ``text`` (a line), longest first."""
    from gclint import secrets

    if not secrets.may_hold(text):
        return ()
    return tuple(sorted({text[s.start : s.end] for s in secrets.find(text)}, key=len, reverse=True))


def number(text: str | None) -> float | None:
    """The number a value holds, or None (no value, or not a number)."""
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        return None


def fmt(value: float) -> str:
    """A number as the page writes it: ``240``, not ``240.0``."""
    if value != value or value in (float("inf"), float("-inf")):
        return str(value)
    return str(int(value)) if value == int(value) and abs(value) < 1e15 else f"{value:g}"
