"""The result cache: a second run over unchanged files reads the findings back; any change that could
change them (content, configuration, rule selection, gclint's code) misses."""

from __future__ import annotations

import json
import os

from gclint import cache as cache_mod
from gclint.cache import ResultCache
from gclint.engine import Options
from gclint.runner import run

from .conftest import run_cli

JOB = "; gclint: dialect=hyrel\nM229 E1 D0\nG1 X1 X2 ; caf\udce9\nM109 T40 S200\n"


def _job(tmp_path, text=JOB, name="a.gcode"):
    path = tmp_path / name
    path.write_bytes(text.encode("utf-8", "surrogateescape"))
    return str(path)


def _key(results):
    return [(f.path, f.line, f.column, f.code, f.severity, f.message, f.source) for r in results for f in r.findings]


def test_second_run_is_served_from_the_cache(tmp_path):
    path = _job(tmp_path)
    cache = ResultCache(str(tmp_path / "cache"))
    first = run([path], Options(), {}, cache=cache)
    assert cache.misses == 1 and cache.hits == 0 and first[0].findings
    second = run([path], Options(), {}, cache=cache)
    assert cache.hits == 1
    assert _key(second) == _key(first)
    assert second[0].lines == first[0].lines and second[0].dialect == first[0].dialect


def test_changes_invalidate(tmp_path, monkeypatch):
    path = _job(tmp_path)
    cache = ResultCache(str(tmp_path / "cache"))
    run([path], Options(), {}, cache=cache)
    # configuration from the command line
    run([path], Options(), {"ignore": ["HY"]}, cache=cache)
    assert cache.hits == 0
    # content (same size, same mtime: the hash decides)
    st = os.stat(path)
    _job(tmp_path, JOB.replace("T40", "T41"))
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))
    result = run([path], Options(), {}, cache=cache)
    assert cache.hits == 0 and "T41" in "".join(f.source or "" for f in result[0].findings)
    # a configuration file next to the job
    (tmp_path / "gclint.toml").write_text('printer = "ehr"\n')
    run([path], Options(), {}, cache=cache)
    assert cache.hits == 0
    # gclint's own code
    run([path], Options(), {}, cache=cache)
    assert cache.hits == 1
    monkeypatch.setattr(cache_mod, "code_fingerprint", lambda: "changed")
    run([path], Options(), {}, cache=cache)
    assert cache.hits == 1


def test_damaged_entries_are_ignored(tmp_path):
    path = _job(tmp_path)
    cache = ResultCache(str(tmp_path / "cache"))
    expected = _key(run([path], Options(), {}, cache=cache))
    for entry in (tmp_path / "cache").rglob("*.json"):
        entry.write_text("{not json")
    assert _key(run([path], Options(), {}, cache=cache)) == expected
    assert cache.hits == 0


def test_cli_cache_dir_and_no_cache(tmp_path):
    path = _job(tmp_path)
    folder = tmp_path / "my-cache"
    first = run_cli("check", path, "--format", "json", "--cache-dir", str(folder))
    assert folder.is_dir() and (folder / ".gitignore").is_file()
    entries = list(folder.rglob("*.json"))
    assert len(entries) == 1
    second = run_cli("check", path, "--format", "json", "--cache-dir", str(folder))
    assert json.loads(first.stdout) == json.loads(second.stdout) and second.returncode == first.returncode == 1
    other = tmp_path / "unused"
    run_cli("check", path, "--no-cache", "--cache-dir", str(other))
    assert not other.exists()


def test_unwritable_cache_folder_is_not_fatal(tmp_path):
    path = _job(tmp_path)
    blocker = tmp_path / "file-not-folder"
    blocker.write_text("x")
    proc = run_cli("check", path, "--cache-dir", str(blocker / "cache"))
    assert proc.returncode == 1 and b"Traceback" not in proc.stderr
