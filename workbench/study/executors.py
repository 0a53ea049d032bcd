"""Executors: run a task function over payloads, yielding results as they finish.

One small interface (:class:`Executor`)::

    with executor:
        for index, outcome in executor.imap_unordered(fn, payloads):
            ...   # outcome is fn(payloads[index]) or a WorkerCrash

``fn`` must catch its own exceptions (:func:`~workbench.study.evaluate.evaluate_payload`
does); executors only report what ``fn`` cannot: a worker process that died (segfault,
``os._exit``, out of memory) as a :class:`WorkerCrash` blamed on the payload it was running.

- :class:`SerialExecutor` -- in-process, one after another; debuggable (pdb, breakpoints),
  used by unit tests; a crash kills the caller too.
- :class:`IsolatedExecutor` -- one at a time in a single spawned child process that is
  restarted after a crash (crash-safe serial; the CLI default).
- :class:`DaskExecutor` -- Dask distributed: a ``LocalCluster`` started inside the command
  (one thread per worker process, ``worker-saturation`` 1.0, ``allowed-failures`` small so a
  crashing task is not retried for ever), an existing scheduler address, or a cluster made by a
  given function (the batch-scheduler clusters of :mod:`workbench.study.cluster`).
"""

from __future__ import annotations

import logging
import multiprocessing as mp
import signal
from dataclasses import dataclass
from typing import Any, Callable, Iterator, Protocol, Sequence

__all__ = ["Executor", "WorkerCrash", "SerialExecutor", "IsolatedExecutor", "DaskExecutor"]


@dataclass(frozen=True)
class WorkerCrash:
    """The worker running a payload died; ``reason`` says how."""

    reason: str


class Executor(Protocol):
    slots: int  # tasks it runs at once (batch sizing)

    def __enter__(self) -> "Executor": ...
    def __exit__(self, *exc: Any) -> None: ...
    def imap_unordered(self, fn: Callable[[Any], Any], payloads: Sequence[Any]) -> Iterator[tuple[int, Any]]: ...


class SerialExecutor:
    """In-process serial execution (no isolation: for debugging and unit tests)."""

    name = "serial (in-process)"
    slots = 1

    def __enter__(self) -> "SerialExecutor":
        return self

    def __exit__(self, *exc: Any) -> None:
        return None

    def imap_unordered(self, fn, payloads):
        for i, p in enumerate(payloads):
            yield i, fn(p)


def _describe_exit(code: int | None) -> str:
    if code is None:
        return "worker process died (exit code unknown)"
    if code < 0:
        try:
            return f"worker process killed by signal {signal.Signals(-code).name}"
        except ValueError:
            return f"worker process killed by signal {-code}"
    return f"worker process exited with status {code}"


def _child_loop(conn, fn) -> None:
    while True:
        try:
            msg = conn.recv()
        except EOFError:
            return
        if msg is None:
            return
        i, payload = msg
        try:
            out = fn(payload)
        except BaseException as e:  # noqa: BLE001 - fn should not raise; report it, keep serving
            out = WorkerCrash(f"task raised {type(e).__name__}: {e}")
        conn.send((i, out))


class IsolatedExecutor:
    """Serial execution in one spawned child process, restarted after a crash."""

    name = "serial (isolated child process)"
    slots = 1

    def __init__(self) -> None:
        self._ctx = mp.get_context("spawn")
        self._proc = None
        self._conn = None
        self._fn = None

    def __enter__(self) -> "IsolatedExecutor":
        return self

    def _start(self, fn) -> None:
        parent, child = self._ctx.Pipe()
        self._proc = self._ctx.Process(target=_child_loop, args=(child, fn), daemon=True)
        self._proc.start()
        child.close()
        self._conn, self._fn = parent, fn

    def _stop(self) -> None:
        if self._proc is None:
            return
        try:
            self._conn.send(None)
        except (BrokenPipeError, OSError):
            pass
        self._proc.join(timeout=5)
        if self._proc.is_alive():
            self._proc.kill()
            self._proc.join()
        self._conn.close()
        self._proc = self._conn = None

    def __exit__(self, *exc: Any) -> None:
        self._stop()

    def imap_unordered(self, fn, payloads):
        for i, p in enumerate(payloads):
            if self._proc is None or self._fn is not fn:
                self._stop()
                self._start(fn)
            try:
                self._conn.send((i, p))
                j, out = self._conn.recv()
            except (EOFError, ConnectionResetError, BrokenPipeError):
                self._proc.join(timeout=10)
                code = self._proc.exitcode
                self._conn.close()
                self._proc = self._conn = None
                yield i, WorkerCrash(_describe_exit(code))
                continue
            yield j, out


class DaskExecutor:
    """Dask distributed execution.

    Parameters
    ----------
    n_workers : int, optional
        Worker processes of the ``LocalCluster`` started on entry (default: CPU count).
    scheduler : str, optional
        Address of an existing scheduler (``tcp://host:8786``) instead of a local cluster.
        Its ``worker-saturation`` / ``allowed-failures`` are the cluster's own settings.
    allowed_failures : int
        How many worker deaths a task may cause before it is marked failed
        (``distributed.scheduler.allowed-failures``; 1 = one retry on another worker).
    lost_timeout : float
        Give up (``RuntimeError``) when the cluster has had no worker for this long [s].
    cluster : callable, optional
        ``cluster() -> distributed cluster``, called on entry inside the Dask settings above
        (instead of a ``LocalCluster``); the cluster is closed on exit.
    """

    def __init__(self, n_workers: int | None = None, scheduler: str | None = None,
                 allowed_failures: int = 1, lost_timeout: float = 120.0,
                 cluster: Callable[[], Any] | None = None) -> None:
        self.lost_timeout = float(lost_timeout)
        if n_workers is not None and n_workers < 1:
            raise ValueError(f"n_workers must be >= 1, got {n_workers}")
        self.n_workers = n_workers
        self.scheduler = scheduler
        self.allowed_failures = int(allowed_failures)
        self.make_cluster = cluster
        self._cluster = None
        self._client = None
        self._cfg = None
        self.name = f"dask ({scheduler})" if scheduler else f"dask LocalCluster ({n_workers or 'auto'} workers)"

    def __enter__(self) -> "DaskExecutor":
        import os

        import dask
        from distributed import Client, LocalCluster

        self._cfg = dask.config.set({
            "distributed.scheduler.worker-saturation": 1.0,
            "distributed.scheduler.allowed-failures": self.allowed_failures,
            "distributed.scheduler.work-stealing": False,
            "distributed.worker.daemon": False,
        })
        self._cfg.__enter__()
        try:
            if self.scheduler:
                self._client = Client(self.scheduler)
            elif self.make_cluster is not None:
                self._cluster = self.make_cluster()
                self._client = Client(self._cluster)
            else:
                n = self.n_workers or os.cpu_count() or 1
                self._cluster = LocalCluster(
                    n_workers=n, threads_per_worker=1, processes=True,
                    dashboard_address=None, silence_logs=logging.CRITICAL,
                )
                self._client = Client(self._cluster)
        except BaseException:
            self.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc: Any) -> None:
        if self._client is not None:
            self._client.close()
            self._client = None
        if self._cluster is not None:
            self._cluster.close()
            self._cluster = None
        if self._cfg is not None:
            self._cfg.__exit__(None, None, None)
            self._cfg = None

    @property
    def slots(self) -> int:
        """Worker threads of the cluster (for batch sizing)."""
        if self._client is None:
            return self.n_workers or 1
        return max(1, sum(self._client.nthreads().values()))

    def imap_unordered(self, fn, payloads):
        import time

        from distributed import wait
        from distributed.scheduler import KilledWorker

        import uuid

        tag = uuid.uuid4().hex[:12]
        index = {}
        futures = []
        for i, p in enumerate(payloads):
            f = self._client.submit(fn, p, pure=False, key=f"cases-{tag}-{i}")
            index[f.key] = i
            futures.append(f)
        remaining = set(futures)
        lost_since = None
        try:
            while remaining:
                try:
                    done, _ = wait(list(remaining), timeout=5.0, return_when="FIRST_COMPLETED")
                except TimeoutError:
                    done = set()
                if not done:
                    # a cluster without workers would wait for ever: give up after a while
                    if not self._client.scheduler_info().get("workers"):
                        lost_since = lost_since or time.monotonic()
                        if time.monotonic() - lost_since > self.lost_timeout:
                            raise RuntimeError(
                                f"the Dask cluster has had no workers for {self.lost_timeout:.0f} s; "
                                f"finished cases are stored (continue with --resume)")
                    else:
                        lost_since = None
                    continue
                for f in done:
                    remaining.discard(f)
                    i = index[f.key]
                    try:
                        out = f.result()
                    except KilledWorker:
                        out = WorkerCrash(f"worker process died while running this case "
                                          f"({self.allowed_failures + 1} worker(s) lost)")
                    except Exception as e:  # noqa: BLE001
                        out = WorkerCrash(f"task failed: {type(e).__name__}: {e}")
                    f.release()
                    yield i, out
        finally:
            for f in futures:
                f.cancel()
