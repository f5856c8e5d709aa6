"""Shared test helpers.  The corpus is read in place from ../shared/corpus (never copied)."""

from __future__ import annotations

import functools
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _shared() -> Path:
    """The workplace's shared folder (corpus, seeds): $GCLINT_SHARED, else the folder ``shared`` beside the checkout,
    else /work/shared (where a clone made elsewhere, e.g. in a temporary folder, still finds it)."""
    for candidate in (os.environ.get("GCLINT_SHARED"), ROOT.parent / "shared", "/work/shared"):
        if candidate and Path(candidate, "corpus").is_dir():
            return Path(candidate).resolve()
    return (ROOT.parent / "shared").resolve()


SHARED = _shared()
CORPUS = Path(os.environ.get("GCLINT_CORPUS", SHARED / "corpus")).resolve()
SEEDS = SHARED / "seeds"
FIXTURES = ROOT / "tests" / "fixtures"


def corpus_available() -> bool:
    return CORPUS.is_dir()


needs_corpus = pytest.mark.skipif(not corpus_available(), reason=f"corpus not found at {CORPUS}")

# The corpus-wide equivalence tests (fast path against grammar, plain route against general route) read
# big jobs as a sample by default: the head and the tail, where slicers put everything but the repeated
# moves.  GCLINT_SLOW=1 reads every line of every job (before a release, or after touching those routes).
SLOW = bool(os.environ.get("GCLINT_SLOW"))
SAMPLE_HEAD, SAMPLE_TAIL = 4000, 1500  # lines kept of a job longer than both
_SAMPLES: dict[Path, str] = {}


def sample_bytes(data: bytes) -> bytes:
    """``data`` (a job's bytes), or its first and last lines when it is long and GCLINT_SLOW is not set."""
    if SLOW:
        return data
    lines = data.splitlines(keepends=True)
    if len(lines) <= SAMPLE_HEAD + SAMPLE_TAIL:
        return data
    return b"".join(lines[:SAMPLE_HEAD] + lines[-SAMPLE_TAIL:])


@functools.cache
def _samples_folder() -> tempfile.TemporaryDirectory:
    """One temporary folder for this process's samples, removed when it exits."""
    return tempfile.TemporaryDirectory(prefix="gclint-samples-")


def corpus_job(path: Path) -> str:
    """The path of ``path`` as a test reads it: the file itself, or a sample of it (``sample_bytes``) in a
    temporary copy with the same name (a regular file, as the original: its tail is read as a file's)."""
    if SLOW or path.stat().st_size < 200_000:
        return str(path)
    sample = _SAMPLES.get(path)
    if sample is None:
        folder = Path(_samples_folder().name, str(len(_SAMPLES)))
        folder.mkdir()
        target = folder / path.name
        target.write_bytes(sample_bytes(path.read_bytes()))
        sample = _SAMPLES[path] = str(target)
    return sample


def run_cli(
    *args: str,
    input: bytes | None = None,
    cwd: str | os.PathLike | None = None,
    env: dict | None = None,
    timeout: float = 120,
) -> subprocess.CompletedProcess:
    """Run ``python -m gclint ARGS`` in a subprocess (the real command line)."""
    full_env = dict(os.environ)
    full_env.pop("GCLINT_CACHE_DIR", None)
    if env:
        full_env.update(env)
    return subprocess.run(
        [sys.executable, "-m", "gclint", *args],
        input=input,
        capture_output=True,
        cwd=cwd,
        env=full_env,
        timeout=timeout,
    )


@pytest.fixture
def cli():
    return run_cli


@pytest.fixture(autouse=True, scope="session")
def _private_user_cache(tmp_path_factory):
    """The result cache lives in the user's cache folder: give the test session its own (subprocesses inherit
    it through the environment), so that tests never read or write the real user's cache."""
    folder = tmp_path_factory.mktemp("user-cache")
    old = os.environ.get("XDG_CACHE_HOME")
    os.environ["XDG_CACHE_HOME"] = str(folder)
    yield folder
    if old is None:
        os.environ.pop("XDG_CACHE_HOME", None)
    else:
        os.environ["XDG_CACHE_HOME"] = old


def pytest_configure(config: pytest.Config) -> None:
    """Compile gclint's modules once, before the workers start: the CLI tests run ``python -m gclint`` in
    hundreds of subprocesses, and where PYTHONDONTWRITEBYTECODE is set (CI sandboxes) each would compile
    every module again (as installed for a user, Python keeps the bytecode)."""
    if not hasattr(config, "workerinput"):  # (the controller, or a run without xdist)
        import compileall

        import gclint

        compileall.compile_dir(os.path.dirname(gclint.__file__), quiet=1)
