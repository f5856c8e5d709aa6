"""``gclint cura-script``: write ``Gclint.py``, a script for Cura's post-processing plugin.

Cura loads post-processing scripts from the ``scripts`` folder of its configuration folder; the module name must equal
the class name (``Gclint``) and the class subclasses Cura's ``Script`` (Cura source,
plugins/PostProcessingPlugin/Script.py and PostProcessingPlugin.py).  Cura runs scripts in its own bundled Python, which
cannot import gclint, so the script runs gclint as a program: the command is written into the script when it is
generated (this Python with ``-m gclint``) and can be changed in the script's settings.

Cura cannot block an export: its plugin catches every script exception and saves the file anyway.  The
script therefore annotates the G-code and shows the findings in a message; it never stops a save.
"""

from __future__ import annotations

import os
import sys
from importlib import resources
from pathlib import Path

from gclint import __version__

SCRIPT_NAME = "Gclint.py"


def template() -> str:
    return resources.files("gclint").joinpath("templates/cura/Gclint.py.tmpl").read_text(encoding="utf-8")


def default_command() -> list[str]:
    """How Cura should start gclint: this interpreter running the gclint module.  ``-P`` keeps the current
    folder (wherever Cura runs the script from) out of the import path, so a ``gclint/`` folder planted
    there is never imported instead of gclint."""
    return [sys.executable, "-P", "-m", "gclint"]


def render(command: list[str] | None = None) -> str:
    text = template()
    return text.replace("@GCLINT_VERSION@", __version__).replace(
        "@GCLINT_COMMAND@", repr(list(command or default_command()))
    )


def cura_script_folders() -> list[Path]:
    """Existing ``scripts`` folders of Cura configurations on this computer (newest version first)."""
    home = Path.home()
    roots = [
        home / ".local" / "share" / "cura",
        home / "Library" / "Application Support" / "cura",
        Path(os.environ.get("APPDATA", home / "AppData" / "Roaming")) / "cura",
    ]
    found: list[Path] = []
    for root in roots:
        if not root.is_dir():
            continue
        versions = sorted((p for p in root.iterdir() if p.is_dir()), key=lambda p: _version_key(p.name), reverse=True)
        found.extend(v / "scripts" for v in versions if (v / "cura.cfg").exists() or (v / "scripts").is_dir())
    return found


def _version_key(name: str) -> tuple:
    return tuple(int(x) if x.isdigit() else 0 for x in name.split("."))


def write(folder: str | os.PathLike, command: list[str] | None = None) -> Path:
    """Write ``Gclint.py`` into ``folder`` (created if missing); returns its path."""
    from gclint.io import AtomicWriter

    target = Path(folder)
    target.mkdir(parents=True, exist_ok=True)
    path = target / SCRIPT_NAME
    with AtomicWriter(str(path)) as out:  # never through a link planted where the script goes
        out.write(render(command).encode("utf-8"))
    return path
