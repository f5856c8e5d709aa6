"""gclint translate and gclint diff: dialect translation and its meaning diff."""

from __future__ import annotations

import sys
from collections.abc import Callable

import click

from gclint import dialects
from gclint.cli.app import (
    _check_dialect,
    _check_printer,
    _fail,
    _same_file,
    main,
)
from gclint.config import ConfigError, parse_tool_map


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
    from gclint.textsafe import HumanStream

    stderr, sys.stderr = sys.stderr, HumanStream(sys.stderr)
    try:  # (its error lines name the files: a name's escape sequences must not reach the terminal)
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
    finally:
        sys.stderr = stderr
    sys.exit(code)
