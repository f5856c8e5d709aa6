"""The machine-state interpreter: the same code, the dialect's meaning."""

from __future__ import annotations

import gc
import weakref

from gclint import dialects
from gclint.machine.interpreter import Interpreter
from gclint.machine.state import EVALUES, NATIVE
from gclint.syntax.nodes import Line
from gclint.syntax.parse import parse_line


def run(text: str, dialect: str = "hyrel") -> Interpreter:
    interp = Interpreter(dialects.get(dialect))
    for n, raw in enumerate(text.strip("\n").splitlines(), 1):
        line = Line(n, raw, "\n", parse_line(raw))
        interp.state.line_number = n
        for cmd in line.commands:
            interp.apply(cmd, line)
    return interp


def test_units_and_positioning():
    st = run("G20\nG91\n").state
    assert st.units == "inch" and not st.absolute
    st = run("G20\nG21\nG91\nG90\n").state
    assert st.units == "mm" and st.absolute


def test_position_absolute_and_relative():
    st = run("G1 X10 Y20\nG91\nG1 X1 Y-2\n").state
    assert st.position.get("X") == 11 and st.position.get("Y") == 18
    st = run("G92 X5\nG0 Z3\n").state
    assert st.position.get("X") == 5 and st.position.get("Z") == 3


def test_e_mode_marlin_couples_to_g90_g91_hyrel_does_not():
    # Marlin: "G90/G91 reset E mode"; Hyrel and RRF: independent (Marlin G-code reference and Duet G-code dictionary, G90)
    assert run("M83\nG90\n", "marlin").state.e_absolute is True
    assert run("M82\nG91\n", "marlin").state.e_absolute is False
    assert run("M83\nG90\n", "hyrel").state.e_absolute is False
    assert run("M83\nG90\n", "reprap").state.e_absolute is False


def test_flow_mode_and_m30_reset():
    st = run("M229 E1 D1\n").state
    assert st.flow_mode == EVALUES and st.e_values()
    st = run("M229 E1 D1\nM106 C255\nM660 H2 Z28.2\nM702 T0 S30\nM30\n").state
    assert st.flow_mode == NATIVE and st.fan_range == 100 and not st.tool_height_offsets
    assert not st.squads and st.after_m30 and st.m30_line == 5 and st.tool == 0


def test_m30_on_marlin_is_not_end_of_job():
    assert run("M30 file.gco\n", "marlin").state.after_m30 is False
    assert run("M2\n", "machinekit").state.after_m30 is True


def test_tool_focus_v5_and_v4():
    assert run("T3\n").state.tool == 3
    st = run("M6 T12 O2 X1 Y2\nT1\n", "hyrel-v4").state
    assert st.tool == 1 and st.declared_heads == {1: 1}  # v4 T12 = yoke 1 position 2 = v5 T1
    assert run("M6 T1 O2\n").state.declared_heads == {1: 1}


def test_fan_range_and_height_offsets():
    st = run("M106 C255\nM660 H2 Z28.2\nG1 X1 Y1 H2\n").state
    assert st.fan_range == 255 and st.tool_height_offsets == {2: 28.2}
    assert st.applied_height_register == 2 and st.applied_height_line == 3


def test_g28_on_hyrel_homes_listed_axes_and_clears_offsets():
    st = run("G92 X5\nM660 H1 Z2\nG1 X1 H1\nG54 X3\nG28 X0 Y0\n").state
    assert st.homed_axes == {"X", "Y"} and st.applied_height_register is None
    assert not st.g92_offsets_active and not st.fixture_offsets_active
    assert run("G28 Z0\n").state.z_homed_line == 1
    assert run("G28\n").state.homed_axes == set()  # bare G28 homes nothing on Hyrel
    assert run("G28\n", "marlin").state.homed_axes == {"X", "Y", "Z"}


def test_motors_off_until_homed():
    st = run("M18\n").state
    assert st.motors_off_line == 1
    # "All axes with homes must be rehomed after an M18" (M18): X and Y have homes ("G28 Send X, Y to Physical
    # Home"); Z only where the job homes it (the pages do not say which models have a Z home)
    assert run("M84\nG28 X0 Y0\n").state.motors_off_line is None
    assert run("G28 Z0\nM84\nG28 X0 Y0\n").state.motors_off_line == 2
    assert run("G28 Z0\nM84\nG28 X0 Y0\n").state.axes_to_rehome == {"Z"}
    assert run("G28 Z0\nM84\nG28 X0 Y0\nG28 Z0\n").state.motors_off_line is None


def test_squads_lasers_spindles():
    st = run("M702 T0 S30\nM703 T1 S30\nM703 T2 S30\nM704 T1 S30\n").state
    assert st.squads == {30: {2}}
    st = run("M620 T21 E1\n").state
    assert st.emitters_enabled == {21: 1} and st.laser_enabled_any
    assert run("M620 T21 E1\nM620 T21 E0\n").state.emitters_enabled == {}
    assert run("M620 T21 E1\nM620 T47 E0\n").state.emitters_enabled == {}  # group T47 switches all off
    st = run("M3 T20 S50\n").state
    assert st.spindles[20][0] == "cw"
    assert 20 not in run("M3 T20 S50\nM3 T20 S0\n").state.spindles  # S0 is off
    assert 20 not in run("M4 T20 S50\nM5 T20\n").state.spindles


def test_temperatures_and_w0():
    st = run("M109 T0 S240 W0\nM190 S60\n").state
    assert st.targets[0] == 240 and st.targets[24] == 60 and st.pending_w0 == {0: 1}
    assert run("M109 T0 S240 W0\nM116\n").state.pending_w0 == {}


def test_printing_moves():
    # Hyrel native flow: any E marks a printing move (G1 section)
    st = run("G0 X1\nG1 X2 E1\n").state
    assert st.moved and st.printed and st.first_print_line == 2
    st = run("M83\nG1 X2 E-1\n", "marlin").state
    assert not st.printed  # a retraction does not print
    st = run("G1 X1 F1200\n").state
    assert st.working_feed_set and st.feed == 1200
    st = run("G0 X1 F9000\n").state  # Hyrel: G0 F is one-shot
    assert not st.working_feed_set and st.feed is None


def test_implicit_motion_uses_modal_mode():
    st = run("G1 X1\nX5 Y6\n", "machinekit").state
    assert st.position.get("X") == 5 and st.position.get("Y") == 6


def test_every_dialect_moves_plainly_and_holds_no_cycle():
    # runs of moves and arcs are applied by plain_run only where G0-G3 are the plain motion handlers; and
    # the handler table holds functions, not bound methods, so an interpreter is freed with its file
    for name in dialects.names():
        interp = Interpreter(dialects.get(name))
        assert [interp.moves_plainly(code) for code in ("G0", "G1", "G2", "G3", "G28")] == [True] * 4 + [False]
        line = Line(1, "G1 X5", "\n", parse_line("G1 X5"))
        interp.handler_for(line.commands[0])(line.commands[0], line)
        assert interp.state.position.snapshot()["X"] == 5.0
        gc.disable()
        try:
            freed = weakref.ref(interp)
            del interp
            assert freed() is None, name
        finally:
            gc.enable()
