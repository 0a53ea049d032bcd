"""Run units of work in a child process with a per-case time limit and a memory cap.

The isolation of every process executor (the default serial one and each Dask worker):
a :class:`Sandbox` keeps one child Python process (``subprocess``, so it also works inside
daemonic Dask workers) and sends it a chunk of units in one message: ``(fn, payloads)`` pickled
with cloudpickle (functions of a ``__main__`` script travel by value; ``fn`` once per chunk).
The child runs the units one after another, streams every item (a result row) back as soon as
it exists, and ends each unit with a message of its own, so a unit that crashes after its first
models keeps their rows and the per-unit cost is two small messages, not a round trip
(:meth:`Sandbox.run_many`; :meth:`Sandbox.run` is a chunk of one).  The parent enforces the time limit
(:class:`~workbench.study.outcomes.CaseLimits`): after ``seconds`` it kills the child (SIGKILL:
a C++ solver loop cannot be interrupted more gently) and reports a ``timeout``; the child caps
its own address space (``RLIMIT_AS``) so a runaway case fails with ``MemoryError`` (``memory``)
instead of taking the machine down.  A child that dies is restarted for the next unit; the dead
unit gets a :class:`~workbench.study.outcomes.Crash` from its exit status
(:func:`~workbench.study.outcomes.crash_from_exit`).

The time limit counts from the moment the unit is sent to a child that is up, or, inside a
chunk, from the moment the previous unit's end is read (a new child's start-up is not charged to
the case); a unit that kills the child or times out is blamed alone and the rest of its chunk
goes to a fresh child.  The child ignores SIGINT and SIGTERM (the parent decides when to stop it, so an interrupted run
records no spurious crash) and exits by itself within a second when its parent disappears
(``kill -9`` of the run).

Checked by ``tests/study/test_sandbox.py`` (timeouts, memory cap, crashes, streaming).
"""

from __future__ import annotations

import os
import pickle
import signal
import subprocess
import sys
import threading
import time
from multiprocessing.connection import Connection
from typing import Any, Callable, Generator, Iterator, Sequence

from .outcomes import Crash, Outcome, crash_from_exit

__all__ = ["Sandbox", "child_main", "default_memory_cap", "prestart"]

_STARTUP_SECONDS = 300.0
#: largest message sent to a busy child (a Linux pipe holds 64 KiB; the message must fit whole)
_AHEAD_BYTES = 32 * 1024


class _StartFailed(RuntimeError):
    """The child process could not be started (reported as a crash of the unit)."""


def default_memory_cap() -> float | None:
    """3/4 of this machine's physical memory [bytes] (``None`` where the platform does not say)."""
    try:
        return 0.75 * os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def _child_env() -> dict[str, str]:
    """This process's environment with its ``sys.path`` as ``PYTHONPATH`` (the child imports what we import)."""
    env = dict(os.environ)
    paths = [p or os.getcwd() for p in sys.path]
    env["PYTHONPATH"] = os.pathsep.join(dict.fromkeys(paths))
    return env


class Sandbox:
    """One child process that runs units; see the module docstring.

    Parameters
    ----------
    memory : float, optional
        Address-space cap of the child [bytes]; default :func:`default_memory_cap`; ``0``: none.
    """

    def __init__(self, memory: float | None = None) -> None:
        self.memory = default_memory_cap() if memory is None else (memory or None)
        self._proc: subprocess.Popen | None = None
        self._tx: Connection | None = None
        self._rx: Connection | None = None

    # -- the child process -------------------------------------------------------------------
    def _start(self) -> None:
        r1, w1 = os.pipe()
        r2, w2 = os.pipe()
        mem = int(self.memory) if self.memory else 0
        code = f"from workbench.study.sandbox import child_main; child_main({r1}, {w2}, {mem}, {os.getpid()})"
        try:
            self._proc = subprocess.Popen([sys.executable, "-c", code], pass_fds=(r1, w2), env=_child_env(),
                                          stdin=subprocess.DEVNULL)
        finally:
            os.close(r1)
            os.close(w2)
        self._tx, self._rx = Connection(w1, readable=False), Connection(r2, writable=False)
        # the case clock starts once the child is up (imports can take seconds on a busy machine)
        if not self._rx.poll(_STARTUP_SECONDS):
            self._discard()
            raise _StartFailed(f"the worker process did not start within {_STARTUP_SECONDS:.0f} s")
        try:
            self._rx.recv_bytes()  # ("ready",)
        except (EOFError, OSError):
            code = self._discard(kill=False)
            raise _StartFailed(f"the worker process died while starting ({crash_from_exit(code).reason})") from None

    def _discard(self, kill: bool = True) -> int | None:
        """Kill (``kill``) and reap the child; its exit status."""
        code = None
        if self._proc is not None:
            if kill and self._proc.poll() is None:
                self._proc.kill()
            try:
                code = self._proc.wait(timeout=30)
            except subprocess.TimeoutExpired:  # pragma: no cover - a zombie that will not die
                code = None
        for c in (self._tx, self._rx):
            if c is not None:
                c.close()
        self._proc = self._tx = self._rx = None
        return code

    def close(self) -> None:
        """Stop the child (EOF first, so it exits by itself; killed if it does not within 5 s)."""
        if self._proc is None:
            return
        try:
            self._tx.close()
            self._tx = None
            self._proc.wait(timeout=5)
        except (OSError, subprocess.TimeoutExpired):
            pass
        self._discard()

    def __enter__(self) -> "Sandbox":
        return self

    def __exit__(self, *exc: Any) -> None:
        if exc and exc[0] is not None:
            self._discard()  # interrupted: do not wait for the case to finish
        else:
            self.close()

    # -- running units -----------------------------------------------------------------------
    def run(self, fn: Callable[[Any], Any], payload: Any, seconds: float | None = None) -> Outcome:
        """Run ``fn(payload)`` in the child; the rows it yielded and the crash that stopped it, if any."""
        return [out for _, out in self.run_many(fn, [payload], seconds)][0]

    def run_many(self, fn: Callable[[Any], Any], payloads: Sequence[Any],
                 seconds: float | None = None, chunk: int | None = None) -> Iterator[tuple[int, Outcome]]:
        """Run ``fn(p)`` for every ``p`` of ``payloads`` in the child, one after another; yield ``(index, Outcome)``.

        The units go to the child ``chunk`` per message (default: all in one; ``fn`` is pickled
        once per message), the child streams every row back and ends each unit with its own
        message, so the per-unit cost is one row message and one end message.  The next message
        is sent as soon as the child has begun the one before (its first unit answered), so the
        child finds it waiting when it finishes and never idles on the parent: on a 2-core
        machine the parent's storing of rows then overlaps the child's cases (messages larger
        than :data:`_AHEAD_BYTES` wait until the child is idle: a pipe write must not block while
        the child streams rows nobody reads).  ``seconds`` limits each unit: its clock starts when
        the end of the unit before it has been read (the first: when the child is up).  A unit that
        kills the child or runs out of time is blamed alone; the units after it (of its message
        and of one already sent) go to a fresh child.  Outcomes come in payload order, one per
        payload.  Leaving the iteration early kills the child (it would still be running them).
        Checked by ``tests/study/test_chunks.py``.
        """
        import cloudpickle

        def message(idx: list[int]) -> bytes:
            return cloudpickle.dumps((fn, [payloads[i] for i in idx]))

        size = max(1, len(payloads) if chunk is None else int(chunk))
        todo = list(range(len(payloads)))
        while todo:
            done = [0]  # units of ``todo`` answered (read by the cleanup when the caller stops early)
            finished = False
            try:
                stop = yield from self._one_child(todo, size, message, seconds, done)
                finished = not stop
            finally:
                if not finished and self._proc is not None and done[0] < len(todo):
                    self._discard()  # the caller stopped listening: the child is mid-chunk
            if stop:
                return
            todo = todo[done[0]:]

    def _one_child(self, todo: list[int], size: int, message: Callable[[list[int]], bytes], seconds: float | None,
                   done: list[int]) -> Generator[tuple[int, Outcome], None, bool]:
        """The units ``todo`` in messages of ``size`` to one child, until it dies (:meth:`run_many`).

        Returns ``True`` when no child could be started (every unit left was yielded failed).
        """
        messages = [todo[k:k + size] for k in range(0, len(todo), size)]
        sent = 0
        for m, idx in enumerate(messages):
            if m == sent:  # the child is idle: the first message, or one too large to send ahead
                crash = self._send(message(idx))
                if crash is not None:
                    for i in todo[done[0]:]:
                        yield i, Outcome([], crash)
                    return True
                sent += 1
            ahead = None
            if sent == m + 1 < len(messages):
                ahead = messages[sent]
            dead, n_ahead = yield from self._units(idx, seconds, done, ahead and (lambda a=ahead: message(a)))
            sent += n_ahead
            if dead:
                break
        return False

    def _units(self, idx: list[int], seconds: float | None, done: list[int],
               ahead: Callable[[], bytes] | None) -> Generator[tuple[int, Outcome], None, tuple[bool, int]]:
        """The outcomes of the message ``idx`` the child runs; returns ``(child died, messages sent ahead)``.

        ``ahead`` builds the next message, sent once the child has answered the first unit.
        """
        n_ahead = 0
        for k, i in enumerate(idx):
            out, state = self._collect(seconds)
            if state == "abort":  # the child could not read this message: its units fail alike
                for j in idx[k:]:
                    done[0] += 1
                    yield j, out
                return False, n_ahead
            done[0] += 1
            yield i, out
            if state == "dead":
                return True, n_ahead
            if k == 0 and ahead is not None:
                n_ahead = self._send_ahead(ahead())
        return False, n_ahead

    def _send_ahead(self, data: bytes) -> int:
        """Queue the next message for a child that is busy with the one before; 1 if sent, 0 if it must wait.

        The child has read the message before (it answered a unit of it), so the pipe is empty and a
        message of at most :data:`_AHEAD_BYTES` fits without blocking.  A child that died meanwhile
        is noticed by the next collect (its EOF), not here.
        """
        if len(data) > _AHEAD_BYTES:
            return 0
        try:
            self._tx.send_bytes(data)
        except (BrokenPipeError, OSError):
            pass  # the units are resent to a fresh child after the collect sees the death
        return 1

    def _send(self, data: bytes) -> Crash | None:
        """Send one chunk to a live child (started or restarted as needed); why not, if it cannot be."""
        for attempt in (0, 1):
            if self._proc is None or self._proc.poll() is not None:
                if self._proc is not None:
                    self._discard()
                try:
                    self._start()
                except _StartFailed as e:
                    return Crash("crash", str(e))
            try:
                self._tx.send_bytes(data)
                return None
            except (BrokenPipeError, OSError):  # the idle child had died: start another once
                self._discard()
        return Crash("crash", "the case's worker process could not be started")

    def _collect(self, seconds: float | None) -> tuple[Outcome, str]:
        """One unit's outcome and the child's state: ``"ok"`` (serves the rest of the chunk), ``"dead"``, ``"abort"``."""
        rows: list[Any] = []
        deadline = None if seconds is None else time.monotonic() + seconds
        rx = self._rx
        while True:
            wait = 1.0 if deadline is None else max(0.0, min(1.0, deadline - time.monotonic()))
            if rx.poll(wait):
                try:
                    msg = pickle.loads(rx.recv_bytes())
                except (EOFError, OSError):
                    return Outcome(rows, crash_from_exit(self._discard(kill=False))), "dead"
                if msg[0] == "row":
                    rows.append(msg[1])
                    continue
                if msg[0] == "done":
                    return Outcome(rows), "ok"
                # ("crash", kind, reason): the unit failed, the child goes on; ("abort", ...): the chunk did
                return Outcome(rows, Crash(msg[1], msg[2])), "ok" if msg[0] == "crash" else "abort"
            if deadline is not None and time.monotonic() >= deadline:
                self._discard()
                return Outcome(rows, Crash("timeout", f"stopped after max_case_seconds = {seconds:g} s "
                                                      f"(the case was still running)")), "dead"


def prestart(box: Sandbox) -> None:
    """Start ``box``'s child ahead of its first unit (run in a background thread while the caller
    prepares); a failure is left for the first unit, which starts the child again and reports it."""
    try:
        box._start()
    except Exception:  # noqa: BLE001
        box._discard()


# ------------------------------------------------------------------------------------------
# the child side
# ------------------------------------------------------------------------------------------
def _watch_parent(parent: int) -> None:
    while True:
        time.sleep(1.0)
        if os.getppid() != parent:
            os._exit(70)


def _cap_memory(memory: int) -> None:
    if not memory:
        return
    import resource

    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    cap = memory if hard == resource.RLIM_INFINITY else min(memory, hard)
    resource.setrlimit(resource.RLIMIT_AS, (cap, hard))


def _unit_in_child(tx: Connection, fn: Callable[[Any], Any], payload: Any, memory: int) -> None:
    """Run one unit in the child: stream its rows, end with ``("done",)`` or ``("crash", kind, reason)``."""
    try:
        for item in fn(payload):
            tx.send_bytes(pickle.dumps(("row", item), protocol=pickle.HIGHEST_PROTOCOL))
        msg = ("done",)
    except MemoryError as e:
        cap = f"{memory / 2**30:.3g} GiB" if memory else "none"
        msg = ("crash", "memory", f"MemoryError: the case exceeded the memory cap (max_case_memory: {cap}) {e}"
               .rstrip())
    except BaseException as e:  # noqa: BLE001 - fn should not raise; report it, keep serving
        msg = ("crash", "crash", f"task raised {type(e).__name__}: {str(e)[:500]}")
    tx.send_bytes(pickle.dumps(msg))


def child_main(rfd: int, wfd: int, memory: int, parent: int) -> None:
    """The child's loop: receive ``(fn, payloads)``; per payload stream ``("row", item)`` and end with ``("done",)``
    or ``("crash", kind, reason)``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    _cap_memory(memory)
    rx, tx = Connection(rfd, writable=False), Connection(wfd, readable=False)
    tx.send_bytes(pickle.dumps(("ready",)))
    while True:
        try:
            data = rx.recv_bytes()
        except (EOFError, OSError):
            return
        try:
            fn, payloads = pickle.loads(data)
        except BaseException as e:  # noqa: BLE001 - e.g. a module the child cannot import: the whole chunk fails
            tx.send_bytes(pickle.dumps(("abort", "crash", f"task raised {type(e).__name__}: {str(e)[:500]}")))
            continue
        for payload in payloads:
            _unit_in_child(tx, fn, payload, memory)
