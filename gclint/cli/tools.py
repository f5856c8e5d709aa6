"""The commands around the linter: gclint clean, server, postprocess, cura-script."""

from __future__ import annotations

import os
import sys

import click

from gclint.cli.app import (
    _check_dialect,
    _check_printer,
    _error,
    _fail,
    fail_on_option,
    main,
)
from gclint.config import ConfigError, parse_heads
from gclint.rules.base import RuleError


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
    """Remove the result cache of the project of PATHS (default: the current folder): only the entries
    gclint wrote, in a folder gclint marked as its cache."""
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
    refused = False
    for folder in folders:
        try:
            removed = cache.clean(folder)
        except cache.NotACache as exc:
            _error(str(exc))
            refused = True
            continue
        if removed:
            click.echo(f"removed {removed} cached result{'s' if removed != 1 else ''} from {human(str(folder))}")
        else:
            click.echo(f"no cached results in {human(str(folder))}")
    if refused:
        sys.exit(2)


@main.command()
@click.option("--stdio", is_flag=True, help="Talk over standard input and output (the default; for LSP clients).")
def server(stdio: bool) -> None:
    """Language server (LSP) over standard input and output, for editors (docs/editors.md)."""
    from gclint.server import main as serve

    serve()


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
@fail_on_option(
    "Exit 1 (the slicer stops the export) when a finding reaches this level: error, warning (the default),"
    " info, or never (report only)."
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
    from gclint.textsafe import human, human_path

    click.echo(f"wrote {human_path(str(path))}")
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
