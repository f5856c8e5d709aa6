"""Spindles: rpm -> percent of the Hyrel spindle's maximum, on/off with the head's address, a stop before
a change of direction (Hyrel Gcode page, M3).

The head a spindle command addresses: the ``spindle`` setting; else, for CNC sources, the head the active
tool maps to (a tool change with a tool map switches heads, "multi-head: T<tools[n]>", docs/translation.md,
Carvera -> Hyrel), so that the spindle runs on the head that cuts; else mapped tool 0.  A spindle running at such
a tool change stops where the source's tool change stops it (``Semantics.tool_change_stops_spindle``: LinuxCNC's
and Machinekit's M6, "The spindle will be stopped"; the Carvera's automatic tool change), else goes to the new
head.

A mixin of ``HyrelTranslator``.
"""

from __future__ import annotations

from gclint.syntax.nodes import Command
from gclint.translate.findings import TR_APPROX, TR_NOTE
from gclint.translate.mixin import TranslatorMixin
from gclint.translate.output import fmt
from gclint.translate.words import fast_float


class Spindles(TranslatorMixin):
    SPINDLE_FOLLOWS_TOOL = False  # CNC sources: the spindle is on the active tool's head (see above)

    def tool_change_stops(self, cmd: Command) -> None:
        """A tool change (M6) on a source machine that stops the spindle for it (``Semantics.tool_change_stops_spindle``:
        LinuxCNC "The spindle will be stopped", the Carvera's ATC): every running spindle stops here, and runs again
        only at the job's next M3/M4."""
        if not self.source.semantics.tool_change_stops_spindle:
            return
        running = sorted(self.hy.spindles_on)
        if not running:
            return
        self.before(*(f"M5 T{address}" for address in running), note="the tool change stops the spindle")
        self.hy.spindles_on.clear()
        self.report(
            TR_NOTE,
            "tool change while the spindle runs: the source machine's M6 stops the spindle (LinuxCNC: \"The spindle "
            'will be stopped"); M5 written, it runs again at the next M3/M4',
            key="M6-stops",
            cmd=cmd,
        )

    def spindle_head(self) -> int:
        """The Hyrel address spindle commands go to now."""
        if self.SPINDLE_FOLLOWS_TOOL and self.opts.spindle is None and self.hy.focus is not None:
            return self.hy.focus
        return self.opts.spindle_address()

    def spindle_to_head(self, old: int | None, new: int) -> None:
        """A tool change from head ``old`` to ``new``: a spindle running on ``old`` stops there and runs on ``new``
        at the same speed (after the T line), where the source's spindle keeps running through a tool change."""
        if not self.SPINDLE_FOLLOWS_TOOL or self.opts.spindle is not None:
            return
        if old is None:
            old = self.opts.spindle_address()  # no head focused yet: the spindle ran on the default one
        if old == new:
            return
        code = self.hy.spindles_on.pop(old, None)
        if code is None:
            return
        # (a source whose tool change stops the spindle stopped it already: ``tool_change_stops``)
        speed = f" S{self.spindle_percent}" if self.spindle_percent is not None else ""
        self.after(f"M5 T{old}", f"{code} T{new}{speed}", note="the spindle follows the tool to its head")
        self.hy.spindles_on[new] = code
        self.report(
            TR_NOTE,
            f"tool change while the spindle runs: it stops on T{old} and runs on T{new}, the new tool's head",
            key="spindle-head",
        )

    def speed_word(self, cmd: Command) -> None:
        """An S word outside M3/M4: the spindle speed (rpm) for the next M3, or a speed change now."""
        s = fast_float(cmd.params.get("S"))
        if s is None:
            return
        self.rpm = s
        address = self.spindle_head()
        running = self.hy.spindles_on.get(address)
        line = self.line
        # (where the source sets a line's S before its commands, LinuxCNC, an M3/M4 anywhere on the line runs after it)
        first = "S" in self.source.semantics.words_first
        rest = () if line is None else line.parsed.commands if first else line.parsed.commands[self.index + 1 :]
        if any(c.code in ("M3", "M4") for c in rest):
            return  # the M3/M4 on this line carries the speed
        if running is not None:
            self.spindle_percent = self.rpm_percent(s, self.MAX_RPM)
            self.before(f"{running} T{address} S{self.spindle_percent}", note="spindle speed")

    def spindle_on(self, cmd: Command, percent: str | None) -> None:
        address = self.spindle_head()
        if percent is not None:
            self.spindle_percent = percent
        code = cmd.code or "M3"
        words = [code, f"T{address}"]
        if percent is not None:
            words.append("S" + percent)
        running = self.hy.spindles_on.get(address)
        stops = percent is not None and float(percent) == 0  # "S0 is the same as turning it off" (M3)
        if running is not None and running != code and not stops:
            # "DO NOT CHANGE DIRECTION while the spindle is in motion" (Hyrel Gcode page, M3).  The page gives
            # no spin-down time: wait the configured one, else pause until the operator resumes.
            dwell = self.opts.spindle_stop_dwell
            wait = (
                f"G4 S{fmt(dwell)}"
                if dwell is not None
                else "M0 ; gclint: spindle stopped; resume when it stands still"
            )
            self.before(f"M5 T{address}", wait, note="stop and wait before changing direction")
            self.report(
                TR_APPROX,
                "spindle direction changed while running: Hyrel needs it stopped first; M5 and "
                + (f"a {fmt(dwell)} s dwell added" if dwell is not None else "a pause added (set spindle-stop-dwell)"),
                key="M3-M4",
                cmd=cmd,
                aspects=("spindle", "dwell" if dwell is not None else "pause"),
            )
        self.replace(cmd, " ".join(words))
        if stops:
            self.hy.spindles_on.pop(address, None)
        else:
            self.hy.spindles_on[address] = code

    def spindle_off(self, cmd: Command) -> None:
        address = self.spindle_head()
        self.replace(cmd, f"M5 T{address}")
        self.hy.spindles_on.pop(address, None)

    def rpm_percent(self, rpm: float, assumed_max: float | None = None) -> str:
        """Spindle rpm -> percent of the Hyrel spindle's maximum (configuration spindle-max-rpm)."""
        top = self.opts.spindle_max_rpm
        if top is None:
            top = assumed_max or 15000.0
            self.report(
                TR_APPROX,
                f"spindle rpm converted to percent of an assumed {fmt(top)} rpm maximum; set "
                "spindle-max-rpm to the Hyrel spindle's",
                key="rpm-assumed",
                aspects="spindle:speed",  # the speed, not whether it runs (compare.Explanations)
            )
        pct = rpm / top * 100
        if pct > 100:
            self.report(
                TR_APPROX,
                f"{fmt(rpm)} rpm is above the spindle's {fmt(top)} rpm: clamped to 100 %",
                key="rpm-clamp",
                aspects="spindle:speed",
            )
            pct = 100
        if 0 < pct < 0.05:  # (written to one decimal it would be S0, which stops Hyrel's spindle: "S0 is off")
            self.report(
                TR_APPROX,
                f"{fmt(rpm)} rpm is below 0.1 % of the spindle's {fmt(top)} rpm: written as 0.1 %, since S0 stops it",
                key="rpm-least",
                aspects="spindle:speed",
            )
            pct = 0.1
        return fmt(max(pct, 0.0), 1)
