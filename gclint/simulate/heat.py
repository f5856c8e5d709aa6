"""Tools, heaters, fans and flow of a source printer (Marlin, RepRapFirmware, Machinekit FDM).

What a source firmware does with them (the Marlin G-code reference and the Duet G-code
dictionary, M104/M109/M106/M221; the Machinekit-FDM README "Machinekit Flavor GCode"):

* Each tool (extruder index) has its own set-point; ``M104``/``M109`` without ``T`` address the active
  tool.  A job that prints with a tool whose set-point it never set runs on a single-nozzle machine (one
  heater shared by every filament, as with a multi-material unit): Marlin refuses cold extrusion, so
  such a job only makes sense with a shared nozzle.  From then on the nozzle's set-point, wait and flow
  are the last ones set, whatever tool is active.
* The part-cooling fan (fan 0, ``M106``/``M107`` without ``P``) is one fan: it cools whatever the active
  tool prints.  Other fan indices are other devices.
* ``M221`` is a percentage per extruder (a multiplier of 1.0 = 100 %).
* RepRapFirmware: ``M563 P<tool> F<fans>`` gives a tool fans of its own, and ``M106`` without ``P`` drives
  "fans of current tool" (Duet G-code dictionary, M106 and M563).  A fan that one tool owns is that
  tool's head's fan (Hyrel's fans are per head); fan 0 of tools that declare none is the part fan above.
"""

from __future__ import annotations

from collections import deque

from gclint.simulate.trace import PART_FAN, Mapping

# A heater's state: (set-point, lowest, highest): the temperatures the nozzle may be at from now until the next
# command about it (None: unknown, as cold as the room).  Ready: both are the set-point.
Heater = tuple[float, float | None, float | None]


def heat_set(old: Heater | None, value: float) -> Heater:
    """A set-point without a wait (M104): the nozzle goes towards ``value`` from where it may be."""
    if old is None:
        return (value, None, value)
    _, low, high = old
    return (value, None if low is None else min(low, value), value if high is None else max(high, value))


def heat_wait(old: Heater | None, value: float, both_ways: bool) -> Heater:
    """A wait for ``value``.  One that cools too (Marlin/RRF ``M109 R``, Hyrel's C/U/R, Machinekit's in-range
    wait, RRF M116) leaves the nozzle at the set-point.  One that only heats (Marlin and RRF ``M109 S``, "set &
    wait only when heating"; Hyrel ``M109`` with no C/U/R, "waits until T >= S-1 °C (heating only)":
    Marlin G-code reference, M109) leaves it at least at the set-point, and as hot as it may have been before
    (a nozzle waited to 250 °C and then set to 220 °C is not waited for at 220 °C)."""
    if both_ways:
        return (value, value, value)
    high = old[2] if old is not None else None
    return (value, value, value if high is None else max(high, value))


def heater_look(heat: Heater | None) -> tuple[float | None, bool, float | None]:
    """How a working head's heater is compared: (set-point, ready, the lowest temperature it may be at)."""
    if heat is None:
        return (None, False, None)
    target, low, high = heat
    return (target, low == target and high == target, low)


class ToolHeat:
    """The set-points, waits, fans and flow of a source printer, per tool index."""

    def __init__(self, mapping: Mapping) -> None:
        self.mapping = mapping
        self.tool: int | None = 0  # the active tool (Marlin starts with T0)
        self.temps: dict[int, Heater] = {}  # tool -> its heater
        self.nozzle: Heater | None = None  # the heater last set, whatever the tool
        self.shared = False  # a single-nozzle machine (inferred)
        self.one_nozzle = False  # the job's settings say so (single_extruder_multi_material): every tool is head 0's
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
        only while heating (``M109 S``: Marlin G-code reference, M109), see ``heat_wait``."""
        if tool is None:
            tool = self.tool if self.tool is not None else 0
        old = self.nozzle if self.shared else self.temps.get(tool)
        if value is None:
            if old is None:
                return
            value = old[0]
        if value < 0:
            value = 0.0  # RepRapFirmware's -273.15: heater off
        entry = heat_wait(old, value, both_ways) if wait else heat_set(old, value)
        self.temps[tool] = entry
        self.nozzle = entry

    def wait_all(self) -> None:
        """RepRapFirmware ``M116``: wait for every set-point ("within tolerance": heating or cooling)."""
        self.temps = {t: (v, v, v) for t, (v, _, _) in self.temps.items()}
        if self.nozzle is not None:
            v = self.nozzle[0]
            self.nozzle = (v, v, v)
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

    def working(self, infer: bool = True) -> tuple[tuple[float | None, bool, float | None], float]:
        """(``heater_look``: set-point, readiness, lowest temperature; flow) of the active tool, inferring a shared
        nozzle when the tool never got a set-point of its own (``infer`` False: what it would be, nothing kept)."""
        tool = self.tool
        shared = self.shared or (tool is not None and tool not in self.temps and self.nozzle is not None)
        if infer:
            if tool is not None:
                self.used.add(tool)
            self.shared = shared
        heat = self.nozzle if shared else self.temps.get(tool) if tool is not None else None
        if shared:
            flow = self.last_flow if self.last_flow is not None else 1.0
        else:
            flow = self.flows.get(tool, 1.0) if tool is not None else 1.0
        return heater_look(heat), flow

    def head(self) -> int | str | None:
        if self.one_nozzle:
            return self.mapping.head(0)
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
                for tool in {0} if self.one_nozzle else self.used or {self.tool or 0}:
                    out[self.mapping.head(tool)] = self.nozzle[0]
        else:
            for tool, (value, _, _) in self.temps.items():
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


class LayerHeights:
    """The layer height a source's printing moves are sliced for, which Hyrel's native flow computes the flow
    from ("We declare M756 at the beginning of every layer"; "M756 will overwrite the Z value from the M221
    command", Gcode page, M756), when the translation asks for native flow (``--flow native``).

    A layer starts at the first printing move at a new Z; its height is the rise from the layer below (the
    first layer: its Z above the bed), or the one the slicer states for it in a comment line (PrusaSlicer and
    Orca ``;HEIGHT:0.2``, Bambu ``; LAYER_HEIGHT: 0.2``); a height stated once for the job (Cura
    ``;Layer height: 0.2``, a ``; layer_height = 0.2`` setting) where the rise says nothing.  Where the
    layer below had one printing move or none (a spiral, or a lone move at its own height), that rise is no
    layer height: the height in force before stays possible too (the last layer not itself above such a one).  ``heights`` are the
    heights a printing move of this layer may be computed with (empty: none known)."""

    def __init__(self) -> None:
        self.z: float | None = None  # the current layer's Z (program coordinates, mm)
        self.moves = 0  # printing moves at that Z
        self.heights: tuple[float, ...] = ()
        # the heights of the last layer that came after a layer of two moves or more (where a spiral started)
        self.held: tuple[float, ...] = ()
        self.thin = False  # the layer below the current one had one printing move
        self.statements: deque[tuple[int, bool, float]] = deque()  # (line, per layer, height) not yet read
        self.stated: float | None = None  # the height the slicer states for the coming layer
        self.nominal: float | None = None  # the height it states once for the job

    def read(self, source):
        """``source`` as the reader reads it, its slicer's statements of the layer height noted on the way
        (the reader gives no comments): a source whose chunks are the same."""
        return _Statements(source, self)

    def printing(self, z: float | None, line: int) -> bool:
        """A printing move on ``line`` ending at ``z``: whether a new layer starts (``heights`` changed)."""
        statements = self.statements
        while statements and statements[0][0] < line:
            _, per_layer, value = statements.popleft()
            if per_layer:
                self.stated = value
            elif self.nominal is None:
                self.nominal = value
        if z is None:
            return False
        current = self.z
        if current is not None and abs(z - current) < 1e-6:
            self.moves += 1
            return False
        thin = current is not None and self.moves <= 1
        if not self.thin:
            self.held = self.heights
        self.z, self.moves, self.thin = z, 1, thin
        rise = round(z - current if current is not None else z, 4)
        heights = {rise} if rise > 0 else set()
        if self.stated is not None:
            heights.add(self.stated)
        elif not heights and self.nominal is not None:
            heights.add(self.nominal)
        if thin:
            heights.update(self.held)
        new = tuple(sorted(heights))
        if new == self.heights:
            return False
        self.heights = new
        return True


# Comment lines where a slicer states the layer height: (prefix, per layer)
_STATEMENTS = (("HEIGHT:", True), ("LAYER_HEIGHT:", True), ("Layer height:", False), ("layer_height =", False))


class _Statements:
    """A source read through, its comment lines that state a layer height noted (``LayerHeights.read``)."""

    def __init__(self, source, layers: LayerHeights) -> None:
        self.source = source
        self.layers = layers
        self.head_text, self.tail_text = source.head_text, source.tail_text  # (the job's settings: read_job)

    def chunks(self):
        note = self.layers.statements.append
        n = 0
        for chunk in self.source.chunks():
            for raw, _ in chunk:
                n += 1
                if ";" in raw and ("eight" in raw or "EIGHT" in raw):
                    text = raw.lstrip()
                    if not text.startswith(";"):
                        continue
                    body = text[1:].strip()
                    for prefix, per_layer in _STATEMENTS:
                        if body.startswith(prefix):
                            words = body[len(prefix) :].split()
                            try:
                                value = float(words[0]) if words else 0.0
                            except ValueError:
                                break
                            if value > 0 and value == value:
                                note((n, per_layer, round(value, 4)))
                            break
            yield chunk
