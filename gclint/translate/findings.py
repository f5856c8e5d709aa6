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
TR_ACTION = "TR009"  # a comment that Hyrel would run as a host action (M0/M792), removed


def codes(text: str, code: str, reason: str) -> dict[str, tuple[str, str]]:
    """Rows of a ``DROPPED`` table: ``codes("M117 M118", TR_DROPPED, "display message")``."""
    return {c: (code, reason) for c in text.split()}


# What a dropped code's loss touches, as the meaning diff names it (gclint/simulate/trace.py ASPECTS), for
# the DROPPED-table codes whose loss the diff can see.  Other TR002 table entries (acceleration, jerk,
# pressure advance, levelling, firmware configuration) touch nothing it compares; TR005 entries may
# touch anything ("*").
def _each(text: str, aspects: tuple[str, ...]) -> dict[str, tuple[str, ...]]:
    return dict.fromkeys(text.split(), aspects)


DROPPED_ASPECTS: dict[str, tuple[str, ...]] = {
    **_each("G30 G31 G32 G33 G34 G35 G80 G425 M290 M306", ("position",)),
    **_each("G29 G29.1 G29.2 G30.1 M600 M601", ("position",)),
    # offsets that last: they explain a position after the moves that set it again (compare.Explanations)
    **_each("M206 M428 M218 G92.2 G92.3 G43 G43.1 G43.2 G49", ("position", "offsets")),
    **_each("G12 G27 G60 M125", ("position", "moves")),
    **_each("M163 M164 M165 M166 M567 M710", ("e",)),
    **_each("M701 M702", ("e", "position")),
    **_each("M404 M405 M406 M407 M700", ("flow", "e")),
    **_each("M10 M11 M380 M381 M126 M127 M128 M129 M240 M851 M852", ("aux",)),
    **_each("M620 M620.1 M620.3 M620.10 M620.11 M621 M622 M622.1 M623 M624 M625", ("head", "e")),
    "G22": ("head",),
    "G23": ("head",),
    "G93": ("feed",),
    "G10": ("position", "wcs", "offsets"),
    "M220": ("feed",),
    "M223": ("spindle",),
    "M325": ("laser",),
    **_each("M323 M324 M321.2 M322.2", ("laser",)),
    "G26": ("*",),
    "M605": ("*",),
    "M410": ("*",),
}


# Codes that set coordinate offsets that last (G92, workspace and tool offsets): a loss in one explains a
# position after later moves set the axis again (compare.Explanations, "offsets").
LASTING_OFFSETS = frozenset(
    {"G92", "G52", *(code for code, aspects in DROPPED_ASPECTS.items() if "offsets" in aspects)}
)


def dropped_aspects(code: str, tr: str) -> tuple[str, ...] | None:
    """The aspects a dropped table code touches; None: any."""
    aspects = DROPPED_ASPECTS.get(code)
    if aspects is not None:
        return None if aspects == ("*",) else aspects
    return () if tr in (TR_LOST, TR_DROPPED) else None
