"""Which translator serves which pair of dialects (``translator_for`` in engine.py asks ``get``).

Targets are Hyrel only: ``hyrel`` (v5) and ``hyrel-v4``.  A foreign source is translated to v5 meaning
first; for a v4 target the v5 lines are then renumbered (renumber.Chain).  v4 <-> v5 is a renumbering.
"""

from __future__ import annotations

from gclint.dialects.base import Dialect
from gclint.translate.engine import Translator


def get(source: Dialect, target: Dialect, options=None) -> Translator | None:
    from gclint.dialects import get as dialect
    from gclint.translate.carvera import CarveraToHyrel
    from gclint.translate.machinekit import MachinekitToHyrel
    from gclint.translate.marlin import MarlinToHyrel, RepRapToHyrel
    from gclint.translate.options import TranslateOptions
    from gclint.translate.renumber import Chain, Renumber

    if target.family != "hyrel":
        return None
    if options is None:
        options = TranslateOptions()
    if source.family == "hyrel":
        return Renumber(source, target, options)
    factories = {
        "marlin": MarlinToHyrel,
        "reprap": RepRapToHyrel,
        "machinekit": MachinekitToHyrel,
        "carvera": CarveraToHyrel,
    }
    factory = factories.get(source.name)
    if factory is None:
        return None
    v5 = dialect("hyrel")
    first = factory(source, v5, options)
    if target.name == v5.name:
        return first
    return Chain(first, Renumber(v5, target, options, count=False))
