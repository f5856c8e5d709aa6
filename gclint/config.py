"""Configuration: ``[tool.gclint]`` in pyproject.toml, or gclint.toml / .gclint.toml, found upward from
the checked file (the nearest one wins, as in ruff).  Read as data only (tomllib); unknown keys and
wrong types are errors that name the file and the key.

    [tool.gclint]
    dialect = "hyrel"
    printer = "16a-dual"
    loaded = ["T0", "T2"]
    select = ["SX", "DL", "HY"]
    ignore = ["HY029"]
    extend-select = []
    per-file-ignores = { "calibration/*.gcode" = ["HY006"] }
    allow-file-writes = ["sys/*.g"]      # SC005 not reported for these files: only in a --config file
    extend-known-codes = ["M900", "PRINT_START"]
    tool-map = { 0 = "T2", 1 = "T3" }
    spindle-max-rpm = 24000
"""

from __future__ import annotations

import math
import os
import re
import tomllib
from dataclasses import replace
from pathlib import Path

from gclint.engine import Options
from gclint.firmware import normal_code

CONFIG_NAMES = ("gclint.toml", ".gclint.toml", "pyproject.toml")


class ConfigError(Exception):
    """A configuration file that cannot be used; the message is one line naming the file."""


def parse_heads(value: object, where: str = "--loaded") -> frozenset[int]:
    """``"T0,T2"``, ``"0 2"``, ``["T0", 2]`` -> ``{0, 2}`` (v5 head positions)."""
    items: list = []
    if isinstance(value, str):
        items = [v for v in re.split(r"[,\s]+", value.strip()) if v]
    elif isinstance(value, (list, tuple)):
        items = list(value)
    else:
        raise ConfigError(f"{where}: expected a list of heads such as T0,T2")
    heads = set()
    for item in items:
        text = str(item).strip().upper()
        if text.startswith("T"):
            text = text[1:]
        if not _DIGITS.fullmatch(text) or not 0 <= int(text) <= 19:
            raise ConfigError(f"{where}: {item!r} is not a head position (T0-T19)")
        heads.add(int(text))
    return frozenset(heads)


# ASCII digits only ("T²" and "T١" are not numbers here), and few of them (int() of 5,000 digits fails)
_DIGITS = re.compile(r"[0-9]{1,6}")


def _number(value: object, key: str, path: Path, low: float, high: float) -> float:
    """A configuration number: finite and in range (a NaN would reach the output as "Snan")."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ConfigError(f"{path}: '{key}' must be a number from {low:,g} to {high:,g} (got {value!r})")
    if not low <= value <= high:
        raise ConfigError(f"{path}: '{key}' must be a number from {low:,g} to {high:,g} (got {value:g})")
    return float(value)


def parse_tool_map(value: object, where: str = "--tool-map") -> dict[int, int]:
    """``"0=T2,1=T3"`` or ``{0 = "T2"}`` -> ``{0: 2, 1: 3}`` (source tool index -> Hyrel T address)."""
    pairs: list[tuple[object, object]] = []
    if isinstance(value, str):
        for part in re.split(r"[,\s]+", value.strip()):
            if not part:
                continue
            if "=" not in part:
                raise ConfigError(f"{where}: {part!r} should look like 0=T2")
            k, v = part.split("=", 1)
            pairs.append((k, v))
    elif isinstance(value, dict):
        pairs = list(value.items())
    else:
        raise ConfigError(f"{where}: expected pairs such as 0=T2,1=T3")
    out: dict[int, int] = {}
    for k, v in pairs:
        ks, vs = str(k).strip().upper().lstrip("T"), str(v).strip().upper().lstrip("T")
        if not _DIGITS.fullmatch(ks) or not _DIGITS.fullmatch(vs) or int(vs) > 48:
            raise ConfigError(f"{where}: {k}={v} is not a tool index and a Hyrel address (0=T2)")
        if int(ks) in out:
            raise ConfigError(f"{where}: tool {int(ks)} is mapped twice (T{out[int(ks)]} and T{int(vs)})")
        out[int(ks)] = int(vs)
    return out


def _codes(value: object, key: str, path: Path) -> list[str]:
    """A list of rule codes, prefixes or names, checked (an unknown one is an error, with a hint)."""
    from gclint.rules.base import UnknownSelector, resolve_selectors

    try:
        return resolve_selectors(_str_list(value, key, path), f"{path}: '{key}': ")
    except UnknownSelector as exc:
        raise ConfigError(str(exc)) from None


def parse_known_codes(value: object, where: str = "--extend-known-codes") -> tuple[str, ...]:
    """``"M900, PRINT_START"`` or ``["M900", "print_start"]`` -> ``("M900", "PRINT_START")``: codes and
    command words DL001 accepts (normalised as a file's commands are: ``M0900`` is ``M900``)."""
    if isinstance(value, str):
        items = [v for v in re.split(r"[,\s]+", value.strip()) if v]
    elif isinstance(value, list) and all(isinstance(v, str) for v in value):
        items = list(value)
    else:
        raise ConfigError(f"{where}: expected a list of codes or command names such as M900, PRINT_START")
    out = []
    for item in items:
        code = normal_code(item)
        if code is None:
            raise ConfigError(f"{where}: {item!r} is not a code (M900, G29.1) or a command name (PRINT_START)")
        out.append(code)
    return tuple(dict.fromkeys(out))


def _str_list(value: object, key: str, path: Path) -> list[str]:
    if isinstance(value, str):
        return [v for v in re.split(r"[,\s]+", value) if v]
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return list(value)
    raise ConfigError(f"{path}: '{key}' must be a list of rule codes or prefixes")


_KEYS = {
    "exclude",
    "extend-exclude",
    "force-exclude",
    "respect-gitignore",
    "severity",
    "dialect",
    "flavor",
    "printer",
    "loaded",
    "select",
    "ignore",
    "extend-select",
    "per-file-ignores",
    "allow-file-writes",
    "extend-known-codes",
    "tool-map",
    "spindle-max-rpm",
}


_LOADED: dict[tuple, dict] = {}  # (file, mtime, size) -> its table, for the current run (read-only)


def load_file(path: Path) -> dict:
    """The gclint table of a configuration file ({} when a pyproject.toml has none); parsed once per
    run unless the file changes."""
    try:
        st = path.stat()
    except OSError:
        return _read_file(path)  # says why, as a ConfigError
    key = (path, st.st_mtime_ns, st.st_size)
    table = _LOADED.get(key)
    if table is None:
        table = _LOADED[key] = _read_file(path)
    return table


def _read_file(path: Path) -> dict:
    try:
        with open(path, "rb") as fh:
            data = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: {exc}") from None
    except RecursionError:  # tomllib reads nested arrays recursively: "x = [[[[...]]]]"
        raise ConfigError(f"{path}: invalid TOML: nested too deeply") from None
    except UnicodeDecodeError:
        raise ConfigError(f"{path}: invalid TOML: not UTF-8 text") from None
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if path.name == "pyproject.toml":
        table = data.get("tool", {}).get("gclint")
        if table is None:
            return {}
    else:
        table = data.get("tool", {}).get("gclint", data)
    if not isinstance(table, dict):
        raise ConfigError(f"{path}: the gclint section must be a table")
    unknown = sorted(set(table) - _KEYS)
    if unknown:
        import difflib

        said = []
        for key in unknown:
            near = difflib.get_close_matches(key, sorted(_KEYS), n=1)
            said.append(f"'{key}'" + (f" (did you mean '{near[0]}'?)" if near else ""))
        raise ConfigError(
            f"{path}: unknown option{'s' if len(said) != 1 else ''} {', '.join(said)} (known: {', '.join(sorted(_KEYS))})"
        )
    _check_patterns(table, path)
    return table


def _check_patterns(table: dict, path: Path) -> None:
    """Path patterns are read when the file is (a walk matches them before anything is checked): one
    that cannot be read is an error naming the file, the key and the pattern."""
    for key in ("exclude", "extend-exclude", "allow-file-writes"):
        if key in table and not (isinstance(table[key], list) and all(isinstance(v, str) for v in table[key])):
            raise ConfigError(f"{path}: '{key}' must be a list of path patterns such as [\"archive/**\"]")
        for pattern in table.get(key) or ():
            check_pattern(pattern, f"{path}: '{key}'")
    pfi = table.get("per-file-ignores")
    if isinstance(pfi, dict):
        for pattern in pfi:
            check_pattern(str(pattern), f"{path}: 'per-file-ignores'")


def check_pattern(pattern: str, where: str) -> None:
    """A ConfigError naming ``where`` when ``pattern`` cannot be read as a path pattern."""
    from gclint.globs import GlobError, check

    try:
        check(pattern)
    except GlobError as exc:
        raise ConfigError(f"{where}: {pattern!r} is not a valid path pattern: {exc}") from None


def flavor_names() -> list[str]:
    """The firmware a file can be declared for (``--flavor``, ``flavor =``): the flavours of a dialect."""
    from gclint import firmware

    return [f.name for f in firmware.all_firmware() if f.flavor]


def check_flavor(name: object, where: str) -> str:
    """``name`` when it is a flavour's name, else a ConfigError naming ``where`` and the choices."""
    names = flavor_names()
    if not isinstance(name, str) or name.lower() not in names:
        import difflib

        near = difflib.get_close_matches(str(name).lower(), names, n=1)
        hint = f" (did you mean '{near[0]}'?)" if near else ""
        raise ConfigError(f"{where}: unknown firmware {name!r}{hint}; known: {', '.join(names)}")
    return name.lower()


def apply(options: Options, table: dict, path: Path) -> Options:
    """``options`` updated with a configuration table (command-line values are applied afterwards)."""
    from gclint import dialects
    from gclint.machine.profiles import UnknownPrinter, get_profile

    changes: dict = {"config_path": str(path)}
    if "dialect" in table:
        name = table["dialect"]
        if not isinstance(name, str):
            raise ConfigError(f"{path}: 'dialect' must be a string")
        if name != "auto":
            try:
                dialects.get(name)
            except dialects.UnknownDialect as exc:
                raise ConfigError(f"{path}: {exc}") from None
        changes["dialect"] = name
        changes["dialect_origin"] = "configuration"
    if "flavor" in table:
        changes["flavor"] = check_flavor(table["flavor"], f"{path}: 'flavor'")
        changes["flavor_origin"] = "configuration"
    if "printer" in table:
        try:
            get_profile(str(table["printer"]))
        except UnknownPrinter as exc:
            raise ConfigError(f"{path}: {exc}") from None
        changes["printer"] = get_profile(str(table["printer"])).name
        changes["printer_origin"] = "configuration"
    if "loaded" in table:
        changes["loaded"] = parse_heads(table["loaded"], f"{path}: 'loaded'")
    if "select" in table:
        changes["select"] = _codes(table["select"], "select", path)
    if "ignore" in table:
        changes["ignore"] = _codes(table["ignore"], "ignore", path)
    if "extend-select" in table:
        changes["extend_select"] = _codes(table["extend-select"], "extend-select", path)
    if "per-file-ignores" in table:
        pfi = table["per-file-ignores"]
        if not isinstance(pfi, dict):
            raise ConfigError(f"{path}: 'per-file-ignores' must be a table of pattern = [codes]")
        changes["per_file_ignores"] = {str(k): _codes(v, f"per-file-ignores.{k}", path) for k, v in pfi.items()}
    if "allow-file-writes" in table:  # (patterns checked by load_file)
        changes["allow_file_writes"] = tuple(table["allow-file-writes"])
    if "extend-known-codes" in table:
        changes["extend_known_codes"] = parse_known_codes(table["extend-known-codes"], f"{path}: 'extend-known-codes'")
    if "tool-map" in table:
        changes["tool_map"] = parse_tool_map(table["tool-map"], f"{path}: 'tool-map'")
    if "severity" in table:
        changes["severity"] = parse_severities(table["severity"], path)
    for key in ("force-exclude", "respect-gitignore"):  # (exclude patterns: checked by load_file)
        if key in table and not isinstance(table[key], bool):
            raise ConfigError(f"{path}: '{key}' must be true or false")
    if "spindle-max-rpm" in table:
        changes["spindle_max_rpm"] = _number(table["spindle-max-rpm"], "spindle-max-rpm", path, 1, 1_000_000)
    return replace(options, **changes)


_FOUND: dict[str, Path | None] = {}  # real folder -> its nearest configuration file, for the current run
_BY_NAME: dict[str, Path | None] = {}  # the same, by the folder name as given


def find_config(directory: str) -> Path | None:
    """The nearest configuration file at or above ``directory`` (a pyproject.toml counts only with
    a [tool.gclint] table).  Cached per folder, parents included (sibling folders share their
    parents' answer); ``runner.run`` clears the cache at the start of every run, so a configuration
    written between runs is seen."""
    if directory in _BY_NAME:
        return _BY_NAME[directory]
    answer = _BY_NAME[directory] = _find_config(real_folder(directory))
    return answer


_REAL: dict[str, str] = {}  # folder (absolute) -> its real path, for the current run


def real_folder(directory: str) -> str:
    """The real path of ``directory``: one ``lstat`` per folder not seen before, its parent's answer
    reused (``Path.resolve`` walks every folder above it again: quadratic in a deep tree)."""
    folder = os.path.abspath(directory)
    chain = []
    at = folder
    while at not in _REAL:
        parent = os.path.dirname(at)
        if parent == at:
            _REAL[at] = at
            break
        chain.append(at)
        at = parent
    real = _REAL[at]
    for at in reversed(chain):
        real = os.path.realpath(at) if os.path.islink(at) else os.path.join(real, os.path.basename(at))
        _REAL[at] = real
    return _REAL[folder]


def _find_config(folder: str) -> Path | None:
    # (folders as strings: a Path of a folder 1,500 deep costs as much to build as its depth)
    visited: list[str] = []
    found: Path | None = None
    while True:
        if folder in _FOUND:
            found = _FOUND[folder]
            break
        visited.append(folder)
        found = _config_in(folder)
        parent = os.path.dirname(folder)
        if found is not None or parent == folder:
            break
        folder = parent
    for seen in visited:
        _FOUND[seen] = found
    return found


def clear_found() -> None:
    """Forget the configuration files found and read (``find_config``, ``real_folder``): a run starts
    with this, so a configuration written since the last run is seen."""
    _FOUND.clear()
    _BY_NAME.clear()
    _LOADED.clear()
    _REAL.clear()


def _config_in(folder: str) -> Path | None:
    for name in CONFIG_NAMES:
        candidate = os.path.join(folder, name)
        if os.path.isfile(candidate):
            if name == "pyproject.toml" and not load_file(Path(candidate)):
                continue
            return Path(candidate)
    return None


def severities_above(config: Path) -> list[dict[str, str]]:
    """The ``severity`` tables of the configurations further up than ``config`` (nearest first); one that
    cannot be read is left out (it applies to no file here)."""
    out: list[dict[str, str]] = []
    folder = os.path.dirname(os.path.dirname(os.path.abspath(config)))
    while (found := find_config(folder)) is not None:
        try:
            table = load_file(found)
            if "severity" in table:
                out.append(parse_severities(table["severity"], found))
        except ConfigError:
            pass
        parent = os.path.dirname(os.path.dirname(os.path.abspath(found)))
        if parent == folder:
            break
        folder = parent
    return out


def config_for(path: str, explicit: str | None = None) -> tuple[Path | None, dict]:
    """The configuration file and table that apply to ``path`` (``explicit`` wins when given)."""
    if explicit:
        p = Path(explicit)
        if not p.is_file():
            raise ConfigError(f"{explicit}: configuration file not found")
        return p, load_file(p)
    directory = os.path.dirname(os.path.abspath(path)) if path != "-" else os.getcwd()
    found = find_config(directory)
    if found is None:
        return None, {}
    return found, load_file(found)


def parse_severities(table: object, path: Path) -> dict[str, str]:
    """``severity = { HY029 = "info", SX = "error" }``: a level for rule codes or prefixes."""
    from gclint.rules.base import Severity

    if not isinstance(table, dict):
        raise ConfigError(f"{path}: 'severity' must be a table such as {{ HY029 = \"info\" }}")
    out: dict[str, str] = {}
    for code, level in table.items():
        _codes([str(code)], f"severity.{code}", path)
        if not isinstance(level, str):
            raise ConfigError(f"{path}: 'severity.{code}' must be error, warning or info")
        try:
            out[str(code).strip().upper()] = Severity.parse(level).label
        except ValueError as exc:
            raise ConfigError(f"{path}: 'severity.{code}': {exc}") from None
    return out
