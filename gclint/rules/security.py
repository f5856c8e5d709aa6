"""SC: security.  Commands that make the host or the printer run programs or touch files, and secrets left
in the job.

A G-code job is data that comes from elsewhere (a slicer, a colleague, a download, a print farm queue) and
is run by software with access to the machine and, on Hyrel printers, to the Windows PC running Repetrel.
These rules apply to every dialect: a hostile job can claim any flavour in its header, so the check does not
trust the dialect.  Messages and ``Finding.source`` go through ``gclint.secrets.mask``.

Lines the grammar cannot parse (``M0 SHELL C:\\x.exe`` without a ``;``, ``M1000 rm -rf /sd``) are still
read: each rule also looks at the start of lines with a parse error.
"""

from __future__ import annotations

import re

from gclint import secrets
from gclint.rules.base import Rule, Severity, register
from gclint.syntax.nodes import Command, Comment, Line

# "M792", "N10 M0", "/M98", "m0792": the code at the start of a line the grammar could not parse.
_LEADING_CODE = re.compile(
    r"[ \t]*+(?:/[ \t]*+)?(?:[Nn][ \t]*+\d{1,12}+[ \t]*+)?([Mm])[ \t]*+(\d{1,8}+(?:\.\d{1,4}+)?)(?![\d.])"
)
_NUMBER = re.compile(r"[-+]?\d+(?:\.\d*)?")


def _code(letter: str, number: str) -> str:
    whole, _, frac = number.partition(".")
    frac = frac.rstrip("0")
    return letter.upper() + (whole.lstrip("0") or "0") + ("." + frac if frac else "")


_PAREN_COMMENT = re.compile(r"\([^)\r\n]*+(?:\)|$)")


def _strip_comment(text: str) -> str:
    """``text`` without its comments (``;`` to the end, ``(...)``): the argument of a command."""
    cut = text.find(";")
    if cut >= 0:
        text = text[:cut]
    if "(" in text:
        text = _PAREN_COMMENT.sub("", text)
    return text.strip(" \t")


def _starts_line(line: Line, cmd: Command | None) -> bool:
    """Marlin and RepRapFirmware run the first command of a line; "(note about M30 ...)" is prose."""
    return cmd is None or line.parsed.commands[0] is cmd


class _SecurityRule(Rule):
    """Listens to ``codes`` on parsed lines and, on lines with a parse error, to the code that starts the line.

    Subclasses implement ``inspect(line, code, rest, column, cmd)``: ``rest`` is the line's text after the
    code word (comments included), ``column`` the 1-based column where ``rest`` starts, ``cmd`` the parsed
    command or None.
    """

    on_issue = True

    def check(self, line: Line, cmd: Command) -> None:
        word = cmd.word
        start = word.end_column if word is not None else cmd.column
        self.inspect(line, cmd.code or "", line.raw[start - 1 :], start, cmd)

    def check_issues(self, line: Line) -> None:
        if line.parsed.commands and any(c.code in self.codes for c in line.parsed.commands):
            return  # already seen by check()
        m = _LEADING_CODE.match(line.raw)
        if m is None:
            return
        code = _code(m.group(1), m.group(2))
        if code in self.codes:
            self.inspect(line, code, line.raw[m.end() :], m.end() + 1, None)

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        raise NotImplementedError

    def report_masked(self, line: Line, message: str, column: int, severity: Severity | None = None) -> None:
        """Report with the message and the source line masked (no secret reaches any output)."""
        self.report(line, secrets.mask(message), column=column, severity=severity)
        finding = self.ctx.findings[-1]
        if finding.line == line.number and finding.source is not None:
            finding.source = secrets.mask(finding.source)  # (the line, or its beginning for a very long one)


# -- Repetrel host actions (Hyrel M0 / M792) ------------------------------------------------------------

_ACTION_SPLIT = re.compile(r"[;()]")


def host_actions(rest: str) -> list[tuple[str, str, int]]:
    """The Repetrel actions in the text after ``M0``/``M792``: ``(KEYWORD, argument, offset)``.

    The Hyrel page writes them after ``;``, one per segment: ``M0 ; SAY Hello Wilbur ; PIC C:\\mr_ed.png``.
    A segment is an action when its first word is one of SAY, PIC, VID, SEND, BEEP, SHELL (any case);
    ``offset`` is where the keyword starts in ``rest``.
    """
    out = []
    pos = 0
    for segment in _ACTION_SPLIT.split(rest):
        stripped = segment.lstrip(" \t")
        keyword = stripped.split(None, 1)[0].upper() if stripped.strip() else ""
        if keyword in ("SAY", "PIC", "VID", "SEND", "BEEP", "SHELL"):
            argument = stripped[len(keyword) :].strip(" \t")
            out.append((keyword, argument, pos + len(segment) - len(stripped)))
        pos += len(segment) + 1
    return out


@register
class HostRunsProgram(_SecurityRule):
    code = "SC001"
    name = "host-runs-program"
    severity = Severity.ERROR
    summary = "The job makes the host computer run a program (M0/M792 SHELL, Klipper RUN_SHELL_COMMAND)"
    explanation = """
        Repetrel's M0 and M792 take actions after the command; "SHELL C:\\program.exe" makes the PC that
        drives the printer execute that file, with the rights of the user running Repetrel.  Klipper's
        gcode_shell_command extension does the same on the printer's host with RUN_SHELL_COMMAND.  A
        G-code job is data: it must not start programs.  Anyone who can hand you a job file (a download,
        a shared folder, a print farm queue) could otherwise run anything on that computer.  Remove the
        action; if a program really must run around a job, start it from the host, not from the file.
    """
    example_bad = "M792 ; SHELL C:\\program.exe"
    example_good = "M792 ; BEEP"
    source = (
        "Gcode page, M0 Stop Until Resume and M792 Execute Action"
        " (SHELL C:\\program.exe - the computer will execute the file)"
    )
    codes = ("M0", "M792", "RUN_SHELL_COMMAND")

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if code == "RUN_SHELL_COMMAND":
            where = cmd.column if cmd is not None else 1
            self.report_masked(
                line, f"RUN_SHELL_COMMAND runs a shell command on the printer's host{_excerpt(rest)}", where
            )
            return
        for keyword, argument, offset in host_actions(rest):
            if keyword == "SHELL":
                target = f" {_quote(argument)}" if argument else ""
                self.report_masked(
                    line,
                    f"{code} SHELL makes the host computer execute{target}: a job file must not run programs",
                    column=column + offset,
                )


@register
class HostOpensFile(_SecurityRule):
    code = "SC002"
    name = "host-opens-file"
    severity = Severity.WARNING
    summary = "The job makes the host open a file named in the job (M0/M792 PIC or VID)"
    explanation = """
        "M792 ; PIC C:\\sample.jpg" and "VID C:\\sample.mp4" make Repetrel open and show a file from the
        host computer's disk, chosen by whoever wrote the job.  That is usually harmless (a picture of
        the next step), but it reads files outside the job, and a crafted media file is a classic way into
        a viewer.  Check that the path is one you expect; a job from someone else should not name files
        on your computer.
    """
    example_bad = "M0 ; PIC C:\\mr_ed.png"
    example_good = "M0 ; SAY Load the blue filament"
    source = "Gcode page, M0 Stop Until Resume and M792 Execute Action (PIC, VID)"
    codes = ("M0", "M792")

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        for keyword, argument, offset in host_actions(rest):
            if keyword in ("PIC", "VID"):
                what = "image" if keyword == "PIC" else "video"
                target = f" {_quote(argument)}" if argument else ""
                self.report_masked(
                    line,
                    f"{code} {keyword} makes the host open the {what}{target} from its own disk",
                    column=column + offset,
                )


@register
class ShellPassThrough(_SecurityRule):
    code = "SC003"
    name = "shell-pass-through"
    severity = Severity.ERROR
    summary = "Carvera/Smoothieware M1000 passes the rest of the line to the controller's shell"
    explanation = """
        On the Carvera (Smoothieware), "M1000 <command>" hands the raw, lower-cased command to the
        controller's simple shell: the same console that deletes, moves and writes files on the SD card
        ("rm", "mv", "config-set").  A job has no business running console commands; one line can erase
        the machine's configuration or other jobs.  Do file and configuration work from the controller's
        console, not from G-code.
    """
    example_bad = "M1000 rm /sd/config.txt"
    example_good = "M1000"
    source = "Carvera M-code table (seeds/carvera-mcodes.md): M1000 pass-through to the simpleshell"
    codes = ("M1000",)

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        argument = _strip_comment(rest)
        if argument:
            self.report_masked(
                line,
                f"M1000 passes {_quote(argument)} to the controller's shell: a job must not run console commands",
                column,
            )


# -- files on the printer ---------------------------------------------------------------------------------


def _file_argument(code: str, rest: str, cmd: Command | None) -> str | None:
    """The file a command names, or None when it names none (``M98 P100`` calls subprogram 100)."""
    argument = _strip_comment(rest)
    if not argument:
        return None
    if code == "M98":
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


def _reprap_configuration(path: str) -> bool:
    """Whether ``path`` is a RepRapFirmware system or macro file: ``.g``, or under ``sys/`` or ``macros/``."""
    parts = path.replace("\\", "/").lower().split("/")
    return parts[-1].endswith(".g") or "sys" in parts[:-1] or "macros" in parts[:-1]


@register
class RunsFile(_SecurityRule):
    code = "SC004"
    name = "runs-file"
    severity = Severity.WARNING
    summary = "The job runs or selects another file on the printer (M98 with a path, M98.1, M32, M23)"
    explanation = """
        M98 P"file" (RepRapFirmware macros), M98.1 {path} (Carvera), M32 (select and start a file) and
        M23 (select a file for M24) make the firmware run a file that is not in this job.  What runs is
        whatever that file holds on the machine at print time, which this check cannot see; on a shared or
        networked printer it may have been changed.  Prefer self-contained jobs; when a macro is
        intended, silence this code for those files with per-file-ignores in the configuration.  A job
        cannot silence SC findings itself: "; noqa: SC004" and "; gclint: disable=SC" are ignored for the
        security rules.

        RepRapFirmware's own configuration is macros calling macros: the firmware runs homeall.g for G28,
        tpre0.g for T0, M<n>.g for a code it does not have, and these files call each other with M98
        (research/firmware_codes.md section 6).  So M98 in a RepRapFirmware system or macro file (a `.g`
        file, or a file in a `sys/` or `macros/` folder, checked as RepRapFirmware) is not reported: it
        runs another part of the same configuration.  A job that calls a macro still is.
    """
    example_bad = 'M98 P"0:/macros/prime.g"'
    example_good = "M98 P100 L2"
    source = "RepRap G-code page (M23, M32, M98); Carvera M-code table (M98, M98.1, M32, M23)"
    codes = ("M98", "M98.1", "M32", "M23")

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self.configuration = ctx.dialect.name == "reprap" and _reprap_configuration(ctx.path)

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if not _starts_line(line, cmd) or (code == "M98" and self.configuration):
            return
        name = _file_argument(code, rest, cmd)
        if name is None:
            return
        verb = {"M23": "selects", "M32": "selects and starts"}.get(code, "runs")
        self.report_masked(line, f"{code} {verb} the file {_quote(name)} on the printer: code outside this job", column)


@register
class ChangesPrinterFiles(_SecurityRule):
    code = "SC005"
    name = "changes-printer-files"
    severity = Severity.ERROR
    summary = "The job deletes, writes or renames files on the printer (M30 <file>, M28, M471, M559, M560)"
    explanation = """
        In Marlin and RepRapFirmware "M30 file" deletes that file from the SD card, M28 writes the
        following lines into a file instead of running them (M28 /sys/config.g replaces the printer's
        configuration), M471 renames or moves a file and M559/M560 upload configuration or web files.
        A job that changes the printer's files outlives the print: it can break the next job, the
        machine's limits or its safety settings.  Plain "M30" (end of program) is fine.  In a job read as
        Hyrel, M30 is "End of Program" and takes no file, but the finding stays: the dialect is read from
        the job itself, and a job that names a file after M30 deletes it wherever Marlin or RepRapFirmware
        runs it.
    """
    example_bad = "M30 /sys/config.g"
    example_good = "M30"
    source = "RepRap G-code page (M28, M30, M471, M559, M560)"
    codes = ("M30", "M28", "M471", "M559", "M560")

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if not _starts_line(line, cmd):
            return
        argument = re.sub(r"\*\d+\s*$", "", _strip_comment(rest))  # (a "*99" checksum is no file name)
        if code in ("M30", "M28"):
            if not argument.strip():
                return
            if code == "M30" and cmd is not None and cmd.words and not any(w.kind == "string" for w in cmd.words):
                return  # "M30 P1": parameter words, no file name
            action = "deletes" if code == "M30" else "writes the following lines into"
            where = "on the printer"
            if code == "M30" and self.ctx.dialect.family == "hyrel":
                # the dialect is read from the job, which an attacker writes: the gate does not rest on it
                where = "on a Marlin or RepRapFirmware printer (on Hyrel, M30 ends the program and takes no file)"
            self.report_masked(line, f"{code} {action} the file {_quote(argument.strip(chr(34)))} {where}", column)
            return
        action = {
            "M471": "renames or moves a file",
            "M559": "uploads a configuration file",
            "M560": "uploads a web file",
        }[code]
        self.report_masked(line, f"{code} {action} on the printer{_excerpt(argument)}", column)


# -- secrets ------------------------------------------------------------------------------------------------


@register
class LeakedSecret(_SecurityRule):
    code = "SC006"
    name = "leaked-secret"
    severity = Severity.ERROR
    summary = "A password, API key or token is left in the job (slicer settings, URLs, WiFi setup)"
    explanation = """
        Slicers append their settings to the job as comments, and some have written the print host's
        credentials there ("; printhost_apikey = ...", "; printhost_password = ..."; OctoPrint's File
        Check warns about the same leak).  URLs with "user:password@", bearer tokens, API keys and
        RepRapFirmware's M587 WiFi password end up in start G-code the same way.  A job file is copied to
        print farms, shared folders and git: whoever gets it gets the secret.  Remove it, clear the field
        in the slicer's printer settings, and revoke the key.  gclint masks the value in every report.
    """
    example_bad = "; printhost_apikey = 0123456789ABCDEF0123456789ABCDEF"
    example_good = "; printhost_apikey = "
    source = "research/anchors.md: OctoPrint File Check, leaked_api_key"
    codes = ("M117", "M118", "M587", "M589")
    on_comment = True

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        self._clean: set[str] = set()  # comment texts with no secret

    def check_comment(self, line: Line, comment: Comment) -> None:
        text = comment.text
        if text in self._clean:  # comments repeat (";TYPE:Perimeter", ";WIDTH:0.45")
            return
        found = secrets.find(text)
        if not found and len(text) <= 1024:  # (long texts are not remembered: memory stays bounded)
            if len(self._clean) >= 8192:
                self._clean.clear()
            self._clean.add(text)
        for s in found:
            self.report_masked(
                line, f"{s.kind} left in a comment: anyone who gets this job can read it", comment.column + s.start
            )

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if cmd is None:
            return  # parse errors are read whole in check_issues
        end = min((c.column for c in line.parsed.comments), default=len(line.raw) + 1)
        start = cmd.column
        for s in secrets.find(line.raw[start - 1 : end - 1]):
            self.report_masked(line, f"{s.kind} in {code}: anyone who gets this job can read it", start + s.start)

    def check_issues(self, line: Line) -> None:
        if line.parsed.kind != "error":
            return
        # The grammar gave up on the line, so its comments were not read: look at the whole text.
        for s in secrets.find(line.raw):
            self.report_masked(line, f"{s.kind} left in the job: anyone who gets this job can read it", s.start + 1)


def _quote(text: str, limit: int = 80) -> str:
    return '"' + (text[:limit] + "..." if len(text) > limit else text) + '"'


def _excerpt(text: str, limit: int = 60) -> str:
    text = _strip_comment(text)
    if not text:
        return ""
    return f" ({text[:limit]}{'...' if len(text) > limit else ''})"
