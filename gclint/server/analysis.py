"""What the language server asks of gclint, without the protocol: the options for a document (client
settings over the configuration file found from the document's folder, as ``gclint check`` does with
its command line), a check that can be abandoned half-way when the text changes again, and the
explanation of the command under the cursor with the machine state the job has at that line.

Nothing here imports the protocol library: the functions are tested directly.
"""

from __future__ import annotations

import re
import threading
from collections.abc import Iterator
from dataclasses import dataclass, replace

from gclint import dialects
from gclint.config import ConfigError, clear_found, parse_heads
from gclint.engine import FileResult, Options
from gclint.explain import Explainer, Explanation
from gclint.fixes import plan_fixes
from gclint.machine.profiles import UnknownPrinter, get_profile
from gclint.machine.state import MachineState
from gclint.rules.base import Finding
from gclint.runner import linter_for, options_for
from gclint.server.text import Snapshot, clean_surrogates
from gclint.syntax.fastpath import PLAIN_MOVE
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line
from gclint.syntax.source import Source, SourceError

# -- settings from the client ---------------------------------------------------------------------------

SETTING_KEYS = ("dialect", "printer", "select", "ignore", "extendSelect", "loaded")
# Keys an editor extension keeps in the same settings section for itself (VS Code sends the whole
# "gclint" section): not gclint's business, not worth a warning.
CLIENT_KEYS = frozenset({"path", "trace", "enable", "args", "command", "interpreter"})


@dataclass(frozen=True)
class Settings:
    """What the editor's settings override (None: not set, the configuration file or default applies)."""

    dialect: str | None = None
    printer: str | None = None
    select: tuple[str, ...] | None = None
    ignore: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] | None = None
    loaded: frozenset[int] | None = None

    def overrides(self) -> dict:
        """The ``Options`` fields these settings set (applied over the configuration file)."""
        out: dict = {}
        if self.dialect is not None:
            out["dialect"] = self.dialect
        if self.printer is not None:
            out["printer"] = self.printer
        if self.select is not None:
            out["select"] = list(self.select)
        if self.ignore is not None:
            out["ignore"] = list(self.ignore)
        if self.extend_select is not None:
            out["extend_select"] = list(self.extend_select)
        if self.loaded is not None:
            out["loaded"] = self.loaded
        return out


def _codes(value: object, key: str) -> tuple[str, ...]:
    """Rule selectors, checked as ``gclint check --select`` checks them: one that matches no rule makes
    the whole setting wrong (a ``select`` of a typo alone would turn every rule off in silence)."""
    from gclint.rules.base import RuleError, resolve_selectors

    if isinstance(value, str):
        items = re.split(r"[,\s]+", value)
    elif isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
        items = list(value)
    else:
        raise ValueError(f'\'{key}\' must be a list of rule codes or prefixes such as ["HY", "SX002"]')
    codes = [v.strip().upper() for v in items if v.strip()]
    try:
        return tuple(resolve_selectors(codes, f"'{key}': "))
    except RuleError as exc:  # a plugin that does not load: the codes cannot be checked
        raise ValueError(f"'{key}': {exc}") from None


def parse_settings(raw: object) -> tuple[Settings, list[str]]:
    """Client settings (``initializationOptions``, ``workspace/didChangeConfiguration`` or
    ``workspace/configuration``) -> ``Settings`` and a list of problems, one line each.

    Accepted shapes: ``{"dialect": ...}``, ``{"gclint": {...}}`` and ``{"settings": {...}}``; keys may be
    camelCase or kebab-case; a bad value is reported and ignored, never fatal."""
    problems: list[str] = []
    if raw is None:
        return Settings(), problems
    if not isinstance(raw, dict):
        return Settings(), [f"settings: expected an object, got {type(raw).__name__}"]
    for wrapper in ("gclint", "settings"):
        inner = raw.get(wrapper)
        if isinstance(inner, dict):
            raw = inner
            break
    values: dict = {}
    for key, value in raw.items():
        name = re.sub(r"[-_]([a-z])", lambda m: m.group(1).upper(), str(key))
        if value is None or value == "" or value == [] or name in CLIENT_KEYS:
            continue  # not set (editors send empty values for settings left at their default)
        try:
            if name == "dialect":
                if not isinstance(value, str):
                    raise ValueError("'dialect' must be a string")
                values["dialect"] = "auto" if value.lower() == "auto" else dialects.get(value).name
            elif name == "printer" and str(value).lower() == "auto":
                continue  # the configuration file's or the default model
            elif name == "printer":
                values["printer"] = get_profile(str(value)).name
            elif name in ("select", "ignore"):
                values[name] = _codes(value, name)
            elif name == "extendSelect":
                values["extend_select"] = _codes(value, "extendSelect")
            elif name == "loaded":
                values["loaded"] = parse_heads(value, "settings: 'loaded'")
            else:
                problems.append(f"settings: unknown key {key!r} ignored (known: {', '.join(SETTING_KEYS)})")
        except (ValueError, ConfigError, UnknownPrinter, dialects.UnknownDialect) as exc:
            if name in ("select", "ignore", "extendSelect"):
                problems.append(
                    f"settings: {exc}; the whole '{key}' setting is ignored"
                    " (the configuration file's or the default applies)"
                )
            else:
                problems.append(f"settings: {exc}; ignored")
    return Settings(**values), problems


def document_options(path: str | None, settings: Settings) -> tuple[Options, str | None]:
    """The options for a document at ``path`` (None for an unsaved document): the configuration file
    found upward from its folder, then the client's settings.  Returns the options and a problem with
    the configuration file (the file is then left out), if any."""
    overrides = settings.overrides()
    if path is None:
        return replace(Options(), **overrides), None
    clear_found()  # a configuration file written since the last check is seen
    try:
        return options_for(path, Options(), overrides, None), None
    except ConfigError as exc:
        return replace(Options(), **overrides), str(exc)
    except OSError as exc:  # an unreadable folder on the way up
        return replace(Options(), **overrides), f"{path}: configuration not read: {exc.strerror or exc}"


def security_off(options: Options) -> str | None:
    """One line when the options switch security rules off, or None.  A configuration found beside the
    document cannot (gclint.trust): the editor's settings did, and the user is told that those findings
    are not shown rather than left to think the job is clean."""
    from gclint.rules.base import all_rules
    from gclint.trust import SECURITY, selected

    on = set(selected(options))
    off = [code for code, rule in all_rules().items() if code.startswith(SECURITY) and rule.default_enabled]
    off = [code for code in off if code not in on]
    if not off:
        return None
    what = f"security rule{'s' if len(off) != 1 else ''} {', '.join(off)}"
    return f"the editor's settings (select/ignore) switch off {what}: their findings are not shown"


# -- checking -------------------------------------------------------------------------------------------


class Cancelled(Exception):
    """The text changed again: the check was abandoned."""


class _CancellableSource(Source):
    """A text source that stops between chunks (about a megabyte of text) once ``cancel`` is set."""

    cancel: threading.Event | None = None

    def blocks(self) -> Iterator[str | list[tuple[str, str]]]:  # (chunks() reads blocks() too)
        cancel = self.cancel
        for block in super().blocks():
            if cancel is not None and cancel.is_set():
                raise Cancelled()
            yield block


def check_text(text: str, path: str, options: Options, cancel: threading.Event | None = None) -> FileResult:
    """Check the text of a document as ``gclint check`` checks a file (the same engine, rules,
    directives and suppressions).  Raises ``Cancelled`` when ``cancel`` is set before the end; any other
    failure is a result with an ``error``, never an exception."""
    text = clean_surrogates(text)
    try:
        linter = linter_for(options)
        source = _CancellableSource.from_text(text, path, cut_long_lines=True)  # checking, not rewriting
        source.cancel = cancel
        result = linter.check_source(source)
    except Cancelled:
        raise
    except SourceError as exc:  # (binary text, not G-code: an error result, as gclint check reports it)
        return FileResult(path, error=str(exc).splitlines()[0][:300] if str(exc) else type(exc).__name__)
    except Exception as exc:
        detail = f"internal error ({type(exc).__name__}: {exc})"
        return FileResult(path, error=detail.splitlines()[0][:300] if detail else type(exc).__name__)
    if cancel is not None and cancel.is_set():
        raise Cancelled()
    return result


def safe_fix_set(
    result: FileResult, text: str, options: Options, cancel: threading.Event | None = None
) -> list[Finding]:
    """The findings whose fixes "fix all" applies: those ``gclint check --fix`` would keep (safe fixes
    after which the text is checked again, and none that brings a new finding)."""
    if not any(f.fix is not None and f.fix.safe for f in result.findings):
        return []
    try:
        plan = plan_fixes(result, linter_for(options), lambda: Source.from_text(clean_surrogates(text), result.path))
    except Exception:  # a fix that cannot be checked is not offered
        return []
    return plan.fixes


# -- hover: explain the command under the cursor ---------------------------------------------------------

HOVER_LINE_LIMIT = 100_000  # longer lines are not explained (a 100 MB line must not stall a hover)


@dataclass
class HoverTarget:
    """The command under the cursor, decoded, and the part of the line the hover covers."""

    explanation: Explanation
    word: str | None  # the exact text of the word under the cursor (None: the command as a whole)
    start: int  # 1-based character columns of the hovered word (end exclusive)
    end: int
    dialect: dialects.Dialect


def _bom(line: str, index: int) -> int:
    return 1 if index == 0 and line.startswith("\ufeff") else 0


def explain_at(
    snapshot: Snapshot,
    line_index: int,
    char_index: int,
    dialect: dialects.Dialect,
    loaded: frozenset[int] | None = None,
    cancel: threading.Event | None = None,
) -> HoverTarget | None:
    """Decode the command at ``char_index`` (0-based) of line ``line_index`` (0-based), in ``dialect``,
    with the machine state the lines before it leave (replayed through the same interpreter the
    linter uses).  None when the cursor is not on a command."""
    if not 0 <= line_index < snapshot.line_count:
        return None
    target_raw = snapshot.line(line_index)
    if len(target_raw) > HOVER_LINE_LIMIT:
        return None
    shift = _bom(target_raw, line_index)
    target_raw = clean_surrogates(target_raw[shift:])
    column = char_index - shift + 1
    parsed = parse_line(target_raw)
    if not parsed.commands:
        return None
    for comment in parsed.comments:
        if comment.column <= column < comment.end_column:
            return None
    chosen = None
    for index, cmd in enumerate(parsed.commands):
        if cmd.column <= column:
            chosen = index
    if chosen is None:
        return None

    explainer = Explainer(dialect, MachineState(loaded_heads=loaded))
    _replay(snapshot, line_index, explainer, cancel)
    line = Line(line_index + 1, target_raw, "\n", parsed)
    explanations = explainer.explain_line(line)
    if chosen >= len(explanations):
        return None
    cmd = parsed.commands[chosen]
    word_node = None
    for node in cmd.nodes():
        if node.column <= column < node.end_column:
            word_node = node
            break
    span = word_node if word_node is not None else cmd.word
    if span is not None:
        start, end = span.column, span.end_column
    else:
        start, end = cmd.column, cmd.column + 1
    word = word_node.text.strip() if word_node is not None and word_node is not cmd.word else None
    return HoverTarget(explanations[chosen], word, start + shift, end + shift, dialect)


def _replay(snapshot: Snapshot, stop: int, explainer: Explainer, cancel: threading.Event | None) -> None:
    """Apply lines ``0..stop-1`` to the explainer's state, as the linter does (plain moves included)."""
    interpreter = explainer.interpreter
    state = explainer.state
    plain_match = PLAIN_MOVE.fullmatch
    plain_move = interpreter.plain_move
    for index in range(stop):
        if cancel is not None and not index % 4096 and cancel.is_set():
            raise Cancelled()
        raw = snapshot.line(index)
        if index == 0 and raw.startswith("\ufeff"):
            raw = raw[1:]
        number = index + 1
        if raw[:1] == "G":
            m = plain_match(raw)
            if m is not None:
                digit, f_first, x, y, z, e, f = m.groups()
                plain_move("G" + digit, number, x, y, z, e, f if f is not None else f_first)
                continue
        parsed = parse_line(clean_surrogates(raw))
        if not parsed.commands:
            continue
        line = Line(number, raw, "\n", parsed)
        state.line_number = number
        for cmd in parsed.commands:
            interpreter.apply(cmd, line)
