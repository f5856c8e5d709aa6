"""How long a job takes: a motion planner over the reader's moves (``gclint.simulate`` events).

``limits.py`` says what the machine may do (accelerations, speeds, jerk or junction deviation): from the slicer's
machine limits in the job's settings, the job's own M201/M203/M204/M205 (and the like) as they run, and otherwise
the firmware's documented defaults where there are some.  ``planner.py`` turns moves into time the way a
firmware's planner does (Marlin's, which PrusaSlicer's and BambuStudio's estimators copy): trapezoidal speed
profiles, junction speeds limited by jerk or junction deviation, a backward and a forward pass over a bounded
look-ahead window, so a multi-million-line job takes linear time and constant memory.  ``slicer.py`` reads what
the slicer wrote about the job: its settings and its own time estimate.
"""

from gclint.timing.limits import MachineLimits, limits_for
from gclint.timing.planner import Planner
from gclint.timing.slicer import slicer_estimate, slicer_settings

__all__ = ["MachineLimits", "Planner", "limits_for", "slicer_estimate", "slicer_settings"]
