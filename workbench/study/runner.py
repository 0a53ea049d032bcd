"""Run a study: one driver for every study kind, and the summary of a result folder.

:func:`run_cases` runs the cases of any :class:`~workbench.study.kinds.StudyKind` through one
:class:`~workbench.study.session.RunSession` (manifest, run record, store, progress bar, finish):
it expands the study, skips the cases already stored (resume), submits batches of cases to the
executor and stores each case's rows as they arrive.  A batch whose worker dies is rerun case by
case, so the crash is blamed on its case (a failed row per model with the executor's reason).
:func:`run_study` is ``run_cases(SWEEP, ...)``; :func:`summarize` counts a stored table.

``open_run_manifest``, ``finish_run``, ``package_versions``, ``git_commit``, ``read_manifest``,
``_now`` and ``_write_manifest`` moved to :mod:`workbench.study.session` and are re-exported here.

Checked by ``tests/study/test_store.py``, ``tests/study/test_executors.py``, ``tests/study/test_cli.py``,
``tests/study/test_kinds.py`` and ``tests/motion/test_motion_run.py``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from .executors import Executor, SerialExecutor, WorkerCrash
from .kinds import SWEEP, StudyKind
from .params import flatten_params
from .rows import failed_rows
from .session import (  # all but RunSession re-exported (their old home; deprecated here)
    RunSession,
    _now,
    _write_manifest,
    finish_run,
    git_commit,
    open_run_manifest,
    package_versions,
    read_manifest,
    study_name,
)
from .spec import Study

__all__ = ["RunSummary", "finish_run", "open_run_manifest", "run_cases", "run_study", "read_manifest",
           "package_versions", "git_commit", "study_name", "summarize"]


@dataclass
class RunSummary:
    """Outcome of :func:`run_cases` (counts over the whole table, including earlier runs)."""

    folder: Path
    n_cases: int
    n_run: int
    n_skipped: int
    n_ok: int
    n_failed: int
    wall_time: float
    per_model: dict[str, dict[str, float]] = field(default_factory=dict)
    failed_cases: list[str] = field(default_factory=list)

    @property
    def exit_code(self) -> int:
        return 1 if self.n_failed else 0


def _execute(kind: StudyKind, spec: Any, session: RunSession, executor: Executor, batch_size: int | None,
             options: Any, recorded: dict[str, dict[str, Any]]) -> None:
    """Submit the session's cases in batches; rerun a crashed batch case by case.

    A case whose worker died gets a failed row per model, recording ``recorded[case_id]``.
    """
    todo = session.todo
    size = batch_size or kind.batch_size(len(todo), getattr(executor, "slots", 1))
    pending = [todo[i:i + size] for i in range(0, len(todo), size)]
    models = kind.models(spec)
    while pending:
        retry: list[list] = []
        payloads = [kind.payload(spec, b, options) for b in pending]
        for i, out in executor.imap_unordered(kind.task, payloads):
            batch = pending[i]
            if isinstance(out, WorkerCrash):
                if len(batch) > 1:  # find the culprit: rerun the batch case by case
                    retry.extend([c] for c in batch)
                    continue
                out = [failed_rows(batch[0].case_id, recorded[batch[0].case_id], models, out.reason)]
            session.record(out, len(batch))
        pending = retry


def run_cases(
    kind: StudyKind,
    spec: Any,
    folder: str | Path,
    executor: Executor | None = None,
    *,
    resume: bool = False,
    progress: bool | None = None,
    flush_rows: int | None = None,
    flush_seconds: float = 2.0,
    batch_size: int | None = None,
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
        Output folder (created).  Without ``resume`` it must not hold results yet.
    executor : Executor, optional
        Default :class:`SerialExecutor`.  Entered and exited here.
    resume : bool
        Skip cases whose rows are already stored; refuses a folder whose manifest has a
        different config hash.
    progress : bool, optional
        Show a tqdm bar (default: only when stderr is a TTY).
    flush_rows, flush_seconds : int, float
        When buffered rows are written as a part (see :class:`ResultStore`); ``flush_rows``
        defaults to ``kind.flush_rows``.
    batch_size : int, optional
        Cases per task; default ``kind.batch_size(n, executor.slots)``.
    **options
        Passed to ``kind.run_options`` (sweep: ``model_lookup``, ``arc_actuation``, see
        :func:`~workbench.study.evaluate.evaluate_case`; picklable for processes).

    Raises
    ------
    StudyError
        Options the kind refuses, or folder/resume mismatch (user errors: the CLI exits with 2).
    """
    run_opts = kind.run_options(spec, **options)
    cases = kind.expand(spec)
    recorded = {c.case_id: kind.recorded_params(spec, c) for c in cases}
    executor = executor or SerialExecutor()
    session = RunSession.open(
        folder, spec, cases, (flatten_params(p) for p in recorded.values()),
        getattr(executor, "name", type(executor).__name__), resume=resume, progress=progress,
        flush_rows=kind.flush_rows if flush_rows is None else flush_rows, flush_seconds=flush_seconds)
    with session, executor:
        _execute(kind, spec, session, executor, batch_size, run_opts, recorded)
    return summarize(session.folder, n_cases=len(cases), n_run=len(session.todo),
                     wall_time=time.perf_counter() - session.t0)


def run_study(
    study: Study,
    folder: str | Path,
    executor: Executor | None = None,
    *,
    resume: bool = False,
    model_lookup: Callable | None = None,
    arc_actuation: Callable | None = None,
    progress: bool | None = None,
    flush_rows: int = 256,
    flush_seconds: float = 2.0,
    batch_size: int | None = None,
) -> RunSummary:
    """Run every (remaining) case of the sweep study ``study`` into ``folder``: ``run_cases(SWEEP, ...)``.

    See :func:`run_cases` for the parameters; ``model_lookup`` and ``arc_actuation`` are passed to
    :func:`~workbench.study.evaluate.evaluate_case`.  A batch whose worker dies is rerun case by
    case, so the crash is blamed on its case.
    """
    return run_cases(SWEEP, study, folder, executor, resume=resume, progress=progress, flush_rows=flush_rows,
                     flush_seconds=flush_seconds, batch_size=batch_size, model_lookup=model_lookup,
                     arc_actuation=arc_actuation)


def summarize(folder: str | Path, *, n_cases: int | None = None, n_run: int = 0,
              wall_time: float = float("nan")) -> RunSummary:
    """Counts over the stored table of ``folder`` (``n_cases`` default: the manifest's)."""
    import pandas as pd

    folder = Path(folder)
    df = pd.read_parquet(folder, columns=["case_id", "model", "status", "wall_time"])
    if n_cases is None:
        n_cases = read_manifest(folder).get("n_cases", df["case_id"].nunique())
    case_ok = df["status"].eq("ok").groupby(df["case_id"]).all()
    per_model = {}
    for m, g in df.groupby("model", sort=True):
        per_model[str(m)] = {"ok": int((g["status"] == "ok").sum()), "failed": int((g["status"] != "ok").sum()),
                             "wall_time": float(g["wall_time"].sum(skipna=True))}
    return RunSummary(
        folder=folder, n_cases=int(n_cases), n_run=n_run, n_skipped=int(n_cases) - n_run,
        n_ok=int(case_ok.sum()), n_failed=int((~case_ok).sum()), wall_time=wall_time,
        per_model=per_model, failed_cases=sorted(case_ok.index[~case_ok.values].tolist()),
    )
