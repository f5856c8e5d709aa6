"""HY: Hyrel semantics, from the Hyrel Gcode page, T_v5 and the hidden-codes page (../shared/seeds).

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
