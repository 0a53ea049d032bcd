"""How one run of a study is carried out: :class:`RunConfig`, the settings of the pipeline (not of the physics).

What a run computes is the study file's (its kind, cases and models); how it is run -- continue a
stored run, show progress, how often rows are written, units per task, per-case limits, the result
cache -- is one frozen :class:`RunConfig` that :func:`workbench.study.runner.run_cases` and
:meth:`workbench.study.session.RunSession.open` take.  The CLI builds it from the ``run`` options.
Checked by ``tests/study/test_session.py``, ``tests/study/test_store.py`` and
``tests/study/test_retry.py``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .outcomes import CaseLimits

__all__ = ["RunConfig"]


@dataclass(frozen=True)
class RunConfig:
    """The settings of one run (see the module docstring).

    Attributes
    ----------
    resume : bool
        Compute only what is not stored (:mod:`workbench.study.plan`: failed rows of the
        infrastructure kinds are retried); refuses a folder whose manifest has another config hash.
    retry_failed : bool
        With ``resume``: also recompute rows that failed for any other reason.
    force : bool
        Discard the folder's stored results first.
    progress : bool or None
        A bar (True), nothing (False), or (None) a bar on a terminal and log lines otherwise.
    progress_seconds : float
        Log lines: at least one this often while cases run, naming the case in progress.
    flush_rows : int or None
        Buffered rows per Parquet part; ``None``: the study kind's ``flush_rows``.
    flush_seconds : float
        Buffered rows are also written on this timer [s].
    batch_size : int or None
        Units per task (per message to the isolated child); ``None``: the kind's
        ``batch_size(n, executor.slots)``, and an executor that adapts (Dask) then sizes later
        tasks by the measured time per unit.
    limits : CaseLimits or None
        Per-case limits; ``None``: the study's (``[solver] max_case_seconds`` / ``max_case_memory``).
    cache : ResultCache, path-like or None
        Reuse rows computed before for the same case, model and model code version, and store
        the new ones (:mod:`workbench.study.cache`); ``None``: no cache.
    """

    resume: bool = False
    retry_failed: bool = False
    force: bool = False
    progress: bool | None = None
    progress_seconds: float = 30.0
    flush_rows: int | None = None
    flush_seconds: float = 2.0
    batch_size: int | None = None
    limits: CaseLimits | None = None
    cache: Any = None
