"""Safe output: write to a temporary file beside the target and rename it over the target, so a failure
never leaves a half-written job; special files (/dev/stdout, pipes, /dev/full) are written directly."""

from __future__ import annotations

import os
import stat
import tempfile
from typing import BinaryIO


class OutputError(Exception):
    """Output that could not be written; the message is one line naming the file."""


class AtomicWriter:
    """``with AtomicWriter(path) as out: out.write(b"...")`` replaces ``path`` only if all went well.

    Call ``discard()`` inside the block to leave the target untouched.
    """

    def __init__(self, path: str, keep_mode_of: str | None = None) -> None:
        self.path = path
        # Replace what a symbolic link points to, not the link (which would leave the real job untouched
        # and turn the link into a copy).  Messages keep the name the user gave.
        self._target = os.path.realpath(path) if os.path.islink(path) else path
        self.keep_mode_of = keep_mode_of
        self._tmp: str | None = None
        self._fh: BinaryIO | None = None
        self._discarded = False
        self._direct = False

    def __enter__(self) -> AtomicWriter:
        try:
            st = os.stat(self._target)
            self._direct = not stat.S_ISREG(st.st_mode)
        except FileNotFoundError:
            self._direct = False
        except OSError as exc:
            raise OutputError(f"{self.path}: cannot write: {exc.strerror or exc}") from None
        try:
            if self._direct:
                self._fh = open(self._target, "wb")  # noqa: SIM115
            else:
                folder = os.path.dirname(os.path.abspath(self._target))
                fd, self._tmp = tempfile.mkstemp(prefix=".gclint-", suffix=".tmp", dir=folder)
                self._fh = os.fdopen(fd, "wb")
        except OSError as exc:
            raise OutputError(f"{self.path}: cannot write: {exc.strerror or exc}") from None
        return self

    def write(self, data: bytes) -> None:
        try:
            self._fh.write(data)  # type: ignore[union-attr]
        except OSError as exc:
            raise OutputError(f"{self.path}: write failed: {exc.strerror or exc}") from None

    def discard(self) -> None:
        self._discarded = True

    def __exit__(self, exc_type, exc, tb) -> None:
        fh, self._fh = self._fh, None
        try:
            if fh is not None:
                try:
                    fh.flush()
                    if exc_type is None and not self._discarded and not self._direct:
                        os.fsync(fh.fileno())
                finally:
                    fh.close()
        except OSError as err:
            self._cleanup()
            if exc_type is None:
                raise OutputError(f"{self.path}: write failed: {err.strerror or err}") from None
            return
        if exc_type is not None or self._discarded:
            self._cleanup()
            return
        if self._tmp is not None:
            try:
                source = self.keep_mode_of or (self._target if os.path.exists(self._target) else None)
                if source is not None:
                    os.chmod(self._tmp, stat.S_IMODE(os.stat(source).st_mode))
                os.replace(self._tmp, self._target)
            except OSError as err:
                self._cleanup()
                raise OutputError(f"{self.path}: cannot replace: {err.strerror or err}") from None
            self._tmp = None

    def _cleanup(self) -> None:
        if self._tmp is not None:
            try:
                os.unlink(self._tmp)
            except OSError:
                pass
            self._tmp = None
