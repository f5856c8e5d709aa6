"""What the settings of a run switch off, said out loud: ``--show-settings`` and the configuration notes
every report format carries (``configuration_notes``: SARIF, GitHub, JUnit, HTML, the text summary, stderr).

A job can never silence its own SC findings (``noqa.INLINE_UNSUPPRESSIBLE``), nor can a configuration found
beside the files (``gclint.trust``); the command line and a configuration named by ``--config`` can.  Whenever
they switch security rules off, or a configuration switches a rule family off or asks in vain, gclint says
which, where and how: a suppression that is not shown would be a way around the gate.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace
from pathlib import Path

from gclint import trust
from gclint.config import ConfigError, apply, config_for
from gclint.engine import Linter, Options
from gclint.rules.base import Severity, all_rules, matches
from gclint.textsafe import human

SECURITY = "SC"


@dataclass(frozen=True)
class Suppression:
    """Security rules ``codes`` switched off by ``origin`` (a configuration file or "the command line")
    through ``how`` (``ignore``, ``select``, ``per-file-ignores 'pattern'``), for ``files`` files."""

    codes: tuple[str, ...]
    origin: str
    how: str
    files: int
    from_config: bool
    verb: str = "switches off"

    def describe(self) -> str:
        what = f"security rule{'s' if len(self.codes) != 1 else ''} {', '.join(self.codes)}"
        count = f"{self.files} file{'s' if self.files != 1 else ''}"
        return f"{self.origin} {self.verb} {what} ({self.how}) for {count}"


def _security_codes() -> list[str]:
    return [code for code in all_rules() if code.startswith(SECURITY)]


def _selected(options: Options) -> set[str]:
    return set(trust.selected(options))


def _how(options: Options) -> str:
    parts = []
    if options.select is not None:
        parts.append("select")
    if options.extend_select:
        parts.append("extend-select")
    if options.ignore:
        parts.append("ignore")
    return "/".join(parts) or "select"


@dataclass
class _Group:
    """The files one configuration (or none) applies to, and what it makes of the options."""

    config: Path | None
    trusted: bool  # named by --config (or no configuration): the user's own
    raw: Options  # the configuration alone, as written
    options: Options  # the configuration, then the command line, held to gclint.trust for a found one
    refusals: list[trust.Refusal]
    paths: list[str]


def _groups(files: Iterable[str], overrides: dict, explicit_config: str | None) -> dict[str | None, _Group]:
    groups: dict[str | None, _Group] = {}
    for path in files:
        try:
            config_path, table = config_for(path, explicit_config)
        except ConfigError:  # reported by the check itself
            continue
        key = str(config_path) if config_path is not None else None
        if key not in groups:
            try:
                raw = apply(Options(), table, config_path) if config_path is not None else Options()
            except ConfigError:
                continue
            options = replace(raw, **overrides) if overrides else raw
            refusals: list[trust.Refusal] = []
            trusted = config_path is None or explicit_config is not None
            if not trusted:
                options, refusals = trust.guard(options, replace(Options(), **overrides))
            groups[key] = _Group(config_path, trusted, raw, options, refusals, [])
        groups[key].paths.append(path)
    return groups


def security_suppressions(
    files: Iterable[str], overrides: dict, explicit_config: str | None = None
) -> list[Suppression]:
    """Every way the configuration files and the command line switch security rules off for ``files``.
    (A configuration found beside the files cannot: ``refusals`` says what one asked for in vain.)"""
    security = _security_codes()
    out: list[Suppression] = []
    for key, group in _groups(files, overrides, explicit_config).items():
        options, config_options, paths = group.options, group.raw, group.paths
        origin = _display(key) if key is not None else "the command line"
        off = set(security) - _selected(options)
        by_config = sorted(off - _selected(config_options)) if key is not None and group.trusted else []
        if by_config:
            out.append(Suppression(tuple(by_config), origin, _how(config_options), len(paths), True))
        by_cli = sorted(off - set(by_config))
        if by_cli:
            out.append(Suppression(tuple(by_cli), "the command line", _how(options), len(paths), False))
        lowered = _lowered_security(options, security)
        if lowered:  # a security rule made info passes the gate as surely as one switched off
            from_config = key is not None and lowered == _lowered_security(config_options, security)
            origin_of = origin if from_config else "the command line"
            out.append(Suppression(tuple(lowered), origin_of, "severity lowered", len(paths), from_config))
        for pattern, codes in options.per_file_ignores.items():
            ignored = [c for c in security if any(c.startswith(s.strip().upper()) for s in codes)]
            single = Linter(replace(options, per_file_ignores={pattern: codes}, allow_file_writes=()))
            matched = sum(1 for p in paths if _hit(single, p, ignored)) if ignored else 0
            if matched:
                out.append(
                    Suppression(tuple(ignored), origin, f"per-file-ignores {pattern!r}", matched, key is not None)
                )
        for pattern in options.allow_file_writes:
            single = Linter(replace(options, per_file_ignores={}, allow_file_writes=(pattern,)))
            matched = sum(1 for p in paths if _hit(single, p, ["SC005"]))
            if matched:
                how = f"allow-file-writes {pattern!r}"
                out.append(Suppression(("SC005",), origin, how, matched, key is not None))
    return out


def configuration_notes(files: list[str], overrides: dict, explicit_config: str | None = None) -> list[str]:
    """What the configuration does that a report must say (every format carries these lines): security
    rules switched off or lowered (``security_suppressions``), what a found configuration asked of them in
    vain, and rule families a configuration switches off."""
    notes = [s.describe() for s in security_suppressions(files, overrides, explicit_config)]
    groups = _groups(files, overrides, explicit_config)
    cli = replace(Options(), **overrides) if overrides else Options()
    kept_by_cli = {code[:2] for code in trust.selected(cli)}
    for key, group in groups.items():
        count = f"{len(group.paths)} file{'s' if len(group.paths) != 1 else ''}"
        for refusal in group.refusals:
            named = len(group.paths)
            if refusal.pattern is not None:  # (the files its pattern names, not every file the configuration covers)
                single = Linter(replace(group.raw, per_file_ignores={refusal.pattern: list(refusal.codes)}))
                named = sum(1 for p in group.paths if _hit(single, p, list(refusal.codes)))
            notes.append(replace(refusal, config=_display(refusal.config)).describe(named))
        if key is None:
            continue
        on = {code[:2] for code in trust.selected(group.options)}
        off = sorted(kept_by_cli - on - {SECURITY})  # (security rules: said above, code by code)
        if off:
            families = f"rule famil{'ies' if len(off) != 1 else 'y'} {', '.join(off)}"
            notes.append(f"{_display(key)} switches off {families} ({_how(group.raw)}) for {count}")
        for pattern, selectors in group.options.per_file_ignores.items():
            single = Linter(replace(group.options, per_file_ignores={pattern: selectors}))
            whole = sorted(
                family
                for family in on - {SECURITY}
                if all(
                    matches(c, [s.upper() for s in selectors]) for c in trust.selected(group.options) if c[:2] == family
                )
            )
            hit = sum(1 for p in group.paths if single.per_file_ignores(p)) if whole else 0
            if hit:
                families = f"rule famil{'ies' if len(whole) != 1 else 'y'} {', '.join(whole)}"
                notes.append(
                    f"{_display(key)} switches off {families} (per-file-ignores {pattern!r}) for {hit} file{'s' if hit != 1 else ''}"
                )
    return notes


def _level(options: Options, code: str) -> Severity | None:
    """The severity the configuration gives ``code`` (the longest matching code or prefix), or None."""
    for length in (5, 4, 3, 2):
        level = options.severity.get(code[:length])
        if level is not None:
            return Severity.parse(level)
    return None


def _lowered_security(options: Options, security: list[str]) -> list[str]:
    """Security rules whose severity the configuration lowers below their own."""
    if not options.severity:
        return []
    rules = all_rules()
    out = []
    for code in security:
        for length in (5, 4, 3, 2):
            level = options.severity.get(code[:length])
            if level is not None:
                if Severity.parse(level) < rules[code].severity:
                    out.append(code)
                break
    return out


def _hit(linter: Linter, path: str, codes: list[str]) -> bool:
    ignored = linter.per_file_ignores(path)
    return any(code.startswith(s) for code in codes for s in ignored)


def _display(path: str) -> str:
    try:
        return str(Path(path).relative_to(Path.cwd()))
    except ValueError:
        return path


def show_settings(files: list[str], overrides: dict, explicit_config: str | None, cache_folder: str | None) -> str:
    """The settings each file is checked with (one block per configuration), as ``--show-settings`` prints."""
    from gclint.runner import options_for

    blocks: dict[str, tuple[Options, list[str]]] = {}
    for path in files:
        options = options_for(path, Options(), overrides, explicit_config)
        blocks.setdefault(options.cache_key() + repr(options.config_path), (options, []))[1].append(path)
    notes = configuration_notes(files, overrides, explicit_config)
    lines: list[str] = []
    for options, paths in blocks.values():
        linter = Linter(options)
        extra = f" (and {len(paths) - 1} more with the same settings)" if len(paths) > 1 else ""
        lines.append(f"Settings for {paths[0]}{extra}:")
        lines.append(f"  configuration file: {options.config_path or '(none)'}")
        lines.append(
            f"  dialect: {options.dialect}"
            + (" (each file's is decided from its content)" if options.dialect == "auto" else "")
        )
        lines.append(f"  firmware (flavor): {options.flavor or '(read from each file)'}")
        lines.append(f"  printer: {options.printer or '(read from each Hyrel job, else 30m)'}")
        loaded = "from the job header" if options.loaded is None else ",".join(f"T{h}" for h in sorted(options.loaded))
        lines.append(f"  loaded heads: {loaded}")
        lines.append(f"  select: {', '.join(options.select) if options.select is not None else '(default rules)'}")
        lines.append(f"  extend-select: {', '.join(options.extend_select) or '(none)'}")
        lines.append(f"  ignore: {', '.join(options.ignore) or '(none)'}")
        pfi = "; ".join(f"{k} = {', '.join(v)}" for k, v in options.per_file_ignores.items()) or "(none)"
        lines.append(f"  per-file-ignores: {pfi}")
        if options.allow_file_writes:
            lines.append(f"  allow-file-writes (SC005 not reported): {', '.join(options.allow_file_writes)}")
        if options.machine_codes:
            shown = ", ".join(options.machine_codes[:12]) + (" ..." if len(options.machine_codes) > 12 else "")
            inis = ", ".join(_display(p) for p in options.machine_config)
            lines.append(f"  machine codes (REMAP in {inis}, LinuxCNC/Machinekit jobs): {shown}")
        if options.spindle_max_rpm is not None:
            lines.append(f"  spindle-max-rpm: {options.spindle_max_rpm:g}")
        if options.tool_map:
            lines.append("  tool-map: " + ", ".join(f"{k}=T{v}" for k, v in sorted(options.tool_map.items())))
        lines.append(f"  rules: {len(linter.rule_classes)} selected")
        lines.append("")
    lines.append("Checked as:")
    for path in files:
        lines.append(f"  {path}: {_checked_as(path, overrides, explicit_config)}")
    lines.append("")
    if notes:
        lines.append("What the configuration switches off:")
        lines.extend(f"  {note}" for note in notes)
    else:
        lines.append("What the configuration switches off: nothing")
    lines.append(f"Result cache: {cache_folder}")
    return "\n".join(human(line) for line in lines) + "\n"  # file names are file text: escaped


def _checked_as(path: str, overrides: dict, explicit_config: str | None) -> str:
    """What ``path`` would be checked as, and why (gclint.context), without checking it."""
    from gclint.runner import options_for
    from gclint.syntax.source import Source, SourceError

    if path == "-":
        return "(standard input: decided when it is read)"
    options = options_for(path, Options(), overrides, explicit_config)
    try:
        source = Source.open(path)
    except SourceError as exc:
        return str(exc)
    try:
        context = Linter(options).context_of(source)
    except SourceError as exc:
        return str(exc)
    finally:
        source.close()
    printer = ""
    if context.printer is not None:
        how = {"option": "--printer", "configuration": "the configuration", "job": "read from the job"}
        printer = f"; printer {context.printer}: {how.get(context.printer_from, 'the default')}"
    evidence = {"none": "no evidence: the default"}.get(context.strength, f"{context.strength} evidence")
    return f"{context.label()} ({evidence}): {context.why()}{printer}"
