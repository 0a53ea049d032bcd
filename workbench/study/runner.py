"""Run a study: expand, skip finished cases (resume), execute, store, manifest, summary."""

from __future__ import annotations

import datetime as _dt
import json
import os
import platform
import socket
import subprocess
import sys
import time
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any, Callable

from .evaluate import evaluate_batch, failed_rows
from .executors import Executor, SerialExecutor, WorkerCrash
from .expand import expand, flatten_params
from .spec import Study, StudyError
from .store import MANIFEST, ResultStore, atomic_write_bytes

__all__ = ["RunSummary", "finish_run", "open_run_manifest", "run_study", "read_manifest", "package_versions", "git_commit"]

_PACKAGES = ("trunk-workbench", "exudyn", "numpy", "scipy", "pandas", "pyarrow", "dask",
             "distributed", "pydantic", "tqdm")


@dataclass
class RunSummary:
    """Outcome of :func:`run_study` (counts over the whole table, including earlier runs)."""

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


def _now() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def package_versions() -> dict[str, str | None]:
    """Installed versions (from package metadata; nothing is imported)."""
    out: dict[str, str | None] = {"python": platform.python_version()}
    for p in _PACKAGES:
        try:
            out[p] = metadata.version(p)
        except metadata.PackageNotFoundError:
            out[p] = None
    if out.get("trunk-workbench") is None:
        from .. import __version__

        out["trunk-workbench"] = __version__
    return out


def git_commit() -> dict[str, Any]:
    """Commit of the workbench source tree (``None`` outside git) and whether it was dirty."""
    root = Path(__file__).resolve().parents[2]
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                              text=True, timeout=10)
        if head.returncode != 0:
            return {"commit": None, "dirty": None}
        st = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                            capture_output=True, text=True, timeout=10)
        return {"commit": head.stdout.strip(), "dirty": bool(st.stdout.strip())}
    except (OSError, subprocess.TimeoutExpired):
        return {"commit": None, "dirty": None}


def read_manifest(folder: str | Path) -> dict[str, Any]:
    return json.loads((Path(folder) / MANIFEST).read_text())


def _write_manifest(folder: Path, manifest: dict[str, Any]) -> None:
    data = json.dumps(manifest, indent=2, sort_keys=False).encode()
    atomic_write_bytes(folder / MANIFEST, lambda f: f.write(data))



def open_run_manifest(folder: Path, config_hash: str, resume: bool,
                      fresh: Callable[[], dict[str, Any]]) -> dict[str, Any]:
    """The manifest a run continues (``resume``) or starts (``fresh()``); refuses to mix runs.

    Raises
    ------
    StudyError
        The folder holds results and ``resume`` is off; the stored config hash differs; or
        the folder holds Parquet parts without a manifest.
    """
    if (folder / MANIFEST).exists():
        old = read_manifest(folder)
        name = (old.get("study") or {}).get("study", {}).get("name")
        if not resume:
            raise StudyError([f"{folder}: already holds results of study {name!r}; "
                              f"use --resume to continue it or --out to choose another folder"])
        if old.get("config_hash") != config_hash:
            raise StudyError([f"{folder}: --resume refused: the study's config hash {config_hash} differs from "
                              f"the stored run's {old.get('config_hash')} (parameters, sweep, seed or models "
                              f"changed); use another --out"])
        return old
    if folder.exists() and any(folder.glob("part-*.parquet")):
        raise StudyError([f"{folder}: holds Parquet parts but no {MANIFEST}; refusing to mix results"])
    return fresh()


def finish_run(folder: Path, manifest: dict[str, Any], run_rec: dict[str, Any], store: ResultStore,
               bar: Any, t0: float) -> None:
    """Flush the store, close the progress bar and record the run's end in the manifest.

    Called from a ``finally`` block, so an interrupted run still leaves a consistent folder.
    """
    store.close()
    if bar is not None:
        bar.close()
    run_rec["end"] = _now()
    run_rec["wall_time"] = round(time.perf_counter() - t0, 3)
    _write_manifest(folder, manifest)

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
    """Run every (remaining) case of ``study`` and store the rows in ``folder``.

    Parameters
    ----------
    study : Study
    folder : path-like
        Output folder (created).  Without ``resume`` it must not hold results yet.
    executor : Executor, optional
        Default :class:`SerialExecutor`.  Entered and exited here.
    resume : bool
        Skip cases whose rows are already stored; refuses a folder whose manifest has a
        different config hash.
    model_lookup, arc_actuation : callable, optional
        Passed to :func:`~workbench.study.evaluate.evaluate_case` (picklable for processes).
    progress : bool, optional
        Show a tqdm bar (default: only when stderr is a TTY).
    flush_rows, flush_seconds : int, float
        When buffered rows are written as a part (see :class:`ResultStore`).
    batch_size : int, optional
        Cases per task.  Default: ``ceil(n / (8 * executor.slots))`` capped to [1, 32], which
        amortises the per-task cost of process executors while keeping the load balanced.
        A batch whose worker dies is rerun case by case, so the crash is blamed on its case.

    Raises
    ------
    StudyError
        Folder/resume mismatch (a user error: the CLI exits with 2).
    """
    folder = Path(folder)
    cases = expand(study)
    config_hash = study.config_hash
    manifest = open_run_manifest(folder, config_hash, resume, lambda: {
        "study": study.resolved(), "study_file": study.path, "config_hash": config_hash,
        "n_cases": len(cases), "versions": package_versions(), "git": git_commit(), "runs": [],
    })
    folder.mkdir(parents=True, exist_ok=True)

    store = ResultStore(folder, (flatten_params(c.params) for c in cases), flush_rows, flush_seconds)
    store.cleanup_temporaries()
    finished = store.finished_case_ids()
    todo = [c for c in cases if c.case_id not in finished]
    executor = executor or SerialExecutor()
    run_rec = {"host": socket.gethostname(), "pid": os.getpid(), "platform": platform.platform(),
               "executor": getattr(executor, "name", type(executor).__name__),
               "start": _now(), "end": None, "cases_to_run": len(todo), "cases_done": 0}
    manifest["runs"].append(run_rec)
    if resume:
        manifest["versions"] = package_versions()
        manifest["git"] = git_commit()
    _write_manifest(folder, manifest)

    show = progress if progress is not None else sys.stderr.isatty()
    n_ok = n_failed = 0
    t0 = time.perf_counter()
    bar = None
    if todo and show:
        from tqdm import tqdm

        bar = tqdm(total=len(todo), unit="case", dynamic_ncols=True, file=sys.stderr)
    try:
        with executor:
            size = batch_size or min(32, max(1, -(-len(todo) // (8 * max(1, getattr(executor, "slots", 1))))))
            pending = [todo[i:i + size] for i in range(0, len(todo), size)]
            while pending:
                retry: list[list] = []
                payloads = [([(c.case_id, c.params) for c in b], study.models, model_lookup, arc_actuation)
                            for b in pending]
                for i, out in executor.imap_unordered(evaluate_batch, payloads):
                    batch = pending[i]
                    if isinstance(out, WorkerCrash):
                        if len(batch) > 1:  # find the culprit: rerun the batch case by case
                            retry.extend([c] for c in batch)
                            continue
                        out = [failed_rows(batch[0].case_id, batch[0].params, study.models, out.reason)]
                    for rows in out:
                        store.add(rows)
                        if all(r["status"] == "ok" for r in rows):
                            n_ok += 1
                        else:
                            n_failed += 1
                    run_rec["cases_done"] += len(batch)
                    if bar is not None:
                        bar.set_postfix_str(f"ok={n_ok} failed={n_failed}", refresh=False)
                        bar.update(len(batch))
                pending = retry
    finally:
        finish_run(folder, manifest, run_rec, store, bar, t0)

    return summarize(folder, n_cases=len(cases), n_run=len(todo), wall_time=time.perf_counter() - t0)


def summarize(folder: str | Path, *, n_cases: int | None = None, n_run: int = 0,
              wall_time: float = float("nan")) -> RunSummary:
    """Counts over the stored table of ``folder``."""
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
