"""Tools, heaters, fans and flow of a source printer (Marlin, RepRapFirmware, Machinekit FDM).

What a source firmware does with them (research/dialects.md 1.3 and 1.4; Marlin and RepRapFirmware G-code
references; the Machinekit FDM README in the seeds):

* Each tool (extruder index) has its own set-point; ``M104``/``M109`` without ``T`` address the active
  tool.  A job that prints with a tool whose set-point it never set runs on a single-nozzle machine (one
  heater shared by every filament, as with a multi-material unit): Marlin refuses cold extrusion, so
  such a job only makes sense with a shared nozzle.  From then on the nozzle's set-point, wait and flow
  are the last ones set, whatever tool is active.
* The part-cooling fan (fan 0, ``M106``/``M107`` without ``P``) is one fan: it cools whatever the active
  tool prints.  Other fan indices are other devices.
* ``M221`` is a percentage per extruder (a multiplier of 1.0 = 100 %).
* RepRapFirmware: ``M563 P<tool> F<fans>`` gives a tool fans of its own, and ``M106`` without ``P`` drives
  "fans of current tool" (research/dialects.md 1.3 M106, 1.5 M563).  A fan that one tool owns is that
  tool's head's fan (Hyrel's fans are per head); fan 0 of tools that declare none is the part fan above.
"""

from __future__ import annotations

from gclint.simulate.trace import PART_FAN, Mapping


def heat_wait(old: tuple[float, float | None] | None, value: float, both_ways: bool) -> float:
    """The set-point a wait for ``value`` leaves waited for, from the heater's ``old`` (set-point, waited).
    A wait that only heats (Marlin and RRF ``M109 S``, "set & wait only when heating"; Hyrel ``M109`` with
    no C/U/R, "waits until T >= S-1 °C (heating only)": research/dialects.md 1.3 M109) does not wait when
    the heater was waited to ``value`` or more and not set below it since: the nozzle is hotter, and
    what it was waited to stays."""
    if not both_ways and old is not None and old[1] is not None and old[1] > value and old[0] >= value:
        return old[1]
    return value


class ToolHeat:
    """The set-points, waits, fans and flow of a source printer, per tool index."""

    def __init__(self, mapping: Mapping) -> None:
        self.mapping = mapping
        self.tool: int | None = 0  # the active tool (Marlin starts with T0)
        self.temps: dict[int, tuple[float, float | None]] = {}  # tool -> (set-point, set-point waited for)
        self.nozzle: tuple[float, float | None] | None = None  # the last set-point set on any tool
        self.shared = False  # a single-nozzle machine (inferred)
        self.flows: dict[int, float] = {}
        self.last_flow: float | None = None
        self.fans: dict[int, float] = {}  # fan index -> fraction
        self.beds: dict[int, tuple[float, float | None]] = {}  # Hyrel address -> (set-point, waited)
        self.used: set[int] = set()  # tools that printed
        self.tool_fans: dict[int, tuple[int, ...]] = {}  # RepRapFirmware M563 F: a tool's own fans

    # -- commands --------------------------------------------------------------------------------------

    def set_temp(self, tool: int | None, value: float | None, wait: bool, both_ways: bool = False) -> None:
        """``M104``/``M109`` on ``tool`` (None: the active tool); ``value`` None: wait for the set-point.
        ``both_ways``: the wait cools too (Marlin/RRF ``M109 R``, Machinekit's in-range wait); else it waits
        only while heating (``M109 S``: research/dialects.md 1.3), see ``heat_wait``."""
        if tool is None:
            tool = self.tool if self.tool is not None else 0
        old = self.nozzle if self.shared else self.temps.get(tool)
        if value is None:
            if old is None:
                return
            value = old[0]
        if value < 0:
            value = 0.0  # RepRapFirmware's -273.15: heater off
        waited = heat_wait(old, value, both_ways) if wait else (old[1] if old is not None else None)
        entry = (value, waited)
        self.temps[tool] = entry
        self.nozzle = entry

    def wait_all(self) -> None:
        """RepRapFirmware ``M116``: wait for every set-point."""
        self.temps = {t: (v, v) for t, (v, _) in self.temps.items()}
        if self.nozzle is not None:
            self.nozzle = (self.nozzle[0], self.nozzle[0])
        self.beds = {a: (v, v) for a, (v, _) in self.beds.items()}

    def set_bed(self, address: int, value: float | None, wait: bool) -> None:
        old = self.beds.get(address)
        if value is None:
            if old is None:
                return
            value = old[0]
        if value < 0:
            value = 0.0
        self.beds[address] = (value, value if wait else (old[1] if old is not None else None))

    def set_flow(self, tool: int | None, fraction: float) -> None:
        if tool is None:
            tool = self.tool if self.tool is not None else 0
        self.flows[tool] = fraction
        self.last_flow = fraction

    def set_fan(self, index: int, fraction: float) -> None:
        self.fans[index] = max(0.0, min(1.0, fraction))

    def owner(self, fan: int) -> int | None:
        """The tool that alone lists ``fan`` among its own (M563 F), or None."""
        owners = [tool for tool, fans in self.tool_fans.items() if fan in fans]
        return owners[0] if len(owners) == 1 else None

    def own_fan(self, tool: int | None) -> float | None:
        """The value of the fans ``tool`` owns alone (the most of them), or None when it has none."""
        if tool is None:
            return None
        fans = [f for f in self.tool_fans.get(tool, ()) if self.owner(f) == tool]
        if not fans:
            return None
        return max(self.fans.get(f, 0.0) for f in fans)

    # -- what the working head sees --------------------------------------------------------------------

    def working(self) -> tuple[tuple[float | None, bool, float | None], float]:
        """(set-point, readiness and the set-point last waited for, flow) of the active tool, inferring a shared nozzle when the tool
        never got a set-point of its own."""
        tool = self.tool
        if tool is not None:
            self.used.add(tool)
        if not self.shared and tool is not None and tool not in self.temps and self.nozzle is not None:
            self.shared = True
        heat = self.nozzle if self.shared else self.temps.get(tool) if tool is not None else None
        if self.shared:
            flow = self.last_flow if self.last_flow is not None else 1.0
        else:
            flow = self.flows.get(tool, 1.0) if tool is not None else 1.0
        if heat is None:
            return (None, False, None), flow
        return (heat[0], heat[1] == heat[0], heat[1]), flow

    def head(self) -> int | str | None:
        return self.mapping.head(self.tool) if self.tool is not None else None

    def bed_look(self) -> tuple:
        return tuple(sorted((a, v, w == v) for a, (v, w) in self.beds.items()))

    def aux_fans(self) -> tuple:
        out = []
        for index, value in sorted(self.fans.items()):
            if index == 0 or value <= 0 or self.owner(index) is not None:
                continue
            address = self.mapping.fan_map.get(index)
            out.append((f"T{address} fan" if address is not None else f"fan {index}", round(value, 3)))
        return tuple(out)

    # -- the end -------------------------------------------------------------------------------------

    def end_heaters(self) -> dict:
        out: dict = {}
        if self.shared:
            if self.nozzle is not None and self.nozzle[0] > 0:
                for tool in self.used or {self.tool or 0}:
                    out[self.mapping.head(tool)] = self.nozzle[0]
        else:
            for tool, (value, _) in self.temps.items():
                if value > 0:
                    out[self.mapping.head(tool)] = value
        for address, (value, _) in self.beds.items():
            if value > 0:
                out[address] = value
        return out

    def end_fans(self) -> dict:
        out: dict = {}
        part = self.fans.get(0, 0.0)
        if part > 0 and self.owner(0) is None:
            # the one part fan, whatever tool is active: on Hyrel it is the fan of whichever head the
            # translation gave it (compare.py folds the output's head fans into it)
            out[PART_FAN] = round(part, 3)
        for tool in sorted(self.tool_fans):
            value = self.own_fan(tool)
            if value:
                out[self.mapping.head(tool)] = round(value, 3)
        for label, value in self.aux_fans():
            out[label] = value
        return out
