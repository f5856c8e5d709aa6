"""The translator every translation into Hyrel v5 shares: the per-line loop and the dispatch.

A pair translator (marlin.py, machinekit.py, carvera.py) is a subclass of ``HyrelTranslator`` with three
tables:

* ``HANDLERS``: source code -> method name.  A handler looks at one command (the source machine state is
  the state *before* the command) and says what Hyrel gets: nothing (the line stays byte for byte),
  ``replace``, ``remove``, lines ``before``/``after``.  The rows every source shares are here; the
  rows the CNC sources share are in cnc.py.
* ``DROPPED``: source code -> (TR code, reason) for codes with no Hyrel counterpart.
* ``END_CODES``: codes that end the program in the source (the footer goes there).

Anything else is dropped with a finding: output is allow-listed (docs/translation.md, rule X1), an unknown
code is never passed through.  The source machine state comes from ``gclint.machine.Interpreter`` for the
source dialect (X3); what the Hyrel side will believe is ``state.HyrelSide``.

The rest of the machinery lives by topic in mixins: writer.py (editing the current line, findings),
heads.py (tool -> head, temperatures, fans), program.py (header and footer), motion.py (G0/G1, E, feed,
plain moves), arc_moves.py (G2/G3), modal.py (units, positioning, G92, workspaces), spindle.py.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator
from typing import ClassVar

from gclint.dialects.base import Dialect
from gclint.machine.interpreter import Interpreter
from gclint.machine.job_settings import read_settings
from gclint.syntax.nodes import ASSIGNMENT, EXTENDED, GCODE, HOST, IMPLICIT, META, OWORD, Command, Line
from gclint.syntax.parse import PARSE_LIMIT, canonical_text, code_before_long_comment, parse_line
from gclint.translate.arc_moves import ArcMoves
from gclint.translate.engine import PlainMove, TranslationResult, Translator
from gclint.translate.findings import (
    LASTING_OFFSETS,
    TR_AFTER_END,
    TR_APPROX,
    TR_DROPPED,
    TR_LOST,
    TR_NOTE,
    TR_UNTRANSLATABLE,
    dropped_aspects,
)
from gclint.translate.heads import Heads
from gclint.translate.mixin import TranslatorMixin
from gclint.translate.modal import Modal
from gclint.translate.motion import Motion
from gclint.translate.options import TranslateOptions
from gclint.translate.output import LINE_LIMIT, LineEdit, fit_line, rewrite
from gclint.translate.program import Program
from gclint.translate.spindle import Spindles
from gclint.translate.state import HyrelSide
from gclint.translate.tools import SourceTools
from gclint.translate.words import INCH, has_expression, num
from gclint.translate.writer import LineWriter

WORKSPACES = {f"G{n}": "workspace" for n in range(54, 60)}  # G54-G59: the same codes on Hyrel
_MOVES = frozenset({"G0", "G1", "G2", "G3"})


class HyrelTranslator(LineWriter, Heads, Program, Motion, ArcMoves, Modal, Spindles, Translator):
    """Translate one source dialect into Hyrel v5 (hyrel-v4 output renumbers this translator's lines)."""

    # the rows every source shares (same code, same meaning or a shared transformation)
    HANDLERS: ClassVar[dict[str, str]] = {
        "G0": "move",
        "G1": "move",
        "G2": "arc",
        "G3": "arc",
        "G17": "keep",
        "G18": "keep",
        "G19": "keep",
        "G20": "units",
        "G21": "units",
        "G90": "positioning",
        "G91": "positioning",
        "G92": "set_position",
        "G92.1": "clear_g92",
        "G4": "dwell",
        "G90.1": "arc_mode",
        "G91.1": "arc_mode",
        **WORKSPACES,
    }
    DROPPED: ClassVar[dict[str, tuple[str, str]]] = {}
    END_CODES: ClassVar[frozenset[str]] = frozenset()
    EXTRUDER = "E"  # the source's extrusion word (Machinekit: A)
    CHECK_EXPRESSIONS = False  # dialects with {expressions}, [expressions] or #parameters
    FAN_MAX = 255.0  # the source's full fan value
    EXTRA_LETTERS: ClassVar[frozenset[str]] = frozenset()  # letters that make ``move`` call ``move_extra``
    MAX_RPM: ClassVar[float | None] = None  # the source machine's top spindle speed (an assumption for %)
    # A subclass whose ``move`` differs from this class's only for words a plain move never has (H, S, R...)
    # says so, to keep plain moves off the tree (``plain_route``).
    MOVE_OVERRIDE_IGNORES_PLAIN: ClassVar[bool] = False
    # The note written with M82/M83 when the source's G90/G91 also switch the E mode (Marlin: G90/G91 set E
    # absolute/relative; Machinekit: the extruder axis A follows them; Hyrel's do not: Marlin G-code reference G90/G91,
    # Machinekit-FDM remap, Hyrel wiki Gcode page M82/M83); None where the E mode is independent (RepRapFirmware,
    # Carvera).
    E_MODE_FOLLOWS_POSITIONING: str | None = None
    DEFAULT_WORKSPACE: str | None = None  # the workspace the source starts in (CNC sources: G54)
    FEED_ON_ANY_COMMAND = False  # an F on a non-motion command sets the feed (LinuxCNC, Carvera)
    TURNS_COUNT_THE_ARC = False  # G2/G3 P: extra full circles (Marlin); LinuxCNC: the turns, P1 the arc itself
    MACHINE = "the source machine's"  # whose machine coordinates G53 names (messages)
    G53_ALONE = "keep"  # G53 with no move on its line: "keep", "drop" (does nothing), "next" (the next G0/G1)
    # The pauses that take a message as the rest of the line ("M0 [S|P] [string]", Marlin G-code
    # reference M0-M1: "wait for user", P ms, S s, the rest of the line a message): a pattern for the line up to the
    # message, or None.  A line the grammar cannot read for its message keeps the pause.
    TEXT_PAUSE: ClassVar[re.Pattern[str] | None] = None

    def __init__(self, source: Dialect, target: Dialect, options: TranslateOptions | None = None) -> None:
        super().__init__(source, target, options)
        self.opts = options if options is not None else TranslateOptions()
        self.interp = Interpreter(source)
        self.state = self.interp.state
        self.evalues = self.opts.flow == "evalues"
        self.inch = False  # the source is in inches (G20): lengths and feeds are converted
        # the units the current line's F words are read in, where the source reads them before the line's G20/G21
        # (LinuxCNC, "G-code Order of Execution": "Set feed rate (F)" before "Set length units (G20, G21)"); None:
        # the units in force (``Motion.feed_inches``)
        self.line_feed_inch: bool | None = None
        self.extra_always = False  # call move_extra on every move (Carvera laser mode)
        self.annotate = self.opts.annotate
        self.positions = frozenset(self.opts.printer.positions)
        # (the class's functions, called with the translator: bound methods here would make a reference cycle)
        self.handlers: dict[str | None, Callable[[TranslatorMixin, Command], None]] = {}
        for klass in reversed(type(self).__mro__):
            for code, name in getattr(klass, "HANDLERS", {}).items():
                self.handlers[code] = getattr(type(self), name)
        self.hy = HyrelSide()  # what the Hyrel printer will believe
        self.arc_absolute = False  # G90.1 in the source: I J K are the centre's coordinates, not offsets
        self.single_nozzle = False  # the job's settings: single_extruder_multi_material (read_job)
        self.rpm: float | None = None  # the source's modal spindle speed (S words)
        self.spindle_percent: str | None = None  # the last spindle speed written (S percent; spindle.py)
        # the workspace the job selected (G54-G59), invoked again after a G53 move (modal.py)
        self.wcs = self.DEFAULT_WORKSPACE or "G54"
        self.wcs_selected = self.DEFAULT_WORKSPACE is not None
        self.g53_next = False  # Carvera: a G53 alone on its line applies to the next G0/G1
        self.g92_axes: set[str] = set()  # X Y Z given a G92 offset since they were last homed (G92.1 clears)
        self.tools = SourceTools()  # what the source firmware believes about its tools (tools.py)
        self.sync_due = True  # (a tool change; the first working move) carry set-point, fan, flow before it
        # native flow: the layer height Hyrel computes the flow with (M756), per layer (motion.py)
        self.layer_z: float | None = None
        self.layer_moves = 0
        self.layer_height: float | None = None  # stated by the slicer for the coming layer
        self.default_layer_height: float | None = None  # stated once for the whole job
        self.height_written: float | None = None
        self.height_before: float | None = None  # the height declared before the last one
        self.pending_height: float | None = None  # declared at the layer's second move (after a 1-move layer)
        self.single_move_layers = 0
        self.spiral = False
        self.native_reported = False  # the native-flow finding (once: it holds for the whole job)
        # the file
        self.default_ending = "\n"
        self._ending_known = False
        self._last_ending = "\n"
        self._aggregate: dict[tuple, list] = {}
        self._head_cache: dict[int, int | None] = {}
        self._head_users: dict[int, int] = {}  # head address -> the source tool it prints for (heads.py)
        # the line being translated
        self.line: Line | None = None
        self.edit: LineEdit | None = None
        self.index = 0
        self.result: TranslationResult | None = None

    # -- the loop --------------------------------------------------------------------------------------

    def mark(self) -> str | None:
        return f"; gclint: dialect={self.target.name} (written by gclint translate from {self.source.name})"

    def read_job(self, source) -> None:
        # several materials through one nozzle and heater (an MMU, an AMS): every source tool is the one head
        self.single_nozzle = read_settings(source.head_text(), source.tail_text()).single_nozzle

    def start(self, result: TranslationResult) -> Iterator[str]:
        self.result = result
        return iter(())

    def _checked(self, line: Line, out: list[str]) -> list[str]:
        for piece in out:
            # (a piece may hold several lines: a changed line's commands, one a line)
            if len(piece) > LINE_LIMIT and any(len(text.rstrip("\r\n")) > LINE_LIMIT for text in _lines(piece)):
                return self._fit(line, out)
        return out

    def _fit(self, line: Line, out: tuple | list) -> list[str]:
        """Output lines over Hyrel's 100 characters ("all lines will be truncated at 100 characters", Gcode
        page, M0): a comment goes onto lines of its own, wrapped; an M0/M792 message is cut; a command
        that is still too long is reported."""
        pieces = [out[0] + out[1]] if type(out) is tuple else list(out)
        pieces = [text for piece in pieces for text in _lines(piece)]
        fitted: list[str] = []
        self.line, self.edit = line, None
        for piece in pieces:
            text = piece.rstrip("\r\n")
            ending = piece[len(text) :] or self.default_ending
            if len(text) <= LINE_LIMIT:
                fitted.append(piece)
                continue
            lines, what = fit_line(text)
            if what == "wrapped":
                self.report(TR_NOTE, "comment longer than Hyrel's 100-character lines: wrapped", key="wrap")
            elif what == "cut":
                self.report(
                    TR_APPROX,
                    "M0/M792 text longer than Hyrel's 100-character lines: cut at 100 (Repetrel truncates it)",
                    key="cut",
                    aspects=(),
                )
            else:
                self.report(
                    TR_APPROX,
                    "a command longer than Hyrel's 100-character lines: Repetrel truncates it",
                    key="too-long",
                )
            fitted.extend(text + (ending if i == len(lines) - 1 else ending) for i, text in enumerate(lines))
            if not piece.endswith(("\n", "\r")):
                fitted[-1] = fitted[-1].rstrip("\r\n")
        self.edit = None
        return fitted

    def translate_line(self, line: Line, result: TranslationResult) -> Iterable[str]:
        """The output of one source line (text and line endings).  Every return point keeps the lines
        within Hyrel's 100 characters (``_fit``)."""
        ending = line.ending
        self._last_ending = ending
        if not self._ending_known and ending:
            self.default_ending = ending
            self._ending_known = True
        parsed = line.parsed
        blanks = None
        if parsed.extra and self.source.semantics.blanks_ignored:
            read = self.source.semantics.parse(line.raw)
            if read is not parsed:
                # the source machine ignores blanks (LinuxCNC: X 2 0 is X20): the line as it reads it, written plainly
                blanks = canonical_text(read)
                line = Line(line.number, blanks, ending, parse_line(blanks))
                parsed = line.parsed
        commands = parsed.commands
        if not commands:
            if parsed.kind == "error" and len(line.raw) > PARSE_LIMIT:
                code = code_before_long_comment(line.raw)
                if code is not None and parse_line(code).kind != "error":
                    # keep the command, drop only the comment that made the line too long to parse
                    short = Line(line.number, code, ending, parse_line(code))
                    self.line, self.edit, self.result = short, None, result
                    self.report(
                        TR_NOTE,
                        f"a comment of {len(line.raw) - len(code):,} characters dropped (lines over "
                        f"{PARSE_LIMIT:,} characters are not parsed); the command is kept",
                        key="huge-comment",
                    )
                    return self.translate_line(short, result)
            if parsed.kind == "error" and self.TEXT_PAUSE is not None:
                kept = _pause_without_text(self.TEXT_PAUSE, line.raw)
                if kept is not None:
                    # the pause kept, its message (text the grammar cannot read) dropped
                    pause = Line(line.number, kept, ending, parse_line(kept))
                    if pause.parsed.kind != "error":
                        self.line, self.edit, self.result = pause, None, result
                        self.report(
                            TR_NOTE,
                            "pause message dropped (it is not a comment on Hyrel, where the text after M0 is a "
                            "list of Repetrel actions)",
                            key="M0-message",
                        )
                        return self.translate_line(pause, result)
            if parsed.kind == "error":
                self.line, self.result = line, result
                dropped = self.edit = LineEdit(line)
                dropped.dropped = dropped.changed = True
                self.report(TR_UNTRANSLATABLE, "the line could not be parsed; dropped", key="unparsed")
                return self._checked(line, dropped.render(self.annotate, self.default_ending))
            if not self.evalues and parsed.comments:
                self.layer_hint(line.raw)
            if len(line.raw) > LINE_LIMIT:
                return self._fit(line, (line.raw, ending))
            return (line.raw, ending)
        self.line = line
        self.edit = None
        self.result = result
        if blanks is not None:
            self.report(
                TR_NOTE,
                "blanks inside a number: the source machine ignores blanks anywhere on a line (LinuxCNC: 'X 2 0' is "
                f"X20); written as {blanks}",
                key="blanks",
            )
            self._edit().changed = True
        if self.hy.ended:
            self._after_end(commands)
        elif len(commands) == 1 and not self.CHECK_EXPRESSIONS:
            # the common case: one command, no expressions possible (Marlin)
            cmd = commands[0]
            self.index = 0
            handler = self.handlers.get(cmd.code)
            if handler is None:
                self.fallback(cmd)
            else:
                handler(self, cmd)
            self.interp.apply(cmd, line)
        else:
            handlers = self.handlers
            apply = self.interp.apply
            check = self.CHECK_EXPRESSIONS
            feed_words = self.FEED_ON_ANY_COMMAND
            # the commands the source machine runs, in the order it runs them (gclint.dialects.semantics)
            facts = self.source.semantics
            running = facts.running(commands)
            index_of = {id(cmd): i for i, cmd in enumerate(commands)}
            for cmd in facts.ignored(commands):
                self.index = index_of[id(cmd)]
                self.remove(
                    cmd,
                    TR_LOST,
                    f"{self.source.title.split(' (')[0]} runs only the first command of a line: "
                    f"{cmd.code or 'this'} never runs there; dropped",
                    key="not-run",
                )
            order = tuple(index_of[id(cmd)] for cmd in running)
            if order != tuple(range(len(order))):
                self._edit().order = order
            feeds = [cmd.params["F"] for cmd in commands if "F" in cmd.params] if "F" in facts.words_first else []
            if feeds:
                self.line_feed_inch = self.inch
            if "S" in facts.words_first and hasattr(self, "rpm"):
                # LinuxCNC sets the spindle speed of any S word on the line before the line's commands run
                # ("G-code Order of Execution": "Set spindle speed (S)" comes before "Spindle on or off")
                speeds = [cmd.params["S"] for cmd in commands if "S" in cmd.params]
                if speeds and num(speeds[-1]) is not None:
                    self.rpm = num(speeds[-1])
            for cmd in running:
                i = index_of[id(cmd)]
                self.index = i
                if self.hy.ended:
                    self.remove(cmd, TR_AFTER_END, "after the end of the program; dropped", key="after-end")
                    continue
                if feed_words and cmd.kind == GCODE and cmd.code not in _MOVES:
                    params = cmd.params
                    if "@" in params or "^" in params:  # LinuxCNC polar words (@ radius, ^ angle): a modal move
                        self.report(
                            TR_UNTRANSLATABLE,
                            "polar coordinates (@ radius, ^ angle) cannot be translated; the move is dropped",
                            key="polar",
                            cmd=cmd,
                        )
                        self.replace(cmd, rewrite(cmd, drop="@^"))
                    if "F" in params:
                        self.modal_feed(cmd)  # (then the command's own handler)
                if check and (cmd.kind == GCODE or cmd.kind == IMPLICIT) and has_expression(cmd):
                    self.untranslatable(
                        cmd,
                        "a parameter is an expression or variable the translator cannot evaluate",
                        key="expression",
                        aspects=("*", "offsets") if cmd.code in LASTING_OFFSETS else None,
                    )
                else:
                    handler = handlers.get(cmd.code)
                    if handler is None:
                        self.fallback(cmd)
                    else:
                        handler(self, cmd)
                apply(cmd, line)
            if feeds:
                # LinuxCNC keeps the feed's speed across the line's change of units (convert_length_units:
                # "settings->feed_rate = GET_EXTERNAL_FEED_RATE()"): the F read in the old units, in the new ones
                f = num(feeds[-1])
                if f is not None and self.line_feed_inch != self.inch:
                    self.state.feed = f / INCH if self.inch else f * INCH
                self.line_feed_inch = None
        edit = self.edit
        if edit is None and len(commands) > 1 and not self.hy.ended:
            edit = self._edit()  # several commands: one a line, as the Hyrel pages show (output.LineEdit)
            edit.changed = True
        if edit is None:
            self.hy.wrote_command = True
            if len(line.raw) > LINE_LIMIT:
                return self._fit(line, (line.raw, ending))
            return (line.raw, ending)
        if edit.changed:
            result.lines_changed += 1
        if not self.hy.wrote_command and (
            edit.before or edit.after or any(edit.replaced.get(i, True) for i in range(len(commands)))
        ):
            self.hy.wrote_command = True
        return self._checked(line, edit.render(self.annotate, self.default_ending))

    def finish(self, result: TranslationResult) -> Iterator[str]:
        footer = not self.hy.ended and self.hy.wrote_command
        if footer and (self.hy.emitters_on or self.hy.spindles_on or self.hy.air_on):
            # the file ends with no end of program and something still on: the footer (X6) switches it off
            self.line, self.edit, self.result = Line(result.lines_in, "", "", parse_line("")), None, result
            self.report(
                TR_APPROX,
                "the job ends with a laser, spindle or air still on; the footer switches it off (M30 last)",
                key="footer-off",
                aspects="end",
            )
            self.edit = None
        for finding, count in self._aggregate.values():
            if count > 1:
                finding.message += f" ({count} lines like this; the first is shown)"
        if not footer:
            return iter(())
        lines = self.footer()
        if self.annotate:
            lines = [f"{text} ; gclint: added (end of job)" for text in lines]
        glue = self.default_ending
        out = "" if self._last_ending else glue
        out += glue.join(lines) + (glue if self._last_ending else "")
        return iter((out,))

    def _after_end(self, commands: tuple[Command, ...]) -> None:
        for i, cmd in enumerate(commands):
            self.index = i
            self.remove(cmd, TR_AFTER_END, "after the end of the program; dropped", key="after-end")

    def plain_route(self) -> PlainMove | None:
        # Plain moves that ``move`` would keep unchanged skip the tree (translate_source): only where G0/G1
        # go to this class's ``move`` with E as the extrusion word and no extra letters among X Y Z E F,
        # and the source interpreter applies them with its motion handler.
        if (
            self.EXTRUDER != "E"
            or not self.EXTRA_LETTERS.isdisjoint("XYZEF")
            or (type(self).move is not HyrelTranslator.move and not self.MOVE_OVERRIDE_IGNORES_PLAIN)
            or type(self).translate_line is not HyrelTranslator.translate_line
        ):
            return None
        for code in ("G0", "G1"):
            if self.handlers.get(code) is not type(self).move or not self.interp.moves_plainly(code):
                return None
        return self.plain_move

    def fallback(self, cmd: Command) -> None:
        code = cmd.code
        kind = cmd.kind
        if kind == IMPLICIT:
            self.implicit_move(cmd)
            return
        if code is not None and code in self.DROPPED:
            tr, reason = self.DROPPED[code]
            self.remove(cmd, tr, reason, key=code, aspects=dropped_aspects(code, tr))
            return
        if kind == GCODE and code and code[0] == "T":
            self.tool_command(cmd)
        elif kind == META:
            self.untranslatable(
                cmd, f"meta command '{code}' (program flow or variables) cannot be translated", key="meta"
            )
        elif kind in (OWORD, ASSIGNMENT):
            self.untranslatable(
                cmd, "O-words and # parameters (program flow, variables) cannot be translated", key="oword"
            )
        elif kind == EXTENDED:
            self.extended(cmd)
        elif kind == HOST:
            self.host_command(cmd)
        elif code in self.END_CODES:
            self.end_program(cmd)
        else:
            what = "G-code" if code and code[0] == "G" else "code"
            self.remove(cmd, TR_LOST, f"this {what} has no Hyrel counterpart; dropped", key=code)

    def extended(self, cmd: Command) -> None:
        self.untranslatable(cmd, "a host macro or extended command cannot be translated", key=cmd.code)

    def host_command(self, cmd: Command) -> None:
        """An OctoPrint @ command: OctoPrint runs it and never sends it to the printer (rules.dialect.HOST_ACTIONS
        says what its own do); Repetrel is the Hyrel job's host.  ``@pause`` is written as Hyrel's pause."""
        from gclint.rules.dialect import HOST_ACTIONS

        code = cmd.code or "@"
        action = HOST_ACTIONS.get(code)
        if code == "@pause":
            self.pause_command(cmd, "M0 ; gclint: pause (@pause)")
            self.report(
                TR_APPROX,
                f"OctoPrint's @pause {action[0] if action else ''}: written as Hyrel's pause M0",
                key="@pause",
                cmd=cmd,
                aspects="pause",
            )
        elif action is not None:
            self.remove(
                cmd, TR_LOST, f"OctoPrint {action[0]}; Repetrel has no counterpart: dropped", key=code, aspects=()
            )
        else:
            self.remove(
                cmd, TR_DROPPED, "an OctoPrint plugin's @ command (the host's, never the printer's): dropped", key=code
            )


_LINE = re.compile(r"[^\r\n]*(?:\r\n|\r|\n)|[^\r\n]+")  # (only the line breaks gclint reads: syntax/source.py)


def _lines(piece: str) -> list[str]:
    """The lines of a piece of output, each with its line ending."""
    return _LINE.findall(piece)


def _pause_without_text(pattern: re.Pattern[str], raw: str) -> str | None:
    """The line ``raw`` as a pause with its message text left out (its S/P timeout and its ``;`` comment
    kept), or None when ``raw`` is no pause with a message."""
    m = pattern.match(raw)
    if m is None:
        return None
    rest = raw[m.end() :]
    cut = rest.find(";")
    comment = rest[cut:] if cut >= 0 else ""
    return m.group(0).rstrip() + (" " + comment if comment else "")
