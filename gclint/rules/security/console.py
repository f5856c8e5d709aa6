"""SC003: lines the Smoothieware (Carvera) console runs."""

from __future__ import annotations

import re

from gclint.rules.base import Severity, register
from gclint.rules.security.base import _SecurityRule
from gclint.rules.security.common import _quote, _strip_comment
from gclint.syntax.nodes import ASSIGNMENT, GCODE, IMPLICIT, META, OWORD, Command, Line

# -- the Smoothieware console (Carvera) ------------------------------------------------------------------

# Smoothieware's console: a line whose first character is a lower-case letter or "$" goes to SimpleShell
# (and to the player's own commands); G-code starts with an upper-case letter.  Carvera Community Firmware,
# src/modules/utils/simpleshell/SimpleShell.cpp (on_console_line_received: "ignore anything that is not
# lowercase or a $"; commands_table, matched by prefix with strncasecmp) and src/modules/utils/player/
# Player.cpp (on_main_loop feeds every line of a played file to ON_CONSOLE_LINE_RECEIVED; play, buffer,
# upload, download, goto, abort, suspend, resume); Smoothieware source @ bb41e992, SimpleShell.cpp.
CONSOLE_START = frozenset("abcdefghijklmnopqrstuvwxyz$")
# What the shell runs for a first word (exact matches first, then SimpleShell's table in its order: a word
# runs the first entry it starts with).
_CONSOLE_EXACT = {
    "config-get": "reads a configuration value",
    "config-set": "changes the configuration on the SD card",
    "config-load": "loads a configuration",
    "config-get-all": "reads the configuration",
    "config-restore": "restores a saved configuration",
    "config-default": "restores the default configuration",
    "play": "plays another file",
    "progress": "reports progress",
    "abort": "aborts the running file",
    "suspend": "suspends the running file",
    "resume": "resumes the running file",
    "buffer": "queues a console command to run",
    "upload": "writes a file to the SD card",
    "download": "sends a file from the SD card",
    "goto": "jumps to a line of the running file",
    "laser": "drives the laser module",
}
_CONSOLE_TABLE = (
    ("ls", "lists files"),
    ("cd", "changes folder"),
    ("pwd", "prints the folder"),
    ("cat", "prints a file"),
    ("echo", "prints its text"),
    ("rm", "deletes a file"),
    ("mv", "moves or renames a file"),
    ("mkdir", "creates a folder"),
    ("reset", "restarts the controller"),
    ("dfu", "starts a firmware update"),
    ("break", "stops the controller in its debugger"),
    ("help", "prints help"),
    ("ftype", "reports the file type"),
    ("version", "prints the version"),
    ("mem", "prints memory use"),
    ("get", "reads machine state"),
    ("set_temp", "sets a temperature"),
    ("switch", "switches an output"),
    ("net", "reports the network"),
    ("ap", "configures the WiFi access point"),
    ("wlan", "configures the WiFi network"),
    ("diagnose", "runs diagnostics"),
    ("sleep", "puts the machine to sleep"),
    ("power", "switches power"),
    ("load", "loads a configuration override"),
    ("save", "writes a configuration override file"),
    ("remount", "remounts the SD card"),
    ("calc_thermistor", "computes thermistor values"),
    ("thermistors", "lists thermistors"),
    ("md5sum", "hashes a file"),
    ("time", "sets the clock"),
    ("test", "runs a hardware test"),
    ("model", "sets the machine model"),
    ("check_5th", "tests the 5th axis"),
    ("check_4th", "tests the 4th axis"),
    ("check_led", "tests the lights"),
    ("fset", "sets a factory value"),
    ("enable_4th_hd", "enables the 4th axis"),
    ("disable_4th_hd", "disables the 4th axis"),
)
# RepRapFirmware's meta commands: lower-case words that RepRapFirmware itself runs (RepRapFirmware
# source @ fc1cd16c, src/GCodes/GCodeBuffer/StringParser.cpp ProcessConditionalGCode).
_FIRST_TOKEN = re.compile(r"[^ \t;(]*")
_LETTERS = re.compile("[A-Za-z]*")


def console_command(token: str) -> str | None:
    """What Smoothieware's console does with a line starting with ``token``, or None when the community
    firmware's tables have no command for it (modules and other versions add their own)."""
    low = token.lower()
    if low in _CONSOLE_EXACT:
        return _CONSOLE_EXACT[low]
    if low.startswith("$"):
        return "runs a grbl command (home, unlock, jog, switch...)"
    for name, what in _CONSOLE_TABLE:
        if low.startswith(name):
            return what
    return None


@register
class ShellPassThrough(_SecurityRule):
    code = "SC003"
    name = "shell-pass-through"
    severity = Severity.ERROR
    summary = "A line Smoothieware/Carvera runs as a console command that acts (rm, play, config-set, $X, M1000...)"
    explanation = """
        The Carvera (Smoothieware) plays a file by handing every line to its console, and the console
        (SimpleShell and the player) runs any line that starts with a lower-case letter or "$" as a
        command: "rm /sd/config.txt" deletes the configuration, "mv" moves files, "play" runs another
        file, "upload" writes one, "config-set" changes settings, "buffer" queues a console command,
        "reset" and "dfu" restart the controller, "$X" unlocks an alarm.  "M1000 <command>" hands the
        lower-cased command to the same shell.  A job has no business running console commands; one line
        can erase the machine's configuration or other jobs.  Do file and configuration work from the
        controller's console, not from G-code.

        Only the commands the community firmware's tables list are reported: a lower-case word the shell has
        no command for does nothing there (a Klipper macro such as "print_start", a lower-case "n0080" line
        number).  Such a line is never G-code on the Carvera, so it is reported in every dialect (a job that runs
        on a Carvera can claim any flavour), with these exceptions, where the dialect documents the line
        as something else: RepRapFirmware's meta commands ("if", "while", "var", "set", "abort",
        "break"...) in a job read as RepRapFirmware, and lower-case G-code words, "n" line numbers, O-words
        and parameter assignments in a job read as Machinekit/LinuxCNC (which reads words in any case).  GRBL's
        system commands ("$H", "$X", "$J=") in a job read as generic (they are what made it so: a GRBL
        machine's own commands) are information only: a normal GRBL job passes the gate.
        "echo" is not
        reported: both firmwares only print its text (RepRapFirmware's "echo >file" writes a file:
        SC005).  Note that "break" and "abort" do something else on a Carvera (stop in the debugger, abort
        the job), and that Klipper reads its commands in any case, so write them in upper case.  Lines
        that start with a space or tab are not sent to the shell (SimpleShell reads the first character
        as it is).
    """
    example_bad = "rm /sd/config.txt"
    example_good = "M1000"
    source = (
        "Carvera M-code table: M1000 pass-through to the simpleshell; Smoothieware source @ bb41e992,"
        " SimpleShell.cpp (console commands); Carvera Community Firmware"
        " SimpleShell.cpp and Player.cpp (every played line goes to the console)"
    )
    codes = ("M1000",)
    on_line_starting_with = CONSOLE_START

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        argument = _strip_comment(rest)
        if argument:
            self.report_masked(
                line,
                f"M1000 passes {_quote(argument)} to the controller's shell: a job must not run console commands",
                column,
            )

    def check_line(self, line: Line) -> None:
        raw = line.raw
        token = _FIRST_TOKEN.match(raw).group(0)  # type: ignore[union-attr]
        if token == "echo" or self._documented_otherwise(line, token):
            return
        what = console_command(token)
        if what is None:
            # a word the shell has no command for does nothing there ("command not found"): a Klipper macro
            # (print_start), a lower-case line number (n0080), a word; only what the tables say acts is reported
            return
        raw = line.raw
        if any(m.contains in raw and re.search(m.pattern, raw) for m in self.ctx.dialect.detection.line_marks):
            # a line of the machines the reading describes (GRBL's $H, $X, $J= in a job read as generic): their
            # own command, which only a Carvera would run as its console's
            self.report_masked(
                line,
                f"{_quote(token, 40)} is a GRBL system command here; a Smoothieware (Carvera) controller would"
                f" run it as a console command (it {what})",
                1,
                Severity.INFO,
            )
            return
        self.report_masked(
            line,
            f"Smoothieware (Carvera) runs this line as the console command {_quote(token, 40)}: it {what};"
            " a job must not run console commands",
            1,
        )

    def _documented_otherwise(self, line: Line, token: str) -> bool:
        dialect = self.ctx.dialect
        parsed = line.parsed
        commands = parsed.commands
        if parsed.issues:
            return False
        if dialect.meta_keywords:  # (RepRapFirmware's meta commands)
            return bool(commands) and commands[0].kind == META and token in dialect.meta_keywords
        if dialect.owords and not dialect.console:  # (LinuxCNC's language: $ spindles, N-numbered comments)
            if token[:1] == "$" and not token[1:2].isdigit():
                return False  # ("$1" is LinuxCNC's spindle word)
            if not commands:
                return parsed.line_number is not None  # "n100 (a comment)"
            if _LETTERS.match(token).end() > 1 and console_command(token) is not None:  # type: ignore[union-attr]
                # ("dfup[1]": LinuxCNC's D word, but SimpleShell matches command names by prefix and runs dfu;
                # a LinuxCNC word is one letter, never followed by more letters)
                return False
            return commands[0].kind in (GCODE, IMPLICIT, OWORD, ASSIGNMENT)
        return False
