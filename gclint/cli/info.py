"""What gclint knows and what a job does: gclint summary, rules, dialects, explain."""

from __future__ import annotations

import sys
from collections.abc import Iterable

import click

from gclint import dialects
from gclint.cli.app import (
    _check_dialect,
    _check_printer,
    _error,
    _fail,
    _left_out_notes,
    _note,
    _same_file,
    main,
)
from gclint.config import ConfigError
from gclint.engine import Options
from gclint.rules.base import RuleError


@main.command()
@click.argument("paths", nargs=-1, type=click.Path(allow_dash=True))
@click.option("--dialect", "-d", metavar="D", help="Dialect (default: decided from each file, as check does).")
@click.option("--printer", "-p", metavar="MODEL", help="Hyrel model (default: read from the job, else 30m).")
@click.option(
    "--format",
    "-f",
    "fmt",
    type=click.Choice(["text", "json", "html"]),
    default="text",
    show_default=True,
    help="html: one self-contained page, each job's summary beside its toolpath (layers, zoom, pan).",
)
@click.option(
    "--output", "-o", type=click.Path(dir_okay=False, allow_dash=True), help="Write the summary here (default: stdout)."
)
@click.option(
    "--config", "config_file", type=click.Path(dir_okay=False), help="Configuration file (else found upward)."
)
def summary(
    paths: tuple[str, ...],
    dialect: str | None,
    printer: str | None,
    fmt: str,
    output: str | None,
    config_file: str | None,
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
    if output not in (None, "-") and (same := _same_file(output, files)) is not None:
        _fail(f"{output}: is {same}, one of the jobs to summarise: the summary would overwrite it")
    options_of = {}
    for path in files:
        try:
            options_of[path] = runner.options_for(path, Options(), overrides, config_file)
        except ConfigError as exc:
            _fail(str(exc))
            return
    from gclint.textsafe import human

    failed = False

    def write(stream) -> None:
        nonlocal failed
        if fmt == "html":
            failed = _html_summaries(files, options_of, stream)
            return
        out = [summarize_path(path, options_of[path]) for path in files]
        failed = any(s.error for s in out)
        if fmt == "json":
            stream.write(json.dumps([s.to_dict() for s in out], indent=2, ensure_ascii=False) + "\n")
            return
        for s in out:
            if s.error:
                _error(s.error)
            else:
                stream.write("".join(human(line) + "\n" for line in render(s).splitlines()))

    if output in (None, "-"):
        write(sys.stdout)  # (as check writes its reports: click.get_text_stream is deprecated in click 8.5)
    else:
        from gclint.io import OutputError, write_text

        try:
            write_text(output, write)  # atomically, never through a link
        except OutputError as exc:
            _fail(f"{exc} (the summary was not written)")
    sys.exit(2 if problems or failed else 0)


def _html_summaries(files: list[str], options_of: dict, stream) -> bool:
    """``summary --format html``: each job summarised, then its toolpath read in the dialect it was read in,
    written as a section of the page as soon as it is done.  Returns whether a job could not be read."""
    from gclint import __version__
    from gclint.engine import Linter
    from gclint.reports.html import SummaryPage
    from gclint.summary import summarize_path
    from gclint.syntax.source import Source, SourceError

    page = SummaryPage(stream, __version__, files)
    failed = False
    for path in files:
        options = options_of[path]
        job = summarize_path(path, options)
        dialect, reason, weak = None, "", False
        if job.error:
            _error(job.error)
            failed = True
        elif path != "-":
            try:
                source = Source.open(path)
                try:
                    context = Linter(options).context_of(source)
                finally:
                    source.close()
                dialect, reason, weak = context.dialect, context.why(), context.weak
            except SourceError:
                pass  # (the summary read it a moment ago: the page says there is no toolpath)
        page.add(job, dialect, reason, weak)
    page.close()
    return failed


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
        f"{'auto':<11} the default for check: a '; gclint: dialect=' line, else the reading that explains the file"
        f" best (each dialect and firmware scored: a code it lacks nearly rules it out, a known mistake costs a"
        f" little, the slicer's flavour is weak evidence: content wins; the extension a tie-breaker, .ngc .nc .cnc"
        f" .tap .g; generic when no known dialect explains it), on a tie {dialects.DEFAULT.name}"
    )


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
@click.option("--dialect", "-d", metavar="D", help="Dialect (default: detected from FILE or the -e lines).")
@click.option("--format", "-f", "fmt", type=click.Choice(["text", "json"]), default="text", show_default=True)
@click.option("--all-lines", is_flag=True, help="Also list lines with no command (comments, blank lines).")
def explain(file: str | None, expressions: tuple[str, ...], dialect: str | None, fmt: str, all_lines: bool) -> None:
    """Decode each command in the printer's own terms (FILE, - for stdin, or -e LINE)."""
    import json

    from gclint.explain import Explanation, explain_source, explain_text
    from gclint.syntax.source import Source, SourceError

    if file and expressions:
        _fail("give either FILE or -e LINE, not both")
    if not file and not expressions:
        _fail('nothing to explain: give a FILE or -e "M109 T0 S240"')
    from gclint.context import infer, infer_source

    chosen = _check_dialect(dialect, allow_auto=True) or "auto"  # (-e lines are read as a file's lines are)
    items: Iterable[Explanation]
    if expressions:
        text = "\n".join(e.replace("\\n", "\n") for e in expressions)
        context = infer(text, dialect=chosen)
        items = explain_text(text, dialects.reading(context.dialect, context.flavor))
        source_name = "-e"
    else:
        try:
            src = Source.open(file)  # type: ignore[arg-type]
        except SourceError as exc:
            _fail(str(exc))
            return
        context = infer_source(src, file or "", dialect=chosen)
        items = explain_source(src, dialects.reading(context.dialect, context.flavor))
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
