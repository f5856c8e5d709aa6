"""The built-in rules.  Importing this package registers them (see base.register)."""

from gclint.rules import dialect, syntax  # noqa: F401
