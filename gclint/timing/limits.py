"""What the machine may do: the motion limits the planner works with, and where each comes from.

In order, later ones winning: the firmware's documented defaults (only where they can be cited: Marlin's, below),
the slicer's machine limits in the job's settings (PrusaSlicer's ``machine_max_acceleration_x = ...``, OrcaSlicer's
and BambuStudio's ``machine_max_speed_x = ...``), then the job's own commands as they run (``simulate.events.Limits``:
M201, M203, M204, M205, RepRapFirmware's M566, Klipper's SET_VELOCITY_LIMIT).  A value nobody gives stays None: no
acceleration known means the time is a lower bound, each move at its feed.
"""

from __future__ import annotations

from dataclasses import dataclass

AXES = "xyze"


@dataclass
class MachineLimits:
    """Motion limits, mm and seconds (None: not known).  The names are ``simulate.events.LIMIT_NAMES``."""

    max_accel_x: float | None = None
    max_accel_y: float | None = None
    max_accel_z: float | None = None
    max_accel_e: float | None = None
    max_feed_x: float | None = None
    max_feed_y: float | None = None
    max_feed_z: float | None = None
    max_feed_e: float | None = None
    max_feed: float | None = None
    accel_print: float | None = None
    accel_travel: float | None = None
    accel_retract: float | None = None
    jerk_x: float | None = None
    jerk_y: float | None = None
    jerk_z: float | None = None
    jerk_e: float | None = None
    junction_deviation: float | None = None
    square_corner_velocity: float | None = None
    min_feed_print: float | None = None
    min_feed_travel: float | None = None

    def update(self, values: dict[str, float]) -> None:
        """Values the job sets (a ``Limits`` event, the slicer's settings); names this model does not know are left
        alone.  Jerks without a junction deviation say the firmware plans with classic jerk (Marlin reads M205 X Y
        only when built with CLASSIC_JERK, Marlin G-code reference M205): a junction deviation set before goes."""
        for name, value in values.items():
            if hasattr(self, name):
                setattr(self, name, value)
        if ("jerk_x" in values or "jerk_y" in values) and "junction_deviation" not in values:
            self.junction_deviation = None

    @property
    def accelerated(self) -> bool:
        """Whether an acceleration is known: otherwise each move runs at its feed from end to end."""
        return self.accel_print is not None or self.accel_travel is not None


# Marlin 2.1's defaults, Marlin/Configuration.h, "@section motion": DEFAULT_MAX_FEEDRATE { 300, 300, 5, 25 } (mm/s),
# DEFAULT_MAX_ACCELERATION { 3000, 3000, 100, 10000 } (mm/s²), DEFAULT_ACCELERATION 3000, DEFAULT_RETRACT_ACCELERATION
# 3000, DEFAULT_TRAVEL_ACCELERATION 3000; CLASSIC_JERK disabled, so JUNCTION_DEVIATION_MM 0.013; DEFAULT_EJERK 5.0.
# A printer's own build often changes them (and its EEPROM may hold others): the time says it rests on them.
MARLIN_DEFAULTS = MachineLimits(
    max_feed_x=300,
    max_feed_y=300,
    max_feed_z=5,
    max_feed_e=25,
    max_accel_x=3000,
    max_accel_y=3000,
    max_accel_z=100,
    max_accel_e=10000,
    accel_print=3000,
    accel_retract=3000,
    accel_travel=3000,
    junction_deviation=0.013,
    jerk_e=5.0,
)

# The defaults each firmware starts with, by dialect and firmware flavour (gclint.context: Context.flavor): plain
# Marlin and Prusa's Marlin-based firmwares run Marlin's planner; Klipper, Bambu's firmware, RepRapFirmware and
# the 2015 RepRap firmwares are left out (no defaults of theirs cited here: their jobs' time is a lower bound
# unless the job states its limits).
FIRMWARE_DEFAULTS: dict[tuple[str, str | None], tuple[MachineLimits, str]] = {
    ("marlin", None): (MARLIN_DEFAULTS, "Marlin"),
    ("marlin", "prusa-buddy"): (MARLIN_DEFAULTS, "Marlin"),
    ("marlin", "prusa-mk3"): (MARLIN_DEFAULTS, "Marlin"),
}

# The slicer's settings -> limits.  PrusaSlicer's names (OrcaSlicer and BambuStudio say machine_max_speed_* for
# machine_max_feedrate_*), their values per mode (normal, silent: the first is the normal mode's); Cura's machine
# settings (fdmprinter.def.json: machine_acceleration, machine_max_jerk_xy...; the job carries those its user
# changed, ``slicer.slicer_settings`` reads them from ;SETTING_3); KISSlicer's printer settings.
_SETTINGS: dict[str, tuple[str, ...]] = {
    **{f"machine_max_acceleration_{a}": (f"max_accel_{a}",) for a in AXES},
    **{f"machine_max_feedrate_{a}": (f"max_feed_{a}",) for a in AXES},
    **{f"machine_max_speed_{a}": (f"max_feed_{a}",) for a in AXES},
    **{f"machine_max_jerk_{a}": (f"jerk_{a}",) for a in AXES},
    "machine_max_acceleration_extruding": ("accel_print",),
    "machine_max_acceleration_travel": ("accel_travel",),
    "machine_max_acceleration_retracting": ("accel_retract",),
    "machine_max_junction_deviation": ("junction_deviation",),
    "machine_min_extruding_rate": ("min_feed_print",),
    "machine_min_travel_rate": ("min_feed_travel",),
    "machine_acceleration": ("accel_print", "accel_travel", "accel_retract"),
    "machine_max_jerk_xy": ("jerk_x", "jerk_y"),
    "machine_minimum_feedrate": ("min_feed_print", "min_feed_travel"),
    "xy_accel_mm_per_s_per_s": ("accel_print", "accel_travel"),
    "z_speed_mm_per_s": ("max_feed_z",),
}


def _first(text: str) -> float | None:
    try:
        value = float(text.split(",")[0].strip().rstrip("%"))
    except ValueError:
        return None
    return value if value == value and value >= 0 else None


def from_settings(settings: dict[str, str]) -> dict[str, float]:
    """The machine limits the slicer's settings state (none when they say the limits are ignored)."""
    if settings.get("machine_limits_usage", "").strip() == "ignore":
        return {}
    values: dict[str, float] = {}
    for key, names in _SETTINGS.items():
        if key in settings:
            value = _first(settings[key])
            if value is not None and value > 0:
                for name in names:
                    values.setdefault(name, value)
    if "accel_travel" not in values and "accel_print" in values:
        values["accel_travel"] = values["accel_print"]  # (older PrusaSlicer: one acceleration for both)
    if "accel_retract" not in values and "accel_print" in values:
        values["accel_retract"] = values["accel_print"]
    return values


def limits_for(dialect: str, flavor: str | None, settings: dict[str, str]) -> tuple[MachineLimits, str, set[str]]:
    """The limits a job starts with: the firmware's defaults (``FIRMWARE_DEFAULTS``), overridden by the slicer's
    machine limits; with the firmware whose defaults they are ("" : none) and the names the settings state."""
    limits = MachineLimits()
    defaults = FIRMWARE_DEFAULTS.get((dialect, flavor))
    firmware = ""
    if defaults is not None:
        limits.update({k: v for k, v in vars(defaults[0]).items() if v is not None})
        firmware = defaults[1]
    stated = from_settings(settings)
    limits.update(stated)
    return limits, firmware, set(stated)


def defaults_used(dialect: str, flavor: str | None, stated: set[str]) -> bool:
    """Whether some of the firmware's defaults are still in force when the job and its settings stated ``stated``
    (jerks stated: the default junction deviation is not)."""
    defaults = FIRMWARE_DEFAULTS.get((dialect, flavor))
    if defaults is None:
        return False
    left = {k for k, v in vars(defaults[0]).items() if v is not None} - stated
    if stated & {"jerk_x", "jerk_y"}:
        left.discard("junction_deviation")
    return bool(left)


# Time a tool change takes that the G-code does not show (the firmware's own moves: the MMU unloads and loads the
# filament), as the slicer's settings state it, in seconds per change: PrusaSlicer's filament_unload_time and
# filament_load_time (per filament), OrcaSlicer's and BambuStudio's machine_unload_filament_time and
# machine_load_filament_time, and OrcaSlicer's machine_tool_change_time.
def tool_change_times(settings: dict[str, str]) -> tuple[list[float], list[float]]:
    """(load, unload) seconds per filament (one value: the same for all); empty when the job states none."""

    def values(*keys: str) -> list[float]:
        for key in keys:
            if key in settings:
                out = []
                for part in settings[key].split(","):
                    try:
                        out.append(max(0.0, float(part)))
                    except ValueError:
                        out.append(0.0)
                return out
        return []

    load = values("filament_load_time", "machine_load_filament_time")
    unload = values("filament_unload_time", "machine_unload_filament_time")
    change = values("machine_tool_change_time")
    if change and any(change):
        load = [a + change[0] for a in (load or [0.0])]
    return load, unload
