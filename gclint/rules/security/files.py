"""SC004, SC005: running and changing files on the printer."""

from __future__ import annotations

import re
from collections.abc import Mapping

from gclint.context.model import CONFIGURATION, CONTENT, OPTION
from gclint.rules.base import Severity, register
from gclint.rules.security import linuxcnc
from gclint.rules.security.base import _SecurityRule
from gclint.rules.security.common import _NUMBER, _excerpt, _quote, _starts_line, _strip_comment
from gclint.syntax.nodes import Command, Line

# -- files on the printer ---------------------------------------------------------------------------------


def _file_argument(code: str, rest: str, cmd: Command | None) -> str | None:
    """The file a command names, or None when it names none (``M98 P100`` calls subprogram 100)."""
    argument = _strip_comment(rest)
    if not argument:
        return None
    if code in ("M98", "M37"):
        if cmd is not None and cmd.words:
            p = cmd.raw("P")
            if p is None:
                return None
            if p.startswith('"'):
                return p.strip('"')
            if _NUMBER.fullmatch(p):
                return None  # subprogram or macro number (Fanuc, Carvera macros/####.cnc)
        if argument[:1] in "Pp":
            value = argument[1:].strip(" \t")
            if not value or _NUMBER.fullmatch(value.split()[0]) or value.startswith("["):
                return None
            return value.strip('"')
        return argument if not _NUMBER.fullmatch(argument) else None
    if code == "M98.1" and "{" in argument:
        return argument[argument.find("{") + 1 :].rstrip("} \t")  # M98.1 L2 {gcodes/test.cnc}
    if "!" in argument:  # Marlin M32 P !/models/part.gco#
        return argument[argument.find("!") + 1 :].split("#", 1)[0]
    return argument.strip('"')


_MACRO_NUMBER = re.compile(r"[Pp][ \t]*+(\d{1,9}+)(?:\.0*+)?(?![\d.])")


def _macro_number(rest: str, cmd: Command | None) -> int | None:
    """The number of ``M98 P1234`` (a Carvera macro file, a LinuxCNC/Fanuc subprogram), or None."""
    if cmd is not None and cmd.words:
        p = cmd.raw("P")
        return int(float(p)) if p is not None and _NUMBER.fullmatch(p) and float(p) >= 0 else None
    m = _MACRO_NUMBER.match(_strip_comment(rest))
    return int(m.group(1)) if m is not None else None


_OUTSIDE = "code outside this job"


def _linuxcnc_codes() -> Mapping[str, object]:
    """The codes the Machinekit/LinuxCNC dialect defines (its FDM configuration's M104, M106, M109...)."""
    from gclint import dialects

    return dialects.get("machinekit").codes


def macro_file(ctx) -> bool:
    """Whether the file checked is one of its firmware's own macro or system files (RepRapFirmware's sys/)."""
    return ctx.dialect.macro_file is not None and ctx.dialect.macro_file(ctx.path)


def system_file(ctx) -> bool:
    return ctx.dialect.system_file is not None and ctx.dialect.system_file(ctx.path)


@register
class RunsFile(_SecurityRule):
    code = "SC004"
    name = "runs-file"
    severity = Severity.WARNING
    summary = (
        "The job runs or selects another file on the printer (M98 with a path or a macro number, M98.1, M32, M23,"
        " Klipper SDCARD_PRINT_FILE)"
    )
    explanation = """
        M98 P"file" (RepRapFirmware macros), M37 P"file" (RepRapFirmware simulates the file: its commands
        run without moving, and file commands among them still act), M98 P1234 (Carvera: the file gcodes/macros/1234.cnc), M98.1
        {path} (Carvera), M32 (select and start a file), M23 (select a file for M24) and Klipper's
        SDCARD_PRINT_FILE FILENAME=... (load a file and start it) make the firmware run a file that is not
        in this job.  What runs is whatever that file holds on the machine at print time, which this check
        cannot see; on a shared or networked printer it may have been changed.  Prefer self-contained jobs;
        when a macro is intended, silence this code for those files with per-file-ignores in the
        configuration.  A job cannot silence SC findings itself: "; noqa: SC004" and "; gclint:
        disable=SC" are ignored for the security rules.

        LinuxCNC and Machinekit run "o<name> call" (or "o100 call", or the Fanuc-style "M98 P100") from a
        subroutine already defined in the job; when none of that name is defined above the call, they
        look for the file name.ngc (100.ngc) in the folders the machine's INI file names (PROGRAM_PREFIX,
        SUBROUTINE_PATH) and run it ("Calling Files" in LinuxCNC's O-code documentation; interp_o_word.cc
        control_back_to).  Such a call, and a call whose name is computed ("o[#1] call"), is reported in
        every dialect, even when a file name.ngc is beside the job: the machine runs the one in its own folders,
        which the gate cannot see.  Define the subroutine in the job, above the call ("o100 sub").  A call of
        a subroutine the job defines below it (a Fanuc-style subprogram after its M98, as LinuxCNC's documentation
        writes them) is information: that subroutine runs unless a file of its name is in the machine's folders.
        A Fanuc-style "O100" above the call defines nothing: LinuxCNC reads it in order as a program number only, and the
        numbered subprogram "must follow the M98 call" (O-code documentation, "Fanuc-Style Numbered
        Programs"; interp_o_word.cc convert_control_functions).  M98 P with a number is reported always
        where the job may run on a Carvera (which runs gcodes/macros/<number>.cnc for it): in every dialect
        but Machinekit/LinuxCNC, and in a .cnc, .nc or .tap file the user did not set to them.  A ".ngc"
        program (LinuxCNC's own extension; a Carvera plays .nc and .cnc files) whose content reads as
        LinuxCNC/Machinekit has its M98 read as LinuxCNC reads it.

        RepRapFirmware's own configuration is macros calling macros: the firmware runs homeall.g for G28, tpre0.g for
        T0, M<n>.g for a code it does not have, and these files call each other with M98 (RepRapFirmware source,
        src/GCodes/GCodes2.cpp: M98 and the macro-file lookup).  So M98 in a RepRapFirmware system or macro file (a `.g`
        file, or a file in a `sys/` or `macros/` folder, checked as RepRapFirmware) is not reported: it runs another
        part of the same configuration.  A job that calls a macro still is.

        M100 to M199, in a job read as Machinekit/LinuxCNC, run the external program of that name from the
        machine's program folder ("M100-M199 User Defined Commands" in LinuxCNC's M-code documentation), or
        the subroutine the machine's INI file remaps the code to; the codes Machinekit's FDM configuration
        defines (M104, M106, M109, M140, M190...) are not reported.  In other dialects they are not reported
        (Marlin's M150 sets LED colours), but in a ".ngc" file, LinuxCNC's own extension, they are unless the
        user set that dialect (on the command line or in a --config) and it has the code.  M98 with a number is
        quiet only where LinuxCNC reads it (the user set Machinekit/LinuxCNC, or a ".ngc" program reads as
        theirs) and the job defines "o<number> sub" above the call: a Carvera runs
        gcodes/macros/<number>.cnc whatever the job defines.
    """
    example_bad = 'M98 P"0:/macros/prime.g"'
    example_good = """
        ; gclint-test: dialect=machinekit
        o<prime> sub
        G0 Z5
        o<prime> endsub
        o<prime> call
    """
    source = (
        "RepRap G-code page (M23, M32, M98); Carvera M-code table (M98 P####: gcodes/macros/####.cnc, M98.1, M32,"
        " M23); Klipper docs/G-Codes.md [virtual_sdcard] (SDCARD_PRINT_FILE: load a file and start SD print);"
        ' LinuxCNC docs/src/gcode/o-code.adoc "Calling Files" and src/emc/rs274ngc/interp_o_word.cc'
        " control_back_to (o<name> call of a subroutine not defined before the call: the file name.ngc)"
    )
    codes = ("M98", "M98.1", "M32", "M23", "M37", "SDCARD_PRINT_FILE", "O", "M99", *(f"M{n}" for n in range(100, 200)))

    # Subroutine names remembered per file: a job that defines more is read as if it defined none after them
    # (its later calls are reported), so memory stays bounded.
    SUBROUTINES_KEPT = 10_000

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.configuration = macro_file(ctx)
        self._subroutines: set[str] = set()  # the O-word subroutines defined so far (LinuxCNC's offset map)
        self._blocks: list[tuple[str, str]] = []  # the O-word blocks open: (label, keyword)
        self._open: dict[tuple[str, str], int] = {}  # how many of each are open
        self._fanuc = False  # within a Fanuc-style subprogram ("O100" ... M99)
        self._joined_tail = 0  # the last line LinuxCNC reads joined to lines before it (check_joined)
        self._called: set[str] = set()  # the subroutines whose outside call was reported
        # calls of subroutines not defined above them, reported once the job is read: a subroutine the job
        # defines below the call (a Fanuc-style subprogram "must follow the M98 call") is information
        self._pending: list[tuple[Line, str | None, str, int]] = []
        self._defined_anywhere: set[str] = set()
        # a job the user did not say is for LinuxCNC (on the command line or in a --config): a Carvera runs
        # gcodes/macros/<P>.cnc for its M98 P<n> whatever O-words the job defines, and LinuxCNC refuses an M98 to
        # an "o<n> sub" (interp_o_word.cc: "'O.... sub' subroutine must be called with 'O.... call'")
        self._user_set = ctx.context.origin in (OPTION, CONFIGURATION) and ctx.options.dialect_trusted
        # A ".ngc" file (LinuxCNC's own program extension; a Carvera plays .nc and .cnc) whose content reads as
        # LinuxCNC/Machinekit: its M98 P<n> is read as LinuxCNC reads it (a Fanuc-style subprogram)
        self._ngc_file = str(ctx.path or "").lower().endswith(".ngc")
        self._ngc_program = self._ngc_file and ctx.context.origin == CONTENT and not ctx.context.assumed

    def check(self, line: Line, cmd: Command) -> None:
        if cmd.code == "O":
            self._oword(line, cmd)  # (every O-word of a line: "sub" and "call" lines are read in order)
        else:
            super().check(line, cmd)

    def _oword(self, line: Line, cmd: Command) -> None:
        # LinuxCNC runs a call from its table of subroutines defined so far, else from the file name.ngc if
        # there is one, else from further down the job (interp_o_word.cc control_back_to, "#1 already
        # defined", "#2 open the File"; https://github.com/LinuxCNC/linuxcnc/blob/master/src/emc/rs274ngc/)
        keyword, name = linuxcnc.oword(line.raw, cmd)
        if keyword != "call":
            # (what the job defines: read on the lines as written, not on a firmware's view of one, and not on
            # lines LinuxCNC reads with another (a line ending in a bare carriage return, and the line after
            # such lines: check_joined); a definition on a block-delete line ("/o<x> sub") counts only when
            # the operator's block-delete switch is off, which is not known before the job runs)
            if self._view is None and line.ending != "\r" and line.number != self._joined_tail:
                self._define(keyword, name, cmd, counts=line.parsed.block_delete is None)
            return
        if name is not None and linuxcnc.looked_up(name) in self._subroutines:
            return
        label = (f"<{name}>" if not name.isdigit() else name) if name is not None else cmd.params.get("label") or ""
        label = label[:60]
        if name is not None and linuxcnc.SHELL_EXPANSION.search(name):
            what = (
                "names no subroutine defined above the call, so LinuxCNC/Machinekit hand the name to the shell's"
                " word expansion to find its file (SC001 reports what that runs)"
            )
        elif name is not None and name[:1] in "/~":
            what = (
                f"runs the file {_quote(name + '.ngc', 60)} (a path on the machine's computer) when one is there:"
                " LinuxCNC/Machinekit look for it first, since no subroutine of that name is defined above the call"
            )
        elif name is not None:
            what = (
                f"runs the file {_quote(name + '.ngc', 60)} from the machine's program or subroutine folders when one"
                " is there: LinuxCNC/Machinekit look for it first, since no subroutine of that name is defined"
                " above the call"
            )
        else:
            what = (
                "names its subroutine by an expression: LinuxCNC/Machinekit run the file of that name from the"
                " machine's program or subroutine folders unless the job defines it above the call"
            )
        if label in self._called:
            return  # (one finding per subroutine a job calls from outside it: the first call)
        if len(self._called) < self.SUBROUTINES_KEPT:
            self._called.add(label)
        self._outside_call(line, name, f"o{label} call {what}", cmd.column)

    # O-word blocks (LinuxCNC's o-code.adoc): what opens one, and what closes what ("while" closes a "do" of its
    # label, else opens a loop)
    _OPENS = frozenset({"sub", "if", "do", "while", "repeat"})
    _CLOSES = {"endsub": "sub", "endif": "if", "endwhile": "while", "endrepeat": "repeat"}

    def check_joined(self, line: Line, text: str, first: int) -> None:
        self._joined_tail = line.number  # (the engine calls this before the line's own commands are read)
        super().check_joined(line, text, first)

    def _outside_call(self, line: Line, name: str | None, what: str, column: int) -> None:
        """A call of a subroutine not defined above it (``what`` says what runs): said once the job is read."""
        if name is None or self._view is not None:  # (a computed name, or a firmware's view: said at once)
            self.report_masked(line, f"{what}: {_OUTSIDE}", column)
        else:
            self._pending.append((line, name, what, column))

    def finish(self) -> None:
        """The calls of subroutines not defined above them: information where the job defines the subroutine
        below the call (LinuxCNC runs it unless a file of that name is in its subroutine folders), a warning
        where the job does not define it at all."""
        for line, name, what, column in self._pending:
            if name is not None and linuxcnc.looked_up(name) in self._defined_anywhere:
                below = "; the job defines it below the call, which runs unless a file of that name is there"
                self.report_masked(line, what + below, column, Severity.INFO)
            else:
                self.report_masked(line, f"{what}: {_OUTSIDE}", column)
        self._pending = []
        super().finish()

    def _define(self, keyword: str, name: str | None, cmd: Command, counts: bool = True) -> None:
        """Follow the job's O-word blocks; a subroutine counts as defined above a call only where it is defined at
        the top level: in LinuxCNC a definition inside an ``if`` not taken, a loop or another subroutine's
        body is skipped with it (interp_o_word.cc: the lines of a block not run are skipped to its end), and
        whether the block runs is not known before the job runs.  A definition that may be skipped (``counts``
        False: a block-delete line) opens its block but defines nothing."""
        label = name if name is not None else linuxcnc.as_linuxcnc_reads(cmd.params.get("label") or "")
        blocks = self._blocks
        if keyword == "while" and blocks and blocks[-1] == (label, "do"):
            self._close((label, "do"))
            return
        if keyword in self._CLOSES:
            self._close((label, self._CLOSES[keyword]))
            return
        top = not blocks and not self._fanuc
        if keyword in self._OPENS:
            kept = len(self._subroutines) < self.SUBROUTINES_KEPT
            if keyword == "sub" and top and counts and name is not None and kept:
                self._subroutines.add(name)
            if keyword == "sub" and top and counts and name is not None and kept:
                self._defined_anywhere.add(name)
            blocks.append((label, keyword))
            self._open[(label, keyword)] = self._open.get((label, keyword), 0) + 1
        elif keyword == "" and label.isdigit():
            # "O100" alone starts a Fanuc-style subprogram (called by M98 P100), which M99 ends (o-code.adoc,
            # "Fanuc-Style Numbered Programs": "the numbered subprogram must follow the M98 call").  Reached in
            # order, LinuxCNC only logs "Entering Fanuc-style program number" and registers nothing
            # (interp_o_word.cc convert_control_functions, O_): a call after it still looks for 100.ngc first.
            self._fanuc = True
            if len(self._defined_anywhere) < self.SUBROUTINES_KEPT:
                self._defined_anywhere.add(label)

    def _close(self, block: tuple[str, str]) -> None:
        """Close the innermost open ``block`` and the blocks left open inside it; nothing when none is open.
        (Each block is opened once and closed once, so following a job's blocks takes linear time.)"""
        if not self._open.get(block):
            return
        while True:
            closed = self._blocks.pop()
            self._open[closed] -= 1
            if closed == block:
                return

    def _user_m_code(self, line: Line, code: str, column: int) -> None:
        """M100-M199 under the LinuxCNC interpreter, where the dialect has no code of its own by that number: the
        external program named M1nn in the machine's program folder runs ("M100-M199 User Defined Commands" in
        LinuxCNC's M-code documentation, https://linuxcnc.org/docs/html/gcode/m-code.html#mcode:m100-m199).
        A machine's INI may remap the code instead, to a subroutine file: code outside the job either way.  In a
        ".ngc" file (LinuxCNC's own program extension) read as another dialect, each is reported unless the user
        set that dialect and it has the code."""
        if not (code[:1] == "M" and code[1:].isdigit() and 100 <= int(code[1:]) <= 199):
            return  # (an "O" or "M99" a firmware's view of a line holds: no user M-code)
        dialect = self.ctx.dialect
        if dialect.semantics.user_programs:
            runs = code not in dialect.codes
        else:  # (a ".ngc" job, LinuxCNC's own extension, read as another dialect: its content chose that reading,
            # so only a dialect the user set, and that has the code, exempts it, or Machinekit's own table: M104...)
            runs = self._ngc_file and not (self._user_set and code in dialect.codes) and code not in _linuxcnc_codes()
        if runs:
            self.report_masked(
                line,
                f"{code} runs the program named {code} from the machine's program folder (a LinuxCNC/Machinekit user"
                " M-code), or the subroutine its INI file remaps it to: code outside this job",
                column,
            )

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if code == "M99":
            if self._view is None:
                self._fanuc = False
            return
        if not _starts_line(line, cmd) or (code == "M98" and self.configuration):
            return
        if code not in ("M98", "M98.1", "M32", "M23", "M37", "SDCARD_PRINT_FILE"):
            self._user_m_code(line, code, column)
            return
        if code == "SDCARD_PRINT_FILE":
            name = cmd.params.get("FILENAME") if cmd is not None else None
            target = f" {_quote(name.strip(chr(34)))}" if name else ""
            where = cmd.column if cmd is not None else 1
            self.report_masked(
                line,
                f"SDCARD_PRINT_FILE loads and starts the file{target} on a Klipper printer: code outside this job",
                where,
            )
            return
        name = _file_argument(code, rest, cmd)
        if name is None:
            number = _macro_number(rest, cmd) if code == "M98" else None
            if number is None:
                return
            linuxcnc_reads = self._user_set or self._ngc_program
            if self.ctx.dialect.semantics.effect("M98") != "call-subroutine" or not linuxcnc_reads:
                # (a Carvera always runs gcodes/macros/<P>.cnc, whatever O-words the job defines: Carvera Community
                # Firmware Player.cpp on_gcode_received, M98; a job read as LinuxCNC by its own content in a Carvera
                # file is not exempt for that)
                self.report_masked(
                    line,
                    f"M98 P{number} runs the file gcodes/macros/{number}.cnc on a Carvera: code outside this job",
                    column,
                )
            elif str(number) not in self._subroutines:
                # (as "o100 call": interp_o_word.cc execute_call)
                self._outside_call(
                    line,
                    str(number),
                    f"M98 P{number} runs the file {_quote(f'{number}.ngc')} from the machine's program or subroutine"
                    f" folders when one is there: LinuxCNC/Machinekit look for it first, since no subprogram O{number}"
                    " is defined above the call",
                    column,
                )
            return
        # (RepRapFirmware's M37 P"file" simulates the file: its commands run without moving, file commands such as
        # M28 and M30 included, and it then writes the simulated time into the file: GCodes2.cpp case 37)
        verb = {"M23": "selects", "M32": "selects and starts", "M37": "simulates (runs without moving)"}.get(
            code, "runs"
        )
        self.report_masked(line, f"{code} {verb} the file {_quote(name)} on the printer: code outside this job", column)


# RepRapFirmware 3.4 and later: "echo >file ...", ">>file" (StringParser.cpp ProcessEchoCommand: '>' opens the
# file for writing, '>>' for appending; any text starting with '>' is read as a redirect).
_ECHO_REDIRECT = re.compile(
    r"""[ \t]*+(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?echo[ \t]*+(>{1,3}+)[ \t]*+("(?:[^"\r\n]|"")*+"?|\{[^}\r\n]*+\}?|[^ \t;]*+)"""
)
_LOG_FILE = re.compile(r"(?i)\.(?:txt|log)$")
# Codes whose file effect belongs to one firmware: Smoothieware keeps settings in a config-override file
# (Smoothieware source @ bb41e992: M500 save overrides, M502 delete override file, M504 save to a named
# file; Carvera M-code table M502 "deletes config-override"), RepRapFirmware writes config-override.g
# (RepRapFirmware source, src/GCodes/GCodes2.cpp M500-M503); Marlin keeps them in EEPROM (Marlin G-code
# reference M500-M504; Prusa-Firmware-Buddy the same), so a job read as Marlin is not reported.
_CONFIG_OVERRIDE = {  # what each does on Smoothieware/Carvera
    "M500": "writes the machine's settings into its config-override file",
    "M502": "deletes the config-override file (the machine falls back to config.txt)",
    "M504": "writes the machine's settings into a named config-override file",
}
# ... and on Marlin, by the dialect's effect (Marlin G-code reference: M500 Save Settings, M502 Factory Reset,
# M504 Validate EEPROM contents)
_EEPROM = {
    "save-settings": "saves the current settings to EEPROM, where they outlive the job",
    "factory-settings": "resets the settings to the firmware's defaults (for the next job too, once saved)",
    "validate-settings": "only validates the stored settings",
}


# RepRapFirmware codes whose P names a file written, or asks for the firmware to be erased (_rrf_file_word)
_RRF_FILE_WORDS = ("G29", "M374", "M999")


def _parameter(rest: str, cmd: Command | None, letter: str) -> str | None:
    """The raw value of parameter ``letter`` of a command (a quoted string kept whole), read from ``cmd`` when
    the grammar read a value, else from its text ``rest``, in either case of the letter."""
    if cmd is not None and cmd.words and cmd.raw(letter):
        return cmd.raw(letter)
    # (not read as a value: an unquoted name, "Pconfig.g", which the grammar reads as flags)
    m = re.search(rf"""(?i)(?<![A-Z]){letter}[ \t]*+("[^"]*+"?|[^ \t;(]++)""", _strip_comment(rest))
    return m.group(1) if m is not None else None


# Codes that replace the printer's firmware: M997 firmware update in Prusa-Firmware-Buddy @ 818d812f, Marlin
# source @ 005ec919 (also M936 OTA update) and RepRapFirmware source @ fc1cd16c (src/GCodes/GCodes2.cpp).
_FIRMWARE_UPDATE = {
    "M997": "starts a firmware update (Marlin, Prusa Buddy, RepRapFirmware): a job must not replace the printer's"
    " firmware",
    "M936": "starts an over-the-air firmware update (Marlin)",
    # (M994: Marlin src/gcode/gcode.h "M994: Load SPI Flash from SD"; M993, its backup, is Bambu's nozzle camera
    # switch in Bambu jobs and writes only a backup file: not reported)
    "M994": "writes a file from the SD card into the printer's SPI flash (Marlin: its settings, fonts and images)",
}


@register
class ChangesPrinterFiles(_SecurityRule):
    code = "SC005"
    name = "changes-printer-files"
    severity = Severity.ERROR
    summary = (
        "The job deletes, writes or renames files on the printer, or replaces its firmware (M30 <file>, M28, M471,"
        " M472, M559, M560, echo >file, M928/M929 into a non-log file, M500/M502/M504, M505, M997, M936, Klipper"
        ' SAVE_CONFIG and SAVE_VARIABLE, G29 S3 P<file>, M374 P<file>, M999 P"ERASE", LinuxCNC (LOGOPEN,file),'
        " (LOGAPPEND,file), (LOG,text), (PROBEOPEN file))"
    )
    explanation = """
        In Marlin and RepRapFirmware "M30 file" deletes that file from the SD card, M28 writes the
        following lines into a file instead of running them (M28 /sys/config.g replaces the printer's
        configuration), M471 renames or moves a file, M472 deletes one and M559/M560 upload configuration
        or web files.  RepRapFirmware 3.4 and later write the text of "echo >"file" ..." into a file
        (">>" appends), so "echo >"0:/sys/config.g" "M112"" replaces the configuration; "M929 P"file" S1"
        logs into a file, which in a .g file puts log lines into a macro the printer runs (log files
        ending in .txt or .log are not reported).  On Smoothieware (Carvera) M500 writes the
        config-override file, M502 deletes it and M504 writes a named one (RepRapFirmware's M500 writes
        config-override.g); they are Marlin's EEPROM settings, and not reported, only where the dialect is
        set to Marlin on the command line or in the configuration: a job that reads as Marlin ("M106
        S255") may still run on a Carvera, where M502 deletes the config override.
        Klipper's SAVE_CONFIG overwrites the printer's config file and restarts the host, and SAVE_VARIABLE
        writes a variable to disk.  Marlin's M928 logs the commands that follow into a named file on the SD
        card (a .txt or .log file is not reported, as for M929); RepRapFirmware's M505 makes another folder
        the system folder, so the printer reads its config.g from there; M997 (Marlin, Prusa, RepRapFirmware)
        and M936 (Marlin) update the firmware.  RepRapFirmware's "G29 S3 P"file"" and "M374 P"file"" save
        the height map into the file named (P"config.g" replaces the configuration), and "M999 P"ERASE""
        erases the firmware as the printer restarts.

        LinuxCNC and Machinekit act on comments (interp_convert.cc convert_comment, in every dialect):
        "(LOGOPEN,file)" truncates a file on the controller PC and "(LOGAPPEND,file)" appends to one, and
        each "(LOG,text)" then writes its text there ("(LOGOPEN,/home/cnc/.bashrc)" then "(LOG,curl ...
        | sh)"); "(PROBEOPEN file)" overwrites a file with probed points.  They are read in any case (but
        PROBEOPEN, which LinuxCNC compares in upper case), after leading blanks, in parentheses or after
        ";".

        A job that changes the printer's files outlives the print: it can break the next job, the
        machine's limits or its safety settings.  Plain "M30" (end of program) is fine, as are a bare M471
        or M472 (on the Carvera they pair the wireless probe and switch its laser on); any text after M30
        is a file name to Marlin, words included ("M30 X1" deletes the file X1).  In a job read as
        Hyrel, M30 is "End of Program" and takes no file, but the finding stays: the dialect is read from
        the job itself, and a job that names a file after M30 deletes it wherever Marlin or RepRapFirmware
        runs it.  The same holds for RepRapFirmware system and macro files: a macro package that writes
        its own files is reported, and a configuration repository silences this code for those files
        with per-file-ignores.

        Smoothieware (Carvera) runs every G and M code of a line, so "G0 X0 M502" is reported (on the
        M502) in every dialect; the dialect's own exemptions still hold.
    """
    example_bad = "M30 /sys/config.g"
    example_good = "M30"
    source = (
        "RepRap G-code page (M28, M30, M471, M559, M560); RepRapFirmware source @ fc1cd16c,"
        " src/GCodes/GCodes2.cpp (M472 delete, M929 logging, M500-M503 config-override, M505 set system folder,"
        " M997 firmware update) and StringParser.cpp ProcessEchoCommand (echo >file, >>file); Smoothieware"
        " source @ bb41e992 (M500, M502 delete override file, M504; GcodeDispatch.cpp splits a line at each"
        " G/M); Klipper docs/G-Codes.md [configfile] SAVE_CONFIG and [save_variables] SAVE_VARIABLE;"
        " Prusa-Firmware @ 0c9bf5d4 (M928 SD logging into a file); Marlin source @ 005ec919 (M928, M997"
        " firmware update, M936 OTA update); Prusa-Firmware-Buddy @ 818d812f (M997); Marlin src/gcode/parser.cpp"
        " GCodeParser::parse (M23, M28, M30: the rest of the line is the file name); LinuxCNC"
        " src/emc/rs274ngc/interp_convert.cc convert_comment, src/emc/task/emccanon.cc COMMENT (PROBEOPEN),"
        ' docs/src/gcode/overview.adoc "Comments", "Logging", "Probe Logging"; RepRapFirmware'
        ' src/GCodes/GCodes2.cpp (G29 S3 and M374 save the height map to the file P names; M999 P"ERASE")'
    )
    on_comment = True  # (LinuxCNC's logging comments)
    comment_hint = staticmethod(linuxcnc.may_be_active)
    active_comments = linuxcnc.FILE_WRITES
    codes = (
        "M30",
        "M28",
        "M471",
        "M472",
        "M559",
        "M560",
        "M929",
        "M500",
        "M502",
        "M504",
        "echo",
        "SAVE_CONFIG",
        "SAVE_VARIABLE",
        "M928",
        "M505",
        "M997",
        "M936",
        "M994",
        "G29",
        "M374",
        "M999",
    )

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._echoed: set[tuple[str, str]] = set()  # the files an "echo >" was reported for (mode, file)
        # M500/M502/M504 are the EEPROM settings only where the dialect says Marlin and the user said so:
        # a job chooses what it is detected as, and on a Carvera M502 deletes the config override.
        self.settings_in_eeprom = (
            ctx.dialect.semantics.effect("M502") == "factory-settings"
            and ctx.context.origin in (OPTION, CONFIGURATION)
            and ctx.options.dialect_trusted  # (not a configuration found beside the job: a change can add one)
        )

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if not _starts_line(line, cmd):
            return
        if code == "echo":
            self._echo(line, cmd.column if cmd is not None else 1)
            return
        if code in ("SAVE_CONFIG", "SAVE_VARIABLE"):
            where = cmd.column if cmd is not None else 1
            what = (
                "overwrites the printer's config file and restarts Klipper"
                if code == "SAVE_CONFIG"
                else "writes a variable to the printer's [save_variables] file"
            )
            self.report_masked(line, f"{code} {what}", where)
            return
        if code in _FIRMWARE_UPDATE:
            self.report_masked(line, f"{code} {_FIRMWARE_UPDATE[code]}{_excerpt(rest)}", column)
            return
        if code in _RRF_FILE_WORDS:
            self._rrf_file_word(line, code, rest, column, cmd)
            return
        if code in _CONFIG_OVERRIDE:
            if not self.settings_in_eeprom:
                self.report_masked(line, self._settings_message(code), column)
            return
        argument = re.sub(r"\*\d+\s*$", "", _strip_comment(rest))  # (a "*99" checksum is no file name)
        if code in ("M30", "M28"):
            if not argument.strip():
                return
            # (Marlin reads everything after M23, M28, M30 as the file name: "M30 X1" deletes the file X1;
            # https://github.com/MarlinFirmware/Marlin/blob/bugfix-2.1.x/Marlin/src/gcode/parser.cpp
            # GCodeParser::parse, "Only use string_arg for these M codes")
            action = "deletes" if code == "M30" else "writes the following lines into"
            printer = "on the printer"
            if code == "M30" and self.ctx.dialect.semantics.effect("M30") == "end-of-job":
                # the dialect is read from the job, which an attacker writes: the gate does not rest on it
                printer = "on a Marlin or RepRapFirmware printer (on Hyrel, M30 ends the program and takes no file)"
            self.report_masked(line, f"{code} {action} the file {_quote(argument.strip(chr(34)))} {printer}", column)
            return
        if code == "M929":
            self._logging(line, argument, column, cmd)
            return
        if code == "M928":
            name = argument.strip().strip('"')
            if name and not (_LOG_FILE.search(name) and "{" not in name):  # (as M929: a .txt/.log file is a log)
                self.report_masked(
                    line,
                    f"M928 starts logging the commands that follow into the file {_quote(name)}"
                    " on the printer's SD card (Marlin, Prusa MK3)",
                    column,
                )
            return
        if code == "M505":
            self.report_masked(
                line,
                f"M505 moves RepRapFirmware's system folder{_excerpt(argument)}: the printer then reads config.g and"
                " its other system files from there",
                column,
            )
            return
        if code in ("M471", "M472") and not argument.strip():
            return  # Carvera: pair the wireless probe, switch its laser on
        action = {
            "M471": "renames or moves a file",
            "M472": "deletes a file",
            "M559": "uploads a configuration file",
            "M560": "uploads a web file",
        }[code]
        self.report_masked(line, f"{code} {action} on the printer{_excerpt(argument)}", column)

    def _rrf_file_word(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        """RepRapFirmware's height map saved into a file the job names (G29 S3 P"file", M374 P"file":
        GCodes2.cpp case 29 "save height map to names file" and case 374, GCodes6.cpp SaveHeightMap), which
        replaces what the file held ("config.g"), and M999 P"ERASE", which erases the firmware (GCodes2.cpp
        case 999, ExceptionHandlers.cpp SoftwareReset).  Read in any case, quoted or not."""
        p = _parameter(rest, cmd, "P")
        if p is None:
            return
        value = p.strip('"')
        if code == "M999":
            # (an expression, "P{"ERASE"}" or "P{var.e}", gives the string GetQuotedString compares: reported too)
            if value.upper() == "ERASE" or "{" in p:
                self.report_masked(
                    line,
                    f"M999 P{p} erases the firmware of a RepRapFirmware printer as it restarts"
                    + (' (when its expression gives "ERASE")' if "{" in p else "")
                    + ": the printer has none until it is flashed again",
                    column,
                )
            return
        if not value or _NUMBER.fullmatch(value):
            return  # (Marlin's G29 P1 is a phase number, not a file)
        if code == "G29":
            s_value = _parameter(rest, cmd, "S")
            if s_value is None or not _NUMBER.fullmatch(s_value) or float(s_value) != 3:
                return
        self.report_masked(
            line,
            f"{code} writes the height map into the file {_quote(value)} on a RepRapFirmware printer, replacing what"
            " it held",
            column,
        )

    def check_issues(self, line: Line) -> None:
        super().check_issues(line)
        if any(c.code == "echo" for c in line.parsed.commands):
            return  # already seen by check()
        if "echo" in line.raw:
            self._echo(line, 1)

    def _settings_message(self, code: str) -> str:
        """What ``code`` does: on the reading's own firmware first where it keeps its settings in EEPROM
        (Marlin), then on Smoothieware/Carvera, which a job read as Marlin may still run on."""
        own = _EEPROM.get(self.ctx.dialect.semantics.effect(code) or "")
        carvera = _CONFIG_OVERRIDE[code]
        if own is not None:
            return f"{code} ({self.ctx.dialect.name}) {own}; on a Smoothieware (Carvera) controller it {carvera}"
        rrf = " (RepRapFirmware: config-override.g)" if code == "M500" else ""
        return f"{code} {carvera} on Smoothieware/Carvera{rrf}"

    def _echo(self, line: Line, column: int) -> None:
        m = _ECHO_REDIRECT.match(line.raw)
        if m is None:
            return
        mode = "appends its text to" if len(m.group(1)) > 1 else "writes its text into"
        target = f" {_quote(m.group(2).strip(chr(34)))}" if m.group(2).strip('"') else ""
        if (mode, target) in self._echoed:
            return  # (one finding per file a job writes or appends to: the first echo)
        if len(self._echoed) < 1000:
            self._echoed.add((mode, target))
        self.report_masked(
            line, f"echo {m.group(1)} {mode} the file{target} on a RepRapFirmware printer (3.4 and later)", column
        )

    def _logging(self, line: Line, argument: str, column: int, cmd: Command | None) -> None:
        if cmd is not None and cmd.words:
            target, level = cmd.raw("P"), cmd.raw("S")
        else:
            m_p = re.search(r"""(?i)P[ \t]*+("[^"]*+"?|\S+)""", argument)
            m_s = re.search(r"(?i)S[ \t]*+(\S+)", argument)
            target, level = (m_p.group(1) if m_p else None), (m_s.group(1) if m_s else None)
        if target is None or (level is not None and _NUMBER.fullmatch(level) and float(level) == 0):
            return  # the default log file (eventlog.txt), or logging stopped
        name = target.strip('"')
        if _LOG_FILE.search(name) and "{" not in name:
            return
        self.report_masked(
            line,
            f"M929 logs into the file {_quote(name)}: log lines written into a file the printer runs (a .g macro)"
            " become G-code",
            column,
        )
