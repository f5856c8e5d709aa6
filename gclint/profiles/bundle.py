"""PrusaSlicer's configuration bundles: the vendor profiles it ships (``resources/profiles/<Vendor>.ini``,
``/usr/share/PrusaSlicer/profiles`` on Debian) and the bundles a user exports.  A bundle holds presets in
sections named ``[printer:Name]``, ``[print:Name]``, ``[filament:Name]``; a preset names its parents with
``inherits = *common*; *0.4nozzle*``, and presets whose names start with ``*`` exist only to be inherited.

``flat(kind, name)`` resolves a preset as ``flatten_configbundle_hierarchy`` (libslic3r/PresetBundle.cpp)
does: the preset's own keys, then its parents' (each already resolved), the last parent first, a key taken
only when not set yet, so a later parent wins over an earlier one; ``renamed_from`` is never inherited, and
``inherits`` itself is dropped.  Each value keeps the line it was written on (a finding in ``*common*``'s
``start_gcode`` points there, whichever preset inherits it).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from gclint.profiles.ini import Entry, ProfileError, Section, read, unescape_list

KINDS = ("printer", "print", "filament")
NOT_SETTINGS = frozenset({"inherits", "renamed_from", "alias"})  # keys of a bundle, not of a configuration


@dataclass
class Bundle:
    """The presets of a bundle, by kind and name."""

    presets: dict[str, dict[str, Section]] = field(default_factory=dict)  # kind -> name -> section
    header: dict[str, Entry] = field(default_factory=dict)  # [vendor] (name, config_version)
    _flat: dict[tuple[str, str], dict[str, Entry]] = field(default_factory=dict)

    @classmethod
    def from_text(cls, text: str) -> Bundle:
        bundle = cls()
        for section in read(text):
            if section.name is None:
                continue
            if section.name == "vendor":
                bundle.header = dict(section.entries)
                continue
            kind, sep, name = section.name.partition(":")
            if sep and kind in KINDS and name:
                bundle.presets.setdefault(kind, {})[name] = section
        return bundle

    @classmethod
    def from_file(cls, path: str) -> Bundle:
        with open(path, encoding="utf-8", errors="replace") as fh:
            return cls.from_text(fh.read())

    @property
    def vendor(self) -> str | None:
        entry = self.header.get("name")
        return entry.value if entry is not None else None

    def names(self, kind: str) -> list[str]:
        """The public presets of ``kind`` (not the ``*intermediate*`` ones), in file order."""
        return [name for name in self.presets.get(kind, {}) if not name.startswith("*")]

    def flat(self, kind: str, name: str) -> dict[str, Entry]:
        """The resolved settings of preset ``name`` (each Entry says where its value was written)."""
        return dict(self._resolve(kind, name, ()))

    def _resolve(self, kind: str, name: str, chain: tuple[str, ...]) -> dict[str, Entry]:
        key = (kind, name)
        done = self._flat.get(key)
        if done is not None:
            return done
        section = self.presets.get(kind, {}).get(name)
        if section is None:
            raise ProfileError(f"no {kind} preset named {name!r} in this bundle")
        if name in chain:
            raise ProfileError(f"{kind} preset {name!r} inherits itself ({' -> '.join(chain + (name,))})")
        merged = {k: e for k, e in section.entries.items() if k != "inherits"}
        parents = section.entries.get("inherits")
        if parents is not None:
            names = [d.text.strip() for d in unescape_list(parents.value, parents.line, parents.column)]
            for parent in reversed([n for n in names if n]):
                for k, e in self._resolve(kind, parent, chain + (name,)).items():
                    if k != "renamed_from":
                        merged.setdefault(k, e)
        self._flat[key] = merged
        return merged

    def slicing_config(
        self, printer: str, print_preset: str | None = None, filament: str | None = None
    ) -> dict[str, str]:
        """One flat configuration for the slicer's command line (``prusa-slicer --load``): the printer
        preset, its default print and filament presets (``default_print_profile``,
        ``default_filament_profile``) unless named, the printer's settings last.  Values as written in the
        bundle (escaped), keys of the bundle's own bookkeeping left out."""
        printer_flat = self.flat("printer", printer)
        if print_preset is None:
            print_preset = _first(printer_flat.get("default_print_profile"))
        if filament is None:
            filament = _first(printer_flat.get("default_filament_profile"))
        config: dict[str, str] = {}
        for kind, name in (("print", print_preset), ("filament", filament)):
            if name is not None and name not in self.presets.get(kind, {}):
                # (Voron's printers name "0.15mm 0.4nozzle"; its presets are "0.15mm 0.4nozzle V2", ...: the
                # slicer takes the first compatible one)
                name = next((n for n in self.names(kind) if n.startswith(name)), None)
            if name is not None:
                config.update({k: e.value for k, e in self.flat(kind, name).items()})
        config.update({k: e.value for k, e in printer_flat.items()})
        for key in NOT_SETTINGS:
            config.pop(key, None)
        return config


def _first(entry: Entry | None) -> str | None:
    if entry is None:
        return None
    names = [d.text.strip() for d in unescape_list(entry.value, entry.line, entry.column)]
    return next((n for n in names if n), None)


def write_ini(config: dict[str, str]) -> str:
    """A flat configuration as PrusaSlicer writes one (``key = value``, sorted by key)."""
    return "".join(f"{key} = {config[key]}\n" for key in sorted(config))
