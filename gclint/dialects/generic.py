"""``generic``: the reading of a file that no known dialect explains (a GRBL job with ``$H``, Mach3, cncjs...).

Such a file is parsed, and the security rules and the rules written for every dialect check it; no HY or DL rule
does, since nothing says which machine's tables apply.  Its semantics say only what holds everywhere: G4's units,
what G28 does and where a move ends after homing are not known.
"""

from __future__ import annotations

from gclint.dialects.base import Detection, Dialect, LineMark
from gclint.dialects.semantics import DWELL_UNKNOWN, Semantics

# What says a file was written for a machine no known dialect describes.  gclint.context counts each as a large
# misfit for every known dialect (evidence for ``generic`` is evidence against all of them), so ``generic`` wins
# only when no known dialect explains the file; content one dialect has alone still outweighs a comment.
GENERIC_DETECTION = Detection(
    patterns=(
        # Senders and CAM tools of GRBL machines (Shapeoko, jscut, bCNC, LaserGRBL, Universal Gcode Sender,
        # Carbide Create/Motion) named in a comment
        (
            r"(?im)^[^;(\n]*[;(][^\n]*\b(?:grbl|shapeoko|jscut|bcnc|lasergrbl|universal ?g-?code ?sender"
            r"|carbide ?(?:create|motion)|mach ?[34])\b",
            10,
        ),
        # jscut's header block ("; Operation: 0", "; Type: Engrave", "; Plunge rate: 127", "; Cut rate: 1016")
        (r"(?im)^;[ \t]*plunge rate:[ \t]*\d", 10),
        # a plasma torch-height controller's S-codes (Mach3 plasma posts: "S900 ;(Global DTHC ON/OFF is ON)")
        (r"(?im)^[^;(\n]*[;(][^\n]*\bD?THC\b", 10),
    ),
    # GRBL's system commands: "$H" (home), "$X" (unlock), "$J=..." (jog), "$32=1" (a setting); the grammar reads
    # "$H" as two flags and "$32=1" not at all: no known dialect has a line starting with "$"
    line_marks=(
        LineMark("$", r"^\s*\$", "a GRBL system command ($H, $X, $J=, $32=1): no known dialect has it", weight=8),
    ),
    prior=-4.5,  # the fixed score a known dialect must beat: only large misfits take every known one below it
)

GENERIC = Dialect(
    name="generic",
    title="generic G-code (no known dialect)",
    family="generic",
    codes={},
    aliases=("unknown",),
    detection=GENERIC_DETECTION,
    extended_commands=True,
    meta_commands=True,
    owords=True,
    open_codes=lambda code: True,
    unknown_severity="info",
    description="A file no known dialect explains: parsing, security and dialect-free rules only.",
    semantics=Semantics(dwell=DWELL_UNKNOWN, home="clearance"),
    known=False,
)
