"""Run a motion study: expand, skip finished cases (resume), evaluate, store, manifest, summary.

Reuses the generic runner's pieces: :class:`~workbench.study.store.ResultStore` (atomic Parquet
parts, schema part), the executors (:mod:`workbench.study.executors`), the manifest writer and
package/git records of :mod:`workbench.study.runner`, and its :func:`summarize`.
"""

from __future__ import annotations

import os
import platform
import socket
import sys
import time
from pathlib import Path
from typing import Any

from ..study.executors import Executor, SerialExecutor, WorkerCrash
from ..study.expand import flatten_params
from ..study.runner import RunSummary, _now, _write_manifest, finish_run, git_commit, open_run_manifest, package_versions, summarize
from ..study.spec import StudyError
from ..study.store import ResultStore
from .expand import expand_motions
from .spec import MotionStudy, is_motion_study, load_motion_study
from .worker import MODELS, evaluate_motion_batch

__all__ = ["run_motion_study", "run_loaded_motion_study", "is_motion_study"]


def _crash_rows(case_id: str, params: dict[str, Any], reason: str) -> list[dict[str, Any]]:
    flat = flatten_params(params)
    return [{"case_id": case_id, "model": m, **flat, "status": "failed", "error": reason, "wall_time": float("nan")}
            for m in MODELS]


def run_motion_study(path: str | Path, out_dir: str | Path, executor: Executor | None = None,
                     resume: bool = False, *, progress: bool | None = None) -> RunSummary:
    """Validate the motion-study file ``path`` and run it into ``out_dir``.

    Parameters
    ----------
    path : path-like
        Study TOML with ``[study] kind = "series_parallel"``.
    out_dir : path-like
        Result folder (Parquet parts + ``_manifest.json``); must be empty unless ``resume``.
    executor : Executor, optional
        Any :mod:`workbench.study.executors` executor (default serial).  Cases are dispatched one
        per task (each costs seconds).
    resume : bool
        Skip cases already stored; refuses a folder whose config hash differs.

    Returns
    -------
    RunSummary
        ``exit_code`` is 1 when any case failed (e.g. an unreachable pose).

    Raises
    ------
    StudyError
        Invalid file (one line per problem) or folder/resume mismatch.
    """
    return run_loaded_motion_study(load_motion_study(path), out_dir, executor, resume=resume, progress=progress)


def run_loaded_motion_study(study: MotionStudy, out_dir: str | Path, executor: Executor | None = None, *,
                            resume: bool = False, progress: bool | None = None, flush_rows: int = 64,
                            model_lookup=None, arc_actuation=None) -> RunSummary:
    """:func:`run_motion_study` for an already validated :class:`MotionStudy`.

    Takes the keyword arguments of :func:`workbench.study.run_study` so that a caller can
    dispatch on the study type with the same call; ``model_lookup`` and ``arc_actuation`` have
    no meaning here and must be None.
    """
    if model_lookup is not None or arc_actuation is not None:
        raise StudyError([f"{study.path}: --model-lookup / --arc-actuation do not apply to a series_parallel motion study"])
    folder = Path(out_dir)
    cases = expand_motions(study)
    config_hash = study.config_hash
    manifest = open_run_manifest(folder, config_hash, resume, lambda: {
        "study": study.resolved(), "study_file": study.path, "config_hash": config_hash,
        "n_cases": len(cases), "versions": package_versions(), "git": git_commit(), "runs": []})
    folder.mkdir(parents=True, exist_ok=True)
    store = ResultStore(folder, (flatten_params(c.params) for c in cases), flush_rows=flush_rows, flush_seconds=2.0)
    store.cleanup_temporaries()
    finished = store.finished_case_ids()
    todo = [c for c in cases if c.case_id not in finished]
    executor = executor or SerialExecutor()
    run_rec = {"host": socket.gethostname(), "pid": os.getpid(), "platform": platform.platform(),
               "executor": getattr(executor, "name", type(executor).__name__), "start": _now(), "end": None,
               "cases_to_run": len(todo), "cases_done": 0}
    manifest["runs"].append(run_rec)
    _write_manifest(folder, manifest)
    show = progress if progress is not None else sys.stderr.isatty()
    bar = None
    if todo and show:
        from tqdm import tqdm

        bar = tqdm(total=len(todo), unit="case", dynamic_ncols=True, file=sys.stderr)
    t0 = time.perf_counter()
    try:
        with executor:
            payloads = [[(c.case_id, c.params)] for c in todo]
            for i, out in executor.imap_unordered(evaluate_motion_batch, payloads):
                case = todo[i]
                rows = _crash_rows(case.case_id, case.params, out.reason) if isinstance(out, WorkerCrash) else out[0]
                store.add(rows)
                run_rec["cases_done"] += 1
                if bar is not None:
                    bar.update(1)
    finally:
        finish_run(folder, manifest, run_rec, store, bar, t0)
    return summarize(folder, n_cases=len(cases), n_run=len(todo), wall_time=time.perf_counter() - t0)
