"""Run a study: one driver for every study kind, and the summary of a result folder.

:func:`run_cases` runs the cases of any :class:`~workbench.study.kinds.StudyKind` through one
:class:`~workbench.study.session.RunSession` (lock, manifest, run record, store, progress,
finish): it expands the study, plans what is left to compute (resume, retries), enters the
executor (a cluster that cannot start stops the run before anything is written), submits the
units and stores each unit's rows as they arrive.  A unit whose process crashed keeps the rows
of the models that finished; the model that was running gets a failed row with the crash's
reason and ``failure`` kind, and for a kind whose models are computed one by one the remaining
models are run again in a fresh process (:func:`_complete`).  :func:`run_study` is
``run_cases(SWEEP, ...)``; :func:`summarize` counts a stored table.

Checked by ``tests/study/test_store.py``, ``tests/study/test_executors.py``, ``tests/study/test_cli.py``,
``tests/study/test_kinds.py``, ``tests/study/test_retry.py`` and ``tests/motion/test_motion_run.py``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from .executors import Executor, SerialExecutor
from .kinds import SWEEP, StudyKind
from .lock import FolderLock
from .outcomes import CaseLimits, Outcome
from .params import flatten_params
from .plan import Unit
from .rows import failed_rows
from .session import RunSession, read_manifest, utc_now
from .spec import Study
from .store import read_columns

__all__ = ["RunSummary", "run_cases", "run_study", "summarize"]

#: failure kinds that make the exit code 3 ("the infrastructure failed": --resume retries them)
_INFRA_EXIT = ("killed", "lost")


@dataclass
class RunSummary:
    """Outcome of :func:`run_cases` (counts over the whole table, including earlier runs).

    ``failures`` counts failed rows per ``failure`` kind; ``n_duplicates`` the rows beyond the
    first of a (case_id, model) pair (0 in a folder only locked runs wrote); ``n_cached`` the
    rows of this run taken from the result cache, ``n_computed`` the cases of this run submitted to
    the executor (the other ``n_run - n_computed`` came whole from the cache; ``None``: not counted).
    """

    folder: Path
    n_cases: int
    n_run: int
    n_skipped: int
    n_ok: int
    n_failed: int
    wall_time: float
    per_model: dict[str, dict[str, float]] = field(default_factory=dict)
    failed_cases: list[str] = field(default_factory=list)
    failures: dict[str, int] = field(default_factory=dict)
    n_duplicates: int = 0
    n_cached: int = 0
    n_computed: int | None = None

    @property
    def exit_code(self) -> int:
        """0 every case ok; 3 some rows failed because workers were killed or lost; else 1 if any failed."""
        if any(self.failures.get(k) for k in _INFRA_EXIT):
            return 3
        return 1 if self.n_failed else 0


def _complete(unit: Unit, out: Outcome, params: dict[str, Any], separable: bool) -> tuple[list[dict], Unit | None]:
    """The rows to store for ``unit`` from ``out``, and the unit still to run (models after a crash), if any."""
    rows = [r for r in out.rows if r.get("model") in unit.models]
    done = {r["model"] for r in rows}
    missing = [m for m in unit.models if m not in done]
    cid = unit.case.case_id
    if not missing:
        return rows, None
    crash = out.crash
    if crash is None:  # a task that ended without a row for some model: a bug, recorded as such
        return rows + failed_rows(cid, params, missing, "the task returned no row for this model",
                                  failure="crash"), None
    if separable and crash.kind in ("crash", "killed"):
        reason = f"{crash.reason} while computing model {missing[0]!r}"
        rows += failed_rows(cid, params, missing[:1], reason, failure=crash.kind)
        return rows, (Unit(unit.case, tuple(missing[1:])) if len(missing) > 1 else None)
    return rows + failed_rows(cid, params, missing, crash.reason, failure=crash.kind), None


def _cached(units: list[Unit], cache: Any, session: RunSession, separable: bool, ok_only: bool = False) -> list[Unit]:
    """Record what ``cache`` holds of ``units`` (``ok_only``: its ok rows); the units (models) still to compute."""
    out = []
    for u in units:
        rows = {m: cache.get(u.case.case_id, m, ok_only=ok_only) for m in u.models}
        missing = tuple(m for m in u.models if rows[m] is None)
        if missing and not separable:  # computed together: all or nothing
            cache.hits -= len(u.models) - len(missing)
            out.append(u)
            continue
        if len(missing) < len(u.models):
            session.record(u.case.case_id, [rows[m] for m in u.models if rows[m] is not None], complete=not missing)
        if missing:
            out.append(Unit(u.case, missing))
    return out


#: largest adaptive chunk (units per task) when the run does not fix ``batch_size``
MAX_ADAPTIVE_CHUNK = 256


def _execute(kind: StudyKind, spec: Any, session: RunSession, executor: Executor, chunk_size: int,
             options: Any, recorded: dict[str, dict[str, Any]], limits: CaseLimits, cache: Any = None,
             retry_failed: bool = False, adaptive: bool = False) -> int:
    """Submit the session's units (those the cache does not hold); store each outcome; rerun the models left after a crash.

    Returns the number of cases submitted (the others came whole from the cache).
    """
    separable = kind.separable_models
    pending = list(session.todo) if cache is None else _cached(list(session.todo), cache, session, separable,
                                                                ok_only=retry_failed)
    n_submitted = len(pending)
    while pending:
        payloads = [kind.payload(spec, u.case, u.models, options) for u in pending]
        requeue: list[Unit] = []
        extra = {"max_chunk": MAX_ADAPTIVE_CHUNK} if adaptive and getattr(executor, "adapts_chunks", False) else {}
        for i, out in executor.imap_unordered(kind.task, payloads, limits, chunk_size, **extra):
            unit = pending[i]
            rows, more = _complete(unit, out, recorded[unit.case.case_id], separable)
            if more is not None:
                requeue.append(more)
            if cache is not None and (separable or all(r.get("status") == "ok" for r in rows)):
                for r in rows:
                    cache.put(r)
            session.record(unit.case.case_id, rows, complete=more is None)
        pending = requeue
    return n_submitted


def run_cases(
    kind: StudyKind,
    spec: Any,
    folder: str | Path,
    executor: Executor | None = None,
    *,
    resume: bool = False,
    retry_failed: bool = False,
    force: bool = False,
    progress: bool | None = None,
    progress_seconds: float = 30.0,
    flush_rows: int | None = None,
    flush_seconds: float = 2.0,
    batch_size: int | None = None,
    limits: CaseLimits | None = None,
    cache: Any = None,
    **options: Any,
) -> RunSummary:
    """Run every (remaining) case of ``spec``, a validated study of ``kind``, into ``folder``.

    Parameters
    ----------
    kind : StudyKind
        E.g. :data:`~workbench.study.kinds.SWEEP` or ``get_kind(kind_of(path))``.
    spec : object
        What ``kind.load`` returned.
    folder : path-like
        Output folder (created; locked while the run lasts).  Without ``resume`` it must not
        hold results yet (``force``: they are discarded).
    executor : Executor, optional
        Default :class:`SerialExecutor`.  Entered (before anything is written) and exited here.
    resume : bool
        Compute only what is not stored (:mod:`workbench.study.plan`: failed rows of the
        infrastructure kinds are retried); refuses a folder whose manifest has another config hash.
    retry_failed : bool
        With ``resume``: also recompute rows that failed for any other reason.
    force : bool
        Discard the folder's stored results first.
    progress : bool, optional
        A bar (True), nothing (False), or (None) a bar on a terminal and log lines otherwise.
    progress_seconds : float
        Log lines: at least one this often while cases run (naming the case in progress).
    flush_rows, flush_seconds : int, float
        When buffered rows are written as a part (also on a timer); ``flush_rows`` defaults to
        ``kind.flush_rows``.  An executor without isolation journals every case at once
        (the next run of the folder stores what a crash left there).
    batch_size : int, optional
        Units per task (per message to the isolated child); default ``kind.batch_size(n,
        executor.slots)``, and an executor that adapts (Dask) then sizes later tasks by the
        measured time per unit (at most :data:`MAX_ADAPTIVE_CHUNK`).
    limits : CaseLimits, optional
        Per-case limits; default ``kind.limits(spec)`` (``[solver] max_case_seconds`` /
        ``max_case_memory``).
    cache : ResultCache or path-like, optional
        Reuse rows computed before for the same case, model and model code version, and store
        the new ones (:mod:`workbench.study.cache`); ignored with a custom ``model_lookup`` /
        ``arc_actuation``.
    **options
        Passed to ``kind.run_options`` (sweep: ``model_lookup``, ``arc_actuation``, see
        :func:`~workbench.study.evaluate.evaluate_case`; picklable for processes).

    Raises
    ------
    StudyError
        Options the kind refuses, a locked folder, folder/resume mismatch (user errors: exit 2).
    InfrastructureError
        The executor could not start or failed during the run (exit 3; finished cases are stored).
    """
    run_opts = kind.run_options(spec, **options)
    cases = kind.expand(spec)
    recorded = {c.case_id: kind.recorded_params(spec, c) for c in cases}
    flat_memo: dict[int, tuple] = {}  # shared robot sections flattened once (flatten_params)
    executor = executor or SerialExecutor()
    limits = limits if limits is not None else kind.limits(spec)
    folder = Path(folder)
    lock = FolderLock(folder).acquire(utc_now())
    try:
        executor.__enter__()
    except BaseException:
        lock.release(remove_folder=True)
        raise
    try:
        session = RunSession.open(
            folder, spec, cases, (flatten_params(p, flat_memo) for p in recorded.values()),
            getattr(executor, "name", type(executor).__name__), models=kind.models(spec),
            separable=kind.separable_models, resume=resume, retry_failed=retry_failed,
            force=force, progress=progress, flush_rows=kind.flush_rows if flush_rows is None else flush_rows,
            flush_seconds=flush_seconds, lock=lock, flush_each=not getattr(executor, "isolates_cases", True),
            limits=limits, progress_seconds=progress_seconds)
        if cache is not None and not any(options.get(k) for k in ("model_lookup", "arc_actuation")):
            from .cache import ResultCache

            cache = cache if isinstance(cache, ResultCache) else ResultCache(cache)
        else:
            cache = None
        with session:
            chunk = batch_size or kind.batch_size(len(session.todo), getattr(executor, "slots", 1))
            try:
                n_computed = _execute(kind, spec, session, executor, chunk, run_opts, recorded, limits, cache,
                                      retry_failed, adaptive=batch_size is None)
            finally:
                if cache is not None:
                    session.run_rec["cache"] = {"folder": str(cache.folder), "hits": cache.hits,
                                                "writes": cache.writes}
    except BaseException as e:
        executor.__exit__(type(e), e, e.__traceback__)
        raise
    executor.__exit__(None, None, None)
    summary = summarize(session.folder, n_cases=len(cases), n_run=len(session.todo),
                        wall_time=time.perf_counter() - session.t0)
    summary.n_cached = cache.hits if cache is not None else 0
    summary.n_computed = n_computed
    return summary


def run_study(
    study: Study,
    folder: str | Path,
    executor: Executor | None = None,
    *,
    resume: bool = False,
    retry_failed: bool = False,
    force: bool = False,
    model_lookup: Callable | None = None,
    arc_actuation: Callable | None = None,
    progress: bool | None = None,
    progress_seconds: float = 30.0,
    flush_rows: int = 256,
    flush_seconds: float = 2.0,
    batch_size: int | None = None,
    limits: CaseLimits | None = None,
    cache: Any = None,
) -> RunSummary:
    """Run every (remaining) case of the sweep study ``study`` into ``folder``: ``run_cases(SWEEP, ...)``.

    See :func:`run_cases` for the parameters; ``model_lookup`` and ``arc_actuation`` are passed to
    :func:`~workbench.study.evaluate.evaluate_case`.
    """
    return run_cases(SWEEP, study, folder, executor, resume=resume, retry_failed=retry_failed, force=force,
                     progress=progress, progress_seconds=progress_seconds, flush_rows=flush_rows,
                     flush_seconds=flush_seconds, batch_size=batch_size,
                     limits=limits, cache=cache, model_lookup=model_lookup, arc_actuation=arc_actuation)


def summarize(folder: str | Path, *, n_cases: int | None = None, n_run: int = 0,
              wall_time: float = float("nan")) -> RunSummary:
    """Counts over the stored table of ``folder`` (``n_cases`` default: the manifest's).

    Raises
    ------
    CorruptPart
        A part file cannot be read (the message names it).
    """
    folder = Path(folder)
    df = read_columns(folder, ["case_id", "model", "status", "wall_time", "failure", "error"])
    if n_cases is None:
        n_cases = read_manifest(folder).get("n_cases", df["case_id"].nunique())
    n_dup = int(df.duplicated(["case_id", "model"]).sum()) if len(df) else 0
    case_ok = df["status"].eq("ok").groupby(df["case_id"]).all()
    per_model = {}
    for m, g in df.groupby("model", sort=True):
        per_model[str(m)] = {"ok": int((g["status"] == "ok").sum()), "failed": int((g["status"] != "ok").sum()),
                             "wall_time": float(g["wall_time"].sum(skipna=True))}
    bad = df[df["status"] != "ok"]
    kinds = bad["failure"].fillna("").where(bad["failure"].fillna("") != "",
                                            bad["error"].fillna("").map(_failure_of_error))
    return RunSummary(
        folder=folder, n_cases=int(n_cases), n_run=n_run, n_skipped=int(n_cases) - n_run,
        n_ok=int(case_ok.sum()), n_failed=int((~case_ok).sum()), wall_time=wall_time,
        per_model=per_model, failed_cases=sorted(case_ok.index[~case_ok.values].tolist()),
        failures={str(k): int(v) for k, v in kinds.value_counts().sort_index().items()}, n_duplicates=n_dup,
    )


def _failure_of_error(e: str) -> str:
    from .outcomes import failure_of_error

    return failure_of_error(e)
