"""Check a slicer profile's custom G-code, as every job sliced with it will carry it.

For each printer in the file (one for a configuration, each printer preset of a bundle), the custom G-code
settings are filled (``placeholders``) and put together in the order the slicer writes them into a job
(``JOB_ORDER``: start, the first layer change, a tool change, the user's pauses and colour changes, end), with
the slicer's flavour said as a job says it (``; gcode_flavor = ...``, Cura's ``;FLAVOR:``, and
``SLIC3R_GCODE_FLAVOR``: the content of the G-code still decides the dialect, as for any job:
gclint.context).  That text is checked with every rule, and each finding is reported where its command is
written in the profile: ``path:line:col`` in the file, the message naming the setting and its line.

What the check filled in is said in the result's notes: the placeholders that got a typical value (a printer
profile has no filament temperature) and the macros gclint does not evaluate.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from gclint.engine import FileResult, Linter
from gclint.options import Options
from gclint.profiles.ini import MAX_BYTES, ProfileError
from gclint.profiles.placeholders import Filled, MacroError, Value, fill
from gclint.profiles.reader import CURA, GcodeSetting, Profile, read_profiles
from gclint.rules.base import Finding, Severity

# Where the slicer writes each setting into a job (PrusaSlicer's GCode.cpp, OrcaSlicer's, CuraEngine's
# start and end G-code): a setting not listed goes before the end G-code, in the file's order.
JOB_ORDER = (
    "start_gcode",
    "machine_start_gcode",
    "machine_extruder_start_code",
    "start_filament_gcode",
    "filament_start_gcode",
    "before_layer_gcode",
    "before_layer_change_gcode",
    "layer_gcode",
    "layer_change_gcode",
    "toolchange_gcode",
    "change_filament_gcode",
    "color_change_gcode",
    "pause_print_gcode",
    "machine_pause_gcode",
    "template_custom_gcode",
    "between_objects_gcode",
    "printing_by_object_gcode",
)
JOB_END = ("end_filament_gcode", "filament_end_gcode", "machine_extruder_end_code", "end_gcode", "machine_end_gcode")
# What the slicer knows while it writes a setting (the rest comes from the profile, else placeholders.TYPICAL)
AT_SETTING: dict[str, dict[str, Value]] = {
    "toolchange_gcode": {"previous_extruder": 0.0, "next_extruder": 1.0, "current_extruder": 0.0},
    "change_filament_gcode": {"previous_extruder": 0.0, "next_extruder": 1.0, "current_extruder": 0.0},
}
# Cura's machine_gcode_flavor, as CuraEngine names it in the ;FLAVOR: header
_CURA_FLAVORS = {
    "reprap (marlin/sprinter)": "Marlin",
    "reprap (volumetric)": "Marlin(Volumetric)",
    "reprap (reprap)": "RepRap",
    "ultigcode": "UltiGCode",
    "griffin": "Griffin",
    "makerbot": "Makerbot",
    "bits from bytes": "BFB",
    "mach3": "Mach3",
    "repetier": "Repetier",
}
MAX_NOTES = 8


@dataclass
class _Piece:
    """The lines one setting puts into the checked text."""

    setting: GcodeSetting
    filled: Filled
    first: int  # its first line in the checked text
    starts: list[int]  # where each of its lines starts in filled.text


def check_profile(path: str, options: Options, linter: Linter | None = None) -> FileResult:
    """Check the slicer profile ``path`` with ``options``: a result like a job's, its findings in the file."""
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as fh:
            text = fh.read(MAX_BYTES + 1)
    except OSError as exc:
        return FileResult(path, error=f"{path}: cannot read: {exc.strerror or exc}")
    try:
        profiles = read_profiles(path, text)
    except ProfileError as exc:
        return FileResult(path, error=f"{path}: {exc}")
    except RecursionError:
        return FileResult(path, error=f"{path}: nested too deeply to read")
    findings: dict[tuple, Finding] = {}
    presets: dict[tuple, list[str]] = {}  # the printer presets of a bundle each finding is made in
    notes: list[str] = []
    result = FileResult(path, lines=text.count("\n") + 1, profile=True)
    several = len(profiles) > 1  # (a bundle: each finding names the printer presets it is found in)
    typical: set[str] = set()
    read_as: dict[str, list[FileResult]] = {}
    for profile in profiles:
        checked = _check(profile, options, findings, presets if several else {}, notes, several, typical)
        if checked is not None:
            read_as.setdefault(checked.read_as, []).append(checked)
    if read_as:  # what most presets were read as ("Checked as ..."), and a note when they differ
        first = max(read_as.values(), key=len)[0]
        result.context, result.dialect, result.dialect_reason = first.context, first.dialect, first.dialect_reason
        if len(read_as) > 1:
            counts = sorted(read_as.items(), key=lambda item: -len(item[1]))
            notes.insert(0, "its printer presets are read as " + "; ".join(f"{k} ({len(v)})" for k, v in counts))
    if typical:
        names = sorted(typical)
        shown = ", ".join(f"{k}={_typical_value(k)}" for k in names[:12]) + (" ..." if len(names) > 12 else "")
        notes.insert(0, f"placeholders with no value in the profile were filled with typical values: {shown}")
    if linter is None:
        linter = Linter(options)
    if any(cls.code == "SC006" for cls in linter.rule_classes):
        secrets = _secrets(path, text, options)
        if secrets:  # (a secret in a setting's G-code is one finding, the profile's, not two: the G-code one
            # quotes the line, whose masking hid its own explanation)
            where = {f.line for f in secrets}
            findings = {k: f for k, f in findings.items() if not (f.code == "SC006" and f.line in where)}
        for f in secrets:
            findings.setdefault((f.line, f.column, f.code, f.message), f)
    result.findings = sorted((_named(f, presets.get(key, [])) for key, f in findings.items()), key=Finding.sort_key)
    result.notes = _dedupe(notes)
    if len(profiles) > 1:
        result.notes.insert(0, f"{len(profiles)} printer presets checked")
    return result


def _check(
    profile: Profile,
    options: Options,
    findings: dict[tuple, Finding],
    presets: dict[tuple, list[str]],
    notes: list[str],
    several: bool,
    typical: set[str],
) -> FileResult | None:
    pieces, text, errors = _job(profile)
    who = f"printer preset {profile.name!r}: " if profile.name and several else ""
    notes.extend(who + note for note in profile.notes)
    for at, setting, message in errors if _enabled(options, "PF001") else ():
        line, column = setting.text.at(at)
        message = f"{setting.label}: {message}"
        key = (line, column, "PF001", message)
        findings.setdefault(key, _finding(profile.path, line, column, "PF001", message, options))
        if profile.name is not None and several:
            presets.setdefault(key, []).append(profile.name)
    if not pieces:
        notes.append(f"{who}no custom G-code setting to check")
        return None
    for piece in pieces:
        typical |= piece.filled.typical
        for at, what in piece.filled.unevaluated:
            line, column = piece.setting.text.at(at)
            notes.append(f"line {line}, column {column}: {piece.setting.label}: {what}")
    flavor = profile.flavor
    run_options = replace(options, env_flavor=flavor) if flavor and profile.slicer != CURA else options
    result = _lint(Linter(run_options), text, profile.path)
    result.dialect_reason = _LINE_REF.sub(lambda m: _line_ref(m, pieces), result.dialect_reason)
    if result.error is not None:
        notes.append(f"{who}{result.error}")
    for f in result.findings:
        mapped = _map(f, pieces, profile)
        if mapped is not None:
            key = (mapped.line, mapped.column, mapped.code, mapped.message)
            findings.setdefault(key, mapped)
            if profile.name is not None and several:
                presets.setdefault(key, []).append(profile.name)
    return result


def _job(profile: Profile) -> tuple[list[_Piece], str, list[tuple[int, GcodeSetting, str]]]:
    """The checked text of ``profile``: its settings filled, in job order, between the lines a job carries
    to say its slicer and flavour."""
    order = {key: i for i, key in enumerate(JOB_ORDER)}
    end = {key: i for i, key in enumerate(JOB_END)}
    settings = [s for s in profile.settings if s.text.text.strip()]
    settings.sort(key=lambda s: (2, end[s.key]) if s.key in end else (0, order[s.key]) if s.key in order else (1, 0))
    lines: list[str] = list(_header(profile))
    pieces: list[_Piece] = []
    errors: list[tuple[int, GcodeSetting, str]] = []
    for setting in settings:
        known = AT_SETTING.get(setting.key, {})

        def lookup(key: str, known: dict = known) -> Value | None:
            return known[key] if key in known else profile.lookup(key)

        try:
            filled = fill(setting.text.text, lookup, cura=profile.slicer == CURA)
        except MacroError as exc:
            errors.append((0, setting, str(exc)))
            continue
        errors.extend((at, setting, what) for at, what in filled.errors)
        body = filled.text
        starts = [0] + [m.end() for m in _BREAK.finditer(body)]
        if body.endswith(("\n", "\r")):
            starts.pop()
        pieces.append(_Piece(setting, filled, len(lines) + 1, starts))
        for i, start in enumerate(starts):
            stop = starts[i + 1] if i + 1 < len(starts) else len(body)
            lines.append(body[start:stop].rstrip("\r\n"))
    lines.extend(_trailer(profile))
    return pieces, "\n".join(lines) + "\n", errors


_BREAK = re.compile(r"\r\n|\r|\n")


def _header(profile: Profile) -> list[str]:
    if profile.slicer == CURA:
        flavor = _CURA_FLAVORS.get((profile.flavor or "").strip().lower())
        return [f";FLAVOR:{flavor}"] if flavor else []
    return []


def _trailer(profile: Profile) -> list[str]:
    """The settings a sliced job writes at its end that say what it is for (gclint.context reads them)."""
    if profile.slicer == CURA:
        return []
    out = []
    for key in ("gcode_flavor", "printer_model", "printer_notes"):
        value = profile.values.get(key)
        if value not in (None, "", []):
            shown = ",".join(str(v) for v in value) if isinstance(value, list) else str(value)
            out.append(f"; {key} = {shown.splitlines()[0] if shown else ''}")
    return out


def _map(f: Finding, pieces: list[_Piece], profile: Profile) -> Finding | None:
    """``f`` (a finding in the checked text) where its command is written in the profile; None for the
    lines only the check added."""
    for piece in reversed(pieces):
        if piece.first <= f.line < piece.first + len(piece.starts):
            k = f.line - piece.first
            start = piece.starts[k]
            stop = piece.starts[k + 1] if k + 1 < len(piece.starts) else len(piece.filled.text)
            index = min(start + max(f.column, 1) - 1, max(start, stop - 1))
            origin = piece.filled.origin[index] if index < len(piece.filled.origin) else len(piece.setting.text.text)
            line, column = piece.setting.text.at(origin)
            shown = piece.filled.text[start:stop].strip()
            if len(shown) > 60:
                shown = shown[:57] + "..."
            said = _LINE_REF.sub(lambda m: _line_ref(m, pieces), f.message)
            message = f"{piece.setting.label} line {k + 1} ({shown}): {said}"
            return replace(
                f, path=profile.path, line=line, column=column, end_column=None, message=message, fix=None, source=None
            )
    return None


def _named(f: Finding, names: list[str]) -> Finding:
    """``f`` with the printer presets of a bundle it is found in (a setting of ``*common*`` is in many)."""
    if not names:
        return f
    shown = ", ".join(repr(n) for n in names[:2]) + (f" and {len(names) - 2} more" if len(names) > 2 else "")
    return replace(f, message=f"{f.message} [printer preset{'s' if len(names) > 1 else ''} {shown}]")


_LINE_REF = re.compile(r"\bline (\d{1,9})\b")


def _line_ref(m: re.Match[str], pieces: list[_Piece]) -> str:
    """ "line 21" of a rule's message (a line of the checked text) as the setting's line it is."""
    number = int(m.group(1))
    for piece in pieces:
        if piece.first <= number < piece.first + len(piece.starts):
            return f"{piece.setting.label} line {number - piece.first + 1}"
    return m.group(0)


def _finding(path: str, line: int, column: int, code: str, message: str, options: Options) -> Finding:
    from gclint.rules.base import all_rules

    rule = all_rules()[code]
    severity = Severity.parse(options.severity[code]) if code in options.severity else rule.severity
    return Finding(path, line, column, code, severity, message, name=rule.name)


def _secrets(path: str, text: str, options: Options) -> list[Finding]:
    """SC006 (a password or API key) in the profile's own lines: a profile in a repository is shared."""
    linter = Linter(replace(options, select=["SC006"], extend_select=[], ignore=[]))
    # each line read as the comment a job carries it in ("; printhost_apikey = ..." in PrusaSlicer's settings)
    commented = "".join(f"; {line}\n" for line in text.splitlines())
    found = _lint(linter, commented, path).findings
    return [
        replace(
            f, column=max(1, f.column - 2), end_column=None, source=None, message=_LEFT_IN.sub(_IN_PROFILE, f.message)
        )
        for f in found
        if f.code == "SC006"
    ]


_LEFT_IN = re.compile(r" left in (?:a comment|the job)\b.*$")
_IN_PROFILE = " left in the profile: anyone who gets the profile can read it"


def _lint(linter: Linter, text: str, path: str) -> FileResult:
    """``text`` checked as G-code, whatever its head looks like (a profile's lines are ``key = value``)."""
    from gclint.syntax.source import Source, SourceError

    try:
        source = Source.from_text(text, path, cut_long_lines=True)
    except SourceError as exc:
        return FileResult(path, error=str(exc))
    return linter.check_source(source, sniff=False)


def _enabled(options: Options, code: str) -> bool:
    return any(cls.code == code for cls in Linter(options).rule_classes)


def _typical_value(key: str) -> str:
    from gclint.profiles.placeholders import TYPICAL, _show

    value = TYPICAL[key]
    return _show(value[0] if isinstance(value, list) and len(value) == 1 else value)


def _dedupe(notes: list[str]) -> list[str]:
    out = list(dict.fromkeys(notes))
    if len(out) > MAX_NOTES:
        more = len(out) - MAX_NOTES
        out = out[:MAX_NOTES] + [f"and {more} more note{'s' if more != 1 else ''} like these"]
    return out
