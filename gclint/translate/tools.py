"""The tool model: what the source firmware believes about its tools (set-points, waits, the part fan,
flow), so that the head Hyrel prints with gets the same when the active tool changes.

Source semantics (Marlin G-code reference and Duet G-code dictionary, M104/M109/M106/M221/T; issue 13):

* A set-point belongs to a tool (M104/M109 T, else the active tool).  A job that prints with a tool it
  never gave a set-point runs on a single-nozzle machine (one heater for every filament, as with a
  multi-material unit; Marlin refuses cold extrusion): from then on the nozzle's set-point, wait and
  flow are the last ones set, whatever tool is active, and every Hyrel head that prints for it must
  have them.
* The part-cooling fan (fan 0: M106/M107 without P) is one fan; it cools whatever the active tool prints.
  Hyrel's fans are per head, so the head that prints gets the fan's value, the one before it is
  switched off.
* Flow (M221) belongs to a tool (the nozzle's, on a single-nozzle machine).
"""

from __future__ import annotations


class SourceTools:
    def __init__(self) -> None:
        self.temps: dict[int, tuple[float, float | None]] = {}  # tool -> (set-point, set-point waited for)
        self.nozzle: tuple[float, float | None] | None = None  # the last set-point set on any tool
        self.shared = False  # a single-nozzle machine (inferred when a tool prints without a set-point)
        self.flows: dict[int, float] = {}
        self.last_flow: float | None = None
        self.fan = 0  # the part-cooling fan, 0-255

    def set_temp(self, tool: int, value: float | None, wait: bool) -> None:
        old = self.nozzle if self.shared else self.temps.get(tool)
        if value is None:
            if old is None:
                return
            value = old[0]
        value = max(value, 0.0)
        entry = (value, value if wait else (old[1] if old is not None else None))
        self.temps[tool] = entry
        self.nozzle = entry

    def wait_all(self) -> None:
        self.temps = {t: (v, v) for t, (v, _) in self.temps.items()}
        if self.nozzle is not None:
            self.nozzle = (self.nozzle[0], self.nozzle[0])

    def set_flow(self, tool: int, fraction: float) -> None:
        self.flows[tool] = fraction
        self.last_flow = fraction

    def heated(self) -> float | None:
        """On a single-nozzle machine, the set-point the nozzle was last waited to (it is at least that hot)."""
        return self.nozzle[1] if self.shared and self.nozzle is not None else None

    def working(self, tool: int) -> tuple[tuple[float, bool] | None, float | None, bool]:
        """(set-point and whether it was waited for, flow) the active tool prints with, and whether this
        call found the job to be a single-nozzle one."""
        inferred = False
        if not self.shared and tool not in self.temps and self.nozzle is not None:
            self.shared = inferred = True
        heat = self.nozzle if self.shared else self.temps.get(tool)
        flow = self.last_flow if self.shared else self.flows.get(tool)
        return (None if heat is None else (heat[0], heat[1] == heat[0])), flow, inferred
