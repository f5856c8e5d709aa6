"""SC: security.  Commands that make the host or the printer run programs or touch files, and secrets left
in the job.

A G-code job is data that comes from elsewhere (a slicer, a colleague, a download, a print farm queue) and
is run by software with access to the machine and, on Hyrel printers, to the Windows PC running Repetrel.
These rules apply to every dialect: a hostile job can claim any flavour in its header, so the check does not
trust the dialect.  Messages and ``Finding.source`` go through ``gclint.secrets.mask``.

Lines the grammar cannot parse (``M0 SHELL C:\\x.exe`` without a ``;``, ``M1000 rm -rf /sd``) are still
read: each rule also looks at the start of lines with a parse error (SC001 and SC002 at each action code
anywhere in them, and the LinuxCNC rules at their comments).  Each rule also reads a line as the
firmwares that edit it before parsing read it (``firmware_views``: Marlin's backspaces, Klipper's
``strip()`` and ``upper()``, Smoothieware running every M code of a line), reporting on the line as written.

Where a firmware documents a line as something harmless the rule says so, but the finding stays unless the
dialect the job is read as documents it otherwise (the SC003 and SC005 explanations list those cases).

One module by topic: ``common`` (shared helpers), ``views`` (the line as each firmware reads it),
``linuxcnc`` (the comments LinuxCNC/Machinekit act on, the subroutines it calls), ``base`` (the rules' base
class), ``actions`` (SC001, SC002), ``console`` (SC003), ``files`` (SC004, SC005), ``leaks`` (SC006),
``network`` (SC007).
"""

from __future__ import annotations

from gclint.rules.security import actions, console, files, leaks, network  # noqa: F401  (registers the rules)
from gclint.rules.security.actions import (
    ACTION_CODES,
    ACTIONS,
    PAUSE_CODES,
    action_shell_column,
    holds_action,
    host_actions,
    shell_offsets,
)
from gclint.rules.security.views import firmware_views

__all__ = [
    "ACTIONS",
    "ACTION_CODES",
    "PAUSE_CODES",
    "action_shell_column",
    "firmware_views",
    "holds_action",
    "host_actions",
    "shell_offsets",
]
