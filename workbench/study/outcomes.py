"""What running one unit of work can end in, why a row failed, and the per-case limits.

A *unit* is one case and the models still to compute for it.  An executor returns an
:class:`Outcome` per unit: the rows it produced (one per model, as they finished) and, when the
process running it died or was stopped, a :class:`Crash`.  Every failed row records its
``failure`` kind (a column of the result table):

========== ===================================================================== ==============
kind       meaning                                                               ``--resume``
========== ===================================================================== ==============
model      the model raised, did not converge, or returned non-finite numbers   ``--retry-failed``
crash      the process running the case died by itself (SIGSEGV, abort, exit)   ``--retry-failed``
timeout    the case ran longer than ``[solver] max_case_seconds`` and was stopped retried
memory     the case hit the memory cap (``[solver] max_case_memory``)             retried
killed     the process was killed from outside (SIGKILL, SIGTERM: OOM killer,   retried
           a scheduler, a person)
lost       the Dask worker running it was lost, or the cluster failed           retried
========== ===================================================================== ==============

:data:`INFRASTRUCTURE` are the kinds ``--resume`` retries by default (they say nothing about the
case); ``--retry-failed`` retries every kind.  :class:`InfrastructureError` stops a whole run
(the CLI's exit code 3; finished cases stay stored); :class:`ExecutorStartError`, its subclass,
means the executor never started (exit 2: nothing was run, no folder is left behind).

Checked by ``tests/study/test_sandbox.py`` and ``tests/study/test_retry.py``.
"""

from __future__ import annotations

import signal
from dataclasses import dataclass, field
from typing import Any

__all__ = ["CaseLimits", "Crash", "ExecutorStartError", "FAILURE_KINDS", "INFRASTRUCTURE", "InfrastructureError",
           "Outcome",
           "crash_from_exit", "failure_of_error"]

FAILURE_KINDS = ("model", "crash", "timeout", "memory", "killed", "lost")
INFRASTRUCTURE = frozenset({"timeout", "memory", "killed", "lost"})
# signals that come from outside the case (a person, a scheduler, the OOM killer)
_EXTERNAL = {signal.SIGKILL, signal.SIGTERM, signal.SIGINT, signal.SIGHUP, signal.SIGQUIT}


class InfrastructureError(RuntimeError):
    """The executor cannot go on (cluster lost, workers cannot run cases); one line in ``str()``."""


class ExecutorStartError(InfrastructureError):
    """The executor could not start (scheduler unreachable, cluster failed to start): nothing was run."""


@dataclass(frozen=True)
class CaseLimits:
    """Per-case limits, enforced by every executor (see each executor for how).

    Attributes
    ----------
    seconds : float or None
        Wall-clock seconds one case (all its models) may take; ``None``: no limit.
    memory : float or None
        Bytes of address space of the process running the case (``RLIMIT_AS``); ``None``: no cap.
    """

    seconds: float | None = None
    memory: float | None = None

    def describe(self) -> str:
        parts = []
        if self.seconds is not None:
            parts.append(f"max_case_seconds = {self.seconds:g} s")
        if self.memory is not None:
            parts.append(f"max_case_memory = {self.memory / 2**30:.3g} GiB")
        return ", ".join(parts) or "no limits"


@dataclass(frozen=True)
class Crash:
    """Why a unit did not finish: ``kind`` (one of :data:`FAILURE_KINDS` but ``model``) and a reason."""

    kind: str
    reason: str


@dataclass(frozen=True)
class Outcome:
    """Rows a unit produced (finished models, in order) and the crash that stopped it, if any."""

    rows: list[dict[str, Any]] = field(default_factory=list)
    crash: Crash | None = None


def crash_from_exit(code: int | None, what: str = "worker process") -> Crash:
    """The :class:`Crash` of a child process that ended with ``code`` (``Popen.returncode`` convention)."""
    if code is None:
        return Crash("lost", f"{what} died (exit status unknown)")
    if code < 0:
        try:
            sig = signal.Signals(-code)
            name = sig.name
        except ValueError:
            sig, name = None, f"signal {-code}"
        kind = "killed" if sig in _EXTERNAL else "crash"
        return Crash(kind, f"{what} killed by {name}")
    return Crash("crash", f"{what} exited with status {code}")


def failure_of_error(error: str) -> str:
    """The failure kind of a failed row stored without a ``failure`` cell (folders of older versions)."""
    e = str(error)
    if e.startswith("worker process") or "died while running this case" in e:
        return "killed" if ("SIGKILL" in e or "SIGTERM" in e or "lost" in e) else "crash"
    if "max_case_seconds" in e:
        return "timeout"
    return "model"
