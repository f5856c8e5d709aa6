"""A result cache keyed by file content, gclint's own code, configuration and rule set (like ruff's).

A second run over unchanged files reads their findings from ``.gclint_cache/`` instead of checking them
again.  Each checked path has one small JSON entry; it is used only when every part of the key matches:

* the file's size, modification time and SHA-256 of its bytes (the hash decides; size and time only
  skip hashing files that obviously changed),
* gclint's version and a fingerprint of its source files and grammar (a changed rule invalidates),
* the options that shape the check (dialect, printer, loaded heads, selection, per-file ignores...),
* the selected rule codes, including plugin rules.

Writes are atomic (temporary file, then rename) and a damaged or foreign entry is ignored, never fatal.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from functools import lru_cache
from pathlib import Path

from gclint import __version__
from gclint.context import Context
from gclint.engine import FileResult
from gclint.rules.base import Edit, Finding, Fix, Severity

DEFAULT_DIR = ".gclint_cache"
_FORMAT = 2


@lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """A hash of gclint's source (so a changed rule or grammar invalidates every entry)."""
    root = Path(__file__).resolve().parent
    digest = hashlib.sha256(__version__.encode())
    for path in sorted(root.rglob("*")):
        if path.suffix in (".py", ".lark") and "__pycache__" not in path.parts:
            digest.update(path.relative_to(root).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def file_digest(path: str) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


class ResultCache:
    """Read and write cached results under ``folder`` (default ``.gclint_cache`` in the current folder)."""

    def __init__(self, folder: str | None = None) -> None:
        self.folder = Path(folder or DEFAULT_DIR)
        self.hits = 0
        self.misses = 0

    def _entry(self, path: str) -> Path:
        name = hashlib.sha256(os.path.abspath(path).encode("utf-8", "surrogateescape")).hexdigest()[:32]
        return self.folder / name[:2] / f"{name}.json"

    @staticmethod
    def settings_key(options_key: str, rule_codes: list[str]) -> str:
        raw = json.dumps([_FORMAT, code_fingerprint(), options_key, sorted(rule_codes)])
        return hashlib.sha256(raw.encode()).hexdigest()[:32]

    def get(self, path: str, settings: str) -> FileResult | None:
        """The cached result for ``path``, or None when it is missing or stale."""
        entry = self._entry(path)
        try:
            st = os.stat(path)
            data = json.loads(entry.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            self.misses += 1
            return None
        if data.get("settings") != settings or data.get("path") != path or data.get("size") != st.st_size:
            self.misses += 1
            return None
        if data.get("mtime_ns") != st.st_mtime_ns:
            try:
                if data.get("sha256") != file_digest(path):
                    self.misses += 1
                    return None
            except OSError:
                self.misses += 1
                return None
        try:
            result = _load(data["result"])
        except (KeyError, TypeError, ValueError):
            self.misses += 1
            return None
        self.hits += 1
        return result

    def put(self, path: str, settings: str, result: FileResult) -> None:
        """Store ``result`` for ``path`` (silently skipped when the cache folder is not writable)."""
        if result.error is not None or path == "-":
            return
        try:
            st = os.stat(path)
            data = {
                "settings": settings,
                "path": path,
                "size": st.st_size,
                "mtime_ns": st.st_mtime_ns,
                "sha256": file_digest(path),
                "result": _dump(result),
            }
            entry = self._entry(path)
            entry.parent.mkdir(parents=True, exist_ok=True)
            _ensure_gitignore(self.folder)
            fd, tmp = tempfile.mkstemp(dir=entry.parent, prefix=".tmp-", suffix=".json")
            try:
                with os.fdopen(fd, "w", encoding="utf-8") as fh:
                    json.dump(data, fh)  # ASCII: keeps undecodable bytes (lone surrogates) intact
                os.replace(tmp, entry)
            except BaseException:
                try:
                    os.unlink(tmp)
                except OSError:
                    pass
                raise
        except OSError:
            return


def _ensure_gitignore(folder: Path) -> None:
    marker = folder / ".gitignore"
    if not marker.exists():
        marker.write_text("# created by gclint: the result cache\n*\n", encoding="utf-8")


def _dump(result: FileResult) -> dict:
    return {
        "path": result.path,
        "dialect": result.dialect,
        "dialect_reason": result.dialect_reason,
        "context": result.context.to_dict() if result.context is not None else None,
        "lines": result.lines,
        "findings": [
            {
                "line": f.line,
                "column": f.column,
                "end_column": f.end_column,
                "code": f.code,
                "severity": f.severity.label,
                "message": f.message,
                "name": f.name,
                "source": f.source,
                "fix": None
                if f.fix is None
                else {
                    "message": f.fix.message,
                    "safe": f.fix.safe,
                    "edits": [[e.line, e.start, e.end, e.text] for e in f.fix.edits],
                },
            }
            for f in result.findings
        ],
    }


def _load(data: dict) -> FileResult:
    findings = []
    for f in data["findings"]:
        fix = None
        if f["fix"] is not None:
            fix = Fix(f["fix"]["message"], tuple(Edit(*e) for e in f["fix"]["edits"]), f["fix"]["safe"])
        findings.append(
            Finding(
                path=data["path"],
                line=f["line"],
                column=f["column"],
                code=f["code"],
                severity=Severity.parse(f["severity"]),
                message=f["message"],
                name=f["name"],
                fix=fix,
                end_column=f["end_column"],
                source=f["source"],
            )
        )
    context = Context.from_dict(data["context"]) if data.get("context") else None
    return FileResult(data["path"], findings, data["dialect"], data["dialect_reason"], data["lines"], context=context)
