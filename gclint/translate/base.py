"""The machinery every translation into Hyrel v5 shares.

A pair translator (marlin.py, machinekit.py, carvera.py) is a subclass of ``HyrelTranslator`` with three
tables:

* ``HANDLERS``: source code -> method name.  A handler looks at one command (the source machine state is
  the state *before* the command) and says what Hyrel gets: nothing (the line stays byte for byte),
  ``replace``, ``remove``, lines ``before``/``after``.
* ``DROPPED``: source code -> (TR code, reason) for codes with no Hyrel counterpart.
* ``END_CODES``: codes that end the program in the source (the footer goes there).

Anything else is dropped with a finding: output is allow-listed (research/dialects.md 2.0 X1), an unknown
code is never passed through.  The source machine state comes from ``gclint.machine.Interpreter`` for the
source dialect (X3); the Hyrel side (what the printer will believe: flow mode, fan range, G1 feed, focused
head, spindles and emitters on) is tracked here.

Header and footer work happens where it is needed, never by looking ahead (the file streams):
``G21``/``G90`` and a ``T`` before the first move (the ``T`` again after every G28, which applies a head
offset of 0), ``M229 E1 D1`` before the first extrusion (flow mode evalues), ``M106 C255`` before the first
fan command, and at the end (or the source's end of program) emitters off, spindles off, air off and ``M30``
last (X5, X6).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import ClassVar

from gclint.dialects.base import Dialect
from gclint.machine.interpreter import Interpreter
from gclint.rules.base import Finding
from gclint.rules.translation import TR_NAME, TR_SEVERITY
from gclint.syntax.nodes import ASSIGNMENT, EXTENDED, GCODE, IMPLICIT, META, OWORD, TEXT, Command, Line, to_number
from gclint.translate import arcs
from gclint.translate.engine import PlainMove, TranslationResult, Translator
from gclint.translate.options import TranslateOptions
from gclint.translate.output import LineEdit, fmt, rewrite

TR_DROPPED = "TR001"
TR_LOST = "TR002"
TR_APPROX = "TR003"
TR_NOTE = "TR004"
TR_UNTRANSLATABLE = "TR005"
TR_ADDRESS = "TR006"
TR_NO_TOOL = "TR007"
TR_AFTER_END = "TR008"

INCH = 25.4
_SCALED = "XYZIJKRE"  # letters converted from inches (F too, handled apart)


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
    """True when a parameter is an expression or a parameter reference ({...}, [...], #...)."""
    return any(value and value[0] in "{[#" for value in cmd.params.values())


WORKSPACES = {f"G{n}": "workspace" for n in range(54, 60)}  # G54-G59: the same codes on Hyrel


class HyrelTranslator(Translator):
    """Translate one source dialect into Hyrel v5 (hyrel-v4 output renumbers this translator's lines)."""

    HANDLERS: ClassVar[dict[str, str]] = {}
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

    def __init__(self, source: Dialect, target: Dialect, options: TranslateOptions | None = None) -> None:
        super().__init__(source, target, options)
        self.opts = options if options is not None else TranslateOptions()
        self.interp = Interpreter(source)
        self.state = self.interp.state
        self.evalues = self.opts.flow == "evalues"
        self.inch = False  # the source is in inches (G20): lengths and feeds are converted
        self.extra_always = False  # call move_extra on every move (Carvera laser mode)
        self.annotate = self.opts.annotate
        self.positions = frozenset(self.opts.printer.positions)
        self.handlers: dict[str, Callable[[Command], None]] = {}
        for klass in reversed(type(self).__mro__):
            for code, name in getattr(klass, "HANDLERS", {}).items():
                self.handlers[code] = getattr(self, name)
        # the Hyrel side
        self.hy_feed: float | None = None  # F of the last G1/G2/G3 written (G0 F is one-shot on Hyrel)
        self.m229_written = False
        self.e_mode_written: bool | None = None
        self.fan_range_written = False
        self.focus: int | None = None  # the address of the last T command written
        self.started_motion = False
        self.units_seen = False
        self.positioning_seen = False
        self.ended = False
        self.spindles_on: dict[int, str] = {}  # address -> "M3" or "M4"
        self.rpm: float | None = None  # the source's modal spindle speed (S words)
        self.emitters_on: set[int] = set()
        self.air_on = False
        self.motors_off = False  # an M18/M84 was written: Hyrel must re-home before moving
        self.wrote_command = False
        self.temps: dict[int, tuple[str, str]] = {}  # address -> (wait code, temperature) set without waiting
        # the file
        self.default_ending = "\n"
        self._ending_known = False
        self._last_ending = "\n"
        self._aggregate: dict[tuple, list] = {}
        self._head_cache: dict[int, int | None] = {}
        # the line being translated
        self.line: Line | None = None
        self.edit: LineEdit | None = None
        self.index = 0
        self.result: TranslationResult | None = None

    # -- the loop --------------------------------------------------------------------------------------

    def start(self, result: TranslationResult) -> Iterator[str]:
        self.result = result
        return iter(())

    def translate_line(self, line: Line, result: TranslationResult) -> Iterator[str]:  # type: ignore[override]
        ending = line.ending
        self._last_ending = ending
        if not self._ending_known and ending:
            self.default_ending = ending
            self._ending_known = True
        parsed = line.parsed
        commands = parsed.commands
        if not commands:
            if parsed.kind == "error":
                self.line, self.result = line, result
                dropped = self.edit = LineEdit(line)
                dropped.dropped = dropped.changed = True
                self.report(TR_UNTRANSLATABLE, "the line could not be parsed; dropped", key="unparsed")
                return dropped.render(self.annotate, self.default_ending)  # type: ignore[return-value]
            return (line.raw, ending)  # type: ignore[return-value]
        self.line = line
        self.edit = None
        self.result = result
        if self.ended:
            self._after_end(commands)
        elif len(commands) == 1 and not self.CHECK_EXPRESSIONS:
            # the common case: one command, no expressions possible (Marlin)
            cmd = commands[0]
            self.index = 0
            handler = self.handlers.get(cmd.code)  # type: ignore[arg-type]
            if handler is None:
                self.fallback(cmd)
            else:
                handler(cmd)
            self.interp.apply(cmd, line)
        else:
            handlers = self.handlers
            apply = self.interp.apply
            check = self.CHECK_EXPRESSIONS
            for i, cmd in enumerate(commands):
                self.index = i
                if self.ended:
                    self.remove(cmd, TR_AFTER_END, "after the end of the program; dropped", key="after-end")
                    continue
                if check and (cmd.kind == GCODE or cmd.kind == IMPLICIT) and has_expression(cmd):
                    self.untranslatable(
                        cmd, "a parameter is an expression or variable the translator cannot evaluate", key="expression"
                    )
                else:
                    handler = handlers.get(cmd.code)  # type: ignore[arg-type]
                    if handler is None:
                        self.fallback(cmd)
                    else:
                        handler(cmd)
                apply(cmd, line)
        edit = self.edit
        if edit is None:
            self.wrote_command = True
            return (line.raw, ending)  # type: ignore[return-value]
        if edit.changed:
            result.lines_changed += 1
        if not self.wrote_command and (
            edit.before or edit.after or any(edit.replaced.get(i, True) for i in range(len(commands)))
        ):
            self.wrote_command = True
        return edit.render(self.annotate, self.default_ending)  # type: ignore[return-value]

    def finish(self, result: TranslationResult) -> Iterator[str]:
        for finding, count in self._aggregate.values():
            if count > 1:
                finding.message += f" ({count} lines like this; the first is shown)"
        if self.ended or not self.wrote_command:
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

    # -- editing the current line ------------------------------------------------------------------------

    def _edit(self) -> LineEdit:
        edit = self.edit
        if edit is None:
            edit = self.edit = LineEdit(self.line)  # type: ignore[arg-type]
        return edit

    def replace(self, cmd: Command, text: str, note: str | None = None) -> None:
        """Write ``text`` instead of the command."""
        edit = self._edit()
        edit.replaced[self.index] = text
        edit.changed = True
        if note:
            edit.notes.append(note)

    def remove(self, cmd: Command, code: str, reason: str, *, key: object = None) -> None:
        """Drop the command, with a finding."""
        self.consume(cmd)
        self.report(code, f"{_show(cmd)}: {reason}", key=key if key is not None else (cmd.code, reason), cmd=cmd)

    def consume(self, cmd: Command, note: str | None = None) -> None:
        """Drop the command without a finding: its meaning is carried elsewhere (a tool prepared for M6,
        an S word that sets the next M3's speed) or a finding was already reported."""
        edit = self._edit()
        edit.replaced[self.index] = ""
        edit.changed = True
        if note:
            edit.notes.append(note)

    def untranslatable(self, cmd: Command, reason: str, *, key: object = None) -> None:
        self.remove(cmd, TR_UNTRANSLATABLE, reason, key=key)

    def before(self, *texts: str, note: str | None = None) -> None:
        """Insert lines before the current line."""
        edit = self._edit()
        if self.annotate and note:
            texts = tuple(f"{t} ; gclint: added ({note})" for t in texts)
        edit.before.extend(texts)

    def after(self, *texts: str, note: str | None = None) -> None:
        edit = self._edit()
        if self.annotate and note:
            texts = tuple(f"{t} ; gclint: added ({note})" for t in texts)
        edit.after.extend(texts)

    def report(self, code: str, message: str, *, key: object = None, cmd: Command | None = None) -> None:
        """A TR finding on the current line; repeated findings (same code and key) are counted, not listed."""
        line = self.line
        assert line is not None and self.result is not None
        edit = self._edit()
        edit.notes.append(f"{code} {message}")
        k = (code, key if key is not None else message)
        entry = self._aggregate.get(k)
        if entry is not None:
            entry[1] += 1
            return
        finding = Finding(
            path=self.result.path,
            line=line.number,
            column=cmd.column if cmd is not None else 1,
            code=code,
            severity=TR_SEVERITY[code],
            message=message,
            name=TR_NAME[code],
            source=line.raw,
        )
        self.result.findings.append(finding)
        self._aggregate[k] = [finding, 1]

    # -- dispatch of what has no handler --------------------------------------------------------------------

    def fallback(self, cmd: Command) -> None:
        code = cmd.code
        kind = cmd.kind
        if kind == IMPLICIT:
            self.implicit_move(cmd)
            return
        entry = self.DROPPED.get(code)  # type: ignore[arg-type]
        if entry is not None:
            self.remove(cmd, entry[0], entry[1], key=code)
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
        elif code in self.END_CODES:
            self.end_program(cmd)
        else:
            what = "G-code" if code and code[0] == "G" else "code"
            self.remove(cmd, TR_LOST, f"this {what} has no Hyrel counterpart; dropped", key=code)

    def extended(self, cmd: Command) -> None:
        self.untranslatable(cmd, "a host macro or extended command cannot be translated", key=cmd.code)

    def implicit_move(self, cmd: Command) -> None:
        """Words with no G code: modal motion (Hyrel gets the G code written out), or a lone F (feed) or
        S (spindle speed) word, which LinuxCNC and Carvera keep for the following commands."""
        params = cmd.params
        mode = self.state.motion_mode
        if not any(a in params for a in "XYZAB"):
            if "S" in params:
                self.speed_word(cmd)
            if "F" in params:
                self.replace(cmd, f"G1 F{params['F']}")
                self.hy_feed = fast_float(params["F"])
                return
            if "S" in params:
                self.consume(cmd)
                return
            self.remove(cmd, TR_LOST, "words with no command; dropped", key="implicit")
            return
        if mode is None:
            self.remove(cmd, TR_LOST, "axis words with no modal motion; dropped", key="implicit")
            return
        handler = self.handlers.get(mode)
        if handler is None:
            self.remove(cmd, TR_LOST, "modal motion with no Hyrel counterpart; dropped", key="implicit")
            return
        handler(_with_code(cmd, mode))
        edit = self.edit
        if edit is None or self.index not in edit.replaced:
            self.replace(cmd, rewrite(cmd, code=mode))
            self._edit().changed = True

    # -- addresses -----------------------------------------------------------------------------------------

    def head(self, index: int | None = None, what: str = "tool") -> int | None:
        """The Hyrel address of source tool ``index`` (None: the focused tool), or None (reported) when the
        printer has no such position.  ``what="fan"``: a fan index through the fan map (fan 0 unmapped:
        the focused head's fan)."""
        if what == "fan":
            address = self.opts.fan_map.get(index)  # type: ignore[arg-type]
            if address is None:
                if index == 0 or index is None:
                    return self.head(None)
                self._no_tool(what, index)
                return None
            return self._on_printer(address, what, index)  # type: ignore[arg-type]
        if index is None:
            index = self.current_tool()
        cache = self._head_cache
        if index in cache:
            address = cache[index]
            if address is None:
                self._no_tool(what, index, self.opts.tool(index))
            return address
        address = cache[index] = self._on_printer(self.opts.tool(index), what, index)
        return address

    def _on_printer(self, address: int, what: str, index: int) -> int | None:
        if address in self.positions or 20 <= address <= 25:
            return address
        self._no_tool(what, index, address)
        return None

    def _no_tool(self, what: str, index: int, address: int | None = None) -> None:
        printer = self.opts.printer
        if address is None:
            self.report(
                TR_LOST,
                f"{what} {index} has no Hyrel address; dropped (map it with --set fan-map={index}=T#)",
                key=(what, index),
            )
            return
        else:
            message = (
                f"{what} {index} maps to T{address}, which the {printer.name} does not have "
                f"({printer.describe_positions()}); use --tool-map or --printer"
            )
        self.report(TR_NO_TOOL, message, key=(what, index))

    def current_tool(self) -> int:
        tool = self.state.tool
        return tool if tool is not None and tool >= 0 else 0

    def focus_address(self) -> int | None:
        """The head Hyrel should focus before the first move."""
        return self.head(None)

    # -- header ------------------------------------------------------------------------------------------

    def rehome(self) -> None:
        """A move after M18/M84: "All axes with homes must be rehomed after an M18" (Hyrel Gcode page)."""
        self.motors_off = False
        lines = ["G28 X0 Y0"]
        address = self.focus if self.focus is not None else self.focus_address()
        if address is not None:
            self.focus = address
            lines.append(f"T{address}")  # G28 applies a head offset of 0: focus the head again
        self.before(*lines, note="re-home after M18/M84")
        self.report(
            TR_APPROX,
            "a move after the motors were disengaged: Hyrel must re-home first, G28 X0 Y0 added",
            key="rehome",
        )

    def before_motion(self, focus: bool = True) -> None:
        """Header lines due before the first move: G21, G90 and a T (X5); ``focus=False`` before a G28,
        which applies a head offset of 0 (the T follows it, as in Hyrel's own header)."""
        self.started_motion = True
        lines = []
        if not self.units_seen:
            lines.append("G21")
            self.units_seen = True
        if not self.positioning_seen:
            lines.append("G90" if self.state.absolute else "G91")
            self.positioning_seen = True
        if self.focus is None and focus:
            address = self.focus_address()
            if address is not None:
                lines.append(f"T{address}")
                self.focus = address
        if lines:
            self.before(*lines, note="header: units, positioning and head focus before the first move")

    def refocus(self) -> None:
        """After a G28: "applies a head offset of 0 mm (as in an M6 O0)" (Gcode page, G28), so the focused
        head is selected again for its offsets to apply."""
        address = self.focus if self.focus is not None else self.focus_address()
        if address is not None:
            self.focus = address
            self.after(f"T{address}", note="head focus again after homing (G28 applies a head offset of 0)")

    def before_extrusion(self) -> None:
        """``M229 E1 D1`` (and the E mode) before the first extrusion when E amounts carry the flow (X4)."""
        self.m229_written = True
        lines = ["M229 E1 D1"]
        absolute = self.e_absolute()
        if self.e_mode_written is None or self.e_mode_written != absolute:
            lines.append("M82" if absolute else "M83")
            self.e_mode_written = absolute
        self.before(*lines, note="header: the E values carry the flow")

    def ensure_fan_range(self) -> None:
        if not self.fan_range_written:
            self.fan_range_written = True
            self.before("M106 C255", note="header: fan values 0-255")

    def e_absolute(self) -> bool:
        return self.state.e_absolute

    # -- footer ------------------------------------------------------------------------------------------

    def footer(self) -> list[str]:
        """Emitters off, spindles off, air off, M30 last (X6)."""
        lines = [f"M620 T{a} E0" for a in sorted(self.emitters_on)]
        lines += [f"M5 T{a}" for a in sorted(self.spindles_on)]
        if self.air_on:
            lines.append("M9")
        lines.append("M30")
        return lines

    def end_program(self, cmd: Command) -> None:
        """The source's end of program: the footer, with M30 in place of the command."""
        lines = self.footer()
        *first, last = lines
        if first:
            self.before(*first, note="footer")
        if cmd.code == "M30" and not cmd.params:
            pass  # M30 stays M30, byte for byte
        else:
            self.replace(cmd, last)
        self.ended = True
        self.emitters_on.clear()
        self.spindles_on.clear()
        self.air_on = False

    # -- motion ------------------------------------------------------------------------------------------

    def e_delta(self, cmd: Command) -> float | None:
        """How far the extruder advances on this move, in source units (None: unknown)."""
        value = fast_float(cmd.params.get(self.EXTRUDER))
        if value is None:
            return None
        if not self.state.e_absolute:
            return value
        current = self.state.e_position
        if current is None:
            return value  # unknown position: assume a print move when the value is positive
        return value - current

    def move(self, cmd: Command) -> None:
        """G0/G1 (and implicit motion): E handling (X7), feed (G0 F is one-shot on Hyrel), inches (X10).

        The hot path: a plain G1 that needs no change returns after a few dictionary lookups."""
        if not self.started_motion:
            self.before_motion()
        if self.motors_off:
            self.rehome()
        params = cmd.params
        ext = self.EXTRUDER
        g0 = cmd.code == "G0"
        out_code: str | None = None
        drop = ""
        values: dict[str, str | None] | None = None
        add: tuple[str, ...] = ()
        rename = None
        if ext in params:
            if "X" not in params and "Y" not in params and "Z" not in params:
                self.extruder_only(cmd, self.e_delta(cmd))
                return
            if ext == "E":  # e_delta, inlined for the hot path
                delta = fast_float(params["E"])
                st = self.state
                if delta is not None and st.e_absolute and st.e_position is not None:
                    delta -= st.e_position
            else:
                delta = self.e_delta(cmd)
            if delta is not None and delta > 0:
                if g0:
                    out_code = "G1"  # Marlin/RRF: G0 is G1 and extrudes (dialects.md 1.1 G0)
                    g0 = False
                if self.evalues:
                    if not self.m229_written:
                        self.before_extrusion()
                    if ext != "E" or self.inch:
                        rename = {ext: "E"} if ext != "E" else None
                        values = {"E": self.scaled_e(params[ext])}
                else:
                    rename = {ext: "E"} if ext != "E" else None
                    values = {"E": "1"}
            else:
                drop = ext
                if delta and self.evalues and self.e_absolute():
                    self.after(f"G92 E{self.scaled_e(params[ext])}", note="keeps Hyrel's E position")
        elif "E" in params:
            drop = "E"
        if self.inch:
            values = dict(values or {})
            for letter in _SCALED:
                if letter in params and letter not in drop and letter not in values and letter != ext:
                    v = fast_float(params[letter])
                    if v is not None:
                        values[letter] = fmt(v * INCH)
            f = fast_float(params.get("F"))
            if f is not None:
                values["F"] = fmt(f * INCH, 2)
        if "F" in params:
            if not g0:  # a G0 F is one-shot on Hyrel; where it is modal in the source, source_feed() differs next
                f = fast_float(params["F"])
                self.hy_feed = f * INCH if f is not None and self.inch else f
        elif not g0:
            feed = self.state.feed
            if feed is not None:
                if self.inch:
                    feed *= INCH
                if feed != self.hy_feed:
                    add = (*add, "F" + fmt(feed, 2))
                    self.hy_feed = feed
        if self.extra_always or not self.EXTRA_LETTERS.isdisjoint(params):
            extra = self.move_extra(cmd, g0)
            if extra is not None:
                drop += extra[0]
                add = (*add, *extra[1])
        if out_code is None and not drop and not values and not add:
            return
        if drop and not add and all(letter in drop for letter in params):
            self.consume(cmd)  # nothing left to move (the words were dropped, with their findings)
            return
        self.replace(cmd, rewrite(cmd, code=out_code, drop=drop, values=values, add=add, rename=rename))

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
            apply = self.interp.handler_for(Command(code, GCODE, 1, {}))
            if self.handlers.get(code) != self.move or getattr(apply, "func", None) != self.interp._motion:
                return None
        return self.plain_move

    def plain_move(
        self,
        g1: bool,
        number: int,
        x: str | None,
        y: str | None,
        z: str | None,
        e: str | None,
        f: str | None,
        ending: str,
    ) -> bool:
        """``translate_line`` for a plain move when ``move`` would leave it unchanged (True), else False
        with nothing done.  The unchanged case of ``move``: motion started, no re-homing due, no inch
        conversion or extra words, an extruding G1 with E values on (M229 written), and a feed that
        Hyrel already has.  tests/test_translate_plain.py checks that the output is the same without."""
        if self.ended or not self.started_motion or self.motors_off or self.inch or self.extra_always:
            return False
        st = self.state
        if e is not None:
            if not g1 or (x is None and y is None and z is None) or not self.evalues or not self.m229_written:
                return False
            delta = float(e)
            if st.e_absolute and st.e_position is not None:
                delta -= st.e_position
            if not delta > 0:
                return False
        if g1:
            if f is not None:
                self.hy_feed = float(f)
            elif st.feed is not None and st.feed != self.hy_feed:
                return False
        self._last_ending = ending
        if not self._ending_known and ending:
            self.default_ending = ending
            self._ending_known = True
        self.wrote_command = True
        self.interp.plain_move("G1" if g1 else "G0", number, x, y, z, e, f)
        return True

    def move_extra(self, cmd: Command, rapid: bool) -> tuple[str, tuple[str, ...]] | None:
        """Dialect hook: (letters to drop, words to add) for a move; None for no change."""
        return None

    def source_feed(self) -> float | None:
        feed = self.state.feed
        if feed is not None and self.inch:
            return feed * INCH
        return feed

    def scaled_e(self, text: str | None) -> str:
        if self.inch:
            v = num(text)
            if v is not None:
                return fmt(v * INCH, 5)
        return text or "0"

    def extruder_only(self, cmd: Command, delta: float | None) -> None:
        """A move of the extruder alone (retract, unretract, prime): Hyrel's heads unprime and prime by
        themselves on print <-> travel transitions (M721/M722), so it is dropped, written as
        M721/M722 I1 (retract=explicit), or, when E values are absolute, kept as G92 E so Hyrel's E
        position stays the source's."""
        params = cmd.params
        if self.opts.retract == "explicit" and delta is not None and delta != 0:
            address = self.head(None)
            text = f"M721 T{address} I1" if delta < 0 else f"M722 T{address} I1"
            if address is None:
                self.remove(cmd, TR_NOTE, "retraction dropped", key="retract")
                return
            if self.evalues and self.e_absolute():
                self.after(f"G92 E{self.scaled_e(params[self.EXTRUDER])}", note="keeps Hyrel's E position")
            self.replace(cmd, text, note="TR004 explicit unprime/prime")
            return
        if self.evalues and self.e_absolute():
            self.replace(cmd, f"G92 E{self.scaled_e(params[self.EXTRUDER])}")
            self.report(
                TR_NOTE,
                "extruder-only move (retract/prime) left to the head's automatic unprime/prime; "
                "written as G92 E so Hyrel's E position stays the source's",
                key="e-only",
                cmd=cmd,
            )
            return
        self.remove(
            cmd,
            TR_NOTE,
            "extruder-only move (retract/prime) left to the head's automatic unprime/prime (M721/M722); dropped",
            key="e-only",
        )

    def arc(self, cmd: Command) -> None:
        """G2/G3: R-form -> I/J, other planes, extra turns and E amounts that matter -> G1 segments (X9)."""
        if not self.started_motion:
            self.before_motion()
        if self.motors_off:
            self.rehome()
        params = cmd.params
        st = self.state
        plane = st.plane if st.plane in arcs.PLANES else 17
        ext = self.EXTRUDER
        delta = self.e_delta(cmd) if ext in params else None
        extruding = delta is not None and delta > 0
        turns = num(params.get("P")) if "P" in params else None
        if plane != 17 or (turns is not None and turns >= 1) or (extruding and self.evalues) or self.inch:
            self.linearize(cmd, plane, delta, int(turns or 0))
            return
        drop = ""
        add: tuple[str, ...] = ()
        values: dict[str, str | None] = {}
        if "R" in params:
            centre = self._centre(cmd)
            if centre is None:
                return
            drop += "R"
            values["I"], values["J"] = fmt(centre[0]), fmt(centre[1])
            self.report(
                TR_NOTE, "R-form arc written with its centre I/J (Hyrel's G2/G3 take no R)", key="arc-R", cmd=cmd
            )
        if "K" in params:
            drop += "K"
        if "P" in params:
            drop += "P"
        if ext in params:
            if extruding:
                if ext != "E":
                    drop += ext
                    add = ("E1",)
                else:
                    values["E"] = "1"
            else:
                drop += ext
                if self.evalues and self.e_absolute() and delta:
                    self.after(f"G92 E{self.scaled_e(params[ext])}", note="keeps Hyrel's E position")
        if "F" in params:
            self.hy_feed = num(params["F"])
        else:
            feed = self.source_feed()
            if feed is not None and feed != self.hy_feed:
                add = (*add, "F" + fmt(feed, 2))
                self.hy_feed = feed
        extra = self.move_extra(cmd, False)
        if extra is not None:
            drop += extra[0]
            add = (*add, *extra[1])
        if drop or add or values:
            self.replace(cmd, rewrite(cmd, drop=drop, values=values, add=add))

    def _centre(self, cmd: Command) -> tuple[float, float] | None:
        """The I/J of an R-form XY arc (None, reported, when it cannot be computed)."""
        st = self.state
        params = cmd.params
        x0, y0 = st.position.get("X"), st.position.get("Y")
        radius = num(params.get("R"))
        if x0 is None or y0 is None or radius is None:
            self.untranslatable(
                cmd, "R-form arc from an unknown position: its centre cannot be computed", key="arc-unknown"
            )
            return None
        x1, y1 = num(params.get("X")), num(params.get("Y"))
        if st.absolute:
            dx = (x1 if x1 is not None else x0) - x0
            dy = (y1 if y1 is not None else y0) - y0
        else:
            dx, dy = x1 or 0.0, y1 or 0.0
        try:
            return arcs.centre_from_radius(dx, dy, radius, cmd.code == "G2")
        except arcs.ArcError as exc:
            self.untranslatable(cmd, f"arc cannot be drawn: {exc}", key="arc-error")
            return None

    def linearize(self, cmd: Command, plane: int, delta: float | None, turns: int) -> None:
        st = self.state
        params = cmd.params
        a, b, oa, ob, helix = arcs.PLANES[plane]
        start = {axis: st.position.get(axis) for axis in (a, b, helix)}
        if any(v is None for v in start.values()):
            if "R" in params:
                self.untranslatable(
                    cmd, "R-form arc from an unknown position: its centre cannot be computed", key="arc-unknown"
                )
            else:
                self.remove(
                    cmd,
                    TR_UNTRANSLATABLE,
                    "arc from an unknown position cannot be written as segments",
                    key="arc-unknown",
                )
            return
        end: dict[str, float] = {}
        for axis in (a, b, helix):
            v = num(params.get(axis))
            if v is None:
                end[axis] = start[axis]  # type: ignore[assignment]
            elif st.absolute:
                end[axis] = v
            else:
                end[axis] = start[axis] + v  # type: ignore[operator]
        clockwise = cmd.code == "G2"
        try:
            if "R" in params:
                radius = num(params["R"])
                if radius is None:
                    raise arcs.ArcError("R is not a number")
                offsets = arcs.centre_from_radius(end[a] - start[a], end[b] - start[b], radius, clockwise)  # type: ignore[operator]
            else:
                offsets = (num(params.get(oa)) or 0.0, num(params.get(ob)) or 0.0)
            points = arcs.segments(start, end, offsets, clockwise, plane, turns)  # type: ignore[arg-type]
        except arcs.ArcError as exc:
            self.untranslatable(cmd, f"arc cannot be drawn: {exc}", key="arc-error")
            return
        scale = INCH if self.inch else 1.0
        ext = self.EXTRUDER
        extruding = delta is not None and delta > 0
        if extruding and self.evalues and not self.m229_written:
            self.before_extrusion()
        e_words: list[str | None] = [None] * len(points)
        if ext in params:
            if extruding and self.evalues:
                n = len(points)
                if self.e_absolute():
                    e0 = (st.e_position if ext == "E" else st.position.get("A")) or 0.0
                    for k in range(1, n):
                        e_words[k - 1] = "E" + fmt((e0 + delta * k / n) * scale, 5)  # type: ignore[operator]
                    e_words[-1] = "E" + self.scaled_e(params[ext])
                else:
                    done = 0.0
                    for k in range(1, n + 1):
                        total = round(delta * k / n * scale, 5)  # type: ignore[operator]
                        e_words[k - 1] = "E" + fmt(total - done, 5)
                        done = total
            elif extruding:
                e_words = ["E1"] * len(points)
            elif self.evalues and self.e_absolute() and delta:
                self.after(f"G92 E{self.scaled_e(params[ext])}", note="keeps Hyrel's E position")
        feed_word = None
        if "F" in params:
            f = num(params["F"])
            if f is not None:
                feed_word = "F" + fmt(f * scale, 2)
                self.hy_feed = f * scale
        else:
            feed = self.source_feed()
            if feed is not None and feed != self.hy_feed:
                feed_word = "F" + fmt(feed, 2)
                self.hy_feed = feed
        extra = self.move_extra(cmd, False)
        extra_words = extra[1] if extra is not None else ()
        if "E1" in extra_words:  # a firing laser move: every segment fires
            extra_words = tuple(w for w in extra_words if w != "E1")
            e_words = ["E1"] * len(points)
        texts = []
        previous = {axis: start[axis] * scale for axis in (a, b, helix)}  # type: ignore[operator]
        for k, point in enumerate(points):
            words = ["G1"]
            for axis in ("X", "Y", "Z"):
                if axis not in point:
                    continue
                value = point[axis] * scale
                if st.absolute:
                    if axis == helix and axis not in params:
                        continue
                    words.append(axis + fmt(value, 4))
                else:
                    rounded = round(value, 4)
                    step = rounded - round(previous[axis], 4)
                    previous[axis] = rounded
                    if axis == helix and axis not in params:
                        continue
                    words.append(axis + fmt(step, 4))
            if e_words[k]:
                words.append(e_words[k])  # type: ignore[arg-type]
            if k == 0:
                if feed_word:
                    words.append(feed_word)
                words.extend(extra_words)
            texts.append(" ".join(words))
        reason = "R-form arc" if "R" in params else (f"arc in the G{plane} plane" if plane != 17 else "arc")
        self.replace(cmd, texts[0], note=f"{reason} written as {len(texts)} G1 segments")
        if len(texts) > 1:
            self._edit().after[:0] = texts[1:]
        if plane != 17 or "R" in params or turns:
            self.report(
                TR_NOTE,
                f"{reason} written as G1 segments (Hyrel G2/G3 draw XY arcs with I/J only)",
                key=("arc", plane, "R" in params),
                cmd=cmd,
            )
        elif extruding and self.evalues:
            self.report(
                TR_NOTE,
                "extruding arc written as G1 segments so its E amount counts "
                "(Hyrel computes arc flow natively even under M229 E1)",
                key="arc-evalues",
                cmd=cmd,
            )

    # -- common commands -----------------------------------------------------------------------------------

    def keep(self, cmd: Command) -> None:
        """Same code, same meaning."""

    def units(self, cmd: Command) -> None:
        self.units_seen = True
        self.inch = cmd.code == "G20"
        if cmd.code == "G20":
            self.replace(cmd, "G21")
            self.report(
                TR_NOTE,
                "inches: Hyrel's G20 is unsupported; written as G21 and every length converted to mm",
                key="G20",
                cmd=cmd,
            )

    # The note written with M82/M83 when the source's G90/G91 also switch the E mode (Marlin: G90/G91
    # set E absolute/relative; Machinekit: the extruder axis A follows them; Hyrel's do not, dialects.md
    # 1.4 M82/M83 and 2.1 G90 row); None where the E mode is independent (RepRapFirmware, Carvera).
    E_MODE_FOLLOWS_POSITIONING: str | None = None

    def workspace(self, cmd: Command) -> None:
        """G54-G59 select a workspace elsewhere; on Hyrel they (re)apply the stored fixture offsets, and
        with values they would store new ones (Gcode page, G54 - G59), so values are dropped."""
        if cmd.params:
            self.replace(cmd, cmd.code or "G54")
        self.report(
            TR_NOTE,
            f"{cmd.code} selects Hyrel's stored fixture offsets (Repetrel Settings > Fixture "
            "Offsets); G54 with values would store new ones",
            key="wcs",
            cmd=cmd,
        )

    def clear_g92(self, cmd: Command) -> None:
        """G92.1 (clear the G92 offsets) is Hyrel's G93 ("G93 clears ALL offsets implemented via G92")."""
        self.replace(cmd, "G93")
        self.report(TR_NOTE, "G92.1 (clear G92 offsets) written as Hyrel's G93", key="G92.1", cmd=cmd)

    def firmware_retract(self, cmd: Command, code: str, what: str, key: str) -> None:
        """A source retract/unretract: left to the head's automatic unprime/prime, or with
        ``retract=explicit`` written as ``M721/M722 T# I1`` (Gcode page, M721/M722: "I1 ... now")."""
        if self.opts.retract == "explicit":
            address = self.head(None)
            if address is not None:
                self.replace(cmd, f"{code} T{address} I1", note=f"TR004 {what} -> {code} I1")
                return
        self.remove(
            cmd,
            TR_NOTE,
            f"{what} left to the head's automatic unprime/prime (set retract=explicit for M721/M722 I1)",
            key=key,
        )

    def positioning(self, cmd: Command) -> None:
        """G90/G91: same meaning for X Y Z; the E mode follows where the source couples them."""
        self.positioning_seen = True
        absolute = cmd.code == "G90"
        note = self.E_MODE_FOLLOWS_POSITIONING
        if note is None or not self.evalues or not self.m229_written or self.e_mode_written == absolute:
            return
        self.after("M82" if absolute else "M83", note=note)
        self.e_mode_written = absolute

    def set_position(self, cmd: Command) -> None:
        """G92: same meaning (X Y Z A B E); Machinekit's extruder A becomes E; inches converted."""
        params = cmd.params
        if not params:
            self.remove(cmd, TR_NOTE, "G92 without axes changes nothing here; dropped", key="G92-bare")
            return
        values: dict[str, str] = {}
        drop = ""
        ext = self.EXTRUDER
        add: tuple[str, ...] = ()
        if ext != "E" and ext in params:
            drop += ext
            add = ("E" + (params[ext] or "0"),)
        if self.inch:
            for letter in "XYZE":
                if letter in params and letter not in drop:
                    v = num(params[letter])
                    if v is not None:
                        values[letter] = fmt(v * INCH)
        for letter in params:
            if letter not in "XYZABE" and letter != ext:
                drop += letter
        if drop or values or add:
            self.replace(cmd, rewrite(cmd, drop=drop, values=values, add=add))

    def dwell_seconds(self, cmd: Command) -> None:
        """G4 P<seconds> (LinuxCNC, Carvera grbl mode) -> G4 S<seconds> (Hyrel P is milliseconds)."""
        params = cmd.params
        if "P" in params:
            self.replace(cmd, rewrite(cmd, drop="P", first=("S" + (params["P"] or "0"),)))
            self.report(
                TR_NOTE, "G4 P is seconds in the source, milliseconds on Hyrel: written as G4 S", key="G4", cmd=cmd
            )

    def speed_word(self, cmd: Command) -> None:
        """An S word outside M3/M4: the spindle speed (rpm) for the next M3, or a speed change now."""
        s = fast_float(cmd.params.get("S"))
        if s is None:
            return
        self.rpm = s
        address = self.opts.spindle_address()
        running = self.spindles_on.get(address)
        if running is not None:
            self.before(f"{running} T{address} S{self.rpm_percent(s, self.MAX_RPM)}", note="spindle speed")

    def spindle_on(self, cmd: Command, percent: str | None) -> None:
        address = self.opts.spindle_address()
        code = cmd.code or "M3"
        words = [code, f"T{address}"]
        if percent is not None:
            words.append("S" + percent)
        running = self.spindles_on.get(address)
        if running is not None and running != code:
            # "DO NOT CHANGE DIRECTION while the spindle is in motion" (Hyrel Gcode page, M3)
            self.before(f"M5 T{address}", note="stop before changing direction")
            self.report(
                TR_APPROX,
                "spindle direction changed while running: Hyrel needs it stopped first, M5 added",
                key="M3-M4",
                cmd=cmd,
            )
        self.replace(cmd, " ".join(words))
        if percent is not None and float(percent) == 0:  # "S0 is the same as turning it off" (M3)
            self.spindles_on.pop(address, None)
        else:
            self.spindles_on[address] = code

    def spindle_off(self, cmd: Command) -> None:
        address = self.opts.spindle_address()
        self.replace(cmd, f"M5 T{address}")
        self.spindles_on.pop(address, None)

    def rpm_percent(self, rpm: float, assumed_max: float | None = None) -> str:
        """Spindle rpm -> percent of the Hyrel spindle's maximum (configuration spindle-max-rpm)."""
        top = self.opts.spindle_max_rpm
        if top is None:
            top = assumed_max or 15000.0
            self.report(
                TR_APPROX,
                f"spindle rpm converted to percent of an assumed {fmt(top)} rpm maximum; set "
                "spindle-max-rpm to the Hyrel spindle's",
                key="rpm-assumed",
            )
        pct = rpm / top * 100
        if pct > 100:
            self.report(
                TR_APPROX, f"{fmt(rpm)} rpm is above the spindle's {fmt(top)} rpm: clamped to 100 %", key="rpm-clamp"
            )
            pct = 100
        return fmt(max(pct, 0.0), 1)

    def fan(self, cmd: Command, address: int | None, value: float | None) -> None:
        """``M106 T# S<0-255>`` (with ``M106 C255`` once before) or M107."""
        if address is None:
            self.consume(cmd)
            return
        if value is None:
            value = self.FAN_MAX
        s = max(0, min(255, round(value / self.FAN_MAX * 255)))
        self.ensure_fan_range()
        self.replace(cmd, f"M106 T{address} S{s}")

    def fan_off(self, cmd: Command, address: int | None) -> None:
        if address is None:
            self.consume(cmd)
            return
        self.replace(cmd, f"M107 T{address}")

    def temperature(
        self,
        cmd: Command,
        code: str,
        address: int | None,
        temp: str | None,
        window: bool = False,
        extra: tuple[str, ...] = (),
    ) -> None:
        """Write a temperature command with an explicit address; ``window`` adds R<temp-window> (the source
        waits heating *or* cooling; Hyrel's R is a +/- tolerance)."""
        if address is None:
            self.consume(cmd)
            return
        words = [code, f"T{address}"]
        if temp is not None:
            value = num(temp)
            if value is not None and value < -200:
                temp = "0"  # RepRapFirmware's -273.15: heater off
            words.append("S" + temp)
            if code in ("M104", "M140", "M141"):
                wait = {"M104": "M109", "M140": "M190", "M141": "M191"}[code]
                self.temps[address] = (wait, temp)
            else:
                self.temps.pop(address, None)
        if window:
            words.append("R" + fmt(self.opts.temp_window))
        words.extend(extra)
        self.replace(cmd, " ".join(words))

    def select_tool(self, cmd: Command, index: int | None) -> None:
        """A source tool change -> ``T<address>`` (Hyrel: focus the head; its M6 offsets, flow and
        prime/unprime apply)."""
        address = self.head(index)
        if address is None:
            self.consume(cmd)
            return
        self.focus = address
        text = f"T{address}"
        if cmd.code == text and not cmd.params:
            return
        self.replace(cmd, text)

    def tool_command(self, cmd: Command) -> None:
        number = cmd.code[1:] if cmd.code else ""
        if number == "-1":
            self.remove(cmd, TR_LOST, "T-1 (deselect every tool) has no Hyrel counterpart; dropped", key="T-1")
            return
        if not number.isdigit():
            self.untranslatable(cmd, "a tool given by a query or expression cannot be translated", key="T?")
            return
        if len(number) > 2:
            self.untranslatable(
                cmd,
                "a vendor pseudo-tool (filament unload, calibration) cannot be translated",
                key=("T-vendor", number),
            )
            return
        dropped = [letter for letter in cmd.params]
        if dropped:
            self.report(
                TR_NOTE,
                f"T parameters {' '.join(dropped)} (tool-change moves, macros) dropped",
                key="T-params",
                cmd=cmd,
            )
        self.select_tool(cmd, int(number))


def _show(cmd: Command) -> str:
    """A short name for messages: the code, or the kind of construct."""
    if cmd.kind in (GCODE, TEXT):
        return cmd.code or "?"
    if cmd.kind == IMPLICIT:
        return "motion words"
    if cmd.kind == META:
        return f"'{cmd.code}'"
    if cmd.kind in (OWORD, ASSIGNMENT):
        return "O-word" if cmd.kind == OWORD else "# parameter"
    return cmd.code or cmd.kind


def _with_code(cmd: Command, code: str) -> Command:
    """An implicit command seen as the modal code (for the handlers)."""
    return Command(code, GCODE, cmd.column, cmd.params, words=cmd.words)
