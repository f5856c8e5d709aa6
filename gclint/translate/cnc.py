"""What the CNC sources (Machinekit/LinuxCNC and Carvera) share: one handler table for their common
rows, the LinuxCNC-style tool change (``T`` prepares, ``M6`` changes), G53 machine-coordinate moves and
the end of program codes.  docs/translation.md, Machinekit -> Hyrel and Carvera -> Hyrel.
"""

from __future__ import annotations

import re
from abc import abstractmethod
from typing import ClassVar

from gclint.syntax.nodes import Command
from gclint.translate.base import HyrelTranslator

_TOOL_NUMBER = re.compile(r"-?[0-9]{1,6}")  # (ASCII digits: str.isdigit() also takes "²")
# The rows Machinekit and Carvera share (the rows every source shares are HyrelTranslator.HANDLERS).
CNC_HANDLERS: dict[str, str] = {
    "G53": "machine_coordinates",
    "M0": "stop",
    "M2": "end_program",
    "M30": "end_program",
    "M3": "spindle",
    "M4": "spindle",
    "M5": "spindle_stop",
    "M6": "tool_change",
}


class CncTranslator(HyrelTranslator):
    """Base of the CNC source translators."""

    HANDLERS: ClassVar[dict[str, str]] = CNC_HANDLERS
    CHECK_EXPRESSIONS = True
    END_CODES: ClassVar[frozenset[str]] = frozenset({"M2", "M30"})
    G53_ALONE = "drop"  # LinuxCNC: "Non-modal; requires G0/G1 active"
    SPINDLE_FOLLOWS_TOOL = True  # a mapped tool is a spindle head (spindle.py)
    DEFAULT_WORKSPACE = "G54"
    # LinuxCNC and the Carvera start in G54 (LinuxCNC G-code docs, G54-G59; Carvera community docs, gcodes.md)
    FEED_ON_ANY_COMMAND = True

    def __init__(self, source, target, options=None) -> None:
        super().__init__(source, target, options)
        self.prepared: int | None = None  # the tool a T word prepared for the next M6

    @abstractmethod
    def spindle(self, cmd: Command) -> None:
        """M3/M4 (``CNC_HANDLERS``): the source's spindle, in the source's speed unit."""

    @abstractmethod
    def tool_change(self, cmd: Command) -> None:
        """M6 (``CNC_HANDLERS``): the change to the tool a T word prepared (``prepared``) or M6 T names."""

    def tool_command(self, cmd: Command) -> None:
        number = (cmd.code or "T")[1:]
        if _TOOL_NUMBER.fullmatch(number) is None:  # (not "--0", which int() refuses)
            self.untranslatable(cmd, "a tool given by an expression cannot be translated", key="T?")
            return
        # LinuxCNC and Carvera: T prepares the tool, M6 changes to it (T6M6)
        self.prepared = int(number)
        self.consume(cmd)

    def focus_address(self) -> int | None:
        """The head to focus before the first move: the active tool's; for a tool the printer has no head
        for (reported, TR007), the spindle head, so that the job's moves have a head (mapped tool 0)."""
        address = self.head(None)
        return address if address is not None else self.opts.spindle_address()

    def stop(self, cmd: Command) -> None:
        """M0: a pause on both sides."""
        self.pause_command(cmd, "M0")

    def spindle_stop(self, cmd: Command) -> None:
        self.spindle_off(cmd)
