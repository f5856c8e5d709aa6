"""Translation between dialects: read with the source dialect, map by meaning, write with the target.

``translator_for`` (pairs.py) picks the translator of a dialect pair; ``translate_source`` (engine.py)
streams a file through it and yields output text line by line.  Untouched lines are rendered from their
lossless tree, so they come out byte for byte.
"""

from __future__ import annotations

from gclint.translate.engine import TranslationResult, Translator, UnsupportedPair, translate_source
from gclint.translate.pairs import translator_for

__all__ = ["TranslationResult", "Translator", "translate_source", "translator_for", "UnsupportedPair"]
