"""gclint: a static linter and dialect translator for G-code, built first for Hyrel 3D printers."""

__version__ = "0.1.0"
