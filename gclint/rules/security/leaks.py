"""SC006: secrets left in the job."""

from __future__ import annotations

from gclint import secrets
from gclint.rules.base import Severity, register
from gclint.rules.security.base import _SecurityRule
from gclint.rules.security.common import _machine_passwords
from gclint.syntax.nodes import Command, Comment, Line

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
        Check warns about the same leak).  URLs with "user:password@", bearer tokens, API keys,
        RepRapFirmware's M587 WiFi password and its M551 machine password (the password of the web
        interface, FTP and Telnet), its M586.4 MQTT password (K), and Marlin's M511/M512 passcode (its
        password feature), end up in start G-code the same way.  A job file is copied to
        print farms, shared folders and git: whoever gets it gets the secret.  Remove it, clear the field
        in the slicer's printer settings, and revoke the key.  gclint masks the value in every report.
    """
    example_bad = "; printhost_apikey = 0123456789ABCDEF0123456789ABCDEF"
    example_good = "; printhost_apikey = "
    source = (
        "OctoPrint File Check (octoprint_file_check/__init__.py: leaked_api_key); RepRapFirmware source @"
        " fc1cd16c, src/GCodes/GCodes2.cpp (M551 password, M587 Wi-Fi networks); Marlin source,"
        " src/gcode/feature/password/M510-M512.cpp (M511 P, M512 P S)"
    )
    codes = ("M117", "M118", "M551", "M587", "M589", "M511", "M512", "M586.4")
    on_comment = True
    comment_hint = staticmethod(secrets.may_hold)

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
        if code == "M551":
            self._machine_password(line)
            return
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
        self._machine_password(line)

    def _machine_password(self, line: Line) -> None:
        for start, _ in _machine_passwords(line.raw):
            self.report_masked(
                line,
                "machine password in M551 (RepRapFirmware's password for the web interface, FTP and Telnet): anyone"
                " who gets this job can read it",
                start + 1,
            )
