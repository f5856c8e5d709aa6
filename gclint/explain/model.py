"""What ``gclint explain`` produces: one ``Explanation`` per command, a list of ``Item``s (the words as
written and what each does, notes and warnings), rendered as the Hyrel page renders its examples."""

from __future__ import annotations

from dataclasses import dataclass, field

DEG = "°C"


@dataclass
class Item:
    """One decoded part of a command: the word as written (empty for notes) and what it does."""

    word: str
    text: str
    warning: bool = False


@dataclass
class Explanation:
    """One command, decoded."""

    line: int
    source: str
    code: str | None
    title: str
    items: list[Item] = field(default_factory=list)
    seconds: float | None = None  # the dwell the command makes (G4), as the dialect counts it

    def add(self, word: str, text: str) -> None:
        self.items.append(Item(word, text))

    def note(self, text: str) -> None:
        self.items.append(Item("", text))

    def warn(self, text: str) -> None:
        self.items.append(Item("", text, warning=True))

    def masked(self) -> Explanation:
        """A copy with every secret of the source line (a password, a key) masked wherever it is quoted."""
        from gclint import secrets

        values = sorted({self.source[s.start : s.end] for s in secrets.find(self.source)}, key=len, reverse=True)
        if not values:
            return self

        def hide(text: str) -> str:
            for value in values:
                text = text.replace(value, secrets.MASK_CHAR * len(value))
            return secrets.mask(text)

        items = [Item(hide(i.word), hide(i.text), warning=i.warning) for i in self.items]
        return Explanation(self.line, hide(self.source), self.code, hide(self.title), items, self.seconds)

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
