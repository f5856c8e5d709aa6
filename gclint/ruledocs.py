"""Where a rule's documentation is, as a link: the language server's ``codeDescription.href`` and SARIF's
``helpUri``, in any install.

The rule reference is ``docs/rules.md`` (generated from the rules by scripts/gen_rules_doc.py; each rule
has a ``### CODE`` heading, hence the anchor ``#hy003``).  The link is, first found:

1. ``GCLINT_DOCS_URL`` (the address of a published ``rules.md``; the GitHub Action sets it to the copy in
   the action's own repository at the ref it was used at);
2. the package's ``[project.urls] Documentation``, once the project publishes one (none is invented);
3. the copy inside the installed package, ``gclint/_docs/rules.md``, as a ``file:`` URL: the build
   (setup.py) copies ``docs/rules.md`` there, so a wheel, ``pip install ./gclint`` or a ``git+`` install
   carries the reference of exactly the rules it runs, and the link works offline;
4. ``docs/rules.md`` of the source checkout (an editable install, where nothing is copied).

So a link is given in every install; it is a ``file:`` URL unless an address is published or given.
"""

from __future__ import annotations

import os
from functools import cache
from pathlib import Path

PACKAGED = Path(__file__).resolve().parent / "_docs" / "rules.md"  # written by setup.py's build step
_ROOT = Path(__file__).resolve().parent.parent
CHECKOUT = _ROOT / "docs" / "rules.md"  # (a source checkout: beside pyproject.toml, not site-packages/docs)


@cache
def reference() -> str | None:
    """The address of the rule reference, without an anchor (None only when no copy can be found)."""
    configured = os.environ.get("GCLINT_DOCS_URL", "").strip()
    if configured:
        return configured
    from gclint.rules.base import project_url

    published = project_url("documentation")
    if published:
        return published
    if PACKAGED.is_file():
        return PACKAGED.as_uri()
    if CHECKOUT.is_file() and (_ROOT / "pyproject.toml").is_file():
        return CHECKOUT.as_uri()
    return None


def rule_url(code: str) -> str | None:
    """The link to one rule's documentation (``rule_url("HY003")`` -> ``.../rules.md#hy003``)."""
    base = reference()
    return f"{base}#{code.lower()}" if base else None
