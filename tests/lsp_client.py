"""A small Language Server Protocol client for the tests and bench/bench_server.py: starts ``gclint
server`` as a real process and talks JSON-RPC over its standard input and output (Content-Length
framing), as an editor does.  Synchronous: a reader thread queues what the server sends."""

from __future__ import annotations

import json
import os
import queue
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent


class ServerGone(Exception):
    pass


class LspClient:
    def __init__(self, args: list[str] | None = None, env: dict | None = None, cwd: str | None = None) -> None:
        full_env = dict(os.environ)
        full_env.pop("GCLINT_CACHE_DIR", None)
        full_env["PYTHONPATH"] = str(ROOT) + os.pathsep + full_env.get("PYTHONPATH", "")
        if env:
            full_env.update(env)
        self.proc = subprocess.Popen(
            args or [sys.executable, "-m", "gclint", "server"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=full_env,
            cwd=cwd,
        )
        self.inbox: queue.Queue = queue.Queue()
        self.notifications: list[dict] = []
        self.requests_from_server: list[dict] = []
        self.responses: dict[Any, dict] = {}
        self.answers: dict[str, Callable[[dict], Any]] = {}  # method -> reply to server requests
        self._next_id = 0
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()
        self._stderr: list[bytes] = []
        self._err_reader = threading.Thread(target=self._read_stderr, daemon=True)
        self._err_reader.start()

    # -- wire ------------------------------------------------------------------------------------------

    def _read(self) -> None:
        out = self.proc.stdout
        assert out is not None
        try:
            while True:
                length = None
                while True:
                    header = out.readline()
                    if not header:
                        self.inbox.put(None)
                        return
                    header = header.strip()
                    if not header:
                        break
                    name, _, value = header.partition(b":")
                    if name.lower() == b"content-length":
                        length = int(value)
                if length is None:
                    continue
                body = out.read(length)
                self.inbox.put(json.loads(body))
        except Exception as exc:  # pragma: no cover - shows in the test's failure
            self.inbox.put({"reader_error": repr(exc)})
            self.inbox.put(None)

    def _read_stderr(self) -> None:
        err = self.proc.stderr
        assert err is not None
        for line in iter(err.readline, b""):
            self._stderr.append(line)

    @property
    def stderr(self) -> str:
        return b"".join(self._stderr).decode("utf-8", "replace")

    def send_raw(self, body: bytes) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.proc.stdin.flush()

    def send(self, message: dict) -> None:
        self.send_raw(json.dumps(message).encode("utf-8"))

    def notify(self, method: str, params: Any = None) -> None:
        message: dict = {"jsonrpc": "2.0", "method": method}
        if params is not None:
            message["params"] = params
        self.send(message)

    def request_async(self, method: str, params: Any = None) -> int:
        self._next_id += 1
        message: dict = {"jsonrpc": "2.0", "id": self._next_id, "method": method}
        if params is not None:
            message["params"] = params
        self.send(message)
        return self._next_id

    def request(self, method: str, params: Any = None, timeout: float = 30) -> Any:
        msg_id = self.request_async(method, params)
        response = self.wait_response(msg_id, timeout)
        if "error" in response:
            raise AssertionError(f"{method} failed: {response['error']}")
        return response.get("result")

    def wait_response(self, msg_id: int, timeout: float = 30) -> dict:
        self._pump(lambda: msg_id in self.responses, timeout, f"response {msg_id}")
        return self.responses.pop(msg_id)

    def wait_notification(
        self, method: str, predicate: Callable[[dict], bool] | None = None, timeout: float = 30, since: int = 0
    ) -> dict:
        """The first notification ``method`` (at index >= ``since``) whose params satisfy ``predicate``."""
        found: list[dict] = []

        def check() -> bool:
            for n in self.notifications[since:]:
                if n.get("method") == method and (predicate is None or predicate(n.get("params"))):
                    found.append(n)
                    return True
            return False

        self._pump(check, timeout, method)
        return found[0]["params"]

    def _pump(self, done: Callable[[], bool], timeout: float, what: str) -> None:
        deadline = time.monotonic() + timeout
        while not done():
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError(f"no {what} within {timeout}s; stderr:\n{self.stderr[-3000:]}")
            try:
                message = self.inbox.get(timeout=remaining)
            except queue.Empty:
                continue
            if message is None:
                self.inbox.put(None)  # keep saying so
                if done():
                    return
                raise ServerGone(f"server closed its output while waiting for {what}; stderr:\n{self.stderr[-3000:]}")
            self._dispatch(message)

    def _dispatch(self, message: dict) -> None:
        if "id" in message and "method" in message:  # a request from the server
            self.requests_from_server.append(message)
            answer = self.answers.get(message["method"])
            result = answer(message) if answer is not None else None
            self.send({"jsonrpc": "2.0", "id": message["id"], "result": result})
        elif "id" in message:
            self.responses[message["id"]] = message
        else:
            self.notifications.append(message)

    def wait_request(self, method: str, timeout: float = 30) -> dict:
        """The first request ``method`` the server sent (already answered through ``answers``)."""
        self._pump(lambda: any(r["method"] == method for r in self.requests_from_server), timeout, method)
        return next(r for r in self.requests_from_server if r["method"] == method)

    def drain(self, seconds: float) -> None:
        """Handle whatever arrives for ``seconds``."""
        deadline = time.monotonic() + seconds
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return
            try:
                message = self.inbox.get(timeout=remaining)
            except queue.Empty:
                return
            if message is None:
                self.inbox.put(None)
                return
            self._dispatch(message)

    # -- conveniences ------------------------------------------------------------------------------------

    def initialize(self, capabilities: dict | None = None, options: Any = None, root: str | None = None) -> dict:
        params: dict = {"processId": os.getpid(), "capabilities": capabilities or {}}
        if options is not None:
            params["initializationOptions"] = options
        if root is not None:
            params["rootUri"] = Path(root).as_uri()
        result = self.request("initialize", params)
        self.notify("initialized", {})
        return result

    def open(self, uri: str, text: str, version: int = 1, language: str = "gcode") -> None:
        self.notify(
            "textDocument/didOpen",
            {"textDocument": {"uri": uri, "languageId": language, "version": version, "text": text}},
        )

    def diagnostics(self, uri: str, version: int | None = None, timeout: float = 30, since: int = 0) -> list[dict]:
        params = self.wait_notification(
            "textDocument/publishDiagnostics",
            lambda p: p["uri"] == uri and (version is None or p.get("version") == version),
            timeout,
            since,
        )
        return params["diagnostics"]

    def logs(self) -> list[str]:
        return [n["params"]["message"] for n in self.notifications if n.get("method") == "window/logMessage"]

    def shutdown_and_exit(self, timeout: float = 30) -> int:
        self.request("shutdown")
        self.notify("exit")
        try:
            assert self.proc.stdin is not None
            self.proc.stdin.close()
        except OSError:
            pass
        return self.proc.wait(timeout)

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(10)
