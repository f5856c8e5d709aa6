"""The tool/head model: source tool -> Hyrel head address (the tool map and the printer's positions),
tool changes, and the per-head commands (temperatures, fans).

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.syntax.nodes import Command
from gclint.translate.findings import TR_LOST, TR_NO_TOOL, TR_NOTE
from gclint.translate.output import fmt
from gclint.translate.words import num


class Heads:
    def head(self, index: int | None = None, what: str = "tool") -> int | None:
        """The Hyrel address of source tool ``index`` (None: the focused tool), or None (reported) when the
        printer has no such position.  ``what="fan"``: a fan index through the fan map (fan 0 unmapped:
        the focused head's fan)."""
        if what == "fan":
            address = self.opts.fan_map.get(index)  # type: ignore[arg-type]
            if address is None:
                if index == 0 or index is None:
                    return self.head(None)
                self._no_tool(what, index)
                return None
            return self._on_printer(address, what, index)  # type: ignore[arg-type]
        if index is None:
            index = self.current_tool()
        cache = self._head_cache
        if index in cache:
            address = cache[index]
            if address is None:
                self._no_tool(what, index, self.opts.tool(index))
            return address
        address = cache[index] = self._on_printer(self.opts.tool(index), what, index)
        return address

    def _on_printer(self, address: int, what: str, index: int) -> int | None:
        if address in self.positions or 20 <= address <= 25:
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
            )
            return
        else:
            message = (
                f"{what} {index} maps to T{address}, which the {printer.name} does not have "
                f"({printer.describe_positions()}); use --tool-map or --printer"
            )
        self.report(TR_NO_TOOL, message, key=(what, index))

    def current_tool(self) -> int:
        tool = self.state.tool
        return tool if tool is not None and tool >= 0 else 0

    def focus_address(self) -> int | None:
        """The head Hyrel should focus before the first move."""
        return self.head(None)

    def select_tool(self, cmd: Command, index: int | None) -> None:
        """A source tool change -> ``T<address>`` (Hyrel: focus the head; its M6 offsets, flow and
        prime/unprime apply)."""
        address = self.head(index)
        if address is None:
            self.consume(cmd)
            return
        self.hy.focus = address
        text = f"T{address}"
        if cmd.code == text and not cmd.params:
            return
        self.replace(cmd, text)

    def tool_command(self, cmd: Command) -> None:
        number = cmd.code[1:] if cmd.code else ""
        if number == "-1":
            self.remove(cmd, TR_LOST, "T-1 (deselect every tool) has no Hyrel counterpart; dropped", key="T-1")
            return
        if not number.isdigit():
            self.untranslatable(cmd, "a tool given by a query or expression cannot be translated", key="T?")
            return
        if len(number) > 2:
            self.untranslatable(
                cmd,
                "a vendor pseudo-tool (filament unload, calibration) cannot be translated",
                key=("T-vendor", number),
            )
            return
        dropped = [letter for letter in cmd.params]
        if dropped:
            self.report(
                TR_NOTE,
                f"T parameters {' '.join(dropped)} (tool-change moves, macros) dropped",
                key="T-params",
                cmd=cmd,
            )
        self.select_tool(cmd, int(number))

    def temperature(
        self,
        cmd: Command,
        code: str,
        address: int | None,
        temp: str | None,
        window: bool = False,
        extra: tuple[str, ...] = (),
    ) -> None:
        """Write a temperature command with an explicit address; ``window`` adds R<temp-window> (the source
        waits heating *or* cooling; Hyrel's R is a +/- tolerance)."""
        if address is None:
            self.consume(cmd)
            return
        words = [code, f"T{address}"]
        if temp is not None:
            value = num(temp)
            if value is not None and value < -200:
                temp = "0"  # RepRapFirmware's -273.15: heater off
            words.append("S" + temp)
            if code in ("M104", "M140", "M141"):
                wait = {"M104": "M109", "M140": "M190", "M141": "M191"}[code]
                self.hy.temps[address] = (wait, temp)
            else:
                self.hy.temps.pop(address, None)
        if window:
            words.append("R" + fmt(self.opts.temp_window))
        words.extend(extra)
        self.replace(cmd, " ".join(words))

    def fan(self, cmd: Command, address: int | None, value: float | None) -> None:
        """``M106 T# S<0-255>`` (with ``M106 C255`` once before) or M107."""
        if address is None:
            self.consume(cmd)
            return
        if value is None:
            value = self.FAN_MAX
        s = max(0, min(255, round(value / self.FAN_MAX * 255)))
        self.ensure_fan_range()
        self.replace(cmd, f"M106 T{address} S{s}")

    def fan_off(self, cmd: Command, address: int | None) -> None:
        if address is None:
            self.consume(cmd)
            return
        self.replace(cmd, f"M107 T{address}")

    def ensure_fan_range(self) -> None:
        if not self.hy.fan_range_written:
            self.hy.fan_range_written = True
            self.before("M106 C255", note="header: fan values 0-255")
