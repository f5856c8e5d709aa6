"""What the mixins of ``HyrelTranslator`` share (writer.py, heads.py, program.py, motion.py, arc_moves.py,
modal.py, spindle.py): each is a subclass of ``TranslatorMixin``, which declares the translator's state
(set in ``HyrelTranslator.__init__``), the class settings a pair translator may change, and the methods
one mixin calls on another.  The methods are abstract: a translator class that lacks one of them (a mixin
left out) cannot be constructed.  Nothing here runs; the declarations are for the type checker and for
readers.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable
from typing import ClassVar

from gclint.dialects.base import Dialect
from gclint.machine.interpreter import Interpreter
from gclint.machine.state import MachineState
from gclint.syntax.nodes import Command, Line
from gclint.translate.engine import TranslationResult
from gclint.translate.options import TranslateOptions
from gclint.translate.output import LineEdit
from gclint.translate.state import HyrelSide
from gclint.translate.tools import SourceTools

Aspects = str | Iterable[str] | None


class TranslatorMixin(ABC):
    # -- the translator (engine.Translator, HyrelTranslator.__init__) -------------------------------------
    source: Dialect
    target: Dialect
    opts: TranslateOptions
    interp: Interpreter
    state: MachineState  # the source machine's state, before the command being translated
    hy: HyrelSide  # what the Hyrel printer will believe
    tools: SourceTools
    handlers: dict[str | None, Callable[[TranslatorMixin, Command], None]]  # looked up with a code, or None
    evalues: bool
    inch: bool
    extra_always: bool
    annotate: bool
    positions: frozenset[int]
    arc_absolute: bool
    single_nozzle: bool
    rpm: float | None
    spindle_percent: str | None
    wcs: str
    wcs_selected: bool
    g53_next: bool
    g92_axes: set[str]
    sync_due: bool
    layer_z: float | None
    layer_moves: int
    layer_height: float | None
    default_layer_height: float | None
    height_written: float | None
    height_before: float | None
    pending_height: float | None
    single_move_layers: int
    spiral: bool
    native_reported: bool
    default_ending: str
    _ending_known: bool
    _last_ending: str
    _aggregate: dict[tuple, list]
    _head_cache: dict[int, int | None]
    _head_users: dict[int, int]
    # the line being translated
    line: Line | None
    line_feed_inch: bool | None  # the units the line's F is in, where they differ from the line's (Motion)
    edit: LineEdit | None
    index: int
    result: TranslationResult | None

    # -- class settings (HyrelTranslator, Motion, Spindles) ----------------------------------------------
    EXTRUDER: str
    FAN_MAX: float
    EXTRA_LETTERS: ClassVar[frozenset[str]]
    MAX_RPM: ClassVar[float | None]
    E_MODE_FOLLOWS_POSITIONING: str | None
    DEFAULT_WORKSPACE: str | None
    TURNS_COUNT_THE_ARC: bool
    MACHINE: str
    G53_ALONE: str
    E_LINEAR: bool
    SPINDLE_FOLLOWS_TOOL: bool

    # -- writer.LineWriter -------------------------------------------------------------------------------
    @abstractmethod
    def _edit(self) -> LineEdit: ...

    @abstractmethod
    def feed_inches(self) -> bool: ...

    @abstractmethod
    def replace(self, cmd: Command, text: str, note: str | None = None) -> None: ...

    @abstractmethod
    def remove(self, cmd: Command, code: str, reason: str, *, key: object = None, aspects: Aspects = None) -> None: ...

    @abstractmethod
    def consume(self, cmd: Command, note: str | None = None) -> None: ...

    @abstractmethod
    def untranslatable(self, cmd: Command, reason: str, *, key: object = None, aspects: Aspects = None) -> None: ...

    @abstractmethod
    def before(self, *texts: str, note: str) -> None: ...

    @abstractmethod
    def after(self, *texts: str, note: str, first: bool = False) -> None: ...

    @abstractmethod
    def report(
        self, code: str, message: str, *, key: object = None, cmd: Command | None = None, aspects: Aspects = None
    ) -> None: ...

    # -- heads.Heads -------------------------------------------------------------------------------------
    @abstractmethod
    def head(self, index: int | None = None, what: str = "tool") -> int | None: ...

    @abstractmethod
    def focus_address(self) -> int | None: ...

    @abstractmethod
    def sync_working_head(self) -> None: ...

    # -- program.Program ---------------------------------------------------------------------------------
    @abstractmethod
    def rehome(self) -> None: ...

    @abstractmethod
    def before_motion(self, focus: bool = True) -> None: ...

    @abstractmethod
    def before_extrusion(self) -> None: ...

    @abstractmethod
    def e_absolute(self) -> bool: ...

    # -- motion.Motion -----------------------------------------------------------------------------------
    @abstractmethod
    def move(self, cmd: Command) -> None: ...

    @abstractmethod
    def mixing_e(self, cmd: Command) -> bool: ...

    @abstractmethod
    def e_delta(self, cmd: Command) -> float | None: ...

    @abstractmethod
    def native_flow(self, cmd: Command) -> None: ...

    @abstractmethod
    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None: ...

    @abstractmethod
    def source_feed(self) -> float | None: ...

    @abstractmethod
    def scaled_e(self, text: str | None) -> str: ...

    # -- modal.Modal -------------------------------------------------------------------------------------
    @abstractmethod
    def g53_move(self, cmd: Command, move: Command | None, axes: str) -> None: ...

    # -- spindle.Spindles --------------------------------------------------------------------------------
    @abstractmethod
    def speed_word(self, cmd: Command) -> None: ...

    @abstractmethod
    def spindle_to_head(self, old: int | None, new: int) -> None: ...

    # -- base.HyrelTranslator ----------------------------------------------------------------------------
    @abstractmethod
    def fallback(self, cmd: Command) -> None: ...
