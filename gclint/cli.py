"""The command line.  Each subcommand is a thin function: parse options, call library code, print.

Exit codes (DESIGN.md): 0 no finding at warning level or above; 1 findings; 2 usage error or a file that
could not be read.  Bad input never shows a traceback: one line on stderr naming the file and the reason.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable

import click

from gclint import __version__, dialects
from gclint.config import ConfigError, check_flavor, parse_heads, parse_known_codes, parse_tool_map
from gclint.engine import FileResult, Options
from gclint.machine.profiles import PROFILES, UnknownPrinter, get_profile
from gclint.rules.base import RuleError, Severity

DIALECT_CHOICES = sorted(set(dialects.names()) | {"auto"})


class UsageFailure(click.ClickException):
    exit_code = 2

    def __init__(self, message: str) -> None:
        from gclint.textsafe import human

        super().__init__(human(message))  # file names and file text: no control character reaches stderr


class _Main(click.Group):
    """The command group: whatever escapes a command becomes one line on stderr and exit code 2, never a
    traceback (DESIGN.md).  ``GCLINT_DEBUG=1`` shows the traceback of an internal error."""

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except (click.exceptions.ClickException, click.exceptions.Abort, click.exceptions.Exit):
            raise
        except BrokenPipeError:  # the reader of standard output has gone ("| head"): nothing to say
            _abandon_stdout()
            raise click.exceptions.Exit(0) from None
        except OSError as exc:  # e.g. standard output on a full disk (> /dev/full)
            _abandon_stdout()
            where = exc.filename if exc.filename is not None else "standard output"
            raise UsageFailure(f"{where}: cannot write: {exc.strerror or exc}") from None
        except Exception as exc:
            if os.environ.get("GCLINT_DEBUG"):
                raise
            detail = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
            raise UsageFailure(
                f"internal error: {detail} (please report it; GCLINT_DEBUG=1 shows the traceback)"
            ) from None


def _abandon_stdout() -> None:
    """After a failed write to standard output, point it at the null device so that the interpreter's final
    flush does not print a second error."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass


def _fail(message: str) -> None:
    raise UsageFailure(message)


def _split(values: tuple[str, ...]) -> list[str]:
    out: list[str] = []
    for v in values:
        out.extend(x.strip() for x in v.split(",") if x.strip())
    return out


def _check_dialect(name: str | None, allow_auto: bool = True) -> str | None:
    if name is None:
        return None
    if allow_auto and name.lower() == "auto":
        return "auto"
    try:
        return dialects.get(name).name
    except dialects.UnknownDialect as exc:
        _fail(str(exc))
    return None


def _check_printer(name: str | None) -> str | None:
    if name is None:
        return None
    try:
        return get_profile(name).name
    except UnknownPrinter as exc:
        _fail(str(exc))
    return None


def _stdout_safe() -> None:
    # File text may hold undecodable bytes (kept as surrogates); never crash while printing them.
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.reconfigure(errors="backslashreplace")  # type: ignore[attr-defined]
        except (AttributeError, ValueError):
            pass


@click.group(cls=_Main, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 110})
@click.version_option(__version__, "-V", "--version", prog_name="gclint")
def main() -> None:
    """gclint: a linter and dialect translator for G-code, built first for Hyrel 3D printers."""
    _stdout_safe()


# -- check -----------------------------------------------------------------------------------------------


@main.command()
@click.argument("paths", nargs=-1, type=click.Path(allow_dash=True, readable=False))
@click.option(
    "--dialect", "-d", metavar="D", help="hyrel, hyrel-v4, marlin, reprap, machinekit, carvera or auto (default)."
)
@click.option("--printer", "-p", metavar="MODEL", help=f"Hyrel model: {', '.join(PROFILES)} (default 30m).")
@click.option(
    "--flavor",
    metavar="FIRMWARE",
    help="The firmware the files are for, when they do not say: prusa-buddy, prusa-mk3, bambu, klipper... "
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
@click.option(
    "--fail-on",
    type=click.Choice(["error", "warning", "info"]),
    default="warning",
    show_default=True,
    help="Exit 1 when a finding reaches this level.",
)
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
    from gclint.reports import MACHINE_FORMATS, ReportContext, formats

    if os.environ.get("PRE_COMMIT") == "1" and paths and "--" not in sys.argv[1:]:
        # pre-commit appends file names after the hook's args: without "--", a committed file named
        # "--config=x.gcode" would be read as an option (.pre-commit-hooks.yaml)
        _fail(
            "as a pre-commit hook, gclint needs '--' before the file names: end the hook's args with '--'"
            " (args: [--printer, 30m, --]) so that a file name is never read as an option"
        )
    writers = formats()
    if fmt not in writers:
        _fail(f"unknown format {fmt!r} (known: {', '.join(sorted(writers))})")
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
    walked: set[str] = set()
    from gclint.excludes import Excluder, LeftOut

    left_out: list[LeftOut] = []
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
    files, problems = runner.collect(paths or (".",), walk_notes, excluder, walked, left_out, walk_roots)
    if force_exclude:  # (pre-commit passes every staged .nc and .g by name: one that is not G-code is skipped)
        walked.update(f for f in files if f != "-")
    if "-" in files and stdin_filename and (why := excluder.excluded(stdin_filename, False, named=True)):
        files = [f for f in files if f != "-"]  # --force-exclude: the file it stands for is excluded
        left_out.append(LeftOut(stdin_filename, why))
        if fix:
            sys.stdout.buffer.write(sys.stdin.buffer.read())  # --fix -: the text goes through unchanged
            sys.exit(0)
    for note in walk_notes:
        _note(note)
    _left_out_notes(left_out, verbose, nothing_left=not files and not problems)
    if output not in (None, "-") and (checked := _same_file(output, files)) is not None:
        _fail(f"{output}: is {checked}, one of the files to check: the report would overwrite it")
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
    suppressions = settings.security_suppressions(files, overrides, config_file)
    for note in suppressions:
        if note.from_config:
            _note(note.describe(), always=True)
    from gclint import progress as progress_bar
    from gclint.cache import ResultCache

    bar = progress_bar.ProgressBar(files) if progress_bar.wanted(progress, fmt, files) else None
    cache = None if (no_cache or fix or show_diff or add_noqa) else ResultCache(cache_dir)
    try:
        from gclint.rules.base import all_rules

        all_rules()
        results = runner.run(
            files,
            Options(),
            overrides,
            explicit_config=config_file,
            jobs=jobs or (runner.default_jobs() if len(files) > 1 else 1),
            stdin_name=stdin_filename or "-",
            progress=bar.advance if bar is not None else None,
            cache=cache,
        )
    except RuleError as exc:
        _fail(str(exc))
        return
    finally:
        if bar is not None:
            bar.close()
    if fix or show_diff or add_noqa:  # never through a link put in a walked folder since it was walked
        for i, r in enumerate(results):
            if (target := runner.outside_walk(r.path, walk_roots)) is not None:
                error = f"{r.path}: now a link to {target}, outside the folder: not fixed"
                results[i] = FileResult(r.path, error=error)
    if add_noqa:
        sys.exit(_add_noqa(problems + results))
    fixed = None
    if fix or show_diff:
        results, fixed = _apply_fixes(
            results, overrides, config_file, unsafe=unsafe_fixes, write=not show_diff, show=show_fixes
        )
        if show_diff:
            remaining = sum(len(r.findings) for r in results)
            click.echo(f"Would fix {fixed} finding{'s' if fixed != 1 else ''} ({remaining} remaining).", err=True)
            sys.exit(2 if any(r.error for r in results + problems) else 1 if fixed else 0)
    # a file found in a folder that is something else (a NetCDF .nc, an ANTLR .g): skipped, with a note
    for r in results:
        if runner.skippable(r, walked):
            _note(f"{r.error}: skipped")
    results = problems + [r for r in results if not runner.skippable(r, walked)]
    for note in cache.notes if cache is not None else ():
        _note(note)
    for r in results:
        if r.error:
            _error(r.error)
    ctx = ReportContext(
        tool_version=__version__,
        fixed=fixed,
        group=not no_group,
        suppressions=[n.describe() for n in suppressions],
    )
    writer = writers[fmt]
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
    if not exit_zero and worst is not None and worst >= Severity.parse(fail_on):
        sys.exit(1)


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
    from gclint.textsafe import human

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

                click.echo(f"Fixed in {human(r.path)}:")
                names = {f.code: f.name for f in outcome.applied}
                for code, n in sorted(Counter(f.code for f in outcome.applied).items()):
                    click.echo(f"  {n} x {code} ({names[code]})")
            r = outcome.result
            if outcome.error is not None:
                r = FileResult(r.path, r.findings, r.dialect, r.dialect_reason, r.lines, outcome.error, r.context)
        out.append(r)
    return out, fixed


def _add_noqa(results: list[FileResult]) -> int:
    """``--add-noqa``: suppress what each file has now, line by line; says how many lines it marked."""
    from gclint.fixes import add_noqa

    added, failed = 0, False
    for r in results:
        if r.error is not None:
            _error(r.error)
            failed = True
            continue
        outcome = add_noqa(r)
        added += outcome.fixed
        if outcome.error is not None:
            _error(outcome.error)
            failed = True
    click.echo(f"Added a noqa comment to {added} line{'s' if added != 1 else ''}.")
    return 2 if failed else 0


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
    from gclint.syntax.source import Source, SourceError

    options = runner.options_for(name, Options(), overrides, config_file)
    linter = runner.linter_for(options)
    with tempfile.SpooledTemporaryFile(max_size=16 << 20) as buffer:  # read twice: check, then fix
        shutil.copyfileobj(sys.stdin.buffer, buffer)

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
    return 1 if not exit_zero and worst is not None and worst >= Severity.parse(fail_on) else 0


def _cache_where(files: list[str], cache_dir: str | None, no_cache: bool) -> str:
    """Where the result cache of these files lives (for --show-settings)."""
    from gclint.cache import ResultCache

    if no_cache:
        return "(not used: --no-cache)"
    cache = ResultCache(cache_dir)
    folders = sorted({str(cache.folder_for(f)) for f in files if f != "-"})
    return ", ".join(folders) if folders else "(nothing to cache)"


_QUIET: list[bool] = []  # check --quiet: notes are not shown (errors still are)


def _left_out_notes(left_out: list, verbose: bool, *, nothing_left: bool) -> None:
    """What a walk or --force-exclude left out: one line (how many, why, the first few), each with -v."""
    from gclint.excludes import summary

    if verbose:
        for item in left_out:
            _note(item.describe())
    said = summary(left_out)
    if nothing_left:
        _note(f"no files left to check (all excluded){': ' + said if said else ''}")
    elif said:
        _note(said if verbose else f"{said}; -v lists them")


def _note(text: str, *, always: bool = False) -> None:
    """A note on stderr (``--quiet`` drops it, but never one that says a security rule is switched off)."""
    if _QUIET and not always:
        return
    from gclint.textsafe import human

    click.echo(f"gclint: note: {human(text)}", err=True)


def _error(text: str) -> None:
    from gclint.textsafe import human

    click.echo(f"gclint: {human(text)}", err=True)


def _same_file(output: str, files: list[str]) -> str | None:
    """The file among ``files`` that ``output`` names (the same file, by any name), or None."""
    try:
        target = os.stat(output)
    except OSError:
        return None
    for path in files:
        try:
            if path != "-" and os.path.samestat(target, os.stat(path)):
                return path
        except OSError:
            continue
    return None


MAX_JOBS = 64


def _cap_jobs(jobs: int | None) -> int | None:
    """``--jobs`` beyond what the computer can use (4 processes per CPU, at most 64) is capped, with a note."""
    from gclint import runner

    cap = min(MAX_JOBS, 4 * runner.default_jobs())
    if jobs is not None and jobs > cap:
        _note(f"--jobs {jobs} is more than this computer can use; using {cap}")
        return cap
    return jobs


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


# -- summary ---------------------------------------------------------------------------------------------


@main.command()
@click.argument("paths", nargs=-1, type=click.Path(allow_dash=True))
@click.option("--dialect", "-d", metavar="D", help="Dialect (default: decided from each file, as check does).")
@click.option("--printer", "-p", metavar="MODEL", help="Hyrel model (default: read from the job, else 30m).")
@click.option("--format", "-f", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option(
    "--config", "config_file", type=click.Path(dir_okay=False), help="Configuration file (else found upward)."
)
def summary(
    paths: tuple[str, ...], dialect: str | None, printer: str | None, fmt: str, config_file: str | None
) -> None:
    """What each job does, in numbers: heads, temperatures, flow, layers, extent, feeds, time."""
    import json

    from gclint import runner
    from gclint.summary import render, summarize_path

    overrides: dict = {}
    if dialect is not None:
        overrides["dialect"] = _check_dialect(dialect)
    if printer is not None:
        overrides["printer"] = _check_printer(printer)
    walk_notes: list[str] = []
    left_out: list = []
    files, problems = runner.collect(paths or (".",), walk_notes, left_out=left_out)
    for note in walk_notes:
        _note(note)
    _left_out_notes(left_out, False, nothing_left=not files and not problems)
    for r in problems:
        _error(r.error or "")
    out = []
    for path in files:
        try:
            options = runner.options_for(path, Options(), overrides, config_file)
        except ConfigError as exc:
            _fail(str(exc))
            return
        out.append(summarize_path(path, options))
    from gclint.textsafe import human

    if fmt == "json":
        click.echo(json.dumps([s.to_dict() for s in out], indent=2, ensure_ascii=False))
    else:
        for s in out:
            if s.error:
                _error(s.error)
            else:
                click.echo("".join(human(line) + "\n" for line in render(s).splitlines()), nl=False)
    sys.exit(2 if problems or any(s.error for s in out) else 0)


# -- translate -------------------------------------------------------------------------------------------


def _translation_options(command: Callable) -> Callable:
    """The options translate and diff share: the target printer, the tool map, the flow, settings, config."""
    for option in reversed(
        (
            click.option("--printer", "-p", metavar="MODEL", help="Hyrel model of the target."),
            click.option("--tool-map", metavar="0=T2,...", help="Source tool index -> Hyrel head address."),
            click.option(
                "--flow",
                type=click.Choice(["evalues", "native"]),
                default=None,
                help="Hyrel flow: keep the E amounts with M229 E1 D1 (evalues, default) or native flow (E1 markers).",
            ),
            click.option(
                "--set",
                "settings",
                multiple=True,
                metavar="KEY=VALUE",
                help="Translation setting (repeatable): retract, fan-map, bed, chamber, temp-window, spindle, "
                "laser, air, max-feed, home-z, spindle-max-rpm, spindle-stop-dwell.  See docs/translation.md.",
            ),
            click.option(
                "--config",
                "config_file",
                type=click.Path(dir_okay=False),
                help="Configuration file (else found upward).",
            ),
        )
    ):
        command = option(command)
    return command


@main.command()
@click.argument("input_path", metavar="INPUT", type=click.Path(allow_dash=True), default="-")
@click.option("--from", "source", required=True, metavar="D", help="Dialect of the input.")
@click.option("--to", "target", required=True, metavar="D", help="Dialect to write.")
@click.option(
    "--output",
    "-o",
    metavar="OUT",
    type=click.Path(dir_okay=False, allow_dash=True),
    help="Output file (default: stdout).",
)
@click.option("--in-place", is_flag=True, help="Replace INPUT (atomically).")
@click.option(
    "--unsupported",
    type=click.Choice(["ignore", "warn", "error"]),
    default="warn",
    show_default=True,
    help="What to do with constructs that cannot be translated exactly.",
)
@click.option("--annotate", is_flag=True, help="Add a '; gclint: ...' comment on each changed or dropped line.")
@_translation_options
def translate(
    input_path: str,
    source: str,
    target: str,
    output: str | None,
    in_place: bool,
    unsupported: str,
    annotate: bool,
    printer: str | None,
    tool_map: str | None,
    config_file: str | None,
    flow: str | None = None,
    settings: tuple[str, ...] = (),
) -> None:
    """Translate INPUT from one dialect to another (- for standard input)."""
    from gclint.translate.cli import run_translate

    src = dialects.get(_check_dialect(source, allow_auto=False))  # type: ignore[arg-type]
    dst = dialects.get(_check_dialect(target, allow_auto=False))  # type: ignore[arg-type]
    if in_place and output:
        _fail("use either --output or --in-place")
    if in_place and input_path == "-":
        _fail("--in-place needs a file, not standard input")
    if output not in (None, "-") and input_path != "-" and _same_file(output, [input_path]) is not None:
        _fail(f"{output}: is the input file; use --in-place to rewrite it")
    try:
        mapping = parse_tool_map(tool_map) if tool_map else None
    except ConfigError as exc:
        _fail(str(exc))
        return
    from gclint.translate.options import parse_settings

    try:
        extra = parse_settings(settings)
    except ValueError as exc:
        _fail(str(exc))
        return
    code = run_translate(
        input_path,
        src,
        dst,
        output=input_path if in_place else output,
        unsupported=unsupported,
        annotate=annotate,
        printer=_check_printer(printer),
        tool_map=mapping,
        config_file=config_file,
        flow=flow,
        settings=extra,
    )
    sys.exit(code)


# -- diff ------------------------------------------------------------------------------------------------


@main.command()
@click.argument("source_path", metavar="SOURCE", type=click.Path(allow_dash=True))
@click.argument("output_path", metavar="OUTPUT", type=click.Path(allow_dash=True))
@click.option("--from", "source", required=True, metavar="D", help="Dialect of SOURCE.")
@click.option("--to", "target", required=True, metavar="D", help="Dialect of OUTPUT (hyrel, hyrel-v4).")
@click.option("--format", "-f", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option(
    "--fail-on",
    type=click.Choice(["any", "unexplained"]),
    default="any",
    show_default=True,
    help="Exit 1 on any difference, or only on one no TR finding explains.",
)
@click.option("--no-explain", is_flag=True, help="Do not translate SOURCE to explain the differences.")
@_translation_options
def diff(
    source_path: str,
    output_path: str,
    source: str,
    target: str,
    fmt: str,
    fail_on: str,
    no_explain: bool,
    printer: str | None,
    tool_map: str | None,
    flow: str | None,
    settings: tuple[str, ...],
    config_file: str | None,
) -> None:
    """Where OUTPUT (a translation of SOURCE) differs from it in meaning; exit 1 if it does."""
    from gclint.simulate.cli import run_diff
    from gclint.translate.options import parse_settings

    src = dialects.get(_check_dialect(source, allow_auto=False))  # type: ignore[arg-type]
    dst = dialects.get(_check_dialect(target, allow_auto=False))  # type: ignore[arg-type]
    if source_path == "-" and output_path == "-":
        _fail("SOURCE and OUTPUT cannot both be standard input")
    try:
        mapping = parse_tool_map(tool_map) if tool_map else None
        extra = parse_settings(settings)
    except (ConfigError, ValueError) as exc:
        _fail(str(exc))
        return
    code = run_diff(
        source_path,
        output_path,
        src,
        dst,
        fmt=fmt,
        explain=not no_explain,
        fail_on=fail_on,
        printer=_check_printer(printer),
        tool_map=mapping,
        config_file=config_file,
        flow=flow,
        settings=extra,
    )
    sys.exit(code)


# -- rules and dialects ------------------------------------------------------------------------------------


@main.command()
@click.argument("code", required=False)
@click.option("--format", "-f", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--all", "show_all", is_flag=True, help="With no CODE: print every rule's full documentation.")
def rules(code: str | None, fmt: str, show_all: bool) -> None:
    """List the rules, or show one rule's documentation."""
    import json

    from gclint.rules.base import all_rules

    try:
        registry = all_rules()
    except RuleError as exc:
        _fail(str(exc))
        return
    if code:
        key = code.strip().upper()
        matched = [r for c, r in registry.items() if c == key or r.name == code.strip().lower()]
        if not matched:
            matched = [r for c, r in registry.items() if c.startswith(key)]
        if not matched:
            _fail(f"no rule {code!r} (see 'gclint rules')")
        if fmt == "json":
            docs = [r.doc() for r in matched]
            click.echo(json.dumps(docs[0] if len(docs) == 1 else docs, indent=2, ensure_ascii=False))
        else:
            click.echo("\n".join(r.render_doc() for r in matched), nl=False)
        return
    if fmt == "json":
        click.echo(json.dumps([r.doc() for r in registry.values()], indent=2, ensure_ascii=False))
        return
    if show_all:
        click.echo("\n".join(r.render_doc() for r in registry.values()), nl=False)
        return
    for c, r in registry.items():  # "[*]": the rule has a fix (gclint check --fix)
        click.echo(f"{c} {'[*]' if r.fixable else '   '} {r.name:<34} {r.severity.label:<8} {r.summary}")


@main.command(name="dialects")
def list_dialects() -> None:
    """List the dialects and their aliases."""
    for d in dialects.all_dialects():
        aliases = f" (also: {', '.join(d.aliases)})" if d.aliases else ""
        click.echo(f"{d.name:<11} {d.title}{aliases}")
    click.echo(
        f"{'auto':<11} the default for check: a '; gclint: dialect=' line, else content only one dialect has, else the"
        f" slicer's flavour (content wins), else the extension as a tie-breaker (.ngc .nc .cnc .tap .g), else"
        f" {dialects.DEFAULT.name}"
    )


# -- clean -----------------------------------------------------------------------------------------------


@main.command()
@click.argument("paths", nargs=-1, type=click.Path(readable=False))
@click.option("--all", "everything", is_flag=True, help="Remove the result cache of every project.")
@click.option(
    "--cache-dir",
    type=click.Path(file_okay=False),
    envvar="GCLINT_CACHE_DIR",
    help="Remove this cache folder's results instead (as given to 'check').",
)
def clean(paths: tuple[str, ...], everything: bool, cache_dir: str | None) -> None:
    """Remove the result cache of the project of PATHS (default: the current folder)."""
    from pathlib import Path

    from gclint import cache
    from gclint.textsafe import human

    if cache_dir:
        folders = [Path(cache_dir)]
    elif everything:
        folders = [cache.user_cache_root()]
    else:  # each path's project, and every project below it (nested configurations), as ruff clean does
        root = cache.user_cache_root()
        folders = sorted({cache.project_folder(root, cache.project_root(p)) for p in paths or (".",)})
        for p in paths or (".",):
            if os.path.isdir(p):
                folders = sorted(set(folders) | set(cache.projects_under(root, Path(p))))
    for folder in folders:
        removed = cache.clean(folder)
        if removed:
            click.echo(f"removed {removed} cached result{'s' if removed != 1 else ''} from {human(str(folder))}")
        else:
            click.echo(f"no cached results in {human(str(folder))}")


# -- explain ---------------------------------------------------------------------------------------------


@main.command()
@click.argument("file", required=False, type=click.Path(allow_dash=True))
@click.option(
    "--expression",
    "-e",
    "expressions",
    multiple=True,
    metavar="LINE",
    help='G-code to explain, e.g. -e "M109 T0 S240 L10 U5" (repeatable; lines may be separated by \\n).',
)
@click.option("--dialect", "-d", metavar="D", help="Dialect (default: detected from FILE; hyrel for -e).")
@click.option("--format", "-f", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--all-lines", is_flag=True, help="Also list lines with no command (comments, blank lines).")
def explain(file: str | None, expressions: tuple[str, ...], dialect: str | None, fmt: str, all_lines: bool) -> None:
    """Decode each command in the printer's own terms (FILE, - for stdin, or -e LINE)."""
    import json

    from gclint.explain import explain_source, explain_text
    from gclint.syntax.source import Source, SourceError

    if file and expressions:
        _fail("give either FILE or -e LINE, not both")
    if not file and not expressions:
        _fail('nothing to explain: give a FILE or -e "M109 T0 S240"')
    from gclint.context import infer, infer_source

    chosen = _check_dialect(dialect, allow_auto=True) or ("auto" if file else "hyrel")
    if expressions:
        text = "\n".join(e.replace("\\n", "\n") for e in expressions)
        context = infer(text, dialect=chosen)
        items = explain_text(text, dialects.get(context.dialect))
        source_name = "-e"
    else:
        try:
            src = Source.open(file)  # type: ignore[arg-type]
        except SourceError as exc:
            _fail(str(exc))
            return
        context = infer_source(src, file or "", dialect=chosen)
        items = explain_source(src, dialects.get(context.dialect))
        source_name = file or "-"
    from gclint.textsafe import human, json_safe

    found = dialects.get(context.dialect)
    try:
        if fmt == "json":
            commands = [e.masked().to_dict() for e in items]
            payload = {"dialect": found.name, "source": human(source_name), "commands": commands}
            click.echo(json_safe(json.dumps(payload, indent=2, ensure_ascii=False)))
            return
        click.echo(f"; dialect: {found.name} ({found.title})")
        if context.origin not in ("option", "configuration", "directive"):
            click.echo(f"; read as {human(context.label())}: {human(context.why())}")
        last = None
        for e in items:
            e = e.masked()
            if e.line != last:
                shown = human(e.source.strip())
                click.echo(f"\n{e.line}: {shown}" if source_name != "-e" else f"\n{shown}")
                last = e.line
            click.echo("\n".join(human(line) for line in e.render().split("\n")))
    except SourceError as exc:
        _fail(str(exc))


# -- language server -------------------------------------------------------------------------------------


@main.command()
@click.option("--stdio", is_flag=True, help="Talk over standard input and output (the default; for LSP clients).")
def server(stdio: bool) -> None:
    """Language server (LSP) over standard input and output, for editors (docs/editors.md)."""
    from gclint.server import ServerUnavailable
    from gclint.server import main as serve

    try:
        serve()
    except ServerUnavailable as exc:
        _fail(str(exc))


# -- slicer post-processing ------------------------------------------------------------------------------


@main.command()
@click.argument("path", type=click.Path(dir_okay=False))
@click.option(
    "--to", "target", metavar="D", help="Translate to this dialect first (e.g. hyrel); default: no translation."
)
@click.option(
    "--from",
    "source",
    metavar="D",
    help="Dialect of the slicer's output (default: SLIC3R_GCODE_FLAVOR, else the header).",
)
@click.option(
    "--fail-on",
    type=click.Choice(["error", "warning", "never"]),
    default="error",
    show_default=True,
    help="Exit 1 (the slicer stops the export) when a finding reaches this level.",
)
@click.option("--printer", "-p", metavar="MODEL", help="Hyrel model of the target.")
@click.option("--loaded", metavar="T0,T2", help="Head positions loaded on the yoke.")
@click.option(
    "--report", "report_path", type=click.Path(dir_okay=False), help="Report file (default: <output>.gclint.txt)."
)
@click.option("--no-report", is_flag=True, help="Do not write a report file.")
def postprocess(
    path: str,
    target: str | None,
    source: str | None,
    fail_on: str,
    printer: str | None,
    loaded: str | None,
    report_path: str | None,
    no_report: bool,
) -> None:
    """Slicer post-processing step: translate and check PATH in place (the path comes last)."""
    from gclint import postprocess as pp

    target_name = _check_dialect(target, allow_auto=False) if target else None
    source_name = _check_dialect(source, allow_auto=True) if source else None
    heads = None
    if loaded is not None:
        try:
            heads = parse_heads(loaded)
        except ConfigError as exc:
            _fail(str(exc))
    try:
        code = pp.main(
            path,
            to=target_name,
            fail_on=fail_on,
            source=source_name,
            printer=_check_printer(printer),
            loaded=heads,
            report=report_path,
            no_report=no_report,
        )
    except RuleError as exc:
        _fail(str(exc))
        return
    sys.exit(code)


@main.command(name="cura-script")
@click.option(
    "--output",
    "-o",
    "folder",
    type=click.Path(file_okay=False),
    default=None,
    help="Folder to write Gclint.py into (default: the current folder).",
)
@click.option("--print", "to_stdout", is_flag=True, help="Print the script instead of writing it.")
def cura_script(folder: str | None, to_stdout: bool) -> None:
    """Write Gclint.py, a script for Cura's post-processing plugin."""
    from gclint import cura_script as cs

    if to_stdout:
        click.echo(cs.render(), nl=False)
        return
    from gclint.io import OutputError

    try:
        path = cs.write(folder or ".")
    except OutputError as exc:
        _fail(str(exc))
        return
    except OSError as exc:
        _fail(f"{folder or '.'}: cannot write {cs.SCRIPT_NAME}: {exc.strerror or exc}")
        return
    from gclint.textsafe import human

    click.echo(f"wrote {human(str(path))}")
    folders = cs.cura_script_folders()
    if folder is None:
        if folders:
            click.echo("Copy it into Cura's scripts folder, e.g.: " + human(str(folders[0])))
        else:
            click.echo(
                "Copy it into the 'scripts' folder of Cura's configuration folder (Help > Show Configuration Folder)."
            )
    click.echo("Then restart Cura: Extensions > Post Processing > Modify G-Code > Add a script > gclint.")
    click.echo("Note: Cura cannot stop an export; the script shows the findings and writes them into the G-code.")


if __name__ == "__main__":  # pragma: no cover
    main()
