"""RepRapFirmware 3 (Duet) -> Hyrel v5 (docs/translation.md, Marlin and RepRapFirmware -> Hyrel): Marlin's translation
plus tool temperatures and offsets in G10, M568, M116, fan values 0-1, M2 as the end of program, and meta commands,
{expressions} and macro files (sys/<code>.g for a code the firmware does not know), which cannot be translated.
"""

from __future__ import annotations

from typing import ClassVar

from gclint.syntax.nodes import Command
from gclint.translate.findings import TR_APPROX, TR_DROPPED, TR_LOST, TR_NOTE, TR_UNTRANSLATABLE
from gclint.translate.findings import codes as _codes
from gclint.translate.marlin import MarlinToHyrel
from gclint.translate.output import fmt
from gclint.translate.words import num


class RepRapToHyrel(MarlinToHyrel):
    """RepRapFirmware 3 (Duet) -> Hyrel v5: like Marlin, plus tool temperatures and offsets in G10, fan values
    0-1, meta commands and macros (untranslatable), M116."""

    TEXT_PAUSE = None  # RepRapFirmware's M0/M1 stop and take no message (Duet G-code dictionary, M0/M1): not guessed
    HANDLERS: ClassVar[dict[str, str]] = {
        "M451": "printer_mode",
        "M452": "printer_mode",
        "M453": "printer_mode",
        "M116": "m116",
        "M568": "m568",
        "M98": "macro",
        "M99": "macro_return",
        "M291": "message_box",
        "M226": "rrf_m226",
        "M0": "rrf_stop",
        "M1": "rrf_stop",
        "M2": "end_program",
        "M563": "m563",
        "M107": "m107",
    }
    DROPPED: ClassVar[dict[str, tuple[str, str]]] = {
        **MarlinToHyrel.DROPPED,
        **_codes(
            "M550 M551 M552 M553 M554 M555 M556 M557 M558 M559 M560 M561 M562 M564 M570 M571 M573 M574 "
            "M575 M576 M577 M578 M579 M580 M581 M582 M584 M585 M586 M587 M588 M589 M594 M595 M596 M597 M598 "
            "M599 M650 M651 M667 M669 M671 M673 M674 M675 M905 M918 M929 M950 M951 M952 M953 M954 M955 M956 "
            "M957 M998 M409 M409.1 M408 M36 M36.1 M37 M38 M39 M101 M102 M103 M144 M470 M471 M472 M500.1 "
            "M569.1 M569.2 M569.3 M569.4 M569.5 M569.6 M569.7 M569.8 M569.9 M586.4 M292 M450 "
            "M201.1 M260.1 M260.2 M261.1 M261.2 M374 M375 M376 M505 M86",
            TR_DROPPED,
            "RepRapFirmware configuration or report (Repetrel configures the Hyrel machine)",
        ),
        **_codes("G22 G23", TR_LOST, "RepRapFirmware G22/G23 (tool change support) has no Hyrel counterpart"),
        **_codes("G68 G69", TR_UNTRANSLATABLE, "coordinate rotation changes the toolpath"),
        **_codes("G93", TR_UNTRANSLATABLE, "inverse-time feed (every F would need converting per move)"),
        **_codes("G94", TR_DROPPED, "units-per-minute feed mode (Hyrel's only mode)"),
    }
    FAN_MAX = 255.0
    RRF = True
    E_MODE_FOLLOWS_POSITIONING = None  # RepRapFirmware: G90/G91 leave the E mode alone
    CHECK_EXPRESSIONS = True
    END_CODES = frozenset({"M2"})
    MOVE_OVERRIDE_IGNORES_PLAIN = True  # move() below adds cases for H, S and R words only
    G53_ALONE = "drop"  # "Non-modal, rest of line only": alone it does nothing

    def __init__(self, source, target, options=None) -> None:
        super().__init__(source, target, options)
        self.tool_fans: dict[int, tuple[int, ...]] = {}  # M563 P<tool> F<fans>: a tool's own fans

    def move(self, cmd: Command) -> None:
        params = cmd.params
        homing = "H" in params and num(params.get("H")) not in (None, 0)
        if homing or (not self.laser and cmd.code == "G1" and num(params.get("S")) in (1, 2)):
            self.untranslatable(
                cmd,
                "homing or endstop-sensing move (G1 H/S) is machine-specific; Hyrel's G1 H "
                "applies a tool-height register",
                key="G1-H",
            )
            return
        if "R" in params and num(params.get("R")) not in (None, 0):
            self.untranslatable(
                cmd, "move to a saved restore point (G0/G1 R) depends on the firmware's memory", key="G1-R"
            )
            return
        super().move(cmd)

    def printer_mode(self, cmd: Command) -> None:
        """M451 FFF, M452 laser, M453 CNC printer mode (Duet G-code dictionary, M451-M453): in laser
        mode M3/M4 S and the S on moves are the laser power."""
        if cmd.code == "M452":
            self.enter_laser(cmd, "M452")
            self.consume(cmd)
        elif self.laser:
            self.leave_laser(cmd)
        else:
            self.remove(cmd, TR_DROPPED, "printer mode (FFF or CNC)", key="M45x")

    def fallback(self, cmd: Command) -> None:
        code = cmd.code
        if (
            cmd.kind == "gcode"
            and code
            and code[0] in "GM"
            and code not in self.DROPPED
            and code not in self.source.codes
        ):
            # RepRapFirmware runs the macro file sys/<code>.g for a code it does not know
            self.untranslatable(
                cmd, "RepRapFirmware runs a macro file for this code; its content is unknown here", key=code
            )
            return
        super().fallback(cmd)

    def _fan_value(self, cmd: Command) -> float | None:
        s = num(cmd.params.get("S"))
        if s is not None and s <= 1.0:
            return s * 255  # RepRapFirmware: S 0.0-1.0 is a fraction, above 1 a 0-255 value
        return s

    def m106(self, cmd: Command) -> None:
        params = cmd.params
        if "S" not in params and any(letter in params for letter in "CLXBHTRAF"):
            self.remove(
                cmd,
                TR_DROPPED,
                "fan configuration (RepRapFirmware M106 with configuration parameters)",
                key="M106-config",
            )
            return
        owner = self._fan_owner(cmd)
        if owner is not None:
            # a tool's own fan is its head's fan on Hyrel (fans are per head): it does not follow the tool
            self.fan(cmd, self.head(owner), self._fan_value(cmd), index=None, own=True)
            return
        super().m106(cmd)

    def m107(self, cmd: Command) -> None:
        owner = self._fan_owner(cmd)
        if owner is not None:
            self.fan_off(cmd, self.head(owner), index=None, own=True)
            return
        super().m107(cmd)

    def _fan_owner(self, cmd: Command) -> int | None:
        """The tool whose own fan (M563 F) this M106/M107 drives: P names the fan, else "S alone -> fans of
        current tool" (Duet G-code dictionary, M106); None for the part fan (fan 0 of tools that declare
        no fans) and fans no single tool owns."""
        fan = self._tool_index(cmd, "P")
        if fan is None:
            tool = self.current_tool()
            fans = self.tool_fans.get(tool)
            return tool if fans and all(self._owner(f) == tool for f in fans) else None
        return self._owner(fan)

    def _owner(self, fan: int) -> int | None:
        owners = [tool for tool, fans in self.tool_fans.items() if fan in fans]
        return owners[0] if len(owners) == 1 else None

    def part_fan_note(self) -> None:
        """RepRapFirmware's fans belong to tools (M563 F): no Marlin fan-count question."""

    def part_fan_follows(self, tool: int) -> bool:
        return not self.tool_fans.get(tool) or any(self._owner(f) != tool for f in self.tool_fans[tool])

    def m563(self, cmd: Command) -> None:
        """Define a tool (configuration: Repetrel configures the Hyrel heads).  Its fans F are kept: "S alone"
        on M106 drives the current tool's fans.  ``M563 S<n>`` (older Duet firmware) adds n to "all tool
        numbers found in the remainder of the current input stream" (RepRap page, M563); RepRapFirmware 3.1
        removed it (Duet G-code dictionary, M563), so the tool numbers are left as written and reported."""
        params = cmd.params
        tool = self._tool_index(cmd, "P")
        if tool is None and "S" in params:
            offset = num(params.get("S"))
            if offset:
                self.remove(
                    cmd,
                    TR_LOST,
                    f"S{params['S']}: older Duet firmware adds {fmt(offset)} to every later tool number "
                    "(RepRapFirmware 3.1 removed it); tool numbers are translated as written",
                    key="M563-S",
                    aspects=("head", "temp", "fan", "flow", "e"),
                )
                return
        if tool is not None and "F" in params:
            fans = tuple(f for f in (num(p) for p in (params["F"] or "").split(":")) if f is not None and f >= 0)
            self.tool_fans[tool] = tuple(int(f) for f in fans)
        self.remove(
            cmd,
            TR_DROPPED,
            "RepRapFirmware configuration or report (Repetrel configures the Hyrel machine)",
            key="M563",
        )

    def g10(self, cmd: Command) -> None:
        params = cmd.params
        if "L" in params:
            level = num(params.get("L"))
            if level == 1 and "P" in params and any(a in params for a in "XYZ") and self.opts.tool_offsets == "m6":
                # "RRF G10 L1 P<t> X Y Z (tool offset) | default dropped; opt M6 T<map> O<reg> X Y Z"
                # (docs/translation.md, Marlin and RepRapFirmware -> Hyrel): as G10 P<t> X Y Z
                self._offsets_as_m6(cmd, self._tool_index(cmd, "P"))
                return
            if level in (2, 20):
                self.untranslatable(
                    cmd,
                    "G10 L2/L20 sets workspace origins; not translated (use Repetrel fixture offsets and G54)",
                    aspects=("wcs", "position", "offsets"),
                )
            else:
                self.remove(
                    cmd,
                    TR_LOST,
                    "tool offsets: Repetrel declares head offsets itself (M6; set tool-offsets=m6 to write them)",
                    key="G10-offset",
                    aspects=("position", "offsets"),
                )
            return
        if "P" not in params:
            self.firmware_retract(cmd, "M721", "firmware retract", "fw-retract")
            return
        index = self._tool_index(cmd, "P")
        if any(a in params for a in "XYZ"):
            if self.opts.tool_offsets == "m6":
                self._offsets_as_m6(cmd, index)
                if "S" not in params:
                    return
            else:
                self.report(
                    TR_LOST,
                    "tool offsets in G10 dropped: Repetrel declares head offsets itself (M6; set "
                    "tool-offsets=m6 to write them)",
                    key="G10-offset",
                    cmd=cmd,
                    aspects=("position", "offsets"),
                )
        if "S" in params:
            if "R" in params:
                self.report(
                    TR_APPROX,
                    "standby temperature (R) has no Hyrel counterpart",
                    key="standby",
                    cmd=cmd,
                    aspects="temp",
                )
            self.temperature(cmd, "M104", self.head(index), params["S"], tool=index)
        elif "R" in params:
            self.remove(
                cmd, TR_APPROX, "standby temperature (R) has no Hyrel counterpart", key="standby", aspects="temp"
            )
        else:
            self.consume(cmd)

    def _offsets_as_m6(self, cmd: Command, index: int | None) -> None:
        """RepRapFirmware subtracts a tool's offset from the position; Hyrel's M6 declares the head's offset
        (register O = position + 1, the v4 convention): written with the opposite sign, to verify."""
        address = self.head(index)
        if address is None:
            return
        words = [f"M6 T{address} O{address + 1}"]
        for letter in "XYZ":
            value = num(cmd.params.get(letter))
            if value is not None:
                words.append(f"{letter}{fmt(-value)}")
        text = " ".join(words)
        if "S" in cmd.params:
            self.before(text, note="tool offsets")
        else:
            self.replace(cmd, text)
        self.report(
            TR_APPROX,
            "tool offsets written as M6 (sign reversed, register O = head + 1): verify on the "
            "machine; Repetrel also sends head offsets at job start",
            key="G10-m6",
            cmd=cmd,
            aspects=("position", "offsets"),
        )

    def m568(self, cmd: Command) -> None:
        params = cmd.params
        index = self._tool_index(cmd, "P")
        s = num(params.get("S"))
        if "A" in params and s is not None and s > 0:
            # M568 tool settings: P tool, R standby, S active, A heater state (Duet G-code dictionary, M568); the
            # sources give no values for A, so whether the heater is on is unknown; heating a tool the source leaves off
            # or at standby would change the job (and a later M116 would wait for it)
            self.remove(
                cmd,
                TR_APPROX,
                f"A{params['A']} sets the tool's heater state, whose values the sources do not give: the active "
                f"temperature S{params['S']} is not written (if the tool is active, add M104 T# S{params['S']})",
                key="M568-A",
                aspects="temp",
            )
            return
        if "S" in params:
            if "R" in params:
                self.report(
                    TR_APPROX,
                    "standby temperature (R) has no Hyrel counterpart",
                    key="standby",
                    cmd=cmd,
                    aspects="temp",
                )
            self.temperature(cmd, "M104", self.head(index), params["S"], tool=index)
        else:
            self.remove(
                cmd,
                TR_APPROX,
                "tool settings without an active temperature have no Hyrel counterpart",
                key="M568",
                aspects="temp",
            )

    def m116(self, cmd: Command) -> None:
        """Wait for every temperature set without waiting: written as explicit waits with a tolerance."""
        window = num(cmd.params.get("S"))
        window_text = fmt(window) if window is not None else fmt(self.opts.temp_window)
        waits = [f"{code} T{address} S{temp} R{window_text}" for address, (code, temp) in sorted(self.hy.temps.items())]
        for address in self.hy.temps:
            state = self.hy.head(address)
            state.waited = state.target
        self.hy.temps.clear()
        self.tools.wait_all()
        if not waits:
            self.remove(cmd, TR_NOTE, "M116 with no temperature set since the last wait; dropped", key="M116-none")
            return
        *first, last = waits
        if first:
            self.before(*first, note="RepRapFirmware M116")
        self.replace(cmd, last)
        self.report(TR_NOTE, "M116 written as explicit waits for the temperatures set before it", key="M116", cmd=cmd)

    def macro(self, cmd: Command) -> None:
        self.untranslatable(cmd, "macro call: the macro's content is not translated")

    def macro_return(self, cmd: Command) -> None:
        self.remove(cmd, TR_DROPPED, "return from a macro", key="M99")

    def message_box(self, cmd: Command) -> None:
        s = num(cmd.params.get("S"))
        if s is not None and s >= 2:
            self.pause_command(cmd, "M0 ; gclint: message")
            self.report(
                TR_APPROX,
                "blocking message box written as a pause (the message text is not shown)",
                key="M291",
                cmd=cmd,
                aspects="pause",
            )
        else:
            self.remove(cmd, TR_DROPPED, "message box", key="M291")

    def rrf_m226(self, cmd: Command) -> None:
        self.pause_command(cmd, "M0")
        self.report(
            TR_APPROX,
            "M226 (pause at this point) written as Hyrel's M0 (wait for Resume)",
            key="M226",
            cmd=cmd,
            aspects=(),
        )

    def rrf_stop(self, cmd: Command) -> None:
        self.pause_command(cmd, "M0")
        self.report(
            TR_APPROX,
            f"RepRapFirmware {cmd.code} stops (and may switch heaters and motors off); written as Hyrel's pause M0",
            key="M0-rrf",
            cmd=cmd,
        )

    def extended(self, cmd: Command) -> None:
        self.untranslatable(cmd, "extended command cannot be translated", key=cmd.code)
