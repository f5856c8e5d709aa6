"""``gclint diff`` and issue 27: what a translation's output may lose that the diff did not see (a program end, an
unprime or prime, a spindle's state and direction, a speed with no maximum known, a layer height in native flow,
a wait), explanations that must cover what they explain, and the false alarms of Machinekit native flow and
velocity extrusion.  Each row: a source, the translator's own output with one line edited, the aspect the diff
must report unexplained."""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from gclint import dialects
from gclint.simulate import Explanations, Mapping, diff_sources
from gclint.simulate.translation import explanations_from
from gclint.syntax.source import Source
from gclint.translate.options import TranslateOptions

from .test_diff import translate_and_diff

PRINT = "M104 S200\nM109 S200\nM140 S60\nM190 S60\nG90\nM83\nG1 X1 Y1 Z0.2 E1 F600\nG1 X2 Y2 E1\nM104 S0\nM140 S0\n"
RETRACTS = (
    "M104 S200\nM109 S200\nG90\nM83\nG1 X1 Y1 Z0.2 E1 F600\nG1 E-0.8 F2400\nG0 X10 Y10\nG1 E0.8 F2400\n"
    "G1 X11 Y11 E1 F600\nG10\nG0 X20 Y20\nG11\nG1 X21 Y21 E1\nM104 S0\n"
)
CUT = "G21 G90\nG0 X0 Y0 Z1\nM3 S1000\nG1 Z-1 F100\nG1 X10\nS2000\nG1 X20\nM5\nG0 Z5\nM3 S1500\nG1 X30\nM5\nM2\n"
NATIVE = (
    ";HEIGHT:0.2\nM104 S200\nM109 S200\nG90\nM83\nG1 X0 Y0 Z0.2 F600\nG1 X10 E1\nG1 X10 Y10 E1\n;HEIGHT:0.15\n"
    "G1 Z0.35\nG1 X0 E1\nG1 Y0 E1\n;HEIGHT:0.15\nG1 Z0.5\nG1 X10 E1\nG1 Y10 E1\nM104 S0\n"
)


@dataclass(frozen=True)
class Edit:
    """The translation of ``source`` with ``old`` replaced by ``new`` must differ in ``aspect``, unexplained."""

    item: str
    dialect: str
    source: str
    old: str
    new: str
    aspect: str
    settings: dict = field(default_factory=dict)


EDITS = [
    Edit("a dropped M30", "marlin", PRINT, "M30\n", "", "end"),
    Edit("a dropped M109", "marlin", PRINT, "M109 T0 S200\n", "", "temp"),
    Edit("a dropped M190", "marlin", PRINT, "M190 T24 S60\n", "", "beds"),
    Edit("a dropped final M104 S0", "marlin", PRINT, "M104 T0 S0\n", "", "end"),
    Edit("a dropped unprime", "marlin", RETRACTS, "M721 T0 I1\n", "", "prime", {"retract": "explicit"}),
    Edit("a dropped prime", "marlin", RETRACTS, "M722 T0 I1\n", "", "prime", {"retract": "explicit"}),
    Edit(
        "an unprime where the source has none", "marlin", RETRACTS, "G0 X20 Y20\n", "M721 T0 I1\nG0 X20 Y20\n", "prime"
    ),
    Edit("a dropped M5", "machinekit", CUT, "M5 T0\nM30", "M30", "end", {"spindle_max_rpm": "10000"}),
    Edit("M3 -> M4", "machinekit", CUT, "M3 T0 S10", "M4 T0 S10", "spindle", {"spindle_max_rpm": "10000"}),
    # no spindle-max-rpm: the speeds are compared relatively (the first one sets the scale)
    Edit("a halved speed, no maximum", "machinekit", CUT, "M3 T0 S13.3", "M3 T0 S6.7", "spindle"),
    Edit("a dropped speed change, no maximum", "machinekit", CUT, "M3 T0 S13.3\n", "", "spindle"),
    Edit("a dropped M756", "marlin", NATIVE, "M756 S0.15\n", "", "layer", {"flow": "native"}),
    Edit("another layer height", "marlin", NATIVE, "M756 S0.15", "M756 S0.25", "layer", {"flow": "native"}),
    Edit("an M221 Z for the layer", "marlin", NATIVE, "M756 S0.15", "M221 T0 Z0.3", "layer", {"flow": "native"}),
]


def _translate(edit: Edit):
    text, result, diff = translate_and_diff(edit.dialect, edit.source, **edit.settings)
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    return text, result


@pytest.mark.parametrize("edit", EDITS, ids=[e.item for e in EDITS])
def test_the_edited_translation_differs_unexplained(edit: Edit) -> None:
    text, result = _translate(edit)
    assert edit.old in text, text
    edited = text.replace(edit.old, edit.new, 1)
    options = TranslateOptions()
    for key, value in edit.settings.items():
        options.set(key.replace("_", "-"), value)
    src, dst = dialects.get(edit.dialect), dialects.get("hyrel")
    # the findings alone (their window, their marks), and with the translator's own differences
    own = diff_sources(
        Source.from_text(edit.source, "s"), Source.from_text(text, "o"), src, dst, Mapping.from_options(options)
    )
    for reference in (None, own.differences):
        explanations = explanations_from(result)
        explanations.reference = reference
        diff = diff_sources(
            Source.from_text(edit.source, "source"),
            Source.from_text(edited, "output"),
            src,
            dst,
            Mapping.from_options(options),
            explanations,
        )
        assert edit.aspect in {d.aspect for d in diff.unexplained()}, [d.to_dict() for d in diff.differences]


# -- explanations that cover what they explain --------------------------------------------------------------

MACRO = "M104 S200\nM98 Pheat.g\nM109 S200\nM140 S60\nM190 S60\nG90\nM83\nG1 X1 Y1 Z0.2 E1 F600\nG1 X2 Y2 E1\n"


@pytest.mark.parametrize("dropped", ["M109 T0 S200\n", "M190 T24 S60\n"])
def test_a_macro_call_does_not_explain_a_later_dropped_wait(dropped: str) -> None:
    """M98 (a macro the translator cannot follow: TR005, any aspect) comes before the wait: the wait set the
    temperature again, so what the macro did cannot be why the output does not wait."""
    text, result, diff = translate_and_diff("reprap", MACRO)
    assert not diff.differences and "M98" not in text
    edited = diff_sources(
        Source.from_text(MACRO, "source"),
        Source.from_text(text.replace(dropped, ""), "output"),
        dialects.get("reprap"),
        dialects.get("hyrel"),
        Mapping(),
        explanations_from(result),
    )
    assert [(d.aspect, d.explained_by) for d in edited.differences] == [("temp" if "M109" in dropped else "beds", None)]


def test_a_finding_on_the_line_that_set_it_explains() -> None:
    """An M109 the translator could not carry (a finding on its own line) explains the wait that differs."""
    source = "M104 S200\nM109 S200\nG90\nM83\nG1 X1 Y1 Z0.2 E1 F600\n"
    output = "M104 T0 S200\nM229 E1 D1\nM83\nT0\nG1 X1 Y1 Z0.2 E1 F600\nM30\n"
    for lines, explained in (([2], ("TR003", 2)), ([1], None)):
        diff = diff_sources(
            Source.from_text(source, "source"),
            Source.from_text(output, "output"),
            dialects.get("marlin"),
            dialects.get("hyrel"),
            Mapping(),
            Explanations([("TR003", frozenset({"temp"}), lines)]),
        )
        assert [(d.aspect, d.explained_by) for d in diff.differences] == [("temp", explained)]


def test_an_edited_output_is_explained_only_where_the_translation_differs_too() -> None:
    """With the translator's own differences given, the same difference stays explained; another one (here a
    changed feed on a move) is not, even though a finding that names any aspect lies before it."""
    source = "M104 S200\nM109 S200\nG90\nM83\nG1 X1 Y1 Z0.2 E1 F600\nM98 Pmacro.g\nG1 X2 Y2 E1\nG1 X3 Y3 E1\n"
    text, result, own = translate_and_diff("reprap", source)
    assert not own.differences
    explanations = Explanations(explanations_from(result).entries, reference=own.differences)
    diff = diff_sources(
        Source.from_text(source, "source"),
        Source.from_text(text.replace("G1 X3 Y3 E1", "G1 X3 Y3 E1 F900"), "output"),
        dialects.get("reprap"),
        dialects.get("hyrel"),
        Mapping(),
        explanations,
    )
    assert [(d.aspect, d.explained_by) for d in diff.differences] == [("feed", None)]


def test_the_cli_explains_an_edited_output_by_the_translation(tmp_path) -> None:
    from .conftest import run_cli

    job = tmp_path / "job.gcode"
    job.write_text(MACRO)
    out = tmp_path / "job.hyrel.gcode"
    assert run_cli("translate", "--from", "reprap", "--to", "hyrel", str(job), "-o", str(out)).returncode == 0
    same = run_cli("diff", str(job), str(out), "--from", "reprap", "--to", "hyrel", "--fail-on", "unexplained")
    assert same.returncode == 0, same.stdout
    out.write_text(out.read_text().replace("M109 T0 S200\n", ""))
    edited = run_cli("diff", str(job), str(out), "--from", "reprap", "--to", "hyrel", "--fail-on", "unexplained")
    assert edited.returncode == 1 and b"temp:" in edited.stdout and b"[unexplained]" in edited.stdout


# -- no false alarm ------------------------------------------------------------------------------------------


def test_a_bare_m106_does_nothing_on_machinekit() -> None:
    """Machinekit's M106 remap needs P: a bare M106 sets no fan (the reader), whatever the translation writes."""
    from gclint.simulate import simulator_for

    sim = simulator_for(dialects.get("machinekit"))
    moves = list(sim.run(Source.from_text("G90\nM106\nG1 X1 Y1 Z0.2 A1 F600\n", "s")))
    assert moves and moves[0].look.fan == 0.0


@pytest.mark.parametrize(
    "source",
    [
        # velocity extrusion: M701/M702 bead, the moves outside G22 ... G23 print, those between travel
        "G90\nM104 P200\nM109 P200\nM701 P0.5\nM702 P0.2\nG1 X0 Y0 Z0.2 F600\nG1 X10\nG22\nG1 X20 Y5\nG23\n"
        "G1 X30\nG1 X40 Y10\nM2\n",
        # G22/G23 before any A move start velocity extrusion too
        "G90\nM104 P200\nM109 P200\nG22\nG0 X0 Y0 Z0.2\nG23\nG1 X10 Y0 F600\nG1 X20\nG22\nG0 X0 Y10\nG23\n"
        "G1 X10 Y10\nM2\n",
    ],
    ids=["M701-M702", "G22-G23"],
)
def test_velocity_extrusion_after_g23_prints_on_both_sides(source: str) -> None:
    _, _, diff = translate_and_diff("machinekit", source)
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]
    assert not [d for d in diff.differences if d.aspect == "e"], [d.to_dict() for d in diff.differences]


def test_machinekit_native_flow_with_travel_feed_moves() -> None:
    """Native flow on a CNC reading (every feed move is compared): travel feed moves between printing ones
    neither agree nor differ on the layer height, and E amounts becoming Hyrel's own flow is what was asked."""
    source = (
        "G90\nM104 P200\nM109 P200\nG0 X0 Y0 Z0.2\nG1 X10 Y0 A1 F600\nG1 X20 A2\nG1 X30 Y5\nG1 X20 Y10 A3\n"
        "G0 Z0.4\nG1 X10 Y10 A4\nG1 X0 Y0\nG1 X5 Y5 A5\nM2\n"
    )
    text, _, diff = translate_and_diff("machinekit", source, flow="native")
    assert "M756 S0.2" in text
    assert diff.differences == [], [d.to_dict() for d in diff.differences]


def test_reprap_tool_offsets_as_m6_are_explained() -> None:
    source = (
        "G10 P0 X10 Y5 Z0\nG10 P1 X-20 Y0 Z0.5\nM104 T0 S200\nM104 T1 S200\nM109 T0 S200\nM109 T1 S200\nG28\nG90\n"
        "M83\nT0\nG1 X10 Y10 Z0.2 F600\nG1 X20 Y10 E1\nT1\nG1 X30 Y10 E1\nG1 X40 E1\n"
    )
    _, _, diff = translate_and_diff("reprap", source, tool_offsets="m6")
    assert not diff.unexplained(), [d.to_dict() for d in diff.unexplained()]


def test_relative_spindle_speeds_agree_when_proportional() -> None:
    """No spindle-max-rpm: 1000, 2000 and 1500 rpm written as 6.7, 13.3 and 10 % of an assumed maximum."""
    text, _, diff = translate_and_diff("machinekit", CUT)
    assert "M3 T0 S6.7" in text and "M3 T0 S13.3" in text
    assert diff.differences == [], [d.to_dict() for d in diff.differences]


def test_a_wait_after_cooling_is_a_wait() -> None:
    """A nozzle waited to 250 °C, set to 140, then 220 and waited for: it may have cooled below 220, so the
    wait matters (the M109 S220 was seen as no wait at all)."""
    source = "M83\nM109 S250\nM104 S140\nM104 S220\nM109 S220\nG1 X1 Y1 Z0.2 E1 F600\n"
    text, _, diff = translate_and_diff("marlin", source)
    assert not diff.differences
    edited = diff_sources(
        Source.from_text(source, "source"),
        Source.from_text(text.replace("M109 T0 S220\n", ""), "output"),
        dialects.get("marlin"),
        dialects.get("hyrel"),
        Mapping(),
    )
    assert [d.aspect for d in edited.differences] == ["temp"]
