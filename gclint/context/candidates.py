"""The readings ``--dialect auto`` chooses between: every known dialect (Hyrel once: v4 or v5 is decided
afterwards, gclint.context.version), each with the firmware flavours whose files it reads (Marlin with Prusa
Buddy, Prusa MK3, Bambu, Klipper, FABlin and the 2015 RepRap firmwares), and ``generic``, the reading of a file no
known dialect explains.

A candidate is asked what the scoring needs: whether it has a code (its dialect's table, and its flavour's
inventory), whether it runs a code it does not list (a RepRapFirmware macro, a LinuxCNC user M-code), whether
its language has a kind of line.  Everything comes from the dialects' and firmwares' own tables.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache, lru_cache

from gclint import dialects, firmware
from gclint.dialects.base import Dialect
from gclint.firmware import Firmware
from gclint.syntax.nodes import EXTENDED

# A flavour starts this far below its dialect: a Marlin file is plain Marlin until something says which
# firmware it was written for (a printer_model line, a command only that firmware has).
FLAVOR_PRIOR = -1.0


@dataclass(frozen=True)
class Candidate:
    """One reading of a file: a dialect, and the firmware flavour of it (None: the dialect's own table)."""

    dialect: Dialect
    flavor: Firmware | None = None

    @property
    def key(self) -> str:
        """``marlin``, ``marlin/klipper``, ``generic``."""
        return self.dialect.name if self.flavor is None else f"{self.dialect.name}/{self.flavor.name}"

    @property
    def known(self) -> bool:
        return self.dialect.known

    @property
    def prior(self) -> float:
        return self.dialect.detection.prior + (FLAVOR_PRIOR + self.flavor.detection.prior if self.flavor else 0.0)

    def has(self, code: str) -> bool:
        """Whether the candidate's tables have ``code`` (its dialect's, or its flavour's inventory when the
        flavour's codes mark the dialect: not the 2015 page, which lists every firmware's numbers)."""
        if code in self.dialect.codes:
            return True
        flavor = self.flavor
        return flavor is not None and flavor.marks_dialect and code in flavor.codes

    def lists_loosely(self, code: str) -> bool:
        """Whether the flavour's inventory lists ``code`` without marking the dialect (the 2015 RepRap page
        lists the numbers of many firmwares of its time, Hyrel's among them)."""
        flavor = self.flavor
        return flavor is not None and not flavor.marks_dialect and code in flavor.codes

    def runs_unlisted(self, code: str) -> bool:
        """Whether the firmware runs ``code`` though its table does not list it (RepRapFirmware's macro files,
        LinuxCNC's user M-codes M100-M199)."""
        open_codes = self.dialect.open_codes
        return open_codes is not None and open_codes(code)

    def supported(self, code: str) -> bool:
        spec = self.dialect.codes.get(code)
        return spec is None or spec.supported

    def accepts(self, kind: str, word: str) -> bool:
        """Whether the candidate's language has a line of ``kind`` (``extended``, ``meta``, ``oword``,
        ``assignment``) whose word is ``word``."""
        if self.dialect.accepts(kind, word):
            return True
        flavor = self.flavor
        if flavor is None:
            return False
        return (kind == EXTENDED and flavor.extended_commands) or word.upper() in flavor.words


@cache
def candidates() -> tuple[Candidate, ...]:
    """Every candidate, the dialects' own first (in the registry's order), then the flavours, ``generic``
    last."""
    own = [Candidate(d) for d in dialects.all_dialects() if d.variant_of is None]
    flavors = [Candidate(d, f) for d in dialects.known_dialects() for f in firmware.flavors_of(d.name)]
    known = [c for c in own if c.known]
    return (*known, *flavors, *(c for c in own if not c.known))


@cache
def dialect_candidates() -> tuple[Candidate, ...]:
    """The known dialects' own readings (no flavour, no ``generic``)."""
    return tuple(c for c in candidates() if c.known and c.flavor is None)


@cache
def flavor_candidates(dialect: str) -> tuple[Candidate, ...]:
    """``dialect``'s own reading and its flavours'."""
    return tuple(c for c in candidates() if c.dialect.name == dialect)


@lru_cache(maxsize=4096)
def having(code: str) -> frozenset[str]:
    """The known dialects that have ``code``, in their table or in a flavour's inventory that marks them."""
    return frozenset(c.dialect.name for c in candidates() if c.known and c.has(code))


__all__ = ["Candidate", "FLAVOR_PRIOR", "candidates", "dialect_candidates", "flavor_candidates", "having"]
