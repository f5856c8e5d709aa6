"""gclint check: lint files and folders, fix them, report in every format."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager

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
def check(
    paths: tuple[str, ...],
    dialect: str | None,
    printer: str | None,
    flavor: str | None,
    loaded: str | None,
    select: tuple[str, ...],
    ignore: tuple[str, ...],
    extend_select: tuple[str, ...],
    extend_known_codes: tuple[str, ...],
    fmt: str,
    output: str | None,
    exit_zero: bool,
    fail_on: str,
    exclude: tuple[str, ...],
    extend_exclude: tuple[str, ...],
    force_exclude: bool | None,
    respect_gitignore: bool | None,
    statistics: bool,
    no_group: bool,
    jobs: int | None,
    config_file: str | None,
    fix: bool,
    unsafe_fixes: bool,
    stdin_filename: str | None,
    no_cache: bool,
    cache_dir: str | None,
    progress: bool | None,
    verbose: bool = False,
    quiet: bool = False,
    show_settings: bool = False,
    show_diff: bool = False,
    show_fixes: bool = False,
    add_noqa: bool = False,
) -> None:
    """Check G-code files and folders (- for standard input)."""
    if quiet:
        _QUIET.append(True)
    from gclint import runner
    from gclint.reports import FORMATS, MACHINE_FORMATS, ReportContext, report_class
    from gclint.reports import writer as write_with

    if os.environ.get("PRE_COMMIT") == "1" and paths and "--" not in sys.argv[1:]:
        # pre-commit appends file names after the hook's args: without "--", a committed file named
        # "--config=x.gcode" would be read as an option (.pre-commit-hooks.yaml)
        _fail(
            "as a pre-commit hook, gclint needs '--' before the file names: end the hook's args with '--'"
            " (args: [--printer, 30m, --]) so that a file name is never read as an option"
        )
    if fmt not in FORMATS:
        _fail(f"unknown format {fmt!r} (known: {', '.join(sorted(FORMATS))})")
    overrides: dict = {}
    if dialect is not None:
        overrides["dialect"] = _check_dialect(dialect)
        overrides["dialect_origin"] = "option"
    if printer is not None:
        overrides["printer"] = _check_printer(printer)
        overrides["printer_origin"] = "option"
    try:
        if flavor is not None:
            overrides["flavor"] = check_flavor(flavor, "--flavor")
            overrides["flavor_origin"] = "option"
        if loaded is not None:
            overrides["loaded"] = parse_heads(loaded)
        if extend_known_codes:
            overrides["extend_known_codes"] = parse_known_codes(",".join(extend_known_codes))
    except ConfigError as exc:
        _fail(str(exc))
    from gclint.rules.base import UnknownSelector, resolve_selectors

    try:
        if select:
            overrides["select"] = resolve_selectors(_split(select), "--select: ")
            overrides.setdefault("ignore", [])  # as ruff: the command line's selection is a new start
        if ignore:
            overrides["ignore"] = resolve_selectors(_split(ignore), "--ignore: ")
        if extend_select:
            overrides["extend_select"] = resolve_selectors(_split(extend_select), "--extend-select: ")
    except (UnknownSelector, RuleError) as exc:
        _fail(str(exc))
    if config_file is not None and not os.path.isfile(config_file):
        _fail(f"{config_file}: configuration file not found")

    walk_notes: list[str] = []
    from gclint.config import check_pattern
    from gclint.excludes import Excluder, LeftOut

    try:
        for pattern in _split(exclude):
            check_pattern(pattern, "--exclude")
        for pattern in _split(extend_exclude):
            check_pattern(pattern, "--extend-exclude")
    except ConfigError as exc:
        _fail(str(exc))
    left_out: list[LeftOut] = []
    security_only: list[LeftOut] = []  # excluded by a configuration found beside them: SC rules only
    links: dict[str, str] = {}  # a link checked under its own name -> the file it points to
    walk_roots: dict[str, str] = {}  # file found in a walk -> the real path of the folder walked

    excluder = Excluder(
        exclude=_split(exclude) or None,
        extend_exclude=_split(extend_exclude),
        force=force_exclude,
        respect_gitignore=respect_gitignore,
        explicit_config=config_file,
    )
    if stdin_filename and not paths:
        paths = ("-",)  # --stdin-filename alone reads standard input (ruff)
    files, problems = runner.collect(
        paths or (".",), walk_notes, excluder, left_out, walk_roots, security_only=security_only, links=links
    )
    if "-" in files and stdin_filename and (why := excluder.excluded(stdin_filename, False, named=True)):
        files = [f for f in files if f != "-"]  # --force-exclude: the file it stands for is excluded
        left_out.append(LeftOut(stdin_filename, why))
        if fix:
            sys.stdout.buffer.write(sys.stdin.buffer.read())  # --fix -: the text goes through unchanged
            sys.exit(0)
    for note in walk_notes:
        _note(note)
    _left_out_notes(left_out, verbose, nothing_left=not files and not problems)
    if output not in (None, "-") and (same := _same_file(output, files)) is not None:
        _fail(f"{output}: is {same}, one of the files to check: the report would overwrite it")
    jobs = _cap_jobs(jobs)
    from gclint import settings

    if show_settings:
        for r in problems:
            _error(r.error or "")
        try:
            shown = settings.show_settings(files, overrides, config_file, _cache_where(files, cache_dir, no_cache))
        except ConfigError as exc:
            _fail(str(exc))
        click.echo(shown, nl=False)
        sys.exit(2 if problems else 0)
    if unsafe_fixes and not (fix or show_diff):
        _fail("--unsafe-fixes goes with --fix or --diff")
    if add_noqa and (fix or show_diff):
        _fail("--add-noqa writes noqa comments; run it without --fix and --diff")
    if statistics and fmt in ("sarif", "junit", "html"):
        _fail(f"--statistics prints a table (text) or JSON (-f json), not {fmt}")
    if select and not overrides.get("select"):
        _fail("--select names no rule (an empty --select would check nothing)")
    if fix and files == ["-"]:  # "--fix -": the fixed text on stdout, the findings left on stderr
        sys.exit(_fix_stdin(overrides, config_file, stdin_filename or "-", unsafe_fixes, exit_zero, fail_on))
    if (fix or show_diff) and "-" in files:
        _fail("--fix and --diff need files; '--fix -' alone fixes standard input to standard output")
    # a broken configuration is one error before anything is checked (not one per file, as ruff)
    for path in dict.fromkeys(files):
        try:
            runner.options_for(stdin_filename or path if path == "-" else path, Options(), overrides, config_file)
        except ConfigError as exc:
            _fail(str(exc))
    configuration = settings.configuration_notes(files, overrides, config_file)
    configuration += _exclusion_notes(left_out, security_only)
    if fmt not in TEXT_FORMATS:  # (the text formats end with them, on standard output)
        for note in configuration:
            _note(note, always=True)
    from gclint import progress as progress_bar
    from gclint.cache import ResultCache

    bar = progress_bar.ProgressBar(files) if progress_bar.wanted(progress, fmt, files) else None
    cache = None if (no_cache or fix or show_diff or add_noqa) else ResultCache(cache_dir)
    run_options: runner.RunOptions = {  # (the same run, file by file for the reports or whole for the fixes)
        "explicit_config": config_file,
        "jobs": jobs or (runner.default_jobs() if len(files) > 1 else 1),
        "stdin_name": stdin_filename or "-",
        "progress": bar.advance if bar is not None else None,
        "cache": cache,
        "security_only": {item.path for item in security_only},
        "links": links,
    }
    if not (fix or show_diff or add_noqa):  # file by file: memory does not grow with the run
        ctx = ReportContext(tool_version=__version__, group=not no_group, configuration=configuration)
        report = report_class(fmt, statistics)
        assert report is not None  # (--statistics with a format that has no table was refused above)
        with _checking(bar):
            checked = runner.results(files, Options(), overrides, **run_options)
            stdin = run_options["stdin_name"] if "-" in files else None
            checked = (_settle(r, overrides, config_file, links, stdin) for r in checked)
            tally, slim = _report(report, ctx, output, problems, checked, bar)
        for note in cache.notes if cache is not None else ():
            _note(note)
        if verbose or fmt not in MACHINE_FORMATS:  # after the report: a report that cannot be written is one line
            from gclint.reports.notes import context_notes

            for note in context_notes(slim, verbose=verbose):
                _note(note)
        if tally.unread:
            sys.exit(2)
        if not exit_zero and _reaches(tally.worst, fail_on):
            sys.exit(1)
        return
    with _checking(bar):
        results = runner.run(files, Options(), overrides, **run_options)
    if fix or show_diff or add_noqa:  # never through a link put in a walked folder since it was walked
        for i, r in enumerate(results):
            if r.path in links:  # (found as a link: its findings carry no fix, and no noqa is written)
                continue
            if (target := runner.outside_walk(r.path, walk_roots)) is not None:
                error = f"{r.path}: now a link to {target}, outside the folder: not fixed"
                results[i] = FileResult(r.path, error=error)
    if add_noqa:
        sys.exit(_add_noqa(problems + results, links, overrides, config_file, fail_on, exit_zero))
    fixed = None
    found = sum(len(r.findings) for r in results)
    if fix or show_diff:
        results, fixed = _apply_fixes(
            results, overrides, config_file, unsafe=unsafe_fixes, write=not show_diff, show=show_fixes
        )
        if show_diff:
            remaining = sum(len(r.findings) for r in results)
            gone = found - fixed - remaining
            also = f", {gone} more would end with them" if gone > 0 else ""
            click.echo(f"Would fix {fixed} finding{'s' if fixed != 1 else ''} ({remaining} remaining{also}).", err=True)
            sys.exit(2 if any(r.error for r in results + problems) else 1 if fixed else 0)
    results = problems + results
    for note in cache.notes if cache is not None else ():
        _note(note)
    for r in results:
        if r.error:
            _error(r.error)
    ctx = ReportContext(
        tool_version=__version__, fixed=fixed, found=found, group=not no_group, configuration=configuration
    )
    writer = write_with(fmt)
    if statistics:  # the counts instead of the findings, as ruff does (JSON with --format json)
        from gclint.reports import json_report, text

        writer = json_report.write_statistics if fmt == "json" else text.write_statistics_report
    _write_report(writer, results, ctx, output)
    if verbose or fmt not in MACHINE_FORMATS:  # after the report: a report that cannot be written is one line
        from gclint.reports.notes import context_notes

        for note in context_notes(results, verbose=verbose):
            _note(note)
    if any(r.error for r in results):
        sys.exit(2)
    worst = max((f.severity for r in results for f in r.findings), default=None)
    if not exit_zero and _reaches(worst, fail_on):
        sys.exit(1)


def _settle(r: FileResult, overrides: dict, config_file: str | None, links: dict, stdin: str | None) -> FileResult:
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

    linter = runner.linter_for(runner.options_for(r.path, Options(), overrides, config_file))
    return settle(r, linter, lambda: Source.open(r.path))


def _apply_fixes(
    results: list[FileResult],
    overrides: dict,
    config_file: str | None,
    *,
    unsafe: bool,
    write: bool,
    show: bool = False,
) -> tuple[list[FileResult], int]:
    """Fix each file (gclint.fixes); with ``write=False`` print the diffs instead.  Returns the results
    as the files are now and the number of findings fixed (or that would be)."""
    from gclint import runner
    from gclint.fixes import fix_file
    from gclint.textsafe import human_path

    out: list[FileResult] = []
    fixed = 0
    for r in results:
        if r.error is None:
            # re-check with the very options of the first check (configuration and command line)
            options = runner.options_for(r.path, Options(), overrides, config_file)
            outcome = fix_file(r, runner.linter_for(options), unsafe=unsafe, write=write)
            fixed += outcome.fixed
            for note in outcome.reverted:
                _note(note)
            if outcome.diff:
                click.echo(outcome.diff, nl=False)
            if show and outcome.applied:
                from collections import Counter

                click.echo(f"Fixed in {human_path(r.path)}:")
                names = {f.code: f.name for f in outcome.applied}
                for code, n in sorted(Counter(f.code for f in outcome.applied).items()):
                    click.echo(f"  {n} x {code} ({names[code]})")
            r = outcome.result
            if outcome.error is not None:
                r = FileResult(r.path, r.findings, r.dialect, r.dialect_reason, r.lines, outcome.error, r.context)
        out.append(r)
    return out, fixed


def _add_noqa(
    results: list[FileResult],
    links: dict[str, str],
    overrides: dict,
    config_file: str | None,
    fail_on: str,
    exit_zero: bool,
) -> int:
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
            r = runner.check_one(r.path, runner.options_for(r.path, Options(), overrides, config_file))
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
    return 1 if not exit_zero and _reaches(worst, fail_on) else 0


def _fix_stdin(
    overrides: dict, config_file: str | None, name: str, unsafe: bool, exit_zero: bool, fail_on: str = "warning"
) -> int:
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
    options = runner.options_for(name, Options(), overrides, config_file)
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
        outcome = fix_stream(result, linter, read, sys.stdout.buffer, unsafe=unsafe)
    sys.stdout.flush()
    from gclint.reports import ReportContext

    write_text([outcome.result], sys.stderr, ReportContext(fixed=outcome.fixed))
    worst = max((f.severity for f in outcome.result.findings), default=None)
    return 1 if not exit_zero and _reaches(worst, fail_on) else 0


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
