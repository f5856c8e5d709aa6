"""Issue 28: the print time's parts (gclint/timing): the planner against times worked out by hand, the limits a job
states (its slicer's settings, its own commands, in each firmware's units) and the slicer's own estimate."""

from __future__ import annotations

import math

import pytest

from gclint.dialects import get
from gclint.simulate import simulator_for
from gclint.simulate.events import Limits
from gclint.syntax.source import Source
from gclint.timing import MachineLimits, Planner, limits_for, slicer_estimate, slicer_settings
from gclint.timing.limits import MARLIN_DEFAULTS, from_settings, tool_change_times
from gclint.timing.planner import trapezoid_time


def _deviation(accel: float = 1000.0, **more) -> MachineLimits:
    return MachineLimits(accel_print=accel, accel_travel=accel, accel_retract=accel, junction_deviation=0.013, **more)


def test_a_move_from_rest_to_rest_accelerates_cruises_and_brakes() -> None:
    # 100 mm at 100 mm/s, 1000 mm/s²: 5 mm to reach 100 mm/s and 5 to stop (0.1 s each), 90 mm cruising (0.9 s)
    planner = Planner(_deviation())
    planner.move(100, 0, 0, 0, 6000)
    assert planner.finish() == pytest.approx(1.1)
    # a move too short to reach its feed: accelerate for half its length, brake for the other half
    planner = Planner(_deviation())
    planner.move(4, 0, 0, 0, 6000)
    assert planner.finish() == pytest.approx(2 * math.sqrt(1000 * 4) / 1000)
    assert trapezoid_time(4, 1000, 100, 0, 0) == pytest.approx(2 * math.sqrt(4000) / 1000)


def test_moves_in_line_run_through_their_junction() -> None:
    planner = Planner(_deviation())
    for _ in range(4):
        planner.move(25, 0, 0, 0, 6000)
    assert planner.finish() == pytest.approx(1.1)  # as one 100 mm move


def test_a_corner_slows_to_the_speed_classic_jerk_allows() -> None:
    # Marlin's classic jerk, 10 mm/s on X and Y: two 100 mm moves at 100 mm/s meeting at a right angle.  The safe
    # speed of each is 10 mm/s (X jumps from 100 to 0: the junction is 100 * 10/100), so each runs 10 -> 100 -> 10:
    # 2 * 0.09 s of speed change and 90.1 mm at 100 mm/s.
    limits = MachineLimits(accel_print=1000, accel_travel=1000, jerk_x=10, jerk_y=10, jerk_z=0.4, jerk_e=5)
    planner = Planner(limits)
    planner.move(100, 0, 0, 0, 6000)
    planner.move(0, 100, 0, 0, 6000)
    assert planner.finish() == pytest.approx(2 * (0.18 + 0.901))


def test_a_reversal_stops_and_the_junction_deviation_bounds_a_corner() -> None:
    back = Planner(_deviation())
    back.move(100, 0, 0, 0, 6000)
    back.move(-100, 0, 0, 0, 6000)
    assert back.finish() == pytest.approx(2.2)  # each from rest to rest
    corner = Planner(_deviation())
    corner.move(100, 0, 0, 0, 6000)
    corner.move(0, 100, 0, 0, 6000)
    # Marlin: v² = a * deviation * sin(θ/2) / (1 - sin(θ/2)), θ/2 = 45°
    half = math.sqrt(0.5)
    v = math.sqrt(1000 * 0.013 * half / (1 - half))
    assert corner.finish() == pytest.approx(2 * trapezoid_time(100, 1000, 100, 0, v))


def test_the_axes_cap_the_feed_and_the_acceleration() -> None:
    planner = Planner(_deviation(max_feed_x=50, max_accel_x=500))
    planner.move(100, 0, 0, 0, 6000)  # asks 100 mm/s on X, which may do 50 at 500 mm/s²
    assert planner.finish() == pytest.approx(trapezoid_time(100, 500, 50, 0, 0))
    # a move of the extruder alone: its filament's length, at the retraction acceleration, within E's speed
    retract = Planner(_deviation(max_feed_e=25))
    retract.move(0, 0, 0, -5, 2400)
    assert retract.finish() == pytest.approx(trapezoid_time(5, 1000, 25, 0, 0))


def test_without_an_acceleration_each_move_runs_at_its_feed_and_a_stop_adds_its_time() -> None:
    planner = Planner(MachineLimits())
    planner.move(100, 0, 0, 0, 6000)
    planner.stop(2.0)  # a dwell
    planner.move(0, 50, 0, 0, 3000)
    assert not planner.accelerated and planner.finish() == pytest.approx(4.0)


def test_without_a_junction_rule_each_move_starts_and_ends_at_rest() -> None:
    planner = Planner(MachineLimits(accel_print=1000, accel_travel=1000))
    assert planner.from_rest
    planner.move(50, 0, 0, 0, 6000)
    planner.move(50, 0, 0, 0, 6000)
    assert planner.finish() == pytest.approx(2 * trapezoid_time(50, 1000, 100, 0, 0))


def test_the_window_keeps_time_linear_and_the_result_that_of_planning_everything_at_once() -> None:
    from gclint.timing import planner as module

    moves = [((i % 7) - 3, (i % 5) - 2, 0.0, 0.01 * (i % 3), 1200 + 300 * (i % 4)) for i in range(3000)]

    def total(refresh: int, keep: int) -> float:
        saved = module.REFRESH, module.KEEP
        module.REFRESH, module.KEEP = refresh, keep
        try:
            planner = Planner(_deviation())
            for move in moves:
                planner.move(*move)
            return planner.finish()
        finally:
            module.REFRESH, module.KEEP = saved

    assert total(256, 64) == pytest.approx(total(10**9, 0), rel=1e-6)


def test_watch_gives_the_time_at_the_end_of_a_move() -> None:
    planner = Planner(_deviation())
    planner.move(100, 0, 0, 0, 6000)
    planner.watch("after the first")
    planner.move(100, 0, 0, 0, 6000)
    planner.finish()
    # (the first move no longer brakes: it runs into the second at full speed)
    assert planner.watched["after the first"] == pytest.approx(0.1 + 0.95)
    assert planner.time == pytest.approx(2.1)


# -- limits ---------------------------------------------------------------------------------------------------


def test_the_slicers_machine_limits() -> None:
    prusa = {
        "machine_max_acceleration_x": "4000,2500",  # normal mode, silent mode: the normal mode's
        "machine_max_feedrate_z": "12,12",
        "machine_max_jerk_x": "8,8",
        "machine_max_acceleration_extruding": "4000",
    }
    assert from_settings(prusa) == {
        "max_accel_x": 4000,
        "max_feed_z": 12,
        "jerk_x": 8,
        "accel_print": 4000,
        "accel_travel": 4000,
        "accel_retract": 4000,
    }
    assert from_settings({**prusa, "machine_limits_usage": "ignore"}) == {}
    assert from_settings({"machine_max_speed_x": "500,200"}) == {"max_feed_x": 500}  # OrcaSlicer, BambuStudio
    assert from_settings({"machine_acceleration": "500", "machine_max_jerk_xy": "10"}) == {  # Cura
        "accel_print": 500,
        "accel_travel": 500,
        "accel_retract": 500,
        "jerk_x": 10,
        "jerk_y": 10,
    }
    assert from_settings({"xy_accel_mm_per_s_per_s": "1500", "z_speed_mm_per_s": "3.5"}) == {  # KISSlicer
        "accel_print": 1500,
        "accel_travel": 1500,
        "accel_retract": 1500,
        "max_feed_z": 3.5,
    }


def test_curas_settings_are_read_from_its_setting_3_lines() -> None:
    tail = (
        ';SETTING_3 {"global_quality": "[general]\\\\nversion = 4\\\\n[values]\\\\nmachine_max_acc\n'
        ';SETTING_3 eleration_x = 50\\\\nspeed_print = 6\\\\n\\\\n"}\n'
    )
    settings = slicer_settings(None, tail)
    assert settings["machine_max_acceleration_x"] == "50" and settings["speed_print"] == "6"


def test_marlins_defaults_only_for_marlin_and_jerks_replace_its_junction_deviation() -> None:
    limits, firmware, stated = limits_for("marlin", None, {})
    assert firmware == "Marlin" and not stated
    assert (limits.accel_print, limits.max_feed_z, limits.junction_deviation) == (3000, 5, 0.013)
    assert limits_for("marlin", "klipper", {})[0] == MachineLimits() and limits_for("reprap", None, {})[1] == ""
    limits, _, stated = limits_for("marlin", None, {"machine_max_jerk_x": "8", "machine_max_jerk_y": "8"})
    assert limits.junction_deviation is None and limits.jerk_x == 8 and stated == {"jerk_x", "jerk_y"}
    assert MARLIN_DEFAULTS.junction_deviation == 0.013  # (the defaults themselves are not changed)


def test_tool_change_times_from_the_settings() -> None:
    assert tool_change_times({"filament_load_time": "10.5,12", "filament_unload_time": "8.5,8.5"}) == (
        [10.5, 12.0],
        [8.5, 8.5],
    )
    assert tool_change_times({"machine_load_filament_time": "29", "machine_unload_filament_time": "28"}) == (
        [29.0],
        [28.0],
    )
    assert tool_change_times({}) == ([], [])


def _limits(dialect: str, text: str) -> list[dict]:
    return [e.values for e in simulator_for(get(dialect)).events(Source.from_text(text)) if type(e) is Limits]


def test_the_reader_gives_the_limits_a_job_sets_in_mm_and_seconds() -> None:
    # Marlin: M203 in units/s, M204 S is printing and travel, M205 X Y jerk, J junction deviation, S T minimum feeds
    assert _limits("marlin", "M201 X1000 Y1000 Z200 E5000\nM203 X200 Z12\nM204 S800\nM204 P1000 R1250 T2000\n") == [
        {"max_accel_x": 1000, "max_accel_y": 1000, "max_accel_z": 200, "max_accel_e": 5000},
        {"max_feed_x": 200, "max_feed_z": 12},
        {"accel_print": 800, "accel_travel": 800},
        {"accel_print": 1000, "accel_retract": 1250, "accel_travel": 2000},
    ]
    assert _limits("marlin", "M205 X8 Y8 Z0.4 E4.5 J0.02 S0 T0\n") == [
        {
            "jerk_x": 8,
            "jerk_y": 8,
            "jerk_z": 0.4,
            "jerk_e": 4.5,
            "junction_deviation": 0.02,
            "min_feed_print": 0,
            "min_feed_travel": 0,
        }
    ]
    # in inches (G20), lengths are converted
    assert _limits("marlin", "G20\nM204 P10\n") == [{"accel_print": 254}]
    # Klipper's SET_VELOCITY_LIMIT (a Marlin-flavour job for a Klipper host)
    assert _limits("marlin", "SET_VELOCITY_LIMIT VELOCITY=300 ACCEL=5000 SQUARE_CORNER_VELOCITY=5\n") == [
        {"max_feed": 300, "accel_print": 5000, "accel_travel": 5000, "square_corner_velocity": 5}
    ]
    # RepRapFirmware: M203 and M566 in mm/min, M204 P and T
    assert _limits("reprap", "M203 X12000 Y12000\nM566 X600 Y600\nM204 P500 T2000\n") == [
        {"max_feed_x": 200, "max_feed_y": 200},
        {"jerk_x": 10, "jerk_y": 10},
        {"accel_print": 500, "accel_travel": 2000},
    ]


# -- the slicer's own estimate ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "seconds"),
    [
        ("; estimated printing time (normal mode) = 1h 2m 3s\n", 3723),
        ("; estimated printing time (normal mode) = 1d 0h 0m 5s\n", 86405),
        ("; model printing time: 1h 57m 37s; total estimated time: 2h 4m 35s\n", 7475),
        (";TIME:3485\n", 3485),
        (";PRINT.TIME:480\n", 480),
        (";Print Time: 811\n", 811),
        (";Print time: 37 minutes\n", 2220),
        (";Print time:     0:42\n", 2520),
        (";   Build time: 1 hour 50 minutes\n", 6600),
        ("; Estimated Build Time:   35.09 minutes\n", 35.09 * 60),
        ("G1 X1\n", None),
    ],
)
def test_the_slicers_own_estimate(text: str, seconds: float | None) -> None:
    found = slicer_estimate(text)
    assert (found[0] if found else None) == (pytest.approx(seconds) if seconds is not None else None)


def test_the_limit_names_are_the_models() -> None:
    from dataclasses import fields

    from gclint.simulate.events import LIMIT_NAMES

    assert {f.name for f in fields(MachineLimits)} == LIMIT_NAMES
