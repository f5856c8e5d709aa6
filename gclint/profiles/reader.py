"""Read a slicer profile: which file is one, and its custom G-code settings with their positions.

* PrusaSlicer, SuperSlicer and OrcaSlicer configurations (``.ini``: ``key = value`` lines, as the slicers
  export them) and configuration bundles (``[printer:Name]`` sections: the vendor profiles, exported bundles);
* OrcaSlicer and Bambu Studio printer profiles (``.json``, ``"machine_start_gcode"``), their ``inherits``
  read from the same folder (the vendor folders keep a profile's parents beside it, named after them);
* Cura machine definitions (``.def.json``; ``"overrides": {"machine_start_gcode": {"default_value": ...}}``)
  and extruder definitions (``machine_extruder_start_code``), their ``inherits`` read from the same folder.

A custom G-code setting is any key ending in ``_gcode`` that is not a ``gcode_...`` option (``gcode_flavor``,
``gcode_comments``), and Cura's ``machine_*_gcode`` / ``machine_extruder_*_code``.  An ``.ini`` that is no
slicer's (a LinuxCNC machine configuration, with its ``[EMC]`` and ``[RS274NGC]`` sections) is not a profile.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field

from gclint.profiles import jsontext
from gclint.profiles.bundle import Bundle
from gclint.profiles.ini import MAX_BYTES, Decoded, Entry, ProfileError, read, unescape, unescape_list
from gclint.profiles.placeholders import Value, value_of

PRUSA = "PrusaSlicer"
ORCA = "OrcaSlicer"
CURA = "Cura"
MAX_PRESETS = 2000  # printer presets of one bundle checked (PrusaResearch.ini 2.5: about 150)
MAX_PARENTS = 16  # inherits followed from a JSON profile
# list settings (one G-code per extruder or filament): "..";".." in an .ini, a JSON array
LIST_SETTINGS = frozenset({"start_filament_gcode", "end_filament_gcode", "filament_start_gcode", "filament_end_gcode"})
CURA_SETTINGS = ("machine_start_gcode", "machine_end_gcode", "machine_extruder_start_code", "machine_extruder_end_code")
CURA_BASES = ("fdmprinter", "fdmextruder")  # Cura's own definitions every machine inherits (its defaults)
_SLICER_SECTION = re.compile(r"(?:printer|print|filament|physical_printer):.+|vendor|presets")
_PROFILE_KEYS = ("gcode_flavor", "printer_technology", "start_gcode", "machine_start_gcode", "bed_shape")


def is_gcode_setting(key: str) -> bool:
    return (key.endswith("_gcode") and not key.startswith("gcode_")) or key in CURA_SETTINGS


@dataclass(frozen=True)
class GcodeSetting:
    """One custom G-code setting: its name (with the element of a list: ``start_filament_gcode[1]``) and its
    text, each character with its position in the file."""

    key: str
    label: str
    text: Decoded


@dataclass
class Profile:
    """What is checked of one printer: its custom G-code and the values its placeholders are filled from."""

    path: str
    slicer: str
    name: str | None
    values: dict[str, Value]
    settings: list[GcodeSetting]
    notes: list[str] = field(default_factory=list)

    def lookup(self, key: str) -> Value | None:
        return self.values.get(key)

    @property
    def flavor(self) -> str | None:
        """The G-code flavour the profile says (``gcode_flavor``, Cura's ``machine_gcode_flavor``)."""
        value = self.values.get("gcode_flavor", self.values.get("machine_gcode_flavor"))
        if isinstance(value, list):
            value = value[0] if value else None
        return str(value) if value is not None else None


def kind_of(path: str, head: str) -> str | None:
    """``ini``, ``json`` when the file (its name and the first part of its text) is a slicer profile gclint
    reads, else None.  Cheap: the first 64 KB decide."""
    name = os.path.basename(path).lower().rstrip(" .")
    if name.endswith(".ini"):
        return "ini" if _ini_is_profile(head) else None
    if name.endswith(".json"):
        stripped = head.lstrip("\ufeff \t\r\n")
        if stripped.startswith("{") and any(f'"{key}"' in head for key in _JSON_MARKS):
            return "json"
    return None


_JSON_MARKS = (
    "machine_start_gcode",
    "machine_end_gcode",
    "machine_extruder_start_code",
    "machine_extruder_end_code",
    "gcode_flavor",
    "machine_gcode_flavor",
    "change_filament_gcode",
    "filament_start_gcode",
)


def _ini_is_profile(head: str) -> bool:
    for raw in head.splitlines()[:400]:
        line = raw.strip()
        if not line or line[0] in "#;":
            continue
        if line.startswith("["):
            return _SLICER_SECTION.fullmatch(line[1:].rstrip("]").strip()) is not None
        key = line.partition("=")[0].strip()
        if key in _PROFILE_KEYS or is_gcode_setting(key):
            return True
    return False


def read_profiles(path: str, text: str) -> list[Profile]:
    """The profiles in ``text`` (the file ``path``): one for a configuration, one per printer preset of a
    bundle, one for a JSON profile."""
    kind = kind_of(path, text[: 64 << 10])
    if kind == "ini":
        return _ini_profiles(path, text)
    if kind == "json":
        return [_json_profile(path, text)]
    raise ProfileError("not a slicer profile gclint reads")


# -- .ini -------------------------------------------------------------------------------------------------


def _ini_profiles(path: str, text: str) -> list[Profile]:
    sections = read(text)
    if any(s.name is not None and _SLICER_SECTION.fullmatch(s.name) for s in sections):
        return _bundle_profiles(path, Bundle.from_text(text))
    entries = sections[0].entries
    for section in sections[1:]:  # (a configuration with sections gclint does not know: read them all)
        entries = {**entries, **section.entries}
    return [_entries_profile(path, None, entries)]


def _bundle_profiles(path: str, bundle: Bundle) -> list[Profile]:
    names = bundle.names("printer")
    out = []
    for name in names[:MAX_PRESETS]:
        flat = bundle.flat("printer", name)
        technology = flat.get("printer_technology")
        if technology is not None and technology.value.strip().upper() == "SLA":
            continue
        merged = dict(flat)
        for kind, key in (("print", "default_print_profile"), ("filament", "default_filament_profile")):
            entry = flat.get(key)
            preset = _first_name(entry) if entry is not None else None
            if preset is not None and preset not in bundle.presets.get(kind, {}):
                preset = next((n for n in bundle.names(kind) if n.startswith(preset)), None)
            if preset is not None:
                for k, e in bundle.flat(kind, preset).items():
                    merged.setdefault(k, e)  # (the printer's own settings win)
        out.append(_entries_profile(path, name, merged))
    if len(names) > MAX_PRESETS:
        out[-1].notes.append(f"only the first {MAX_PRESETS:,} printer presets of {len(names):,} were checked")
    if not out:
        raise ProfileError("a configuration bundle with no FFF printer preset: nothing to check")
    return out


def _first_name(entry: Entry) -> str | None:
    names = [d.text.strip() for d in unescape_list(entry.value, entry.line, entry.column)]
    return next((n for n in names if n), None)


def _entries_profile(path: str, name: str | None, entries: dict[str, Entry]) -> Profile:
    values: dict[str, Value] = {}
    settings: list[GcodeSetting] = []
    for key, entry in entries.items():
        if is_gcode_setting(key):
            if key in LIST_SETTINGS or entry.value.startswith('"'):
                items = unescape_list(entry.value, entry.line, entry.column)
                for i, item in enumerate(items):
                    label = f"{key}[{i}]" if len(items) > 1 else key
                    settings.append(GcodeSetting(key, label, item))
                values[key] = [item.text for item in items]
            else:
                decoded = unescape(entry.value, entry.line, entry.column)
                settings.append(GcodeSetting(key, key, decoded))
                values[key] = decoded.text  # ("[start_filament_gcode]" in a start_gcode writes it there)
            continue
        values[key] = value_of(entry.value)
    slicer = ORCA if "machine_start_gcode" in entries else PRUSA
    return Profile(path, slicer, name, values, settings)


# -- .json --------------------------------------------------------------------------------------------------


def _json_profile(path: str, text: str) -> Profile:
    doc = jsontext.load(text)
    if not isinstance(doc, dict):
        raise ProfileError("a JSON document that is not an object: not a slicer profile")
    chain = [doc]
    notes: list[str] = []
    folder = os.path.dirname(os.path.abspath(path))
    cura = "overrides" in doc or path.lower().endswith(".def.json")
    seen = {os.path.basename(path)}
    current = doc
    while len(chain) <= MAX_PARENTS:
        parent = current.get("inherits")
        parent = parent.value if isinstance(parent, jsontext.Text) else None
        if not parent:
            break
        found = _parent_file(folder, parent, cura)
        if found is None or os.path.basename(found) in seen:
            if parent not in CURA_BASES:
                notes.append(f"inherits {parent!r}: not found beside the profile, its settings are not read")
            break
        seen.add(os.path.basename(found))
        try:
            with open(found, encoding="utf-8-sig", errors="replace") as fh:
                loaded = jsontext.load(fh.read(MAX_BYTES + 1))
        except (OSError, ProfileError) as exc:
            notes.append(f"inherits {parent!r}: {os.path.basename(found)} could not be read ({exc})")
            break
        if not isinstance(loaded, dict):
            break
        current = loaded
        chain.append(current)
    profile = _cura(path, chain) if cura else _orca(path, chain)
    profile.notes.extend(notes)
    return profile


def _parent_file(folder: str, name: str, cura: bool) -> str | None:
    """The parent profile ``name`` beside the profile (not through a link that leaves the folder)."""
    if "/" in name or "\\" in name or name.startswith("."):
        return None
    candidate = os.path.join(folder, f"{name}.def.json" if cura else f"{name}.json")
    if os.path.islink(candidate) or not os.path.isfile(candidate):
        return None
    return candidate


def _orca(path: str, chain: list[dict]) -> Profile:
    values: dict[str, Value] = {}
    settings: dict[str, list[GcodeSetting]] = {}
    for doc in chain:  # (the profile first: its own settings win over its parents')
        for key, raw in doc.items():
            if key in values or key in settings:
                continue
            if is_gcode_setting(key):
                items = raw if isinstance(raw, list) else [raw]
                texts = [t for t in items if isinstance(t, jsontext.Text)]
                settings[key] = [
                    GcodeSetting(key, f"{key}[{i}]" if len(texts) > 1 else key, t.decoded) for i, t in enumerate(texts)
                ]
            else:
                values[key] = _json_value(raw)
    name = values.get("name")
    flat = [s for group in settings.values() for s in group]
    return Profile(path, ORCA, str(name) if name is not None else None, values, flat)


def _cura(path: str, chain: list[dict]) -> Profile:
    values: dict[str, Value] = {}
    settings: dict[str, GcodeSetting] = {}
    notes: list[str] = []
    for doc in chain:
        overrides = doc.get("overrides")
        if not isinstance(overrides, dict):
            continue
        for key, spec in overrides.items():
            if not isinstance(spec, dict) or key in values or key in settings:
                continue
            default = spec.get("default_value")
            if is_gcode_setting(key):
                if isinstance(default, jsontext.Text):
                    settings[key] = GcodeSetting(key, key, default.decoded)
                elif "value" in spec:
                    notes.append(f"{key} is computed by Cura (value = ...): not checked")
                continue
            if default is not None:
                values[key] = _json_value(default)
    name = chain[0].get("name")
    profile = Profile(
        path, CURA, name.value if isinstance(name, jsontext.Text) else None, values, list(settings.values())
    )
    profile.notes.extend(notes)
    return profile


def _json_value(raw: object) -> Value:
    plain = jsontext.plain(raw)
    if isinstance(plain, list):
        items = [_json_value(v) for v in plain]
        return items[0] if len(items) == 1 and not isinstance(items[0], (float, bool)) else items
    if isinstance(plain, bool):
        return plain
    if isinstance(plain, (int, float)):
        return float(plain)
    if isinstance(plain, str):
        return value_of(plain)
    return ""
