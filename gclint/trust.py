"""What a configuration found beside the files may change, and what only the user can.

A configuration file found by walking up from the files (``.gclint.toml``, ``gclint.toml``,
``pyproject.toml [tool.gclint]``) travels with them: a pull request can add one next to the jobs it adds.
It may tune the SX, DL and HY rules, but it cannot switch a security (SC) rule off, lower its severity or
keep it from a file (``select``, ``ignore``, ``per-file-ignores``, ``allow-file-writes``, ``severity``; its ``exclude`` patterns
are read by ``gclint.excludes``).  Only the command line, an editor's settings or a configuration named by
``--config`` can: they are the user's.  ``guard`` holds the options a found configuration made to that,
and says what it refused.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from gclint.options import Options
from gclint.rules.base import Severity, all_rules, matches, select_rules

SECURITY = "SC"


@dataclass(frozen=True)
class Refusal:
    """What a found configuration asked of the security rules and did not get."""

    config: str
    codes: tuple[str, ...]
    how: str  # "select/ignore", "severity", "per-file-ignores 'pattern'"
    pattern: str | None = None  # (per-file-ignores, allow-file-writes: the files it names)

    def describe(self, files: int | None = None) -> str:
        what = f"security rule{'s' if len(self.codes) != 1 else ''} {', '.join(self.codes)}"
        verb = "lower the severity of" if self.how == "severity" else "switch off"
        count = "" if files is None else f" for {files} file{'s' if files != 1 else ''}"
        return (
            f"{self.config} asks to {verb} {what} ({self.how}){count}: refused, a configuration found beside the"
            " files cannot (the command line or a configuration named by --config can)"
        )


def selected(options: Options) -> list[str]:
    """The codes of the rules ``options`` selects (as ``Linter`` selects them)."""
    select = options.select
    if select is not None or options.extend_select:
        base = select if select is not None else [r.code for r in all_rules().values() if r.default_enabled]
        select = list(base) + list(options.extend_select)
    return [rule.code for rule in select_rules(all_rules().values(), select, options.ignore)]


def level(options: Options, code: str) -> Severity:
    """The severity ``options`` gives ``code``: the longest matching code or prefix of ``severity``, else
    the rule's own."""
    for length in (5, 4, 3, 2):
        said = options.severity.get(code[:length])
        if said is not None:
            return Severity.parse(said)
    return all_rules()[code].severity


def guard(options: Options, trusted: Options) -> tuple[Options, list[Refusal]]:
    """``options`` (a found configuration, then the command line) with every security rule that
    ``trusted`` (the defaults and the command line alone) checks still checked, at a severity no lower
    than ``trusted`` gives it, and on every file; and what that took back, per way of asking."""
    key = (options.cache_key(), options.config_path, trusted.cache_key())
    done = _GUARDED.get(key)
    if done is None:
        if len(_GUARDED) > 256:
            _GUARDED.clear()
        done = _GUARDED[key] = _guard(options, trusted)
    return replace(done[0]), list(done[1])  # (a copy: options are mutable)


_GUARDED: dict[tuple, tuple[Options, tuple[Refusal, ...]]] = {}  # per run, many files share their options


def _guard(options: Options, trusted: Options) -> tuple[Options, tuple[Refusal, ...]]:
    config = options.config_path or "the configuration"
    kept = [code for code in selected(trusted) if code.startswith(SECURITY)]
    refused: list[Refusal] = []
    changes: dict = {}
    now = set(selected(options))
    off = [code for code in kept if code not in now]
    if off:
        # the rule set, spelled out: a selector added to the found one would not do (the most specific
        # selector wins, and an extend-select of codes makes every default code outrank a prefix ignored)
        changes["select"] = [code for code in all_rules() if code in now or code in off]
        changes["extend_select"] = []
        changes["ignore"] = []
        refused.append(Refusal(config, tuple(off), "select/ignore"))
    lowered = [code for code in kept if level(options, code) < level(trusted, code)]
    if lowered:
        severity = dict(options.severity)
        for code in lowered:
            severity[code] = level(trusted, code).label  # a full code outranks any prefix
        changes["severity"] = severity
        refused.append(Refusal(config, tuple(lowered), "severity"))
    if options.allow_file_writes and "SC005" in kept:
        changes["allow_file_writes"] = ()
        refused.extend(
            Refusal(config, ("SC005",), f"allow-file-writes {p!r}", pattern=p) for p in options.allow_file_writes
        )
    if options.per_file_ignores:
        codes = list(all_rules())
        per_file: dict[str, list[str]] = {}
        for pattern, selectors in options.per_file_ignores.items():
            hit = [code for code in kept if matches(code, [s.strip().upper() for s in selectors])]
            if not hit:
                per_file[pattern] = selectors
                continue
            refused.append(Refusal(config, tuple(hit), f"per-file-ignores {pattern!r}", pattern=pattern))
            rest = [c for c in codes if c not in hit and matches(c, [s.strip().upper() for s in selectors])]
            if rest:
                per_file[pattern] = rest
        if per_file != options.per_file_ignores:
            changes["per_file_ignores"] = per_file
    return (replace(options, **changes) if changes else options), tuple(refused)


def keep_raised(options: Options, above: list[dict[str, str]]) -> Options:
    """``options`` with each security rule at no lower a severity than a configuration further up gives it
    (``above``: their ``severity`` tables): the nearest configuration applies alone, so one added in a
    sub-folder would otherwise drop, without a word about security, what the project's own raised."""
    if not above:
        return options
    severity = dict(options.severity)
    for code in all_rules():
        if not code.startswith(SECURITY):
            continue
        now = level(options, code)
        for table in above:
            said = level(replace(options, severity=table), code)
            if said > now:
                now = said
                severity[code] = said.label
    return replace(options, severity=severity) if severity != options.severity else options


def security_only(options: Options) -> Options:
    """``options`` with only the security rules they check: for a file a found configuration excludes."""
    codes = [code for code in selected(options) if code.startswith(SECURITY)]
    return replace(options, select=codes, extend_select=[], ignore=[])
