"""``gclint server``: the Language Server Protocol over standard input and output, for editors.

* ``text``: document text, lines and positions as the protocol counts them (pure);
* ``analysis``: options, a cancellable check, the explanation under the cursor (pure gclint);
* ``convert``: findings, fixes, noqa comments and explanations as protocol data (pure);
* ``jsonrpc``: JSON-RPC over standard input and output, with the protocol's framing (standard library);
* ``protocol``: the server's methods, which wire them to the editor.

Nothing beyond gclint's own dependencies is needed (``pip install gclint`` is enough; the ``server``
extra is kept, empty, for old install lines).  Set-up for VS Code, Neovim, Helix and Emacs:
docs/editors.md.
"""

from __future__ import annotations

import os
import sys


def main() -> None:
    """Run the server until the client says exit, then end the process with the protocol's status (0
    after a shutdown request, 1 without).  Ends the process even if the reader thread still waits on
    standard input."""
    from gclint.server.protocol import run

    code = run()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:
            pass
    os._exit(code)
