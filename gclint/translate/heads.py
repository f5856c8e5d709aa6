"""The tool/head model: source tool -> Hyrel head address (the tool map and the printer's positions),
tool changes, and the per-head commands (temperatures, fans, flow).

Hyrel addresses every head command explicitly (docs/translation.md, rule X2) and keeps set-points, fans
and flow per head; a source firmware keeps them per tool, and its part fan is one fan for all tools
(tools.py).  So what the source's active tool prints with is carried to the Hyrel head that prints:
before the first working move after a tool change (``sync_working_head``), the head gets the set-point,
wait, fan and flow the source tool has, and the head before it gives up the part fan.  What the source
switches off is switched off on every head that carried it.

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.syntax.nodes import Command
from gclint.translate.findings import TR_APPROX, TR_LOST, TR_NO_TOOL, TR_NOTE
from gclint.translate.mixin import TranslatorMixin
from gclint.translate.options import ToolMapClash
from gclint.translate.output import fmt
from gclint.translate.words import num


class Heads(TranslatorMixin):
    # -- addresses -------------------------------------------------------------------------------------

    def head(self, index: int | None = None, what: str = "tool") -> int | None:
        """The Hyrel address of source tool ``index`` (None: the active tool), or None (reported) when the
        printer has no such position.  ``what="fan"``: a fan index through the fan map (fan 0 unmapped:
        the focused head's fan).  The active tool with no head of its own: the head that prints for it
        (the focused one; its T command was reported)."""
        if what == "fan":
            if index is None:
                return self.head(None)
            address = self.opts.fan_map.get(index)
            if address is None:
                if index == 0:
                    return self.head(None)
                self._no_tool(what, index)
                return None
            return self._on_printer(address, what, index)
        active = index is None
        if index is None:
            index = self.current_tool()
        if self.single_nozzle:  # (one nozzle and heater for every tool: base.read_job)
            index = 0
        cache = self._head_cache
        if index in cache:
            address = cache[index]
            if address is None:
                if active and self.hy.focus is not None:
                    return self.hy.focus
                self._no_tool(what, index, self.opts.tool(index))
            return address
        address = cache[index] = self._on_printer(self.opts.tool(index), what, index)
        if address is not None:
            self._head_user(index, address)
        if address is None and active and self.hy.focus is not None:
            return self.hy.focus
        return address

    def _head_user(self, tool: int, address: int) -> None:
        """A second source tool on a head another tool of the job already uses (``--tool-map 0=T1`` and tool 1
        with the identity default) is refused: the head would print, heat and cool for both."""
        other = self._head_users.setdefault(address, tool)
        if other == tool:
            return
        how = {
            t: (f"{t}=T{address}" if t in self.opts.tool_map else f"tool {t} unmapped, T{t} by default")
            for t in (other, tool)
        }
        raise ToolMapClash(
            f"tools {other} and {tool} both map to head T{address} ({how[other]}; {how[tool]}); "
            f"map tool {tool if tool not in self.opts.tool_map else other} to a head of its own with --tool-map"
        )

    def _on_printer(self, address: int, what: str, index: int) -> int | None:
        if address in self.positions or (what != "tool" and 20 <= address <= 25):
            return address
        self._no_tool(what, index, address)
        return None

    def _no_tool(self, what: str, index: int, address: int | None = None) -> None:
        printer = self.opts.printer
        if address is None:
            self.report(
                TR_LOST,
                f"{what} {index} has no Hyrel address; dropped (map it with --set fan-map={index}=T#)",
                key=(what, index),
                aspects="aux",
            )
            return
        message = (
            f"{what} {index} maps to T{address}, which the {printer.name} does not have "
            f"({printer.describe_positions()}); use --tool-map or --printer"
        )
        if what == "tool" and self.hy.focus is not None:
            message += f"; the head that was printing (T{self.hy.focus}) goes on printing for it"
        elif what == "tool" and self.SPINDLE_FOLLOWS_TOOL:  # (CNC: cnc.focus_address)
            message += f"; the spindle head (T{self.opts.spindle_address()}) works for it"
        self.report(TR_NO_TOOL, message, key=(what, index))

    def current_tool(self) -> int:
        tool = self.state.tool
        return tool if tool is not None and tool >= 0 else 0

    def focus_address(self) -> int | None:
        """The head Hyrel should focus before the first move."""
        return self.head(None)

    # -- tool changes ----------------------------------------------------------------------------------

    def select_tool(self, cmd: Command, index: int | None) -> None:
        """A source tool change -> ``T<address>`` (Hyrel: focus the head; its M6 offsets, flow and
        prime/unprime apply).  What the tool prints with is carried before its first working move."""
        self.sync_due = True
        address = self.head(index)
        if address is None:
            self.consume(cmd)
            return
        old, self.hy.focus = self.hy.focus, address
        self.spindle_to_head(old, address)
        text = f"T{address}"
        if cmd.code == text and not cmd.params:
            return
        self.replace(cmd, text)

    def tool_command(self, cmd: Command) -> None:
        number = cmd.code[1:] if cmd.code else ""
        if number == "-1":
            self.remove(
                cmd, TR_LOST, "T-1 (deselect every tool) has no Hyrel counterpart; dropped", key="T-1", aspects="head"
            )
            return
        if not number.isdigit():
            self.untranslatable(cmd, "a tool given by a query or expression cannot be translated", key="T?")
            return
        if len(number) > 2:
            self.untranslatable(
                cmd,
                "a vendor pseudo-tool (filament unload, calibration) cannot be translated",
                key=("T-vendor", number),
                aspects=(),
            )
            return
        if self.single_nozzle and number != "0":
            self.report(
                TR_APPROX,
                "single-nozzle multi-material (single_extruder_multi_material = 1): the tools are filaments through "
                "one nozzle and heater, printed by one Hyrel head; the filament changes themselves (unload, load, "
                "purge) are not Hyrel operations",
                key="single-nozzle",
                cmd=cmd,
                aspects=("head",),
            )
        dropped = [letter for letter in cmd.params]
        if dropped:
            self.report(
                TR_NOTE,
                f"T parameters {' '.join(dropped)} (tool-change moves, macros) dropped",
                key="T-params",
                cmd=cmd,
            )
        self.select_tool(cmd, int(number))

    def sync_working_head(self) -> None:
        """Before a working move after a tool change: give the head that prints what the source's active
        tool prints with (set-point and wait, part fan, flow)."""
        self.sync_due = False
        address = self.head(None)
        if address is None:
            return
        tools = self.tools
        heat, flow, inferred = tools.working(self.current_tool())
        state = self.hy.head(address)
        lines = []
        if heat is not None:
            target, ready = heat
            heated = tools.heated()
            if tools.shared and not ready and heated and state.waited != heated:
                # the source's one nozzle was waited hot (to ``heated``) and heads towards ``target``; this
                # head was not: it waits for that heat first, else it would print cold (Hyrel M109 without
                # a window waits while heating only, Hyrel firmware source, src/MCode.c M109)
                lines.append(f"M109 T{address} S{fmt(heated, 1)}")
                state.target = state.waited = heated
                self.hy.temps.pop(address, None)
                self.hy.nozzle_heads.add(address)
                self.report(
                    TR_NOTE,
                    f"T{address} prints for the single nozzle after a set-point it was not waited for: it waits "
                    f"for {fmt(heated, 1)} °C, the heat the source's nozzle was waited to, before it prints",
                    key=("nozzle-wait", address),
                )
            if state.target != target or (ready and state.waited != target):
                lines.append(f"{'M109' if ready else 'M104'} T{address} S{fmt(target, 1)}")
                state.target = target
                if ready:
                    state.waited = target
                    self.hy.temps.pop(address, None)
                if tools.shared:
                    self.hy.nozzle_heads.add(address)
        if inferred:
            self.report(
                TR_NOTE,
                f"tool {self.current_tool()} prints without a set-point of its own: a single-nozzle job; "
                "each head that prints gets the nozzle's set-point, wait and flow",
                key="single-nozzle",
            )
        if (tools.fan or self.hy.part_fan_heads) and self.part_fan_follows(self.current_tool()):
            for other in sorted(self.hy.part_fan_heads - {address}):
                if self.hy.head(other).fan:
                    lines.append(f"M107 T{other}")
                    self.hy.head(other).fan = 0
            if state.fan != tools.fan:
                if tools.fan:
                    self.ensure_fan_range()
                    lines.append(f"M106 T{address} S{tools.fan}")
                else:
                    lines.append(f"M107 T{address}")
                state.fan = tools.fan
            self.hy.part_fan_heads = {address} if tools.fan else set()
            if tools.fan and self.current_tool() != 0:
                self.part_fan_note()
        if flow is not None and state.flow != flow:  # explicit, not the head's stored value (X2)
            lines.append(f"M221 T{address} S{fmt(flow, 4)}")
            state.flow = flow
        if lines:
            self.before(*lines, note=f"what the source's tool {self.current_tool()} prints with, on T{address}")

    # -- temperatures, fans, flow ----------------------------------------------------------------------

    def temperature(
        self,
        cmd: Command,
        code: str,
        address: int | None,
        temp: str | None,
        window: bool = False,
        extra: tuple[str, ...] = (),
        tool: int | None = None,
    ) -> None:
        """Write a temperature command with an explicit address; ``window`` adds R<temp-window> (the source
        waits heating *or* cooling; Hyrel's R is a +/- tolerance).  ``tool``: the source tool of a head
        set-point (M104/M109; None: the active tool)."""
        head_command = code in ("M104", "M109")
        value = num(temp) if temp is not None else None
        if value is not None and value < -200:
            temp, value = "0", 0.0  # RepRapFirmware's -273.15: heater off
        if head_command:
            self.tools.set_temp(self.current_tool() if tool is None else tool, value, code == "M109")
        if address is None:
            self.consume(cmd)
            return
        words = [code, f"T{address}"]
        state = self.hy.head(address)
        if head_command:
            self.hy.nozzle_heads.add(address)  # on a single-nozzle job, a head heated as the nozzle
        if temp is not None:
            words.append("S" + temp)
            if value is not None:
                state.target = value
            if code in ("M104", "M140", "M141"):
                wait = {"M104": "M109", "M140": "M190", "M141": "M191"}[code]
                self.hy.temps[address] = (wait, temp)
            else:
                self.hy.temps.pop(address, None)
        if code in ("M109", "M190", "M191"):
            state.waited = state.target
        if window:
            words.append("R" + fmt(self.opts.temp_window))
        words.extend(extra)
        self.replace(cmd, " ".join(words))
        if head_command and self.tools.shared and value == 0:
            # the nozzle is off: so is every head that was heated as the nozzle
            others = sorted(a for a in self.hy.nozzle_heads if a != address and self.hy.head(a).target)
            for other in others:
                self.hy.head(other).target = 0.0
                self.hy.temps.pop(other, None)
            if others:
                self.after(*(f"M104 T{a} S0" for a in others), note="the single nozzle is off on every head")

    def part_fan_note(self) -> None:
        """The part fan (M106 without P) drives a tool other than tool 0: dialect note (Marlin)."""

    def part_fan_follows(self, tool: int) -> bool:
        """Whether the part fan follows ``tool`` to its head (RepRapFirmware: not for a tool with fans of its
        own)."""
        return True

    def fan(
        self, cmd: Command, address: int | None, value: float | None, index: int | None = 0, own: bool = False
    ) -> None:
        """``M106 T# S<0-255>`` (with ``M106 C255`` once before) or M107.  ``index`` 0 (or None): the part
        fan, which follows the active tool; ``own``: a tool's own fan (its head's, RepRapFirmware M563 F)."""
        if value is None:
            value = self.FAN_MAX
        s = max(0, min(255, round(value / self.FAN_MAX * 255)))
        part = not index and not own
        if part:
            self.tools.fan = s
        if address is None:
            self.consume(cmd)
            return
        self.ensure_fan_range()
        self.replace(cmd, f"M106 T{address} S{s}")
        self.hy.head(address).fan = s
        if part:
            self.hy.part_fan_heads.add(address)

    def fan_off(self, cmd: Command, address: int | None, index: int | None = 0, own: bool = False) -> None:
        part = not index and not own
        if part:
            self.tools.fan = 0
        if address is None:
            self.consume(cmd)
            return
        self.replace(cmd, f"M107 T{address}")
        self.hy.head(address).fan = 0
        if part:
            others = sorted(a for a in self.hy.part_fan_heads if a != address and self.hy.head(a).fan)
            for other in others:
                self.hy.head(other).fan = 0
            if others:
                self.after(*(f"M107 T{a}" for a in others), note="the part fan is off on every head")
            self.hy.part_fan_heads = set()

    def flow(self, cmd: Command, address: int | None, fraction: float, tool: int | None = None) -> None:
        """``M221 T# S<multiplier>`` for the source tool's flow."""
        self.tools.set_flow(self.current_tool() if tool is None else tool, fraction)
        if address is None:
            self.consume(cmd)
            return
        self.replace(cmd, f"M221 T{address} S{fmt(fraction, 4)}")
        self.hy.head(address).flow = fraction

    def ensure_fan_range(self) -> None:
        if not self.hy.fan_range_written:
            self.hy.fan_range_written = True
            self.before("M106 C255", note="header: fan values 0-255")
