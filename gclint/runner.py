"""Run checks over many paths: collect G-code files from folders, apply the configuration that belongs
to each file, spread the work over processes, and return results in a stable order."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from gclint.config import ConfigError, apply, config_for, find_config
from gclint.engine import FileResult, Linter, Options
from gclint.syntax.source import Source, SourceError

if TYPE_CHECKING:
    from gclint.cache import ResultCache

GCODE_EXTENSIONS = (".gcode", ".gco", ".g", ".nc", ".ngc", ".cnc", ".tap")


def collect(paths: Iterable[str]) -> tuple[list[str], list[FileResult]]:
    """Expand folders into their G-code files (sorted, hidden folders skipped).

    Returns the files to check and results for the paths that cannot be checked (missing, empty folder).
    """
    files: list[str] = []
    problems: list[FileResult] = []
    seen: set[str] = set()
    for path in paths:
        if path == "-":
            files.append(path)
            continue
        if os.path.isdir(path):
            found = []
            for folder, subdirs, names in os.walk(path):
                subdirs[:] = sorted(d for d in subdirs if not d.startswith("."))
                for name in sorted(names):
                    if name.lower().endswith(GCODE_EXTENSIONS):
                        found.append(os.path.join(folder, name))
            if not found:
                problems.append(
                    FileResult(path, error=f"{path}: no G-code files in this folder ({' '.join(GCODE_EXTENSIONS)})")
                )
            for f in found:
                if f not in seen:
                    seen.add(f)
                    files.append(f)
        elif os.path.exists(path):
            if path not in seen:
                seen.add(path)
                files.append(path)
        else:
            problems.append(FileResult(path, error=f"{path}: no such file or folder"))
    return files, problems


def options_for(path: str, base: Options, overrides: dict, explicit_config: str | None) -> Options:
    """Defaults, then the configuration file that applies to ``path``, then the command line."""
    config_path, table = config_for(path, explicit_config)
    options = base
    if config_path is not None:
        options = apply(options, table, config_path)
    if overrides and overrides.get("extend_known_codes"):  # adds to the configuration's codes
        overrides = {**overrides, "extend_known_codes": options.extend_known_codes + overrides["extend_known_codes"]}
    return replace(options, **overrides) if overrides else options


_LINTERS: dict[str, Linter] = {}


def linter_for(options: Options) -> Linter:
    """The (per-process, cached) linter for ``options``."""
    return _linter(options)


def _linter(options: Options) -> Linter:
    key = options.cache_key()
    linter = _LINTERS.get(key)
    if linter is None:
        linter = _LINTERS[key] = Linter(options)
    return linter


def check_one(path: str, options: Options) -> FileResult:
    """Check one file with its options; never raises for a bad file."""
    try:
        return _linter(options).check_path(path)
    except SourceError as exc:
        return FileResult(path, error=str(exc))
    except RecursionError:
        return FileResult(path, error=f"{path}: nesting too deep to check")
    except MemoryError:
        return FileResult(path, error=f"{path}: out of memory while checking")
    except Exception as exc:  # a bug in gclint itself: name the file, keep going with the others
        detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
        return FileResult(path, error=f"{path}: internal error while checking ({detail}); please report this")


def _check_task(args: tuple[str, Options]) -> FileResult:
    return check_one(*args)


def run(
    files: list[str],
    base: Options,
    overrides: dict,
    explicit_config: str | None = None,
    jobs: int = 1,
    stdin_name: str = "-",
    progress: Callable[[FileResult], None] | None = None,
    cache: ResultCache | None = None,
) -> list[FileResult]:
    """Check ``files``; results come back in the order of ``files``.

    With a ``cache``, files whose content, configuration and rule set are unchanged since the last run
    are not checked again.
    """
    find_config.cache_clear()
    tasks: list[tuple[str, Options]] = []
    keys: dict[int, str] = {}
    results: dict[int, FileResult] = {}
    for index, path in enumerate(files):
        try:
            options = options_for(path, base, overrides, explicit_config)
        except ConfigError as exc:
            results[index] = FileResult(path, error=str(exc))
            continue
        if path == "-":
            linter = _linter(options)
            try:
                results[index] = linter.check_source(Source(_stdin(), stdin_name))
            except SourceError as exc:
                results[index] = FileResult(stdin_name, error=str(exc))
            except Exception as exc:  # a bug in gclint itself: one line, no traceback
                detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
                error = f"{stdin_name}: internal error while checking ({detail}); please report this"
                results[index] = FileResult(stdin_name, error=error)
            continue
        if cache is not None:
            key = cache.settings_key(options.cache_key(), [r.code for r in _linter(options).rule_classes])
            cached = cache.get(path, key)
            if cached is not None:
                results[index] = cached
                if progress is not None:
                    progress(cached)
                continue
            keys[index] = key
        tasks.append((path, options))
    order = [i for i in range(len(files)) if i not in results]
    for index, result in zip(order, _map(tasks, jobs), strict=True):
        results[index] = result
        if cache is not None and index in keys:
            cache.put(files[index], keys[index], result)
        if progress is not None:
            progress(result)
    return [results[i] for i in range(len(files))]


def _map(tasks: list[tuple[str, Options]], jobs: int) -> Iterator[FileResult]:
    if jobs <= 1 or len(tasks) <= 1:
        for task in tasks:
            yield _check_task(task)
        return
    workers = min(jobs, len(tasks))
    with ProcessPoolExecutor(max_workers=workers) as pool:
        # chunksize > 1 keeps the inter-process traffic low for many small files
        chunk = max(1, min(16, len(tasks) // (workers * 4)))
        yield from pool.map(_check_task, tasks, chunksize=chunk)


def _stdin():
    import sys

    return sys.stdin.buffer


def default_jobs() -> int:
    return os.cpu_count() or 1


__all__ = ["collect", "run", "check_one", "options_for", "GCODE_EXTENSIONS", "default_jobs", "Path"]
