"""Laser, UV pen and spindle rules (HY020, HY021, HY023, HY024, HY028, HY040, HY041): device tracking."""

from __future__ import annotations

from gclint.engine import check_text


def found(text: str, code: str, **options):
    options.setdefault("dialect", "hyrel")
    return [f for f in check_text(text, **options) if f.code == code]


def lines(text: str, code: str, **options) -> list[int]:
    return [f.line for f in found(text, code, **options)]


# -- HY024: spindle direction, per head -------------------------------------------------------------------


def test_direction_change_on_the_same_head():
    assert lines("M3 T20 S75\nM4 T20 S75\n", "HY024") == [2]
    assert lines("M4 T2 S75\nM3 T2 S75\n", "HY024") == [2]


def test_stop_between_clears_it():
    assert lines("M3 T20 S75\nM5 T20\nM4 T20 S75\n", "HY024") == []
    assert lines("M3 T20 S75\nM3 T20 S0\nM4 T20 S75\n", "HY024") == []
    assert lines("M3 T20 S75\nM4 T20 S0\nM4 T20 S75\n", "HY024") == []  # M4 S0 is off too


def test_heads_are_tracked_separately():
    text = "M3 T1 S50\nM4 T2 S50\nM5 T1\nM4 T1 S50\nM3 T2 S50\n"
    assert lines(text, "HY024") == [5]


def test_stopping_another_head_does_not_stop_this_one():
    assert lines("M3 T1 S50\nM5 T2\nM4 T1 S50\n", "HY024") == [3]


def test_focused_head_without_t():
    # M3 without T acts on the focused head; T focuses it
    assert lines("T1\nM3 S50\nM4 T1 S50\n", "HY024") == [3]
    assert lines("T1\nM3 S50\nT2\nM4 S50\n", "HY024") == []
    # M5 without T stops the focused head's spindle
    assert lines("T1\nM3 S50\nM5\nM4 S50\n", "HY024") == []


def test_same_direction_is_not_a_change():
    assert lines("M3 T20 S20\nM3 T20 S80\n", "HY024") == []


def test_v4_addresses():
    # v4: T26 is the spindle (v5 T20), T11 is head T0
    assert lines("M3 T26 S50\nM4 T26 S50\n", "HY024", dialect="hyrel-v4") == [2]
    assert lines("M3 T11 S50\nM4 T12 S50\n", "HY024", dialect="hyrel-v4") == []
    message = found("M3 T26 S50\nM4 T26 S50\n", "HY024", dialect="hyrel-v4")[0].message
    assert "M5 T26" in message


# -- HY028: state at M30 and at the end of the file -------------------------------------------------------


def test_laser_on_at_m30():
    assert lines("M620 T21 E1\nG1 X1 E1 F600\nM30\n", "HY028") == [3]
    assert lines("M620 T21 E1\nM620 T21 E0\nM30\n", "HY028") == []


def test_group_disable_switches_off_every_emitter():
    assert lines("M620 T21 E1\nM620 T2 E1\nM620 T40 E0\nM30\n", "HY028") == []


def test_each_device_reported():
    result = found("M620 T21 E1\nM620 T3 E1\nM3 T20 S50\nM30\n", "HY028")
    assert len(result) == 3
    assert all(f.line == 4 for f in result)


def test_end_of_file_without_m30_reports_at_the_enabling_line():
    assert lines("M620 T21 E1\nG1 X1 E1 F600\n", "HY028") == [1]
    assert lines("G0 X0\nM3 T20 S50\nG1 X1 F600\n", "HY028") == [2]


def test_reported_once_across_m30_and_end_of_file():
    assert lines("M620 T21 E1\nM30\n", "HY028") == [2]


def test_spindle_stopped_is_fine():
    assert lines("M3 T20 S50\nM5 T20\nM30\n", "HY028") == []
    assert lines("M4 T20 S50\nM4 T20 S0\nM30\n", "HY028") == []


def test_v4_laser_named_as_written():
    result = found("M620 T41 E1\nM30\n", "HY028", dialect="hyrel-v4")
    assert len(result) == 1 and "M620 T41 E0" in result[0].message


# -- HY040, HY021, HY020, HY023, HY041 --------------------------------------------------------------------


def test_power_before_enable():
    assert lines("M621 P40\nM620 T21 E1\nM621 P40\nM620 T21 E0\nM621 P40\n", "HY040") == [1, 5]


def test_emit_duration():
    def severities(text):
        return [f.severity.label for f in found(text, "HY021")]

    assert severities("M620 T21 E1\nM623 P50 D1000\n") == []
    assert severities("M620 T21 E1\nM623 P50 D1001\n") == ["error"]  # the CO2 laser is not a UV pen
    assert severities("M620 T2 E1\nM623 P50 D30000\n") == ["warning"]  # a head: may be a UV pen
    assert severities("M623 P50 D30000\n") == ["warning"]  # nothing enabled: unknown device
    assert severities("M620 T2 E1\nM623 P50 D60001\n") == ["error"]


def test_m620_needs_t():
    assert lines("T21\nM620 E1\n", "HY020") == [2]
    assert lines("M620 T21 E1\n", "HY020") == []


def test_spindle_power_percent():
    assert lines("M3 T20 S12000\n", "HY023") == [1]
    assert "RPM" in found("M3 T20 S12000\n", "HY023")[0].message
    assert lines("M4 T20 S100\n", "HY023") == []


def test_lathe_only_on_16a():
    # "Only available on Hydra 16A models" (M253, and M254: "All options are identical"); M255 stops the
    # lathe "(if it has one)": harmless without one, as is M253 S0 ("S0 is the same as turning it off")
    text = "M253 S75\nM255\nM254 S20\nM253 S0\nM254\n"
    for printer in ("30m", "esr", "ehr"):
        assert lines(text, "HY041", printer=printer) == [1, 3, 5]
    for printer in ("16a", "16a-dual"):
        assert lines(text, "HY041", printer=printer) == []
    message = found("M253 S75\n", "HY041", printer="esr")[0].message
    assert "esr" in message and "Only available on Hydra 16A models" in message
