"""HY rules for lasers, UV pens, spindles and lathes (M620-M623, M3/M4/M5, M253-M255, M30).

Sources: the Hyrel Gcode page ("Controlling Lasers and UV Pens", "Controlling Spindles and Lathes", "M30
End of Program"), see docs/sources.md.  ``MachineState.emitters_enabled`` and ``spindles`` say which devices are on.
"""

from __future__ import annotations

from gclint.dialects.addressing import LASER, V5_TO_V4_VARIABLE, resolve_v4_variable, resolve_v5
from gclint.dialects.base import Param
from gclint.rules.base import Rule, Severity, register
from gclint.rules.dialect import ParamTableRule
from gclint.syntax.nodes import Command, Line


class _DeviceRule(Rule):
    """Names devices (kept as v5 addresses in the state) the way the file writes them."""

    families = ("hyrel",)

    def number(self, v5: int) -> int:
        """The T number the file uses for the device at v5 address ``v5``."""
        if self.ctx.dialect.extras.get("firmware") == 4:
            return V5_TO_V4_VARIABLE.get(v5, v5)
        return v5

    def label(self, v5: int) -> str:
        if v5 < 0:
            return "the focused head"
        if self.ctx.dialect.extras.get("firmware") == 4 and v5 in V5_TO_V4_VARIABLE:
            return resolve_v4_variable(V5_TO_V4_VARIABLE[v5]).label
        return resolve_v5(v5).label

    def t_word(self, v5: int) -> str:
        return " T#" if v5 < 0 else f" T{self.number(v5)}"


@register
class EmitterNeedsTarget(ParamTableRule):
    code = "HY020"
    name = "emitter-needs-target"
    severity = Severity.ERROR
    summary = "M620 without T: the laser/UV pen to enable must be named"
    explanation = """
        M620 enables (E1) or disables (E0) a laser or UV pen.  Its T is the "target head - MUST be
        specified, can NOT be inherited": unlike most codes, M620 does not fall back to the focused head.
        Without T nothing is enabled (and the firmware reports a missing T argument).
    """
    example_bad = "M620 E1"
    example_good = "M620 T21 E1"
    source = "Gcode page, M620 Enable Device"
    families = ("hyrel",)

    def missing_message(self, cmd: Command, p: Param) -> str:
        return "M620 needs T: the target device MUST be specified, it can NOT be inherited from the focused head"


@register
class EmitDurationTooLong(_DeviceRule):
    code = "HY021"
    name = "emit-duration-too-long"
    severity = Severity.ERROR
    summary = "M623 D over 60,000 ms (any device) or over 1,000 ms (lasers and other non-UV devices)"
    explanation = """
        M623 emits for D milliseconds: "Dn max for UV pens is 60,000 (1 minute); Dn max for other devices
        1,000 (1 second)".  Above 60,000 is an error for every device.  Between 1,000 and 60,000 only a UV
        pen may run: gclint knows the CO2 laser (T21) is not one, so with the laser enabled that is an
        error; other devices are heads whose type a G-code file does not say (a UV pen or a diode laser),
        so it is a warning to check that the enabled device is a UV pen.
    """
    example_bad = """
        M620 T21 E1
        M623 P80 D5000
    """
    example_good = """
        M620 T21 E1
        M623 P80 D500
    """
    source = "Gcode page, M623 Duration Emit"
    codes = ("M623",)

    UV_MAX = 60000.0
    OTHER_MAX = 1000.0

    def check(self, line: Line, cmd: Command) -> None:
        d = cmd.get("D")
        if d is None or d <= self.OTHER_MAX:
            return
        node = cmd.param("D") or cmd
        text = cmd.raw("D")
        if d > self.UV_MAX:
            self.report(line, f"M623 D{text} ms is over 60,000 ms (1 minute), the most even a UV pen allows", node=node)
            return
        enabled = self.state.emitters_enabled
        lasers = [dev for dev in enabled if resolve_v5(dev).kind == LASER]
        if enabled and len(lasers) == len(enabled):
            message = (
                f"M623 D{text} ms is over 1,000 ms (1 second), the most for {self.label(lasers[0])}; "
                "only UV pens may emit up to 60,000 ms"
            )
            self.report(line, message, node=node)
        else:
            message = (
                f"M623 D{text} ms is over 1,000 ms (1 second): allowed only if the enabled device is a UV pen "
                "(up to 60,000 ms); lasers and other devices stop at 1,000 ms"
            )
            self.report(line, message, node=node, severity=Severity.WARNING)


@register
class SpindlePowerOver100(ParamTableRule):
    code = "HY023"
    name = "spindle-power-over-100"
    severity = Severity.WARNING
    summary = "M3/M4 S is percent power (0-100); a larger value looks like RPM"
    explanation = """
        Hyrel's M3 activates the spindle "using the value set on the head for RPM", and its S is
        "Sn - power (0-100%)" (M4: "All options are identical").  CNC programs (LinuxCNC, Carvera,
        Marlin with a spindle) write `M3 S12000` in RPM: a value outside the page's 0-100, and the pages
        do not say what Repetrel does with it.  Write the power as a percentage (0-100).
    """
    example_bad = "M3 T20 S12000"
    example_good = "M3 T20 S75"
    source = (
        "Gcode page, M3 Turn On Spindle (CW); Hyrel firmware source, src/MCode.c M_Code_M3 (S goes to the "
        "spindle PWM as it is)"
    )
    families = ("hyrel",)

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return rpm_message(cmd, problem) or f"{cmd.code}: {problem} (S is percent power, 0-100)"


def rpm_message(cmd: Command, problem: str = "above 100") -> str | None:
    """HY023's message for an M3/M4 whose S is above 100 (an rpm; explain says the same), or None."""
    value = cmd.get("S")
    if value is None or value <= 100:
        return None
    return (
        f"{cmd.code} S{cmd.raw('S')}: S is 'power (0-100%)' on Hyrel, not RPM ({problem}); the pages do not "
        "say what a value above 100 does"
    )


@register
class SpindleDirectionChange(_DeviceRule):
    code = "HY024"
    name = "spindle-direction-change"
    severity = Severity.ERROR
    summary = "M3 to M4 (or M4 to M3) on a running spindle without M5 or S0 between"
    explanation = """
        "Note: DO NOT CHANGE DIRECTION while the spindle is in motion."  Reversing a turning spindle with
        M4 after M3 (or M3 after M4) strains the motor and the tool.  Stop it first with `M5 T#` (or
        `M3 S0`, "the same as turning it off"), wait for it to stop, then start it the other way.
        Spindles on different heads are tracked separately.
    """
    example_bad = """
        M3 T20 S75
        M4 T20 S75
    """
    example_good = """
        M3 T20 S75
        M5 T20
        G4 S2
        M4 T20 S75
    """
    source = "Gcode page, M3 Turn On Spindle (CW)"
    codes = ("M3", "M4")

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.get("S") == 0:
            return  # S0 turns it off
        device = self.ctx.interpreter.target(cmd)
        if device is None:
            device = -1
        running = self.state.spindles.get(device)
        direction = "cw" if cmd.code == "M3" else "ccw"
        if running is None or running[0] == direction:
            return
        started_by = "M3" if running[0] == "cw" else "M4"
        t = self.t_word(device)
        self.report(
            line,
            f"{cmd.code} reverses the spindle on {self.label(device)} while it still turns ({started_by} on line "
            f"{running[1]}): stop it with M5{t} (or S0) before changing direction",
            node=cmd,
        )


@register
class EmitterOnAtEnd(_DeviceRule):
    code = "HY028"
    name = "emitter-on-at-end"
    severity = Severity.WARNING
    summary = "A laser or UV pen still enabled, or a spindle still turning, at M30 or the end of the file"
    explanation = """
        The laser and UV pen examples end with "M620 T# E0 ; disable target device <= should be before
        M30 command": M30 ends the job but does not say the device was switched off.  Likewise "the
        spindle tool is turned on with an M3 or M4 before this command, and turned off with an M5 after all
        work is done".  Reported at M30, or at the line that switched the device on when the file ends
        without M30.
    """
    example_bad = """
        M620 T21 E1
        M621 P40
        G1 X10 Y10 E1 F600
        M30
    """
    example_good = """
        M620 T21 E1
        M621 P40
        G1 X10 Y10 E1 F600
        M620 T21 E0
        M30
    """
    source = "Gcode page, Laser Examples / UV Pen Examples and G81 Peck Drilling"
    codes = ("M30",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.reported: set[tuple[str, int, int]] = set()  # (kind, device, line switched on)

    def check(self, line: Line, cmd: Command) -> None:
        self._left_on(line, "at M30")

    def finish(self) -> None:
        self._left_on(None, "at the end of the file")

    def _left_on(self, at: Line | None, when: str) -> None:
        st = self.state
        for device, on_line in sorted(st.emitters_enabled.items()):
            key = ("emitter", device, on_line)
            if key in self.reported:
                continue
            self.reported.add(key)
            t = self.t_word(device)
            self.report(
                at if at is not None else on_line,
                f"{self.label(device)} is still enabled {when} (M620{t} E1 on line {on_line}): "
                f"add M620{t} E0 before M30",
            )
        for device, (direction, on_line) in sorted(st.spindles.items()):
            key = ("spindle", device, on_line)
            if key in self.reported:
                continue
            self.reported.add(key)
            started_by = "M3" if direction == "cw" else "M4"
            t = self.t_word(device)
            self.report(
                at if at is not None else on_line,
                f"the spindle on {self.label(device)} is still turning {when} ({started_by} on line {on_line}): "
                f"add M5{t} before M30",
            )


@register
class LaserPowerBeforeEnable(_DeviceRule):
    code = "HY040"
    name = "laser-power-before-enable"
    severity = Severity.WARNING
    summary = "M621/M623 with no laser or UV pen enabled by M620 T# E1"
    explanation = """
        M621 takes no T: "No tool is specified; this will happen on the laser already enabled with M620."
        M623 likewise emits on the enabled laser or UV pen.  Before any `M620 T# E1` (or after the device
        was disabled) there is no device for the power to go to.
    """
    example_bad = """
        M621 P40
        M620 T21 E1
    """
    example_good = """
        M620 T21 E1
        M621 P40
    """
    source = "Gcode page, M621 Set Laser Power and M623 Duration Emit"
    codes = ("M621", "M623")

    def check(self, line: Line, cmd: Command) -> None:
        st = self.state
        if st.emitters_enabled:
            return
        if st.laser_enabled_any:
            why = "every device enabled with M620 E1 has been disabled again"
        else:
            why = "no laser or UV pen has been enabled yet"
        self.report(line, f"{cmd.code} sets the power of the device enabled with M620 T# E1, but {why}", node=cmd)


@register
class LatheOnNon16A(Rule):
    code = "HY041"
    name = "lathe-on-non-16a"
    severity = Severity.ERROR
    summary = "M253/M254 turn on a lathe on a printer other than the Hydra 16A"
    explanation = """
        "M253 tells the printer to activate (start) the lathe motor in the clockwise direction (if it
        has one), using the value set with M92 for RPM.  Only available on Hydra 16A models."  M254 is
        the same counter-clockwise ("All options are identical, with the exception of direction").  On
        another model there is no lathe to turn, and the work the job expects it to do is not done.
        Choose the printer with `--printer 16a` (or `16a-dual`) when the job is for a 16A; the message
        names the model gclint checked for (the 30m unless told).

        Turning the lathe off is not reported: "M255 tells the printer to deactivate (stop) the lathe
        motor (if it has one)", and the M255 section has no 16A-only note, so an M255 (like a
        `M253 S0`, since "S0 is the same as turning it off") on a printer without a lathe stops nothing
        and harms nothing (end-of-job code shared between printers often has one).
    """
    example_bad = "; gclint-test: printer=30m dialect=hyrel\nM253 S75"
    example_good = "; gclint-test: printer=30m dialect=hyrel\nM255"
    source = "Gcode page, M253 Turn On Lathe (CW), M254 Turn On Lathe (CCW), M255 Turn Off Lathe"
    codes = ("M253", "M254")
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        profile = self.ctx.profile
        if not self.ctx.on_every_model(lambda p: not p.lathe):
            return
        s = cmd.get("S")
        if s is not None and s == 0:
            return  # "S0 is the same as turning it off": nothing to turn off on this model
        self.report(
            line,
            f"{cmd.code} turns on the lathe, which is 'Only available on Hydra 16A models'; "
            f"gclint checked for {profile.a} ({profile.title}){self.ctx.model_note()}",
            node=cmd,
        )
