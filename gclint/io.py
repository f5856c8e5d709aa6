"""Safe output: write to a temporary file beside the target and rename it over the target, so a failure
never leaves a half-written job; special files (/dev/stdout, pipes, /dev/full) are written directly.

* Links: an output gclint creates (a report, ``-o``, the Cura script) is never written through a symbolic
  link: a link planted where the output goes (``job.gcode.gclint.txt -> ~/.bashrc``) is refused with one
  line.  Only the links of the system's own stream files (``/dev/stdout``, ``/dev/fd/1``) are followed.
  In-place rewrites of a file the user named (``--in-place``, ``--fix``, ``postprocess``) pass
  ``follow_links=True``: the job the link points to is rewritten and the link stays a link.
* The temporary file is created exclusively (``mkstemp``) in the target's folder, so it never follows a
  link either; the rename replaces the directory entry, never what it points to.
* Mode, owner and group of a replaced file are kept where the system allows it.
* A named pipe is opened without waiting: one that nothing reads is refused with one line (a FIFO planted
  where ``postprocess`` writes its report would otherwise hang the slicer's export).
* SIGTERM while a temporary file exists removes it before the process ends (a killed job leaves nothing).
"""

from __future__ import annotations

import errno
import os
import signal
import stat
import threading
from typing import BinaryIO

_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)
_SYSTEM_LINKS = ("/dev/", "/proc/")  # /dev/stdout -> /proc/self/fd/1 -> a pipe, a tty or a redirected file


class OutputError(Exception):
    """Output that could not be written; the message is one line naming the file."""


# -- temporary files removed on SIGTERM ---------------------------------------------------------------------------

_LIVE: set[str] = set()
_installed = False


def _on_sigterm(signum, frame) -> None:
    for path in list(_LIVE):
        try:
            os.unlink(path)
        except OSError:
            pass
    _LIVE.clear()
    previous = _previous_handler
    if callable(previous):
        previous(signum, frame)
        return
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    os.kill(os.getpid(), signal.SIGTERM)


_previous_handler: object = None


def _install_sigterm() -> None:
    global _installed, _previous_handler
    if _installed or threading.current_thread() is not threading.main_thread() or not hasattr(signal, "SIGTERM"):
        return
    try:
        _previous_handler = signal.signal(signal.SIGTERM, _on_sigterm)
        _installed = True
    except (ValueError, OSError):  # not the main interpreter thread
        pass


class AtomicWriter:
    """``with AtomicWriter(path) as out: out.write(b"...")`` replaces ``path`` only if all went well.

    Call ``discard()`` inside the block to leave the target untouched.
    """

    def __init__(self, path: str, keep_mode_of: str | None = None, *, follow_links: bool = False) -> None:
        self.path = path
        self.keep_mode_of = keep_mode_of
        self.follow_links = follow_links
        self._target = path
        self._tmp: str | None = None
        self._fh: BinaryIO | None = None
        self._discarded = False
        self._direct = False
        self._via_link = False
        self._fifo = False

    def _where(self) -> None:
        """Decide what to write: the target file and whether it is written directly (a stream) or replaced."""
        try:
            st = os.lstat(self.path)
        except FileNotFoundError:
            return
        if stat.S_ISLNK(st.st_mode):
            if not (self.follow_links or self.path.startswith(_SYSTEM_LINKS)):
                raise OutputError(
                    f"{self.path}: is a symbolic link; gclint does not write through links (remove it or name its target)"
                )
            self._via_link = True
            try:
                st = os.stat(self.path)
            except FileNotFoundError:
                self._target = os.path.realpath(self.path)
                return
            if stat.S_ISREG(st.st_mode):
                # Replace what the link points to, not the link (which would leave the real job untouched
                # and turn the link into a copy).  Messages keep the name the user gave.
                self._target = os.path.realpath(self.path)
                return
        if stat.S_ISREG(st.st_mode):
            return
        if stat.S_ISDIR(st.st_mode):
            raise OutputError(f"{self.path}: is a folder")
        if stat.S_ISBLK(st.st_mode):
            raise OutputError(f"{self.path}: is a disk device; gclint does not write to it")
        self._direct = True  # a terminal, a pipe, /dev/null, /dev/full
        self._fifo = stat.S_ISFIFO(st.st_mode)

    def __enter__(self) -> AtomicWriter:
        try:
            self._where()
        except OSError as exc:
            raise OutputError(f"{self.path}: cannot write: {exc.strerror or exc}") from None
        try:
            if self._direct:
                fd = _open_direct(self._target, self._fifo, follow=self._via_link)
                self._fh = os.fdopen(fd, "wb")
            else:
                _install_sigterm()
                folder = os.path.dirname(os.path.abspath(self._target))
                import tempfile  # (here: the check's report to standard output needs none)

                fd, self._tmp = tempfile.mkstemp(prefix=".gclint-", suffix=".tmp", dir=folder)
                _LIVE.add(self._tmp)
                self._fh = os.fdopen(fd, "wb")
        except OSError as exc:
            self._cleanup()
            if self._fifo and exc.errno == errno.ENXIO:
                raise OutputError(f"{self.path}: is a named pipe that nothing reads") from None
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
                self._keep_attributes(self._tmp)
                os.replace(self._tmp, self._target)
            except OSError as err:
                self._cleanup()
                raise OutputError(f"{self.path}: cannot replace: {err.strerror or err}") from None
            _LIVE.discard(self._tmp)
            self._tmp = None

    def _keep_attributes(self, tmp: str) -> None:
        """Mode, owner and group of the file being replaced (or of ``keep_mode_of``)."""
        source = self.keep_mode_of or self._target
        try:
            st = os.stat(source)
        except OSError:  # a new file: the mode any new file gets (mkstemp makes it private)
            os.chmod(tmp, 0o666 & ~_umask())
            return
        if hasattr(os, "chown") and hasattr(os, "getuid"):
            own = os.stat(tmp)
            if (own.st_uid, own.st_gid) != (st.st_uid, st.st_gid):
                try:
                    os.chown(tmp, st.st_uid, st.st_gid)
                except OSError:
                    try:  # not allowed to give the file away: keep at least the group
                        os.chown(tmp, -1, st.st_gid)
                    except OSError:
                        pass
        os.chmod(tmp, stat.S_IMODE(st.st_mode))

    def _cleanup(self) -> None:
        if self._tmp is not None:
            try:
                os.unlink(self._tmp)
            except OSError:
                pass
            _LIVE.discard(self._tmp)
            self._tmp = None


def _open_direct(path: str, fifo: bool, *, follow: bool) -> int:
    """Open a stream file for writing.  A named pipe is opened without waiting: with nothing reading it,
    opening would block for ever (a FIFO planted where a report goes must not hang a slicer's export); it
    fails with ENXIO instead.  Once open, writes block as usual."""
    flags = os.O_WRONLY | os.O_TRUNC | (0 if follow else _NOFOLLOW)
    if not fifo or not _NONBLOCK:
        return os.open(path, flags)
    fd = os.open(path, flags | _NONBLOCK)
    try:
        import fcntl

        fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) & ~_NONBLOCK)
    except (ImportError, OSError):
        pass
    return fd


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


class TextOutput:
    """A text stream over an ``AtomicWriter`` (UTF-8; text that cannot be encoded as backslash escapes)."""

    def __init__(self, writer: AtomicWriter) -> None:
        self._writer = writer

    def write(self, text: str) -> int:
        self._writer.write(text.encode("utf-8", "backslashreplace"))
        return len(text)

    def flush(self) -> None:
        pass


def write_text(path: str, render) -> None:
    """Write ``render(stream)``'s text to ``path`` atomically, never through a link (raises OutputError)."""
    with AtomicWriter(path) as out:
        render(TextOutput(out))
