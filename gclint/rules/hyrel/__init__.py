"""HY: Hyrel semantics, from the Hyrel wiki pages Gcode, T_v5 and Sekret! (docs/sources.md).

One module per topic; importing this package registers the rules.
"""

from gclint.rules.hyrel import (  # noqa: F401
    addressing,
    arcs,
    flow,
    jobflow,
    lasers_spindles,
    motion,
    offsets,
    temperature,
)
