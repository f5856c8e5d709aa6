"""What a file is: its dialect, Hyrel firmware version and printer model, decided from the evidence (what
the user said, the content, the slicer header, the extension) with the reasons kept for the user.

``infer(head, path, ...)`` is the one place this is decided; the check, ``explain``, ``postprocess`` and
the reports all use its ``Context``.
"""

from gclint.context.decide import SLICER_FLAVORS, infer, infer_source, slicer_flavor
from gclint.context.model import Context

__all__ = ["Context", "infer", "infer_source", "slicer_flavor", "SLICER_FLAVORS"]
