"""The walker: explains lines in order through the machine ``Interpreter``, so "the head with current
focus", relative moves, the fan range and stored offsets are the ones the job set up.  A command goes to
its topic's decoder when it has one (``TOPICS``), else it is read from the dialect's table alone."""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator

from gclint import secrets
from gclint.dialects.base import Dialect
from gclint.explain import addressing, arcs, fans, flow, jobflow, lasers_spindles, motion, offsets, temperature
from gclint.explain.generic import generic, title, unknown
from gclint.explain.job import Decoder, Job
from gclint.explain.model import Explanation, secret_values
from gclint.machine.state import MachineState
from gclint.rules.hyrel.jobflow import exponent_message
from gclint.syntax.build import exponents
from gclint.syntax.nodes import ASSIGNMENT, EXTENDED, GCODE, HOST, IMPLICIT, META, OWORD, PERCENT, TEXT, Command, Line
from gclint.syntax.source import Source

# One module per topic; each says which codes it decodes for a job's dialect (``decoders(job)``: by the codes'
# effects and the dialect's facts, never its name).
TOPICS = (motion, offsets, temperature, fans, arcs, flow, addressing, lasers_spindles, jobflow)


class Explainer(Job):
    """Explains lines in order, keeping the machine state between them."""

    def __init__(self, dialect: Dialect, state: MachineState | None = None) -> None:
        super().__init__(dialect, state)
        self._decoders: dict[str, Decoder] = {}
        for topic in TOPICS:
            self._decoders.update(topic.decoders(self))
        self._word_issues = _word_issues(dialect)
        self._exponents = _rule_applies("HY067", dialect)  # (numbers in exponent notation)

    def explain_line(self, line: Line) -> list[Explanation]:
        """The line's commands in the order the machine runs them (LinuxCNC's order of execution), with its
        secrets masked (the command line and the editor's hover show them as they are); those the machine does
        not run (Marlin runs a line's first command only) are said so."""
        out = []
        self.state.line_number = line.number
        values, starts = _secrets_of(line.raw)  # (once for the line: it may hold 30,000 commands)
        commands = line.commands
        facts = self.facts
        issues = _issues_by_command(line, starts, self._word_issues) if line.parsed.issues else {}
        for cmd in facts.running(commands) if len(commands) > 1 else commands:
            hidden = _hidden_words(cmd, starts) if starts else ()
            exp = self.explain_command(cmd, line)
            if self._exponents:
                for _, _, number in exponents(cmd):
                    exp.warn(exponent_message(number))  # (as HY067 reports it)
            for message in issues.get(id(cmd), ()):
                exp.warn(message)  # (as check reports it: SX002, SX006, SX007)
            out.append(exp.masked(values, hidden))
            self.interpreter.apply(cmd, line)
        for cmd in facts.ignored(commands):
            exp = Explanation(line.number, line.raw, cmd.code, "not run").masked(values, ())
            exp.warn(
                f"{self.dialect.title.split(' (')[0]} runs only the first command of a line: the rest are its "
                "parameters"
            )
            out.append(exp)
        return out

    def explain_command(self, cmd: Command, line: Line) -> Explanation:
        code = cmd.code
        if cmd.kind == GCODE and code:
            if code[0] == "T" and code[1:].lstrip("-").isdigit():
                return addressing.tool(self, cmd, line)
            spec = self.dialect.spec(code)
            exp = Explanation(line.number, line.raw, code, title(self.dialect, code, spec))
            if not self.dialect.knows(code):
                unknown(self.dialect, exp, cmd)
                return exp
            if spec is not None and not spec.supported:
                exp.warn(f"{self.dialect.title} does not support {code}")
            decoder = self._decoders.get(code)
            if decoder is not None:
                decoder(self, exp, cmd, spec)
            else:
                generic(self.dialect, exp, cmd, spec)
            return exp
        return self._other(cmd, line)

    def _other(self, cmd: Command, line: Line) -> Explanation:
        """Lines that are not a G/M/T code: modal axis words, free text, Klipper, RepRapFirmware meta
        commands, O-words, parameter assignments, ``%``."""
        kind = cmd.kind
        if kind == IMPLICIT:
            mode = self.state.motion_mode
            params = cmd.params
            if params and all(letter in self.facts.words_first for letter in params):
                # words with no command that the machine sets before the line's commands (LinuxCNC's F, S, T:
                # "S10000 M3"): modal values, no motion
                exp = Explanation(line.number, line.raw, None, "words with no command: they set modal values")
                motion.spindle_speed(self, exp, cmd)
                f = cmd.param("F")
                if f is not None:
                    exp.add(f.text.strip(), f"the feed of later moves: {f.value} mm/min")
                generic(self.dialect, exp, cmd, None, skip="SF")
                return exp
            if mode is None:
                exp = Explanation(
                    line.number, line.raw, None, "axis words with no motion code: no modal motion is active"
                )
                generic(self.dialect, exp, cmd, None)
                return exp
            exp = Explanation(line.number, line.raw, None, f"modal {mode} move: the words repeat the last motion code")
            motion.move(self, exp, cmd, self.dialect.spec(mode), mode)
            return exp
        if kind == TEXT:
            spec = self.dialect.spec(cmd.code or "")
            exp = Explanation(line.number, line.raw, cmd.code, title(self.dialect, cmd.code or "", spec))
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
        if kind == HOST:
            from gclint.rules.dialect import HOST_ACTIONS

            exp = Explanation(
                line.number,
                line.raw,
                cmd.code,
                "OctoPrint @ command: OctoPrint runs it and never sends it to the printer",
            )
            action = HOST_ACTIONS.get(cmd.code or "")
            if action is not None:
                exp.add(cmd.code or "", f"OctoPrint {action[0]}")
            else:
                exp.add(
                    cmd.code or "", "a plugin's command, if a plugin handles it: OctoPrint itself does nothing with it"
                )
            return exp
        return Explanation(line.number, line.raw, cmd.code, f"{kind} command")


def _secrets_of(raw: str) -> tuple[tuple[str, ...], tuple[int, ...]]:
    """The secret values of a line, longest first, and the columns where its secrets start."""
    if not secrets.may_hold(raw):
        return (), ()
    found = secrets.find(raw)
    return secret_values(raw) if found else (), tuple(s.start + 1 for s in found)


# The parser's findings on the words of a command (check reports them as these rules): a repeated letter, a
# value that is not a number, a number with no letter.
_WORD_ISSUES = ("SX002", "SX006", "SX007")


def _rule_applies(code: str, dialect: Dialect) -> bool:
    """Whether the rule ``code`` checks files of ``dialect`` (what explain says, check says)."""
    from gclint.rules.base import all_rules

    rule = all_rules().get(code)
    return rule is not None and rule.applies_to(dialect)


def _word_issues(dialect: Dialect) -> frozenset[str]:
    """The codes of ``_WORD_ISSUES`` whose rule checks files of ``dialect``."""
    return frozenset(code for code in _WORD_ISSUES if _rule_applies(code, dialect))


def _issues_by_command(line: Line, starts: tuple[int, ...], codes: frozenset[str]) -> dict[int, list[str]]:
    """The parser's word issues of a line (``codes``), by the command (``id``) they fall in; none from a secret
    on."""
    commands = line.commands
    secret = min(starts, default=None)
    found: dict[int, list[str]] = {}
    for issue in line.parsed.issues:
        if issue.code not in codes or (secret is not None and issue.column >= secret):
            continue
        cmd = max((c for c in commands if c.column <= issue.column), key=lambda c: c.column, default=None)
        if cmd is not None:
            found.setdefault(id(cmd), []).append(issue.message)
    return found


def _hidden_words(cmd: Command, starts: tuple[int, ...]) -> frozenset[str]:
    """The words of ``cmd`` from its first secret on ("M551 Phunter2" is read as the words P, h, u, n, t, e,
    r2: each would show a letter of the password, and SX002 would name the repeated ones)."""
    start = min((column for column in starts if column >= cmd.column), default=None)
    if start is None:
        return frozenset()
    return frozenset(word.text.strip() for word in cmd.words if word.end_column > start)


def explain_lines(
    lines: Iterable[tuple[str, str]], dialect: Dialect, state: MachineState | None = None
) -> Iterator[Explanation]:
    """Explanations of ``(text, ending)`` lines, in order."""
    explainer = Explainer(dialect, state)
    read = dialect.semantics.parse  # (LinuxCNC ignores blanks: X 2 0 is X20)
    for number, (raw, ending) in enumerate(lines, start=1):
        yield from explainer.explain_line(Line(number, raw, ending, read(raw)))


def explain_text(text: str, dialect: Dialect, state: MachineState | None = None) -> list[Explanation]:
    """Explain G-code given as text (one or more lines)."""
    return list(explain_lines(((line, "\n") for line in re.split(r"\r\n|\r|\n", text)), dialect, state))


def explain_source(source: Source, dialect: Dialect, state: MachineState | None = None) -> Iterator[Explanation]:
    """Explain a whole file, streaming."""
    return explain_lines(source.lines(), dialect, state)
