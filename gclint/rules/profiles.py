"""PF: findings about a slicer profile itself (``gclint check profile.ini``), beyond the G-code it writes.

The G-code of a profile's custom settings is checked by every other rule (gclint.profiles.check); these rules
are about the profile's own text.  ``families = ()`` keeps them out of the check of a job: only the profile
check (gclint/profiles/check.py) reports them.
"""

from __future__ import annotations

from gclint.rules.base import Rule, Severity, register


class ProfileRule(Rule):
    """Base of the PF rules: reported by the profile check, never on a job."""

    families = ()

    @classmethod
    def doc(cls) -> dict:
        out = super().doc()
        out["applies_to"] = ["slicer profiles (gclint check profile.ini, Orca .json, Cura .def.json)"]
        return out


@register
class MacroError(ProfileRule):
    code = "PF001"
    name = "placeholder-macro-error"
    severity = Severity.ERROR
    summary = "A placeholder macro in a custom G-code setting that the slicer refuses (the export stops)"
    explanation = """
        PrusaSlicer, SuperSlicer, OrcaSlicer and Bambu Studio fill the placeholders of custom G-code before
        they write it (PrusaSlicer's manual, "Macro language"): `{...}` is a macro, and `{if ...}` must be
        closed by `{endif}`.  A `{` with no closing `}` on its line, an `{endif}`, `{else}` or `{elsif}`
        with no `{if}` before it, or an `{if}` never closed, makes the slicer stop the export with a
        "Parsing error" naming the setting: no job can be sliced with the profile.
    """
    example_bad = "start_gcode = M104 S{first_layer_temperature[0]\\nG28"
    example_good = "start_gcode = M104 S{first_layer_temperature[0]}\\nG28"
    source = "PrusaSlicer manual, Macro language (placeholders, {if} blocks); libslic3r/PlaceholderParser.cpp"
