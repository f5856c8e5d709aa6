"""The translator classes are whole: the mixins of ``HyrelTranslator`` declare what they share
(gclint/translate/mixin.py), and a class that lacks a method its handler tables or its mixins need cannot be
constructed, instead of failing on the first line that needs it."""

from __future__ import annotations

import inspect

import pytest

from gclint import dialects
from gclint.syntax.nodes import Command
from gclint.syntax.source import Source
from gclint.translate import TranslationResult, translate_source
from gclint.translate.arc_moves import ArcMoves
from gclint.translate.cnc import CncTranslator
from gclint.translate.engine import Translator
from gclint.translate.heads import Heads
from gclint.translate.modal import Modal
from gclint.translate.motion import Motion
from gclint.translate.options import TranslateOptions
from gclint.translate.pairs import TO_HYREL
from gclint.translate.program import Program
from gclint.translate.reprap import RepRapToHyrel
from gclint.translate.spindle import Spindles


@pytest.mark.parametrize("source", sorted(TO_HYREL))
def test_every_translator_has_every_handler(source):
    cls = TO_HYREL[source]
    assert not inspect.isabstract(cls), cls.__abstractmethods__
    translator = cls(dialects.get(source), dialects.get("hyrel"), TranslateOptions())
    for klass in cls.__mro__:
        for code, name in getattr(klass, "HANDLERS", {}).items():
            method = getattr(cls, name)
            assert inspect.isfunction(method) and not getattr(method, "__isabstractmethod__", False), (code, name)
    assert set(translator.handlers) >= set(cls.HANDLERS)


def test_a_cnc_translator_without_its_tool_change_cannot_be_made():
    """CNC_HANDLERS send M6 to ``tool_change`` and M3/M4 to ``spindle``, which each CNC source defines."""

    class NoToolChange(CncTranslator):
        def spindle(self, cmd: Command) -> None:
            self.spindle_on(cmd, None)

    with pytest.raises(TypeError, match="tool_change"):
        NoToolChange(dialects.get("machinekit"), dialects.get("hyrel"), TranslateOptions())


def test_a_translator_without_the_line_writer_cannot_be_made():
    """The mixins call one another (``report``, ``replace``...): leaving one out is an error at construction."""

    class NoWriter(Heads, Program, Motion, ArcMoves, Modal, Spindles, Translator):
        pass

    with pytest.raises(TypeError, match="report"):
        NoWriter(dialects.get("marlin"), dialects.get("hyrel"), TranslateOptions())


def test_a_feed_on_any_command_is_translated_by_any_translator_that_reads_it():
    """``FEED_ON_ANY_COMMAND`` makes the loop call ``modal_feed``, which only the CNC translators had: another
    translator setting it failed with an AttributeError on the first ``G90 F300``."""

    class FeedAnywhere(RepRapToHyrel):
        FEED_ON_ANY_COMMAND = True

    translator = FeedAnywhere(dialects.get("reprap"), dialects.get("hyrel"), TranslateOptions())
    result = TranslationResult("t", "reprap", "hyrel")
    out = "".join(translate_source(Source.from_text("G21\nG90 F300\nG1 X5 Y5\n"), translator, result))
    lines = out.splitlines()
    assert "G90" in lines and "G1 X5 Y5 F300" in lines, out
