"""The Dask worker side of :class:`~workbench.study.executors.DaskExecutor`: a sandbox per worker thread.

:class:`SandboxPlugin` is registered on every worker of the cluster (now and later ones) when
the executor is entered; :func:`run_units` is the task the executor submits: it runs a chunk of
units one by one in the worker's :class:`~workbench.study.sandbox.Sandbox` (a child process of
the worker), so a case that crashes, hangs or eats memory is stopped there and comes back as an
ordinary :class:`~workbench.study.outcomes.Outcome` -- the Dask worker itself survives, and a
lost worker (``KilledWorker``) means the machine or the cluster failed.  Imported only on
workers and by the executor (it imports ``distributed``).

Checked by ``tests/study/test_executors.py`` (the Dask cases).
"""

from __future__ import annotations

import threading
from typing import Any, Callable, Sequence

from distributed import get_worker
from distributed.diagnostics.plugin import WorkerPlugin

from .outcomes import CaseLimits, Outcome
from .sandbox import Sandbox, prestart

__all__ = ["PLUGIN_NAME", "SandboxPlugin", "run_chunk", "run_units"]

PLUGIN_NAME = "workbench-sandbox"


class SandboxPlugin(WorkerPlugin):
    """One :class:`Sandbox` per worker thread, closed when the worker closes.

    On setup (when the executor registers the plugin) every worker starts one sandbox per
    thread in the background, with the default memory cap, so the children import while the
    runner opens its session instead of when the first task arrives.  A task whose limits ask
    for another cap replaces it.
    """

    name = PLUGIN_NAME
    #: a later run on the same cluster keeps the workers' running sandboxes (Dask skips registering
    #: a plugin of this name again): a run against a persistent scheduler pays no child start-up
    idempotent = True

    def setup(self, worker: Any) -> None:
        # created on the worker (a lock cannot travel to it)
        self._boxes: dict[int, Sandbox] = {}
        self._lock = threading.Lock()
        self._spares: list[tuple[threading.Thread, Sandbox]] = []
        for _ in range(max(1, int(getattr(worker.state, "nthreads", 1) or 1))):
            box = Sandbox(None)
            t = threading.Thread(target=prestart, args=(box,), name="workbench-sandbox-start", daemon=True)
            t.start()
            self._spares.append((t, box))

    def teardown(self, worker: Any) -> None:
        with self._lock:
            boxes, self._boxes = list(self._boxes.values()), {}
            spares, self._spares = self._spares, []
        for t, b in spares:
            t.join(timeout=30)
            boxes.append(b)
        for b in boxes:
            b.close()

    def sandbox(self, memory: float | None) -> Sandbox:
        """The calling thread's sandbox (with cap ``memory``; replaced when the cap changes)."""
        key = threading.get_ident()
        want = Sandbox(memory)
        with self._lock:
            box = self._boxes.get(key)
            spare = self._spares.pop() if box is None and self._spares else None
        if spare is not None:  # started in the background: take it once its start is over
            spare[0].join()
            box = spare[1]
        if box is None or box.memory != want.memory:
            if box is not None:
                box.close()
            box = want
        with self._lock:
            self._boxes[key] = box
        return box


def run_units(fn: Callable[[Any], Any], payloads: Sequence[Any], limits: CaseLimits) -> list[Outcome]:
    """The Dask task: every unit of a chunk in this worker thread's sandbox, one outcome each."""
    plugin = get_worker().plugins[PLUGIN_NAME]
    box = plugin.sandbox(limits.memory)
    return [out for _, out in box.run_many(fn, payloads, limits.seconds)]  # one message per chunk


def run_chunk(fn: Callable[[Any], Any], payloads: Sequence[Any], limits: CaseLimits) -> tuple[list[Outcome], float]:
    """:func:`run_units` and the seconds the chunk took in the worker (the executor sizes later chunks by it)."""
    import time

    t0 = time.perf_counter()
    outs = run_units(fn, payloads, limits)
    return outs, time.perf_counter() - t0
