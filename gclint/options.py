"""``Options``: everything that shapes a check, from the command line and the configuration file.  The
engine, the rules (``ctx.options``), the runner and the reports read it; it depends on nothing."""

from __future__ import annotations

import os
from dataclasses import dataclass, field


@dataclass
class Options:
    """Everything that shapes a check, from the command line and the configuration file."""

    dialect: str = "auto"
    printer: str | None = None  # a Hyrel model; None = read it from the job (else the default, 30m)
    dialect_origin: str = "option"  # where an explicit dialect/printer came from: option or configuration
    # the dialect was said by the user (the command line, an editor, --config), not by a configuration found beside
    # the files, which a change can add (gclint.trust): only the user's word relaxes a security rule
    dialect_trusted: bool = True
    printer_origin: str = "option"
    flavor: str | None = None  # the firmware of a Marlin/RepRap/CNC file (klipper); None = read it from the file
    flavor_origin: str = "option"
    loaded: frozenset[int] | None = None  # v5 head positions; None = take them from the job header
    select: list[str] | None = None
    ignore: list[str] = field(default_factory=list)
    extend_select: list[str] = field(default_factory=list)
    per_file_ignores: dict[str, list[str]] = field(default_factory=dict)
    # path patterns of files allowed to write the printer's files (SC005 not reported: RepRapFirmware system
    # macros, sys/*.g); only the user's configuration (--config) may say so (gclint.trust)
    allow_file_writes: tuple[str, ...] = ()
    extend_known_codes: tuple[str, ...] = ()  # codes and command words DL001 accepts (site macros, REMAPs)
    # the codes the LinuxCNC machine's INI beside the job remaps (gclint.machine.linuxcnc_ini), and that INI
    machine_codes: tuple[str, ...] = ()
    machine_config: tuple[str, ...] = ()
    env_flavor: str | None = None  # SLIC3R_GCODE_FLAVOR for postprocess
    spindle_max_rpm: float | None = None
    severity: dict[str, str] = field(default_factory=dict)  # code or prefix -> level (configuration)
    tool_map: dict[int, int] = field(default_factory=dict)
    config_path: str | None = None

    def cache_key(self) -> str:
        """What a cached result depends on besides the file: every setting, and where the configuration is (its
        per-file-ignores and allow-file-writes patterns are relative to its folder: the same bytes in another
        folder match other files)."""
        return repr(
            (
                os.path.abspath(self.config_path) if self.config_path is not None else None,
                sorted(self.machine_config),
                self.dialect,
                self.printer,
                self.dialect_origin,
                self.dialect_trusted,
                self.printer_origin,
                self.flavor,
                self.flavor_origin,
                sorted(self.loaded) if self.loaded is not None else None,
                self.select,
                sorted(self.ignore),
                sorted(self.extend_select),
                sorted((k, sorted(v)) for k, v in self.per_file_ignores.items()),
                sorted(self.allow_file_writes),
                sorted(self.extend_known_codes),
                sorted(self.machine_codes),
                self.env_flavor,
                self.spindle_max_rpm,
                sorted(self.severity.items()),
                sorted(self.tool_map.items()),
            )
        )
