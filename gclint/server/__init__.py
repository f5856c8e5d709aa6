"""``gclint server``: the Language Server Protocol over standard input and output, for editors.

* ``text``: document text, lines and positions as the protocol counts them (pure);
* ``analysis``: options, a cancellable check, the explanation under the cursor (pure gclint);
* ``convert``: findings, fixes, noqa comments and explanations as protocol data (pure);
* ``protocol``: the pygls server that wires them to the editor.

pygls and lsprotocol come with the ``server`` extra (``pip install 'gclint[server]'``); without them
``gclint server`` says so in one line.  Set-up for VS Code, Neovim, Helix and Emacs: docs/editors.md.
"""

from __future__ import annotations

import os
import sys

INSTALL_HINT = "pip install 'gclint[server]'"


class ServerUnavailable(Exception):
    """The language server packages are missing or too old; the message says what to install."""


def check_available() -> None:
    """Raise ``ServerUnavailable`` unless pygls 2 and lsprotocol can be imported."""
    try:
        import lsprotocol.types  # noqa: F401
        import pygls.lsp.server  # noqa: F401  (pygls 2; pygls 1 has no pygls.lsp.server)
    except ImportError as exc:
        missing = getattr(exc, "name", None) or "pygls"
        raise ServerUnavailable(
            f"gclint server needs pygls 2 and lsprotocol ({missing} could not be imported): {INSTALL_HINT}"
        ) from None


def main() -> None:
    """Run the server until the client says exit, then end the process with the protocol's status (0
    after a shutdown request, 1 without).  Ends the process even if a reader thread still waits on
    standard input."""
    check_available()
    from gclint.server.protocol import run

    code = run()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:
            pass
    os._exit(code)
