"""SC007: network services switched on."""

from __future__ import annotations

import re

from gclint.rules.base import Severity, register
from gclint.rules.security.base import _SecurityRule
from gclint.rules.security.common import _NUMBER, _quote, _starts_line, _strip_comment
from gclint.rules.security.files import system_file
from gclint.syntax.nodes import Command, Line

# -- network services ----------------------------------------------------------------------------------------

# RepRapFirmware src/Networking/NetworkDefs.h: HttpProtocol = 0, FtpProtocol = 1, TelnetProtocol = 2,
# MulticastDiscoveryProtocol = 3, MqttProtocol = 4 (M586 P); S1 enables, S0 disables
# (src/GCodes/GCodes2.cpp @ fc1cd16c: M586 "Configure network protocols").
_PROTOCOLS = {
    0: "HTTP (the web interface: files, configuration, any G-code)",
    1: "FTP (read and write access to the SD card)",
    2: "Telnet (a G-code console)",
    3: "multicast discovery",
    4: "MQTT",
}


# Network settings a job may change (RepRapFirmware src/GCodes/GCodes2.cpp cases 540, 552-554, 587-589; P is the
# address; Marlin's M552-M554 do the same on Ethernet builds)
_NETWORK_SETTINGS = {  # code -> (only with P, what it does)
    "M552": (True, "sets the printer's IP address"),
    "M553": (True, "sets the printer's netmask"),
    "M554": (True, "sets the printer's gateway"),
    "M540": (True, "sets the printer's MAC address"),
    "M587": (False, "adds a Wi-Fi network the printer joins"),
    "M588": (False, "forgets remembered Wi-Fi networks"),
    "M589": (False, "sets up the printer's Wi-Fi access point"),
}

STARTUP_FILES = frozenset({"config.g", "config-override.g", "runonce.g"})


def _name(path: str | None) -> str:
    return str(path or "").replace("\\", "/").rpartition("/")[2].lower()


@register
class OpensNetworkService(_SecurityRule):
    code = "SC007"
    name = "opens-network-service"
    severity = Severity.ERROR
    summary = "The job switches on a network service of the printer (RepRapFirmware M586: HTTP, FTP, Telnet; M552; M586 C CORS)"
    explanation = """
        RepRapFirmware's "M586 P<protocol> S1" switches on a network service: P0 the web interface (HTTP),
        P1 FTP, P2 Telnet.  FTP reads and writes every file on the SD card and Telnet is a G-code console,
        both protected only by the M551 password (if one is set).  A job that turns them on leaves the
        machine open to anyone on its network after the print.  The network belongs in the printer's
        configuration: M586 in the files RepRapFirmware runs at start-up, right in a `sys/` folder (config.g,
        config-override.g, runonce.g, checked as RepRapFirmware), is not reported; in any other file it is
        (a change can add a file of any name to a `sys/` folder; silence a macro that config.g runs with
        per-file-ignores in a configuration the CI names).  Switching a service off (S0) is not reported.
        The same holds for "M552 S1" (the network on) and "S2" (a Wi-Fi access point), and for "M586 C"*""
        (web pages of any site may use the web interface: CORS).  A job that changes the network settings
        is reported too: "M552 P", "M553 P" and "M554 P" set the IP address, the netmask and the gateway
        (RepRapFirmware, and Marlin's Ethernet builds), "M540 P" the MAC address, "M587" adds a Wi-Fi
        network the printer joins, "M588" forgets remembered ones and "M589" sets up its access point
        (RepRapFirmware GCodes2.cpp cases 540, 552-554, 587-589): the printer may join another network or
        drop off its own.
    """
    example_bad = "M586 P2 S1"
    example_good = "M586 P2 S0"
    source = (
        "RepRapFirmware source @ fc1cd16c, src/GCodes/GCodes2.cpp (M586 network protocols) and"
        " src/Networking/NetworkDefs.h"
        " (protocol numbers: 0 HTTP, 1 FTP, 2 Telnet)"
    )
    codes = ("M586", "M552", "M553", "M554", "M540", "M587", "M588", "M589")

    def __init__(self, ctx) -> None:
        super().__init__(ctx)
        # (only the files RepRapFirmware runs at start-up set up its network: src/GCodes/GCodes.h CONFIG_FILE
        # "config.g", CONFIG_OVERRIDE_G "config-override.g", RUNONCE_G "runonce.g"; a job's repository can
        # name any other file sys/x.g)
        self.configuration = system_file(ctx) and _name(ctx.path) in STARTUP_FILES

    def inspect(self, line: Line, code: str, rest: str, column: int, cmd: Command | None) -> None:
        if self.configuration or not _starts_line(line, cmd):
            return
        if cmd is not None and cmd.words:
            protocol, state, cors = cmd.raw("P"), cmd.raw("S"), cmd.raw("C")
        else:
            argument = _strip_comment(rest)
            m_p = re.search(r"(?i)P[ \t]*+(\S+)", argument)
            m_s = re.search(r"(?i)S[ \t]*+(\S+)", argument)
            m_c = re.search(r"(?i)C[ \t]*+(\S+)", argument)
            protocol, state = (m_p.group(1) if m_p else None), (m_s.group(1) if m_s else None)
            cors = m_c.group(1) if m_c else None
        if code == "M586" and cors is not None and cors.strip('"'):
            # (GCodes2.cpp case 586: C sets the site the web interface accepts requests from, CORS; "*" is any)
            self.report_masked(
                line,
                f"M586 C{cors} lets the web pages of {_quote(cors.strip(chr(34)))} control the printer through its web"
                " interface (CORS): a job must not open the machine to other sites",
                column,
            )
        setting = _NETWORK_SETTINGS.get(code)
        if setting is not None and (not setting[0] or protocol is not None):
            with_p, what = setting
            self.report_masked(
                line,
                f"the job {what} ({code}{' P' if with_p else ''}): a job must not change the network settings (the"
                " machine may join another network or drop off its own)",
                column,
            )
        if code not in ("M552", "M586"):
            return
        if state is None or (_NUMBER.fullmatch(state) and float(state) == 0):
            return
        if code == "M552":
            if _NUMBER.fullmatch(state) and float(state) <= 0:
                return  # (S0 stops the network, S-1 holds the Wi-Fi module in reset; an expression may be 1)
            # (GCodes2.cpp case 552: S1 starts the network, S2 the Wi-Fi access point; the services it starts are
            # those config.g enabled, HTTP by default: src/Networking/NetworkInterface.cpp)
            self.report_masked(
                line,
                f"M552 S{state} switches the printer's network on (S2: as a Wi-Fi access point): its web interface and"
                " the other services configured become reachable after this job",
                column,
            )
            return
        number = int(float(protocol)) if protocol is not None and _NUMBER.fullmatch(protocol) else None
        what = _PROTOCOLS.get(number, f"network protocol P{protocol}") if number is not None else "a network service"
        self.report_masked(
            line,
            f"M586 switches on {what}: anyone on the printer's network can reach the machine through it after this job",
            column,
        )
