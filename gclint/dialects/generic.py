"""``generic``: the reading of a file that no known dialect explains (a GRBL job with ``$H``, Mach3, cncjs...).

Such a file is parsed, and the security rules and the rules written for every dialect check it; no HY or DL rule
does, since nothing says which machine's tables apply.  Its semantics say only what holds everywhere: G4's units,
what G28 does and where a move ends after homing are not known.
"""

from __future__ import annotations

from gclint.dialects.base import Detection, Dialect
from gclint.dialects.semantics import DWELL_UNKNOWN, Semantics

GENERIC = Dialect(
    name="generic",
    title="generic G-code (no known dialect)",
    family="generic",
    codes={},
    aliases=("unknown",),
    detection=Detection(),
    extended_commands=True,
    meta_commands=True,
    owords=True,
    open_codes=lambda code: True,
    unknown_severity="info",
    description="A file no known dialect explains: parsing, security and dialect-free rules only.",
    semantics=Semantics(dwell=DWELL_UNKNOWN, home="clearance"),
    known=False,
)
