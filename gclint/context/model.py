"""``Context``: what a file was read as (dialect, Hyrel firmware version, printer model) and why."""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields

from gclint.secrets import mask

# Where the dialect came from, strongest first.
OPTION = "option"  # --dialect / --printer on the command line
CONFIGURATION = "configuration"  # gclint.toml / pyproject.toml
DIRECTIVE = "directive"  # "; gclint: dialect=NAME" in the file
CONTENT = "content"  # codes and addressing only one dialect has
HEADER = "header"  # the slicer's flavour (";FLAVOR:", "; gcode_flavor =", SLIC3R_GCODE_FLAVOR)
EXTENSION = "extension"  # the file extension, as a tie-breaker
DEFAULT = "default"  # nothing decided: the first target, hyrel

EXPLICIT_ORIGINS = (OPTION, CONFIGURATION, DIRECTIVE)

# How sure the decision is.
EXPLICIT = "explicit"  # the user said so
STRONG = "strong"  # clear evidence, nothing against it
WEAK = "weak"  # little evidence, or evidence against it: shown to the user
NONE = "none"  # nothing decided: the default


@dataclass(frozen=True)
class Context:
    """The context a file is checked in, with the evidence kept for the user.

    ``version_evidence`` is what the file's own Hyrel addresses say (4, 5, or None when they say
    nothing or are even), whatever version the file is checked as: HY008 reports v4 numbers in a file
    checked as v5 only when the file's evidence says v4.

    The evidence texts quote the file (``M587 S"home" P"..." at line 2``), and every output shows them
    (``why()``, ``to_dict()``: notes, SARIF, JUnit, HTML, explain, the cache): their secrets are masked
    here, once, as the context is made (gclint.context.content masks what it quotes before cutting it
    short; this catches the rest: header lines, a context built by ``from_dict``).
    """

    dialect: str
    origin: str = DEFAULT
    strength: str = NONE
    reasons: tuple[str, ...] = ()
    conflict: str = ""
    firmware: int | None = None  # Hyrel: 4 or 5
    firmware_origin: str = DEFAULT
    firmware_reasons: tuple[str, ...] = ()
    version_evidence: int | None = None
    printer: str | None = None  # Hyrel model (gclint.machine.profiles), None for other dialects
    printer_origin: str = DEFAULT
    printer_reasons: tuple[str, ...] = ()
    printer_candidates: tuple[str, ...] = ()  # every model the job fits as well (the first is ``printer``)
    flavor: str | None = None  # the firmware a Marlin-flavour file was written for (gclint.firmware)
    flavor_reasons: tuple[str, ...] = ()
    # every candidate reading's score, best first (``marlin/klipper``: Marlin with Klipper's inventory), and
    # what costs the leading ones most (gclint.context.score): ``gclint check -v`` shows them
    candidates: tuple[tuple[str, float], ...] = ()
    candidate_reasons: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        for name in _EVIDENCE:
            value = getattr(self, name)
            shown: str | tuple
            if isinstance(value, str):
                shown = mask(value)
            elif isinstance(value, tuple):
                shown = tuple(mask(text) if isinstance(text, str) else text for text in value)
            else:
                continue  # (not evidence text: from_dict's caller rejects it)
            if shown != value:
                object.__setattr__(self, name, shown)

    @property
    def printer_assumed(self) -> bool:
        """True when no one said which model the job is for (the default, or read from the job)."""
        return self.printer is not None and self.printer_origin not in (OPTION, CONFIGURATION)

    @property
    def assumed(self) -> bool:
        """True when the dialect is only the default reading: nothing in the file is for it (no evidence at
        all, or none that sets it above another dialect but the default's prior).  The findings of its
        dialect's rules are then information (gclint.engine): true of the default dialect, not of the file."""
        return self.strength == NONE

    def assumed_note(self) -> str:
        """What a finding of the assumed dialect's rules adds."""
        return f" (dialect assumed: nothing in the file says it is for {self.dialect_label()}; set it with --dialect)"

    @property
    def weak(self) -> bool:
        """True when the user should be told how the file was read (little or conflicting evidence)."""
        return self.strength in (WEAK, NONE) or bool(self.conflict)

    def dialect_label(self) -> str:
        """``hyrel v5`` / ``marlin`` / ``marlin (prusa-buddy)``: the label without the printer."""
        text = self.dialect
        if self.flavor is not None:
            text += f" ({self.flavor})"
        if self.firmware is not None:
            text = f"hyrel v{self.firmware}"
        return text

    def label(self) -> str:
        """``hyrel v5, printer 30m (assumed)`` / ``marlin`` / ``marlin (prusa-buddy)``."""
        text = self.dialect_label()
        if self.assumed:
            text += " (assumed)"
        if self.printer is not None:
            text += f", printer {self.printer}"
            if self.printer_origin == DEFAULT:
                text += " (assumed)"
            elif self.printer_assumed:
                text += " (from the job)"
        return text

    def why(self) -> str:
        """Why the file was read so, in one sentence (for notes and -v)."""
        if self.origin in (OPTION, CONFIGURATION) and self.reasons:
            base = f"set by {self.reasons[0]}"  # a declared firmware (--flavor) says its dialect
        elif self.origin == OPTION:
            base = "set with --dialect"
        elif self.origin == CONFIGURATION:
            base = "set in the configuration"
        elif self.origin == DIRECTIVE:
            base = "set by a '; gclint: dialect=' line"
        elif self.origin == DEFAULT:
            base = "nothing in the file tells the dialect; hyrel is the default"
        else:
            evidence = "; ".join(self.reasons[:3])
            base = {CONTENT: "content", HEADER: "slicer header", EXTENSION: "file extension"}[self.origin]
            base = f"{base}: {evidence}" if evidence else base
        parts = [base]
        if self.conflict:
            parts.append(self.conflict)
        if self.firmware is not None and self.firmware_origin not in EXPLICIT_ORIGINS and self.firmware_reasons:
            parts.append(f"v{self.firmware}: " + "; ".join(self.firmware_reasons[:3]))
        if self.flavor is not None and self.flavor_reasons and self.flavor_reasons != self.reasons:
            parts.append(f"{self.flavor}: " + "; ".join(self.flavor_reasons[:2]))
        if self.printer is not None and self.printer_reasons and self.printer_origin not in (OPTION, CONFIGURATION):
            parts.append(f"printer {self.printer}: " + "; ".join(self.printer_reasons[:2]))
        return "; ".join(parts)

    def model_note(self) -> str:
        """What a finding that rests on the printer model adds: which model it assumed and why."""
        if not self.printer_assumed:
            return ""
        if self.printer_origin == DEFAULT:
            return f" (printer assumed: {self.printer}, the default; set it with --printer)"
        told = self.printer_reasons[0].split(": ")[0].removesuffix(" names it") if self.printer_reasons else "the job"
        return f" (printer {self.printer}, from {told}; set another with --printer)"

    @property
    def printer_from(self) -> str:
        """Where the model came from: ``option``, ``configuration``, ``job`` or ``default``."""
        if self.printer_origin in (OPTION, CONFIGURATION):
            return self.printer_origin
        return "job" if self.printer_origin == CONTENT else "default"

    def scores_text(self) -> str:
        """``hyrel 9.5, marlin -14, ...``: the candidates' scores (``-v``), and what costs the leading ones."""
        if not self.candidates:
            return ""
        shown = ", ".join(f"{name} {value:g}" for name, value in self.candidates[:6])
        more = len(self.candidates) - 6
        text = f"scores {shown}" + (f" (and {more} more)" if more > 0 else "")
        if self.candidate_reasons:
            text += "; against: " + "; ".join(self.candidate_reasons[:3])
        return text

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict) -> Context:
        known = {f.name for f in fields(cls)}
        values = {k: _tuples(v) for k, v in data.items() if k in known}
        return cls(**values)


def _tuples(value):
    """JSON lists back to the tuples a context holds (``candidates`` holds pairs)."""
    return tuple(_tuples(v) for v in value) if isinstance(value, list) else value


# The fields that quote the file (what the user is told as evidence).
_EVIDENCE = ("reasons", "conflict", "firmware_reasons", "printer_reasons", "flavor_reasons", "candidate_reasons")
