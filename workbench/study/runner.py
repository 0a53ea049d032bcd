"""Run a study: one driver for every study kind, and the summary of a result folder.

:func:`run_cases` runs the cases of any :class:`~workbench.study.kinds.StudyKind` through one
:class:`~workbench.study.session.RunSession` (lock, manifest, run record, store, progress,
finish): it expands the study, plans what is left to compute (resume, retries), enters the
executor (a cluster that cannot start stops the run before anything is written), submits the
units and stores each unit's rows as they arrive.  A unit whose process crashed keeps the rows
of the models that finished; the model that was running gets a failed row with the crash's
reason and ``failure`` kind, and for a kind whose models are computed one by one the remaining
models are run again in a fresh process (:func:`_complete`).  How the run is carried out
(resume, progress, flushing, batch size, limits, cache) is one frozen
:class:`~workbench.study.run_config.RunConfig`.  :func:`run_study` is ``run_cases(SWEEP, ...)``;
:func:`summarize` counts a stored table.  Tests run the real pipeline on fake models by passing
their own kind (``tests/study/study_fakes.py``: ``sweep_kind(lookup)``), never through a flag.

Checked by ``tests/study/test_store.py``, ``tests/study/test_executors.py``, ``tests/study/test_cli.py``,
``tests/study/test_kinds.py``, ``tests/study/test_retry.py`` and ``tests/motion/test_motion_run.py``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from .executors import Executor, SerialExecutor
from .kinds import SWEEP, StudyKind
from .lock import FolderLock
from .outcomes import CaseLimits, Outcome
from .params import flatten_params
from .plan import Unit
from .rows import failed_rows
from .run_config import RunConfig
from .session import RunSession, read_manifest, utc_now
from .spec import Study
from .store import read_columns

__all__ = ["MAX_ADAPTIVE_CHUNK", "RunSummary", "run_cases", "run_study", "summarize"]

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


def _execute(kind: StudyKind, spec: Any, session: RunSession, executor: Executor, config: RunConfig,
             recorded: dict[str, dict[str, Any]], limits: CaseLimits, cache: Any = None) -> int:
    """Submit the session's units (those the cache does not hold); store each outcome; rerun the models left after a crash.

    Returns the number of cases submitted (the others came whole from the cache).
    """
    separable = kind.separable_models
    pending = list(session.todo) if cache is None else _cached(list(session.todo), cache, session, separable,
                                                                ok_only=config.retry_failed)
    n_submitted = len(pending)
    chunk_size = config.batch_size or kind.batch_size(len(session.todo), executor.slots)
    extra = {"max_chunk": MAX_ADAPTIVE_CHUNK} if config.batch_size is None and executor.adapts_chunks else {}
    while pending:
        payloads = [kind.payload(spec, u.case, u.models) for u in pending]
        requeue: list[Unit] = []
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


def run_cases(kind: StudyKind, spec: Any, folder: str | Path, executor: Executor | None = None,
              config: RunConfig = RunConfig()) -> RunSummary:
    """Run every (remaining) case of ``spec``, a validated study of ``kind``, into ``folder``.

    Parameters
    ----------
    kind : StudyKind
        E.g. :data:`~workbench.study.kinds.SWEEP` or ``get_kind(kind_of(path))``.
    spec : object
        What ``kind.load`` returned.
    folder : path-like
        Output folder (created; locked while the run lasts).  Without ``config.resume`` it must
        not hold results yet (``config.force``: they are discarded).
    executor : Executor, optional
        Default :class:`SerialExecutor`.  Entered (``with executor:``, before anything is
        written) and exited here.  An executor without isolation journals every case at once
        (the next run of the folder stores what a crash left there).
    config : RunConfig
        How the run is carried out (:class:`~workbench.study.run_config.RunConfig`: resume,
        retries, progress, flushing, batch size, limits, cache).

    Raises
    ------
    StudyError
        A locked folder, folder/resume mismatch (user errors: exit 2).
    InfrastructureError
        The executor could not start or failed during the run (exit 3; finished cases are stored).
    """
    cases = kind.expand(spec)
    recorded = {c.case_id: kind.recorded_params(spec, c) for c in cases}
    executor = executor or SerialExecutor()
    limits = config.limits if config.limits is not None else kind.limits(spec)
    if config.flush_rows is None:
        config = replace(config, flush_rows=kind.flush_rows)
    folder = Path(folder)
    lock = FolderLock(folder).acquire(utc_now())
    entered = False
    try:
        with executor:
            entered = True
            session, n_computed, cache = _run_session(kind, spec, folder, executor, config, cases, recorded,
                                                      limits, lock)
    except BaseException:
        if not entered:
            lock.release(remove_folder=True)
        raise
    summary = summarize(session.folder, n_cases=len(cases), n_run=len(session.todo),
                        wall_time=time.perf_counter() - session.t0)
    summary.n_cached = cache.hits if cache is not None else 0
    summary.n_computed = n_computed
    return summary


def _run_session(kind, spec, folder, executor, config, cases, recorded, limits, lock):
    """Open the run session (inside the entered executor), compute, close; ``(session, n_computed, cache)``."""
    flat_memo: dict[int, tuple] = {}  # shared robot sections flattened once (flatten_params)
    session = RunSession.open(folder, spec, cases, (flatten_params(p, flat_memo) for p in recorded.values()),
                              executor.name, config, models=kind.models(spec), separable=kind.separable_models,
                              lock=lock, flush_each=not executor.isolates_cases, limits=limits)
    cache = config.cache
    if cache is not None:
        from .cache import ResultCache

        cache = cache if isinstance(cache, ResultCache) else ResultCache(cache)
    with session:
        try:
            n_computed = _execute(kind, spec, session, executor, config, recorded, limits, cache)
        finally:
            if cache is not None:
                session.run_rec["cache"] = {"folder": str(cache.folder), "hits": cache.hits, "writes": cache.writes}
    return session, n_computed, cache


def run_study(study: Study, folder: str | Path, executor: Executor | None = None,
              config: RunConfig = RunConfig()) -> RunSummary:
    """Run every (remaining) case of the sweep study ``study`` into ``folder``: ``run_cases(SWEEP, ...)``."""
    return run_cases(SWEEP, study, folder, executor, config)


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
