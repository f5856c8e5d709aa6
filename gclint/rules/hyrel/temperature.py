"""HY temperature rules: M104, M109/M190/M191 waits, W0 and M116.

Sources: the Hyrel Gcode page, "Controlling Temperature" (M104, M109 Wait for Temp (Head), M116 Wait for
Temps (v5+), M190, M191) and the T_v5 chart of addresses; see docs/sources.md.
"""

from __future__ import annotations

from gclint.dialects.addressing import BED, GROUP, GROUP_MEMBERS, HEAD, RESERVED, VIRTUAL, wait_fails
from gclint.dialects.base import Param
from gclint.dialects.habits import marlin_style_r
from gclint.rules.base import ANY_T, Rule, Severity, register
from gclint.rules.dialect import ParamTableRule
from gclint.rules.hyrel.addressing import reported_as_v4
from gclint.syntax.nodes import Command, Line, to_number

_WAITS = ("M109", "M190", "M191")
_GROUPS = (("H", "C"), ("L", "U"), ("R",))
_WAITED = {"M109": "head", "M190": "bed", "M191": "chamber"}
_SETS = ("M104", "M140", "M141")
_SET = {"M104": "head", "M140": "bed", "M141": "chamber"}


def _device(rule: Rule, cmd: Command) -> int:
    """The device a temperature command acts on, keyed as the interpreter keys ``state.targets``."""
    interpreter = rule.ctx.interpreter
    if cmd.code in ("M190", "M191", "M140", "M141"):
        address = interpreter.address(cmd)
        device = address.v5 if address is not None else 24  # "default is the primary bed / chamber"
    else:
        device = interpreter.target(cmd)
    return -1 if device is None else device


# -- HY002 ---------------------------------------------------------------------------------------------


@register
class WaitParameterGroups(Rule):
    code = "HY002"
    name = "wait-parameter-groups"
    severity = Severity.ERROR
    summary = "M109/M190/M191 mixes the H/C, L/U and R ways of ending the wait"
    explanation = """
        A Hyrel wait ends in one of three ways: absolute limits (H "heat up to", C "cool down to"),
        limits relative to S (L below, U above), or a window around S (R).  The page is explicit:
        "Please use EITHER (H and/or C) OR (L and/or U) OR (R) with your M109 command", and "You can use
        Hn or Ln, but not both.  You can use Cn or Un, but not both."  The pages do not say which group
        counts when a line has more than one, so the line does not say where the wait ends.
    """
    example_bad = "M109 T0 S240 H230 L10"
    example_good = "M109 T0 S240 L10 U5"
    source = "Gcode page, M109 Wait for Temp (Head), M190 Wait for Temp (Bed), M191 Wait for Temp (Chamber)"
    codes = _WAITS
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        params = cmd.params
        used = [group for group in _GROUPS if any(letter in params for letter in group)]
        if len(used) < 2:
            return
        letters = ["".join(letter for letter in group if letter in params) for group in used]
        both = []
        if "H" in params and "L" in params:
            both.append("'You can use Hn or Ln, but not both'")
        if "C" in params and "U" in params:
            both.append("'You can use Cn or Un, but not both'")
        extra = f" ({'; '.join(both)})" if both else ""
        self.report(
            line,
            f"{cmd.code} mixes {' with '.join(letters)}: 'use EITHER (H and/or C) OR (L and/or U) OR (R)'{extra}; "
            "the pages do not say which one counts",
            node=_second_group_word(cmd) or cmd,
        )


def _second_group_word(cmd: Command):
    """The first word (in source order) of a group other than the group of the first H/C/L/U/R word."""
    first = None
    for word in cmd.words:
        group = next((g for g in _GROUPS if word.letter in g), None)
        if group is None:
            continue
        if first is None:
            first = group
        elif group is not first:
            return word
    return None


# -- HY003 ---------------------------------------------------------------------------------------------


@register
class WaitOnGroupAddress(Rule):
    code = "HY003"
    name = "wait-on-group-address"
    severity = Severity.ERROR
    summary = "M109/M190/M191 addressed to a virtual or group address (T30-T48): the wait fails"
    explanation = """
        "Note, this will FAIL (non-fatally) if you address a virtual group address; be sure to use an
        actual physical address."  A wait on T30-T39 (clone squads) or T40-T48 (all devices, a yoke,
        all beds...) sets the temperature but never waits, so the job starts printing cold.  Wait on each
        physical head or bed instead (`M109 T0 ...`, `M109 T1 ...`), or set them all with W0 and wait
        with M116 (v5).  In v4 files the v4 group numbers count (T0 all devices, T10/T20 a yoke, T90 all
        beds, T100 all heads, T50-T57 groups).
    """
    example_bad = "M109 T40 S200"
    example_good = "M109 T0 S200"
    source = "Gcode page, M109 Wait for Temp (Head) (also M190, M191)"
    codes = _WAITS
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        if "T" not in cmd.params:
            return
        address = self.ctx.interpreter.address(cmd)
        if address is not None and wait_fails(address):
            self.report(
                line,
                f"{cmd.code} T{cmd.params['T']} waits on {address.label}, a virtual or group address: "
                "the wait fails and the job goes on without waiting; address one physical device",
                node=cmd.param("T"),
            )


# -- HY027 ---------------------------------------------------------------------------------------------


@register
class V5OnlyCodeOnV4(Rule):
    code = "HY027"
    name = "v5-only-code-on-v4"
    severity = Severity.ERROR
    summary = "M116 or a W0 wait in a v4 job: both exist only from Repetrel v5"
    explanation = """
        "Codes in Orange are supported on version 5 and above (v5+) only": M116 ("supported with
        version 5.x and later") and the W0 of M109/M190/M191 ("will set the temp and advance to the next
        line without pause, but upon executing M116, will pause until temp is reached").  On v4
        firmware M116 does not exist and W0 does not defer the wait, so the job does not wait where it
        means to.  Use a plain M109/M190/M191 wait on v4, or run the job on v5.
    """
    example_bad = """
        ; gclint-test: dialect=hyrel-v4
        M109 T11 S200 W0
        M116
    """
    example_good = """
        ; gclint-test: dialect=hyrel-v4
        M109 T11 S200
    """
    source = "Gcode page, M109 Wait for Temp (Head) ([v5+] W0) and M116 Wait for Temps (v5+)"
    codes = ("M116", *_WAITS)
    dialects = ("hyrel-v4",)

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.code == "M116":
            self.report(
                line,
                "M116 (wait for W0 temperatures) is supported from v5 only; v4 firmware does not know it",
                node=cmd,
            )
            return
        w = cmd.params.get("W")
        if w is not None and w.strip("+-0.") == "":
            self.report(line, f"{cmd.code} W0 (set now, wait at M116) is supported from v5 only", node=cmd.param("W"))


# -- HY035 ---------------------------------------------------------------------------------------------


@register
class WaitRIsATolerance(Rule):
    code = "HY035"
    name = "wait-r-is-a-tolerance"
    severity = Severity.ERROR
    summary = "M109/M190/M191 R above 50 without S: R is a tolerance around the set point, not a target (Marlin)"
    explanation = """
        On Hyrel, "Rn if present, is how close the relative temperature needs to be to the set temp to
        end the pause", and "Sn (optional) is the new set temperature in °C; if omitted, no new target
        temperature is set".  Marlin and RepRapFirmware read `M109 R210` as "set 210 °C and wait, also
        when cooling"; on Hyrel it sets nothing and waits until the head is within ±210 °C of the
        temperature already set.  An R above 50 °C with no S is taken for such a Marlin target (the
        threshold is gclint's own choice, not the page's): write `M109 S210 R5`.
        With S, R is the tolerance the page describes, whatever its size: the page gives no limit, so
        `M109 T0 S240 R60` is not reported.

        A wait without S is the page's own example: `M109 R10`, "(no T# - use head with current focus)
        R10 (to get +/-10°C of set temperature)".  The set temperature may come from the job, from the
        head settings Repetrel sends at the start ("All parameters are persistent"), or from the
        operator, so a small R without S is not reported.
    """
    example_bad = "M109 T0 R210"
    example_good = "M109 T0 S210 R5"
    source = "Gcode page, M109 Wait for Temp (Head) (Sn, Rn, Example 6; also M190, M191)"
    codes = _WAITS
    families = ("hyrel",)

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        return frozenset("R")

    def check(self, line: Line, cmd: Command) -> None:
        message = r_target_message(cmd)
        if message is not None:
            self.report(line, message, node=cmd.param("R"))


def r_target_message(cmd: Command) -> str | None:
    """HY035's message for a Hyrel wait whose R looks like a Marlin target (explain says the same), or None."""
    if not marlin_style_r(cmd):
        return None  # (R is the tolerance around S, or a tolerance: the page sets no limit on it)
    return (
        f"{cmd.code} R{cmd.params['R']} is a Marlin-style target, but Hyrel's R is a tolerance and "
        f"sets nothing ('if omitted, no new target temperature is set'): write {cmd.code} S{cmd.params['R']} R5"
    )


# -- HY036 ---------------------------------------------------------------------------------------------


@register
class W0NeverWaited(Rule):
    code = "HY036"
    name = "w0-never-waited"
    severity = Severity.WARNING
    summary = "An M109/M190/M191 W0 is never followed by M116, so nothing waits for that temperature"
    explanation = """
        "W0 if present, will set the temp and advance to the next line without pause, but upon
        executing M116, will pause until temp is reached."  Without a later M116 (or a plain wait on
        the same device) before the job ends, the job never waits for that temperature and starts
        printing while the head or bed is still heating.  An M116 with no W0 pending is reported as
        info: it waits for nothing.
    """
    example_bad = """
        M109 T0 S200 W0
        G1 X10 E1 F600
        M30
    """
    example_good = """
        M109 T0 S200 W0
        M190 T24 S60 W0
        M116
        G1 X10 E1 F600
        M30
    """
    source = "Gcode page, M109 Wait for Temp (Head) ([v5+] W0) and M116 Wait for Temps (v5+)"
    codes = ("M116", "M30")
    dialects = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.reported: set[int] = set()

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.code == "M116":
            if not self.state.pending_w0:
                self.report(
                    line,
                    "M116 waits for temperatures set with W0, and none is pending",
                    node=cmd,
                    severity=Severity.INFO,
                )
            return
        self._unwaited(f"before M30 at line {line.number}")

    def finish(self) -> None:
        self._unwaited("before the end of the file")

    def _unwaited(self, where: str) -> None:
        for device, w0_line in sorted(self.state.pending_w0.items(), key=lambda kv: kv[1]):
            if w0_line in self.reported:
                continue
            self.reported.add(w0_line)
            what = f"T{device}" if device >= 0 else "the focused head"
            self.report(
                w0_line,
                f"W0 sets {what} to heat without waiting, but no M116 (or plain wait) follows {where}: "
                "nothing waits for that temperature",
            )


# -- HY046 ---------------------------------------------------------------------------------------------


@register
class WaitTargetKind(Rule):
    code = "HY046"
    name = "wait-target-kind"
    severity = Severity.WARNING
    summary = (
        "A head temperature command (M104, M109) addressed to something other than a head, or a bed or "
        "chamber one (M140, M141, M190, M191) to something other than a bed/chamber"
    )
    explanation = """
        M109 waits for a head ("T# is the target head"), M190 for a bed and M191 for a chamber ("T# is
        the target bed" / "the target chamber"); M104 sets a head ("T# (target head)"), M140 a bed and
        M141 a chamber ("T# is the target bed" / "the target chamber").  In v5, beds and chambers are
        T24 and T25 ("Bed1 / Chamber1", "Bed2 / Chamber2") and heads T0-T19: `M190 T0`, `M140 T0` or
        `M109 T24` waits for or sets the wrong kind of device, most often because the T was copied from
        another line; the message names the command for that device.  The 3-phase spindle (T20), the
        CO2 laser (T21) and the aux ports (T22, T23) are none of these, and the page gives them no
        temperature, so no temperature command fits them.  (Group addresses are HY003 for the waits,
        unknown addresses HY047.)  The rule keeps its first name, from when it checked the waits only.
    """
    example_bad = "M190 T0 S60"
    example_good = "M190 T24 S60"
    source = (
        "Gcode page, M104 / M109 / M140 / M141 / M190 / M191 (T# is the target head / bed / chamber); "
        "T_v5, Chart of Addresses"
    )
    codes = (*_WAITS, *_SETS)
    families = ("hyrel",)

    def check(self, line: Line, cmd: Command) -> None:
        if "T" not in cmd.params or reported_as_v4(self.ctx, cmd):
            return
        address = self.ctx.interpreter.address(cmd)
        if address is None or address.kind in (VIRTUAL, GROUP, RESERVED):
            return
        code = str(cmd.code)
        expected = HEAD if code in ("M104", "M109") else BED
        if address.kind == expected:
            return
        waits = code in _WAITS
        if address.kind == BED:
            hint = (
                "; for that device use M190 (bed) or M191 (chamber)"
                if waits
                else "; for that device use M140 (bed) or M141 (chamber)"
            )
        elif address.kind == HEAD:
            hint = "; for a head use M109" if waits else "; for a head use M104"
        else:
            hint = ", which is not a head, bed or chamber: the page gives it no temperature to " + (
                "wait for (M109 waits for a head, M190 for a bed, M191 for a chamber)"
                if waits
                else "set (M104 sets a head, M140 a bed, M141 a chamber)"
            )
        if waits:
            what = f"{code} waits for a {_WAITED[code]}"
        else:
            what = f"{code} sets a {_SET[code]}"
        self.report(line, f"{what}, but T{cmd.params['T']} is {address.label}{hint}", node=cmd.param("T"))


# -- HY051 ---------------------------------------------------------------------------------------------


ABSOLUTE_ZERO = -273.15
_BED_CODES = ("M140", "M141", "M190", "M191")


@register
class NegativeTemperature(ParamTableRule):
    code = "HY051"
    name = "negative-temperature"
    severity = Severity.INFO
    summary = "A head set below 0 °C (M104/M109 S): only a chilled (sub-ambient) head goes there"
    explanation = """
        "Sn is the new set temperature in °C" for the head (M104, M109), and "Remember, we have both
        heated and chilled (sub-ambient) heads as options."  The page gives no lowest set point, so a
        set point below 0 °C is not an error: it is right for a chilled head and a typo (or a value in
        another unit) for a heated one, and a G-code file does not say which head is which.  gclint
        mentions it (info) so that a heated head set to `S-20` instead of `S20` is noticed; beds and
        chambers ("heated and chilled (sub-ambient) beds", "chambers") are not reported.  The ranges
        are data in gclint/dialects/hyrel.py (`rule="HY051"`).  A set point below absolute zero
        (-273.15 °C), for a head, a bed or a chamber, is an error: no device reaches it.
    """
    example_bad = "M104 T0 S-20"
    example_good = "M104 T0 S20"
    source = (
        "Gcode page, M104 Set Temp (Head) and M109 Wait for Temp (Head) ('heated and chilled (sub-ambient) " "heads')"
    )
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        # below absolute zero no head, bed or chamber can go (physics, not a limit of the pages): an error
        self.codes = tuple(dict.fromkeys((*self.codes, *(c for c in _BED_CODES if c in ctx.dialect.codes))))

    def trigger_letters(self, code: str) -> frozenset[str] | None:
        return frozenset("S")

    def check(self, line: Line, cmd: Command) -> None:
        value = to_number(cmd.params.get("S") or "")
        if value is not None and value < ABSOLUTE_ZERO:
            self.report(
                line,
                f"{cmd.code} S{cmd.params['S']} is below absolute zero ({ABSOLUTE_ZERO} °C): no device can reach it",
                node=cmd.param("S") or cmd,
                severity=Severity.ERROR,
            )
        elif cmd.code in self.table:
            super().check(line, cmd)

    def range_message(self, cmd: Command, p: Param, problem: str) -> str:
        return (
            f"{cmd.code} S{cmd.params.get('S')} sets a head below 0 °C: fine for a chilled (sub-ambient) head, "
            "a typo for a heated one"
        )


# -- HY063 ---------------------------------------------------------------------------------------------


@register
class HeadPrintsWithoutTemperature(Rule):
    code = "HY063"
    name = "head-prints-without-temperature"
    severity = Severity.WARNING
    summary = (
        "A head prints after a T command, but no M104/M109 set its temperature (the job heats other heads), or "
        "a head prints after it was set to S0"
    )
    explanation = """
        A T command changes the head that prints, "invoking the parameters specified in the M6" (flow,
        prime, unprime, offsets); it does not heat the head.  Temperatures come from the job: "the
        slicing program generates gcode which dictates temperature and movement commands", M104 "sets
        the extruder temperature" ("T# is the tool assignment for this temperature command"), and "All
        parameters are persistent, so once they are set, they will remain in place".  A head that a
        tool change brings in and that no M104/M109 has set (by its own address, or a group address
        covering it: T40 "ALL DEVICES", T41-T44 "Yoke n, all Heads", T47 "All non-Bed / non-Chamber
        devices", a clone squad it belongs to) prints at whatever it holds, cold for a heated head.

        Not every head needs heat, and a file does not say which head is which, so this is a warning
        and it assumes a heated head.  gclint leaves out what it can recognise: heads enabled with
        `M620 T# E1` ("The CO_2 and Diode Lasers and the UV Pens require the following enabling
        codes"), spindle heads (M3/M4), and jobs whose file sets no head temperature at all (other than
        S0, which footers use to switch heaters off): such a job leaves temperatures to Repetrel (the
        head settings and header it sends "when you start a job") or runs heads that need none.  A
        cold paste or bio head at room temperature, or a chilled head ("we have both heated and chilled
        (sub-ambient) heads as options"), printing beside heated ones is reported: ignore the finding
        for it (`; noqa: HY063`), or set its temperature in the job.  An M104/M109 without T before the
        first T command heats the head Repetrel focused at the start, which gclint cannot name, so
        every head then counts as set.  Each head is reported once, at its first printing move without
        a temperature.

        Likewise a head whose temperature the job set to 0 (`M104 T0 S0`, or a group address covering
        it, as footers switch heaters off) and that prints afterwards, with no new temperature between:
        "S0 (to 0°C)" is a set point of 0 °C (M109 Example 5), cold for a heated head.  With the same
        exceptions (a job that heats no head, lasers, UV pens, spindles), reported once per head.
    """
    example_bad = """
        M109 T0 S215
        T0
        G1 X10 Y10 E1 F1200
        T1
        G1 X20 Y10 E1
    """
    example_good = """
        M104 T41 S215
        M109 T0 R5
        T0
        G1 X10 Y10 E1 F1200
        T1
        M109 R5
        G1 X20 Y10 E1
    """
    source = (
        "Gcode page, What is GCode?, Controlling Material Flow, M104 Set Temp (Head), T Tool Change, "
        "Controlling Lasers and UV Pens; T_v5, Chart of Addresses (group addresses)"
    )
    codes = (ANY_T, "M104", "M109", "M140", "M141", "M190", "M191", "M30", "M620", "M3", "M4")
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.judged = False  # the printing since the last T command has been looked at
        self.first_heat: int | None = None  # first M104/M109 with a non-zero S
        self.candidates: list[tuple[int, int, int | None]] = []  # (first print, head, line of its T command)
        self.no_heat: set[int] = set()  # heads known to need no heat: lasers/UV pens (M620), spindles
        self.zero_lines: dict[int, int] = {}  # device written on an M104/M109 S0 (-1: the focused one) -> line
        self.cold: list[tuple[int, int, int]] = []  # (first print, head or -1, line of the S0 that covers it)

    def check(self, line: Line, cmd: Command) -> None:
        code = cmd.code
        interpreter = self.ctx.interpreter
        if code == "M620":
            address = interpreter.address(cmd)
            if address is not None and address.position is not None and cmd.get("E") == 1:
                self.no_heat.add(address.position)
            return
        if code == "M3" or code == "M4":
            device = interpreter.target(cmd)
            if device is not None and 0 <= device <= 19:
                self.no_heat.add(device)
            return
        self._settle()
        if code == "M104" or code == "M109":
            s = cmd.get("S")
            if s is not None and s != 0 and self.first_heat is None:
                self.first_heat = line.number
            if s == 0:
                self.zero_lines[_device(self, cmd)] = line.number
        elif code == "M30" or (code is not None and code[0] == "T"):
            self.judged = False

    def _settle(self) -> None:
        """Look at the printing since the last T command once: was the printing head set, before it?"""
        if self.judged:
            return
        st = self.state
        printed = st.first_print_since_tool_line
        if printed is None:
            return
        self.judged = True
        head = st.tool
        targets = st.targets
        key = head if head is not None and head in targets else -1
        if targets.get(key) == 0 and (head is None or 0 <= head <= 19):
            zero = self._zero_line(-1 if head is None else head)
            if zero is not None:
                self.cold.append((printed, -1 if head is None else head, zero))
                return
        if head is None or not 0 <= head <= 19 or st.tool_line is None:
            return  # no T command: the head Repetrel focused at the start (Default Mode)
        if head in targets or -1 in targets:
            return
        self.candidates.append((printed, head, st.tool_line))

    def _zero_line(self, head: int) -> int | None:
        """The line of the last M104/M109 S0 written to ``head``, to the focused head, or to a group or
        squad covering it."""
        squads = self.state.squads
        lines = [
            line
            for device, line in self.zero_lines.items()
            if device in (head, -1) or head in GROUP_MEMBERS.get(device, ()) or head in squads.get(device, ())
        ]
        return max(lines, default=None)

    def finish(self) -> None:
        self._settle()
        if self.first_heat is None:
            return  # the file sets no head temperature: Repetrel's settings, or heads that need none
        reported: set[int] = set()
        for printed, head, zero in self.cold:
            if head in self.no_heat or head in reported:
                continue
            reported.add(head)
            named = f"head T{head}" if head >= 0 else "the focused head"
            self.report(
                printed,
                f"{named} prints here, but its temperature was set to 0 at line {zero} and not set again: "
                "S0 is a set point of 0 °C, cold for a heated head (ignore this for a head that needs no heat "
                "or a chilled head)",
            )
        for printed, head, tool_line in self.candidates:
            if head in self.no_heat or head in reported:
                continue
            reported.add(head)
            self.report(
                printed,
                f"head T{head} (selected at line {tool_line}) prints here, but no M104/M109 before this line "
                f"set its temperature, while the job does set head temperatures (line {self.first_heat}): a "
                "heated head prints cold (ignore this for a head that needs no heat: a UV pen, a laser, a "
                "room-temperature paste or bio head)",
            )


# -- HY065 ---------------------------------------------------------------------------------------------


@register
class HeadHeatedNeverSelected(Rule):
    code = "HY065"
    name = "head-heated-never-selected"
    severity = Severity.WARNING
    summary = "A head is heated and waited on (M109 T#), but no T command of the job ever selects it"
    explanation = """
        In a job that changes heads with T commands, a head prints only once a T command gives it the
        focus: "when printing with multiple heads, the requirement - to explicitly direct Repetrel's
        'focus' to a particular head" (T_v5, Default Mode), and a T command "invoke[s] all flow, prime,
        unprime, and offset parameters" of the head.  A head that the job heats and waits on with
        `M109 T#` but that no T command selects never prints: the job waits for a head it does not
        use (and keeps its material hot), or the T command that should select it is missing or names
        another head.  "Although we don't generally recommend keeping heads loaded if they will be
        unused on the current job, you might want to do this" (Explicit Mode): heat it only if it is
        used.

        Not reported in a job with no T command at all (Repetrel then focuses "the first head it
        detects", which a file does not name), nor for a head that prints through a clone squad or
        copies another head (M703 T#, T_v5).  A wait that cools a head (`M109 T1 S0`) is not a heating.
    """
    example_bad = """
        M109 T0 S215
        M109 T1 S215
        T0
        G1 X10 Y10 E1 F1200
        M30
    """
    example_good = """
        M109 T0 S215
        M109 T1 S215
        T0
        G1 X10 Y10 E1 F1200
        T1
        G1 X20 Y10 E1
        M30
    """
    source = "T_v5, Default Mode and Explicit Mode; Gcode page, M109 Wait for Temp (Head) and T Tool Change"
    codes = (ANY_T, "M109", "M703")
    families = ("hyrel",)

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.waited: dict[int, tuple[int, str]] = {}  # head position -> (first line heating it and waiting, label)
        self.selected: set[int] = set()  # positions a T command selects
        self.copies: set[int] = set()  # heads that print through a squad or copy a head (M703 T#)
        self.any_t = False

    def check(self, line: Line, cmd: Command) -> None:
        interpreter = self.ctx.interpreter
        if cmd.code == "M703":
            address = interpreter.address(cmd)
            if address is not None and address.position is not None:
                self.copies.add(address.position)
            return
        if cmd.code == "M109":
            address = interpreter.address(cmd)
            if address is None or address.kind != HEAD or address.position is None:
                return
            s = cmd.get("S")
            target = s if s is not None else self.state.targets.get(address.v5)  # type: ignore[arg-type]
            if target is not None and target > 0:
                self.waited.setdefault(address.position, (line.number, address.label))
            return
        address = interpreter.tool_command_address(cmd)
        if address is not None:
            self.any_t = True
            if address.position is not None:
                self.selected.add(address.position)

    def finish(self) -> None:
        if not self.any_t:
            return  # Default Mode: the head Repetrel focuses is not named in the file
        for head, (at, label) in sorted(self.waited.items(), key=lambda item: item[1]):
            if head in self.selected or head in self.copies:
                continue
            self.report(
                at,
                f"{label} is heated and waited on here, but no T command of the job selects it: in a job "
                "that changes heads with T commands it never prints, so the job waits for a head it does not "
                "use (or the T command for it is missing)",
            )
