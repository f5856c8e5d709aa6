"""``gclint explain``: decode each command in the printer's own terms.

Modelled on the "This command is decoded and executed by the printer as follows" sections of the Hyrel
Gcode page (../shared/seeds/hyrel-gcode-reference.wiki.txt):

    M109 T0 S240 L10 U5
    * M109 (wait for head temperature)
    ** T0 (head T0: yoke 1, position 1)
    ** S240 (and set the temperature to 240°C)
    ** L10 (but end the wait once the temperature reaches 10°C below the set point)
    ** U5 (or end the wait once the temperature reaches 5°C above the set point)
    ** note: the wait ends when the temperature is anywhere between 230°C and 245°C

Every dialect is decoded from its code table (``Code.summary``, parameter meanings); the commands whose
meaning depends on numbers or on the job so far (temperature windows, the M106 C range, T addressing in
v4 and v5, M229, lasers, M660 offsets, clone squads, G28, arcs and spirals) have their own decoders.
A file is explained line by line through the machine ``Interpreter``, so "the head with current focus",
relative moves, the fan range and stored offsets are the ones the job set up.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field

from gclint.dialects.addressing import GROUP, HEAD, VIRTUAL, Address, yoke_label
from gclint.dialects.base import Code, Dialect
from gclint.machine.interpreter import Interpreter
from gclint.machine.state import EVALUES, MachineState
from gclint.syntax.nodes import ASSIGNMENT, EXTENDED, GCODE, IMPLICIT, META, OWORD, PERCENT, TEXT, Command, Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source

DEG = "°C"


@dataclass
class Item:
    """One decoded part of a command: the word as written (empty for notes) and what it does."""

    word: str
    text: str
    warning: bool = False


@dataclass
class Explanation:
    """One command, decoded."""

    line: int
    source: str
    code: str | None
    title: str
    items: list[Item] = field(default_factory=list)

    def add(self, word: str, text: str) -> None:
        self.items.append(Item(word, text))

    def note(self, text: str) -> None:
        self.items.append(Item("", text))

    def warn(self, text: str) -> None:
        self.items.append(Item("", text, warning=True))

    def masked(self) -> Explanation:
        """A copy with every secret of the source line (a password, a key) masked wherever it is quoted."""
        from gclint import secrets

        values = sorted({self.source[s.start : s.end] for s in secrets.find(self.source)}, key=len, reverse=True)
        if not values:
            return self

        def hide(text: str) -> str:
            for value in values:
                text = text.replace(value, secrets.MASK_CHAR * len(value))
            return secrets.mask(text)

        items = [Item(hide(i.word), hide(i.text), warning=i.warning) for i in self.items]
        return Explanation(self.line, hide(self.source), self.code, hide(self.title), items)

    def to_dict(self) -> dict:
        return {
            "line": self.line,
            "source": self.source,
            "code": self.code,
            "title": self.title,
            "items": [{"word": i.word, "text": i.text, "warning": i.warning} for i in self.items],
        }

    def render(self) -> str:
        head = f"* {self.code} ({self.title})" if self.code else f"* ({self.title})"
        lines = [head]
        for item in self.items:
            if item.word:
                lines.append(f"** {item.word} ({item.text})")
            elif item.warning:
                lines.append(f"** warning: {item.text}")
            else:
                lines.append(f"** note: {item.text}")
        return "\n".join(lines)


def _num(text: str | None) -> float | None:
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        return None


def _fmt(value: float) -> str:
    if value != value or value in (float("inf"), float("-inf")):
        return str(value)
    return str(int(value)) if value == int(value) and abs(value) < 1e15 else f"{value:g}"


# Letter meanings used when a code's table says nothing about a letter.
_GENERIC = {
    "X": "X",
    "Y": "Y",
    "Z": "Z",
    "A": "A axis",
    "B": "B axis",
    "C": "C axis",
    "E": "extruder",
    "F": "feed rate, mm/min",
    "S": "S value",
    "P": "P value",
    "T": "tool",
    "I": "I value",
    "J": "J value",
    "K": "K value",
    "R": "R value",
    "H": "H value",
    "D": "D value",
    "L": "L value",
    "Q": "Q value",
}


class Explainer:
    """Explains lines in order, keeping the machine state between them."""

    def __init__(self, dialect: Dialect, state: MachineState | None = None) -> None:
        self.dialect = dialect
        self.family = dialect.family
        self.hyrel = dialect.family == "hyrel"
        self.state = state if state is not None else MachineState()
        self.interpreter = Interpreter(dialect, self.state)
        self.firmware = dialect.extras.get("firmware")
        self._decoders = self._table()

    # -- entry points -------------------------------------------------------------------------------

    def explain_line(self, line: Line) -> list[Explanation]:
        out = []
        self.state.line_number = line.number
        for cmd in line.commands:
            out.append(self.explain_command(cmd, line))
            self.interpreter.apply(cmd, line)
        return out

    def explain_command(self, cmd: Command, line: Line) -> Explanation:
        code = cmd.code
        if cmd.kind == GCODE and code:
            if code[0] == "T" and code[1:].lstrip("-").isdigit():
                return self._tool(cmd, line)
            spec = self.dialect.spec(code)
            decoder = self._decoders.get(code)
            known = self.dialect.knows(code)
            exp = Explanation(line.number, line.raw, code, self._title(code, spec))
            if not known:
                self._unknown(exp, cmd)
                return exp
            if spec is not None and not spec.supported:
                exp.warn(f"{self.dialect.title} does not support {code}")
            if decoder is not None:
                decoder(exp, cmd, spec)
            else:
                self._generic(exp, cmd, spec)
            return exp
        return self._other(cmd, line)

    # -- titles and generic decoding ----------------------------------------------------------------

    def _title(self, code: str, spec: Code | None) -> str:
        if spec is not None and spec.summary:
            return spec.summary
        if spec is not None or self.dialect.knows(code):
            return f"a {self.dialect.name} command"
        return f"not a code of {self.dialect.title}"

    def _meaning(self, spec: Code | None, letter: str) -> str | None:
        return spec.meaning(letter) if spec is not None else None

    def _generic(self, exp: Explanation, cmd: Command, spec: Code | None, skip: Iterable[str] = ()) -> None:
        skip = set(skip)
        for word in cmd.words:
            if word.letter in skip:
                continue
            meaning = self._meaning(spec, word.letter)
            text = word.text.strip()
            if spec is not None and spec.params is not None and spec.param(word.letter) is None:
                exp.items.append(
                    Item(text, f"{cmd.code} takes no {word.letter} in {self.dialect.name}: ignored or rejected", True)
                )
                continue
            param = spec.param(word.letter) if spec is not None else None
            if param is not None and param.forbidden:
                exp.items.append(Item(text, param.meaning, True))
                continue
            value = word.value if word.value is not None else ""
            if meaning is None:
                meaning = _GENERIC.get(word.letter, f"{word.letter} value")
            exp.add(text, f"{meaning}: {value}" if value else f"{meaning} (no value)")
        if spec is not None and spec.params:
            for letter, param in spec.params.items():
                if param.required and letter not in cmd.params:
                    exp.warn(f"{letter} is required ({param.meaning})")

    def _unknown(self, exp: Explanation, cmd: Command) -> None:
        if self.dialect.unknown_severity == "error":
            if self.hyrel:
                exp.warn(
                    f"Repetrel does not list {cmd.code}; Hyrel reuses many numbers for other things, so it is "
                    "rejected or does something else"
                )
            else:
                exp.warn(f"the {self.dialect.name} interpreter stops on an unknown code")
        else:
            exp.warn(
                f"{self.dialect.title} does not list {cmd.code}: the firmware skips it (or runs a macro of that name)"
            )
        for word in cmd.words:
            exp.add(word.text.strip(), _GENERIC.get(word.letter, f"{word.letter} value"))

    def _other(self, cmd: Command, line: Line) -> Explanation:
        kind = cmd.kind
        if kind == IMPLICIT:
            mode = self.state.motion_mode
            if mode is None:
                exp = Explanation(
                    line.number, line.raw, None, "axis words with no motion code: no modal motion is active"
                )
                self._generic(exp, cmd, None)
                return exp
            exp = Explanation(line.number, line.raw, None, f"modal {mode} move: the words repeat the last motion code")
            self._motion(exp, cmd, self.dialect.spec(mode), mode)
            return exp
        if kind == TEXT:
            spec = self.dialect.spec(cmd.code or "")
            exp = Explanation(line.number, line.raw, cmd.code, self._title(cmd.code or "", spec))
            text = cmd.args.text.strip() if cmd.args is not None else ""
            if text:
                exp.add(text, "the text")
            return exp
        if kind == EXTENDED:
            exp = Explanation(line.number, line.raw, cmd.code, "Klipper extended command (or a macro of that name)")
            for key, value in cmd.params.items():
                exp.add(f"{key}={value}", f"{key.lower()} = {value}")
            if not self.dialect.extended_commands:
                exp.warn(f"{self.dialect.title} has no Klipper-style commands")
            return exp
        if kind == META:
            exp = Explanation(
                line.number, line.raw, cmd.code, "RepRapFirmware meta command (conditional code, variables, messages)"
            )
            if not self.dialect.meta_commands:
                exp.warn(f"{self.dialect.title} has no meta commands")
            return exp
        if kind == OWORD:
            exp = Explanation(
                line.number,
                line.raw,
                cmd.code,
                f"O-word {cmd.params.get('keyword') or ''} (LinuxCNC subroutine or control flow)".replace("  ", " "),
            )
            if not self.dialect.owords:
                exp.warn(f"{self.dialect.title} has no O-words")
            return exp
        if kind == ASSIGNMENT:
            return Explanation(
                line.number, line.raw, None, f"set parameter {cmd.params.get('target')} to {cmd.params.get('value')}"
            )
        if kind == PERCENT:
            return Explanation(line.number, line.raw, "%", "program start/end marker")
        return Explanation(line.number, line.raw, cmd.code, f"{kind} command")

    # -- addressing ---------------------------------------------------------------------------------

    def _address_text(self, address: Address) -> str:
        if self.firmware == 4:
            # v4 labels read "yoke 1, position 1 (v4 T11)"; add the v5 number the rest of gclint speaks
            text = address.label
            if address.v5 is not None and text.endswith(")"):
                text = f"{text[:-1]} = v5 T{address.v5})"
            if address.kind == HEAD:
                text = "head at " + text
        elif address.kind == HEAD and address.v5 is not None:
            text = f"head T{address.v5} ({yoke_label(address.v5)})"
        else:
            text = address.label
        if not address.certain:
            text += "; this v4 correspondence is inferred, not documented"
        return text

    def _target(
        self,
        exp: Explanation,
        cmd: Command,
        role: str = "target head",
        default: str | None = None,
        physical: bool = False,
        declares: bool = False,
    ) -> Address | None:
        """Decode the T variable of an M-code; ``default`` says what happens without one.  ``declares``:
        the command itself declares the head loaded (Repetrel's ``M6 T# O...``), so it takes effect on it."""
        word = cmd.param("T")
        if word is None:
            focus = self.state.tool
            if default is None:
                default = "no T: use the head with current focus"
                if focus is not None:
                    default += f" (T{focus})"
            exp.note(default)
            return None
        address = self.interpreter.address(cmd)
        if address is None:
            exp.add(word.text.strip(), f"{role}: {word.value!r} is not a device number")
            return None
        text = self._address_text(address)
        if role == "target head" and text.startswith("head "):
            exp.add(word.text.strip(), f"target {text}")
        else:
            exp.add(word.text.strip(), f"{role}: {text}")
        if address.kind == "reserved":
            exp.warn(f"no device has the address T{address.number}")
        if physical and address.kind in (VIRTUAL, GROUP):
            exp.warn(f"{cmd.code} will FAIL (non-fatally) on a virtual or group address: use a physical address")
        if (
            address.kind == HEAD
            and address.position is not None
            and not (declares and self.state.loaded_heads is None)
            and self.state.head_loaded(address.position) is False
        ):
            exp.warn(f"no head is loaded at T{address.position} (per the job header or --loaded)")
        return address

    def _tool(self, cmd: Command, line: Line) -> Explanation:
        code = cmd.code or ""
        digits = code[1:]
        if len(digits.lstrip("-")) > 6:  # no printer has a million tools: do not parse 5000 digits
            return Explanation(line.number, line.raw, code[:12] + "...", "a T number too large for any tool or head")
        number = int(digits)
        if not self.hyrel:
            exp = Explanation(line.number, line.raw, code, f"select tool {number}")
            if number < 0:
                exp = Explanation(line.number, line.raw, code, "deselect the current tool")
            if self.family in ("linuxcnc", "smoothie"):
                exp.note(
                    "prepares the tool; M6 changes to it"
                    if self.family == "linuxcnc"
                    else "select the tool (M6 T changes it on the ATC)"
                )
            else:
                exp.note(f"extruder/tool {number} becomes active (its offsets and temperature apply)")
            return exp
        address = self.interpreter.tool_command_address(cmd)
        if address is None:
            return Explanation(line.number, line.raw, code, "tool change")
        if address.kind == HEAD:
            exp = Explanation(
                line.number,
                line.raw,
                code,
                f"switch to head T{address.v5}: {yoke_label(address.v5)}, and invoke all its flow, prime, "  # type: ignore[arg-type]
                "unprime and offset parameters",
            )
            if self.firmware == 4 and address.v5 != address.number:
                exp.note(f"v4 tool number {address.number}")
            loaded = self.state.head_loaded(address.v5)  # type: ignore[arg-type]
            if loaded is False:
                exp.warn(
                    f"no head is loaded at T{address.v5}: Repetrel warns when T commands do not match the loaded heads"
                )
            return exp
        if address.kind == VIRTUAL:
            exp = Explanation(line.number, line.raw, code, f"switch to {address.label}: the squad's heads act together")
            members = self.state.squads.get(address.v5)  # type: ignore[arg-type]
            if members:
                exp.note("heads in the squad: " + ", ".join(f"T{h}" for h in sorted(members)))
            elif members is None:
                exp.warn(f"no M702 established squad T{address.v5} before this line")
            return exp
        if address.kind == "reserved":
            exp = Explanation(line.number, line.raw, code, f"{address.label}")
            exp.warn("no device answers to this tool number")
            return exp
        return Explanation(line.number, line.raw, code, f"switch focus to {self._address_text(address)}")

    # -- the decoder table --------------------------------------------------------------------------

    def _table(self) -> dict[str, Callable[[Explanation, Command, Code | None], None]]:
        table: dict[str, Callable[[Explanation, Command, Code | None], None]] = {
            "G0": lambda e, c, s: self._motion(e, c, s, "G0"),
            "G1": lambda e, c, s: self._motion(e, c, s, "G1"),
            "G4": self._dwell,
            "G28": self._home,
            "G90": lambda e, c, s: e.note("positions (X Y Z A B) are absolute from here on"),
            "G91": lambda e, c, s: e.note("positions (X Y Z A B) are relative to the last position from here on"),
            "G92": self._set_position,
            "M82": lambda e, c, s: e.note("E values are absolute from here on"),
            "M83": lambda e, c, s: e.note("E values are relative from here on"),
        }
        if self.hyrel:
            table.update(
                {
                    "G2": self._arc,
                    "G3": self._arc,
                    "G2.1": self._spiral,
                    "G3.1": self._spiral,
                    "G2.2": self._spiral,
                    "G3.2": self._spiral,
                    "G2.3": self._arc3,
                    "G3.3": self._arc3,
                    "M104": self._set_temp,
                    "M140": self._set_temp,
                    "M141": self._set_temp,
                    "M109": self._wait_temp,
                    "M190": self._wait_temp,
                    "M191": self._wait_temp,
                    "M116": lambda e, c, s: e.note(
                        "pause until every temperature set with W0 (M109/M190/M191) is reached"
                    ),
                    "M106": self._fan,
                    "M107": self._fan_off,
                    "M229": self._m229,
                    "M620": self._m620,
                    "M621": self._m621,
                    "M623": self._m623,
                    "M660": self._m660,
                    "M702": self._m702,
                    "M703": self._m703,
                    "M704": self._m704,
                    "M6": self._m6,
                    "M0": self._m0,
                    "M3": self._spindle,
                    "M4": self._spindle,
                    "M5": self._spindle_off,
                    "G81": self._g81,
                    "M721": self._prime,
                    "M722": self._prime,
                    "M221": self._targeted,
                    "M723": self._targeted,
                    "M728": self._targeted,
                    "M701": self._targeted,
                    "M783": self._targeted,
                }
            )
        else:
            table.update(
                {
                    "M104": self._set_temp,
                    "M109": self._wait_temp,
                    "M140": self._set_temp,
                    "M190": self._wait_temp,
                    "M106": self._fan,
                    "M107": self._fan_off,
                }
            )
            if self.family in ("linuxcnc", "smoothie"):
                table.update(
                    {"M3": self._spindle, "M4": self._spindle, "M5": self._spindle_off, "M6": self._tool_change}
                )
        return table

    # -- motion -------------------------------------------------------------------------------------

    def _axis_text(self, letter: str, value: str | None) -> str:
        unit = "in" if self.state.units == "inch" else "mm"
        if value is None:
            return f"{letter} with no value"
        if self.state.absolute:
            return f"to {letter}{value}"
        number = _num(value)
        if number is None:
            return f"by {value} {unit} in {letter}"
        return f"{'+' if number >= 0 else ''}{_fmt(number)} {unit} in {letter}"

    def _motion(self, exp: Explanation, cmd: Command, spec: Code | None, mode: str) -> None:
        p = cmd.params
        if mode == "G0":
            exp.note("rapid (non-working) straight line move from the current location")
        else:
            exp.note(
                "working speed straight line move from the current location" if self.hyrel else "straight line move"
            )
        for letter in "XYZAB":
            word = cmd.param(letter)
            if word is not None:
                exp.add(word.text.strip(), self._axis_text(letter, word.value))
        if self.hyrel:
            for letter in "AB":
                if letter not in p and any(a in p for a in "XYZ"):
                    exp.note(f"no change in {letter}")
        e = cmd.param("E")
        if e is not None:
            if mode == "G0":
                exp.items.append(Item(e.text.strip(), "E on a G0 does nothing: G0 never works", self.hyrel))
            elif self.hyrel and self.state.flow_mode != EVALUES:
                exp.add(e.text.strip(), "while extruding; native flow ignores the amount (M229 E1 D1 uses it)")
            elif self.state.e_absolute:
                exp.add(e.text.strip(), f"extrude until the E position is {e.value}")
            else:
                exp.add(
                    e.text.strip(),
                    f"extrude {e.value} mm of filament"
                    if _num(e.value) and (_num(e.value) or 0) > 0
                    else f"E by {e.value} (retract)",
                )
        f = cmd.param("F")
        if f is not None:
            if mode == "G0" and self.family in ("hyrel", "smoothie"):
                exp.add(f.text.strip(), f"one-time speed of {f.value} mm/min, not persistent")
            else:
                exp.add(f.text.strip(), f"moving at {f.value} mm/min")
        elif mode == "G0" and self.hyrel:
            exp.note("no F: use the G0 speed from the settings (or M203)")
        elif self.state.feed is not None:
            exp.note(f"using the previously set F{_fmt(self.state.feed)}")
        h = cmd.param("H")
        if h is not None and self.hyrel:
            register = _num(h.value)
            offsets = self.state.tool_height_offsets
            stored = offsets.get(int(register)) if register is not None and register == int(register) else None
            if register is not None and register == int(register) and int(register) in offsets:
                extra = (
                    f": Z{'+' if (stored or 0) >= 0 else ''}{_fmt(stored)} stored by M660" if stored is not None else ""
                )
                exp.add(h.text.strip(), f"invoke the offsets stored in register H{int(register)}{extra}")
            else:
                exp.add(h.text.strip(), f"invoke the offsets stored in register H{h.value}")
                exp.warn(f"no M660 H{h.value} stored an offset before this line")
        s = cmd.param("S")
        if s is not None:
            if self.hyrel and mode == "G1":
                exp.add(s.text.strip(), f"one-time flow multiplier {s.value} for this move only")
            elif self.family == "reprap":
                exp.add(s.text.strip(), "S1 on G1: endstop-checking move (homing)" if s.value == "1" else f"S{s.value}")
            else:
                exp.add(s.text.strip(), self._meaning(spec, "S") or f"S{s.value}")
        known = set("XYZABEFHS")
        self._generic(exp, cmd, spec, skip=known)

    def _arc(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        direction = "clockwise" if cmd.code == "G2" else "counter-clockwise"
        exp.note(f"working speed {direction} arc/circle move from the current location")
        for letter in "XYZ":
            word = cmd.param(letter)
            if word is not None:
                exp.add(word.text.strip(), self._axis_text(letter, word.value))
        for letter, axis in (("I", "X"), ("J", "Y")):
            word = cmd.param(letter)
            if word is not None:
                exp.add(word.text.strip(), f"centered about a point {word.value} mm further in {axis}")
        self._segments(exp, cmd)
        if "E" in cmd.params:
            exp.add(cmd.param("E").text.strip(), "while extruding")  # type: ignore[union-attr]
        f = cmd.param("F")
        if f is not None:
            exp.add(f.text.strip(), f"moving at {f.value} mm/min")
        else:
            exp.note("using the previously established F rate")
        exp.note("printed with Hyrel's native flow (nozzle, layer, feed) even under M229 E1")
        self._generic(exp, cmd, spec, skip="XYZIJSEF")

    def _segments(self, exp: Explanation, cmd: Command) -> None:
        word = cmd.param("S")
        if word is None:
            exp.note("default segments of 0.33333 mm")
            return
        value = _num(word.value)
        if value is None:
            exp.add(word.text.strip(), "segment length or count")
        elif value < 3:
            exp.add(word.text.strip(), f"segments {word.value} mm long")
        else:
            exp.add(word.text.strip(), f"made up of {_fmt(value)} segments (only allowed on complete 360° circles)")

    def _spiral(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        code = cmd.code or ""
        direction = "clockwise" if code.startswith("G2") else "counter-clockwise"
        exp.note(f"working speed {direction} spiral move from the current location")
        if code.endswith(".1"):
            exp.note("ends where it starts in X/Y (full laps around the center)")
        for letter in "XYZ":
            word = cmd.param(letter)
            if word is not None:
                exp.add(word.text.strip(), self._meaning(spec, letter) or letter)
        for letter, axis in (("I", "X"), ("J", "Y")):
            word = cmd.param(letter)
            if word is not None:
                exp.add(word.text.strip(), f"centered about a point {word.value} mm further in {axis}")
        laps = cmd.param("L")
        exp.add(laps.text.strip(), f"complete no more than {laps.value} laps") if laps is not None else exp.note(
            "complete all laps"
        )
        pitch = cmd.param("P")
        if pitch is not None:
            exp.add(pitch.text.strip(), f"{pitch.value} mm between centers of travel of adjacent laps")
        if "E" in cmd.params:
            exp.add(cmd.param("E").text.strip(), "while extruding")  # type: ignore[union-attr]
        self._segments(exp, cmd)
        r = cmd.param("R")
        if code.endswith(".1"):
            flags = {
                "0": "spiral in toward the center from the current location",
                "1": "spiral out from the center to the current location (after an inward jump)",
                "2": "spiral out from the current position",
            }
            if r is not None:
                exp.add(r.text.strip(), flags.get(r.value or "", "unknown spiral direction flag"))
            else:
                exp.note("default R0: spiral in toward the center")
        f = cmd.param("F")
        exp.add(f.text.strip(), f"at a speed of {f.value} mm/min") if f is not None else exp.note(
            "moving at the established G1 F speed"
        )
        self._generic(exp, cmd, spec, skip="XYZIJLPESRF")

    def _arc3(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        direction = "clockwise" if cmd.code == "G2.3" else "counter-clockwise"
        exp.note(f"working speed {direction} arc in 3-space (not bound to the X/Y plane)")
        plane = {16: "any plane (U V W give the normal vector)", 17: "X/Y plane", 18: "X/Z plane", 19: "Y/Z plane"}
        exp.note(f"arc plane: {plane.get(self.state.plane, 'X/Y plane')}")
        self._segments(exp, cmd)
        self._generic(exp, cmd, spec, skip="S")

    def _dwell(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        s = _num(cmd.raw("S"))
        p = _num(cmd.raw("P"))
        p_seconds = self.family in ("linuxcnc", "smoothie")  # Machinekit/LinuxCNC and Carvera: P is seconds
        if cmd.has("S"):
            exp.add(cmd.param("S").text.strip(), f"{cmd.raw('S')} s")  # type: ignore[union-attr]
        if cmd.has("P"):
            exp.add(cmd.param("P").text.strip(), f"{cmd.raw('P')} {'s' if p_seconds else 'ms'}")  # type: ignore[union-attr]
        total = (s or 0) + ((p or 0) if p_seconds else (p or 0) / 1000)
        if s is not None and p is not None:
            exp.note(f"pause for {_fmt(total)} s in all (S and P add up)")
        elif s is None and p is None:
            exp.note("no S or P: no pause")

    def _home(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        listed = [a for a in "XYZAB" if a in cmd.params]
        if self.hyrel:
            exp.note("send the listed axes to their sensor-defined physical home, then pop off and re-acquire slowly")
            for axis in "XYZAB":
                word = cmd.param(axis)
                if word is not None:
                    exp.add(word.text.strip(), f"home the {axis} axis")
                else:
                    exp.note(f"{axis} remains unchanged")
            if not listed:
                exp.warn("no axis listed: Hyrel homes only the axes named (G28 X0 Y0)")
            exp.note(
                "afterwards G92 and H (M660) offsets are cleared, a G53 is performed and a head offset of 0 is applied"
            )
        elif self.family == "reprap":
            if listed:
                for axis in listed:
                    exp.add(cmd.param(axis).text.strip(), f"home {axis}")  # type: ignore[union-attr]
            else:
                exp.note("no axis listed: home all axes")
        else:
            exp.note(
                "go to the stored G28 position (through the listed axes' intermediate point)"
                if self.family == "linuxcnc"
                else "go to the clearance (G28) position"
            )
            self._generic(exp, cmd, spec)

    def _set_position(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        exp.note("replace the current position values (no motion)")
        for word in cmd.words:
            if word.letter in "XYZABE":
                exp.add(
                    word.text.strip(),
                    f"present {word.letter} position is {word.value if word.value is not None else 0}",
                )
            else:
                self._generic(
                    exp, Command(cmd.code, cmd.kind, cmd.column, {word.letter: word.value}, words=(word,)), spec
                )

    # -- temperatures -------------------------------------------------------------------------------

    def _device_default(self, code: str) -> str:
        if code in ("M140", "M190"):
            return (
                "no T: the primary bed" if code == "M140" else "no T: use the bed with current focus (the primary bed)"
            )
        if code in ("M141", "M191"):
            return (
                "no T: the primary chamber"
                if code == "M141"
                else "no T: use the chamber with current focus (the primary chamber)"
            )
        focus = self.state.tool
        return "no T: use the head with current focus" + (f" (T{focus})" if focus is not None else "")

    def _set_temp(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        code = cmd.code or ""
        role = {"M140": "target bed", "M141": "target chamber"}.get(code, "target head")
        if self.hyrel:
            self._target(exp, cmd, role, self._device_default(code))
        elif "T" in cmd.params:
            exp.add(cmd.param("T").text.strip(), f"extruder/tool {cmd.raw('T')}")  # type: ignore[union-attr]
        s = cmd.param("S")
        if s is not None:
            exp.add(s.text.strip(), f"to {s.value}{DEG}" + (" (off)" if _num(s.value) == 0 else ""))
        exp.note("set the temperature and go on without waiting")
        self._generic(exp, cmd, spec, skip="TS")

    def _wait_temp(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        code = cmd.code or ""
        if not self.hyrel:
            self._wait_temp_reprap(exp, cmd, spec)
            return
        role = {"M190": "target bed", "M191": "target chamber"}.get(code, "target head")
        address = self._target(exp, cmd, role, self._device_default(code), physical=True)
        s_word = cmd.param("S")
        s = _num(s_word.value) if s_word is not None else None
        if s_word is not None:
            exp.add(
                s_word.text.strip(),
                f"and set the temperature to {s_word.value}{DEG}" if s else f"to {s_word.value}{DEG}",
            )
        else:
            key = (
                address.v5
                if address is not None and address.v5 is not None
                else (self.state.tool if code == "M109" else 24)
            )
            known = self.state.targets.get(key) if key is not None else None
            exp.note(
                "no S: no new temperature is set"
                + (f"; the set point stays {_fmt(known)}{DEG}" if known is not None else "")
            )
            s = known
        low = high = None
        groups = []
        for letter in ("H", "C", "L", "U", "R"):
            word = cmd.param(letter)
            if word is None:
                continue
            value = _num(word.value)
            v = word.value
            if letter == "H":
                exp.add(word.text.strip(), f"but end the wait once the temperature reaches {v}{DEG}")
                low = value
            elif letter == "C":
                exp.add(word.text.strip(), f"or end the wait once the temperature cools down to {v}{DEG}")
                high = value
            elif letter == "L":
                exp.add(
                    word.text.strip(), f"but end the wait once the temperature reaches {v}{DEG} below the set point"
                )
                low = s - value if s is not None and value is not None else None
            elif letter == "U":
                exp.add(word.text.strip(), f"or end the wait once the temperature reaches {v}{DEG} above the set point")
                high = s + value if s is not None and value is not None else None
            else:
                exp.add(
                    word.text.strip(), f"but end the wait once the temperature is within +/-{v}{DEG} of the set point"
                )
                if s is not None and value is not None:
                    low, high = s - value, s + value
        if any(x in cmd.params for x in "HC"):
            groups.append("H/C")
        if any(x in cmd.params for x in "LU"):
            groups.append("L/U")
        if "R" in cmd.params:
            groups.append("R")
        if len(groups) > 1:
            exp.warn(
                "the Hyrel page says: use EITHER (H and/or C) OR (L and/or U) OR (R); this mixes "
                + " and ".join(groups)
            )
        if "H" in cmd.params and "L" in cmd.params or "C" in cmd.params and "U" in cmd.params:
            exp.warn("you can use H or L, but not both; C or U, but not both")
        if low is not None and high is not None:
            exp.note(f"the wait ends when the temperature is anywhere between {_fmt(low)}{DEG} and {_fmt(high)}{DEG}")
        elif low is not None:
            exp.note(f"the wait ends once the temperature is {_fmt(low)}{DEG} or more")
        elif high is not None:
            exp.note(f"the wait ends once the temperature is {_fmt(high)}{DEG} or less")
        w = cmd.param("W")
        if w is not None:
            if w.value == "0":
                exp.add(w.text.strip(), "but do not pause until M116 is executed (v5+)")
                if self.firmware == 4:
                    exp.warn("W0 and M116 exist from v5 on")
            else:
                exp.items.append(Item(w.text.strip(), "only W0 is defined", True))
        self._generic(exp, cmd, spec, skip="TSHCLURW")

    def _wait_temp_reprap(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        code = cmd.code or ""
        what = "bed" if code == "M190" else "hotend"
        if "T" in cmd.params and code == "M109":
            exp.add(cmd.param("T").text.strip(), f"extruder/tool {cmd.raw('T')}")  # type: ignore[union-attr]
        s = cmd.param("S")
        r = cmd.param("R")
        if self.family == "linuxcnc":
            self._generic(exp, cmd, spec)
            return
        if s is not None:
            exp.add(s.text.strip(), f"set the {what} to {s.value}{DEG} and wait only while heating up to it")
        if r is not None:
            exp.add(r.text.strip(), f"set the {what} to {r.value}{DEG} and wait while heating or cooling to it")
        if s is None and r is None:
            exp.note(f"no S or R: wait for the {what} target already set")
        self._generic(exp, cmd, spec, skip="TSR")

    # -- fans and UV -------------------------------------------------------------------------------

    def _fan(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        if not self.hyrel:
            self._fan_reprap(exp, cmd, spec)
            return
        c_word = cmd.param("C")
        c = _num(c_word.value) if c_word is not None else None
        if "T" in cmd.params:
            self._target(exp, cmd)
        elif c_word is not None and not any(x in cmd.params for x in "SP"):
            exp.note("on all tools")
        else:
            self._target(exp, cmd)
        fan_range = c if c is not None and c > 0 else self.state.fan_range
        s = cmd.param("S")
        if s is not None:
            value = _num(s.value)
            if value is not None and fan_range:
                share = value / fan_range * 100
                exp.add(
                    s.text.strip(),
                    f"target value of {s.value} of range 0-{_fmt(fan_range)}: {_fmt(round(share, 1))}% duty",
                )
                if value > fan_range:
                    exp.warn(f"S{s.value} is above the range 0-{_fmt(fan_range)} (M106 C sets the range)")
            else:
                exp.add(s.text.strip(), f"target value of {s.value}")
        elif c_word is not None and "P" not in cmd.params:
            exp.note("no speed")
        if c_word is not None:
            exp.add(
                c_word.text.strip(),
                f"of range 0-{c_word.value}: all following M106 commands of this job use this range",
            )
        elif s is not None:
            src = f"set by M106 C at line {self.state.fan_range_line}" if self.state.fan_range_line else "default 0-100"
            exp.note(f"range 0-{_fmt(self.state.fan_range)} ({src})")
        p = cmd.param("P")
        if p is not None:
            exp.add(p.text.strip(), f"during extrusion moves only, at {p.value}% duty")
        self._generic(exp, cmd, spec, skip="TSCP")

    def _fan_reprap(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        if self.family == "linuxcnc":
            self._generic(exp, cmd, spec)
            return
        p = cmd.param("P")
        if p is not None:
            exp.add(p.text.strip(), f"fan number {p.value}")
        s = cmd.param("S")
        if s is not None:
            value = _num(s.value)
            if (
                value is not None
                and value <= 1
                and "." in (s.value or "")
                and self.family == "reprap"
                and self.dialect.name == "reprap"
            ):
                exp.add(s.text.strip(), f"fan speed {_fmt(value * 100)}% (RepRapFirmware reads 0-1 as a fraction)")
            elif value is not None:
                exp.add(s.text.strip(), f"fan speed {s.value} of 255: {_fmt(round(value / 255 * 100, 1))}%")
        else:
            exp.note("no S: full speed")
        self._generic(exp, cmd, spec, skip="PS")

    def _fan_off(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        if self.hyrel:
            self._target(exp, cmd)
            exp.note("set cooling/LEDs to 0% (same as M106 S0); also turns off the Quiet Storm fan")
        else:
            exp.note("fan off")
            self._generic(exp, cmd, spec)

    # -- Hyrel flow, lasers, offsets, squads ----------------------------------------------------------

    def _m229(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        e = cmd.param("E")
        d = cmd.param("D")
        if e is not None:
            exp.add(
                e.text.strip(),
                {
                    "0": "disabled: native flow from speed, layer height and nozzle; E marks printing moves",
                    "1": "enabled: the slicer's E values drive the flow",
                }.get(e.value or "", "E must be 0 or 1"),
            )
        routes = {
            "0": "flow calculations on the head controller; constant, not adjusted for acceleration",
            "1": "flow calculations directed via CANBUS and adjusted to motion acceleration/deceleration",
            "2": "on the motion controller, sent to the head via the C axis step pin, adjusted for acceleration",
            "3": "on the motion controller, sent via CANBUS and the C axis, adjusted for acceleration",
        }
        if d is not None:
            exp.add(d.text.strip(), routes.get(d.value or "", "D must be 0 to 3"))
        s = cmd.param("S")
        if s is not None:
            exp.add(
                s.text.strip(),
                f"isolated non-printing moves of under {s.value} seconds will not trigger unprime/prime actions",
            )
        if e is not None and e.value == "1" and d is not None and d.value == "0":
            exp.warn("E1 D0 is an illegal combination (use M229 E1 D1)")
        elif e is not None and e.value == "1" and d is None:
            exp.note("M229 E1 D1 is the default way to enable E values")
        self._generic(exp, cmd, spec, skip="EDS")

    def _m620(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        if "T" not in cmd.params:
            exp.warn("T must be specified: M620 can NOT inherit the head with focus")
        else:
            self._target(exp, cmd, "target device")
        e = cmd.param("E")
        if e is None or e.value == "0":
            exp.add(e.text.strip(), "disable") if e is not None else exp.note("no E: disable (E0 is the default)")
        elif e.value == "1":
            exp.add(e.text.strip(), "enable")
        a = cmd.param("A")
        if a is not None:
            exp.add(
                a.text.strip(), f"cooling stays on for {a.value} s after shut-off (temperature safety still applies)"
            )
        self._generic(exp, cmd, spec, skip="TEA")

    def _m621(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        exp.note("on the laser already enabled with M620 (no T)")
        p = cmd.param("P")
        if p is not None:
            exp.add(p.text.strip(), f"at {p.value}% during printing (E) moves")
        d = cmd.param("D")
        if d is not None:
            exp.add(d.text.strip(), f"initial (pierce) power {d.value}% to penetrate the material")
        elif p is not None:
            exp.note("no D: the initial power is P")
        if not self.state.laser_enabled_any:
            exp.warn("no M620 T# E1 enabled a laser before this line")
        self._generic(exp, cmd, spec, skip="PD")

    def _m623(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        exp.note("static emission (not during moves) from the laser or UV pen")
        p = cmd.param("P")
        if p is not None:
            exp.add(p.text.strip(), f"power {p.value}%")
        d = cmd.param("D")
        if d is not None:
            value = _num(d.value)
            secs = f" ({_fmt(value / 1000)} seconds)" if value is not None and value >= 1000 else ""
            exp.add(d.text.strip(), f"duration {d.value} milliseconds{secs}")
            if value is not None and value > 1000:
                exp.note("D above 1,000 ms is only allowed for UV pens (max 60,000); other devices stop at 1,000")
            if value is not None and value > 60000:
                exp.warn("D is above the UV pen maximum of 60,000 ms")
        self._generic(exp, cmd, spec, skip="PD")

    def _m660(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        h = cmd.param("H")
        z = cmd.param("Z")
        if h is not None:
            exp.add(h.text.strip(), f"store in register {h.value}")
        if z is not None:
            exp.add(
                z.text.strip(),
                f"{'+' if (_num(z.value) or 0) >= 0 and not (z.value or '').startswith('+') else ''}{z.value} to the Z position",
            )
        exp.note(
            f"applied only when a G1 carries H{h.value if h is not None else 'n'}; the EHR needs G28 Z0 in the header"
        )
        self._generic(exp, cmd, spec, skip="HZ")

    def _squad(self, cmd: Command) -> int | None:
        value = _num(cmd.raw("S"))
        return int(value) if value is not None and value == int(value) else None

    def _m702(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        self._target(exp, cmd, "using the flow values (pulse, prime, unprime) from")
        s = cmd.param("S")
        if s is not None:
            exp.add(
                s.text.strip(), f"designate clone squad T{s.value}: its heads will perform the same extrusion commands"
            )
        exp.note("an M30 decommissions every clone squad")
        self._generic(exp, cmd, spec, skip="TS")

    def _m703(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        squad = self._squad(cmd)
        s = cmd.param("S")
        if self.firmware == 4:
            self._target(exp, cmd, "device")
            if s is not None:
                exp.add(
                    s.text.strip(),
                    f"gets the alias {s.value} (v4 cloning: commands sent to {s.value} reach this device too)",
                )
            self._generic(exp, cmd, spec, skip="TS")
            return
        if squad is not None and 30 <= squad <= 39:
            self._target(exp, cmd, "head to add to the squad")
            exp.add(s.text.strip(), f"clone squad T{squad} to join")  # type: ignore[union-attr]
            if squad not in self.state.squads:
                exp.warn(f"no M702 established squad T{squad} before this line")
        else:
            self._target(exp, cmd, "head on which to imitate the actions of head S")
            if s is not None:
                exp.add(s.text.strip(), f"head T{s.value}, which T will imitate")
        self._generic(exp, cmd, spec, skip="TS")

    def _m704(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        squad = self._squad(cmd)
        s = cmd.param("S")
        self._target(exp, cmd, "head to remove" if self.firmware != 4 else "device")
        if s is not None:
            if self.firmware == 4:
                exp.add(s.text.strip(), f"remove the alias {s.value}")
            elif squad is not None and 30 <= squad <= 39:
                exp.add(s.text.strip(), f"from clone squad T{squad}")
            else:
                exp.add(s.text.strip(), f"stop imitating head T{s.value}")
        self._generic(exp, cmd, spec, skip="TS")

    def _m6(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        if "T" in cmd.params:
            # "M6 T# O..." is the header line that declares the head: it is loaded from this line on
            self._target(exp, cmd, declares="O" in cmd.params)
        else:
            exp.note("all future T# or M6 commands")
        o = cmd.param("O")
        if o is not None:
            exp.add(o.text.strip(), f'offset stored in register "O{o.value}"')
        for axis in "XYZAB":
            word = cmd.param(axis)
            if word is not None:
                value = word.value or "0"
                exp.add(word.text.strip(), f"{axis}{'+' if not value.startswith(('-', '+')) else ''}{value}")
        d = cmd.param("D")
        if d is not None:
            exp.add(d.text.strip(), f"tool diameter {d.value} mm (pocket commands)")
        i = cmd.param("I")
        if i is not None:
            exp.add(i.text.strip(), "store and move these distances" if i.value == "1" else "store the values, no move")
        elif "T" in cmd.params:
            exp.note("no move")
        k = cmd.param("K")
        if k is not None:
            exp.add(
                k.text.strip(), "always force I0 with M6 unless K0 is given" if k.value == "1" else "use the I value"
            )
        exp.note("Repetrel sends one M6 per loaded head when a job starts; it is not a tool change (T is)")
        self._generic(exp, cmd, spec, skip="TOXYZABDIK")

    _ACTIONS = ("SAY", "PIC", "VID", "SEND", "BEEP", "SHELL")

    def _m0(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        exp.note("pause until the operator clicks Play; text after ';' is shown on the print mask")
        line = exp.source
        comment = line.split(";", 1)[1] if ";" in line else ""
        what = {
            "SAY": "announce text",
            "PIC": "display image",
            "VID": "play video",
            "SEND": "send to the Aux port",
            "BEEP": "sound a beep",
            "SHELL": "execute the program",
        }
        for part in comment.split(";"):
            part = part.strip()
            keyword = part.split(" ", 1)[0].upper() if part else ""
            if keyword in what:
                argument = part[len(keyword) :].strip()
                exp.add(part, f"{what[keyword]}: {argument}" if argument else what[keyword])
                if keyword == "SHELL":
                    exp.warn("SHELL runs a program on the Repetrel computer when the job reaches this line")

    def _spindle(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        direction = "clockwise" if cmd.code == "M3" else "counter-clockwise"
        exp.note(f"start the spindle {direction}")
        if self.hyrel:
            self._target(exp, cmd)
            s = cmd.param("S")
            if s is not None:
                exp.add(
                    s.text.strip(), "S0: the same as turning it off" if _num(s.value) == 0 else f"at {s.value}% power"
                )
            f = cmd.param("F")
            exp.add(f.text.strip(), f"PWM at {f.value} Hz") if f is not None else exp.note("default PWM")
            exp.note("do not change direction while the spindle is in motion")
            self._generic(exp, cmd, spec, skip="TSF")
        else:
            s = cmd.param("S")
            if s is not None:
                exp.add(s.text.strip(), f"at {s.value} RPM")
            self._generic(exp, cmd, spec, skip="S")

    def _spindle_off(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        exp.note("stop the spindle")
        if self.hyrel:
            self._target(exp, cmd)
            self._generic(exp, cmd, spec, skip="T")
        else:
            self._generic(exp, cmd, spec)

    def _tool_change(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        t = cmd.param("T")
        if t is not None:
            exp.add(t.text.strip(), f"change to tool {t.value}")
        elif self.state.tool is not None:
            exp.note(f"change to the tool selected by T (T{self.state.tool})")
        else:
            exp.note("change to the tool selected by T")
        self._generic(exp, cmd, spec, skip="T")

    def _g81(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        exp.note("begin pecking cycle")
        if "T" in cmd.params:
            self._target(exp, cmd)
        x, y = cmd.param("X"), cmd.param("Y")
        if x is not None or y is not None:
            words = " ".join(w.text.strip() for w in (x, y) if w is not None)
            exp.add(words, f"move to the X/Y starting position {words}")
        texts = {
            "I": lambda v: f"move to Z starting position Z{v}, which will be the greatest retract height",
            "P": lambda v: f"peck downward an additional {v} mm at a time",
            "Q": lambda v: f"retract upward {v.lstrip('-')} mm after each peck (to clear debris)",
            "Z": lambda v: f"peck to a maximum depth of {v.lstrip('-')} mm",
            "F": lambda v: f"working (drilling) travel speed of {v} mm/min",
        }
        for letter, text in texts.items():
            word = cmd.param(letter)
            if word is not None:
                exp.add(word.text.strip(), text(word.value or ""))
        exp.note("after this, the head retracts to the I position before moving on to the next line")
        if self.state.applied_height_register is None:
            exp.warn("an M660 offset must be set and applied (G1 H#) before G81, to allow for tool length")
        self._generic(exp, cmd, spec, skip="TXYIPQZF")

    def _prime(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        what = "unprime (retract)" if cmd.code == "M721" else "prime (advance)"
        texts = {
            "S": lambda v: f"set rate to {v} pulses per second",
            "E": lambda v: f"set pulses to {v}",
            "P": lambda v: (
                f"{v.lstrip('-')} ms {'before' if v.startswith('-') else 'after'} the {'end' if cmd.code == 'M721' else 'start'} of the print move"
            ),
        }
        for letter, text in texts.items():
            word = cmd.param(letter)
            if word is not None:
                exp.add(word.text.strip(), text(word.value or ""))
        self._target(exp, cmd)
        i = cmd.param("I")
        if i is not None and i.value == "1":
            exp.add(i.text.strip(), f"{what} now")
        else:
            exp.note(f"no immediate execution: {what} when needed")
        self._generic(exp, cmd, spec, skip="SEPTI")

    def _targeted(self, exp: Explanation, cmd: Command, spec: Code | None) -> None:
        self._target(exp, cmd)
        self._generic(exp, cmd, spec, skip="T")


# -- convenience ---------------------------------------------------------------------------------------


def explain_lines(
    lines: Iterable[tuple[str, str]], dialect: Dialect, state: MachineState | None = None
) -> Iterator[Explanation]:
    """Explanations of ``(text, ending)`` lines, in order."""
    explainer = Explainer(dialect, state)
    for number, (raw, ending) in enumerate(lines, start=1):
        yield from explainer.explain_line(Line(number, raw, ending, parse_line(raw)))


def explain_text(text: str, dialect: Dialect, state: MachineState | None = None) -> list[Explanation]:
    """Explain G-code given as text (one or more lines)."""
    return list(explain_lines(((line, "\n") for line in re.split(r"\r\n|\r|\n", text)), dialect, state))


def explain_source(source: Source, dialect: Dialect, state: MachineState | None = None) -> Iterator[Explanation]:
    """Explain a whole file, streaming."""
    return explain_lines(source.lines(), dialect, state)
