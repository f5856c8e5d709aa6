"""Options of a translation: from the command line and the configuration file."""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint.config import ConfigError, config_for, parse_tool_map
from gclint.machine.profiles import DEFAULT_PROFILE, PrinterProfile, get_profile


@dataclass
class TranslateOptions:
    printer: PrinterProfile = field(default_factory=lambda: get_profile(DEFAULT_PROFILE))
    tool_map: dict[int, int] = field(default_factory=dict)
    annotate: bool = False
    unsupported: str = "warn"
    spindle_max_rpm: float | None = None

    @classmethod
    def build(cls, input_path: str, *, printer: str | None = None, tool_map: dict[int, int] | None = None,
              annotate: bool = False, unsupported: str = "warn", config_file: str | None = None) -> "TranslateOptions":
        try:
            path, table = config_for(input_path, config_file)
        except ConfigError as exc:
            raise ValueError(str(exc)) from None
        opts = cls(annotate=annotate, unsupported=unsupported)
        name = printer or table.get("printer")
        if name:
            opts.printer = get_profile(str(name))
        if "tool-map" in table:
            opts.tool_map = parse_tool_map(table["tool-map"], f"{path}: 'tool-map'")
        if tool_map:
            opts.tool_map = dict(tool_map)
        if "spindle-max-rpm" in table:
            opts.spindle_max_rpm = float(table["spindle-max-rpm"])
        return opts
