"""The TR codes a translator reports (documented as rules in gclint/rules/translation.py)."""

from __future__ import annotations

TR_DROPPED = "TR001"  # no Hyrel counterpart, no effect on the job
TR_LOST = "TR002"  # no Hyrel counterpart, the source firmware did something
TR_APPROX = "TR003"  # the nearest Hyrel command; the behaviour differs
TR_NOTE = "TR004"  # translated, with a documented difference
TR_UNTRANSLATABLE = "TR005"  # cannot be translated
TR_ADDRESS = "TR006"  # Hyrel v4 <-> v5: no certain counterpart
TR_NO_TOOL = "TR007"  # a tool maps to an address the printer does not have
TR_AFTER_END = "TR008"  # after the source's end of program


def codes(text: str, code: str, reason: str) -> dict[str, tuple[str, str]]:
    """Rows of a ``DROPPED`` table: ``codes("M117 M118", TR_DROPPED, "display message")``."""
    return {c: (code, reason) for c in text.split()}
