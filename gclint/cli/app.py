"""The command group and what every command shares: one-line usage errors, notes on stderr, option checks.

Exit codes (README.md, docs/entry-points.md): 0 no finding at warning level or above; 1 findings; 2 usage error or a
file that could not be read.  Bad input never shows a traceback: one line on stderr naming the file and the reason.
"""

from __future__ import annotations

import os
import sys

import click

from gclint import __version__, dialects
from gclint.machine.profiles import UnknownPrinter, get_profile

DIALECT_CHOICES = sorted(set(dialects.names()) | {"auto"})


class UsageFailure(click.ClickException):
    exit_code = 2

    def __init__(self, message: str) -> None:
        from gclint.textsafe import human

        super().__init__(human(message))  # file names and file text: no control character reaches stderr


class _Main(click.Group):
    """The command group: whatever escapes a command becomes one line on stderr and exit code 2, never a
    traceback (docs/entry-points.md).  ``GCLINT_DEBUG=1`` shows the traceback of an internal error."""

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


# --fail-on, the same in every entry point that gates (check, postprocess, the pre-commit hooks, which run
# check, and the GitHub Action, which passes its fail-on input to check): exit 1 when a finding reaches
# this level; "never" reports only.
FAIL_ON_LEVELS = ("error", "warning", "info", "never")
DEFAULT_FAIL_ON = "warning"
FAIL_ON_HELP = "Exit 1 when a finding reaches this level: error, warning (the default), info, or never (report only)."


def fail_on_option(help_text: str = FAIL_ON_HELP):
    return click.option(
        "--fail-on", type=click.Choice(FAIL_ON_LEVELS), default=DEFAULT_FAIL_ON, show_default=True, help=help_text
    )


def _reaches(worst, fail_on: str) -> bool:
    """Whether the worst severity found (None: no finding) reaches ``--fail-on``."""
    from gclint.rules.base import Severity

    return fail_on != "never" and worst is not None and worst >= Severity.parse(fail_on)


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
        reconfigure = getattr(stream, "reconfigure", None)  # (a TextIOWrapper's; a test's capture may lack it)
        if reconfigure is not None:
            try:
                reconfigure(errors="backslashreplace")
            except ValueError:
                pass


@click.group(cls=_Main, context_settings={"help_option_names": ["-h", "--help"], "max_content_width": 110})
@click.version_option(__version__, "-V", "--version", prog_name="gclint")
def main() -> None:
    """gclint: a linter and dialect translator for G-code, built first for Hyrel 3D printers."""
    _stdout_safe()


_QUIET: list[bool] = []  # check --quiet: notes are not shown (errors still are)


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
