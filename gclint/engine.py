"""Lint one file: read lines, parse, dispatch commands to rules, track the machine state.

One pass, one line at a time; nothing but findings is kept, so memory does not grow with the file.
``Linter`` checks files; ``Linter._run`` is the pass over one file, in steps on a ``_FileRun``: the
file's rules (``_make_rules``), their hooks (``_Hooks``) and dispatch (``_Dispatch``: built per command
code the first time the code is seen, so a ``G1`` line only touches the rules that listen to ``G1``, and
the G0/G1 move listeners rules declared, ``rules.base.MoveListener``), the plain-move route and the runs
applied at once (``runs``, gclint/runs.py), the loop (``read``, ``read_line``) and the rules' ``finish``.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable
from copy import copy
from dataclasses import dataclass, field, replace
from itertools import chain

from gclint import dialects, firmware, globs
from gclint.context import Context, infer_source
from gclint.filecontext import MAX_FINDINGS, PER_LINE, SOURCE_LIMIT, FileContext
from gclint.machine.interpreter import Interpreter
from gclint.machine.profiles import DEFAULT_PROFILE, get_profile
from gclint.noqa import INLINE_UNSUPPRESSIBLE, NO_CODES
from gclint.options import Options
from gclint.rules.base import ANY_T, Finding, MoveListener, Rule, Severity, all_rules, matches, select_rules
from gclint.runs import CodeLines, Runs, combined, comment_tests, rule_run_filters
from gclint.syntax.build import TEXT_CODES
from gclint.syntax.fastpath import PLAIN_MOVE, run_pattern
from gclint.syntax.nodes import EXTENDED, GCODE, Command, Line
from gclint.syntax.parse import PARSE_LIMIT, parse_line
from gclint.syntax.sniff import not_gcode_reason
from gclint.syntax.source import NotGcode, Source, SourceError

FILE_WRITES = "SC005"  # the rule ``allow-file-writes`` lets files write the printer's files past

# Options and FileContext live in their own modules (gclint.options, gclint.filecontext), so that the rules
# can name the context they report into without importing the engine; they are importable from here too.

__all__ = [
    "MAX_FINDINGS",
    "PER_LINE",
    "SOURCE_LIMIT",
    "FileContext",
    "FileResult",
    "Linter",
    "Options",
    "check_text",
]


@dataclass
class FileResult:
    """What checking one file produced."""

    path: str
    findings: list[Finding] = field(default_factory=list)
    dialect: str | None = None
    dialect_reason: str = ""
    lines: int = 0
    error: str | None = None  # the file could not be read (exit code 2)
    context: Context | None = None  # what the file was read as, and why (gclint.context)
    digest: str | None = None  # SHA-256 of the bytes checked (Source.sha256), for --fix and the cache
    not_gcode: bool = False  # the error says the file is something else (a walk skips it with a note)
    notes: list[str] = field(default_factory=list)  # what a person should know of how it was checked (a profile's)
    profile: bool = False  # a slicer profile (gclint.profiles): its findings point into the profile, no fix or noqa

    @classmethod
    def unreadable(cls, path: str, exc: SourceError) -> FileResult:
        """The result for a file that could not be read (``exc`` says why, in one line)."""
        return cls(path, error=str(exc), not_gcode=isinstance(exc, NotGcode))

    @property
    def read_as(self) -> str:
        """What the file was checked as: ``hyrel v5, printer 30m (assumed)``, ``marlin``."""
        if self.context is not None:
            return self.context.label()
        return self.dialect or ""

    def counts(self) -> dict[str, int]:
        out = {"error": 0, "warning": 0, "info": 0}
        for f in self.findings:
            out[f.severity.label] += 1
        return out


class Linter:
    """Checks files with one set of options.  Reusable across files (rules are instantiated per file)."""

    def __init__(self, options: Options | None = None) -> None:
        self.options = options or Options()
        select = self.options.select
        if select is not None or self.options.extend_select:
            base = select if select is not None else [r.code for r in all_rules().values() if r.default_enabled]
            select = list(base) + list(self.options.extend_select)
        self.rule_classes = select_rules(all_rules().values(), select, self.options.ignore)
        if self.options.printer is not None:
            get_profile(self.options.printer)  # an unknown model fails here, once, not per file
        if self.options.dialect != "auto":
            dialects.get(self.options.dialect)

    # -- entry points ---------------------------------------------------------------------------------

    def check_path(self, path: str) -> FileResult:
        try:
            source = Source.open(path, digest=True, cut_long_lines=True)
        except SourceError as exc:
            return FileResult.unreadable(path, exc)
        return self.check_source(source)

    def check_text(self, text: str, path: str = "<text>") -> FileResult:
        try:
            source = Source.from_text(text, path, cut_long_lines=True)
        except SourceError as exc:  # binary text (NUL bytes): a result with an error, as for check_path
            return FileResult.unreadable(path, exc)
        return self.check_source(source)

    def check_source(self, source: Source, *, sniff: bool = True) -> FileResult:
        """Check ``source``.  ``sniff=False`` reads it even when its head says it is not G-code (the
        security rules read such files anyway: gclint.notgcode)."""
        path = source.display
        reason = not_gcode_reason(source.head_text(8192)) if sniff else None
        if reason is not None:
            source.close()
            return FileResult(path, error=f"{path}: {reason}", not_gcode=True)
        ctx, result = self.prepare(source)
        try:
            self._run(source, ctx, result)
        except SourceError as exc:
            result.error = str(exc)
            return result
        finally:
            ctx.release()
        result.digest = source.sha256
        ignored = self.per_file_ignores(path)
        if ctx.may_suppress() or ignored:
            result.findings = [
                f for f in ctx.findings if not ctx.suppressed(f) and not (ignored and matches(f.code, ignored))
            ]
        else:
            result.findings = ctx.findings
        ctx.findings = []
        if source.byte_view is not None and source.byte_view.lines:
            result.findings += self._byte_view_findings(path, source.byte_view.lines, ignored)
        self._check_suppressions(ctx, result)
        if result.context is not None and result.context.assumed:
            _as_assumed(result.findings, result.context)
        result.findings.sort(key=Finding.sort_key)
        return result

    def _byte_view_findings(self, path: str, lines: list[tuple[int, str]], ignored: tuple[str, ...]) -> list[Finding]:
        """The security findings of a UTF-16/32 file's lines as a firmware that reads bytes sees them
        (``Source.byte_view``), on line 1 of the file, each naming the line of that view it is on."""
        codes = [cls.code for cls in self.rule_classes if cls.code.startswith("SC") and not matches(cls.code, ignored)]
        if not codes:
            return []
        view = Linter(
            Options(select=codes, severity=self.options.severity, spindle_max_rpm=self.options.spindle_max_rpm)
        )
        numbers = [number for number, _ in lines]
        checked = view.check_text("\n".join(text for _, text in lines) + "\n", path)
        return [
            replace(
                f,
                line=1,
                column=1,
                end_column=None,
                fix=None,
                message=f"read as bytes (as a firmware that ignores the byte order mark does), line "
                f"{numbers[f.line - 1] if f.line <= len(numbers) else '?'}: {f.message}",
            )
            for f in checked.findings
            if f.code.startswith("SC")
        ]

    def _check_suppressions(self, ctx: FileContext, result: FileResult) -> None:
        """A ``noqa`` or ``gclint: disable`` naming no rule is an error (exit 2, with what was meant); with
        SX008 selected, a ``noqa`` code that suppressed nothing is a finding."""
        from gclint.rules.base import UnknownSelector, resolve_selectors

        # (lazily: a job may have a million noqa comments)
        named = chain(ctx.noqa.items(), ((line, codes) for line, _, codes in ctx.directives))
        problems: list[str] = []
        verdicts: dict[tuple[str, ...], str | None] = {}  # a list repeated on many lines is resolved once
        for line, codes in named:
            if codes not in verdicts:
                if NO_CODES in codes:
                    verdicts[codes] = "a 'noqa:' or 'disable=' with no rule code after it"
                else:
                    try:
                        resolve_selectors(c for c in codes if c != "ALL")
                        verdicts[codes] = None
                    except UnknownSelector as exc:
                        verdicts[codes] = f"a noqa or disable names an {exc}"
            problem = verdicts[codes]
            if problem is not None:
                problems.append(f"{result.path}:{line}: {problem}")
                if len(problems) > 5:
                    break
        if problems:  # every one in one line: the job's own comments are a usage error, as --select HY999 is
            message = "; ".join(problems[:5]) + (" (and more)" if len(problems) > 5 else "")
            result.error = message if result.error is None else f"{result.error}; {message}"
        if "SX008" not in ctx.enabled_codes:
            return
        from gclint.rules.syntax import UnusedNoqa

        more = 0  # past MAX_FINDINGS, counted on the last one listed (as FileContext.add does)
        for line, codes in ctx.noqa.items():  # (in line order)
            unused = [c for c in codes if (line, c) not in ctx.noqa_used]
            if unused:
                if len(result.findings) >= MAX_FINDINGS and result.findings[-1].code == UnusedNoqa.code:
                    more += 1
                    continue
                what = "noqa suppresses nothing here" if unused == ["ALL"] else f"unused noqa: {', '.join(unused)}"
                if any(c.startswith(INLINE_UNSUPPRESSIBLE) for c in unused):
                    what += " (a job cannot silence security findings)"
                result.findings.append(
                    Finding(
                        result.path,
                        line,
                        1,
                        UnusedNoqa.code,
                        ctx.severity_of(UnusedNoqa.code, UnusedNoqa.severity),
                        what,
                        name=UnusedNoqa.name,
                    )
                )
        if more:
            last = result.findings[-1]
            last.message += f" (and {more:,} more {last.code} findings later in the file, not listed)"

    def context_of(self, source: Source) -> Context:
        """What ``source`` is checked as (its head decides; the stream is not consumed)."""
        options = self.options
        return infer_source(
            source,
            dialect=options.dialect,
            dialect_origin=options.dialect_origin,
            printer=options.printer,
            printer_origin=options.printer_origin,
            flavor=options.flavor,
            flavor_origin=options.flavor_origin,
            env_flavor=options.env_flavor,
            machine_codes=tuple(options.machine_codes),
        )

    def prepare(self, source: Source) -> tuple[FileContext, FileResult]:
        """The per-file world for ``source`` and its (empty) result, in the file's context."""
        context = self.context_of(source)
        dialect = dialects.reading(context.dialect, context.flavor)  # (the firmware's own meanings, if any)
        profile = get_profile(context.printer or DEFAULT_PROFILE)
        result = FileResult(source.display, dialect=dialect.name, dialect_reason=context.why(), context=context)
        return FileContext(source.display, dialect, profile, self.options, context), result

    def per_file_ignores(self, path: str) -> tuple[str, ...]:
        """The codes ``per-file-ignores`` switches off for ``path``, and SC005 where ``allow-file-writes``
        names it: patterns (ruff's globs, gclint.globs) are read relative to the folder of the configuration
        file that names them."""
        if not self.options.per_file_ignores and not self.options.allow_file_writes:
            return ()
        config = self.options.config_path
        rel = globs.relative(path, os.path.dirname(os.path.abspath(config)) if config else os.getcwd())
        out: list[str] = []
        for pattern, codes in self.options.per_file_ignores.items():
            if globs.matches(pattern, rel):
                out.extend(c.upper() for c in codes)
        if any(globs.matches(pattern, rel) for pattern in self.options.allow_file_writes):
            out.append(FILE_WRITES)
        return tuple(out)

    # -- the loop --------------------------------------------------------------------------------------

    def _run(self, source: Source, ctx: FileContext, result: FileResult) -> None:
        """Check ``source``: make the file's rules, their hooks and dispatch (``_FileRun``), open the
        plain-move route and the runs where no rule would look at them, read the lines the runs leave,
        and finish the rules."""
        run = _FileRun(self, ctx, result)
        runs = run.runs(source)
        run.read(runs.lines(source, run.may_apply))
        result.lines = ctx.state.line_number = runs.total
        run.finish()

    plain_moves_enabled = True  # the tests switch this off to compare

    @staticmethod
    def _plain_arcs(build: Callable, interpreter: Interpreter) -> bool:
        """Whether runs take arcs (fastpath.run_pattern: G2/G3 with X Y Z I J E F) in this file: the
        interpreter's own arc handler applies them, and every rule that listens to G2/G3 (for letters those
        arcs may carry) has a run filter (``rule_run_filters`` asks it about the arcs of runs too)."""
        for code in ("G2", "G3"):
            always, filtered, _ = build(Command(code, GCODE, 1, {}))
            if not interpreter.moves_plainly(code):
                return False
            listening = (*always, *(handler for handler, letters in filtered if not letters.isdisjoint("XYZIJEF")))
            if any(getattr(handler.__self__, "run_filter", None) is None for handler in listening):
                return False
        return True

    def _plain_moves(
        self, build: Callable, interpreter: Interpreter, line_hooks: tuple
    ) -> dict[str, tuple[str, tuple[Callable[..., bool], ...]]] | None:
        """How plain G0/G1 lines may skip the tree in this file: ``{"0": ("G0", filters), "1": ...}``, or
        None when they may not.

        A rule that listens to every G0/G1 allows the route by having a ``plain_filter(mode, x, y, z, e,
        f)`` that says (True) when a plain move needs its ``check``, a move listener by its ``wants_plain``;
        rules that listen only for letters a plain move never carries (S, H, A...) do not count."""
        if not self.plain_moves_enabled or line_hooks:
            return None
        out = {}
        for code in ("G0", "G1"):
            always, filtered, _ = build(Command(code, GCODE, 1, {}))
            if any(not letters.isdisjoint("XYZEF") for _, letters in filtered):
                return None
            if not interpreter.moves_plainly(code):
                return None
            found = [_plain_filter(handler.__self__) for handler in always]
            filters = tuple(f for f in found if f is not None)
            if len(filters) != len(found):
                return None
            out[code[1]] = (code, filters)
        return out


# -- one file's run ------------------------------------------------------------------------------------------
#
# Linter._run is a pipeline: ``_FileRun`` makes the file's rules and gathers their hooks (``_Hooks``) and
# dispatch (``_Dispatch``), decides the plain-move route and builds the runs (``runs``), then ``read`` is the
# loop over the lines the runs leave, and ``finish`` ends the rules.  ``disable`` is what a failing rule
# takes with it.  Every rule call is guarded (a "try" costs nothing until something raises, Python 3.11+).

_Handler = Callable[[Line, Command], None]
# code -> (handlers always called, (handler, letters) called when a letter is present, the interpreter's
# function for the code)
_Entry = tuple[tuple[_Handler, ...], tuple[tuple[_Handler, frozenset[str]], ...], Callable[[Command, Line], None]]
_Plain = dict[str, tuple[str, tuple[Callable[..., bool], ...]]]  # (Linter._plain_moves)


class _Hooks:
    """The rules' hooks other than their codes, by kind: tuples of bound methods (a rule that fails is taken
    out by making new tuples, ``without``: a loop over the old one goes on with the other rules' hooks)."""

    __slots__ = ("line", "long", "after_end", "start", "numbered", "issue", "ignored", "comment", "view", "cr")

    def __init__(self, rules: list[Rule]) -> None:
        self.line = tuple(r.check_line for r in rules if r.on_line)
        self.long = tuple((r.on_line_longer_than, r.check_line) for r in rules if r.on_line_longer_than is not None)
        self.after_end = tuple(r.check_line for r in rules if r.on_line_after_m30)
        self.start = tuple((r.on_line_starting_with, r.check_line) for r in rules if r.on_line_starting_with)
        self.numbered = tuple(r.check_line for r in rules if r.on_numbered)
        self.issue = tuple(r.check_issues for r in rules if r.on_issue)
        self.ignored = tuple(r.check_ignored for r in rules if r.on_ignored_command)
        self.comment = tuple(r.check_comment for r in rules if r.on_comment)
        # (security rules: lines a firmware edits before it reads them, read again as it does; rules/security/views.py)
        views: dict = {}  # (one search per line for the rules that share a pattern)
        for r in rules:
            if r.on_line_matching is not None:
                views.setdefault(r.on_line_matching.search, []).append(r.check_view)
        self.view = tuple((wants, tuple(hooks)) for wants, hooks in views.items())
        # (lines ending in a bare carriage return, read with the next as LinuxCNC reads them: one line)
        self.cr = tuple(r.check_joined for r in rules if getattr(r, "on_bare_cr", False))

    def without(self, gone: list) -> _Hooks:
        """These hooks but those of the rules in ``gone``."""

        def keep(hooks: Iterable[Callable]) -> tuple:
            return tuple(h for h in hooks if getattr(h, "__self__", None) not in gone)

        out = copy(self)
        for kind in ("line", "after_end", "numbered", "issue", "ignored", "comment", "cr"):
            setattr(out, kind, keep(getattr(self, kind)))
        out.long = tuple((n, h) for n, h in self.long if getattr(h, "__self__", None) not in gone)
        out.start = tuple((c, h) for c, h in self.start if getattr(h, "__self__", None) not in gone)
        out.view = tuple((wants, keep(hooks)) for wants, hooks in self.view)
        return out


class _Dispatch:
    """Which rules' ``check`` a command goes to: an entry per code (``_Entry``), built the first time the code
    is seen (``build``), so that a ``G1`` line only touches the rules that listen to ``G1``.  The G0/G1 move
    listeners (``MoveListener``) stand where their first member stands among the rules."""

    def __init__(self, rules: list[Rule], listeners: list[MoveListener], ctx: FileContext) -> None:
        self.by_code: dict[str, list[_Handler]] = {}
        self.any_t: list[_Handler] = []
        self.unknown: list[_Handler] = []
        for r in rules:
            for c in r.codes:
                if c == ANY_T:
                    self.any_t.append(r.check)
                else:
                    self.by_code.setdefault(c, []).append(r.check)
            if r.on_unknown_code:
                self.unknown.append(r.check)
            for listener in listeners:
                if listener.members[0] is r:
                    self.by_code.setdefault("G0", []).append(listener.move)
                    self.by_code.setdefault("G1", []).append(listener.move)
        self.dialect, self.interpreter = ctx.dialect, ctx.interpreter
        # a Marlin-flavour file is read as Klipper's too unless its firmware is known to be another one
        flavor = ctx.context.flavor if ctx.context is not None else None
        self.no_extended = flavor is not None and not firmware.get(flavor).extended_commands
        self.table: dict[str | None, _Entry] = {}  # (the same dict all along: the loop holds its ``get``)

    def build(self, cmd: Command) -> _Entry:
        """The entry of ``cmd``'s code (kept for the next command with it)."""
        code, dialect = cmd.code, self.dialect
        handlers = list(self.by_code.get(code, ())) if code is not None else []
        if code is not None and cmd.kind == GCODE and code[0] == "T":
            handlers.extend(self.any_t)
        if not dialect.accepts(cmd.kind, code) or (
            self.no_extended and cmd.kind == EXTENDED and not (code is not None and dialect.knows(code))
        ):  # (Prusa's MMU "Tx" and "Tc" read as command words, and are Marlin's)
            handlers.extend(self.unknown)
        always, filtered = [], []
        for handler in handlers:
            # (a command with no code, words alone, reaches a rule only as an unknown code: every such rule
            # looks at it; trigger_letters takes a code; a move listener wants every G0/G1)
            owner = getattr(handler, "__self__")  # noqa: B009 (typed as a plain callable)
            letters = owner.trigger_letters(code) if code is not None and isinstance(owner, Rule) else None
            if letters is None:
                always.append(handler)
            elif letters:
                filtered.append((handler, letters))
        out = (tuple(always), tuple(filtered), self.interpreter.handler_for(cmd))
        self.table[code] = out
        return out

    def without(self, gone: list) -> None:
        """Stop calling the rules (and listeners) in ``gone``: the entries are built again."""
        for code, handlers in list(self.by_code.items()):
            self.by_code[code] = [h for h in handlers if getattr(h, "__self__", None) not in gone]
        self.any_t[:] = [h for h in self.any_t if getattr(h, "__self__", None) not in gone]
        self.unknown[:] = [h for h in self.unknown if getattr(h, "__self__", None) not in gone]
        self.table.clear()


class _FileRun:
    """One file's check in progress (``Linter._run``): its rules, their hooks and dispatch, the plain-move
    route (``plain``: None when closed), and the lines joined across bare carriage returns."""

    def __init__(self, linter: Linter, ctx: FileContext, result: FileResult) -> None:
        self.linter, self.ctx, self.result = linter, ctx, result
        self.state, self.interpreter = ctx.state, ctx.interpreter
        self.rules = _make_rules(linter.rule_classes, ctx, result)
        self.hooks = _Hooks(self.rules)
        # the G0/G1 listeners rules declared (FileContext.move_listener)
        self.listeners = _live_listeners(ctx.move_listeners, self.rules)
        self.dispatch = _Dispatch(self.rules, self.listeners, ctx)
        self.shortest_long = min((n for n, _ in self.hooks.long), default=None)  # (the shortest line a hook wants)
        self.long_limit = self.shortest_long if self.shortest_long is not None else 1 << 62
        self.first_chars: frozenset[str] = frozenset().union(*(chars for chars, _ in self.hooks.start))
        self.view_patterns = tuple(wants for wants, _ in self.hooks.view)
        self.plain: _Plain | None = None  # (set by ``runs``)
        self.run_filters: tuple | None = None
        self.joined = _Joined()  # (lines ending in a bare carriage return: hooks.cr)

    def disable(self, hook: Callable, exc: Exception, line_number: int | None) -> None:
        """A rule raised: say so once (naming the rule, the file and the line), drop the rule for the rest
        of this file and go on."""
        gone = _failed(getattr(hook, "__self__", None), exc, self.rules, self.listeners)
        if not gone:  # pragma: no cover - hooks are bound methods of rules and listeners
            raise exc
        _rule_failed(self.result, type(gone[0]), exc, line_number)
        self.hooks = self.hooks.without(gone)
        self.dispatch.without(gone)
        self.plain = None  # (conservative: the plain-move route stays off for the rest of the file)

    def runs(self, source: Source) -> Runs:
        """Open the plain-move route where no rule would look at plain moves, and make the file's runs.

        Plain moves ("G1 X10 Y20 E0.5", most lines of a job) skip the tree when no rule would look at them:
        no rule listens to the code unless the line has a letter a plain move never carries, and the
        interpreter's own motion handler applies it.  Runs of plain moves, comment lines, empty lines and
        (when no rule looks at them either) arcs are applied at once (gclint.runs).  tests/test_plain_moves.py
        checks that the findings are the same with and without them on every corpus file."""
        linter, build, interpreter = self.linter, self.dispatch.build, self.interpreter
        if "G" not in self.first_chars:
            self.plain = linter._plain_moves(build, interpreter, self.hooks.line)
        plain = self.plain is not None
        arcs = plain and linter._plain_arcs(build, interpreter)
        self.run_filters = rule_run_filters(build, arcs) if plain else None
        view_patterns, first_chars = self.view_patterns, self.first_chars
        return Runs(
            run_pattern(arcs, self.shortest_long)
            if plain and (RUNS_IN_SMALL_FILES or not source.head_is_whole)
            else None,
            interpreter,
            comment_tests(self.rules, view_patterns),
            together=all(wants.__self__.flags & re.MULTILINE for wants in view_patterns),
            every_comment=";" in first_chars,
            longest=self.shortest_long,
            alone=combined(self.run_filters) if self.run_filters else None,
            codes=CodeLines(self.effect_of),
            add=self.ctx.add_on,
        )

    def may_apply(self) -> bool:
        """Whether runs may be applied at once now (a rule's plain filter without a run filter, and the hooks
        after the end of the job, would look at the moves)."""
        return not (self.plain is None or self.run_filters is None or (self.hooks.after_end and self.state.after_m30))

    def effect_of(self, raw: str) -> tuple[tuple, ...] | None:
        """What an M-code line of a run does that the interpreter has nothing to do with, no view pattern is
        about, and only pure rules look at: their findings on it, as CodeLines repeats them; None: read it."""
        parsed = parse_line(raw)
        if parsed.special or len(parsed.commands) != 1 or "M" in self.first_chars:
            return None
        cmd = parsed.commands[0]
        if cmd.kind != GCODE or cmd.code in TEXT_CODES:
            return None
        always, filtered, apply = self.dispatch.table.get(cmd.code) or self.dispatch.build(cmd)
        if apply != self.interpreter.apply or any(wants(raw) for wants in self.view_patterns):
            return None
        handlers = [*always, *(h for h, letters in filtered if not letters.isdisjoint(cmd.params))]
        if not handlers:
            return ()
        if not all(getattr(getattr(h, "__self__", None), "pure", False) for h in handlers):
            return None
        line = Line(0, raw, "\n", parsed)
        try:
            made = self.ctx.made_by(lambda: [handler(line, cmd) for handler in handlers])
        except Exception:  # (read on its own, the rule fails again and is dropped)
            return None
        if any(fix is not None for _, _, _, fix, _, _ in made):
            return None  # (a fix names its line)
        return tuple((rule, column, end, message, severity) for rule, column, message, _, severity, end in made)

    def read(self, lines: Iterable[tuple[int, list[tuple[str, str]]]]) -> None:
        """The loop over the lines the runs leave (``(number of the line before, lines)``): a plain move the
        plain filters let by is applied by its route, without a tree; any other line goes to ``read_line``."""
        state, joined, read_line = self.state, self.joined, self.read_line
        plain_match, plain_move = PLAIN_MOVE.fullmatch, self.interpreter.plain_move
        long_limit, has_cr = self.long_limit, bool(self.hooks.cr)
        for number, chunk in lines:
            for raw, ending in chunk:
                number += 1
                if has_cr and (ending == "\r" or joined.parts) and joined.add(number, raw, ending):
                    self.read_joined(number, raw, ending)
                plain = self.plain
                if plain is not None and raw[:1] == "G" and len(raw) <= long_limit:
                    m = plain_match(raw)
                    if m is not None and not (state.after_m30 and self.hooks.after_end):
                        digit, f_first, x, y, z, e, f = m.groups()
                        mode, filters = plain[digit]
                        if f is None:
                            f = f_first
                        for wants in filters:
                            try:
                                if wants(mode, x, y, z, e, f):
                                    break
                            except Exception:  # the rule's own check will run (and be dropped if it fails)
                                break
                        else:
                            plain_move(mode, number, x, y, z, e, f)
                            continue
                read_line(number, raw, ending)
        if joined.parts and self.hooks.cr:  # (the file ends in a bare carriage return)
            self.read_joined(*joined.last)

    def read_line(self, number: int, raw: str, ending: str) -> None:
        """Read one line through its tree: the hooks on lines, then each command the machine runs (the rules
        that listen to its code, then the interpreter), then the view hooks."""
        parsed = parse_line(raw)
        line = Line(number, raw, ending, parsed)
        hooks = self.hooks
        if parsed.special:
            self.special(line)
        if len(raw) > self.long_limit:
            self.long_line(line)
        if self.state.after_m30 and hooks.after_end:
            self.call_each(self.hooks.after_end, line)
        if hooks.line:
            self.call_each(self.hooks.line, line)
        if self.first_chars and raw[:1] in self.first_chars:
            self.starting(line)
        commands = parsed.commands
        if len(commands) > 1:  # the dialect says which of them run, and in what order
            commands = self.running(line, commands)
        get = self.dispatch.table.get
        for cmd in commands:
            entry = get(cmd.code)
            if entry is None:
                entry = self.dispatch.build(cmd)
            always, filtered, apply = entry
            for handler in always:
                try:
                    handler(line, cmd)
                except Exception as exc:
                    self.disable(handler, exc, number)
            if filtered:
                params = cmd.params
                for handler, letters in filtered:
                    if not letters.isdisjoint(params):
                        try:
                            handler(line, cmd)
                        except Exception as exc:
                            self.disable(handler, exc, number)
            apply(cmd, line)
        for wants, view_hooks in self.hooks.view:
            if wants(raw) is not None:
                self.call_each(view_hooks, line)

    def call_each(self, hooks: tuple[Callable[[Line], None], ...], line: Line) -> None:
        for hook in hooks:
            try:
                hook(line)
            except Exception as exc:
                self.disable(hook, exc, line.number)

    def special(self, line: Line) -> None:
        """The hooks of a line with comments, syntax issues, an N number or a checksum (and its directives)."""
        parsed = line.parsed
        if parsed.comments:
            self.ctx.read_directives(line)
            for comment_hook in self.hooks.comment:
                try:
                    for comment in parsed.comments:
                        comment_hook(line, comment)
                except Exception as exc:
                    self.disable(comment_hook, exc, line.number)
        if parsed.issues:
            self.call_each(self.hooks.issue, line)
        if parsed.line_number is not None or parsed.checksum is not None:
            self.call_each(self.hooks.numbered, line)

    def long_line(self, line: Line) -> None:
        size = len(line.raw)
        for limit, hook in self.hooks.long:
            if size > limit:
                try:
                    hook(line)
                except Exception as exc:
                    self.disable(hook, exc, line.number)

    def starting(self, line: Line) -> None:
        first = line.raw[:1]
        for chars, hook in self.hooks.start:
            if first in chars:
                try:
                    hook(line)
                except Exception as exc:
                    self.disable(hook, exc, line.number)

    def running(self, line: Line, commands: tuple[Command, ...]) -> tuple[Command, ...]:
        """The commands of a line the machine runs, in its order; the others go to the ignored-command hooks."""
        semantics = self.ctx.dialect.semantics
        ran = semantics.running(commands)
        if len(ran) < len(commands):
            for cmd in semantics.ignored(commands):
                for hook in self.hooks.ignored:
                    try:
                        hook(line, cmd)
                    except Exception as exc:
                        self.disable(hook, exc, line.number)
        return ran

    def read_joined(self, number: int, raw: str, ending: str) -> None:
        """The hooks on lines joined across bare carriage returns (``_Joined``), at the line that ends them."""
        text, first = self.joined.text(raw)
        line = Line(number, raw, ending, parse_line(raw))
        for hook in self.hooks.cr:
            try:
                hook(line, text, first)
            except Exception as exc:
                self.disable(hook, exc, number)

    def finish(self) -> None:
        """The end of the file: each rule's ``finish``."""
        for r in list(self.rules):
            try:
                r.finish()
            except Exception as exc:
                self.disable(r.finish, exc, None)


def _make_rules(classes: Iterable[type[Rule]], ctx: FileContext, result: FileResult) -> list[Rule]:
    """The file's rules: one of each class that applies to its dialect.  A rule whose constructor fails
    (often a plugin) is named in the result and left out: it must not stop the check."""
    classes = [cls for cls in classes if cls.applies_to(ctx.dialect)]
    ctx.enabled_codes = frozenset(cls.code for cls in classes)
    rules: list[Rule] = []
    for cls in classes:
        try:
            rules.append(cls(ctx))
        except Exception as exc:
            _rule_failed(result, cls, exc, None)
    return rules


# A file shorter than the head read at opening (64 KiB) is read line by line, without runs: compiling the runs'
# pattern costs more than it saves there, and it was most of a one-file check's time.  (Tests of runs set this.)
RUNS_IN_SMALL_FILES = False


class _Joined:
    """Lines that end in a bare carriage return, and the one after them: LinuxCNC/Machinekit read them as one
    line (only a line feed ends a line for them: rules/security/linuxcnc.py), up to PARSE_LIMIT characters (those the grammar parses)."""

    def __init__(self) -> None:
        self.parts: list[str] = []
        self.first = self.next = self.size = 0
        self.last: tuple[int, str, str] = (0, "", "")

    def add(self, number: int, raw: str, ending: str) -> bool:
        """Take line ``number``; True when it ends a group of joined lines (then read ``text``)."""
        if self.parts and number != self.next:  # (lines in between were applied in a run: not joined)
            self.parts = []
        if ending != "\r":
            return bool(self.parts)
        if not self.parts:
            self.first, self.size = number, 0
        if self.size < PARSE_LIMIT:
            self.parts.append(raw)
            self.size += len(raw) + 1
        self.next, self.last = number + 1, (number, raw, ending)
        return False

    def text(self, raw: str) -> tuple[str, int]:
        """The group's text ending with ``raw`` (the line after the bare carriage returns), and its first line;
        the group is then done."""
        parts, self.parts = self.parts, []
        if self.last[1] is raw and parts and parts[-1] is raw:
            parts.pop()  # (the file ended in a bare carriage return: ``raw`` is the last part)
        return "\r".join([*parts, raw])[:PARSE_LIMIT], self.first


def _plain_filter(owner: object) -> Callable[..., bool] | None:
    """The plain filter of the owner of a G0/G1 handler: a move listener's ``wants_plain``, a rule's
    ``plain_filter`` (None: it has none)."""
    if isinstance(owner, MoveListener):
        return owner.wants_plain
    return getattr(owner, "plain_filter", None)


def _live_listeners(listeners: list[MoveListener], rules: list[Rule]) -> list[MoveListener]:
    """The move listeners with a member among ``rules`` (a rule whose constructor failed after joining is
    dropped from its listener)."""
    out = []
    for listener in listeners:
        for member in list(listener.members):
            if member not in rules:
                listener.drop(member)
        if listener.members:
            out.append(listener)
    return out


def _failed(owner: object, exc: Exception, rules: list[Rule], listeners: list[MoveListener]) -> list:
    """What goes when ``owner``'s hook raised ``exc``: the failing rule first (removed from ``rules`` and
    dropped from the listeners), then a listener left with no member.  For a move listener, the failing
    rule is the member whose method was running (the traceback's first frame of a member); where the
    listener's own code failed, it goes with all its members (named by the first).  Empty: not a hook."""
    if isinstance(owner, MoveListener) and owner in listeners:
        culprit = _member_in(exc, owner.members)
        gone: list = [culprit] if culprit is not None else [*owner.members, owner]
    elif isinstance(owner, Rule) and owner in rules:
        gone = [owner]
    else:
        return []
    for listener in listeners:
        for rule in gone:
            if rule in listener.members:
                listener.drop(rule)
        if not listener.members and listener not in gone:
            gone.append(listener)
    rules[:] = [r for r in rules if r not in gone]
    return gone


def _member_in(exc: Exception, members: list[Rule]) -> Rule | None:
    """The member whose method was running when ``exc`` was raised (the outermost such frame), if any."""
    tb = exc.__traceback__
    while tb is not None:
        owner = tb.tb_frame.f_locals.get("self")
        if owner is not None and any(owner is m for m in members):
            return owner
        tb = tb.tb_next
    return None


def _rule_failed(result: FileResult, rule: type[Rule], exc: Exception, line_number: int | None) -> None:
    """Record that ``rule`` raised while checking ``result.path``: one line for the user (exit code 2)."""
    where = f" at line {line_number}" if line_number is not None else ""
    from gclint.secrets import mask  # the exception may quote file text

    detail = mask(f"{type(exc).__name__}: {exc}".splitlines()[0][:200] if str(exc) else type(exc).__name__)
    origin = rule.__module__.split(".")[0]
    blame = "" if origin == "gclint" else f" from plugin module {rule.__module__!r}"
    message = (
        f"{result.path}: internal error in rule {rule.code} ({rule.name or rule.__name__}){blame}{where}: {detail};"
        " the rule was skipped for the rest of the file"
    )
    result.error = message if result.error is None else f"{result.error}; {message}"


def check_text(text: str, **options) -> list[Finding]:
    """Convenience for tests and library users: the findings for G-code ``text``."""
    return Linter(Options(**options)).check_text(text).findings


# The rule families whose findings hold only under the file's dialect (SX and SC hold whatever it is for).
DIALECT_FAMILIES = ("HY", "DL")


def _as_assumed(findings: list[Finding], context: Context) -> None:
    """A file whose dialect is only assumed (``Context.assumed``): its dialect's findings are information,
    each saying so; the gate does not fail a file on what is true only of a dialect it was not shown to be for."""
    note = context.assumed_note()
    for f in findings:
        if f.code.startswith(DIALECT_FAMILIES):
            f.severity = min(f.severity, Severity.INFO)
            f.message += note
