"""What a file is: its dialect (and firmware flavour), Hyrel firmware version and printer model.  What the
user said wins; otherwise every candidate reading is scored on how well it explains the file
(gclint.context.score), and the version and model are decided by the weight of all its lines
(gclint.context.version, gclint.context.printer).  The reasons and every reading's score are kept for the user.

``infer(head, path, ...)`` is the one place this is decided; the check, ``explain``, ``postprocess`` and
the reports all use its ``Context``.
"""

from gclint.context.decide import SLICER_FLAVORS, infer, infer_source, scores, slicer_flavor
from gclint.context.model import Context

__all__ = ["Context", "infer", "infer_source", "scores", "slicer_flavor", "SLICER_FLAVORS"]
