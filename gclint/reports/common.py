"""Helpers every report shares: masking secrets in file text, making text safe for a format, rule docs.

File text reaches reports as ``Finding.source`` (the line) and inside messages.  It may hold credentials
(PrusaSlicer writes ``; printhost_apikey = ...`` into its header), terminal escape sequences, control
characters XML cannot carry, and undecodable bytes kept as lone surrogates.  Each format escapes text
its own way (HTML autoescape, XML escaping, GitHub command escaping); these helpers do the part they share.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass

from gclint.engine import FileResult
from gclint.rules.base import Finding
from gclint.textsafe import clean, human, json_safe, mask, printable  # noqa: F401  (re-exported)


def source_line(finding: Finding) -> str | None:
    """The finding's line as a report may show it: secrets masked, control characters escaped."""
    if finding.source is None:
        return None
    return human(finding.source)


def message(finding: Finding) -> str:
    """The finding's message, safe to print (messages may quote file text)."""
    return human(finding.message)


def rule_docs(codes: set[str] | None = None) -> dict[str, dict]:
    """``Rule.doc()`` of every registered rule (or of ``codes``), by code."""
    from gclint.rules.base import all_rules

    try:
        registry = all_rules()
    except Exception:  # a broken plugin must not stop a report; check already said so
        return {}
    return {code: rule.doc() for code, rule in registry.items() if codes is None or code in codes}


def codes_in(results: list[FileResult]) -> set[str]:
    return {f.code for r in results for f in r.findings}


def totals(results: list[FileResult]) -> dict[str, int]:
    out = {"error": 0, "warning": 0, "info": 0}
    for r in results:
        for f in r.findings:
            out[f.severity.label] += 1
    return out


# -- grouping repeated findings (human formats) -------------------------------------------------------------

SHOWN_PER_CODE = 3  # findings of one code shown per file before "... and N more like this"


@dataclass(frozen=True)
class Elided:
    """Stands for the findings of one code in one file after the first few (text, full, grouped)."""

    path: str
    code: str
    count: int

    def __str__(self) -> str:
        return f"... and {self.count} more like this ({self.code})"


def grouped(findings: list[Finding], group: bool = True, shown: int = SHOWN_PER_CODE) -> Iterator[Finding | Elided]:
    """One file's ``findings`` (in order) as the human formats show them: with ``group``, each code's
    first ``shown`` findings, then one ``Elided`` for the rest of that code (``--no-group``: every one)."""
    if not group:
        yield from findings
        return
    total = Counter(f.code for f in findings)
    seen: Counter = Counter()
    for f in findings:
        seen[f.code] += 1
        # security findings are never folded away (each names a different program or file), and folding
        # a single finding into "1 more" saves nothing
        if seen[f.code] <= shown or f.code.startswith("SC") or total[f.code] <= shown + 1:
            yield f
            if seen[f.code] == shown and total[f.code] > shown + 1 and not f.code.startswith("SC"):
                yield Elided(f.path, f.code, total[f.code] - shown)
