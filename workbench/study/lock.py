"""The exclusive lock of a result folder: one run writes into a folder at a time.

A run holds ``<folder>/_lock`` locked (``fcntl.flock``, exclusive, non-blocking) for its whole
life; the file holds the holder's pid, host, start time and command line (JSON).  A second run
into the same folder is refused at once with one line naming the holder
(:class:`FolderLocked`, a :class:`~workbench.study.messages.StudyError`: the CLI exits with 2).
The operating system releases the lock when the holder dies, however it dies (``kill -9``
included), so a stale lock cannot block a folder: a new run takes it over and records the dead
holder (:attr:`FolderLock.stale`).  The file is never deleted (deleting a lock file while
another process opens it lets two processes hold "the" lock); an empty file means "free".
Linux ``flock`` works across hosts on NFS (emulated with POSIX locks); the name starts with
``_``, so Parquet dataset discovery skips it.

:func:`lock_holder` reads the holder for ``workbench show`` without touching the lock.

Checked by ``tests/study/test_lock.py`` (two processes, one folder: exactly one runs).
"""

from __future__ import annotations

import fcntl
import json
import os
import socket
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .messages import StudyError

__all__ = ["LOCK_FILE", "FolderLock", "FolderLocked", "lock_holder", "describe_holder"]

LOCK_FILE = "_lock"


class FolderLocked(StudyError):
    """Another live process holds the folder's lock (``holder``: what its lock file says)."""

    def __init__(self, folder: Path, holder: dict[str, Any]):
        self.holder = holder
        super().__init__([f"{folder}: another run is writing into this folder ({describe_holder(holder)}); "
                          f"wait for it to finish or choose another --out"])


def describe_holder(holder: dict[str, Any]) -> str:
    """``"pid 123 on host h, started 2026-...: workbench run ..."`` (what is known of it)."""
    if not holder:
        return "holder unknown"
    text = f"pid {holder.get('pid', '?')} on host {holder.get('host', '?')}"
    if holder.get("start"):
        text += f", started {holder['start']}"
    if holder.get("command"):
        text += f": {holder['command'][:120]}"
    return text


def _read(fd: int) -> dict[str, Any]:
    os.lseek(fd, 0, os.SEEK_SET)
    raw = b""
    while chunk := os.read(fd, 65536):
        raw += chunk
    try:
        data = json.loads(raw.decode("utf-8")) if raw.strip() else {}
    except (UnicodeDecodeError, json.JSONDecodeError):
        data = {"unreadable": raw[:200].decode("utf-8", "replace")}
    return data if isinstance(data, dict) else {}


@dataclass
class FolderLock:
    """The lock of ``folder`` (created with its parents on :meth:`acquire`).

    Attributes
    ----------
    folder : Path
    created_folder : bool
        The folder did not exist before :meth:`acquire` (so a run that fails before writing
        anything can remove it again, :meth:`release` with ``remove_folder=True``).
    stale : dict or None
        The lock file's content when it was taken over from a holder that died.
    """

    folder: Path
    created_folder: bool = False
    stale: dict[str, Any] | None = None
    _fd: int | None = None

    def __post_init__(self) -> None:
        self.folder = Path(self.folder)

    def acquire(self, start: str = "") -> "FolderLock":
        """Take the lock or raise :class:`FolderLocked`; ``OSError`` becomes a one-line :class:`StudyError`."""
        try:
            self.created_folder = not self.folder.exists()
            self.folder.mkdir(parents=True, exist_ok=True)
            fd = os.open(self.folder / LOCK_FILE, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as e:
            raise StudyError([f"{self.folder}: cannot create the result folder or its lock file: "
                              f"{e.strerror or e}"]) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            holder = _read(fd)
            os.close(fd)
            raise FolderLocked(self.folder, holder) from None
        old = _read(fd)
        self.stale = old or None
        me = {"pid": os.getpid(), "host": socket.gethostname(), "start": start,
              "command": " ".join(sys.argv)}
        os.ftruncate(fd, 0)
        os.lseek(fd, 0, os.SEEK_SET)
        os.write(fd, json.dumps(me).encode())
        os.fsync(fd)
        self._fd = fd
        return self

    def release(self, remove_folder: bool = False) -> None:
        """Empty the lock file and unlock; ``remove_folder``: remove a folder :meth:`acquire` created if it holds only the lock."""
        if self._fd is None:
            return
        try:
            os.ftruncate(self._fd, 0)
        finally:
            fcntl.flock(self._fd, fcntl.LOCK_UN)
            os.close(self._fd)
            self._fd = None
        if remove_folder and self.created_folder:
            rest = [p for p in self.folder.iterdir() if p.name != LOCK_FILE]
            if not rest:
                (self.folder / LOCK_FILE).unlink(missing_ok=True)
                try:
                    self.folder.rmdir()
                except OSError:
                    pass

    @property
    def held(self) -> bool:
        return self._fd is not None

    def __enter__(self) -> "FolderLock":
        return self.acquire() if not self.held else self

    def __exit__(self, *exc: Any) -> None:
        self.release()


def lock_holder(folder: str | Path) -> tuple[str, dict[str, Any]]:
    """What the lock file of ``folder`` says, without taking the lock.

    Returns ``(state, holder)`` with state ``"free"`` (no file or empty), ``"running"`` (the
    holder is a live process on this host), ``"dead"`` (its pid no longer exists on this host:
    the run was killed) or ``"elsewhere"`` (held from another host: running or killed).
    """
    path = Path(folder) / LOCK_FILE
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return "free", {}
    try:
        holder = _read(fd)
    finally:
        os.close(fd)
    if not holder:
        return "free", {}
    if holder.get("host") != socket.gethostname():
        return "elsewhere", holder
    try:
        os.kill(int(holder.get("pid", -1)), 0)
    except (ProcessLookupError, ValueError, TypeError, OverflowError):
        return "dead", holder
    except PermissionError:
        pass
    return "running", holder
