"""A result cache keyed by file content, gclint's own code, configuration and rule set (like ruff's), that can
never change an answer.

A second run over unchanged files reads their findings back instead of checking them again.  gclint is a
security gate (SC rules), so the cache is built so that nobody can make a job pass through it:

* Where it lives: the user's cache folder (``$XDG_CACHE_HOME/gclint``, ``~/Library/Caches/gclint``,
  ``%LOCALAPPDATA%\\gclint\\Cache``), one sub-folder per project (the folder of the nearest configuration
  file, else the nearest folder with ``.git``, else the file's folder), never in the project or the
  working folder.  ``--cache-dir`` / ``GCLINT_CACHE_DIR`` choose another folder.
* Whose entries count: each entry is signed (HMAC-SHA256) with a per-user key kept in the user's cache
  folder (``key``, mode 0600), never in a project.  An entry committed with a pull request, copied from
  another user or written into a shared folder by someone else fails the signature and is ignored; git
  cannot even check out a file with the key's mode.  A cache folder that other users can write to, or that
  belongs to another user, is not used at all (a note on stderr says so).
* What an entry stands for: the SHA-256 of exactly the bytes that were checked, computed while they were
  read (``Source.open(..., digest=True)``), plus the path, gclint's version and source fingerprint, the
  options and the selected rule codes.  There is no size/mtime shortcut: a lookup hashes the file.  Only
  regular files are cached; standard input, pipes (``/dev/stdin``, ``<(...)``) and devices are read once
  and never cached.
* Reading: entries are opened without following symbolic links, size-limited, signature-checked, then
  validated field by field; anything unexpected is a miss, never an error.
* Writing: a temporary file created exclusively (``O_EXCL``) in a folder gclint made (mode 0700, not a
  link), then renamed over the entry: a planted link is replaced, never followed.  Findings are stored
  with secrets masked.
"""

from __future__ import annotations

# (json, hmac, secrets and tempfile are imported where an entry is read or written: a --no-cache check
# does not pay for them)
import hashlib
import math
import os
import re
import stat
import sys
from functools import lru_cache
from pathlib import Path

from gclint import __version__
from gclint.checkout import Roots, escapes
from gclint.context import Context
from gclint.engine import FileResult
from gclint.rules.base import Edit, Finding, Fix, Severity

ENV = "GCLINT_CACHE_DIR"
_FORMAT = 2
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)
MAX_ENTRY_BYTES = 64 << 20
MAX_CACHED_FINDINGS = 100_000
_KEY_BYTES = 32
_MARKER = "# created by gclint: the result cache\n*\n"
_ENTRY_NAME = re.compile(r"[0-9a-f]{32}\.json")
_SUB_NAME = re.compile(r"[0-9a-f]{2}")
_CODE = re.compile(r"[A-Z]{2}[0-9]{3}")


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


def user_cache_root() -> Path:
    """gclint's folder in the user's cache folder (where the key and the per-project caches live)."""
    if os.name == "nt":
        base = os.environ.get("LOCALAPPDATA") or os.path.join(os.path.expanduser("~"), "AppData", "Local")
        return Path(base) / "gclint" / "Cache"
    if sys.platform == "darwin":
        return Path(os.path.expanduser("~/Library/Caches")) / "gclint"
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    base = xdg if os.path.isabs(xdg) else os.path.expanduser("~/.cache")
    return Path(base) / "gclint"


def project_root(path: str, roots: Roots | None = None) -> Path:
    """The project a file belongs to: the folder of its nearest configuration file, else the nearest
    folder holding ``.git``, else the file's own folder.  (``roots``: repository roots already found, so
    that the files of a deep tree are placed in linear time.)"""
    from gclint.config import find_config, real_folder

    where = os.path.abspath(path)
    folder = where if os.path.isdir(where) else os.path.dirname(where)
    config = find_config(folder)
    if config is not None:
        return config.parent.resolve()
    real = real_folder(folder)
    root = (roots or Roots()).root_of(real)
    if root is not None:
        return Path(root)
    here = Path.cwd().resolve()
    return here if Path(real).is_relative_to(here) else Path(real)  # (as ruff: the working folder is the project)


_ROOT_NOTE = "project"  # in each project's cache folder: the project's path


def projects_under(root: Path, top: Path) -> list[Path]:
    """The cache folders of every project at or below the folder ``top`` (their ``project`` notes)."""
    out: list[Path] = []
    try:
        with os.scandir(root / "projects") as listing:
            folders = [Path(e.path) for e in listing if e.is_dir(follow_symlinks=False)]
    except OSError:
        return out
    top = top.resolve()
    for folder in folders:
        try:
            with open(folder / _ROOT_NOTE, "rb") as fh:
                project = Path(os.fsdecode(fh.read(4096)))
        except OSError:
            continue
        if project == top or project.is_relative_to(top):
            out.append(folder)
    return out


def project_folder(root: Path, project: Path) -> Path:
    name = hashlib.sha256(os.fsencode(str(project))).hexdigest()[:16]
    return root / "projects" / name


def file_digest(path: str) -> str | None:
    """SHA-256 of a regular file's bytes; None for anything else (never blocks on a pipe)."""
    try:
        fd = os.open(path, os.O_RDONLY | _NONBLOCK)
    except OSError:
        return None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        digest = hashlib.sha256()
        while True:
            block = os.read(fd, 1 << 20)
            if not block:
                return digest.hexdigest()
            digest.update(block)
    except OSError:
        return None
    finally:
        os.close(fd)


# -- trust ----------------------------------------------------------------------------------------------------


def _private_dir(folder: Path, create: bool) -> str | None:
    """Make sure ``folder`` is a real folder of this user that nobody else can write to; returns why not."""
    try:
        st = os.lstat(folder)
    except FileNotFoundError:
        if not create:
            return "does not exist"
        try:
            folder.mkdir(mode=0o700, parents=True)
            st = os.lstat(folder)
        except OSError as exc:
            return f"cannot be created ({exc.strerror or exc})"
    except OSError as exc:
        return f"cannot be read ({exc.strerror or exc})"
    if not stat.S_ISDIR(st.st_mode):
        return "is not a folder (or is a symbolic link)"
    if hasattr(os, "getuid"):
        if st.st_uid != os.getuid():
            return "belongs to another user"
        if st.st_mode & 0o022:
            return "can be written by other users"
    return None


class ResultCache:
    """Read and write signed results under ``folder`` (default: the user cache folder, per project).

    ``root`` is gclint's user cache folder, which holds the signing key (tests give another one)."""

    def __init__(self, folder: str | None = None, *, root: str | os.PathLike | None = None) -> None:
        self.folder = Path(folder) if folder else None
        self.root = Path(root) if root is not None else user_cache_root()
        self.hits = 0
        self.misses = 0
        self.notes: list[str] = []  # why the cache was not used, once per folder (for stderr)
        self._key: bytes | None = None
        self._key_loaded = False
        self._trusted: dict[Path, bool] = {}
        self._roots = Roots()
        self._projects: dict[str, Path] = {}  # a file's folder -> its project

    # -- where --------------------------------------------------------------------------------------------

    def folder_for(self, path: str) -> Path:
        if self.folder is not None:
            return self.folder
        return project_folder(self.root, self._project_of(path))

    def _project_of(self, path: str) -> Path:
        folder = os.path.dirname(os.path.abspath(path))
        found = self._projects.get(folder)
        if found is None:
            try:
                found = project_root(path, self._roots)
            except Exception:  # a broken configuration on the way up: the file's own folder
                found = Path(folder)
            self._projects[folder] = found
        return found

    def _entry(self, path: str) -> Path:
        name = hashlib.sha256(os.fsencode(os.path.abspath(path))).hexdigest()[:32]
        return self.folder_for(path) / name[:2] / f"{name}.json"

    def _usable(self, folder: Path, create: bool) -> bool:
        known = self._trusted.get(folder)
        if known is not None:
            return known
        if self.folder is None:  # the per-user folders: gclint's own, private
            problem = _private_dir(self.root, create) or _private_dir(folder.parent, create)
            problem = problem or _private_dir(folder, create)
        elif (outside := escapes(str(folder))) is not None:  # a link committed where the cache is to go
            problem = f"is a link out of this checkout (to {outside})"
        else:
            try:
                real = Path(os.path.realpath(folder))  # the folder the user named may be a link; not below it
            except OSError:
                real = folder
            problem = _private_dir(real, create)
        if problem == "does not exist":
            return False  # nothing cached yet: not a problem, and not remembered
        ok = problem is None and self._signing_key() is not None
        if problem is not None and not problem.startswith("cannot be created"):
            self.notes.append(f"cache folder {folder} {problem}: the result cache is not used")
        self._trusted[folder] = ok
        return ok

    # -- the key ------------------------------------------------------------------------------------------

    def _signing_key(self) -> bytes | None:
        if not self._key_loaded:
            self._key_loaded = True
            self._key = self._load_key()
        return self._key

    def _load_key(self, create: bool = True) -> bytes | None:
        if _private_dir(self.root, create=create) is not None:
            return None
        path = self.root / "key"
        try:
            fd = os.open(path, os.O_RDONLY | _NOFOLLOW)
        except FileNotFoundError:
            return self._new_key(path) if create else None
        except OSError:
            return None
        try:
            st = os.fstat(fd)
            if not stat.S_ISREG(st.st_mode) or st.st_size != _KEY_BYTES:
                return None
            if hasattr(os, "getuid") and (st.st_uid != os.getuid() or st.st_mode & 0o077):
                self.notes.append(f"{path} is not private to this user: the result cache is not used")
                return None
            data = os.read(fd, _KEY_BYTES + 1)
            return data if len(data) == _KEY_BYTES else None
        except OSError:
            return None
        finally:
            os.close(fd)

    def _new_key(self, path: Path) -> bytes | None:
        import secrets as _random
        import tempfile

        key = _random.token_bytes(_KEY_BYTES)
        try:
            fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".key-")
            try:
                os.write(fd, key)
                os.fsync(fd)
            finally:
                os.close(fd)
            try:
                os.link(tmp, path)  # fails if another gclint made one meanwhile: then use that one
            except FileExistsError:
                os.unlink(tmp)
                return self._load_key()
            os.unlink(tmp)
            return key
        except OSError:
            return None

    def _sign(self, body: bytes) -> bytes:
        key = self._signing_key()
        if key is None:
            raise OSError("no signing key")
        import hmac

        return hmac.new(key, body, hashlib.sha256).hexdigest().encode() + b"\n" + body

    def _unsign(self, data: bytes) -> bytes | None:
        return data.partition(b"\n")[2] if _verifies(data, self._signing_key()) else None

    # -- lookups ------------------------------------------------------------------------------------------

    @staticmethod
    def settings_key(options_key: str, rule_codes: list[str]) -> str:
        import json

        raw = json.dumps([_FORMAT, code_fingerprint(), options_key, sorted(rule_codes)])
        return hashlib.sha256(raw.encode()).hexdigest()[:32]

    def get(self, path: str, settings: str) -> FileResult | None:
        """The cached result for the current content of ``path``, or None (never raises)."""
        try:
            result = self._get(path, settings)
        except Exception:  # a damaged entry is a miss, whatever is wrong with it
            result = None
        if result is None:
            self.misses += 1
        else:
            self.hits += 1
        return result

    def _get(self, path: str, settings: str) -> FileResult | None:
        if path == "-":
            return None
        entry = self._entry(path)
        if not self._usable(entry.parent.parent, create=False):
            return None
        data = _read_entry(entry)
        if data is None:
            return None
        body = self._unsign(data)
        if body is None:
            return None
        import json

        record = json.loads(body)
        if not isinstance(record, dict) or record.get("format") != _FORMAT:
            return None
        if record.get("settings") != settings or record.get("path") != path:
            return None
        digest = file_digest(path)  # the content now; no size/mtime shortcut
        if digest is None or record.get("sha256") != digest:
            return None
        return _load(record.get("result"), path)

    def put(self, path: str, settings: str, result: FileResult, digest: str) -> None:
        """Store ``result``, the result of checking the bytes whose SHA-256 is ``digest``.  Silently skipped
        when the folder cannot be used."""
        if result.error is not None or path == "-" or not digest or len(result.findings) > MAX_CACHED_FINDINGS:
            return
        try:
            entry = self._entry(path)
            folder = entry.parent.parent
            if not self._usable(folder, create=True):
                return
            if self.folder is not None:
                _write_new(folder / ".gitignore", _MARKER.encode())
            else:  # which project this is, for "gclint clean PATH" (every project at or below PATH)
                _write_new(folder / _ROOT_NOTE, os.fsencode(str(self._project_of(path))))
            if _private_dir(entry.parent, create=True) is not None:
                return
            record = {"format": _FORMAT, "settings": settings, "path": path, "sha256": digest, "result": _dump(result)}
            import json
            import tempfile

            body = json.dumps(record).encode("ascii")  # ASCII: keeps undecodable bytes (lone surrogates) intact
            fd, tmp = tempfile.mkstemp(dir=entry.parent, prefix=".tmp-", suffix=".json")
            try:
                with os.fdopen(fd, "wb") as fh:
                    fh.write(self._sign(body))
                os.replace(tmp, entry)  # replaces a planted link itself, never what it points to
            except BaseException:
                try:
                    os.unlink(tmp)
                except OSError:
                    pass
                raise
        except Exception:  # the cache never stops a check (an unreadable configuration, a full disk...)
            return


def _read_entry(entry: Path) -> bytes | None:
    try:
        fd = os.open(entry, os.O_RDONLY | _NOFOLLOW | _NONBLOCK)
    except OSError:
        return None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or st.st_size > MAX_ENTRY_BYTES:
            return None
        chunks: list[bytes] = []
        size = 0
        while size <= MAX_ENTRY_BYTES:
            block = os.read(fd, 1 << 20)
            if not block:
                return b"".join(chunks)
            chunks.append(block)
            size += len(block)
        return None
    except OSError:
        return None
    finally:
        os.close(fd)


def _write_new(path: Path, data: bytes) -> None:
    """Create ``path`` with ``data`` unless something (a file, a link) is already there."""
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW, 0o600)
    except OSError:
        return
    try:
        os.write(fd, data)
    finally:
        os.close(fd)


# -- removing (gclint clean) -----------------------------------------------------------------------------------


class NotACache(Exception):
    """A folder ``gclint clean`` leaves alone; the message says why (one line)."""


_TMP_NAME = re.compile(r"\.tmp-[A-Za-z0-9_]{1,32}\.json")  # (tempfile.mkstemp's names, prefix and suffix)
_PROJECT_NAME = re.compile(r"[0-9a-f]{16}")


def clean(folder: Path, root: Path | None = None) -> int:
    """Remove the result cache in ``folder`` and return the number of entries removed.

    Only a folder gclint marked as its cache is touched: a ``--cache-dir`` folder holding the
    ``.gitignore`` gclint writes there, a project's folder in gclint's user cache folder (``root``), or
    that folder itself (every project's).  In it, only the entries (and temporary files) whose signature
    verifies with this user's key are removed; the marker and the folder go last, when nothing else is
    left.  So ``gclint clean --cache-dir notes`` removes nothing of a folder of notes, and entries planted
    by someone else stay where they are.  Raises ``NotACache`` for a folder that is not marked."""
    root = root if root is not None else user_cache_root()
    try:
        st = os.lstat(folder)
    except OSError:
        return 0  # nothing cached there
    if not stat.S_ISDIR(st.st_mode):
        raise NotACache(f"{folder}: not a folder (or a symbolic link): nothing removed")
    key = ResultCache(root=root)._load_key(create=False)
    real, real_root = os.path.realpath(folder), os.path.realpath(root)
    if real == real_root:
        removed = 0
        projects = folder / "projects"
        try:
            with os.scandir(projects) as listing:
                found = [Path(e.path) for e in listing if e.is_dir(follow_symlinks=False)]
        except OSError:
            return 0
        for project in found:
            if _PROJECT_NAME.fullmatch(project.name):
                removed += _clean(project, key, (_ROOT_NOTE,))
        _rmdir(str(projects))
        return removed
    if os.path.dirname(real) == os.path.join(real_root, "projects") and _PROJECT_NAME.fullmatch(folder.name):
        return _clean(folder, key, (_ROOT_NOTE,))
    if not _marked(folder / ".gitignore"):
        raise NotACache(
            f"{folder}: not a result cache folder (gclint marks its own with a .gitignore it writes there):"
            " nothing removed"
        )
    return _clean(folder, key, (".gitignore",))


def _marked(marker: Path) -> bool:
    data = _read_entry(marker)
    return data is not None and data.decode("utf-8", "replace") == _MARKER


def _clean(folder: Path, key: bytes | None, markers: tuple[str, ...]) -> int:
    """Remove the verified entries of one cache folder; then its markers and itself if nothing else is left."""
    removed = 0
    try:
        with os.scandir(folder) as listing:
            subs = [Path(e.path) for e in listing if e.is_dir(follow_symlinks=False) and _SUB_NAME.fullmatch(e.name)]
    except OSError:
        return 0
    for sub in subs:
        try:
            with os.scandir(sub) as inner:
                items = [Path(e.path) for e in inner if e.is_file(follow_symlinks=False)]
        except OSError:
            continue
        for item in items:
            entry = _ENTRY_NAME.fullmatch(item.name) is not None
            if not (entry or _TMP_NAME.fullmatch(item.name)):
                continue
            data = _read_entry(item)
            if data is None or not (_verifies(data, key) or (not entry and data == b"")):
                continue  # not written by this user's gclint (or not whole yet): left alone
            try:
                os.unlink(item)
                removed += entry
            except OSError:
                pass
        _rmdir(str(sub))
    try:
        left = set(os.listdir(folder))
    except OSError:
        return removed
    if left <= set(markers):
        for name in left:
            try:
                os.unlink(folder / name)
            except OSError:
                pass
        _rmdir(str(folder))
    return removed


def _verifies(data: bytes, key: bytes | None) -> bool:
    mac, sep, body = data.partition(b"\n")
    if key is None or not sep or len(mac) != 64:
        return False
    import hmac

    return hmac.compare_digest(mac, hmac.new(key, body, hashlib.sha256).hexdigest().encode())


def _rmdir(path: str) -> None:
    try:
        os.rmdir(path)
    except OSError:
        pass  # not empty (files that are not gclint's), or gone


# -- entries ----------------------------------------------------------------------------------------------------


def _dump(result: FileResult) -> dict:
    from gclint.secrets import mask

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
                "message": mask(f.message),
                "name": f.name,
                "source": mask(f.source) if f.source is not None else None,
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


class _Bad(ValueError):
    pass


def _context(data: object) -> Context | None:
    """The stored ``Context``, every field checked (strings, whole numbers, tuples of strings)."""
    if data is None:
        return None
    if not isinstance(data, dict):
        raise _Bad
    try:
        context = Context.from_dict(data)
    except TypeError:
        raise _Bad from None
    for name, value in vars(context).items():
        if name == "candidates":  # (name, score) pairs
            if not isinstance(value, tuple) or not all(_candidate(v) for v in value):
                raise _Bad
            continue
        if isinstance(value, tuple) and not all(isinstance(v, str) and len(v) < 2000 for v in value):
            raise _Bad
        if value is not None and not isinstance(value, (str, int, tuple)):
            raise _Bad
    _str(context.dialect, 40)
    return context


def _candidate(pair: object) -> bool:
    """A stored candidate score: a short name and a finite number."""
    return (
        isinstance(pair, tuple)
        and len(pair) == 2
        and isinstance(pair[0], str)
        and len(pair[0]) < 80
        and type(pair[1]) in (int, float)
        and math.isfinite(pair[1])
    )


def _int(value: object, low: int = 0) -> int:
    if type(value) is not int or not low <= value < 1 << 62:
        raise _Bad
    return value


def _str(value: object, limit: int = 1 << 20) -> str:
    if type(value) is not str or len(value) > limit:
        raise _Bad
    return value


def _load(data: object, path: str) -> FileResult:
    """A FileResult from an entry's ``result``, every field checked (raises ValueError otherwise)."""
    if not isinstance(data, dict) or data.get("path") != path:
        raise _Bad
    dialect = data.get("dialect")
    if dialect is not None:
        _str(dialect, 40)
    raw_findings = data.get("findings")
    if not isinstance(raw_findings, list):
        raise _Bad
    findings = []
    for f in raw_findings:
        if not isinstance(f, dict):
            raise _Bad
        fix = None
        raw_fix = f.get("fix")
        if raw_fix is not None:
            if not isinstance(raw_fix, dict) or type(raw_fix.get("safe")) is not bool:
                raise _Bad
            edits = raw_fix.get("edits")
            if not isinstance(edits, list):
                raise _Bad
            fix = Fix(
                _str(raw_fix.get("message")),
                tuple(
                    Edit(_int(e[0], 1), _int(e[1], 1), _int(e[2], 1), _str(e[3]))
                    for e in edits
                    if isinstance(e, list) and len(e) == 4
                ),
                raw_fix["safe"],
            )
        code = _str(f.get("code"), 5)
        if not _CODE.fullmatch(code):
            raise _Bad
        end_column = f.get("end_column")
        source = f.get("source")
        findings.append(
            Finding(
                path=path,
                line=_int(f.get("line"), 1),
                column=_int(f.get("column"), 1),
                code=code,
                severity=Severity.parse(_str(f.get("severity"), 10)),
                message=_str(f.get("message")),
                name=_str(f.get("name"), 200),
                fix=fix,
                end_column=_int(end_column, 1) if end_column is not None else None,
                source=_str(source) if source is not None else None,
            )
        )
    context = _context(data.get("context"))
    return FileResult(
        path, findings, dialect, _str(data.get("dialect_reason"), 2000), _int(data.get("lines")), context=context
    )
