"""Slicer profiles (gclint.profiles): PrusaSlicer's bundles and their ``inherits`` chains, the placeholder macro
language, and ``gclint check`` on a profile: its custom G-code checked in its flavour, each finding where its
command is written in the profile (``path:line:col`` in the .ini or .json)."""

from __future__ import annotations

import json
import re
import textwrap
from pathlib import Path

import pytest

from gclint.options import Options
from gclint.profiles.bundle import Bundle
from gclint.profiles.check import check_profile
from gclint.profiles.ini import unescape, unescape_list
from gclint.profiles.placeholders import fill
from gclint.rules.base import all_rules
from tests.conftest import CORPUS, needs_corpus, run_cli

VENDOR_PROFILES = Path("/usr/share/PrusaSlicer/profiles")
HYREL_PROFILE = CORPUS / "hyrel" / "oinkotariah__printer_30M-ESR_T1_Heated.ini"

BUNDLE = """\
[vendor]
name = Test

[printer:*common*]
gcode_flavor = marlin2
start_gcode = G28\\nM104 S[first_layer_temperature]
retract_length = 1

[printer:*bowden*]
retract_length = 5
renamed_from = "Old name"

[printer:*direct*]
retract_length = 0.8

[printer:Test One]
inherits = *common*; *bowden*; *direct*
printer_model = ONE
default_filament_profile = "Test PLA"

[printer:Test Two]
inherits = *common*; *direct*; *bowden*
retract_length = 2
renamed_from = "Two"

[filament:Test PLA]
first_layer_temperature = 205
"""


# -- the bundle resolver ------------------------------------------------------------------------------------


def test_inherits_later_parents_win_and_own_settings_win_over_all():
    bundle = Bundle.from_text(BUNDLE)
    assert bundle.names("printer") == ["Test One", "Test Two"]  # (*intermediate* presets are not public)
    one = bundle.flat("printer", "Test One")
    assert one["retract_length"].value == "0.8"  # *direct* is the last parent
    assert one["start_gcode"].section == "printer:*common*" and one["start_gcode"].line == 6
    assert "renamed_from" not in one  # (never inherited)
    assert "inherits" not in one
    two = bundle.flat("printer", "Test Two")
    assert two["retract_length"].value == "2"
    assert two["renamed_from"].value == '"Two"'


def test_slicing_config_takes_the_default_filament_and_drops_bundle_keys():
    config = Bundle.from_text(BUNDLE).slicing_config("Test One")
    assert config["first_layer_temperature"] == "205"
    assert config["printer_model"] == "ONE"
    assert not {"inherits", "renamed_from", "alias"} & set(config)


def test_an_inherits_cycle_is_an_error_not_a_hang():
    from gclint.profiles.ini import ProfileError

    bundle = Bundle.from_text(
        "[printer:*a*]\ninherits = *b*\n[printer:*b*]\ninherits = *a*\n[printer:P]\ninherits = *a*\n"
    )
    with pytest.raises(ProfileError, match="inherits itself"):
        bundle.flat("printer", "P")


# -- values and placeholders --------------------------------------------------------------------------------


def test_ini_values_are_decoded_as_prusaslicer_decodes_them_with_their_columns():
    decoded = unescape(r"G28\nM117 a\\b", 3, 15)
    assert decoded.text == "G28\nM117 a\\b"
    assert decoded.at(4) == (3, 20)  # "M" of M117: after the two characters of "\n"
    items = unescape_list(r'"G1 X1\nG1 X2";"M104 S0"', 1, 1)
    assert [d.text for d in items] == ["G1 X1\nG1 X2", "M104 S0"]


def test_placeholders_are_filled_from_the_profile_then_typical_values():
    values = {"nozzle_diameter": [0.4, 0.6], "printer_model": "MK3S", "layer_height": 0.3}
    text = (
        'M862.3 P "[printer_model]"\nM104 S[first_layer_temperature]\n[nozzle_diameter_1]\n'
        "{if layer_height<0.075}M221 S100{else}M221 S95{endif}\nG1 Z{layer_height*2+0.1}\n"
        "print_start EXTRUDER=[first_layer_temperature[initial_tool]] {if printer_model=~/.*MK3.*/}yes{endif}\n[foo]"
    )
    filled = fill(text, values.get)
    assert filled.text.splitlines() == [
        'M862.3 P "MK3S"',
        "M104 S215",
        "0.6",
        "M221 S95",
        "G1 Z0.7",
        "print_start EXTRUDER=215 yes",
        "[foo]",  # (not a placeholder: PrusaSlicer leaves it)
    ]
    assert filled.typical == {"first_layer_temperature", "initial_tool"}
    assert not filled.errors and not filled.unevaluated
    assert filled.origin[filled.text.index("215")] == text.index("[first_layer_temperature]")


def test_macros_gclint_does_not_evaluate_are_said_and_broken_ones_are_errors():
    filled = fill("M104 S{nothing_known}\n{if some_unknown}A{else}B{endif}", {}.get)
    assert filled.text == "M104 S0\nA"
    assert [what for _, what in filled.unevaluated] == [
        "{nothing_known}: no value for 'nothing_known' in the profile; 0 was used",
        "{if some_unknown}: no value for 'some_unknown' in the profile; its first branch was taken",
    ]
    assert [what for _, what in fill("M104 S{x\nG28", {}.get).errors] == [
        "a '{' with no closing '}': the slicer stops the export"
    ]
    assert fill("{endif}", {}.get).errors and fill("{if 1}G28", {}.get).errors


def test_cura_settings_of_an_extruder():
    filled = fill(
        "M109 S{material_print_temperature_layer_0, 0}", {"material_print_temperature_layer_0": 230.0}.get, cura=True
    )
    assert filled.text == "M109 S230"


# -- gclint check on a profile ------------------------------------------------------------------------------


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def test_a_finding_points_at_its_command_in_the_ini(tmp_path):
    profile = _write(
        tmp_path,
        "printer.ini",
        r"""
        # generated by PrusaSlicer 2.5.0
        gcode_flavor = marlin2
        start_gcode = G28\nM104 S[first_layer_temperature]\nG1 X10 X20 F3000
        end_gcode = M104 S0\nM84 ; noqa: DL001
        """,
    )
    proc = run_cli("check", profile.name, cwd=tmp_path)
    out = proc.stdout.decode()
    column = (profile.read_text().splitlines()[3]).index("X20") + 1
    assert (
        f"printer.ini:4:{column}: SX002 [error] start_gcode line 3 (G1 X10 X20 F3000): X appears more than once" in out
    )
    assert proc.returncode == 1
    assert "Checked as marlin" in out
    assert "typical values: first_layer_temperature=215" in proc.stderr.decode()


def test_a_noqa_in_the_settings_g_code_works(tmp_path):
    profile = _write(tmp_path, "p.ini", "gcode_flavor = marlin2\nstart_gcode = G28\\nG1 X1 X2 F600 ; noqa: SX002\n")
    assert check_profile(str(profile), Options()).findings == []


def test_a_linuxcnc_ini_is_no_profile(tmp_path):
    """An INI that no slicer wrote is refused as before: not G-code (exit 2), read by the SC rules."""
    ini = _write(tmp_path, "machine.ini", "[EMC]\nMACHINE = mill\n[RS274NGC]\nREMAP=M206 modalgroup=10 ngc=fan\n")
    proc = run_cli("check", ini.name, cwd=tmp_path)
    assert proc.returncode == 2
    assert "not G-code" in proc.stderr.decode()


def test_orca_json_profile_with_its_parent_beside_it(tmp_path):
    (tmp_path / "fdm_klipper_common.json").write_text(
        json.dumps({"type": "machine", "name": "fdm_klipper_common", "gcode_flavor": "klipper"}, indent=4)
    )
    profile = tmp_path / "My Voron.json"
    start = "PRINT_START EXTRUDER=[nozzle_temperature_initial_layer]\nG1 X10 X20 F600"
    profile.write_text(
        json.dumps({"name": "My Voron", "inherits": "fdm_klipper_common", "machine_start_gcode": start}, indent=4)
    )
    result = check_profile(str(profile), Options())
    [finding] = result.findings
    line = profile.read_text().splitlines()[finding.line - 1]
    assert finding.code == "SX002" and line[finding.column - 1 :].startswith("X20")
    assert result.read_as == "marlin (klipper)"  # (the parent's gcode_flavor)


def test_cura_definition(tmp_path):
    definition = {
        "name": "My Ender",
        "inherits": "fdmprinter",
        "overrides": {
            "machine_gcode_flavor": {"default_value": "RepRap (Marlin/Sprinter)"},
            "machine_start_gcode": {
                "default_value": "G28\nM190 S{material_bed_temperature_layer_0}\nG1 Z0.3 Z0.4 F300"
            },
        },
    }
    path = tmp_path / "my_ender.def.json"
    path.write_text(json.dumps(definition, indent=4))
    result = check_profile(str(path), Options())
    assert [(f.code, f.message.split(":")[0]) for f in result.findings] == [
        ("SX002", "machine_start_gcode line 3 (G1 Z0.3 Z0.4 F300)")
    ]
    assert result.notes == [
        "placeholders with no value in the profile were filled with typical values: material_bed_temperature_layer_0=60"
    ]


def test_pf001_examples():
    rule = all_rules()["PF001"]
    assert any(f.code == "PF001" for f in _check_text(rule.example_bad))
    assert not any(f.code == "PF001" for f in _check_text(rule.example_good))


def _check_text(text: str) -> list:
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder, "p.ini")
        path.write_text("gcode_flavor = marlin2\n" + text + "\n")
        return check_profile(str(path), Options()).findings


def test_a_profile_is_never_given_a_noqa(tmp_path):
    profile = _write(tmp_path, "p.ini", "gcode_flavor = marlin2\nstart_gcode = G1 X1 X2 F600\n")
    proc = run_cli("check", "--add-noqa", profile.name, cwd=tmp_path)
    assert "no noqa added" in proc.stderr.decode()
    assert profile.read_text() == "gcode_flavor = marlin2\nstart_gcode = G1 X1 X2 F600\n"


def test_a_secret_in_a_profile(tmp_path):
    profile = _write(tmp_path, "p.ini", "gcode_flavor = marlin2\nprinthost_apikey = 0123456789abcdef0123456789abcdef\n")
    assert [f.code for f in check_profile(str(profile), Options()).findings] == ["SC006"]


@needs_corpus
def test_hyrel_profile():
    """Hyrel's own 30M/ESR profile: checked as Hyrel v4 (its M109 T12), and the tool change G-code's "M171 I1"
    (between an M721 and a T: M721 was meant) is an error at its place in the .ini."""
    proc = run_cli("check", str(HYREL_PROFILE))
    out = proc.stdout.decode()
    assert proc.returncode == 1, out
    assert re.search(r"\.ini:21:58: DL001 \[error\] toolchange_gcode line 4 \(M171 I1\): M171 is not a Hyrel code", out)
    assert "Checked as hyrel v4, printer 30m" in out
    # the messages name the setting's own lines, not the lines of the text gclint put together
    assert "(M229 E1 on start_gcode line 21)" in out
    assert "typical values: bed_temperature=60, layer_height=0.2, layer_num=1, temperature=215" in proc.stderr.decode()


vendor = pytest.mark.skipif(not VENDOR_PROFILES.is_dir(), reason="PrusaSlicer's vendor profiles are not installed")


@vendor
def test_a_vendor_bundle_bug_found_where_it_is_written():
    """Anycubic's Mega Zero start G-code writes "Z0.3[first_layer_height]": every job gets "Z0.30.2"."""
    result = check_profile(str(VENDOR_PROFILES / "Anycubic.ini"), Options())
    [bad] = [f for f in result.findings if f.code == "SX006"]
    line = (VENDOR_PROFILES / "Anycubic.ini").read_text().splitlines()[bad.line - 1]
    assert line[bad.column - 1 :].startswith("Z0.3[first_layer_height]")
    assert "Z value '0.30.2' is not a number" in bad.message and "'Anycubic Mega Zero'" in bad.message


@vendor
@pytest.mark.parametrize("name", ["Voron", "Jubilee", "TriLAB", "Creality"])
def test_vendor_bundles_without_findings(name):
    result = check_profile(str(VENDOR_PROFILES / f"{name}.ini"), Options())
    assert result.error is None and result.findings == [], [
        f"{f.line}:{f.column} {f.code} {f.message}" for f in result.findings
    ]


def test_a_secret_in_a_settings_g_code_is_one_finding_with_its_explanation(tmp_path):
    profile = tmp_path / "printer.ini"
    profile.write_text(
        "printer_technology = FFF\nprinter_model = MK3\ngcode_flavor = marlin2\n"
        "start_gcode = G28\\nM104 S200\\n; printhost_apikey = abc123def\\nG1 X1\nend_gcode = M84\n"
    )
    proc = run_cli("check", "--no-cache", "-f", "json", str(profile))
    found = [f for f in json.loads(proc.stdout) if f["code"] == "SC006"]
    assert len(found) == 1 and found[0]["message"].startswith("API key left in the profile"), found
    assert "abc123def" not in proc.stdout.decode()
