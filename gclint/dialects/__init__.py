"""The dialect registry: look dialects up by name or alias.  Which dialect a file is written in is
decided by gclint.context from the evidence the dialects declare (``Detection``).

Adding a dialect is adding one module that builds a ``Dialect`` and listing it in ``_ALL``.
"""

from __future__ import annotations

import functools
from dataclasses import replace

from gclint.dialects.base import Code, Dialect, Param
from gclint.dialects.carvera import CARVERA
from gclint.dialects.generic import GENERIC
from gclint.dialects.hyrel import HYREL_V4, HYREL_V5
from gclint.dialects.machinekit import MACHINEKIT
from gclint.dialects.marlin import MARLIN
from gclint.dialects.reprap import REPRAP

__all__ = [
    "Code",
    "Dialect",
    "Param",
    "all_dialects",
    "known_dialects",
    "get",
    "reading",
    "names",
    "UnknownDialect",
    "DEFAULT",
    "GENERIC",
]

_ALL: tuple[Dialect, ...] = (HYREL_V5, HYREL_V4, MARLIN, REPRAP, MACHINEKIT, CARVERA, GENERIC)
_BY_NAME: dict[str, Dialect] = {}
for _d in _ALL:
    _BY_NAME[_d.name] = _d
    for _alias in _d.aliases:
        _BY_NAME[_alias] = _d

DEFAULT = HYREL_V5


class UnknownDialect(ValueError):
    pass


def all_dialects() -> tuple[Dialect, ...]:
    return _ALL


def known_dialects() -> tuple[Dialect, ...]:
    """The dialects whose tables say what a machine has (every one but ``generic``)."""
    return tuple(d for d in _ALL if d.known)


def names() -> list[str]:
    """The dialect names accepted on the command line (aliases included)."""
    return sorted(_BY_NAME)


@functools.cache
def reading(name: str, flavor: str | None = None) -> Dialect:
    """The dialect called ``name`` as a file written for the firmware ``flavor`` is read: the firmware's own
    meanings (``Firmware.semantics``: Bambu's arc turns, Machinekit FDM's G28) replace the dialect's."""
    dialect = get(name)
    if flavor is None:
        return dialect
    from gclint import firmware  # (the firmware inventories are built on the dialects' tables)

    try:
        changes = firmware.get(flavor).semantics
    except KeyError:
        return dialect
    if not changes:
        return dialect
    return replace(dialect, semantics=dialect.semantics.derive(**changes))


def get(name: str) -> Dialect:
    """The dialect called ``name`` (case-insensitive; aliases such as ``rrf`` and ``hyrel-v5`` work)."""
    dialect = _BY_NAME.get(name.strip().lower())
    if dialect is None:
        known = ", ".join(d.name for d in _ALL)
        raise UnknownDialect(f"unknown dialect {name!r} (known: {known}, auto)")
    return dialect
