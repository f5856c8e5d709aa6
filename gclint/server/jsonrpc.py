"""JSON-RPC 2.0 over a byte stream with the Language Server Protocol's ``Content-Length`` framing.

The language server's own transport, with nothing but the standard library: a reader thread parses
messages from standard input and hands them to the asyncio loop; requests run as tasks (cancelled by
``$/cancelRequest``), notifications in the order they came; the server's own requests to the client
(``workspace/configuration``) wait for their answer on a future.  Messages are plain dicts, as JSON has
them.  (pygls and lsprotocol did this before; importing lsprotocol's types alone took longer than
checking a 20,000-line job, bench/bench_server.py.)

Robustness, as an editor's server needs it: a body that is not valid UTF-8 is repaired (bad bytes
become U+FFFD), a huge ``Content-Length`` is read in pieces, a message that is not JSON or not a
JSON-RPC message is one line in the log, and a request whose params do not fit is answered with
InvalidParams naming the place (``$.params.position.line``) instead of going unanswered.
"""

from __future__ import annotations

import asyncio
import inspect
import json
import threading
from collections.abc import Callable
from typing import Any, BinaryIO

# JSON-RPC and LSP error codes
PARSE_ERROR = -32700
INVALID_REQUEST = -32600
METHOD_NOT_FOUND = -32601
INVALID_PARAMS = -32602
INTERNAL_ERROR = -32603
SERVER_NOT_INITIALIZED = -32002
REQUEST_CANCELLED = -32800

PIECE = 1 << 24  # a body is read in pieces of this size (a huge Content-Length is not allocated at once)
MAX_HEADER_LINE = 1 << 16


class InvalidParams(Exception):
    """The params of a message do not fit what the method takes; the text names where (``@ $.params.x``)."""


class ResponseError(Exception):
    def __init__(self, code: int, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


# -- reading params -------------------------------------------------------------------------------------


def obj(value: Any, where: str) -> dict:
    if not isinstance(value, dict):
        raise InvalidParams(f"expected an object @ {where}")
    return value


def member(container: dict, key: str, where: str, kind: type | tuple[type, ...], default: Any = ...) -> Any:
    """``container[key]`` when it has the type ``kind``; ``default`` when it is missing (or null) and a
    default is given; else InvalidParams naming the place."""
    value = container.get(key)
    if value is None:
        if default is not ...:
            return default
        raise InvalidParams(f"missing '{key}' @ {where}.{key}")
    if isinstance(value, bool) and bool not in (kind if isinstance(kind, tuple) else (kind,)):
        raise InvalidParams(f"invalid value @ {where}.{key}")
    if not isinstance(value, kind):
        raise InvalidParams(f"invalid value @ {where}.{key}")
    return value


def uint(container: dict, key: str, where: str) -> int:
    """A non-negative integer (the protocol's ``uinteger``: lines, characters)."""
    value = member(container, key, where, int)
    if value < 0:
        raise InvalidParams(f"invalid value @ {where}.{key}")
    return value


def position(value: Any, where: str) -> tuple[int, int]:
    p = obj(value, where)
    return uint(p, "line", where), uint(p, "character", where)


def range_of(value: Any, where: str) -> tuple[tuple[int, int], tuple[int, int]]:
    r = obj(value, where)
    return position(r.get("start"), f"{where}.start"), position(r.get("end"), f"{where}.end")


def document_uri(params: dict, where: str = "$.params") -> str:
    doc = obj(params.get("textDocument"), f"{where}.textDocument")
    return member(doc, "uri", f"{where}.textDocument", str)


# -- the wire -------------------------------------------------------------------------------------------


def read_message(stream: BinaryIO) -> bytes | None:
    """The body of the next message (headers up to an empty line, then ``Content-Length`` bytes), or
    None at the end of the stream.  Header blocks without a length are skipped."""
    while True:
        length = None
        while True:
            line = stream.readline(MAX_HEADER_LINE)
            if not line:
                return None
            line = line.strip()
            if not line:
                if length is not None:
                    break
                continue  # (blank lines between messages)
            name, _, value = line.partition(b":")
            if name.strip().lower() == b"content-length":
                try:
                    length = int(value.strip())
                except ValueError:
                    length = None
        if length < 0:
            continue
        parts = []
        left = length
        while left > 0:
            part = stream.read(min(left, PIECE))
            if not part:
                return None
            parts.append(part)
            left -= len(part)
        return b"".join(parts)


def decode(body: bytes) -> Any:
    """JSON from a body: bytes that are not UTF-8 become U+FFFD rather than failing the message."""
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError:
        text = body.decode("utf-8", "replace")
    return json.loads(text)


def encode(message: dict) -> bytes:
    body = json.dumps(message, ensure_ascii=False, separators=(",", ":"))
    try:
        data = body.encode("utf-8")
    except UnicodeEncodeError:  # a lone surrogate (from the client's own JSON escapes): escaped, valid JSON
        data = json.dumps(message, ensure_ascii=True, separators=(",", ":")).encode("ascii")
    return b"Content-Length: %d\r\n\r\n" % len(data) + data


Handler = Callable[[Any], Any]


class Endpoint:
    """One side of a JSON-RPC connection, run on an asyncio loop.

    ``requests`` and ``notifications`` map method names to handlers taking the params (a handler may be
    a coroutine function).  ``problem`` is called with one line for whatever cannot be handled (a body
    that is not JSON, a failing notification, a request whose params do not fit).  ``gate`` is asked
    before each request is run and may raise ResponseError (not initialized, shut down)."""

    def __init__(self, reader: BinaryIO, writer: BinaryIO) -> None:
        self.reader = reader
        self.writer = writer
        self.requests: dict[str, Handler] = {}
        self.notifications: dict[str, Handler] = {}
        self.problem: Callable[[str], None] = lambda text: None
        self.gate: Callable[[str], None] = lambda method: None
        self.loop: asyncio.AbstractEventLoop | None = None
        self.closed = False
        self._write_lock = threading.Lock()
        self._running: dict[Any, asyncio.Task] = {}
        self._pending: dict[int, asyncio.Future] = {}
        self._next_id = 0
        self._done: asyncio.Future | None = None

    # -- sending (from any thread) --------------------------------------------------------------------

    def send(self, message: dict) -> None:
        data = encode(message)
        with self._write_lock:
            if self.closed:
                return
            try:
                self.writer.write(data)
                self.writer.flush()
            except (OSError, ValueError):  # the client has gone
                self.closed = True

    def notify(self, method: str, params: Any = None) -> None:
        message: dict = {"jsonrpc": "2.0", "method": method}
        if params is not None:
            message["params"] = params
        self.send(message)

    async def request(self, method: str, params: Any = None, timeout: float | None = None) -> Any:
        """Ask the client; returns its result, raises ResponseError for its error (TimeoutError after
        ``timeout`` seconds)."""
        assert self.loop is not None
        self._next_id += 1
        msg_id = self._next_id
        future = self.loop.create_future()
        self._pending[msg_id] = future
        message: dict = {"jsonrpc": "2.0", "id": msg_id, "method": method}
        if params is not None:
            message["params"] = params
        self.send(message)
        try:
            return await asyncio.wait_for(future, timeout)
        finally:
            self._pending.pop(msg_id, None)

    def _respond(self, msg_id: Any, result: Any = None, error: tuple[int, str] | None = None) -> None:
        message: dict = {"jsonrpc": "2.0", "id": msg_id}
        if error is not None:
            message["error"] = {"code": error[0], "message": error[1]}
        else:
            message["result"] = result
        self.send(message)

    # -- running --------------------------------------------------------------------------------------

    def serve(self, started: Callable[[], None] | None = None) -> None:
        """Read and handle messages until ``stop()`` or the end of the input."""
        loop = asyncio.new_event_loop()
        self.loop = loop
        asyncio.set_event_loop(loop)
        self._done = loop.create_future()
        reader = threading.Thread(target=self._read, name="gclint-reader", daemon=True)
        reader.start()
        if started is not None:
            started()
        try:
            loop.run_until_complete(self._done)
        finally:
            for task in list(self._running.values()):
                task.cancel()
            try:
                loop.run_until_complete(asyncio.sleep(0))
            except Exception:
                pass
            loop.close()

    def stop(self) -> None:
        if self._done is not None and not self._done.done():
            self._done.set_result(None)

    def _post(self, func: Callable, *args: Any) -> bool:
        """Run ``func(*args)`` on the loop (from the reader thread); False once the loop is closed."""
        loop = self.loop
        if loop is None:
            return False
        try:
            loop.call_soon_threadsafe(func, *args)
            return True
        except RuntimeError:  # the loop is closed: the server has ended
            return False

    def _read(self) -> None:
        try:
            while True:
                body = read_message(self.reader)
                if body is None:
                    break
                try:
                    message: Any = decode(body)
                except ValueError as exc:
                    detail = " ".join(str(exc).split())[:200]
                    if not self._post(self.problem, f"server error (reader): not JSON: {detail}"):
                        return
                    continue
                if not self._post(self._dispatch, message):
                    return
        except Exception as exc:  # the input broke: as the end of it
            self._post(self.problem, f"server error (reader): {type(exc).__name__}: {exc}")
        self._post(self.stop)

    def _dispatch(self, message: Any) -> None:
        if not isinstance(message, dict):
            self.problem(f"server error (reader): not a JSON-RPC message: {type(message).__name__}")
            return
        method = message.get("method")
        msg_id = message.get("id")
        if method is None:
            if "result" in message or "error" in message:
                self._answer(message)
            else:
                self.problem("server error (reader): a message with neither method nor result")
                if msg_id is not None:
                    self._respond(msg_id, error=(INVALID_REQUEST, "not a request, a notification or a response"))
            return
        if not isinstance(method, str):
            self.problem("server error (reader): a method that is not a string")
            if msg_id is not None:
                self._respond(msg_id, error=(INVALID_REQUEST, "the method must be a string"))
            return
        params = message.get("params")
        if "id" in message:
            if not isinstance(msg_id, (int, str)) or isinstance(msg_id, bool):
                self.problem(f"server error (reader): request {method[:100]} with an id that is not a number or string")
                return
            self._start_request(msg_id, method, params)
        else:
            self._notification(method, params)

    def _answer(self, message: dict) -> None:
        future = self._pending.get(message.get("id"))  # type: ignore[arg-type]
        if future is None or future.done():
            return
        if "error" in message:
            error = message["error"] if isinstance(message["error"], dict) else {}
            future.set_exception(ResponseError(int(error.get("code", INTERNAL_ERROR)), str(error.get("message", ""))))
        else:
            future.set_result(message.get("result"))

    def _notification(self, method: str, params: Any) -> None:
        if method == "$/cancelRequest":
            target = params.get("id") if isinstance(params, dict) else None
            task = self._running.get(target)
            if task is not None:
                task.cancel()
            return
        handler = self.notifications.get(method)
        if handler is None:
            return  # (unknown notifications, "$/..." ones included, are ignored, as the protocol says)
        try:
            outcome = handler(params)
        except InvalidParams as exc:
            self.problem(f"{method[:100]}: invalid params ({exc})")
            return
        except Exception as exc:
            self.problem(f"server error ({method[:100]}): {type(exc).__name__}: {exc}")
            return
        if inspect.isawaitable(outcome):
            task = asyncio.ensure_future(outcome)
            task.add_done_callback(lambda t: self._notification_done(method, t))

    def _notification_done(self, method: str, task: asyncio.Future) -> None:
        if task.cancelled():
            return
        exc = task.exception()
        if isinstance(exc, InvalidParams):
            self.problem(f"{method[:100]}: invalid params ({exc})")
        elif exc is not None:
            self.problem(f"server error ({method[:100]}): {type(exc).__name__}: {exc}")

    def _start_request(self, msg_id: Any, method: str, params: Any) -> None:
        try:
            self.gate(method)
        except ResponseError as exc:
            self._respond(msg_id, error=(exc.code, exc.message))
            return
        handler = self.requests.get(method)
        if handler is None:
            self._respond(msg_id, error=(METHOD_NOT_FOUND, f"{method[:100]}: no such method"))
            return
        task = asyncio.ensure_future(self._run_request(msg_id, method, handler, params))
        self._running[msg_id] = task
        task.add_done_callback(lambda t: self._running.pop(msg_id, None) if self._running.get(msg_id) is t else None)

    async def _run_request(self, msg_id: Any, method: str, handler: Handler, params: Any) -> None:
        try:
            result = handler(params)
            if inspect.isawaitable(result):
                result = await result
        except asyncio.CancelledError:
            self._respond(msg_id, error=(REQUEST_CANCELLED, f"{method[:100]}: cancelled"))
            return
        except InvalidParams as exc:
            what = f"{method[:100]}: invalid params ({exc})"
            self._respond(msg_id, error=(INVALID_PARAMS, what))
            self.problem(f"request {msg_id!r} {what}")
            return
        except ResponseError as exc:
            self._respond(msg_id, error=(exc.code, exc.message))
            return
        except Exception as exc:
            what = f"{method[:100]} failed: {type(exc).__name__}: {exc}"
            self._respond(msg_id, error=(INTERNAL_ERROR, what[:300]))
            self.problem(what)
            return
        self._respond(msg_id, result)
