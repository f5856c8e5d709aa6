"""The built-in rules.  Importing this package registers them (see base.register)."""

from gclint.rules import dialect, hyrel, profiles, security, syntax, translation  # noqa: F401
