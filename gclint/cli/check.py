"""gclint check: lint files and folders, fix them, report in every format.

The command is a pipeline of named steps over one ``CheckRequest`` (its parameters, checked once):

1. ``CheckRequest.from_click``: the parameters, each checked (the usage errors) and resolved into the
   ``overrides`` every file's options start from;
2. ``_collect``: the files the paths name, and what the walk left out (notes);
3. ``_refuse_overwriting``, ``_cap_jobs``; ``--show-settings`` (``_show_settings``) ends here;
4. ``CheckRequest.refusal``: the flag combinations refused (after the walk and ``--show-settings``,
   which ignores them); ``--fix -`` (``_fix_stdin``) ends here;
5. ``_configure``: every file's configuration read once (a broken one is one usage error), the
   configuration notes;
6. ``_prepare``: the progress bar, the cache and the run's options (``_Run``);
7. ``_check_and_report`` (the report written file by file) or ``_check_and_rewrite`` (``--fix``,
   ``--diff``, ``--add-noqa``: the whole run, then the files rewritten);
8. ``_exit_for``: exit 2 for a file that could not be read, 1 for a finding that reaches ``--fail-on``.

Imports are lazy (inside the steps, as the formats' registry is): a one-file check's start-up is measured by
bench/bench_startup.py, and ``python -X importtime -m gclint check one.gcode`` shows what it loads.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, NoReturn

import click

from gclint import __version__
from gclint.cli.app import (
    _QUIET,
    _abandon_stdout,
    _check_dialect,
    _check_printer,
    _error,
    _fail,
    _left_out_notes,
    _note,
    _reaches,
    _same_file,
    _split,
    fail_on_option,
    main,
)
from gclint.config import ConfigError, check_flavor, parse_heads, parse_known_codes
from gclint.engine import FileResult, Options
from gclint.machine.profiles import PROFILES
from gclint.rules.base import RuleError

if TYPE_CHECKING:
    from gclint.cache import ResultCache
    from gclint.excludes import LeftOut
    from gclint.progress import ProgressBar
    from gclint.runner import RunOptions


@dataclass(kw_only=True)
class CheckRequest:
    """``gclint check``'s command line: click's parameters (their defaults are the options' own) and the
    ``overrides`` they resolve to (``from_click``).  The steps read it; none changes it."""

    paths: tuple[str, ...]
    dialect: str | None
    printer: str | None
    flavor: str | None
    loaded: str | None
    select: tuple[str, ...]
    ignore: tuple[str, ...]
    extend_select: tuple[str, ...]
    extend_known_codes: tuple[str, ...]
    fmt: str
    output: str | None
    exit_zero: bool
    fail_on: str
    exclude: tuple[str, ...]
    extend_exclude: tuple[str, ...]
    force_exclude: bool | None
    respect_gitignore: bool | None
    statistics: bool
    no_group: bool
    jobs: int | None
    config_file: str | None
    fix: bool
    unsafe_fixes: bool
    show_diff: bool
    show_fixes: bool
    add_noqa: bool
    stdin_filename: str | None
    no_cache: bool
    cache_dir: str | None
    progress: bool | None
    verbose: bool
    quiet: bool
    show_settings: bool
    # what the command line sets in every file's options (runner.options_for), from the parameters above
    overrides: dict = field(default_factory=dict)

    @classmethod
    def from_click(cls, params: dict[str, Any]) -> CheckRequest:
        """The request of click's parameters, checked: a parameter that is wrong is a usage error (exit 2),
        the first one found in the order below."""
        request = cls(**params)
        request._check_entry()
        request.overrides = request._resolve()
        request._check_paths_options()
        return request

    @property
    def fixing(self) -> bool:
        """``--fix`` or ``--diff``: the fixes are applied (or shown)."""
        return self.fix or self.show_diff

    @property
    def rewriting(self) -> bool:
        """``--fix``, ``--diff`` or ``--add-noqa``: the whole run is checked first, then the files rewritten."""
        return self.fix or self.show_diff or self.add_noqa

    @property
    def stdin_name(self) -> str:
        return self.stdin_filename or "-"

    def _check_entry(self) -> None:
        if os.environ.get("PRE_COMMIT") == "1" and "--" not in sys.argv[1:]:
            # pre-commit appends file names after the hook's args: without "--", a committed file named
            # "--config=x.gcode" would be read as an option (.pre-commit-hooks.yaml); refused even when no
            # path is left, since the only file named may have been read as one ("--output=ok.gcode")
            _fail(
                "as a pre-commit hook, gclint needs '--' before the file names: end the hook's args with '--'"
                " (args: [--printer, 30m, --]) so that a file name is never read as an option"
            )
        from gclint.reports import FORMATS

        if self.fmt not in FORMATS:
            _fail(f"unknown format {self.fmt!r} (known: {', '.join(sorted(FORMATS))})")

    def _resolve(self) -> dict:
        """The overrides: dialect, printer, flavour, heads, known codes and rule selection, each checked."""
        overrides: dict = {}
        if self.dialect is not None:
            overrides["dialect"] = _check_dialect(self.dialect)
            overrides["dialect_origin"] = "option"
        if self.printer is not None:
            overrides["printer"] = _check_printer(self.printer)
            overrides["printer_origin"] = "option"
        try:
            if self.flavor is not None:
                overrides["flavor"] = check_flavor(self.flavor, "--flavor")
                overrides["flavor_origin"] = "option"
            if self.loaded is not None:
                overrides["loaded"] = parse_heads(self.loaded)
            if self.extend_known_codes:
                overrides["extend_known_codes"] = parse_known_codes(",".join(self.extend_known_codes))
        except ConfigError as exc:
            _fail(str(exc))
        from gclint.rules.base import UnknownSelector, resolve_selectors

        try:
            if self.select:
                overrides["select"] = resolve_selectors(_split(self.select), "--select: ")
                overrides.setdefault("ignore", [])  # as ruff: the command line's selection is a new start
            if self.ignore:
                overrides["ignore"] = resolve_selectors(_split(self.ignore), "--ignore: ")
            if self.extend_select:
                overrides["extend_select"] = resolve_selectors(_split(self.extend_select), "--extend-select: ")
        except (UnknownSelector, RuleError) as exc:
            _fail(str(exc))
        return overrides

    def _check_paths_options(self) -> None:
        if self.config_file is not None and not os.path.isfile(self.config_file):
            _fail(f"{self.config_file}: configuration file not found")
        from gclint.config import check_pattern

        try:
            for pattern in _split(self.exclude):
                check_pattern(pattern, "--exclude")
            for pattern in _split(self.extend_exclude):
                check_pattern(pattern, "--extend-exclude")
        except ConfigError as exc:
            _fail(str(exc))

    def refusal(self) -> str | None:
        """The usage error of a combination of flags, or None.  Asked after the walk's notes and
        ``--show-settings`` (which ignores these flags), where gclint has always refused them."""
        if self.unsafe_fixes and not self.fixing:
            return "--unsafe-fixes goes with --fix or --diff"
        if self.add_noqa and self.fixing:
            return "--add-noqa writes noqa comments; run it without --fix and --diff"
        if self.statistics and self.fmt in ("sarif", "junit", "html"):
            return f"--statistics prints a table (text) or JSON (-f json), not {self.fmt}"
        if self.select and not self.overrides.get("select"):
            return "--select names no rule (an empty --select would check nothing)"
        return None


@dataclass
class _Files:
    """What the paths name: the files to check and what the walk met on the way."""

    files: list[str]
    problems: list[FileResult]  # paths that could not be read (not found, not G-code...)
    left_out: list[LeftOut]
    security_only: list[LeftOut]  # excluded by a configuration found beside them: SC rules only
    links: dict[str, str]  # a link checked under its own name -> the file it points to
    walk_roots: dict[str, str]  # file found in a walk -> the real path of the folder walked


@dataclass
class _Run:
    """What one run needs besides the files: the configuration notes, the progress bar, the cache and
    the options ``runner.run`` and ``runner.results`` share."""

    configuration: list[str]
    bar: ProgressBar | None
    cache: ResultCache | None
    options: RunOptions


@main.command()
@click.argument("paths", nargs=-1, type=click.Path(allow_dash=True, readable=False))
@click.option(
    "--dialect", "-d", metavar="D", help="hyrel, hyrel-v4, marlin, reprap, machinekit, carvera or auto (default)."
)
@click.option("--printer", "-p", metavar="MODEL", help=f"Hyrel model: {', '.join(PROFILES)} (default 30m).")
@click.option(
    "--flavor",
    metavar="FIRMWARE",
    help="The firmware the files are for, when they do not say: prusa-buddy, prusa-mk3, bambu, klipper, fablin... "
    "(else read from each file's slicer settings).",
)
@click.option(
    "--loaded",
    metavar="T0,T2",
    help="Head positions loaded on the yoke, in v5 numbering T0-T19 (else from the job header).",
)
@click.option("--select", multiple=True, metavar="CODES", help="Only these rule codes or prefixes (comma separated).")
@click.option("--ignore", multiple=True, metavar="CODES", help="Skip these rule codes or prefixes.")
@click.option("--extend-select", multiple=True, metavar="CODES", help="Add these to the selected rules.")
@click.option(
    "--extend-known-codes",
    multiple=True,
    metavar="CODES",
    help="Codes and command names the machine has besides its firmware's (site macros, REMAPs): never DL001.",
)
@click.option(
    "--format",
    "--output-format",  # ruff's spelling
    "-f",
    "fmt",
    default="text",
    show_default=True,
    metavar="F",
    help="text, json, sarif, github, junit, html, full, grouped.",
)
@click.option(
    "--output", "-o", type=click.Path(dir_okay=False, writable=True, allow_dash=True), help="Write the report here."
)
@click.option("--exclude", "exclude", multiple=True, metavar="GLOB", help="Leave these paths out (replaces exclude).")
@click.option("--extend-exclude", multiple=True, metavar="GLOB", help="Leave these paths out too.")
@click.option("--force-exclude", is_flag=True, default=None, help="Exclude files named on the command line too.")
@click.option(
    "--respect-gitignore/--no-respect-gitignore", default=None, help="Leave out what .gitignore ignores (default on)."
)
@click.option("--exit-zero", is_flag=True, help="Exit 0 even when findings exist.")
@fail_on_option()
@click.option(
    "--statistics",
    is_flag=True,
    help="Show the number of findings per code instead of the findings (JSON with -f json).",
)
@click.option(
    "--no-group",
    is_flag=True,
    help="Text formats: show every finding (by default a code's findings in a file after the first 3 are one line).",
)
@click.option("--jobs", "-j", type=click.IntRange(min=1), default=None, help="Parallel processes (default: CPU count).")
@click.option(
    "--config", "config_file", type=click.Path(dir_okay=False), help="Configuration file (else found upward)."
)
@click.option("--fix", is_flag=True, help="Apply the safe fixes in place.")
@click.option("--unsafe-fixes", is_flag=True, help="With --fix or --diff, apply unsafe fixes too.")
@click.option("--diff", "show_diff", is_flag=True, help="Print the fixes as a unified diff; write nothing.")
@click.option("--show-fixes", is_flag=True, help="With --fix: list the fixes applied, per file and code.")
@click.option("--add-noqa", is_flag=True, help="Add '; noqa: CODES' to every line with findings (not SC), then exit.")
@click.option("--stdin-filename", metavar="NAME", help="Name to use for the file read from '-'.")
@click.option("--no-cache", is_flag=True, help="Do not read or write the result cache.")
@click.option(
    "--cache-dir",
    type=click.Path(file_okay=False),
    envvar="GCLINT_CACHE_DIR",
    help="Cache folder (default: gclint's folder in the user cache folder, per project).",
)
@click.option(
    "--progress/--no-progress", default=None, help="Progress bar on stderr (default: on a terminal, for many files)."
)
@click.option(
    "--verbose",
    "-v",
    is_flag=True,
    help="Say for every file what it was checked as (dialect, firmware, printer) and why.",
)
@click.option("--quiet", "-q", is_flag=True, help="No notes on stderr (how files were read, what was skipped).")
@click.option(
    "--show-settings",
    is_flag=True,
    help="Print the settings each file is checked with and what it would be checked as, then exit.",
)
def check(**params: Any) -> None:
    """Check G-code files and folders (- for standard input)."""
    if params["quiet"]:
        _QUIET.append(True)
    request = CheckRequest.from_click(params)
    found = _collect(request)
    _refuse_overwriting(request, found.files)
    request = replace(request, jobs=_cap_jobs(request.jobs))
    if request.show_settings:
        _show_settings(request, found)
    if (refused := request.refusal()) is not None:
        _fail(refused)
    if request.fix and found.files == ["-"]:  # "--fix -": the fixed text on stdout, the findings left on stderr
        sys.exit(_fix_stdin(request))
    if request.fixing and "-" in found.files:
        _fail("--fix and --diff need files; '--fix -' alone fixes standard input to standard output")
    run = _prepare(request, found, _configure(request, found))
    if request.rewriting:
        _check_and_rewrite(request, found, run)
    else:
        _check_and_report(request, found, run)


def _collect(request: CheckRequest) -> _Files:
    """The files to check; the walk's notes and what it left out are said on stderr.  ``--stdin-filename``
    naming an excluded file leaves standard input out (with ``--fix``, it goes through unchanged)."""
    from gclint import runner
    from gclint.excludes import Excluder, LeftOut

    walk_notes: list[str] = []
    found = _Files([], [], left_out=[], security_only=[], links={}, walk_roots={})
    excluder = Excluder(
        exclude=_split(request.exclude) or None,
        extend_exclude=_split(request.extend_exclude),
        force=request.force_exclude,
        respect_gitignore=request.respect_gitignore,
        explicit_config=request.config_file,
    )
    paths = request.paths
    if request.stdin_filename and not paths:
        paths = ("-",)  # --stdin-filename alone reads standard input (ruff)
    found.files, found.problems = runner.collect(
        paths or (".",),
        walk_notes,
        excluder,
        found.left_out,
        found.walk_roots,
        security_only=found.security_only,
        links=found.links,
    )
    name = request.stdin_filename
    if "-" in found.files and name and (why := excluder.excluded(name, False, named=True)):
        found.files = [f for f in found.files if f != "-"]  # --force-exclude: the file it stands for is excluded
        found.left_out.append(LeftOut(name, why))
        if request.fix:
            sys.stdout.buffer.write(sys.stdin.buffer.read())  # --fix -: the text goes through unchanged
            sys.exit(0)
    for note in walk_notes:
        _note(note)
    _left_out_notes(found.left_out, request.verbose, nothing_left=not found.files and not found.problems)
    return found


def _refuse_overwriting(request: CheckRequest, files: list[str]) -> None:
    if request.output not in (None, "-") and (same := _same_file(request.output, files)) is not None:
        _fail(f"{request.output}: is {same}, one of the files to check: the report would overwrite it")


def _show_settings(request: CheckRequest, found: _Files) -> NoReturn:
    """``--show-settings``: each file's settings and what it would be checked as, then exit."""
    from gclint import settings

    for r in found.problems:
        _error(r.error or "")
    try:
        where = _cache_where(found.files, request.cache_dir, request.no_cache)
        shown = settings.show_settings(found.files, request.overrides, request.config_file, where)
    except ConfigError as exc:
        _fail(str(exc))
    click.echo(shown, nl=False)
    sys.exit(2 if found.problems else 0)


def _configure(request: CheckRequest, found: _Files) -> list[str]:
    """Every file's configuration read once, before anything is checked: a broken one is one usage error
    (not one per file, as ruff).  Returns the configuration notes (said on stderr unless the report's
    summary carries them)."""
    from gclint import runner, settings

    for path in dict.fromkeys(found.files):
        try:
            name = request.stdin_filename or path if path == "-" else path
            runner.options_for(name, Options(), request.overrides, request.config_file)
        except ConfigError as exc:
            _fail(str(exc))
    configuration = settings.configuration_notes(found.files, request.overrides, request.config_file)
    configuration += _exclusion_notes(found.left_out, found.security_only)
    if request.fmt not in TEXT_FORMATS:  # (the text formats end with them, on standard output)
        for note in configuration:
            _note(note, always=True)
    return configuration


def _prepare(request: CheckRequest, found: _Files, configuration: list[str]) -> _Run:
    """The progress bar, the result cache (not when files are rewritten) and the run's options."""
    from gclint import progress as progress_bar
    from gclint import runner
    from gclint.cache import ResultCache

    files = found.files
    bar = progress_bar.ProgressBar(files) if progress_bar.wanted(request.progress, request.fmt, files) else None
    cache = None if (request.no_cache or request.rewriting) else ResultCache(request.cache_dir)
    options: RunOptions = {  # (the same run, file by file for the reports or whole for the fixes)
        "explicit_config": request.config_file,
        "jobs": request.jobs or (runner.default_jobs() if len(files) > 1 else 1),
        "stdin_name": request.stdin_name,
        "progress": bar.advance if bar is not None else None,
        "cache": cache,
        "security_only": {item.path for item in found.security_only},
        "links": found.links,
    }
    return _Run(configuration, bar, cache, options)


def _check_and_report(request: CheckRequest, found: _Files, run: _Run) -> None:
    """Check and report file by file (memory does not grow with the run), then the notes and the exit code."""
    from gclint import runner
    from gclint.reports import ReportContext, report_class

    ctx = ReportContext(tool_version=__version__, group=not request.no_group, configuration=run.configuration)
    report = report_class(request.fmt, request.statistics)
    assert report is not None  # (--statistics with a format that has no table was refused above)
    with _checking(run.bar):
        checked = runner.results(found.files, Options(), request.overrides, **run.options)
        stdin = request.stdin_name if "-" in found.files else None
        checked = (_settle(r, request, found.links, stdin) for r in checked)
        tally, slim = _report(report, ctx, request.output, found.problems, checked, run.bar)
    _cache_notes(run.cache)
    _context_notes(request, slim)
    _exit_for(request, tally.worst, unread=bool(tally.unread))


def _check_and_rewrite(request: CheckRequest, found: _Files, run: _Run) -> None:
    """``--fix``, ``--diff``, ``--add-noqa``: check the whole run, then rewrite the files (or show the diff);
    then the report of what remains, the notes and the exit code."""
    from gclint import runner

    with _checking(run.bar):
        results = runner.run(found.files, Options(), request.overrides, **run.options)
    results = _not_through_new_links(results, found)
    if request.add_noqa:
        sys.exit(_add_noqa(found.problems + results, found.links, request))
    before = sum(len(r.findings) for r in results)
    results, fixed = _apply_fixes(results, request)
    if request.show_diff:
        _diff_summary(before, fixed, results, found.problems)
    results = found.problems + results
    _cache_notes(run.cache)
    for r in results:
        if r.error:
            _error(r.error)
    _write_whole_report(request, results, run.configuration, fixed=fixed, found=before)
    _context_notes(request, results)
    worst = max((f.severity for r in results for f in r.findings), default=None)
    _exit_for(request, worst, unread=any(r.error for r in results))


def _not_through_new_links(results: list[FileResult], found: _Files) -> list[FileResult]:
    """Files are never fixed (nor noqa written) through a link put in a walked folder since it was walked."""
    from gclint import runner

    for i, r in enumerate(results):
        if r.path in found.links:  # (found as a link: its findings carry no fix, and no noqa is written)
            continue
        if (target := runner.outside_walk(r.path, found.walk_roots)) is not None:
            error = f"{r.path}: now a link to {target}, outside the folder: not fixed"
            results[i] = FileResult(r.path, error=error)
    return results


def _diff_summary(before: int, fixed: int, results: list[FileResult], problems: list[FileResult]) -> NoReturn:
    """``--diff``: how many findings the fixes would end, on stderr, then the exit code (1: a fix to make)."""
    remaining = sum(len(r.findings) for r in results)
    gone = before - fixed - remaining
    also = f", {gone} more would end with them" if gone > 0 else ""
    click.echo(f"Would fix {fixed} finding{'s' if fixed != 1 else ''} ({remaining} remaining{also}).", err=True)
    sys.exit(2 if any(r.error for r in results + problems) else 1 if fixed else 0)


def _write_whole_report(
    request: CheckRequest, results: list[FileResult], configuration: list[str], *, fixed: int, found: int
) -> None:
    """The report of the files as they are after ``--fix`` (the counts instead with ``--statistics``)."""
    from gclint.reports import ReportContext
    from gclint.reports import writer as write_with

    ctx = ReportContext(
        tool_version=__version__, fixed=fixed, found=found, group=not request.no_group, configuration=configuration
    )
    writer = write_with(request.fmt)
    if request.statistics:  # the counts instead of the findings, as ruff does (JSON with --format json)
        from gclint.reports import json_report, text

        writer = json_report.write_statistics if request.fmt == "json" else text.write_statistics_report
    _write_report(writer, results, ctx, request.output)


def _cache_notes(cache: ResultCache | None) -> None:
    for note in cache.notes if cache is not None else ():
        _note(note)


def _context_notes(request: CheckRequest, results: list[FileResult]) -> None:
    """What each file was checked as, when it was weakly decided (every file's with ``-v``)."""
    from gclint.reports import MACHINE_FORMATS

    if (
        request.verbose or request.fmt not in MACHINE_FORMATS
    ):  # after the report: one that cannot be written is one line
        from gclint.reports.notes import context_notes

        for note in context_notes(results, verbose=request.verbose):
            _note(note)


def _exit_for(request: CheckRequest, worst: Any, *, unread: bool) -> None:
    """The exit code: 2 when a file could not be read, 1 when a finding reaches ``--fail-on`` (unless
    ``--exit-zero``), else the command returns (0)."""
    if unread:
        sys.exit(2)
    if not request.exit_zero and _reaches(worst, request.fail_on):
        sys.exit(1)


def _settle(r: FileResult, request: CheckRequest, links: dict, stdin: str | None) -> FileResult:
    """The result with a safe fix that ``--fix`` would take back marked unsafe (gclint.fixes.settle): the
    report's "[*]" marks and "N fixable" count what --fix applies.  Only a file with a safe fix pays for
    the second check; standard input and links found in a walk are left as they are."""
    if r.error is not None or r.path == stdin or r.path in links:
        return r
    if not any(f.fix is not None and f.fix.safe for f in r.findings):
        return r
    from gclint import runner
    from gclint.fixes import settle
    from gclint.syntax.source import Source

    linter = runner.linter_for(runner.options_for(r.path, Options(), request.overrides, request.config_file))
    return settle(r, linter, lambda: Source.open(r.path))


def _apply_fixes(results: list[FileResult], request: CheckRequest) -> tuple[list[FileResult], int]:
    """Fix each file (gclint.fixes); with ``--diff`` print the diffs instead.  Returns the results as the
    files are now and the number of findings fixed (or that would be)."""
    from gclint import runner
    from gclint.fixes import fix_file

    out: list[FileResult] = []
    fixed = 0
    for r in results:
        if r.error is None:
            # re-check with the very options of the first check (configuration and command line)
            options = runner.options_for(r.path, Options(), request.overrides, request.config_file)
            outcome = fix_file(r, runner.linter_for(options), unsafe=request.unsafe_fixes, write=not request.show_diff)
            fixed += outcome.fixed
            for note in outcome.reverted:
                _note(note)
            if outcome.diff:
                click.echo(outcome.diff, nl=False)
            if request.show_fixes and outcome.applied:
                _show_fixes(r.path, outcome.applied)
            r = outcome.result
            if outcome.error is not None:
                r = FileResult(r.path, r.findings, r.dialect, r.dialect_reason, r.lines, outcome.error, r.context)
        out.append(r)
    return out, fixed


def _show_fixes(path: str, applied: list) -> None:
    """``--show-fixes``: the fixes applied to one file, per code."""
    from collections import Counter

    from gclint.textsafe import human_path

    click.echo(f"Fixed in {human_path(path)}:")
    names = {f.code: f.name for f in applied}
    for code, n in sorted(Counter(f.code for f in applied).items()):
        click.echo(f"  {n} x {code} ({names[code]})")


def _add_noqa(results: list[FileResult], links: dict[str, str], request: CheckRequest) -> int:
    """``--add-noqa``: suppress what each file has now, line by line; says how many lines it marked, and
    which findings it could not mark and why.  Each file written is checked again: the exit code is what
    ``gclint check`` would now say (0 when every file passes)."""
    from gclint import runner
    from gclint.fixes import add_noqa
    from gclint.textsafe import human

    added, failed = 0, False
    left: list[FileResult] = []
    for r in results:
        if r.error is not None:
            _error(r.error)
            failed = True
            continue
        if r.path in links:
            if r.findings:
                _note(f"{r.path}: a link found in a folder: no noqa added (check the file it points to)")
                left.append(r)
            continue
        if r.profile:  # (its findings are in the G-code of its settings: a noqa goes there, by hand)
            if r.findings:
                _note(f"{r.path}: a slicer profile: no noqa added (write '; noqa: CODE' in the setting's G-code)")
            continue
        outcome = add_noqa(r)
        added += outcome.fixed
        for why in outcome.reverted:
            click.echo(f"gclint: note: {human(why)}", err=True)
        if outcome.error is not None:
            _error(outcome.error)
            failed = True
            continue
        if outcome.fixed:  # (what the file says now, as gclint check reads it)
            r = runner.check_one(r.path, runner.options_for(r.path, Options(), request.overrides, request.config_file))
        left.append(r)
    click.echo(f"Added a noqa comment to {added} line{'s' if added != 1 else ''}.")
    remaining = [(r.path, f) for r in left for f in r.findings]
    if remaining:
        noun = "finding is" if len(remaining) == 1 else "findings are"
        where = ", ".join(f"{human(path)}:{f.line} {f.code}" for path, f in remaining[:10])
        more = f" and {len(remaining) - 10} more" if len(remaining) > 10 else ""
        click.echo(f"{len(remaining)} {noun} still reported ({where}{more}); the notes above say why.")
    if failed:
        return 2
    worst = max((f.severity for _, f in remaining), default=None)
    return 1 if not request.exit_zero and _reaches(worst, request.fail_on) else 0


def _fix_stdin(request: CheckRequest) -> int:
    """``gclint check --fix -`` (what editors run): standard input, fixed, to standard output; the
    findings that remain on standard error.  Returns the exit code."""
    import shutil
    import tempfile

    from gclint import runner
    from gclint.fixes import fix_stream
    from gclint.reports.text import write as write_text
    from gclint.syntax.source import Source, SourceError, stdin

    try:
        given = stdin()
    except SourceError as exc:
        click.echo(f"gclint: {exc}", err=True)
        return 2
    name = request.stdin_name
    options = runner.options_for(name, Options(), request.overrides, request.config_file)
    linter = runner.linter_for(options)
    with tempfile.SpooledTemporaryFile(max_size=16 << 20) as buffer:  # read twice: check, then fix
        shutil.copyfileobj(given, buffer)

        def read() -> Source:
            buffer.seek(0)
            return Source(buffer, name)

        try:
            result = linter.check_source(read())
        except SourceError as exc:
            result = FileResult(name, error=str(exc))
        if result.error is not None:
            click.echo(f"gclint: {result.error}", err=True)
            buffer.seek(0)
            shutil.copyfileobj(buffer, sys.stdout.buffer)  # nothing lost: the text goes through unchanged
            return 2
        outcome = fix_stream(result, linter, read, sys.stdout.buffer, unsafe=request.unsafe_fixes)
    sys.stdout.flush()
    from gclint.reports import ReportContext

    write_text([outcome.result], sys.stderr, ReportContext(fixed=outcome.fixed))
    worst = max((f.severity for f in outcome.result.findings), default=None)
    return 1 if not request.exit_zero and _reaches(worst, request.fail_on) else 0


def _cache_where(files: list[str], cache_dir: str | None, no_cache: bool) -> str:
    """Where the result cache of these files lives (for --show-settings)."""
    from gclint.cache import ResultCache

    if no_cache:
        return "(not used: --no-cache)"
    cache = ResultCache(cache_dir)
    folders = sorted({str(cache.folder_for(f)) for f in files if f != "-"})
    return ", ".join(folders) if folders else "(nothing to cache)"


TEXT_FORMATS = frozenset({"text", "concise", "full", "grouped"})  # (their summary carries the configuration notes)


def _exclusion_notes(left_out: list, security_only: list) -> list[str]:
    """What the user's patterns leave out and what a found configuration tried to, for every report."""
    from gclint.excludes import security_only_summary, summary

    notes = []
    chosen = summary([x for x in left_out if x.why.chosen])
    if chosen:
        notes.append(chosen)
    tried = security_only_summary(security_only)
    if tried:
        notes.append(tried)
    return notes


MAX_JOBS = 64


def _cap_jobs(jobs: int | None) -> int | None:
    """``--jobs`` beyond what the computer can use (4 processes per CPU, at most 64) is capped, with a note."""
    from gclint import runner

    cap = min(MAX_JOBS, 4 * runner.default_jobs())
    if jobs is not None and jobs > cap:
        _note(f"--jobs {jobs} is more than this computer can use; using {cap}")
        return cap
    return jobs


class _Stdout:
    """Standard output for a report written as the files are checked: when the reader has gone ("| head"),
    the rest is dropped in silence (the run goes on: the exit code still tells)."""

    def __init__(self) -> None:
        self.gone = False

    def write(self, text: str) -> None:
        if not self.gone:
            try:
                sys.stdout.write(text)
            except BrokenPipeError:
                self._leave()

    def flush(self) -> None:
        if not self.gone:
            try:
                sys.stdout.flush()
            except BrokenPipeError:
                self._leave()

    def _leave(self) -> None:
        self.gone = True
        _abandon_stdout()


def _report(report_class, ctx, output: str | None, problems: list[FileResult], checked, bar):
    """Write the report as results come (``checked``, after ``problems``), keeping only the counts and, of
    each file, what the notes need (not its findings).  Returns the ``Tally`` and those slim results.  A
    report file is written to a temporary file renamed at the end: never half-written."""
    from contextlib import nullcontext
    from dataclasses import replace

    from gclint.io import AtomicWriter, OutputError, TextOutput

    slim: list[FileResult] = []

    def above():  # the progress bar (on a terminal) steps aside while the report or an error is written
        return bar.above() if bar is not None else nullcontext()

    def feed(report) -> None:
        for r in problems:
            _error(r.error or "")
            report.add(r)
            slim.append(r)
        for r in checked:
            if r.error:
                with above():
                    _error(r.error)
            with above():
                report.add(r)
            slim.append(replace(r, findings=[]) if r.findings else r)
        report.close()

    if output in (None, "-"):
        out = _Stdout()
        report = report_class(out, ctx)
        feed(report)
        out.flush()
        return report.tally, slim
    try:
        with AtomicWriter(output) as writer:  # never through a link
            report = report_class(TextOutput(writer), ctx)
            feed(report)
    except OutputError as exc:
        _fail(f"{exc} (the report was not written)")
    return report.tally, slim


def _write_report(writer, results: list[FileResult], ctx, output: str | None) -> None:
    from gclint.io import OutputError, write_text

    if output in (None, "-"):
        try:
            writer(results, sys.stdout, ctx)
            sys.stdout.flush()
        except BrokenPipeError:  # the reader has gone ("| head"): say nothing; the exit code still tells
            _abandon_stdout()
        return
    try:
        write_text(output, lambda out: writer(results, out, ctx))  # atomically, never through a link
    except OutputError as exc:
        _fail(f"{exc} (the report was not written)")


@contextmanager
def _checking(bar) -> Iterator[None]:
    """Around the check: the rules (plugins included) loaded first, a broken plugin one usage error, and
    the progress bar closed whatever happens."""
    try:
        from gclint.rules.base import all_rules

        all_rules()
        yield
    except RuleError as exc:
        _fail(str(exc))  # (raises)
    finally:
        if bar is not None:
            bar.close()
