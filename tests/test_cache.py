"""The result cache: a second run over unchanged files reads the findings back; any change that could
change them (content, configuration, rule selection, gclint's code) misses."""

from __future__ import annotations

import hashlib
import io
import json
import os
import re
import threading
from pathlib import Path

import pytest

from gclint import cache as cache_mod
from gclint.cache import ResultCache
from gclint.engine import Linter, Options
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


# -- the cache can never change an answer (issue 12, items 1-3) ------------------------------------------------

CLEAN = b"; gclint: dialect=hyrel\nG28 X0 Y0\nM30\n"
HOSTILE = b"; gclint: dialect=hyrel\nM792 ; SHELL C:\\x.exe\n"


def _user_env(tmp_path, name="user"):
    """An environment whose user cache folder is private to this test."""
    home = tmp_path / name
    home.mkdir(exist_ok=True)
    return {"XDG_CACHE_HOME": str(home), "HOME": str(home)}


def test_stdin_through_dev_stdin_is_never_cached(tmp_path):
    env = _user_env(tmp_path)
    first = run_cli("check", "/dev/stdin", input=CLEAN, env=env, cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    second = run_cli("check", "/dev/stdin", input=HOSTILE, env=env, cwd=tmp_path)
    assert second.returncode == 1 and b"SC001" in second.stdout, (second.stdout, second.stderr)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes")
def test_named_pipe_is_read_once_as_a_stream(tmp_path):
    env = _user_env(tmp_path)
    fifo = tmp_path / "job.gcode"
    os.mkfifo(fifo)
    for content, code in ((CLEAN, 0), (HOSTILE, 1), (CLEAN, 0)):
        writer = threading.Thread(target=fifo.write_bytes, args=(content,))
        writer.start()
        proc = run_cli("check", str(fifo), env=env, cwd=tmp_path, timeout=30)
        writer.join(timeout=30)
        assert proc.returncode == code, (content, proc.stdout, proc.stderr)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes")
def test_named_pipe_in_a_folder_is_not_opened(tmp_path):
    folder = tmp_path / "jobs"
    folder.mkdir()
    (folder / "a.gcode").write_bytes(CLEAN)
    os.mkfifo(folder / "pipe.gcode")
    proc = run_cli("check", str(folder), env=_user_env(tmp_path), cwd=tmp_path, timeout=30)
    stderr = proc.stderr.decode()
    assert proc.returncode == 2 and "pipe.gcode" in stderr and "not a regular file" in stderr, stderr


def test_result_is_stored_under_the_bytes_that_were_checked(tmp_path, monkeypatch):
    """A file replaced while it is checked: the result belongs to the old bytes, not to the new ones."""
    path = _job(tmp_path, CLEAN.decode())
    cache = ResultCache(str(tmp_path / "cache"))
    original = Linter.check_source

    def check_then_replace(self, source):
        result = original(self, source)
        Path(path).write_bytes(HOSTILE)
        return result

    monkeypatch.setattr(Linter, "check_source", check_then_replace)
    first = run([path], Options(), {}, cache=cache)
    assert first[0].findings == []
    monkeypatch.setattr(Linter, "check_source", original)
    second = run([path], Options(), {}, cache=cache)
    assert [f.code for f in second[0].findings] == ["SC001"]


def test_same_size_same_mtime_rewrite_is_seen(tmp_path):
    path = _job(tmp_path, "; gclint: dialect=hyrel\nM792 ; BEEP1 C:\\x.exe\n")
    cache = ResultCache(str(tmp_path / "cache"))
    run([path], Options(), {}, cache=cache)
    st = os.stat(path)
    Path(path).write_bytes(b"; gclint: dialect=hyrel\nM792 ; SHELL C:\\x.exe\n")
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))
    assert os.stat(path).st_size == st.st_size
    result = run([path], Options(), {}, cache=cache)
    assert [f.code for f in result[0].findings] == ["SC001"]


def test_cache_is_not_in_the_project_or_the_working_folder(tmp_path):
    env = _user_env(tmp_path)
    project = tmp_path / "project"
    project.mkdir()
    (project / "job.gcode").write_bytes(CLEAN)
    proc = run_cli("check", "job.gcode", env=env, cwd=project)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in project.iterdir()) == ["job.gcode"]
    assert list((tmp_path / "user" / "gclint").rglob("*.json")), "no entry in the user cache folder"


def test_a_committed_cache_entry_is_not_trusted(tmp_path):
    """An entry planted in the checkout (the old .gclint_cache, or a --cache-dir inside the project), with the
    right sha256 and no findings, never makes a hostile job pass."""
    env = _user_env(tmp_path)
    project = tmp_path / "project"
    project.mkdir()
    job = project / "job.gcode"
    job.write_bytes(CLEAN)
    folder = project / ".gclint_cache"
    assert run_cli("check", "--cache-dir", str(folder), str(job), env=env, cwd=project).returncode == 0
    entries = list(folder.rglob("*.json"))
    assert len(entries) == 1
    planted = entries[0].read_bytes()
    job.write_bytes(HOSTILE)
    digest = hashlib.sha256(HOSTILE).hexdigest()
    forged = re.sub(rb'"sha256": ?"[0-9a-f]{64}"', b'"sha256": "' + digest.encode() + b'"', planted)
    forged = re.sub(rb'"size": ?\d+', b'"size": %d' % len(HOSTILE), forged)
    forged = re.sub(rb'"mtime_ns": ?\d+', b'"mtime_ns": %d' % job.stat().st_mtime_ns, forged)
    assert forged != planted
    entries[0].write_bytes(forged)
    for args in (("--cache-dir", str(folder)), ()):
        proc = run_cli("check", *args, str(job), env=env, cwd=project)
        assert proc.returncode == 1 and b"SC001" in proc.stdout, (args, proc.stdout, proc.stderr)
    # the old format (JSON only, no signature), as committed with a pull request
    old = {"settings": "x", "path": str(job), "size": len(HOSTILE), "sha256": digest, "result": {"findings": []}}
    entries[0].write_text(json.dumps(old))
    proc = run_cli("check", "--cache-dir", str(folder), str(job), env=env, cwd=project)
    assert proc.returncode == 1 and b"SC001" in proc.stdout


def test_entries_of_another_user_are_not_trusted(tmp_path):
    project = tmp_path / "project"
    project.mkdir()
    job = project / "job.gcode"
    job.write_bytes(CLEAN)
    folder = tmp_path / "shared-cache"
    alice, bob = _user_env(tmp_path, "alice"), _user_env(tmp_path, "bob")
    assert run_cli("check", "--cache-dir", str(folder), str(job), env=alice).returncode == 0
    # Alice's entry says "clean" for the clean bytes; Bob's gclint must not take it as its own...
    cache = ResultCache(str(folder), root=tmp_path / "bob" / "gclint")
    key = ResultCache.settings_key(Options(dialect="auto").cache_key(), ["SC001"])
    assert cache.get(str(job), key) is None
    # ... and Bob's run checks the file itself (and still gets the right answer).
    job.write_bytes(HOSTILE)
    proc = run_cli("check", "--cache-dir", str(folder), str(job), env=bob)
    assert proc.returncode == 1 and b"SC001" in proc.stdout


@pytest.mark.skipif(os.name == "nt", reason="POSIX permissions")
def test_world_writable_cache_folder_is_refused(tmp_path):
    folder = tmp_path / "shared"
    folder.mkdir()
    folder.chmod(0o777)
    job = _job(tmp_path, CLEAN.decode())
    proc = run_cli("check", "--cache-dir", str(folder), job, env=_user_env(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert b"not used" in proc.stderr and str(folder).encode() in proc.stderr
    assert not list(folder.rglob("*.json")), "an entry was written into a world-writable folder"


def test_cache_writes_never_follow_symbolic_links(tmp_path):
    job = _job(tmp_path, CLEAN.decode())
    folder = tmp_path / "cache"
    outside = tmp_path / "outside"
    outside.mkdir()
    env = _user_env(tmp_path)
    assert run_cli("check", "--cache-dir", str(folder), job, env=env).returncode == 0
    [entry] = list(folder.rglob("*.json"))
    # a dangling link where the entry goes, and a linked sub-folder
    entry.unlink()
    entry.symlink_to(outside / "victim.json")
    assert run_cli("check", "--cache-dir", str(folder), job, env=env).returncode == 0
    assert not (outside / "victim.json").exists()
    sub = entry.parent
    for child in sub.iterdir():
        child.unlink()
    sub.rmdir()
    sub.symlink_to(outside, target_is_directory=True)
    assert run_cli("check", "--cache-dir", str(folder), job, env=env).returncode == 0
    assert list(outside.iterdir()) == []
    # the .gitignore marker too
    (folder / ".gitignore").unlink()
    (folder / ".gitignore").symlink_to(outside / "marker")
    assert run_cli("check", "--cache-dir", str(folder), job, env=env).returncode == 0
    assert not (outside / "marker").exists()


MALFORMED = [
    b"",
    b"\x00\xff" * 100,
    b"[]",
    b"null",
    b'{"result": 5}',
    b'{"result": {"findings": [{"line": "x"}]}}',
    b'{"result": {"path": 1, "findings": "abc", "dialect": [], "dialect_reason": {}, "lines": -1}}',
    b"[" * 100_000,
    b'{"result": {"findings": [{"line": 1e400, "column": -5, "code": 7, "severity": "fatal"}]}}',
]


@pytest.mark.parametrize("payload", MALFORMED, ids=[f"malformed-{i}" for i in range(len(MALFORMED))])
def test_malformed_entries_never_crash_any_format(tmp_path, payload):
    """Even an entry that carries this user's valid signature is checked field by field before use."""
    from gclint.reports import ReportContext, formats

    path = _job(tmp_path)
    cache = ResultCache(str(tmp_path / "cache"))
    expected = _key(run([path], Options(), {}, cache=cache))
    [entry] = list((tmp_path / "cache").rglob("*.json"))
    data = json.loads(cache._unsign(entry.read_bytes()))
    body = payload
    if payload.startswith(b"{") and b'"result"' in payload:
        patch = json.loads(payload)
        data["result"] = {**data["result"], **patch["result"]} if isinstance(patch["result"], dict) else 5
        body = json.dumps(data).encode()
    entry.write_bytes(cache._sign(body))
    results = run([path], Options(), {}, cache=cache)
    assert _key(results) == expected and cache.hits == 0
    for writer in formats().values():
        writer(results, io.StringIO(), ReportContext())


def test_cache_files_hold_no_secret(tmp_path):
    secret = "hunter2 with spaces"
    path = _job(tmp_path, f"; gclint: dialect=marlin\n; printhost_password = {secret}\nM117 token=abcdef123456\n")
    folder = tmp_path / "cache"
    run([path], Options(), {}, cache=ResultCache(str(folder)))
    blob = b"".join(p.read_bytes() for p in folder.rglob("*") if p.is_file())
    assert b"hunter2" not in blob and b"with spaces" not in blob and b"abcdef123456" not in blob


def test_clean_removes_the_result_cache(tmp_path):
    env = _user_env(tmp_path)
    project = tmp_path / "project"
    project.mkdir()
    (project / "job.gcode").write_bytes(CLEAN)
    assert run_cli("check", "job.gcode", env=env, cwd=project).returncode == 0
    user_cache = tmp_path / "user" / "gclint"
    assert list(user_cache.rglob("*.json"))
    proc = run_cli("clean", env=env, cwd=project)
    assert proc.returncode == 0 and b"removed" in proc.stdout + proc.stderr, proc.stderr
    assert not list(user_cache.rglob("*.json"))
    # --cache-dir / GCLINT_CACHE_DIR, and nothing but gclint's own files is ever removed there
    folder = tmp_path / "mine"
    assert run_cli("check", "--cache-dir", str(folder), str(project / "job.gcode"), env=env).returncode == 0
    (folder / "notes.txt").write_text("keep me")
    proc = run_cli("clean", env={**env, "GCLINT_CACHE_DIR": str(folder)}, cwd=project)
    assert proc.returncode == 0, proc.stderr
    assert not list(folder.rglob("*.json")) and (folder / "notes.txt").read_text() == "keep me"


def test_clean_leaves_a_folder_gclint_did_not_mark_alone(tmp_path):
    """Issue 25: ``gclint clean --cache-dir notes`` deleted notes/project, notes/ab/.tmp-draft and the folder,
    then said "no cached results".  Only a folder gclint marked as its cache is cleaned."""
    env = _user_env(tmp_path)
    notes = tmp_path / "notes"
    (notes / "ab").mkdir(parents=True)
    (notes / "project").write_text("my project notes\n")
    (notes / "ab" / ".tmp-draft").write_text("draft\n")
    (notes / "ab" / ("a" * 32 + ".json")).write_text("{}\n")
    proc = run_cli("clean", "--cache-dir", str(notes), env=env)
    [line] = proc.stderr.decode().splitlines()
    assert proc.returncode == 2 and "notes: not a result cache folder" in line and "nothing removed" in line
    assert sorted(p.relative_to(notes).as_posix() for p in notes.rglob("*")) == [
        "ab", "ab/.tmp-draft", "ab/" + "a" * 32 + ".json", "project",
    ]  # fmt: skip


def test_clean_removes_only_entries_that_verify(tmp_path):
    env = _user_env(tmp_path)
    (tmp_path / "job.gcode").write_bytes(CLEAN)
    folder = tmp_path / "cache"
    assert run_cli("check", "--cache-dir", str(folder), str(tmp_path / "job.gcode"), env=env).returncode == 0
    [entry] = folder.rglob("*.json")
    planted = entry.parent / ("b" * 32 + ".json")  # an entry someone else wrote (a forged or foreign one)
    planted.write_bytes(b"0" * 64 + b"\n{}")
    (entry.parent / ".tmp-draft").write_text("not gclint's\n")
    proc = run_cli("clean", "--cache-dir", str(folder), env=env)
    assert proc.returncode == 0 and b"removed 1 cached result" in proc.stdout, proc.stderr
    assert not entry.exists() and planted.exists() and (entry.parent / ".tmp-draft").exists()
    assert (folder / ".gitignore").exists()  # the marker and the folder stay while anything else does
    planted.unlink()
    (entry.parent / ".tmp-draft").unlink()
    assert run_cli("clean", "--cache-dir", str(folder), env=env).returncode == 0
    assert not folder.exists()


def test_a_committed_cache_folder_link_never_takes_writes_out_of_the_checkout(tmp_path):
    """Issue 25: a committed ``.gclint_cache -> somewhere`` with ``--cache-dir .gclint_cache`` (as CI caches
    it) made gclint write its entries outside the checkout."""
    env = _user_env(tmp_path)
    repo = tmp_path / "repo"
    repo.mkdir()
    (repo / ".git").mkdir()
    (repo / "job.gcode").write_bytes(CLEAN)
    outside = tmp_path / "outside"
    outside.mkdir()
    (repo / ".gclint_cache").symlink_to(outside, target_is_directory=True)
    for args in (["--cache-dir", ".gclint_cache"], []):
        extra = {} if args else {"GCLINT_CACHE_DIR": ".gclint_cache"}
        proc = run_cli("check", *args, "job.gcode", env={**env, **extra}, cwd=repo)
        assert proc.returncode == 0 and list(outside.iterdir()) == [], proc.stderr
        assert b"is a link out of this checkout" in proc.stderr
    # a cache folder the user names outside the checkout is the user's choice
    assert run_cli("check", "--cache-dir", str(outside), "job.gcode", env=env, cwd=repo).returncode == 0
    assert list(outside.rglob("*.json"))


def test_the_same_configuration_elsewhere_is_another_cache_key(tmp_path):
    """allow-file-writes and per-file-ignores patterns are relative to the configuration's folder: the same
    bytes in another folder match other files, so a cached result made under one must not answer the other
    (a cached "passed" hid an SC005 error)."""
    (tmp_path / "p" / "sys").mkdir(parents=True)
    (tmp_path / "p" / "sys" / "save.g").write_text('M28 "0:/sys/foo.g"\n')
    rule = 'allow-file-writes = ["sys/*.g"]\n'
    (tmp_path / "p" / "here.toml").write_text(rule)
    (tmp_path / "up.toml").write_text(rule)
    env = {"GCLINT_CACHE_DIR": str(tmp_path / "cache")}
    assert run_cli("check", "p", "--config", "p/here.toml", cwd=tmp_path, env=env).returncode == 0
    proc = run_cli("check", "p", "--config", "up.toml", cwd=tmp_path, env=env)
    assert proc.returncode == 1 and b"SC005" in proc.stdout, proc.stdout
