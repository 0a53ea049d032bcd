"""Executors: run units of work, yielding an :class:`~workbench.study.outcomes.Outcome` per unit.

One small interface (:class:`Executor`)::

    with executor:
        for index, outcome in executor.imap_unordered(fn, payloads, limits, chunk_size):
            ...   # outcome.rows: what fn(payloads[index]) yielded; outcome.crash: why it stopped

``fn(payload)`` yields the rows of one unit (one case, the models still to run) and catches
its own exceptions (:func:`~workbench.study.evaluate.evaluate_rows` does); executors report what
``fn`` cannot: the process running it died, ran past ``limits.seconds`` or hit ``limits.memory``
(:class:`~workbench.study.outcomes.CaseLimits`).

- :class:`SerialExecutor` -- in this process, one after another: the debugging executor
  (pdb, breakpoints), **without isolation**: a case that crashes the process ends the run (the
  rows of the cases before it are kept: the runner journals every case, and the next run of the
  folder stores them); the time limit
  interrupts Python code only (SIGALRM), there is no memory cap.
- :class:`IsolatedExecutor` -- one at a time in a child process (a
  :class:`~workbench.study.sandbox.Sandbox`) that is restarted after a crash or timeout: the
  CLI default.  Units go to the child ``chunk_size`` per message (the child streams rows and
  the end of every unit back), so a unit costs no round trip; a crash still blames its unit.
- :class:`DaskExecutor` -- Dask distributed: a ``LocalCluster`` started inside the command
  (one thread per worker process), an existing scheduler, or a cluster made by a given function
  (the batch-scheduler clusters of :mod:`workbench.study.cluster`); every worker runs its units in its
  own sandbox (:mod:`workbench.study.dask_worker`), so only a lost worker is a Dask failure.
  Cluster failures raise :class:`~workbench.study.outcomes.InfrastructureError` with one line.

Checked by ``tests/study/test_executors.py`` and ``tests/study/test_sandbox.py``.
"""

from __future__ import annotations

import logging
import signal
import threading
import time
import uuid
from abc import ABC, abstractmethod
from typing import Any, Callable, Iterator, Sequence

from .outcomes import CaseLimits, Crash, ExecutorStartError, InfrastructureError, Outcome
from .sandbox import Sandbox, prestart

__all__ = ["DASK_SETTINGS", "DaskExecutor", "Executor", "IsolatedExecutor", "SerialExecutor"]

_NO_LIMITS = CaseLimits()


class Executor(ABC):
    """What the runner needs of an executor (see the module docstring); used as ``with executor:``.

    Attributes
    ----------
    name : str
        Recorded in the run record and printed by ``run --dry-run``.
    slots : int
        Units it runs at once (chunk sizing).
    isolates_cases : bool
        ``False``: a crashing case takes the caller down (the runner journals every case).
    adapts_chunks : bool
        :meth:`imap_unordered` takes ``max_chunk`` and sizes later tasks by the measured time per unit.
    """

    name: str = "executor"
    slots: int = 1
    isolates_cases: bool = True
    adapts_chunks: bool = False

    def __enter__(self) -> "Executor":
        return self

    def __exit__(self, *exc: Any) -> None:
        return None

    @abstractmethod
    def imap_unordered(self, fn: Callable[[Any], Any], payloads: Sequence[Any], limits: CaseLimits = _NO_LIMITS,
                       chunk_size: int = 1) -> Iterator[tuple[int, Outcome]]:
        """``(index, outcome)`` for every payload, in the order they finish."""


class _CaseTimeout(BaseException):
    """Raised by SIGALRM inside an in-process case (a BaseException: models catch ``Exception``)."""


def _run_here(fn: Callable[[Any], Any], payload: Any, seconds: float | None) -> Outcome:
    rows: list[Any] = []
    timed = seconds is not None and threading.current_thread() is threading.main_thread()

    def _alarm(*_: Any) -> None:
        raise _CaseTimeout

    old = signal.signal(signal.SIGALRM, _alarm) if timed else None
    if timed:
        signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        for row in fn(payload):
            rows.append(row)
    except _CaseTimeout:
        return Outcome(rows, Crash("timeout", f"stopped after max_case_seconds = {seconds:g} s (in-process: "
                                              f"the limit interrupts Python code only)"))
    except MemoryError as e:
        return Outcome(rows, Crash("memory", f"MemoryError: {e}"))
    except Exception as e:  # noqa: BLE001 - fn should not raise; blame the unit, go on
        return Outcome(rows, Crash("crash", f"task raised {type(e).__name__}: {str(e)[:500]}"))
    finally:
        if timed:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old)
    return Outcome(rows)


class SerialExecutor(Executor):
    """In-process serial execution: the debugging executor, without isolation (module docstring)."""

    name = "serial (in-process, no isolation)"
    slots = 1
    isolates_cases = False

    def __enter__(self) -> "SerialExecutor":
        return self

    def __exit__(self, *exc: Any) -> None:
        return None

    def imap_unordered(self, fn, payloads, limits=_NO_LIMITS, chunk_size=1):
        for i, p in enumerate(payloads):
            yield i, _run_here(fn, p, limits.seconds)


class IsolatedExecutor(Executor):
    """Serial execution in one child process (a sandbox), restarted after a crash or timeout."""

    name = "serial (isolated child process)"
    slots = 1
    isolates_cases = True

    def __init__(self) -> None:
        self._box: Sandbox | None = None
        self._starting: threading.Thread | None = None

    def __enter__(self) -> "IsolatedExecutor":
        # the child (default memory cap) imports in the background while the runner expands the
        # study and opens its session; a run with another cap replaces it (imap_unordered)
        self._box = Sandbox(None)
        self._starting = threading.Thread(target=prestart, args=(self._box,), name="workbench-sandbox-start",
                                          daemon=True)
        self._starting.start()
        return self

    def _started(self) -> None:
        if self._starting is not None:
            self._starting.join()
            self._starting = None

    def __exit__(self, *exc: Any) -> None:
        self._started()
        if self._box is not None:
            self._box.__exit__(*exc)
            self._box = None

    def imap_unordered(self, fn, payloads, limits=_NO_LIMITS, chunk_size=1):
        self._started()
        want = Sandbox(limits.memory)
        if self._box is None or self._box.memory != want.memory:
            if self._box is not None:
                self._box.close()
            self._box = want
        # a chunk per message, the next one sent while the child runs this one: no round trip per unit
        yield from self._box.run_many(fn, payloads, limits.seconds, chunk=max(1, int(chunk_size)))


def check_scheduler_address(address: str, timeout: float = 5.0) -> str | None:
    """Why ``address`` is not a reachable Dask scheduler (``None`` when a TCP connection succeeds).

    Accepts ``tcp://host:port``, ``tls://host:port`` and ``host:port``; other protocols
    (``inproc://``, ``ucx://``) are passed on unchecked.
    """
    import socket

    proto, sep, rest = address.partition("://")
    if not sep:
        proto, rest = "tcp", address
    if proto not in ("tcp", "tls"):
        return None if proto in ("inproc", "ucx", "ws", "wss") else f"unknown protocol {proto!r} (use tcp://host:port)"
    host, _, port = rest.rstrip("/").rpartition(":")
    host = host.strip("[]")
    if not host or not port.isdigit() or not 0 < int(port) < 65536:
        return "not an address of the form tcp://host:port"
    try:
        with socket.create_connection((host, int(port)), timeout=timeout):
            return None
    except socket.gaierror as e:
        return f"unknown host {host!r} ({e.strerror or e})"
    except OSError as e:
        return f"nothing answers at {host}:{port} ({e.strerror or e}); is the scheduler running?"


#: Dask settings of :class:`DaskExecutor` (a ``LocalCluster`` it starts passes them to its workers).
#: No queueing beyond the slots and no work stealing (the executor sizes and balances the chunks);
#: the diagnostics a dashboard would show are off or slowed (there is no dashboard): the workers'
#: stack profiler (a sample every 10 ms), the event-loop health tick (20 ms -> 0.5 s) and the system
#: monitor (0.5 -> 5 s).  The CPU this saves per case: ``benchmarks/README.md`` ("Dask settings"
#: row; ``benchmarks/bench_runner.py`` uses the same settings).
DASK_SETTINGS = {
    "distributed.scheduler.worker-saturation": 1.0,
    "distributed.scheduler.allowed-failures": 1,
    "distributed.scheduler.work-stealing": False,
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "500ms",
    "distributed.admin.system-monitor.interval": "5s",
}


class DaskExecutor(Executor):
    """Dask distributed execution.

    Parameters
    ----------
    n_workers : int, optional
        Worker processes of the ``LocalCluster`` started on entry (default: CPU count).
    scheduler : str, optional
        Address of an existing scheduler (``tcp://host:8786``) instead of a local cluster.  Its
        ``allowed-failures`` is read from the scheduler (for the lost-worker message).
    allowed_failures : int
        Local cluster: how many worker losses a task may cause before it is given up
        (``distributed.scheduler.allowed-failures``; 1 = one retry on another worker).
    lost_timeout : float
        Give up (:class:`InfrastructureError`) when the cluster has had no worker for this long [s].
    connect_timeout : float
        Seconds to wait for the scheduler on entry.
    cluster : callable, optional
        ``cluster() -> distributed cluster``, called on entry inside the Dask settings above
        (instead of a ``LocalCluster``); the cluster is closed on exit.
    """

    isolates_cases = True

    def __init__(self, n_workers: int | None = None, scheduler: str | None = None,
                 allowed_failures: int = 1, lost_timeout: float = 120.0, connect_timeout: float = 10.0,
                 cluster: Callable[[], Any] | None = None) -> None:
        if n_workers is not None and n_workers < 1:
            raise ValueError(f"n_workers must be >= 1, got {n_workers}")
        self.n_workers, self.scheduler = n_workers, scheduler
        self.allowed_failures = int(allowed_failures)
        self.lost_timeout, self.connect_timeout = float(lost_timeout), float(connect_timeout)
        self.make_cluster = cluster
        self._cluster = self._client = self._cfg = None
        self.name = f"dask ({scheduler})" if scheduler else f"dask LocalCluster ({n_workers or 'auto'} workers)"

    def __enter__(self) -> "DaskExecutor":
        try:
            self._connect()
        except BaseException as e:
            self.__exit__(None, None, None)
            if isinstance(e, KeyboardInterrupt):
                raise
            where = self.scheduler or ("a local cluster" if self.make_cluster is None else self.name)
            first = str(e).splitlines()[0] if str(e) else ""
            raise ExecutorStartError(f"cannot start Dask on {where}: {type(e).__name__}: {first}".rstrip(": ")) \
                from None
        return self

    def _connect(self) -> None:
        import os

        import dask
        from distributed import Client, LocalCluster

        from .dask_worker import SandboxPlugin

        self._cfg = dask.config.set({**DASK_SETTINGS, "distributed.scheduler.allowed-failures": self.allowed_failures})
        self._cfg.__enter__()
        if self.scheduler:
            self._client = Client(self.scheduler, timeout=self.connect_timeout)
            try:
                self.allowed_failures = int(self._client.run_on_scheduler(_allowed_failures))
            except Exception:  # noqa: BLE001 - an old scheduler: keep the local setting
                pass
        elif self.make_cluster is not None:
            self._cluster = self.make_cluster()
            self._client = Client(self._cluster, timeout=self.connect_timeout)
        else:
            n = self.n_workers or os.cpu_count() or 1
            # no dashboard; the scheduler's HTTP routes on a free port (the default 8787 may be taken)
            self._cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                         dashboard_address=":0", scheduler_kwargs={"dashboard": False},
                                         silence_logs=logging.CRITICAL)
            self._client = Client(self._cluster, timeout=self.connect_timeout)
        self._client.register_plugin(SandboxPlugin(), name="workbench-sandbox")

    def __exit__(self, *exc: Any) -> None:
        for obj in (self._client, self._cluster):
            if obj is not None:
                try:
                    obj.close()
                except Exception:  # noqa: BLE001 - closing a broken cluster: nothing left to save
                    pass
        self._client = self._cluster = None
        if self._cfg is not None:
            self._cfg.__exit__(None, None, None)
            self._cfg = None

    @property
    def slots(self) -> int:
        """Worker threads of the cluster (for chunk sizing)."""
        if self._client is None:
            return self.n_workers or 1
        try:
            return max(1, sum(self._client.nthreads().values()))
        except Exception:  # noqa: BLE001
            return 1

    def _lost(self) -> Crash:
        n = self.allowed_failures
        return Crash("lost", f"the Dask worker running this case was lost {n + 1} time(s) "
                             f"(the scheduler's allowed-failures = {n}); --resume retries it")

    #: the runner may pass ``max_chunk`` (adaptive chunk sizes)
    adapts_chunks = True
    #: adaptive chunks aim at this many seconds of work per task (Dask's 2-3 ms per task is then < 1 %)
    task_seconds = 0.5

    def _chunk(self, size: int, cap: int, per_unit: float | None, left: int, slots: int) -> int:
        """Units of the next task: ``size`` until a chunk was timed, then ``task_seconds`` of work, at most
        ``cap`` and a quarter of the remaining units per slot (the tail stays balanced)."""
        if per_unit is None or cap <= size:
            return size
        want = int(self.task_seconds / max(per_unit, 1e-6))
        return max(1, min(cap, want, -(-left // (4 * slots))))

    def imap_unordered(self, fn, payloads, limits=_NO_LIMITS, chunk_size=1, max_chunk=None):
        """Yield ``(index, Outcome)`` per payload, submitted as tasks of several units.

        Fixed ``chunk_size`` units per task, or with ``max_chunk`` adaptive sizes: ``chunk_size``
        until the first tasks report their time per unit, then about :attr:`task_seconds` of
        work per task (at most ``max_chunk``); about two tasks per worker slot are in flight
        (:class:`_Tasks`).  A task whose worker was lost (Dask's ``KilledWorker``) is resubmitted
        one unit per task, so only a unit that loses workers by itself is stored ``lost``.
        """
        size = max(1, int(chunk_size))
        tasks = _Tasks(self, fn, payloads, limits, size, size if max_chunk is None else max(size, int(max_chunk)))
        lost_since = None
        slots, slots_at = self.slots, time.monotonic()  # asked again every 5 s (workers come and go)
        try:
            while True:
                if time.monotonic() - slots_at > 5.0:
                    slots, slots_at = self.slots, time.monotonic()
                tasks.fill(slots)
                if not tasks.futures:
                    return
                done, lost_since = self._wait(tasks.pending(), lost_since)
                for f in done:
                    yield from tasks.collect(f)
        finally:
            tasks.cancel()

    def _wait(self, remaining, lost_since):
        """Futures done within 5 s; raises :class:`InfrastructureError` after ``lost_timeout`` without workers."""
        from distributed import wait

        try:
            done, _ = wait(list(remaining), timeout=min(5.0, max(0.5, self.lost_timeout / 2)),
                           return_when="FIRST_COMPLETED")
        except TimeoutError:
            done = set()
        except Exception as e:  # noqa: BLE001 - the scheduler went away
            raise InfrastructureError(f"lost the Dask scheduler: {type(e).__name__}: {e}") from None
        if done:
            return done, None
        try:
            workers = self._client.scheduler_info().get("workers")
        except Exception as e:  # noqa: BLE001
            raise InfrastructureError(f"lost the Dask scheduler: {type(e).__name__}: {e}") from None
        if workers:
            return set(), None
        lost_since = lost_since or time.monotonic()
        if time.monotonic() - lost_since > self.lost_timeout:
            raise InfrastructureError(f"the Dask cluster has had no workers for {self.lost_timeout:.0f} s")
        return set(), lost_since


class _Tasks:
    """The Dask tasks of one :meth:`DaskExecutor.imap_unordered` call: what to submit next, what came back.

    ``nxt`` is the next payload to submit; ``singles`` the units of lost chunks, resubmitted one
    per task; ``seconds`` / ``units`` the measured work (adaptive chunk sizes).
    """

    def __init__(self, executor: DaskExecutor, fn: Callable[[Any], Any], payloads: Sequence[Any],
                 limits: CaseLimits, size: int, cap: int) -> None:
        self.executor, self.fn, self.payloads, self.limits = executor, fn, payloads, limits
        self.size, self.cap = size, cap
        self.tag, self.count = uuid.uuid4().hex[:12], 0
        self.nxt, self.singles = 0, []
        self.futures: dict[str, tuple[Any, list[int]]] = {}
        self.seconds = self.units = 0.0

    def pending(self) -> set:
        return {f for f, _ in self.futures.values()}

    def submit(self, idx: list[int]) -> None:
        """One task of the units ``idx`` (:func:`~workbench.study.dask_worker.run_chunk`)."""
        from .dask_worker import run_chunk

        try:
            f = self.executor._client.submit(run_chunk, self.fn, [self.payloads[i] for i in idx], self.limits,
                                             pure=False, key=f"cases-{self.tag}-{self.count}")
        except Exception as e:  # noqa: BLE001
            raise InfrastructureError(f"cannot submit to the Dask scheduler: {type(e).__name__}: {e}") from None
        self.count += 1
        self.futures[f.key] = (f, idx)

    def fill(self, slots: int) -> None:
        """Submit until about two tasks per slot are in flight (lost units first, one per task)."""
        while len(self.futures) < 2 * slots and (self.singles or self.nxt < len(self.payloads)):
            if self.singles:
                self.submit([self.singles.pop(0)])
                continue
            per_unit = self.seconds / self.units if self.units else None
            k = self.executor._chunk(self.size, self.cap, per_unit, len(self.payloads) - self.nxt, slots)
            self.submit(list(range(self.nxt, min(len(self.payloads), self.nxt + k))))
            self.nxt += k

    def collect(self, f) -> list[tuple[int, Outcome]]:
        """The ``(index, Outcome)`` of the finished task ``f`` (none when its lost chunk is resubmitted)."""
        from distributed.scheduler import KilledWorker

        _, idx = self.futures.pop(f.key)
        try:
            outs, took = f.result()
        except KilledWorker:
            f.release()
            if len(idx) > 1:
                self.singles.extend(idx)  # blame the right unit: one per task
                return []
            return [(idx[0], Outcome([], self.executor._lost()))]
        except Exception as e:  # noqa: BLE001 - the sandbox catches every case: systemic
            raise InfrastructureError(
                f"the Dask workers cannot run the cases: {type(e).__name__}: {str(e)[:300]} (is the "
                f"same workbench installed in the workers' environment?)") from None
        f.release()
        if took:
            self.seconds, self.units = self.seconds + took, self.units + len(idx)
        return list(zip(idx, outs))

    def cancel(self) -> None:
        """Cancel what is still in flight (the caller stopped early or failed)."""
        for f, _ in self.futures.values():
            try:
                f.cancel()
            except Exception:  # noqa: BLE001
                pass


def _allowed_failures(dask_scheduler=None) -> int:
    return dask_scheduler.allowed_failures
