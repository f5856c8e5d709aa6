"""The language server: the Language Server Protocol methods gclint answers, over ``gclint.server.jsonrpc``.

* Diagnostics are pushed on open and save at once, and on change after a short pause (``DEBOUNCE``).
  Checks run in worker threads, never on the event loop; a check whose text has changed since it
  started is abandoned (the reader stops at its next chunk) and its result is never published.
* Hover decodes the command under the cursor (``gclint explain``), with the dialect the check found and
  the machine state the lines above leave.
* Code actions: each fix, "suppress with noqa" for the line, "fix all safe" (also as
  ``source.fixAll.gclint``, for fix-on-save).
* Options: the configuration file found from the document's folder (as ``gclint check``), overridden by
  the editor's settings (``initializationOptions``, ``workspace/didChangeConfiguration``, or
  ``workspace/configuration`` when the client offers it).

Each method is one handler, ``handler(server, params)`` (a coroutine function where it waits), registered
in ``METHODS``: adding a method is a function and a row there (and its capability in ``initialize``).
``GclintServer`` holds the state and what the handlers share (the log, the checks and the diagnostics
they publish, the editor's settings).  Whatever goes wrong in a handler becomes one line in the client's
log (``window/logMessage``); the server keeps running.  The document text is kept here (``Snapshot``),
with LSP line breaks.

Start-up is kept short (the first diagnostics of a 20,000-line job within half a second of starting the
process, bench/bench_server.py): only the standard library and gclint are imported, and the rules are
loaded in a worker thread while the client sends ``initialized`` and opens the first file.
"""

from __future__ import annotations

import asyncio
import functools
import logging
import os
import sys
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, BinaryIO
from urllib.parse import unquote, urlparse

from gclint import __version__, dialects
from gclint.engine import FileResult, Options
from gclint.runner import linter_for
from gclint.server import analysis, convert
from gclint.server.analysis import Cancelled, Settings
from gclint.server.jsonrpc import (
    INVALID_REQUEST,
    SERVER_NOT_INITIALIZED,
    Endpoint,
    InvalidParams,
    ResponseError,
    document_uri,
    member,
    obj,
    position,
    range_of,
)
from gclint.server.text import UTF8, UTF16, UTF32, Snapshot, clean_surrogates, units_to_char
from gclint.syntax.source import Source, SourceError

logger = logging.getLogger("gclint.server")

DEBOUNCE = 0.3  # seconds of quiet after a change before the text is checked
MAX_DIAGNOSTICS = 10_000  # per document; beyond that the editor gains nothing and slows down
ANALYSIS_WAIT = 5.0  # how long a code action waits for the check of the current text
HOVER_WAIT = 1.0  # how long a hover waits for it (it needs only the dialect)
CONFIG_WAIT = 5.0  # how long to wait for the client's answer to workspace/configuration

# MessageType
ERROR, WARNING, INFO = 1, 2, 3
# TextDocumentSyncKind.Incremental
INCREMENTAL = 2


@dataclass
class Analysis:
    """One finished check: the text it read, its result, the options it ran with."""

    snapshot: Snapshot
    result: FileResult
    options: Options


@dataclass
class Document:
    uri: str
    path: str | None  # the file on disk (None for an unsaved buffer): configuration is found from it
    name: str  # the name findings and dialect detection see (the path, else the URI)
    snapshot: Snapshot
    analysis: Analysis | None = None
    task: asyncio.Task | None = None
    cancel: threading.Event | None = None
    problems: set[str] = field(default_factory=set)  # already logged for this document


def _path_of(uri: str) -> str | None:
    try:
        parsed = urlparse(uri)
        if parsed.scheme != "file":
            return None
        if os.name == "nt":
            from nturl2path import url2pathname  # (urllib.request's, without importing http and ssl)

            path = url2pathname(parsed.path)
            if parsed.netloc and parsed.netloc != "localhost":  # a UNC path (file://server/share/...)
                path = f"\\\\{parsed.netloc}{path}"
        else:
            path = unquote(parsed.path)
            if parsed.netloc and parsed.netloc != "localhost":
                path = f"//{parsed.netloc}{path}"
        return path or None
    except Exception:
        return None


def _choose_encoding(capabilities: dict) -> str:
    """The position encoding: the first the client offers that gclint counts in, else UTF-16 (the
    protocol's default, and all a client that offers nothing understands)."""
    general = capabilities.get("general")
    offered = general.get("positionEncodings") if isinstance(general, dict) else None
    if isinstance(offered, list):
        for name in offered:
            if name in (UTF8, UTF16, UTF32):
                return name
    return UTF16


def _flag(caps: dict, *path: str) -> Any:
    """``caps[path[0]][path[1]]...`` or None where the path ends early (capabilities are all optional)."""
    value: Any = caps
    for key in path:
        if not isinstance(value, dict):
            return None
        value = value.get(key)
    return value


class GclintServer:
    """The server's state (the open documents, the settings, what the client can do) and what the
    protocol's handlers share: the log, the checks and the diagnostics they publish, the editor's
    settings.  The handlers themselves are the functions below, one per method (``METHODS``)."""

    def __init__(self, endpoint: Endpoint) -> None:
        self.endpoint = endpoint
        self.documents: dict[str, Document] = {}
        self.settings = Settings()
        # Checks in their own threads (two: one long job does not hold up another file); hovers in
        # another, so that a hover never waits behind a check.
        self.checks = ThreadPoolExecutor(max_workers=2, thread_name_prefix="gclint-check")
        self.requests = ThreadPoolExecutor(max_workers=1, thread_name_prefix="gclint-request")
        self.initialized = False
        self.shutdown_requested = False
        self.exit_status: int | None = None
        self.encoding = UTF16
        self.markdown = False
        self.versioned_edits = False
        self.pull_configuration = False
        self.logged: set[str] = set()
        self.warmed = threading.Event()  # set when the warm-up has ended, or should (a document came)

    # -- helpers ------------------------------------------------------------------------------------------

    def log(self, message: str, kind: int = INFO) -> None:
        """One line in the client's log (window/logMessage) and on standard error."""
        message = " ".join(str(message).split())[:2000]
        logger.log(logging.ERROR if kind == ERROR else logging.INFO, "%s", message)
        self.endpoint.notify("window/logMessage", {"type": kind, "message": f"gclint: {message}"})

    def log_once(self, message: str, kind: int = WARNING) -> None:
        if message not in self.logged:
            if len(self.logged) > 1000:
                self.logged.clear()
            self.logged.add(message)
            self.log(message, kind)

    def warn_once(self, message: str) -> None:
        """A warning the user should see (window/showMessage) and in the log, once."""
        if message in self.logged:
            return
        self.log_once(message)
        self.endpoint.notify("window/showMessage", {"type": WARNING, "message": f"gclint: {message}"})

    def problem(self, text: str) -> None:
        """What the transport could not handle (not JSON, params that do not fit): a line in the log."""
        self.log(text, WARNING if "invalid params" in text else ERROR)

    def gate(self, method: str) -> None:
        if self.shutdown_requested:
            raise ResponseError(INVALID_REQUEST, f"{method[:100]}: the server is shutting down")
        if not self.initialized and method != "initialize":
            raise ResponseError(SERVER_NOT_INITIALIZED, f"{method[:100]}: the server is not initialized")

    def publish(self, uri: str, diagnostics: list[dict], version: int | None = None) -> None:
        params: dict = {"uri": uri, "diagnostics": diagnostics}
        if version is not None:
            params["version"] = version
        self.endpoint.notify("textDocument/publishDiagnostics", params)

    def apply_settings(self, raw: object) -> None:
        """Take the client's settings; open documents are checked again when they change anything."""
        settings, problems = analysis.parse_settings(raw)
        for problem in problems:
            self.log_once(problem)
        if settings != self.settings:
            self.settings = settings
            for doc in list(self.documents.values()):
                self.schedule(doc, 0)

    # -- checking and diagnostics -------------------------------------------------------------------------

    def schedule(self, doc: Document, delay: float) -> None:
        """Check ``doc``'s current text after ``delay`` seconds, abandoning any check of older text."""
        if doc.cancel is not None:
            doc.cancel.set()
        if doc.task is not None and not doc.task.done():
            doc.task.cancel()
        doc.cancel = threading.Event()
        doc.task = asyncio.ensure_future(self._check(doc, doc.snapshot, doc.cancel, delay))

    async def _check(self, doc: Document, snapshot: Snapshot, cancel: threading.Event, delay: float) -> None:
        try:
            if delay:
                await asyncio.sleep(delay)
            options, problem = analysis.document_options(doc.path, self.settings)
            if problem:
                self.log_once(problem)
            if (off := analysis.security_off(options)) is not None:
                self.warn_once(off)
            loop = asyncio.get_running_loop()
            work = functools.partial(_analyse, snapshot, doc.name, options, cancel, self.encoding)
            try:
                result, diagnostics = await loop.run_in_executor(self.checks, work)
            except Cancelled:
                return
            if cancel.is_set() or self.documents.get(doc.uri) is not doc:
                return
            doc.analysis = Analysis(snapshot, result, options)
            if result.error:
                self._log_document(doc, result.error)
            if len(result.findings) > len(diagnostics):
                self._log_document(
                    doc,
                    f"{doc.name}: {len(result.findings):,} findings; the first {len(diagnostics):,} are shown"
                    " (gclint check lists them all)",
                )
            self.publish(doc.uri, diagnostics, snapshot.version)
        except asyncio.CancelledError:
            cancel.set()
            raise
        except Exception as exc:
            self.log(f"{doc.name}: check failed: {type(exc).__name__}: {exc}", ERROR)

    def _log_document(self, doc: Document, message: str) -> None:
        if message not in doc.problems:
            doc.problems.add(message)
            self.log(message, WARNING)

    async def current_analysis(self, doc: Document, timeout: float) -> Analysis | None:
        """The analysis of ``doc``'s current text, waiting up to ``timeout`` seconds for it (a check is
        started if none is under way); else the latest one there is (None when there is none)."""
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout
        while True:
            if doc.analysis is not None and doc.analysis.snapshot is doc.snapshot:
                return doc.analysis
            remaining = deadline - loop.time()
            if remaining <= 0:
                return doc.analysis
            if doc.task is None or doc.task.done():
                self.schedule(doc, 0)
            task = doc.task
            assert task is not None
            await asyncio.wait({task}, timeout=remaining)
            if task is doc.task and task.done() and (doc.analysis is None or doc.analysis.snapshot is not doc.snapshot):
                return doc.analysis  # the check ended without a result for this text (it failed)

    async def run_in_thread(self, func: Callable, *args: Any) -> Any:
        """``func(*args, cancel)`` in a worker thread; the cancel event is set when the request is
        cancelled (the client moved on), so that long replays stop."""
        cancel = threading.Event()
        loop = asyncio.get_running_loop()
        try:
            return await loop.run_in_executor(self.requests, functools.partial(func, *args, cancel=cancel))
        except asyncio.CancelledError:
            cancel.set()
            raise

    def stop(self) -> None:
        for doc in self.documents.values():
            if doc.cancel is not None:
                doc.cancel.set()
        self.checks.shutdown(wait=False, cancel_futures=True)
        self.requests.shutdown(wait=False, cancel_futures=True)

    async def pull_settings(self) -> None:
        """Ask the client for its gclint settings (``workspace/configuration``) and take them."""
        try:
            answer = await self.endpoint.request(
                "workspace/configuration", {"items": [{"section": "gclint"}]}, timeout=CONFIG_WAIT
            )
        except Exception as exc:
            self.log(f"could not read the editor's gclint settings: {type(exc).__name__}: {exc}", WARNING)
            return
        if isinstance(answer, list) and answer:
            self.apply_settings(answer[0])


# -- the protocol's methods: one handler per feature, ``handler(server, params)``, registered in METHODS --
#
# Lifecycle: what the client can ask of gclint (capabilities), the editor's settings, the warm-up; the end.


def initialize(server: GclintServer, params: Any) -> dict:
    params = obj(params, "$.params")
    caps = member(params, "capabilities", "$.params", dict, {})
    server.encoding = _choose_encoding(caps)
    formats = _flag(caps, "textDocument", "hover", "contentFormat")
    server.markdown = isinstance(formats, list) and "markdown" in formats
    server.versioned_edits = bool(_flag(caps, "workspace", "workspaceEdit", "documentChanges"))
    server.pull_configuration = bool(_flag(caps, "workspace", "configuration"))
    server.initialized = True
    server.apply_settings(params.get("initializationOptions"))
    server.checks.submit(_warm_up, server.warmed, server.settings)  # while the editor opens the first file
    return {
        "capabilities": {
            "positionEncoding": server.encoding,
            "textDocumentSync": {"openClose": True, "change": INCREMENTAL, "save": {"includeText": False}},
            "hoverProvider": True,
            "codeActionProvider": {"codeActionKinds": [convert.QUICK_FIX, convert.FIX_ALL_KIND]},
        },
        "serverInfo": {"name": "gclint", "version": __version__},
    }


async def initialized(server: GclintServer, params: Any) -> None:
    if server.pull_configuration:
        await server.pull_settings()


def shutdown(server: GclintServer, params: Any) -> None:
    server.shutdown_requested = True
    server.stop()
    return None


def exit_(server: GclintServer, params: Any) -> None:
    server.exit_status = 0 if server.shutdown_requested else 1
    server.endpoint.stop()


# Configuration: the editor's settings changed (pushed with the notification, or to be pulled).


async def did_change_configuration(server: GclintServer, params: Any) -> None:
    settings = params.get("settings") if isinstance(params, dict) else None
    if settings is None or (server.pull_configuration and settings in ({}, {"gclint": None})):
        await server.pull_settings()  # the client says "changed" and expects to be asked
    else:
        server.apply_settings(settings)


# Document synchronisation: the text is kept here; each change schedules a check, whose diagnostics
# GclintServer publishes (textDocument/publishDiagnostics); closing a document clears them.


def did_open(server: GclintServer, params: Any) -> None:
    params = obj(params, "$.params")
    item = obj(params.get("textDocument"), "$.params.textDocument")
    where = "$.params.textDocument"
    uri = member(item, "uri", where, str)
    text = member(item, "text", where, str)
    version = member(item, "version", where, int, None)
    old = server.documents.get(uri)
    if old is not None and old.cancel is not None:
        old.cancel.set()
    path = _path_of(uri)
    doc = Document(uri, path, path or unquote(uri), Snapshot(text, version))
    server.documents[uri] = doc
    server.warmed.set()  # the check of this document warms up what it needs: no time for the rest
    server.schedule(doc, 0)


def did_change(server: GclintServer, params: Any) -> None:
    params = obj(params, "$.params")
    uri = document_uri(params)
    version = member(params["textDocument"], "version", "$.params.textDocument", int, None)
    changes = member(params, "contentChanges", "$.params", list)
    doc = server.documents.get(uri)
    if doc is None:
        return
    text = doc.snapshot.text
    for i, change in enumerate(changes):
        where = f"$.params.contentChanges[{i}]"
        change = obj(change, where)
        new_text = member(change, "text", where, str)
        if change.get("range") is not None:
            (l0, c0), (l1, c1) = range_of(change["range"], f"{where}.range")
            text = Snapshot(text).edited((l0, c0), (l1, c1), new_text, server.encoding)
        else:
            text = new_text
    doc.snapshot = Snapshot(text, version)
    server.schedule(doc, DEBOUNCE)


def did_save(server: GclintServer, params: Any) -> None:
    params = obj(params, "$.params")
    doc = server.documents.get(document_uri(params))
    if doc is None:
        return
    text = params.get("text")
    if isinstance(text, str) and text != doc.snapshot.text:
        doc.snapshot = Snapshot(text, doc.snapshot.version)
    server.schedule(doc, 0)  # at once: the configuration may have changed too


def did_close(server: GclintServer, params: Any) -> None:
    params = obj(params, "$.params")
    doc = server.documents.pop(document_uri(params), None)
    if doc is None:
        return
    if doc.cancel is not None:
        doc.cancel.set()
    if doc.task is not None:
        doc.task.cancel()
    server.publish(doc.uri, [])


# Hover: the command under the cursor decoded (gclint explain), with the dialect the check found.


async def hover(server: GclintServer, params: Any) -> dict | None:
    params = obj(params, "$.params")
    uri = document_uri(params)
    line, character = position(params.get("position"), "$.params.position")
    doc = server.documents.get(uri)
    if doc is None:
        return None
    snapshot = doc.snapshot
    encoding = server.encoding
    char = units_to_char(snapshot.line(line), character, encoding)
    # the dialect of the last check (it rarely changes while typing); wait only when there is none
    done = doc.analysis if doc.analysis is not None else await server.current_analysis(doc, HOVER_WAIT)
    options = done.options if done is not None else analysis.document_options(doc.path, server.settings)[0]
    dialect, reason = _dialect_for(done, options, snapshot, doc.name)
    target = await server.run_in_thread(analysis.explain_at, snapshot, line, char, dialect, options.loaded)
    if target is None:
        return None
    return convert.hover(target, convert.Geometry(snapshot, encoding), line + 1, server.markdown, reason)


# Code actions: each fix, "suppress with noqa" for the line, "fix all safe" (also source.fixAll.gclint,
# for fix-on-save), on the check of the current text.


async def code_action(server: GclintServer, params: Any) -> list[dict] | None:
    params = obj(params, "$.params")
    uri = document_uri(params)
    (first, _), (last, _) = range_of(params.get("range"), "$.params.range")
    context = obj(params.get("context"), "$.params.context")
    only_raw = member(context, "only", "$.params.context", list, None)
    only = [str(k) for k in only_raw] if only_raw else None
    doc = server.documents.get(uri)
    if doc is None:
        return None
    done = await server.current_analysis(doc, ANALYSIS_WAIT)
    if done is None or done.snapshot is not doc.snapshot:
        return None  # edits computed on other text would land in the wrong places
    # "fix all" applies what --fix would: the safe fixes that bring no new finding (gclint.fixes)
    fix_all = await server.run_in_thread(analysis.safe_fix_set, done.result, done.snapshot.text, done.options)
    actions = convert.code_actions(
        doc.uri,
        done.result.findings,
        convert.Geometry(done.snapshot, server.encoding),
        first,
        last,
        only,
        version=done.snapshot.version if server.versioned_edits else None,
        fix_all=fix_all,
    )
    return actions or None


@dataclass(frozen=True)
class Method:
    """One protocol method gclint answers: its handler (``handler(server, params)``, a coroutine function
    where it waits), and whether it is a notification (no answer).  Before ``initialize`` requests are
    refused (``GclintServer.gate``) and notifications dropped, but those marked ``early``."""

    name: str
    handler: Callable[..., Any]
    notification: bool = False
    early: bool = False


METHODS: tuple[Method, ...] = (
    Method("initialize", initialize),
    Method("initialized", initialized, notification=True),
    Method("shutdown", shutdown),
    Method("exit", exit_, notification=True, early=True),
    Method("workspace/didChangeConfiguration", did_change_configuration, notification=True),
    Method("textDocument/didOpen", did_open, notification=True),
    Method("textDocument/didChange", did_change, notification=True),
    Method("textDocument/didSave", did_save, notification=True),
    Method("textDocument/didClose", did_close, notification=True),
    Method("textDocument/hover", hover),
    Method("textDocument/codeAction", code_action),
)


def _analyse(
    snapshot: Snapshot, name: str, options: Options, cancel: threading.Event, encoding: str
) -> tuple[FileResult, list[dict]]:
    """In a worker thread: check the text and turn the findings into diagnostics."""
    result = analysis.check_text(snapshot.text, name, options, cancel)
    geo = convert.Geometry(snapshot, encoding)
    return result, convert.diagnostics(result.findings, geo, MAX_DIAGNOSTICS)


def _guard(server: GclintServer, name: str, handler: Callable) -> Callable:
    """``handler(server, params)`` as the transport calls it, ``(params)``: any exception but params that
    do not fit (answered InvalidParams by the transport) becomes a line in the client's log and an empty
    answer."""

    if asyncio.iscoroutinefunction(handler):

        @functools.wraps(handler)
        async def wrapped_async(params: Any) -> Any:
            try:
                return await handler(server, params)
            except (asyncio.CancelledError, InvalidParams, ResponseError):
                raise
            except Exception as exc:
                server.log(f"{name} failed: {type(exc).__name__}: {exc}", ERROR)
                return None

        return wrapped_async

    @functools.wraps(handler)
    def wrapped(params: Any) -> Any:
        try:
            return handler(server, params)
        except (InvalidParams, ResponseError):
            raise
        except Exception as exc:
            server.log(f"{name} failed: {type(exc).__name__}: {exc}", ERROR)
            return None

    return wrapped


def create_server(reader: BinaryIO, writer: BinaryIO) -> GclintServer:
    """A server on this stream, answering the methods of ``METHODS``."""
    endpoint = Endpoint(reader, writer)
    server = GclintServer(endpoint)
    endpoint.problem = server.problem
    endpoint.gate = server.gate
    for method in METHODS:
        handler = _guard(server, method.name, method.handler)
        if not method.notification:
            endpoint.requests[method.name] = handler
        elif method.early:
            endpoint.notifications[method.name] = handler
        else:  # (the protocol drops notifications before "initialize")
            endpoint.notifications[method.name] = _before_initialize(server, handler)
    return server


def _before_initialize(server: GclintServer, handler: Callable) -> Callable:
    @functools.wraps(handler)
    def wrapped(params: Any) -> Any:
        if not server.initialized:
            return None
        return handler(params)

    return wrapped


def _dialect_for(
    done: Analysis | None, options: Options, snapshot: Snapshot, name: str
) -> tuple[dialects.Dialect, str]:
    """The dialect the check found for the document; before any check (or when it failed), the one
    the options or the document's header give."""
    if done is not None and done.result.dialect:
        try:
            return dialects.get(done.result.dialect), done.result.dialect_reason
        except dialects.UnknownDialect:
            pass
    try:
        context = linter_for(options).context_of(Source.from_text(clean_surrogates(snapshot.text[:65536]), name))
    except SourceError:  # (not G-code: its check says so; hover reads it as the options' dialect)
        try:
            return dialects.get(options.dialect), ""
        except dialects.UnknownDialect:  # ("auto")
            return dialects.get("hyrel"), ""
    return dialects.reading(context.dialect, context.flavor), context.why()


# What the first check of a job would otherwise do on top of checking it (about four times the check of
# 20,000 lines): load the rules and the grammar, compile the patterns that find runs of plain moves, and
# check a Hyrel and a Marlin job once.  Done step by step in a worker thread after "initialize", until
# the first document is opened (its own check then warms up what it needs, no more).
_WARM_HYREL = (
    "; gclint: dialect=hyrel\nM6 T0 O1 X0 Y0 Z0\nG21\nG90\nG28 X0 Y0\nM106 C255\nM229 E1 D1\nM109 T0 S215\nT0\n"
    + "".join(f"G1 X{i % 50}.5 Y{i % 30}.25 E{i * 0.05:.3f} F1800\n" for i in range(60))
    + "G2 X10 Y10 I5 J0 E4\nM104 T0 S0\nM30\n"
)
_WARM_MARLIN = (
    ";FLAVOR:Marlin\nM140 S60\nM104 S200\nG28\nM190 S60\nM109 S200\nG92 E0\n"
    + "".join(f"G1 X{i % 50}.5 Y{i % 30}.25 E{i * 0.1:.3f} F1800\nG0 X1 Y2 F9000 ; travel\n" for i in range(60))
    + "G2 X10 Y10 I5 J0 E1\nM104 S0\nM84\n"
)


def _warm_up(stop: threading.Event, settings: Settings) -> None:
    def steps():
        from gclint.rules.base import all_rules
        from gclint.syntax.fastpath import run_pattern
        from gclint.syntax.parse import parse_slow

        yield all_rules
        yield lambda: parse_slow("G1 X1 (warm up) ; the grammar")
        yield lambda: run_pattern(False)
        yield lambda: run_pattern(True)
        options = analysis.document_options(None, settings)[0]
        for text in (_WARM_HYREL, _WARM_MARLIN):
            yield functools.partial(analysis.check_text, text, "warm-up.gcode", options, stop)

    try:
        for step in steps():
            if stop.is_set():
                return
            step()
    except Exception:  # (Cancelled included: a document came)
        pass
    finally:
        stop.set()


class _OneLine(logging.Formatter):
    """Log records on standard error (the editor's server log) as one line each: the exception's type
    and message, not its traceback (GCLINT_DEBUG=1 keeps tracebacks)."""

    def format(self, record: logging.LogRecord) -> str:
        text = f"gclint server: {record.levelname.lower()}: {record.getMessage()}"
        if record.exc_info and record.exc_info[1] is not None:
            exc = record.exc_info[1]
            if os.environ.get("GCLINT_DEBUG"):
                return text + "\n" + self.formatException(record.exc_info)
            text += f" ({type(exc).__name__}: {exc})"
        return " ".join(text.split())[:2000]


def run(stdin: BinaryIO | None = None, stdout: BinaryIO | None = None) -> int:
    """Serve over standard input and output until the client says exit (or goes away).  Returns the exit
    status the protocol asks for: 0 after a shutdown request, else 1."""
    out = stdout if stdout is not None else sys.stdout.buffer
    source = stdin if stdin is not None else sys.stdin.buffer
    if stdout is None:
        sys.stdout = sys.stderr  # a stray print must not corrupt the protocol stream
    if not logging.getLogger().handlers:
        handler = logging.StreamHandler(sys.stderr)
        handler.setFormatter(_OneLine())
        logging.basicConfig(level=logging.WARNING, handlers=[handler])
    server = create_server(source, out)
    try:
        server.endpoint.serve()
    finally:
        server.stop()
    if server.exit_status is not None:
        return server.exit_status
    return 0 if server.shutdown_requested else 1
