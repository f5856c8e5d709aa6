"""HY addressing rules: which head a T number names, whether it exists on the printer, whether it is
loaded, v4 numbers in v5 files, clone squads.

Sources (docs/sources.md): the T_v5 page (https://hyrel3d.com/wiki/index.php/T_v5: "Chart of Addresses",
the per-model tables, "Default Mode", "Explicit Mode", "Error Messages", M702-M704), the Gcode page
("Understanding the T", "T Tool Change"), and for v4 device addresses and the v4 -> v5 map the T_v4 page
and the Hyrel v4 firmware source (HydraSt_407: Hydra4/main.c toolNumberMap, Hydra4/common/inc/hyrel.h).

A "T command" is a line ``T3`` (changes the focused head); a "T variable" is the T word of an M-code
(``M104 T3 S200``: the device the command acts on).  ``Interpreter.address`` resolves T variables and
``Interpreter.tool_command_address`` T commands, with the numbering of the file's dialect (v4 files are
translated to v5 positions), so these rules speak v5 positions whatever the file.
"""

from __future__ import annotations

from gclint.dialects.addressing import (
    AUX,
    BED,
    GROUP,
    HEAD,
    RESERVED,
    SQUAD_CODES,
    V4_STYLE_VARIABLES,
    VIRTUAL,
    Address,
    Renumbering,
    fits,
    renumberings,
    resolve_v4_command,
    resolve_v4_variable,
    resolve_v5,
)
from gclint.dialects.base import Dialect, Param
from gclint.rules.base import ANY_T, Edit, Fix, Rule, Severity, register
from gclint.rules.dialect import ParamTableRule
from gclint.rules.syntax import with_checksum
from gclint.syntax.nodes import GCODE, Command, Line, Word, is_number, to_number

# -- helpers shared by the HY rules ------------------------------------------------------------------


def int_value(text: str | None) -> int | None:
    """A whole-number parameter value (``"12"``, ``"12.0"``), or None."""
    if text is None or len(text) > 12 or not is_number(text):
        return None
    value = to_number(text)  # (hex such as "0x0b" included; None when not finite)
    return int(value) if value is not None and value == int(value) else None


def is_v5(ctx) -> bool:
    """True for a file read with v5 addressing (dialect ``hyrel``), False for ``hyrel-v4``."""
    return ctx.dialect.extras.get("firmware") == 5


def t_variable_codes(dialect: Dialect) -> tuple[str, ...]:
    """The codes whose T parameter is an address (a T variable) in the dialect's table."""
    return tuple(code for code, spec in dialect.codes.items() if spec.params and "T" in spec.params)


def reads_v4_numbers(ctx) -> bool:
    """True when HY008 reads v4 numbers in this file: it is checked as v5 (``--dialect hyrel``, the
    configuration or a directive) but its own addresses say v4 (``Context.version_evidence``).  A file
    whose addresses say v5 is never re-read as v4: a number wrong in v5 is reported as what it is in
    v5, with a hint of its v4 meaning (``v4_hint``)."""
    return is_v5(ctx) and ctx.enabled("HY008") and ctx.context.version_evidence == 4


def reported_as_v4(ctx, cmd: Command, letter: str = "T") -> bool:
    """True when HY008 reports this word as a v4 device number.

    The other address rules then leave it alone: one cause, one finding (HY008 says what it most
    likely means and how to write it in v5).
    """
    if not reads_v4_numbers(ctx):
        return False
    return int_value(cmd.params.get(letter)) in V4_STYLE_VARIABLES


def v4_hint(ctx, number: int | None) -> str:
    """ " (in v4 numbering T12 was yoke 1, position 2)" for a v4-style number in a file read as v5."""
    if number is None or number not in V4_STYLE_VARIABLES or not is_v5(ctx):
        return ""
    v4 = resolve_v4_variable(number)
    return f" (in v4 numbering T{number} was {v4.label.removesuffix(f' (v4 T{number})')})"


def heads_text(heads) -> str:
    return ", ".join(f"T{h}" for h in sorted(heads)) or "none"


def _t_number(cmd: Command) -> str:
    return cmd.code[1:] if cmd.code else ""


# -- HY006 ---------------------------------------------------------------------------------------------


@register
class ToolNotLoaded(Rule):
    code = "HY006"
    name = "tool-not-loaded"
    severity = Severity.WARNING
    summary = "The T commands and the loaded heads do not match (a T command with no head there, or a loaded head no T command calls)"
    explanation = """
        A T command moves Repetrel's focus to the head in that tool position.  When a job is loaded,
        Repetrel "check[s] which heads are called out with T commands in your gcode ... and we compare
        that with which tool positions on the yoke actually have heads.  If there is any mismatch,
        warning message popups will appear.  If you have your heads called out in your gcode and the
        same tool positions loaded with heads, you will not see these warnings."  gclint makes the same
        comparison before the job reaches the printer, both ways: a T command that selects a position
        with no head (reported at its first T command), and a loaded head that no T command calls
        (reported at its `M6 T# O...` line, or line 1 when it comes from `--loaded`).  Heads that print
        through a clone squad or copy another head (`M703 T# S#`) count as called.  A job with no T
        command at all and one loaded head is Default Mode ("the gcode will be executed with the only
        head loaded") and is not reported.

        The loaded heads come from `--loaded T0,T2` (or `loaded = ["T0", "T2"]` in the configuration);
        without them, from the job header, where Repetrel writes one `M6 T# O...` line for every loaded
        head.  When neither says which heads are loaded, the rule stays silent.  Each position is
        reported once.  A position the printer model does not have at all is HY007.
    """
    example_bad = """
        M6 T0 O1 X0 Y0 Z0
        T1
    """
    example_good = """
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X0 Y0 Z0
        T0
        T1
    """
    source = "T_v5, Error Messages and Default Mode (M6 T# O... for every loaded head)"
    codes = (ANY_T, "M703")
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.seen: set[int] = set()  # positions called out by T commands
        self.copies: set[int] = set()  # heads that print through a squad or copy a head (M703 T#)
        self.pending: list[tuple[Line, Command, Address]] = []  # waiting for the whole header (no --loaded)

    def check(self, line: Line, cmd: Command) -> None:
        interpreter = self.ctx.interpreter
        if cmd.code == "M703":
            if not reported_as_v4(self.ctx, cmd):
                copier = interpreter.address(cmd)
                if copier is not None and copier.position is not None:
                    self.copies.add(copier.position)
            return
        address = interpreter.tool_command_address(cmd)
        if address is None or address.position is None:
            return
        position = address.position
        if position in self.seen:
            return
        self.seen.add(position)
        if position not in self.ctx.profile.positions:
            return  # HY007: the model has no such position
        loaded = self.state.loaded_heads
        if loaded is not None:
            if position not in loaded:
                self._report(line, cmd, address, f"loaded: {heads_text(loaded)}, from --loaded or the configuration")
        else:
            self.pending.append((line, cmd, address))

    def finish(self) -> None:
        st = self.state
        declared = st.declared_heads
        if st.loaded_heads is None and declared:
            for line, cmd, address in self.pending:
                if address.position not in declared:
                    self._report(line, cmd, address, f"the job header declares {heads_text(declared)} with M6 T# O...")
        loaded = st.loaded_heads if st.loaded_heads is not None else (frozenset(declared) or None)
        if loaded is None:
            return  # nobody says which heads are loaded: stay silent
        if not self.seen and len(loaded) < 2:
            return  # Default Mode: no T command, "executed with the only head loaded"
        for position in sorted(loaded - self.seen - self.copies):
            if position not in self.ctx.profile.positions:
                continue
            at = declared.get(position)
            where = f"declared by M6 T# O... at line {at}" if at is not None else "from --loaded or the configuration"
            self.report(
                at if at is not None else 1,
                f"head T{position} is loaded ({where}), but no T command calls it: Repetrel warns when the "
                "heads called out with T commands and the loaded heads do not match ('any mismatch')",
            )

    def _report(self, line: Line, cmd: Command, address: Address, where: str) -> None:
        self.report(
            line,
            f"{cmd.code} selects {address.label}, but no head is loaded there ({where}); "
            "Repetrel warns about the mismatch when the job is loaded",
            node=cmd,
        )


# -- HY007 ---------------------------------------------------------------------------------------------


@register
class ToolBeyondModel(Rule):
    code = "HY007"
    name = "tool-beyond-model"
    severity = Severity.ERROR
    summary = "A T command or T variable names a head position (or a second bed) the printer model does not have"
    explanation = """
        Each Hyrel model has a fixed number of tool positions (T_v5, "Using the T with ..."): the
        System 30M and Engine SR have four (T0-T3), the Engine HR and the single-yoke Hydra 16A five
        (T0-T4), the dual-yoke Hydra 16A ten (T0-T9).  T10-T19 exist only on three- and four-yoke units.
        A T command or an M-code addressed to a position the model lacks selects or heats nothing, and
        the moves that follow run with the wrong head.  Choose the printer with `--printer` (or
        `printer = "16a-dual"` in the configuration); the default is the 30m.

        T25 is "Bed2 / Chamber2" (T_v5, Chart of Addresses), and "our Hydra models have room to have a
        second hotbed" (Gcode page, Controlling Temperature): `M140 T25` or `M190 T25` on a model that
        is not a Hydra (16A) heats or waits for a bed the pages give that model no room for (warning:
        the pages do not say outright that the others have none).  A second chamber is only something
        Hyrel has "talked about", on no model, so M141/M191 T25 are not reported.
    """
    example_bad = """
        ; gclint-test: printer=30m
        T4
    """
    example_good = """
        ; gclint-test: printer=30m
        T3
    """
    source = (
        "T_v5, Chart of Addresses and Using the T with the ESR and 30M / EHR and 16A / 16A (Dual Yoke); Gcode "
        "page, Controlling Temperature (Hotbed 2)"
    )
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.codes = (ANY_T, *t_variable_codes(ctx.dialect))

    def check(self, line: Line, cmd: Command) -> None:
        interpreter = self.ctx.interpreter
        address = interpreter.tool_command_address(cmd)
        node: Command | Word | None = cmd
        if address is None:
            if reported_as_v4(self.ctx, cmd):
                return
            address = interpreter.address(cmd)
            node = cmd.param("T")
            what = f"{cmd.code} T{cmd.params.get('T')}"
        else:
            what = str(cmd.code)
        if address is not None and address.kind == BED and address.v5 == 25 and cmd.code in ("M140", "M190"):
            self._second_bed(line, node, what, address)
            return
        if address is None or address.kind != HEAD:
            return
        profile = self.ctx.profile
        position = address.position
        if self.ctx.on_every_model(lambda p: position not in p.positions):
            hint = v4_hint(self.ctx, int_value(cmd.params.get("T"))) if node is not cmd else ""
            self.report(
                line,
                f"{what} names {address.label}, but {profile.a} has tool positions "
                f"{profile.describe_positions()} only ({profile.title}){self.ctx.model_note()}{hint}",
                node=node,
            )

    def _second_bed(self, line: Line, node: Command | Word | None, what: str, address: Address) -> None:
        """Bed2 (T25) on a model the pages give no second bed ("our Hydra models have room to have a second
        hotbed", Controlling Temperature)."""
        if not self.ctx.on_every_model(lambda p: not p.second_bed):
            return
        profile = self.ctx.profile
        self.report(
            line,
            f"{what} names {address.label}, but the pages give a second bed to the Hydra models only ('our Hydra models "
            f"have room to have a second hotbed'), and {profile.a} is not one{self.ctx.model_note()}",
            node=node,
            severity=Severity.WARNING,
        )


# -- HY008 ---------------------------------------------------------------------------------------------


_MAX_KEPT = 50_000  # findings kept for the end of the file (memory stays bounded on absurd files)
# Words the conversion of one file may change.  Every HY008 finding carries the whole conversion (all of
# it or none applies, whichever finding's fix is chosen), so the output grows with the square of this.
_MAX_FIX_EDITS = 200
_T_ONLY = frozenset("T")
_T_AND_S = frozenset("TS")


@register
class V4AddressingInV5(Rule):
    code = "HY008"
    name = "v4-addressing-in-v5"
    severity = Severity.WARNING
    fixable = True
    fix_applicability = "sometimes"
    summary = "A file checked as v5 whose addresses are v4 numbers (T11-T15, T21-T25, T90-T92, T100...)"
    explanation = """
        Before Repetrel v5, "the nomenclature for T Commands and the T Variables were not the same": a
        tool change said `T1`, but the M-codes for that head said `T12` (yoke 1 heads were T11-T15, yoke 2
        T21-T25, the aux port T16, the spindle T26, the beds T91/T92, all beds T90, all heads T100, all
        devices T0).  In v5 "T0 always means the first head on the first yoke, regardless of how or why we
        are referring to it", so the old numbers name other devices or none: v4 `M109 T12 S200` heats
        the second head, v5 reads it as head T12 on a third yoke that the printer does not have.

        The rule speaks only when a file is checked as v5 (`--dialect hyrel`, `dialect = "hyrel"` in the
        configuration, or `; gclint: dialect=hyrel`) while its own addresses say v4: more of its T
        variables fit their commands in v4 numbering than in v5 (gclint weighs every address; `M116`
        and `W0` count for v5) and at least one is a v4-style number.  It reports every address whose
        v4 meaning differs from its v5 one then: the v4-style numbers, and with them v4 `T0` ("all
        devices", v5 `T40`), `T20`, `T41` and the tool numbers `T11`-`T14` of T commands, which alone
        are read as v5.  In a file whose addresses say v5, a v4-style number is what
        it is in v5 (HY007, HY047 report it, with its v4 meaning as a hint): nothing re-reads a v5 file
        as v4.  With `--dialect auto` (the default) a v4 file is checked as `hyrel-v4` and this rule is
        silent.

        The fix converts the whole file, as `gclint translate --from hyrel-v4 --to hyrel` does (the same
        v4 -> v5 map, where it is certain: docs/sources.md, Hyrel v4 addressing, confidence "high"): a file half in v4
        and half in v5 numbering means something else again (`M104 T0 S0` left alone would switch off
        head T0 only).  Every finding carries the same fix.  It is safe when no converted line also
        means something in v5 (a head the model lacks, an address no device has); when one does (`M140
        T24` is Bed1 in v5, `M104 T0` head T0), the whole fix is unsafe (`--unsafe-fixes`).  A file
        with an address that has no certain v5 counterpart (v4 `T16`, the aux port: "medium"; a number
        no v4 device has) gets no fix at all, nor does one with more than 200 addresses to convert (use the translator), nor a
        file with a parse error.  A right `*` checksum on a converted line is recomputed.
    """
    example_bad = """
        ; gclint: dialect=hyrel
        M6 T12 O2 X0 Y0 Z0
        M109 T12 S200
    """
    example_good = """
        ; gclint: dialect=hyrel
        M6 T1 O2 X0 Y0 Z0
        M109 T1 S200
    """
    source = (
        "Gcode page, Understanding the T; T_v5, The T and Chart of Addresses; T_v4 page; Hyrel v4 firmware "
        "source, Hydra4/main.c toolNumberMap and Hydra4/common/inc/hyrel.h (v4 device addresses)"
    )
    families = ("hyrel",)
    on_issue = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.active = reads_v4_numbers(ctx)
        if self.active:
            # every command: the fix converts the file as the translator does (any T word, T commands)
            self.codes = (ANY_T, *ctx.dialect.codes)
            self.on_unknown_code = True
        else:
            self.codes = ()
        self.unparsable = False
        # reported at the end, when it is known whether the file parses and the whole conversion
        self.found: list[tuple[Line, Word, str, int | None, bool]] = []
        self.conversion: dict[int, tuple[Line, list[Renumbering]]] = {}  # line -> its renumbered words
        self.converted = 0  # words the conversion changes
        self.unsafe: bool = False  # some word of the conversion also means something in v5
        self.blocked: str | None = None  # the first word with no certain v5 counterpart
        self.v4_only = False  # a v4-style number (T11-T16, T21-T26, T90-T92, T100) was seen

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        if code[:1] == "T":
            return None
        return _T_AND_S if code in SQUAD_CODES else _T_ONLY

    def check_issues(self, line: Line) -> None:
        if any(issue.code == "SX001" for issue in line.issues):
            self.unparsable = True  # a fix is never applied to a file that does not parse

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.kind != GCODE:
            return  # (the translator renumbers G/M/T commands only)
        for r in renumberings(cmd):
            if r.new is None:
                if self.blocked is None:
                    what = f"T{r.number}" if r.tool_command else f"{cmd.code} {r.letter}{r.number}"
                    self.blocked = f"line {line.number} ({what})"
            elif r.changes:
                self.converted += 1
                if self.converted <= _MAX_FIX_EDITS:
                    self.conversion.setdefault(line.number, (line, []))[1].append(r)
            if r.tool_command:
                if r.changes:
                    self._tool_command(line, cmd, r)
            elif r.letter == "T":
                if r.number in V4_STYLE_VARIABLES:
                    self.v4_only = True
                if r.changes or r.number in V4_STYLE_VARIABLES:
                    self._variable(line, cmd, r)
            elif cmd.code in ("M703", "M704") and r.number in V4_STYLE_VARIABLES:
                self._copied_head(line, cmd, r)

    def _variable(self, line: Line, cmd: Command, r: Renumbering) -> None:
        number = r.number
        v4, v5 = resolve_v4_variable(number), resolve_v5(number)
        problem = self._misfit(cmd.code, v5)  # type: ignore[arg-type]
        if problem is None:
            message = (
                f"{cmd.code} T{number}: the file's addresses are v4, where T{number} is {v4.label}; "
                f"in v5 it is {v5.label}"
            )
        else:
            message = (
                f"{cmd.code} T{number} is v4 numbering: in v4 it is {v4.label}; in v5 T{number} is {v5.label}{problem}"
            )
        self._report(line, r, message, problem is not None)

    def _tool_command(self, line: Line, cmd: Command, r: Renumbering) -> None:
        v4, v5 = resolve_v4_command(r.number), resolve_v5(r.number)
        problem = ", a line that selects no head" if v5.kind == RESERVED else self._beyond(v5)
        message = (
            f"{cmd.code} is a v4 tool number: in v4 it selects {v4.label}; in v5 {cmd.code} selects {v5.label}{problem}"
        )
        self._report(line, r, message, bool(problem))

    def _copied_head(self, line: Line, cmd: Command, r: Renumbering) -> None:
        # M703/M704 S: in v4 an alias (a device address, "M703 T14 S12": the pen answers to head 12);
        # in v5 a squad (30-39) or "the head which T# will duplicate" (T_v5, M703).
        number = r.number
        v4 = resolve_v4_variable(number)
        if v4.kind != HEAD:
            return
        self.v4_only = True
        v5 = resolve_v5(number)
        valid_in_v5 = v5.kind == HEAD and v5.position in self.ctx.profile.positions
        message = (
            f"{cmd.code} S{number} is v4 numbering: in v4 S{number} is {v4.label}; in v5 S names the "
            f"head to copy, and S{number} is {v5.label}{self._beyond(v5)}"
        )
        self._report(line, r, message, not valid_in_v5)

    def _misfit(self, code: str, v5: Address) -> str | None:
        """Why the v5 reading does not fit the command, or None when it does."""
        if v5.kind == RESERVED:
            return ", an address no device has"
        if not fits(code, v5):
            return f", which {code} does not address"
        if v5.kind == HEAD and v5.position not in self.ctx.profile.positions:
            return self._beyond(v5)
        return None

    def _beyond(self, v5: Address) -> str:
        if v5.kind == HEAD and v5.position not in self.ctx.profile.positions:
            profile = self.ctx.profile
            return f", a position {profile.a} does not have ({profile.describe_positions()}){self.ctx.model_note()}"
        return ""

    def _report(self, line: Line, r: Renumbering, message: str, safe: bool) -> None:
        if r.changes and not safe:
            self.unsafe = True
        if len(self.found) < _MAX_KEPT:
            self.found.append((line, r.node, message, r.new if r.changes else None, safe))

    def finish(self) -> None:
        if not self.v4_only:
            # T0, T20, T41 and tool numbers T11-T14 mean something in both numberings: alone they are
            # read as v5 (HY046, HY007... report them); they are converted with the v4-only numbers
            return
        edits, why_not = self._conversion()
        for found in self.found:
            self._emit(*found, edits, why_not)

    def _conversion(self) -> tuple[tuple[Edit, ...], str]:
        """The edits that convert every address of the file (all of them or none: a file half in v4 and
        half in v5 numbering means something else), or why there are none."""
        if self.unparsable or not self.converted:
            return (), ""
        translate = "gclint translate --from hyrel-v4 --to hyrel (and check its TR006 notes)"
        if self.blocked is not None:
            return (), (
                f"; no fix: the file's v4 addresses are converted all together or not at all, and the one at "
                f"{self.blocked} has no certain v5 counterpart (the map is inferred there): convert by hand or with "
                f"{translate}"
            )
        if self.converted > _MAX_FIX_EDITS:
            return (), (
                f"; no fix: the file has {self.converted:,} v4 addresses to convert together, more than one fix "
                f"carries ({_MAX_FIX_EDITS}): convert it with {translate}"
            )
        edits: list[Edit] = []
        for line, words in self.conversion.values():
            line_edits = [Edit(line.number, w.node.column, w.node.end_column, w.text()) for w in words]
            edits.extend(with_checksum(line, line_edits))
        return tuple(edits), ""

    def _emit(
        self, line: Line, word: Word, message: str, target: int | None, safe: bool, edits: tuple, why_not: str
    ) -> None:
        letter = word.text[0].upper()
        if target is None:
            self.report(line, f"{message}; the v4 -> v5 map is uncertain here: check the address by hand", node=word)
            return
        fix = None
        if edits:
            others = self.converted - 1
            also = (
                f" and the file's {others} other v4 address{'es' if others != 1 else ''} with their v5 numbers"
                if others
                else ""
            )
            fix = Fix(f"Replace {word.text} with {letter}{target}{also}", edits, safe=not self.unsafe)
        advice = f"in v5 write {letter}{target}" if safe else f"if it is the v4 number, write {letter}{target}"
        self.report(line, f"{message}; {advice}{why_not}", node=word, fix=fix)


# -- HY022 ---------------------------------------------------------------------------------------------


@register
class SquadNumberRange(ParamTableRule):
    code = "HY022"
    name = "squad-number-range"
    severity = Severity.ERROR
    summary = "A clone squad number outside 30-39, or a squad command whose head is not one physical head"
    explanation = """
        M702 establishes a clone squad: "S# is the clone squad number designation and must be in the
        range 30 - 39", and T# is the head whose flow settings are copied.  M703/M704 add or remove the
        head T# to or from squad S#, "OR" make T# duplicate (or stop duplicating) the head S#: so S must
        be a squad (30-39) or a physical head (T0-T19), and T one physical head.  Anything else
        establishes nothing, and the heads the job expects to print together print alone (or not at
        all).

        In v4 files (`--dialect hyrel-v4`) M702 seeds the groups 50-57 instead (Hyrel v4 firmware
        source, Hydra4/src/MCode.c M_Code_M702-M_Code_M704), and M703/M704 give a device an alias, so
        only the M702 range is checked there.
    """
    example_bad = "M702 T0 S40"
    example_good = "M702 T0 S30"
    source = "T_v5, M702 Establish Clone Squad, M703 Add to Clone Squad, M704 Remove from Clone Squad"
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.v5 = is_v5(ctx)
        extra = ("M702", "M703", "M704") if self.v5 else ("M702",)
        self.codes = tuple(dict.fromkeys((*self.codes, *(c for c in extra if c in ctx.dialect.codes))))

    def check(self, line: Line, cmd: Command) -> None:
        super().check(line, cmd)
        code = cmd.code
        if code != "M702" and not self.v5:
            return
        if "T" in cmd.params and not reported_as_v4(self.ctx, cmd):
            address = self.ctx.interpreter.address(cmd)
            if address is not None and address.kind != HEAD:
                role = "the head whose settings are copied" if code == "M702" else "the head to add or remove"
                self.report(
                    line,
                    f"{code} T: T is {role} and must be one physical head (T0-T19); "
                    f"T{cmd.params['T']} is {address.label}",
                    node=cmd.param("T"),
                )
        if code in ("M703", "M704") and not reported_as_v4(self.ctx, cmd, "S"):
            squad = int_value(cmd.params.get("S"))
            if squad is not None and not (30 <= squad <= 39 or 0 <= squad <= 19):
                self.report(
                    line,
                    f"{code} S{squad}: S must be a clone squad (30-39) or the head to copy (T0-T19)",
                    node=cmd.param("S"),
                )

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        kind = "clone squad" if self.v5 else "v4 group"
        return f"{cmd.code}: {problem}; {kind} numbers are {p.minimum:g}-{p.maximum:g}"

    def missing_message(self, cmd: Command, p: Param) -> str:
        return f"{cmd.code} needs S, the {'clone squad' if self.v5 else 'group'} number"


# -- HY045 ---------------------------------------------------------------------------------------------

# Codes whose T variable names the head that prints (their heads make a file multi-head).
_HEAD_CODES = ("M104", "M109", "M106", "M107", "M221", "M721", "M722", "M723", "M728", "M620", "M3", "M4", "M5")


@register
class NoHeadFocusBeforePrinting(Rule):
    code = "HY045"
    name = "no-head-focus-before-printing"
    severity = Severity.ERROR
    summary = "A multi-head job prints (or moves) before a T command sets the focused head"
    explanation = """
        When a job starts, Repetrel "focus[es] on the first head it detects".  With one head that is
        fine; "when printing with multiple heads, the requirement [is] to explicitly direct Repetrel's
        focus": "force focus with a T command in the gcode before your first print move.  We recommend
        doing this before any movements, in case your head will collide with the bed without the
        offset."

        A job is multi-head when more than one head is loaded (`--loaded`), declared (`M6 T# O...`),
        selected with T commands or addressed by head commands (M104, M109, M221, M721...).  No T
        command before the first printing move is an error; a T command after the first move but before
        printing is a warning.  Homing (G28) is not a move here.
    """
    example_bad = """
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X20 Y0 Z0
        G1 X10 Y10 E1 F1200
        T1
    """
    example_good = """
        M6 T0 O1 X0 Y0 Z0
        M6 T1 O2 X20 Y0 Z0
        T1
        G1 X10 Y10 E1 F1200
    """
    source = "T_v5, Default Mode and Explicit Mode"
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.codes = (ANY_T, *(c for c in _HEAD_CODES if c in ctx.dialect.codes))
        self.heads: set[int] = set()
        self.first_t: int | None = None

    def check(self, line: Line, cmd: Command) -> None:
        interpreter = self.ctx.interpreter
        address = interpreter.tool_command_address(cmd)
        if address is not None:
            if self.first_t is None:
                self.first_t = line.number
        elif not reported_as_v4(self.ctx, cmd):
            address = interpreter.address(cmd)
        if address is not None and address.position is not None:
            self.heads.add(address.position)

    def finish(self) -> None:
        st = self.state
        heads = self.heads | set(st.declared_heads) | set(st.loaded_heads or ())
        if len(heads) < 2:
            return
        first_print, first_move, first_t = st.first_print_line, st.first_move_line, self.first_t
        names = heads_text(heads)
        if first_print is not None and (first_t is None or first_t > first_print):
            later = f"the first T command is at line {first_t}" if first_t is not None else "the file has no T command"
            self.report(
                first_print,
                f"printing starts before any T command ({later}) in a job with heads {names}: "
                "Repetrel prints with the first head it detects; put a T command before the first move",
            )
        elif first_move is not None and first_t is not None and first_t > first_move:
            self.report(
                first_move,
                f"the first move comes before the first T command (line {first_t}) in a job with heads "
                f"{names}: the head may collide with the bed without its offset",
                severity=Severity.WARNING,
            )


# -- HY047 ---------------------------------------------------------------------------------------------


@register
class AddressOutOfTable(Rule):
    code = "HY047"
    name = "address-out-of-table"
    severity = Severity.ERROR
    fixable = True
    fix_applicability = "unsafe"
    summary = "A T number that no device has, or a T command that focuses a bed, an aux port or a group"
    explanation = """
        The T_v5 "Chart of Addresses" lists every address: T0-T19 heads, T20 spindle, T21 CO2 laser,
        T22/T23 Aux1/Aux2, T24/T25 beds and chambers, T30-T39 virtual heads (clone squads), T40-T48
        groups.  T26-T29 and T49 and above name nothing (error), nor does a number that is not whole
        (`M104 T0.5`: the chart has whole numbers only), and so do v4 numbers outside the v4
        tables in a `hyrel-v4` file (a v4 T command is a tool number 0-9, 10-14 for the aux port, laser,
        spindle and beds; 4.1+ firmware drops other T lines).

        A T command changes which head "has the focus of the motion controller and is executing the
        gcode": focusing a bed, an aux port or a group of devices is almost certainly a T variable
        written as a T command (warning).

        In a v5 file (its addresses say v5), a number that is an address only in v4 numbering (T26,
        T90-T92, T100: the v4 spindle, beds and wildcards, as in Hyrel's old standard footer `M104 T100
        S0`, `M140 T90 S0`) is reported with its v4 meaning, and an unsafe fix (`--unsafe-fixes`) writes
        the v5 address that meaning has, where docs/sources.md (Hyrel v4 addressing) rates the map "high"
        (special devices and wildcards) and the device fits the command.  A file whose addresses say v4 is HY008's.
    """
    example_bad = "M104 T27 S200"
    example_good = "M104 T2 S200"
    source = "T_v5, Chart of Addresses; Gcode page, Understanding the T and T Tool Change"
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.codes = (ANY_T, *t_variable_codes(ctx.dialect))

    def check(self, line: Line, cmd: Command) -> None:
        interpreter = self.ctx.interpreter
        address = interpreter.tool_command_address(cmd)
        if address is not None:
            if address.kind == RESERVED:
                self.report(line, f"{cmd.code}: {address.label}: the line selects no head", node=cmd)
            elif address.kind in (BED, AUX, GROUP):
                self.report(
                    line,
                    f"{cmd.code} makes {address.label} the focused tool: a T command selects the head "
                    "that executes the moves; address other devices with the T variable of an M-code",
                    node=cmd,
                    severity=Severity.WARNING,
                )
            return
        if cmd.kind == GCODE and cmd.code and cmd.code[0] == "T":
            number = _t_number(cmd)
            if number.isdigit():  # (T0.5 and the like are no Hyrel code: DL001)
                reason = _not_an_address(number, interpreter.resolve_command)
                if reason is not None:
                    self.report(line, f"{reason}: the line selects no head", node=cmd)
            return
        value = cmd.params.get("T")
        if value is None or reported_as_v4(self.ctx, cmd):
            return
        address = interpreter.address(cmd)
        if address is None:
            reason = _not_an_address(value, interpreter.resolve_variable)
            if reason is not None:
                self.report(line, f"{cmd.code} {reason}: the command addresses nothing", node=cmd.param("T"))
            return
        if address is not None and address.kind == RESERVED:
            word = cmd.param("T")
            fix, advice = self._v4_fix(line, cmd, word, address.number)
            self.report(
                line,
                f"{cmd.code} T{cmd.params['T']}: {address.label}: the command addresses nothing"
                f"{v4_hint(self.ctx, address.number)}{advice}",
                node=word,
                fix=fix,
            )

    def _v4_fix(self, line: Line, cmd: Command, word: Word | None, number: int) -> tuple[Fix | None, str]:
        """In a file whose addresses say v5: the fix to the v5 address a v4 number (T26, T90-T92, T100)
        means, where docs/sources.md (Hyrel v4 addressing) rates the map "high" and the device fits the
        command.  Unsafe: the file mixes numberings, and only its author knows this line is the v4 one."""
        if word is None or number not in V4_STYLE_VARIABLES or not is_v5(self.ctx):
            return None, ""
        v4 = resolve_v4_variable(number)
        if v4.v5 is None:
            return None, ""
        if not v4.certain:
            return None, "; the v4 -> v5 map is uncertain here (inferred, not documented): check the address by hand"
        if self.ctx.context.version_evidence != 5 or not fits(str(cmd.code), resolve_v5(v4.v5)):
            return None, ""  # a v4 file (HY008 converts it whole) or a device the command does not address
        text = f"{word.text[0]}{v4.v5}"
        edits = with_checksum(line, [Edit(line.number, word.column, word.end_column, text)])
        return Fix(f"Replace {word.text} with {text} (its v4 meaning)", tuple(edits), safe=False), (
            f"; if it is the v4 number, write {text}"
        )


def _not_an_address(text: str, resolve) -> str | None:
    """Why a T value that reads as a number but not as an address (``Interpreter.address`` takes whole
    numbers of up to 12 characters) names no device: a fraction, or a number beyond every address.  None
    for text that is no number at all (the syntax rules report it) and for a long spelling of an address."""
    if not is_number(text):
        return None
    value = to_number(text)  # (None: too large for a float)
    if value is not None and value != int(value):
        return f"T{text} is not a device number (the Chart of Addresses numbers devices with whole numbers)"
    if value is not None and abs(value) < 1e15 and resolve(int(value)).kind != RESERVED:
        return None  # ("T000000000000012" is T12, however it is spelled)
    return f"T{text}: no device has this address"


# -- HY048 ---------------------------------------------------------------------------------------------


@register
class SquadNotEstablished(Rule):
    code = "HY048"
    name = "squad-not-established"
    severity = Severity.WARNING
    summary = "A clone squad (T30-T39) is used before M702 establishes it, or after M30 dissolved it"
    explanation = """
        M702 establishes a clone squad; M703 adds heads to "the Clone Squad we established with an
        M702"; M704 removes a head that M703 added.  Using a squad number (M703/M704 S30, a T30 command,
        `M104 T30`) before any `M702 ... S30` addresses a squad with no flow settings and no heads
        (warning).  "Note that an M30 decommissions any clone squads that were in effect": a squad used
        after an M30 without a new M702 is an error.  M704 for a head that is not in the squad is a
        warning.  v5 only: in v4 files M703/M704 give aliases.
    """
    example_bad = "M703 T1 S30"
    example_good = """
        M702 T0 S30
        M703 T1 S30
    """
    source = "T_v5, M702 Establish Clone Squad, M703 Add to Clone Squad, M704 Remove from Clone Squad"
    dialects = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        others = tuple(c for c in t_variable_codes(ctx.dialect) if c not in ("M702", "M703", "M704"))
        self.codes = (ANY_T, "M30", "M703", "M704", *others)
        self.dissolved: dict[int, int] = {}  # squad -> line of the M30 that dissolved it
        self.reported: set[tuple[int, bool]] = set()

    def check(self, line: Line, cmd: Command) -> None:
        code = cmd.code
        squads = self.state.squads
        if code == "M30":
            for established in squads:
                self.dissolved[established] = line.number
            self.reported.clear()
            return
        if code in ("M703", "M704"):
            squad = int_value(cmd.params.get("S"))
            if squad is None or not 30 <= squad <= 39:
                return
            if squad not in squads:
                self._missing(line, cmd.param("S") or cmd, squad, f"{code} S{squad}", once=False)
            elif code == "M704":
                head = self.ctx.interpreter.target(cmd)
                if head is not None and head not in squads[squad]:
                    self.report(line, f"M704 removes T{head} from squad S{squad}, but no M703 added it", node=cmd)
            return
        interpreter = self.ctx.interpreter
        address = interpreter.tool_command_address(cmd)
        node: Command | Word | None = cmd
        if address is None:
            address = interpreter.address(cmd)
            node = cmd.param("T")
        if address is not None and address.kind == VIRTUAL and address.v5 is not None and address.v5 not in squads:
            what = str(cmd.code) if node is cmd else f"{cmd.code} T{cmd.params['T']}"
            self._missing(line, node, address.v5, what, once=True)

    def _missing(self, line: Line, node, squad: int, what: str, once: bool) -> None:
        dissolved = self.dissolved.get(squad)
        if once:
            key = (squad, dissolved is not None)
            if key in self.reported:
                return
            self.reported.add(key)
        if dissolved is not None:
            self.report(
                line,
                f"{what}: squad {squad} was dissolved by M30 at line {dissolved} ('an M30 decommissions any "
                f"clone squads'); establish it again with M702 T# S{squad}",
                node=node,
                severity=Severity.ERROR,
            )
        else:
            self.report(line, f"{what}: no M702 T# S{squad} has established squad {squad} before this line", node=node)
