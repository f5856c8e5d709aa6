"""Options of a translation: from the command line and the configuration file.

The choices a translation to Hyrel needs (docs/translation.md, Settings), with
their defaults:

    flow          evalues   keep the slicer's E amounts and switch Hyrel to them (M229 E1 D1);
                            native: reduce E to E1 markers, Hyrel computes the flow (X4, X7)
    retract       auto      retraction moves and firmware retracts (G10/G11, G22/G23) are left to the
                            head's automatic unprime/prime; explicit: M721 T# I1 / M722 T# I1
    fan-map       {}        source fan index -> Hyrel address; fan 0 (and an unmapped M106 without P)
                            is the fan of the focused head
    bed, chamber  T24       the Hyrel address of the heated bed / chamber (T24 Bed1/Chamber1)
    temp-window   2         C, the tolerance written as R when the source waits heating *or* cooling
    spindle       mapped tool 0   the Hyrel head that carries the spindle (CNC sources)
    laser         mapped tool 0   the Hyrel head or device that carries the laser (Carvera laser mode)
    air           M7        the aux port Carvera's air (M7/M9) goes to: M7 (Aux1), M8 (Aux2) or M685 (16A)
    max-feed      drop      M203 (mm/s caps): drop, or convert (to Hyrel's G0 speeds in mm/min)
    home-z        per printer   a bare G28 also homes Z (G28 X0 Y0 Z0); default: on the EHR, which needs
                            G28 Z0 for M660 (Gcode page), off elsewhere
    tool-offsets  drop      RepRapFirmware G10 tool offsets: drop (Repetrel declares head offsets itself),
                            or m6 (M6 T# O<n> X Y Z, sign and register to verify on the machine)
    spindle-max-rpm         the rpm of the Hyrel spindle at 100 % (M3 S rpm -> percent)
    spindle-stop-dwell      s to wait after the M5 added before a change of spindle direction ("DO NOT
                            CHANGE DIRECTION while the spindle is in motion", M3); unset: a pause (M0)

``--set KEY=VALUE`` (repeatable) sets any of them on the command line.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint.config import ConfigError, config_for, parse_tool_map
from gclint.machine.profiles import DEFAULT_PROFILE, PrinterProfile, get_profile

FLOW_MODES = ("evalues", "native")
RETRACT_MODES = ("auto", "explicit")
AIR_PORTS = ("M7", "M8", "M685", "M679")


@dataclass
class TranslateOptions:
    printer: PrinterProfile = field(default_factory=lambda: get_profile(DEFAULT_PROFILE))
    tool_map: dict[int, int] = field(default_factory=dict)
    annotate: bool = False
    unsupported: str = "warn"
    spindle_max_rpm: float | None = None
    flow: str = "evalues"
    retract: str = "auto"
    fan_map: dict[int, int] = field(default_factory=dict)
    bed: int = 24
    chamber: int = 24
    temp_window: float = 2.0
    spindle: int | None = None
    laser: int | None = None
    air: str = "M7"
    max_feed: str = "drop"
    home_z: bool | None = None  # None: as the printer needs (EHR: yes)
    tool_offsets: str = "drop"
    spindle_stop_dwell: float | None = None  # s to wait after M5 before reversing (None: pause, M0)

    @classmethod
    def build(
        cls,
        input_path: str,
        *,
        printer: str | None = None,
        tool_map: dict[int, int] | None = None,
        annotate: bool = False,
        unsupported: str = "warn",
        config_file: str | None = None,
        flow: str | None = None,
        settings: dict[str, str] | None = None,
        spindle_max_rpm: float | None = None,
    ) -> TranslateOptions:
        from gclint.config import apply as apply_config
        from gclint.engine import Options

        try:
            path, table = config_for(input_path, config_file)
            # the configuration's values are checked the way ``check`` checks them (errors name the file)
            checked = apply_config(Options(), table, path) if path is not None else Options()
        except ConfigError as exc:
            raise ValueError(str(exc)) from None
        opts = cls(annotate=annotate, unsupported=unsupported)
        name = printer or table.get("printer")
        if name:
            opts.printer = get_profile(str(name))
        if "tool-map" in table:
            opts.tool_map = dict(checked.tool_map)
            _check_tool_map(opts.tool_map, f"{path}: tool-map ")
        if tool_map:
            opts.tool_map = dict(tool_map)
            _check_tool_map(opts.tool_map, "--tool-map ")
        if "spindle-max-rpm" in table:
            opts.spindle_max_rpm = checked.spindle_max_rpm
        if spindle_max_rpm is not None:
            opts.spindle_max_rpm = float(spindle_max_rpm)
        for key, value in (settings or {}).items():
            opts.set(key, value)
        if flow is not None:
            opts.set("flow", flow)
        return opts

    def set(self, key: str, value: str) -> None:
        """Set one option from text (``--set KEY=VALUE``); ValueError names the key."""
        k = key.strip().lower().replace("_", "-")
        v = str(value).strip()
        try:
            if k == "flow":
                self.flow = _choice(v.lower(), FLOW_MODES)
            elif k == "retract":
                self.retract = _choice(v.lower(), RETRACT_MODES)
            elif k == "fan-map":
                self.fan_map = parse_tool_map(v, "fan-map")
            elif k == "tool-map":
                self.tool_map = parse_tool_map(v, "tool-map")
                _check_tool_map(self.tool_map, "")
            elif k in ("bed", "chamber", "spindle", "laser"):
                setattr(self, k, _address(v))
            elif k == "temp-window":
                self.temp_window = _positive(v)
            elif k == "air":
                self.air = _choice(v.upper(), AIR_PORTS)
            elif k == "max-feed":
                self.max_feed = _choice(v.lower(), ("drop", "convert"))
            elif k == "home-z":
                self.home_z = v.lower() in ("1", "true", "yes", "on")
            elif k == "tool-offsets":
                self.tool_offsets = _choice(v.lower(), ("drop", "m6"))
            elif k == "spindle-max-rpm":
                self.spindle_max_rpm = _positive(v)
            elif k == "spindle-stop-dwell":
                self.spindle_stop_dwell = _positive(v)
            elif k == "printer":
                self.printer = get_profile(v)
            else:
                raise ValueError(f"unknown translation setting {key!r} (known: {', '.join(SETTINGS)})")
        except ConfigError as exc:
            raise ValueError(str(exc)) from None
        except ValueError as exc:
            if str(exc).startswith("unknown translation setting"):
                raise
            raise ValueError(f"--set {key}={value}: {exc}") from None

    def homes_z(self) -> bool:
        """Whether a bare G28 homes Z too: as set, else as the printer needs (EHR: G28 Z0 before M660)."""
        if self.home_z is not None:
            return self.home_z
        return self.printer.needs_z_home_for_m660

    def tool(self, index: int) -> int:
        """The Hyrel address of source tool ``index`` (identity unless mapped)."""
        return self.tool_map.get(index, index)

    def spindle_address(self) -> int:
        return self.spindle if self.spindle is not None else self.tool(0)

    def laser_address(self) -> int:
        return self.laser if self.laser is not None else self.tool(0)


SETTINGS = (
    "flow",
    "retract",
    "fan-map",
    "tool-map",
    "bed",
    "chamber",
    "temp-window",
    "spindle",
    "laser",
    "air",
    "max-feed",
    "home-z",
    "tool-offsets",
    "spindle-max-rpm",
    "spindle-stop-dwell",
    "printer",
)


def parse_settings(values: tuple[str, ...] | list[str]) -> dict[str, str]:
    """``("flow=native", "air=M8")`` -> ``{"flow": "native", "air": "M8"}``."""
    out: dict[str, str] = {}
    for item in values:
        if "=" not in item:
            raise ValueError(f"--set {item!r}: use KEY=VALUE (keys: {', '.join(SETTINGS)})")
        key, value = item.split("=", 1)
        out[key.strip()] = value.strip()
    return out


class ToolMapClash(ValueError):
    """Two source tools map to one Hyrel head (refused: one line, exit 2)."""


def _check_tool_map(tool_map: dict[int, int], where: str) -> None:
    """A source tool becomes a Hyrel head: T0-T19 ("we have the ability to control up to 20 tool positions or
    heads", T_v5, Chart of Addresses); a bed, spindle, laser or group address is refused."""
    from gclint.dialects.addressing import resolve_v5

    users: dict[int, int] = {}
    for tool, address in sorted(tool_map.items()):
        if address in users:
            # one head cannot print for two tools: it has one set-point, one fan value, one flow, one filament
            raise ToolMapClash(
                f"{where}{users[address]}=T{address} and {tool}=T{address}: tools {users[address]} and {tool} both "
                f"map to head T{address}; map each tool to a head of its own"
            )
        users[address] = tool
        if not 0 <= address <= 19:
            raise ValueError(
                f"{where}{tool}=T{address}: a tool maps to a head (T0-T19); T{address} is "
                f"{resolve_v5(address).label} (Hyrel wiki, T_v5)"
            )


def _choice(value: str, choices: tuple[str, ...]) -> str:
    if value not in choices:
        raise ValueError(f"expected one of {', '.join(choices)}")
    return value


def _address(value: str) -> int:
    text = value.upper().lstrip("T")
    if not (text.isascii() and text.isdigit() and len(text) <= 6) or int(text) > 48:
        raise ValueError("expected a Hyrel address such as T0 or T20")
    return int(text)


def _positive(value: str) -> float:
    try:
        number = float(value)
    except ValueError:
        raise ValueError("expected a number") from None
    if not 0 < number < 1e12:  # also refuses nan and inf
        raise ValueError("expected a positive number")
    return number
