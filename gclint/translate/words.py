"""Reading source words: numbers, flags, expressions, inches."""

from __future__ import annotations

from gclint.dialects.semantics import computed
from gclint.syntax.nodes import Command, to_number

INCH = 25.4
SCALED = "XYZIJKRE"  # letters converted from inches (F too, handled apart)


def num(text: str | None) -> float | None:
    """A parameter value as a number (None for a flag, an expression or a bad number)."""
    if text is None:
        return None
    return to_number(text)


def fast_float(text: str | None) -> float | None:
    """``float(text)`` for the hot path (no regex); None for a flag, a bad number, inf or nan."""
    try:
        value = float(text)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return None
    return value if value - value == 0 else None


def has_expression(cmd: Command) -> bool:
    """True when a parameter is an expression, a parameter reference or a function ({...}, [...], #..., SIN[30]:
    ``gclint.dialects.semantics.computed``)."""
    return any(computed(value) for value in cmd.params.values())
