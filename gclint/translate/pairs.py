"""Which translator serves which pair of dialects.

Targets are Hyrel only: ``hyrel`` (v5) and ``hyrel-v4``.  A foreign source is translated to v5 meaning
first; for a v4 target the v5 lines are then renumbered (renumber.Chain).  v4 <-> v5 is a renumbering.
The same dialect on both sides is the identity (every byte kept).
"""

from __future__ import annotations

from gclint import dialects
from gclint.dialects.base import Dialect
from gclint.translate.base import HyrelTranslator
from gclint.translate.carvera import CarveraToHyrel
from gclint.translate.engine import Translator, UnsupportedPair
from gclint.translate.machinekit import MachinekitToHyrel
from gclint.translate.marlin import MarlinToHyrel
from gclint.translate.options import TranslateOptions
from gclint.translate.renumber import Chain, Renumber
from gclint.translate.reprap import RepRapToHyrel

# The dialect the translators write, with its versions (``Dialect.variant_of``): Hyrel v5, and v4 by renumbering.
TARGET = "hyrel"

# source dialect -> the translator into Hyrel v5
TO_HYREL: dict[str, type[HyrelTranslator]] = {
    "marlin": MarlinToHyrel,
    "reprap": RepRapToHyrel,
    "machinekit": MachinekitToHyrel,
    "carvera": CarveraToHyrel,
}


def translator_for(source: Dialect, target: Dialect, options: TranslateOptions | None = None) -> Translator:
    """The translator from ``source`` to ``target``; UnsupportedPair when there is none."""
    if source.name == target.name:
        return Translator(source, target, options)
    translator = get(source, target, options)
    if translator is None:
        raise UnsupportedPair(f"translation from {source.name} to {target.name} is not supported")
    return translator


def is_target(dialect: Dialect) -> bool:
    """Whether the translators write ``dialect`` (Hyrel, either version)."""
    return (dialect.variant_of or dialect.name) == TARGET


def get(source: Dialect, target: Dialect, options: TranslateOptions | None = None) -> Translator | None:
    if not is_target(target):
        return None
    if options is None:
        options = TranslateOptions()
    if is_target(source):
        return Renumber(source, target, options)
    factory = TO_HYREL.get(source.name)
    if factory is None:
        return None
    v5 = dialects.get(TARGET)
    first = factory(source, v5, options)
    if target.name == v5.name:
        return first
    return Chain(first, Renumber(v5, target, options, count=False))
