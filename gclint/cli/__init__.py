"""The command line, one module per group of commands.  Each subcommand is a thin function: parse options,
call library code, print.  ``main`` (gclint.cli.app) is the entry point; importing the command modules
registers their commands on it."""

from gclint.cli import check, info, tools, translation  # noqa: F401  (registers the commands)
from gclint.cli.app import main

__all__ = ["main"]
