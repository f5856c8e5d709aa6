"""The command line.  Each subcommand is a thin function: parse options, call library code, print.

Exit codes (DESIGN.md): 0 no finding at warning level or above; 1 findings; 2 usage error or a file that
could not be read.  Bad input never shows a traceback: one line on stderr naming the file and the reason.
"""

from __future__ import annotations

import os
import sys

import click

from gclint import __version__, dialects
from gclint.config import ConfigError, parse_heads, parse_tool_map
from gclint.engine import FileResult, Options
from gclint.machine.profiles import PROFILES, UnknownPrinter, get_profile
from gclint.rules.base import RuleError, Severity

DIALECT_CHOICES = sorted(set(dialects.names()) | {"auto"})


class UsageFailure(click.ClickException):
    exit_code = 2


class _Main(click.Group):
    """The command group: whatever escapes a command becomes one line on stderr and exit code 2, never a
    traceback (DESIGN.md).  ``GCLINT_DEBUG=1`` shows the traceback of an internal error."""

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except (click.exceptions.ClickException, click.exceptions.Abort, click.exceptions.Exit):
            raise
        except OSError as exc:  # e.g. standard output on a full disk (> /dev/full) or a closed pipe
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
        out.extend(x.strip().upper() for x in v.split(",") if x.strip())
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
@click.argument("paths", nargs=-1, type=click.Path(allow_dash=True))
@click.option(
    "--dialect", "-d", metavar="D", help="hyrel, hyrel-v4, marlin, reprap, machinekit, carvera or auto (default)."
)
@click.option("--printer", "-p", metavar="MODEL", help=f"Hyrel model: {', '.join(PROFILES)} (default 30m).")
@click.option("--loaded", metavar="T0,T2", help="Head positions loaded on the yoke (else from the job header).")
@click.option("--select", multiple=True, metavar="CODES", help="Only these rule codes or prefixes (comma separated).")
@click.option("--ignore", multiple=True, metavar="CODES", help="Skip these rule codes or prefixes.")
@click.option("--extend-select", multiple=True, metavar="CODES", help="Add these to the selected rules.")
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
@click.option("--exit-zero", is_flag=True, help="Exit 0 even when findings exist.")
@click.option("--statistics", is_flag=True, help="Show the number of findings per code.")
@click.option("--jobs", "-j", type=click.IntRange(min=1), default=None, help="Parallel processes (default: CPU count).")
@click.option(
    "--config", "config_file", type=click.Path(dir_okay=False), help="Configuration file (else found upward)."
)
@click.option("--fix", is_flag=True, help="Apply the safe fixes in place.")
@click.option("--unsafe-fixes", is_flag=True, help="With --fix, apply unsafe fixes too.")
@click.option("--stdin-filename", metavar="NAME", help="Name to use for the file read from '-'.")
@click.option("--no-cache", is_flag=True, help="Do not read or write the result cache.")
@click.option(
    "--cache-dir",
    type=click.Path(file_okay=False),
    envvar="GCLINT_CACHE_DIR",
    help="Cache folder (default .gclint_cache).",
)
@click.option(
    "--progress/--no-progress", default=None, help="Progress bar on stderr (default: on a terminal, for many files)."
)
def check(
    paths: tuple[str, ...],
    dialect: str | None,
    printer: str | None,
    loaded: str | None,
    select: tuple[str, ...],
    ignore: tuple[str, ...],
    extend_select: tuple[str, ...],
    fmt: str,
    output: str | None,
    exit_zero: bool,
    statistics: bool,
    jobs: int | None,
    config_file: str | None,
    fix: bool,
    unsafe_fixes: bool,
    stdin_filename: str | None,
    no_cache: bool,
    cache_dir: str | None,
    progress: bool | None,
) -> None:
    """Check G-code files and folders (- for standard input)."""
    from gclint import runner
    from gclint.reports import ReportContext, formats

    writers = formats()
    if fmt not in writers:
        _fail(f"unknown format {fmt!r} (known: {', '.join(sorted(writers))})")
    overrides: dict = {}
    if dialect is not None:
        overrides["dialect"] = _check_dialect(dialect)
    if printer is not None:
        overrides["printer"] = _check_printer(printer)
    try:
        if loaded is not None:
            overrides["loaded"] = parse_heads(loaded)
    except ConfigError as exc:
        _fail(str(exc))
    if select:
        overrides["select"] = _split(select)
    if ignore:
        overrides["ignore"] = _split(ignore)
    if extend_select:
        overrides["extend_select"] = _split(extend_select)
    if config_file is not None and not os.path.isfile(config_file):
        _fail(f"{config_file}: configuration file not found")

    files, problems = runner.collect(paths or (".",))
    if fix and "-" in files:
        _fail("--fix cannot rewrite standard input")
    from gclint import progress as progress_bar
    from gclint.cache import ResultCache

    bar = progress_bar.ProgressBar(files) if progress_bar.wanted(progress, fmt, files) else None
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
            cache=None if (no_cache or fix) else ResultCache(cache_dir),
        )
    except RuleError as exc:
        _fail(str(exc))
        return
    finally:
        if bar is not None:
            bar.close()
    if fix:
        from gclint.fixes import apply_fixes

        fixed = []
        for r in results:
            if r.error is None:
                # re-check with the very options of the first check (configuration and command line)
                options = runner.options_for(r.path, Options(), overrides, config_file)
                r = apply_fixes(r, unsafe=unsafe_fixes, linter=runner.linter_for(options))
            fixed.append(r)
        results = fixed
    results = problems + results
    for r in results:
        if r.error:
            click.echo(f"gclint: {r.error}", err=True)
    ctx = ReportContext(tool_version=__version__, statistics=statistics)
    _write_report(writers[fmt], results, ctx, output)
    if any(r.error for r in results):
        sys.exit(2)
    worst = max((f.severity for r in results for f in r.findings), default=None)
    if not exit_zero and worst is not None and worst >= Severity.WARNING:
        sys.exit(1)


def _write_report(writer, results: list[FileResult], ctx, output: str | None) -> None:
    if output in (None, "-"):
        writer(results, sys.stdout, ctx)
        return
    try:
        with open(output, "w", encoding="utf-8", errors="backslashreplace", newline="\n") as fh:
            writer(results, fh, ctx)
    except OSError as exc:
        _fail(f"{output}: cannot write the report: {exc.strerror or exc}")


# -- translate -------------------------------------------------------------------------------------------


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
@click.option("--printer", "-p", metavar="MODEL", help="Hyrel model of the target.")
@click.option("--tool-map", metavar="0=T2,...", help="Source tool index -> Hyrel head address.")
@click.option(
    "--flow",
    type=click.Choice(["evalues", "native"]),
    default=None,
    help="Hyrel flow: keep the E amounts with M229 E1 D1 (evalues, default) or native flow (E1 markers).",
)
@click.option(
    "--set",
    "settings",
    multiple=True,
    metavar="KEY=VALUE",
    help="Translation setting (repeatable): retract, fan-map, bed, chamber, temp-window, spindle, laser, "
    "air, max-feed, home-z, spindle-max-rpm.  See docs/translation.md.",
)
@click.option(
    "--config", "config_file", type=click.Path(dir_okay=False), help="Configuration file (else found upward)."
)
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
@click.option("--printer", "-p", metavar="MODEL", help="Hyrel model of the target.")
@click.option("--tool-map", metavar="0=T2,...", help="Source tool index -> Hyrel head address.")
@click.option("--flow", type=click.Choice(["evalues", "native"]), default=None, help="As given to translate.")
@click.option("--set", "settings", multiple=True, metavar="KEY=VALUE", help="Translation setting, as for translate.")
@click.option(
    "--config", "config_file", type=click.Path(dir_okay=False), help="Configuration file (else found upward)."
)
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
    for c, r in registry.items():
        click.echo(f"{c}  {r.name:<34} {r.severity.label:<8} {r.summary}")


@main.command(name="dialects")
def list_dialects() -> None:
    """List the dialects and their aliases."""
    for d in dialects.all_dialects():
        aliases = f" (also: {', '.join(d.aliases)})" if d.aliases else ""
        click.echo(f"{d.name:<11} {d.title}{aliases}")
    click.echo(f"{'auto':<11} detect from the file (directive, slicer header, codes); default {dialects.DEFAULT.name}")


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
    chosen = dialects.get(_check_dialect(dialect, allow_auto=True)) if dialect and dialect.lower() != "auto" else None  # type: ignore[arg-type]
    if expressions:
        text = "\n".join(e.replace("\\n", "\n") for e in expressions)
        found = (
            chosen or dialects.detect(text)[0] if dialect and dialect.lower() == "auto" else chosen or dialects.DEFAULT
        )
        items = explain_text(text, found)
        source_name = "-e"
    else:
        try:
            src = Source.open(file)  # type: ignore[arg-type]
        except SourceError as exc:
            _fail(str(exc))
            return
        found = chosen or dialects.detect(src.head_text(), file or "")[0]
        items = explain_source(src, found)
        source_name = file or "-"
    try:
        if fmt == "json":
            click.echo(
                json.dumps(
                    {"dialect": found.name, "source": source_name, "commands": [e.to_dict() for e in items]},
                    indent=2,
                    ensure_ascii=False,
                )
            )
            return
        click.echo(f"; dialect: {found.name} ({found.title})")
        last = None
        for e in items:
            if e.line != last:
                click.echo(f"\n{e.line}: {e.source.strip()}" if source_name != "-e" else f"\n{e.source.strip()}")
                last = e.line
            click.echo(e.render())
    except SourceError as exc:
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
    try:
        path = cs.write(folder or ".")
    except OSError as exc:
        _fail(f"{folder or '.'}: cannot write {cs.SCRIPT_NAME}: {exc.strerror or exc}")
        return
    click.echo(f"wrote {path}")
    folders = cs.cura_script_folders()
    if folder is None:
        if folders:
            click.echo("Copy it into Cura's scripts folder, e.g.: " + str(folders[0]))
        else:
            click.echo(
                "Copy it into the 'scripts' folder of Cura's configuration folder (Help > Show Configuration Folder)."
            )
    click.echo("Then restart Cura: Extensions > Post Processing > Modify G-Code > Add a script > gclint.")
    click.echo("Note: Cura cannot stop an export; the script shows the findings and writes them into the G-code.")


if __name__ == "__main__":  # pragma: no cover
    main()
