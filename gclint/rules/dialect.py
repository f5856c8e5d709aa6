"""DL: dialect conformance.  Whether the dialect has a code, takes a parameter, allows a value.

The facts are the dialect's tables (gclint/dialects/*.py).  ``ParamTableRule`` checks the parameters
that a table entry assigns to a rule (``Param(rule="HY023")``); the HY rules whose check is a range
in the Hyrel table subclass it, so the range lives once, as data.
"""

from __future__ import annotations

from gclint import dialects, firmware
from gclint.dialects.base import Param
from gclint.rules.base import Rule, Severity, register
from gclint.syntax.nodes import (
    EXTENDED,
    GCODE,
    HOST,
    IMPLICIT,
    META,
    OWORD,
    TEXT,
    WORD_LETTERS,
    Command,
    Line,
    to_number,
)

_ARC_LETTERS = frozenset("XYZIJEF")  # (the words of an arc of a run: fastpath.run_pattern)


@register
class UnknownCode(Rule):
    code = "DL001"
    name = "unknown-code"
    severity = Severity.WARNING
    summary = "A code the dialect does not have"
    explanation = """
        Each firmware knows its own list of codes.  An unknown code is skipped at best (Marlin prints
        "Unknown command"); on Hyrel, Repetrel reuses many numbers for other things (M204, M205, M220...
        mean something else there), and LinuxCNC stops the program.  The severity follows the dialect:
        error on Hyrel and Machinekit/LinuxCNC, warning elsewhere.

        A Marlin-flavour file written for Prusa (Buddy or MK3), Bambu Lab or Klipper firmware, as its
        slicer settings say (`; printer_model = MK4S`, `M862.3 P "MK4S"`, `; gcode_flavor = klipper`),
        is checked against Marlin and that firmware's inventory: `M74` is not unknown in a job for an
        MK4S.  Codes your machine has besides its firmware's (site macros, Klipper `[gcode_macro]`s) are
        declared with `extend-known-codes` in the configuration.  A LinuxCNC or Machinekit job's
        `REMAP=` codes are read from the machine's INI file (its `[RS274NGC]` section) in the job's folder or
        a folder above it, up to the repository root; M100-M199 are LinuxCNC's user M-codes.
    """
    example_bad = "; gclint: dialect=hyrel\nM204 S1000"
    example_good = "; gclint: dialect=hyrel\nM203 X6000 Y6000"
    source = (
        "dialect inventories (gclint/dialects/, each naming its public sources: Hyrel Gcode page, Code_Chart; "
        "Marlin G-code reference; Duet G-code dictionary; Machinekit-FDM remap.ini; Carvera M-code table); "
        "firmware inventories (gclint/firmware/, each naming its firmware repository and commit)"
    )
    on_unknown_code = True
    pure = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        flavor = ctx.context.flavor
        self.flavor = firmware.get(flavor) if flavor is not None else None
        self.declared = frozenset(ctx.options.extend_known_codes)
        if ctx.dialect.machine_ini:  # (the REMAP codes of the LinuxCNC INI beside the job)
            self.declared |= frozenset(ctx.options.machine_codes)
        self.verdicts: dict[tuple[str, str | None], tuple[str, Severity] | None] = {}  # (codes repeat: M204)

    def check(self, line: Line, cmd: Command) -> None:
        key = (cmd.kind, cmd.code)
        try:
            verdict = self.verdicts[key]
        except KeyError:
            if len(self.verdicts) >= 4096:
                self.verdicts.clear()
            verdict = self.verdicts[key] = self._verdict(cmd)
        if verdict is not None:
            self.report(line, verdict[0], node=cmd, severity=verdict[1])

    def _verdict(self, cmd: Command) -> tuple[str, Severity] | None:
        """The message and severity for a command of this kind and code, or None when it is known."""
        code = cmd.code
        if code is not None and (
            code in self.declared
            or code.upper() in self.declared
            or (self.flavor is not None and self.flavor.knows(code))
        ):
            return None
        dialect = self.ctx.dialect
        name = dialect.title.split(" (")[0]  # without the description in brackets
        severity = Severity.parse(dialect.unknown_severity)
        kind = cmd.kind
        if kind in (GCODE, TEXT):
            message = f"{code} is not a {self._checked_against()} code{self._documented_elsewhere(code)}"
        elif kind == EXTENDED:
            has = f"neither {name} nor {self.flavor.title} has" if self.flavor is not None else f"{name} has no"
            message = f"{code}: {has} Klipper-style extended commands"
        elif kind == META:
            if code == "echo":  # also Smoothieware's console (Carvera's firmware)
                message = f"'echo': {name} has no RepRapFirmware meta commands or Smoothieware console"
            else:
                message = f"'{code}': {name} has no RepRapFirmware meta commands"
        elif kind == OWORD:
            message = f"O-word: {name} has no LinuxCNC O-word subroutines or control flow"
        elif kind in (IMPLICIT, HOST):  # (an OctoPrint @ command is the host's, never the printer's: DL007)
            return None
        else:
            message = f"'#' parameters: {name} has no LinuxCNC parameters"
        return message, severity

    def _checked_against(self) -> str:
        title = self.ctx.dialect.title.split(" (")[0]  # the name, without the description in brackets
        return title if self.flavor is None else f"{title} or {self.flavor.title}"

    def _documented_elsewhere(self, code: str | None) -> str:
        """Names the firmware that has ``code`` (" (Prusa Buddy firmware has it)") when its files are read
        like this one's: the file may be for it (what its header would say, or extend-known-codes)."""
        if code is None:
            return ""
        related = self.ctx.dialect.related()
        found = [f for f in firmware.documenting(code, related) if f is not self.flavor]
        if any(code in d.codes for d in dialects.known_dialects() if d.name not in related):
            # another dialect's code: an inventory that lists every firmware's numbers (the 2015 RepRap page,
            # ``marks_dialect`` False) is not cited, its entry of that number may be another command (its M229
            # is no Hyrel M229)
            found = [f for f in found if f.marks_dialect]
        if not found:
            return ""
        verb = "has" if len(found) == 1 and not found[0].plural else "have"
        return f" ({' and '.join(f.title for f in found)} {verb} it)"


class ParamTableRule(Rule):
    """Checks a command's parameters against the dialect table entries that name this rule.

    Listens to every code with at least one such parameter; reports values outside the bounds, letters
    marked forbidden, and (for ``required`` parameters) missing letters.
    """

    report_missing = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.table: dict[str, list[Param]] = {}
        for spec in ctx.dialect.codes.values():
            if spec.params:
                mine = [p for p in spec.params.values() if p.rule == self.code and p.constrained]
                if mine:
                    self.table[spec.code] = mine
        self.codes = tuple(self.table)

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        """The engine calls ``check`` only for commands with one of these letters (None: always)."""
        if type(self).check is not ParamTableRule.check:
            return None  # a subclass that checks more than the table must see every command
        params = self.table.get(code, ())
        if any(p.required for p in params):
            return None
        return frozenset(p.letter for p in params)

    def check(self, line: Line, cmd: Command) -> None:
        params = cmd.params
        for p in self.table.get(cmd.code, ()):  # type: ignore[arg-type]
            if p.letter not in params:
                if p.required and self.report_missing:
                    self.report(line, self.missing_message(cmd, p), node=cmd)
                continue
            raw = params[p.letter]
            if p.forbidden:
                self.report(
                    line, f"{cmd.code}: {p.letter} is not allowed ({p.meaning})", node=cmd.param(p.letter) or cmd
                )
                continue
            if raw is None:
                if p.required:
                    self.report(line, f"{cmd.code}: {p.letter} needs a value", node=cmd.param(p.letter) or cmd)
                continue
            value = to_number(raw)
            if value is None:
                continue  # not a plain number (expression, bad number: SX006)
            problem = p.problem(value)
            if problem is not None:
                self.report(line, self.range_message(cmd, p, problem), node=cmd.param(p.letter) or cmd)

    def missing_message(self, cmd: Command, p: Param) -> str:
        return f"{cmd.code} needs {p.letter} ({p.meaning})"

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return f"{cmd.code}: {problem} ({p.meaning})"


@register
class ValueOutOfRange(ParamTableRule):
    code = "DL003"
    name = "value-out-of-range"
    severity = Severity.WARNING
    summary = "A parameter value outside the range the dialect documents"
    explanation = """
        The dialect's documentation gives a range for many parameters (percentages 0-100, flags 0 or
        1, register numbers).  Firmware clamps or ignores values outside it, so the command does less
        than it says.  Ranges that have a dedicated rule (HY0nn) are reported by that rule.
    """
    example_bad = "; gclint: dialect=hyrel\nM229 E2 D1"
    example_good = "; gclint: dialect=hyrel\nM229 E1 D1"
    source = "dialect tables (gclint/dialects/*.py), each entry naming its source"
    report_missing = False  # DL004 reports missing parameters


@register
class MissingParameter(ParamTableRule):
    code = "DL004"
    name = "missing-parameter"
    severity = Severity.ERROR
    summary = "A parameter the code requires is missing"
    explanation = """
        Some codes do nothing, or something else, without a parameter: Hyrel M756 without S has no
        layer height to set, M702 without S has no squad to establish.
    """
    example_bad = "; gclint: dialect=hyrel\nM756"
    example_good = "; gclint: dialect=hyrel\nM756 S0.2"
    source = "dialect tables (gclint/dialects/*.py)"

    def __init__(self, ctx) -> None:
        Rule.__init__(self, ctx)
        self.table = {}
        for spec in ctx.dialect.codes.values():
            if spec.params:
                mine = [p for p in spec.params.values() if p.required and p.rule == "DL003"]
                if mine:
                    self.table[spec.code] = mine
        self.codes = tuple(self.table)

    def check(self, line: Line, cmd: Command) -> None:
        for p in self.table.get(cmd.code, ()):  # type: ignore[arg-type]
            if p.letter not in cmd.params:
                self.report(line, f"{cmd.code} needs {p.letter} ({p.meaning})", node=cmd)


@register
class UnknownParameter(Rule):
    code = "DL002"
    name = "unknown-parameter"
    severity = Severity.WARNING
    summary = "A parameter letter the code does not take in this dialect"
    explanation = """
        A letter the code does not document is ignored by the firmware, which usually means the author
        expected another firmware's meaning (Marlin's "M106 P1" fan index is a duty cycle on Hyrel;
        "M18 S30" is a timeout on Marlin but Hyrel's M18 takes nothing and cuts the motors at once).
    """
    example_bad = "; gclint: dialect=hyrel\nM84 S30"
    example_good = "; gclint: dialect=hyrel\nM84"
    source = "dialect tables (gclint/dialects/*.py)"

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.allowed: dict[str, frozenset[str]] = {
            spec.code: frozenset(spec.params) for spec in ctx.dialect.codes.values() if spec.params is not None
        }
        self.codes = tuple(self.allowed)
        self._seen: dict[tuple, tuple[str, ...]] = {}
        if all(self.allowed.get(code, _ARC_LETTERS) >= _ARC_LETTERS for code in ("G2", "G3")):
            self.run_filter = self._no_arcs

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        # Moves are the hot path: call check only when a G0/G1 has a letter the dialect does not allow.
        if code in ("G0", "G1") and code in self.allowed:
            return WORD_LETTERS - self.allowed[code]
        return None

    @staticmethod
    def _no_arcs(text: str, start: int, end: int) -> list[int]:
        """The run filter where G2 and G3 take every letter an arc of a run may carry (X Y Z I J E F):
        it wants none of them (gclint.runs asks it only about arcs)."""
        return []

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.params.keys() <= self.allowed[cmd.code]:  # type: ignore[index]
            return
        key = (cmd.code, *cmd.params)
        unknown = self._seen.get(key)
        if unknown is None:
            allowed = self.allowed[cmd.code]  # type: ignore[index]
            unknown = tuple(letter for letter in cmd.params if letter not in allowed)
            if len(self._seen) < 4096:
                self._seen[key] = unknown
        for letter in unknown:
            spec = self.ctx.dialect.spec(cmd.code)  # type: ignore[arg-type]
            takes = "nothing" if not spec.params else " ".join(sorted(spec.params))  # type: ignore[union-attr]
            self.report(
                line,
                f"{cmd.code} does not take {letter} in {self.ctx.dialect.name} (it takes {takes})",
                node=cmd.param(letter) or cmd,
            )


@register
class WordNotInDialect(Rule):
    code = "DL005"
    name = "word-not-in-dialect"
    severity = Severity.ERROR
    summary = "A move with a word the dialect's language does not have (E in Machinekit/LinuxCNC)"
    explanation = """
        LinuxCNC's RS274NGC has no E word on moves: Machinekit drives the extruder as the A axis ("A follows
        G90/G91"; the gcode-to-ngc filter rewrites RepRap E to A).  A move written with E is refused by the
        interpreter ("Bad character used") or, after a careless conversion, extrudes nothing.  The file was
        probably written for another firmware: check the dialect, or write the extrusion on A.
    """
    example_bad = "; gclint: dialect=machinekit\nG1 X10 Y10 E0.5 F1200"
    example_good = "; gclint: dialect=machinekit\nG1 X10 Y10 A0.5 F1200"
    source = (
        "Machinekit-FDM GCode.org and subroutines/g28.ngc (the extruder is the A axis); machinekit-cnc "
        'scripts/gcode-to-ngc (RepRap E rewritten to A); LinuxCNC source, src/emc/rs274ngc/interp_read.cc ("Bad '
        'character used")'
    )
    codes = ("G0", "G1", "G2", "G3")
    families = ("linuxcnc",)

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        return None  # plain moves carry E: ``plain_filter`` picks the ones to check

    def plain_filter(self, mode, x, y, z, e, f) -> bool:
        return e is not None

    def check(self, line: Line, cmd: Command) -> None:
        if "E" in cmd.params:
            self.report(
                line,
                f"{cmd.code} E: E is not a word of {self.ctx.dialect.title}; the extruder is the A axis",
                node=cmd.param("E") or cmd,
            )


@register
class CommandNeverRuns(Rule):
    code = "DL006"
    name = "command-never-runs"
    severity = Severity.ERROR
    summary = "A second command on a line of a firmware that runs only the first"
    explanation = """
        Marlin reads one command a line: the first G, M or T code is the command and everything after it is
        read as its parameters (Marlin's `GCodeParser::parse`, `Marlin/src/gcode/parser.cpp`).  In
        `G91 G1 X10 E1` only `G91` runs; the move never happens, and the lines after it run in relative mode
        from a place the file did not mean.  Put each command on its own line.  (RepRapFirmware, LinuxCNC and
        Hyrel run every command of a line; LinuxCNC in its documented order, not as written.)
    """
    example_bad = "; gclint: dialect=marlin\nG91 G1 X10 E1"
    example_good = "; gclint: dialect=marlin\nG91\nG1 X10 E1"
    source = "Marlin firmware, Marlin/src/gcode/parser.cpp (GCodeParser::parse)"
    on_ignored_command = True

    def check_ignored(self, line: Line, cmd: Command) -> None:
        first = line.commands[0].code or "the first command"
        what = cmd.code or "these words"
        self.report(
            line,
            f"{what} never runs: {self.ctx.dialect.title.split(' (')[0]} runs only the first command of a line "
            f"({first}) and reads the rest as its parameters; put {what} on a line of its own",
            node=cmd,
        )


# OctoPrint's built-in @ commands and what each does (docs.octoprint.org, Features, "@ Commands", version 1.3.7 on:
# "@cancel: OctoPrint will cancel the current print job like if the "Cancel" button had been clicked", "@abort:
# Same as cancel", "@pause ... just like if the "Pause" button had been clicked", "@resume ... just like if the
# "Resume" button had been clicked").  OctoPrint looks its handlers up by the name as written (comm.py
# _process_atcommand_phase: "_atcommand_{name}_{phase}"), so "@PAUSE" is not one of them.
HOST_ACTIONS = {
    "@pause": ("pauses the print, as if its Pause button had been clicked", Severity.INFO),
    "@resume": ("resumes a paused print, as if its Resume button had been clicked", Severity.INFO),
    "@cancel": ("cancels the print, as if its Cancel button had been clicked: the lines after it never run", None),
    "@abort": ("cancels the print (as @cancel): the lines after it never run", None),
}


@register
class HostCommand(Rule):
    code = "DL007"
    name = "host-command"
    severity = Severity.WARNING
    summary = "An OctoPrint @ command that acts on the print: @pause, @resume (info), @cancel, @abort"
    explanation = """
        A line that starts with "@" and a name is an OctoPrint @ command (a "host command"): OctoPrint runs it
        itself and never sends it to the printer.  Plugins add their own (`@BEDLEVELVISUALIZER` asks the Bed
        Visualizer plugin to record the mesh that the next G29 reports) and gclint reads them as what they
        are, not as G-code words.  OctoPrint's own commands act on the print: `@pause` and `@resume` pause
        and resume it (reported as info, as a pause written on purpose), `@cancel` and `@abort` cancel it,
        so the rest of the job never runs when it is printed through OctoPrint (a warning).  Printed from
        the printer's SD card or by another host, the line reaches the firmware, which does not know it.
        OctoPrint matches the names as written: `@PAUSE` is none of these.
    """
    example_bad = "G1 X10 Y10\n@cancel\nG1 X20 Y20"
    example_good = "G1 X10 Y10\n@BEDLEVELVISUALIZER\nG29"
    source = "OctoPrint documentation, Features, @ Commands (docs.octoprint.org/en/1.10.1/features/atcommands.html)"
    codes = tuple(HOST_ACTIONS)

    def check(self, line: Line, cmd: Command) -> None:
        does, severity = HOST_ACTIONS[cmd.code]  # type: ignore[index]
        self.report(line, f"{cmd.code}: OctoPrint {does} (an OctoPrint @ command)", node=cmd, severity=severity)
