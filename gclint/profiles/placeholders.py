"""Fill a custom G-code setting's placeholders, as the slicer does before it writes the G-code.

PrusaSlicer (and SuperSlicer, OrcaSlicer, Bambu Studio, which share its ``PlaceholderParser``) read two
syntaxes in custom G-code (PrusaSlicer's manual, "Macro language"):

* the legacy one, ``[key]``, ``[key_0]`` (an element of a list), ``[key[initial_tool]]``;
* macros in braces: ``{key}``, ``{key[0]}``, expressions (``{first_layer_temperature[0] + 10}``, ``and``,
  ``or``, ``not``, comparisons, ``=~ /regex/``, ``min()``, ``max()``, ``int()``, ``round()``, ``digits()``)
  and blocks ``{if cond}...{elsif cond}...{else}...{endif}``.

Cura's start and end G-code name settings the same way in braces (``{material_print_temperature}``,
``{material_bed_temperature_layer_0, 0}``: a setting of extruder 0).

Values come from the profile; a key the profile does not set gets a typical value (``TYPICAL``: a PLA job on
a 0.4 mm nozzle, at its first layer), and the caller says which.  What cannot be evaluated (a function
gclint does not know, a setting with no value at all) is filled with 0 and said too; an ``{if}`` whose
condition cannot be evaluated takes its first branch.  Each character of the result keeps the index of the
character of the setting it came from (the placeholder's first character for what a placeholder wrote), so
that a finding in the filled G-code points into the profile.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field

Value = float | str | bool | list

# Typical values for what a printer profile alone does not set (the print and filament presets, and what the
# slicer knows only while it writes the job: the layer, the tool).  PrusaSlicer's names, OrcaSlicer's and Cura's.
TYPICAL: dict[str, Value] = {
    # temperatures (PLA)
    "temperature": [215.0],
    "first_layer_temperature": [215.0],
    "bed_temperature": [60.0],
    "first_layer_bed_temperature": [60.0],
    "chamber_temperature": [0.0],
    "idle_temperature": [0.0],
    "nozzle_temperature": [215.0],
    "nozzle_temperature_initial_layer": [215.0],
    "bed_temperature_initial_layer": [60.0],
    "bed_temperature_initial_layer_single": 60.0,
    "hot_plate_temp": [60.0],
    "hot_plate_temp_initial_layer": [60.0],
    "material_print_temperature": 215.0,
    "material_print_temperature_layer_0": 215.0,
    "material_initial_print_temperature": 210.0,
    "material_final_print_temperature": 205.0,
    "material_standby_temperature": 175.0,
    "material_bed_temperature": 60.0,
    "material_bed_temperature_layer_0": 60.0,
    "print_temperature": 215.0,
    "print_bed_temperature": 60.0,
    "build_volume_temperature": 0.0,
    # filament
    "filament_type": ["PLA"],
    "filament_diameter": [1.75],
    "material_diameter": 1.75,
    "filament_settings_id": ["PLA"],
    "filament_preset": ["PLA"],
    "extrusion_multiplier": [1.0],
    # the print
    "layer_height": 0.2,
    "first_layer_height": 0.2,
    "initial_layer_print_height": 0.2,
    "layer_height_0": 0.2,
    "extrusion_width": 0.45,
    "first_layer_speed": 20.0,
    "travel_speed": 150.0,
    "speed_travel": 150.0,
    "print_settings_id": "",
    "print_preset": "",
    "has_wipe_tower": False,
    "has_single_extruder_multi_material_priming": False,
    "wipe_tower": False,
    "single_extruder_multi_material": False,
    "use_relative_e_distances": False,
    "use_firmware_retraction": False,
    "retract_length": [0.8],
    "retract_speed": [35.0],
    "retraction_amount": 0.8,
    "retraction_speed": 35.0,
    # the printer (a profile sets these; for one that does not)
    "nozzle_diameter": [0.4],
    "machine_nozzle_size": 0.4,
    "max_print_height": 200.0,
    "machine_width": 200.0,
    "machine_depth": 200.0,
    "machine_height": 200.0,
    "printer_model": "",
    "printer_settings_id": "",
    "printer_preset": "",
    # where and when the slicer writes the G-code
    "layer_num": 1.0,
    "layer_z": 0.4,
    "max_layer_z": 10.0,
    "total_layer_count": 50.0,
    "initial_tool": 0.0,
    "initial_extruder": 0.0,
    "initial_extruder_nr": 0.0,
    "current_extruder": 0.0,
    "previous_extruder": 0.0,
    "next_extruder": 1.0,
    "toolchange_z": 0.4,
    "color_change_extruder": 0.0,
    "is_extruder_used": [True],
    "total_toolchanges": 0.0,
    "first_layer_print_min": [90.0, 90.0],
    "first_layer_print_max": [110.0, 110.0],
    "first_layer_print_size": [20.0, 20.0],
    "print_bed_min": [0.0, 0.0],
    "print_bed_max": [200.0, 200.0],
    "print_bed_size": [200.0, 200.0],
    "first_layer_center_no_wipe_tower": [100.0, 100.0],
    "extruded_volume": [1000.0],
    "extruded_weight": [1.2],
    "total_weight": 1.2,
    "total_print_time": "10m",
    "input_filename_base": "job",
    "input_filename": "job.gcode",
    "timestamp": "20240101-120000",
    "year": 2024.0,
    "month": 1.0,
    "day": 1.0,
    "hour": 12.0,
    "minute": 0.0,
    "second": 0.0,
    "curr_bed_type": "Textured PEI Plate",
    "plate_name": "",
    "in_head_wrap_detect_zone": False,
    "outer_wall_volumetric_speed": 12.0,
    "filament_extruder_id": 0.0,
    "z_offset": 0.0,
}


class NotEvaluated(Exception):
    """A macro gclint does not evaluate (the message says what)."""


class MacroError(Exception):
    """A macro the slicer refuses (unclosed brace, {endif} with no {if}): the export stops."""


@dataclass
class Filled:
    """A setting's G-code with its placeholders filled."""

    text: str
    origin: list[int]  # origin[i]: the index in the setting of the character that made text[i]
    typical: set[str] = field(default_factory=set)  # keys that got a typical value
    unevaluated: list[tuple[int, str]] = field(default_factory=list)  # (index in the setting, what)
    errors: list[tuple[int, str]] = field(default_factory=list)  # (index in the setting, what): the slicer stops


Lookup = Callable[[str], Value | None]

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
# [key], [key_3], [key[expr]] (legacy); a LinuxCNC "[#1 + 2]" or a "[ ... ]" of text is left alone
_LEGACY = re.compile(r"\[([A-Za-z_][A-Za-z0-9_]*)(?:\[([^\[\]{}]*)\])?\]")
_KEYWORDS = ("if", "elsif", "elif", "else", "endif")  # (Cura writes elif)
MAX_LENGTH = 1 << 20  # characters of one setting (more is not a profile's custom G-code)
MAX_OUTPUT = 4 << 20


def value_of(text: str) -> Value:
    """A profile value as the macro language sees it: a number, a list (``0.4,0.4``), a bool or a string."""
    t = text.strip()
    if "," in t and not t.startswith('"'):
        parts = [p.strip() for p in t.split(",")]
        converted = [_scalar(p) for p in parts]
        if all(isinstance(v, float) for v in converted):
            return converted
        return [p for p in parts]
    if ";" in t and t.startswith('"'):
        return [p.strip().strip('"') for p in t.split(";")]
    return _scalar(t)


def _scalar(t: str) -> Value:
    try:
        number = float(t)
    except ValueError:
        return t.strip('"')
    return number if math.isfinite(number) else t


class _Resolver:
    def __init__(self, lookup: Lookup, filled: Filled) -> None:
        self.lookup = lookup
        self.filled = filled
        self.at = 0

    def get(self, name: str) -> Value:
        value = self.lookup(name)
        if value is not None:
            return value
        typical = TYPICAL.get(name)
        if typical is not None:
            self.filled.typical.add(name)
            return typical
        if name in ("true", "false"):
            return name == "true"
        raise NotEvaluated(f"no value for '{name}' in the profile")


def fill(text: str, lookup: Lookup, cura: bool = False) -> Filled:
    """``text`` (a custom G-code setting) with its placeholders filled from ``lookup`` (None: not set)."""
    if len(text) > MAX_LENGTH:
        raise MacroError(f"a custom G-code setting of more than {MAX_LENGTH:,} characters")
    out: list[str] = []
    origin: list[int] = []
    filled = Filled("", origin)
    resolver = _Resolver(lookup, filled)
    # each entry: [this branch is written, a branch of this block was taken, an {else} was seen, where]
    blocks: list[list] = []
    i, n = 0, len(text)

    def writing() -> bool:
        return all(b[0] for b in blocks)

    def emit(piece: str, at: int) -> None:
        if writing():
            if len(out) + len(piece) > MAX_OUTPUT:
                raise MacroError("the filled G-code grows past 4 million characters")
            out.append(piece)
            origin.extend([at] * len(piece))

    while i < n:
        c = text[i]
        if c == "{":
            end = _closing(text, i)
            if end < 0:
                filled.errors.append((i, "a '{' with no closing '}': the slicer stops the export"))
                emit(text[i:], i)
                break
            body = text[i + 1 : end].strip()
            resolver.at = i
            keyword, _, rest = body.partition(" ")
            if keyword in _KEYWORDS:
                _block(keyword, rest, blocks, resolver, filled, i, cura)
            elif writing():
                emit(_show(_evaluate_or_zero(body, resolver, filled, i, cura)), i)
            i = end + 1
            continue
        if c == "[" and not cura:
            m = _LEGACY.match(text, i)
            if m is not None:
                piece = _legacy(m, resolver, filled, i)
                if piece is not None:
                    emit(piece, i)
                    i = m.end()
                    continue
        if writing():
            out.append(c)
            origin.append(i)
        i += 1
    for block in blocks:
        filled.errors.append((block[3], "an {if} with no {endif}: the slicer stops the export"))
    origin.append(n)
    filled.text = "".join(out)
    return filled


def _closing(text: str, start: int) -> int:
    """The index of the '}' that closes the macro opened at ``start`` (strings may hold braces), or -1."""
    i = start + 1
    in_string = False
    while i < len(text):
        c = text[i]
        if in_string:
            if c == "\\":
                i += 2
                continue
            if c == '"':
                in_string = False
        elif c == '"':
            in_string = True
        elif c == "}":
            return i
        elif c in "{\n":
            return -1  # (a macro is one line, and macros do not nest)
        i += 1
    return -1


def _block(keyword: str, rest: str, blocks: list, resolver: _Resolver, filled: Filled, at: int, cura: bool) -> None:
    if keyword == "if":
        truth = _condition(rest, resolver, filled, at, cura)
        blocks.append([truth, truth, False, at])
        return
    if not blocks:
        filled.errors.append((at, f"{{{keyword}}} with no {{if}} before it: the slicer stops the export"))
        return
    block = blocks[-1]
    if keyword in ("elsif", "elif"):
        if block[2]:
            filled.errors.append((at, f"{{{keyword}}} after {{else}}: the slicer stops the export"))
        truth = not block[1] and _condition(rest, resolver, filled, at, cura)
        block[0] = truth
        block[1] = block[1] or truth
    elif keyword == "else":
        block[0] = not block[1]
        block[1] = True
        block[2] = True
    else:
        blocks.pop()


def _condition(text: str, resolver: _Resolver, filled: Filled, at: int, cura: bool) -> bool:
    try:
        return _truth(_Expression(text, resolver, cura).parse())
    except (NotEvaluated, ValueError, ZeroDivisionError, IndexError, TypeError, re.error) as exc:
        filled.unevaluated.append((at, f"{{if {text.strip()}}}: {_reason(exc)}; its first branch was taken"))
        return True


def _evaluate_or_zero(text: str, resolver: _Resolver, filled: Filled, at: int, cura: bool) -> Value:
    try:
        return _Expression(text, resolver, cura).parse()
    except (NotEvaluated, ValueError, ZeroDivisionError, IndexError, TypeError, re.error) as exc:
        filled.unevaluated.append((at, f"{{{text}}}: {_reason(exc)}; 0 was used"))
        return 0.0


def _reason(exc: Exception) -> str:
    return str(exc) if isinstance(exc, NotEvaluated) else f"not evaluated ({type(exc).__name__})"


def _legacy(m: re.Match[str], resolver: _Resolver, filled: Filled, at: int) -> str | None:
    """What ``[key]``, ``[key_N]`` or ``[key[expr]]`` writes; None when it names nothing (left as text)."""
    name, index_text = m.group(1), m.group(2)
    index: int | None = None
    if index_text is not None:
        try:
            index = int(_number(_Expression(index_text, resolver, False).parse()))
        except (NotEvaluated, ValueError, TypeError, ZeroDivisionError, IndexError, re.error) as exc:
            filled.unevaluated.append((at, f"{m.group(0)}: {_reason(exc)}; element 0 was used"))
            index = 0
    try:
        value = resolver.get(name)
    except NotEvaluated:
        base, _, digits = name.rpartition("_")
        if not (base and digits.isdigit() and len(digits) < 4):
            return None  # not a placeholder: PrusaSlicer leaves such text as it is
        try:
            value = resolver.get(base)
        except NotEvaluated:
            return None
        index = int(digits)
    if isinstance(value, list):
        if not value:
            return ""
        value = value[min(index or 0, len(value) - 1)]
    return _show(value)


def _show(value: Value) -> str:
    """A value as the slicer writes it: numbers without a needless ".0"."""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        if value == int(value) and abs(value) < 1e15:
            return str(int(value))
        return f"{value:g}" if abs(value) >= 1e-4 else f"{value:f}".rstrip("0")
    if isinstance(value, list):
        return ",".join(_show(v) for v in value)
    return str(value)


def _truth(value: Value) -> bool:
    if isinstance(value, bool):
        return value
    if isinstance(value, float):
        return value != 0
    if isinstance(value, list):
        return bool(value)
    return value not in ("", "0", "false")


def _number(value: Value) -> float:
    if isinstance(value, bool):
        return 1.0 if value else 0.0
    if isinstance(value, float):
        return value
    if isinstance(value, list):
        if not value:
            raise ValueError("an empty list")
        return _number(value[0])
    return float(value)


_TOKEN = re.compile(
    r"""\s*(?:
    (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
    |(?P<string>"(?:[^"\\]|\\.)*")
    |(?P<regex>/(?:[^/\\]|\\.)*/)
    |(?P<name>[A-Za-z_][A-Za-z0-9_]*)
    |(?P<op>==|!=|<>|<=|>=|=~|!~|&&|\|\||[-+*/%<>()!,\[\]?:])
    )""",
    re.VERBOSE,
)
_BINARY = {
    "or": 1,
    "||": 1,
    "and": 2,
    "&&": 2,
    "==": 3,
    "!=": 3,
    "<>": 3,
    "<": 3,
    ">": 3,
    "<=": 3,
    ">=": 3,
    "=~": 3,
    "!~": 3,
    "+": 4,
    "-": 4,
    "*": 5,
    "/": 5,
    "%": 5,
}
MAX_TOKENS = 2000


class _Expression:
    """A macro's expression, evaluated as it is read (precedence climbing)."""

    def __init__(self, text: str, resolver: _Resolver, cura: bool) -> None:
        self.tokens: list[tuple[str, str]] = []
        pos = 0
        text = text.strip()
        if cura and "," in text and _IDENT.fullmatch(text.split(",", 1)[0].strip()):
            text = text.split(",", 1)[0]  # {material_print_temperature, 0}: extruder 0's setting
        while pos < len(text):
            m = _TOKEN.match(text, pos)
            if m is None or m.end() == pos:
                if text[pos:].strip() == "":
                    break
                raise NotEvaluated(f"cannot read {text[pos : pos + 20]!r}")
            kind = m.lastgroup or ""
            self.tokens.append((kind, m.group(kind)))
            if len(self.tokens) > MAX_TOKENS:
                raise NotEvaluated("too long an expression")
            pos = m.end()
        self.i = 0
        self.resolver = resolver

    def parse(self) -> Value:
        if not self.tokens:
            raise NotEvaluated("an empty macro")
        value = self.expression(0)
        if self.i != len(self.tokens):
            raise NotEvaluated(f"cannot read {self.tokens[self.i][1]!r}")
        return value

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self, text: str | None = None) -> tuple[str, str]:
        token = self.peek()
        if token is None or (text is not None and token[1] != text):
            raise NotEvaluated(f"expected {text!r}" if text else "an expression ends too early")
        self.i += 1
        return token

    def expression(self, level: int) -> Value:
        left = self.unary()
        while True:
            token = self.peek()
            if token is None:
                return left
            op = token[1]
            if op == "?" and level == 0:
                self.take()
                yes = self.expression(0)
                self.take(":")
                no = self.expression(0)
                left = yes if _truth(left) else no
                continue
            precedence = _BINARY.get(op)
            if precedence is None or precedence < level:
                return left
            self.take()
            right = self.expression(precedence + 1)
            left = _apply(op, left, right)

    def unary(self) -> Value:
        token = self.take()
        kind, text = token
        if text in ("-", "+"):
            number = _number(self.unary())
            return -number if text == "-" else number
        if text in ("!", "not"):
            return not _truth(self.unary())
        if text == "(":
            value = self.expression(0)
            self.take(")")
            return value
        if kind == "number":
            return float(text)
        if kind == "string":
            return re.sub(r"\\(.)", r"\1", text[1:-1])
        if kind == "regex":
            return text
        if kind == "name":
            if text in ("true", "false"):
                return text == "true"
            nxt = self.peek()
            if nxt is not None and nxt[1] == "(":
                return self.call(text)
            value = self.resolver.get(text)
            nxt = self.peek()
            if nxt is not None and nxt[1] == "[":
                self.take()
                index = int(_number(self.expression(0)))
                self.take("]")
                if isinstance(value, list):
                    if not value:
                        raise NotEvaluated(f"'{text}' has no elements")
                    return value[min(max(index, 0), len(value) - 1)]
            elif isinstance(value, list) and len(value) == 1:
                return value[0]
            return value
        raise NotEvaluated(f"cannot read {text!r}")

    def call(self, name: str) -> Value:
        self.take("(")
        args: list[Value] = []
        while True:
            token = self.peek()
            if token is not None and token[1] == ")":
                break
            args.append(self.expression(0))
            token = self.peek()
            if token is not None and token[1] == ",":
                self.take()
                continue
            break
        self.take(")")
        if name == "min" and args:
            return min(_number(a) for a in args)
        if name == "max" and args:
            return max(_number(a) for a in args)
        if name == "int" and len(args) == 1:
            return float(math.trunc(_number(args[0])))
        if name == "round" and len(args) == 1:
            return float(math.floor(_number(args[0]) + 0.5))
        if name in ("digits", "zdigits") and len(args) in (2, 3):
            decimals = int(_number(args[2])) if len(args) == 3 else 0
            width = int(_number(args[1]))
            if not (0 <= width <= 30 and 0 <= decimals <= 30):
                raise NotEvaluated(f"{name}() with {width} digits")
            number = _number(args[0])
            return f"{number:0{width}.{decimals}f}" if name == "zdigits" else f"{number:{width}.{decimals}f}"
        if name == "is_nil" and len(args) == 1:
            return False
        raise NotEvaluated(f"the function {name}() is not evaluated by gclint")


def _apply(op: str, left: Value, right: Value) -> Value:
    if op in ("or", "||"):
        return _truth(left) or _truth(right)
    if op in ("and", "&&"):
        return _truth(left) and _truth(right)
    if op in ("=~", "!~"):
        pattern = str(right)
        if pattern.startswith("/") and pattern.endswith("/") and len(pattern) >= 2:
            pattern = pattern[1:-1]
        if len(pattern) > 200:
            raise NotEvaluated("too long a regular expression")
        found = re.fullmatch(pattern, str(left)) is not None
        return found if op == "=~" else not found
    if op in ("==", "!=", "<>"):
        if isinstance(left, str) or isinstance(right, str):
            same = str(left) == str(right)
        else:
            same = _number(left) == _number(right)
        return same if op == "==" else not same
    if op in ("<", ">", "<=", ">="):
        a, b = _number(left), _number(right)
        return {"<": a < b, ">": a > b, "<=": a <= b, ">=": a >= b}[op]
    if op == "+" and (isinstance(left, str) or isinstance(right, str)):
        return _show(left) + _show(right)
    a, b = _number(left), _number(right)
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if op == "/":
        return a / b
    return math.fmod(a, b)
