"""The language server: pygls glue between the editor and gclint.

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

Whatever goes wrong in a handler becomes one line in the client's log (``window/logMessage``); the
server keeps running.  The document text is kept here (``Snapshot``), with LSP line breaks, instead of in
pygls' workspace.
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

from lsprotocol import types as lsp
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol, lsp_method
from pygls.uris import to_fs_path

from gclint import __version__, dialects
from gclint.engine import FileResult, Options
from gclint.runner import linter_for
from gclint.server import analysis, convert
from gclint.server.analysis import Cancelled, Settings
from gclint.server.text import UTF8, UTF16, UTF32, Snapshot, clean_surrogates, units_to_char
from gclint.syntax.source import Source

logger = logging.getLogger("gclint.server")

DEBOUNCE = 0.3  # seconds of quiet after a change before the text is checked
MAX_DIAGNOSTICS = 10_000  # per document; beyond that the editor gains nothing and slows down
ANALYSIS_WAIT = 5.0  # how long a code action waits for the check of the current text
HOVER_WAIT = 1.0  # how long a hover waits for it (it needs only the dialect)
CONFIG_WAIT = 5.0  # how long to wait for the client's answer to workspace/configuration


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
    if urlparse(uri).scheme != "file":
        return None
    try:
        return to_fs_path(uri)
    except Exception:
        return None


@dataclass
class _Unreadable:
    """A message whose params do not fit the protocol's types (a negative position, a missing field):
    answered with InvalidParams when it is a request, instead of going unanswered."""

    msg_id: Any  # None for a notification
    method: str
    problem: str


def _problem(exc: BaseException) -> str:
    """What is wrong with a message, in one short line (``invalid value @ $.params.position``)."""
    try:
        import cattrs

        said = "; ".join(cattrs.transform_error(exc)) if isinstance(exc, cattrs.BaseValidationError) else ""
    except Exception:
        said = ""
    return " ".join((said or f"{type(exc).__name__}: {exc}").split())[:300]


class GclintProtocol(LanguageServerProtocol):
    """pygls' protocol without its own copy of the documents (the server keeps them, split into lines
    the way the protocol counts them), and with an answer to a request that cannot be read; everything
    else is pygls'.

    pygls (2.x) reads a message whose params do not deserialize by raising JsonRpcInvalidParams from the
    JSON decoder's object hook: the exception ends in its reader loop, which logs it (a cattrs traceback)
    and never answers, so the client waits forever for that request.  Here such a message becomes an
    ``_Unreadable``, answered with the JSON-RPC error InvalidParams (-32602) and one line in the log."""

    def structure_message(self, data: dict[str, Any]):
        if "jsonrpc" in data and "method" in data and "error" not in data:
            message_type = self.get_message_type(data["method"])
            if message_type is not None:
                try:
                    return self._converter.structure(data, message_type)
                except Exception as exc:  # what pygls turns into an unanswered JsonRpcInvalidParams
                    return _Unreadable(data.get("id"), str(data["method"])[:100], _problem(exc))
        return super().structure_message(data)

    def handle_message(self, message):
        if not isinstance(message, _Unreadable):
            return super().handle_message(message)
        what = f"{message.method}: invalid params ({message.problem})"
        if message.msg_id is not None and not self._shutdown:
            self._send_response(
                message.msg_id, None, lsp.ResponseError(code=lsp.ErrorCodes.InvalidParams, message=what)
            )
        if message.msg_id is not None:
            what = f"request {message.msg_id!r} {what}"
        server = self._server
        if isinstance(server, GclintServer):
            server.log(what, lsp.MessageType.Warning)
        else:
            logger.warning("%s", what)

    @lsp_method(lsp.TEXT_DOCUMENT_DID_OPEN)
    def lsp_text_document__did_open(self, params: lsp.DidOpenTextDocumentParams):
        if (handler := self.fm.features.get(lsp.TEXT_DOCUMENT_DID_OPEN)) is not None:
            yield handler, (params,), None

    @lsp_method(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def lsp_text_document__did_change(self, params: lsp.DidChangeTextDocumentParams):
        if (handler := self.fm.features.get(lsp.TEXT_DOCUMENT_DID_CHANGE)) is not None:
            yield handler, (params,), None

    @lsp_method(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def lsp_text_document__did_close(self, params: lsp.DidCloseTextDocumentParams):
        if (handler := self.fm.features.get(lsp.TEXT_DOCUMENT_DID_CLOSE)) is not None:
            yield handler, (params,), None


class GclintServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__(
            "gclint",
            __version__,
            text_document_sync_kind=lsp.TextDocumentSyncKind.Incremental,
            protocol_cls=GclintProtocol,
        )
        self.documents: dict[str, Document] = {}
        self.settings = Settings()
        # Checks in their own threads (two: one long job does not hold up another file); hovers in
        # another, so that a hover never waits behind a check.
        self.checks = ThreadPoolExecutor(max_workers=2, thread_name_prefix="gclint-check")
        self.requests = ThreadPoolExecutor(max_workers=1, thread_name_prefix="gclint-request")
        self.shutdown_requested = False
        self.markdown = False
        self.versioned_edits = False
        self.pull_configuration = False
        self.logged: set[str] = set()

    # -- helpers ------------------------------------------------------------------------------------------

    @property
    def encoding(self) -> str:
        try:
            chosen = self.workspace.position_encoding
        except RuntimeError:  # not initialized yet
            return UTF16
        value = getattr(chosen, "value", chosen)
        return value if value in (UTF8, UTF16, UTF32) else UTF16

    def log(self, message: str, kind: lsp.MessageType = lsp.MessageType.Info) -> None:
        """One line in the client's log (window/logMessage) and on standard error."""
        message = " ".join(str(message).split())[:2000]
        logger.log(logging.ERROR if kind == lsp.MessageType.Error else logging.INFO, "%s", message)
        try:
            self.window_log_message(lsp.LogMessageParams(type=kind, message=f"gclint: {message}"))
        except Exception:  # the client is gone: nothing more to say
            pass

    def log_once(self, message: str, kind: lsp.MessageType = lsp.MessageType.Warning) -> None:
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
        try:
            self.window_show_message(lsp.ShowMessageParams(type=lsp.MessageType.Warning, message=f"gclint: {message}"))
        except Exception:  # the client is gone: nothing more to say
            pass

    def report_server_error(self, error: Exception, source: Any) -> None:
        """pygls' out-of-band errors (a message that is not JSON, a failing notification): a line in the
        client's log, not a pop-up."""
        detail = f"{type(error).__name__}: {error}".splitlines()[0][:300]
        self.log(f"server error ({getattr(source, '__name__', source)}): {detail}", lsp.MessageType.Error)

    def apply_settings(self, raw: object) -> None:
        """Take the client's settings; open documents are checked again when they change anything."""
        settings, problems = analysis.parse_settings(raw)
        for problem in problems:
            self.log_once(problem)
        if settings != self.settings:
            self.settings = settings
            for doc in list(self.documents.values()):
                self.schedule(doc, 0)

    # -- checking -----------------------------------------------------------------------------------------

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
            encoding = self.encoding
            loop = asyncio.get_running_loop()
            work = functools.partial(_analyse, snapshot, doc.name, options, cancel, encoding)
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
            self.text_document_publish_diagnostics(
                lsp.PublishDiagnosticsParams(uri=doc.uri, diagnostics=diagnostics, version=snapshot.version)
            )
        except asyncio.CancelledError:
            cancel.set()
            raise
        except Exception as exc:
            self.log(f"{doc.name}: check failed: {type(exc).__name__}: {exc}", lsp.MessageType.Error)

    def _log_document(self, doc: Document, message: str) -> None:
        if message not in doc.problems:
            doc.problems.add(message)
            self.log(message, lsp.MessageType.Warning)

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


def _analyse(
    snapshot: Snapshot, name: str, options: Options, cancel: threading.Event, encoding: str
) -> tuple[FileResult, list[lsp.Diagnostic]]:
    """In a worker thread: check the text and turn the findings into diagnostics."""
    result = analysis.check_text(snapshot.text, name, options, cancel)
    geo = convert.Geometry(snapshot, encoding)
    return result, convert.diagnostics(result.findings, geo, MAX_DIAGNOSTICS)


def _guard(handler: Callable) -> Callable:
    """Any exception in a handler becomes a line in the client's log and an empty answer."""

    if asyncio.iscoroutinefunction(handler):

        @functools.wraps(handler)
        async def wrapped_async(ls: GclintServer, params: Any) -> Any:
            try:
                return await handler(ls, params)
            except asyncio.CancelledError:
                raise
            except Exception as exc:
                ls.log(f"{handler.__name__} failed: {type(exc).__name__}: {exc}", lsp.MessageType.Error)
                return None

        return wrapped_async

    @functools.wraps(handler)
    def wrapped(ls: GclintServer, params: Any) -> Any:
        try:
            return handler(ls, params)
        except Exception as exc:
            ls.log(f"{handler.__name__} failed: {type(exc).__name__}: {exc}", lsp.MessageType.Error)
            return None

    return wrapped


def create_server() -> GclintServer:
    server = GclintServer()

    @server.feature(lsp.INITIALIZE)
    @_guard
    def initialize(ls: GclintServer, params: lsp.InitializeParams) -> None:
        caps = params.capabilities
        hover_caps = caps.text_document.hover if caps.text_document is not None else None
        formats = (hover_caps.content_format or []) if hover_caps is not None else []
        ls.markdown = lsp.MarkupKind.Markdown in formats
        edit_caps = caps.workspace.workspace_edit if caps.workspace is not None else None
        ls.versioned_edits = bool(edit_caps is not None and edit_caps.document_changes)
        ls.pull_configuration = bool(caps.workspace is not None and caps.workspace.configuration)
        ls.apply_settings(params.initialization_options)
        ls.checks.submit(_warm_up)  # load the rules while the editor opens the first file

    @server.feature(lsp.INITIALIZED)
    @_guard
    async def initialized(ls: GclintServer, params: lsp.InitializedParams) -> None:
        if ls.pull_configuration:
            await _pull_settings(ls)

    @server.feature(lsp.SHUTDOWN)
    @_guard
    def shutdown(ls: GclintServer, params: Any) -> None:
        ls.shutdown_requested = True
        ls.stop()

    @server.feature(lsp.WORKSPACE_DID_CHANGE_CONFIGURATION)
    @_guard
    async def did_change_configuration(ls: GclintServer, params: lsp.DidChangeConfigurationParams) -> None:
        if params.settings is None or (ls.pull_configuration and params.settings in ({}, {"gclint": None})):
            await _pull_settings(ls)  # the client says "changed" and expects to be asked
        else:
            ls.apply_settings(params.settings)

    @server.feature(lsp.TEXT_DOCUMENT_DID_OPEN)
    @_guard
    def did_open(ls: GclintServer, params: lsp.DidOpenTextDocumentParams) -> None:
        item = params.text_document
        old = ls.documents.get(item.uri)
        if old is not None and old.cancel is not None:
            old.cancel.set()
        path = _path_of(item.uri)
        doc = Document(item.uri, path, path or unquote(item.uri), Snapshot(item.text, item.version))
        ls.documents[item.uri] = doc
        ls.schedule(doc, 0)

    @server.feature(lsp.TEXT_DOCUMENT_DID_CHANGE)
    @_guard
    def did_change(ls: GclintServer, params: lsp.DidChangeTextDocumentParams) -> None:
        doc = ls.documents.get(params.text_document.uri)
        if doc is None:
            return
        text = doc.snapshot.text
        encoding = ls.encoding
        for change in params.content_changes:
            if isinstance(change, lsp.TextDocumentContentChangePartial):
                r = change.range
                text = Snapshot(text).edited(
                    (r.start.line, r.start.character), (r.end.line, r.end.character), change.text, encoding
                )
            else:
                text = change.text
        doc.snapshot = Snapshot(text, params.text_document.version)
        ls.schedule(doc, DEBOUNCE)

    @server.feature(lsp.TEXT_DOCUMENT_DID_SAVE, lsp.SaveOptions(include_text=False))
    @_guard
    def did_save(ls: GclintServer, params: lsp.DidSaveTextDocumentParams) -> None:
        doc = ls.documents.get(params.text_document.uri)
        if doc is None:
            return
        if params.text is not None and params.text != doc.snapshot.text:
            doc.snapshot = Snapshot(params.text, doc.snapshot.version)
        ls.schedule(doc, 0)  # at once: the configuration may have changed too

    @server.feature(lsp.TEXT_DOCUMENT_DID_CLOSE)
    @_guard
    def did_close(ls: GclintServer, params: lsp.DidCloseTextDocumentParams) -> None:
        doc = ls.documents.pop(params.text_document.uri, None)
        if doc is None:
            return
        if doc.cancel is not None:
            doc.cancel.set()
        if doc.task is not None:
            doc.task.cancel()
        ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(uri=doc.uri, diagnostics=[]))

    @server.feature(lsp.TEXT_DOCUMENT_HOVER)
    @_guard
    async def hover(ls: GclintServer, params: lsp.HoverParams) -> lsp.Hover | None:
        doc = ls.documents.get(params.text_document.uri)
        if doc is None:
            return None
        snapshot = doc.snapshot
        encoding = ls.encoding
        line = params.position.line
        char = units_to_char(snapshot.line(line), params.position.character, encoding)
        # the dialect of the last check (it rarely changes while typing); wait only when there is none
        done = doc.analysis if doc.analysis is not None else await ls.current_analysis(doc, HOVER_WAIT)
        options = done.options if done is not None else analysis.document_options(doc.path, ls.settings)[0]
        dialect, reason = _dialect_for(done, options, snapshot, doc.name)
        target = await ls.run_in_thread(analysis.explain_at, snapshot, line, char, dialect, options.loaded)
        if target is None:
            return None
        return convert.hover(target, convert.Geometry(snapshot, encoding), line + 1, ls.markdown, reason)

    @server.feature(
        lsp.TEXT_DOCUMENT_CODE_ACTION,
        lsp.CodeActionOptions(code_action_kinds=[lsp.CodeActionKind.QuickFix, convert.FIX_ALL_KIND]),
    )
    @_guard
    async def code_action(ls: GclintServer, params: lsp.CodeActionParams) -> list[lsp.CodeAction] | None:
        doc = ls.documents.get(params.text_document.uri)
        if doc is None:
            return None
        done = await ls.current_analysis(doc, ANALYSIS_WAIT)
        if done is None or done.snapshot is not doc.snapshot:
            return None  # edits computed on other text would land in the wrong places
        only = [str(getattr(k, "value", k)) for k in params.context.only] if params.context.only else None
        # "fix all" applies what --fix would: the safe fixes that bring no new finding (gclint.fixes)
        fix_all = await ls.run_in_thread(analysis.safe_fix_set, done.result, done.snapshot.text, done.options)
        actions = convert.code_actions(
            doc.uri,
            done.result.findings,
            convert.Geometry(done.snapshot, ls.encoding),
            params.range.start.line,
            params.range.end.line,
            only,
            version=done.snapshot.version if ls.versioned_edits else None,
            fix_all=fix_all,
        )
        return actions or None

    return server


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
    context = linter_for(options).context_of(Source.from_text(clean_surrogates(snapshot.text[:65536]), name))
    return dialects.reading(context.dialect, context.flavor), context.why()


async def _pull_settings(ls: GclintServer) -> None:
    try:
        answer = await asyncio.wait_for(
            ls.workspace_configuration_async(lsp.ConfigurationParams(items=[lsp.ConfigurationItem(section="gclint")])),
            CONFIG_WAIT,
        )
    except Exception as exc:
        ls.log(f"could not read the editor's gclint settings: {type(exc).__name__}: {exc}", lsp.MessageType.Warning)
        return
    if answer:
        ls.apply_settings(answer[0])


def _warm_up() -> None:
    try:
        analysis.check_text("G28\n", "warm-up.gcode", Options())
    except Exception:
        pass


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


class _Input:
    """Standard input for pygls' reader, made safe: a message body that is not valid UTF-8 is repaired
    (bad bytes become U+FFFD) instead of failing to parse, and a huge Content-Length is read in pieces
    rather than allocated at once."""

    PIECE = 1 << 24

    def __init__(self, raw: BinaryIO) -> None:
        self.raw = raw

    def readline(self) -> bytes:
        return self.raw.readline()

    def read(self, n: int) -> bytes:
        if n <= self.PIECE:
            data = self.raw.read(n)
        else:
            parts = []
            left = n
            while left > 0:
                part = self.raw.read(min(left, self.PIECE))
                if not part:
                    break
                parts.append(part)
                left -= len(part)
            data = b"".join(parts)
        try:
            data.decode("utf-8")
        except UnicodeDecodeError:
            data = data.decode("utf-8", "replace").encode("utf-8")
        return data


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
    server = create_server()
    try:
        server.start_io(_Input(source), out)  # type: ignore[arg-type]
    finally:
        server.stop()
    return 0 if server.shutdown_requested else 1
