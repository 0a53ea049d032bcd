"""The run session of one study run: folder lock, manifest, run record, store, progress, finish.

Every study kind runs through one :class:`RunSession` (:func:`workbench.study.runner.run_cases`):

1. the folder's lock is taken (:class:`~workbench.study.lock.FolderLock`: one run per folder;
   a second is refused with one line) and held until :meth:`RunSession.close`;
2. :func:`open_run_manifest` continues (``resume``) or starts ``_manifest.json`` and refuses
   to mix runs of different studies; a changed name, description or ``[report]`` is recorded
   (:func:`presentation_changes`) and the manifest takes the new values;
3. the :class:`~workbench.study.store.ResultStore` is opened (``p.*`` column types fixed up
   front) and the work is planned (:mod:`workbench.study.plan`): per case the models not
   stored yet, plus those whose stored rows failed for a reason ``--resume`` retries
   (:data:`~workbench.study.outcomes.INFRASTRUCTURE`; every failure with ``retry_failed``) and
   duplicated rows; the rows to recompute are removed first;
4. a run record (host, pid, executor, limits, start, what is retried) is appended; on resume
   the versions and git commit are refreshed to the code that continues the run;
5. :meth:`RunSession.record` stores the rows of finished units; a timer thread flushes rows
   that waited ``flush_seconds`` (a run killed between cases loses at most that much);
6. :meth:`RunSession.close` (also on errors and interrupts) flushes, records the end, the wall
   time and the outcome, and releases the lock.

``open_run_manifest``, ``finish_run``, ``package_versions``, ``git_commit``, ``read_manifest``,

Checked by ``tests/study/test_store.py``, ``tests/study/test_session.py``, ``tests/study/test_lock.py``
and ``tests/study/test_retry.py``.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import platform
import socket
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping, Sequence

from .lock import FolderLock
from .messages import StudyError
from .outcomes import CaseLimits
from .plan import Unit, plan_units
from .progress import Progress
from .run_config import RunConfig
from .store import MANIFEST, CorruptPart, ResultStore, SchemaMismatch, atomic_write_bytes

__all__ = ["RunSession", "Unit", "finish_run", "git_commit", "open_run_manifest", "package_versions",
           "presentation_changes", "read_manifest", "study_name"]

_PACKAGES = ("trunk-workbench", "exudyn", "numpy", "scipy", "numba", "pandas", "pyarrow", "dask",
             "distributed", "dask-jobqueue", "pydantic", "tqdm")


def utc_now() -> str:
    """The current UTC time as ISO 8601 (seconds): the times of the manifest's run records and the lock."""
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
    """The ``_manifest.json`` of a result folder.

    Raises
    ------
    StudyError
        The file is not a JSON object (one line naming it); ``FileNotFoundError`` when missing.
    """
    path = Path(folder) / MANIFEST
    text = path.read_bytes()
    try:
        data = json.loads(text.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise StudyError([f"{path}: corrupt manifest, not valid JSON ({e}); restore it or use another --out"]) \
            from None
    if not isinstance(data, dict):
        raise StudyError([f"{path}: corrupt manifest: a JSON {type(data).__name__}, not an object"])
    return data


def study_name(manifest: Mapping[str, Any], default: Any = None) -> Any:
    """The study's name recorded in a manifest (``manifest["study"]["study"]["name"]``), else ``default``."""
    return ((manifest.get("study") or {}).get("study") or {}).get("name", default)


def _write_manifest(folder: Path, manifest: dict[str, Any]) -> None:
    data = json.dumps(manifest, indent=2, sort_keys=False).encode()
    atomic_write_bytes(folder / MANIFEST, lambda f: f.write(data))


def presentation_changes(old: Mapping[str, Any], new: Mapping[str, Any]) -> dict[str, list[Any]]:
    """What differs between two resolved specs in what does not change results: name, description, ``[report]``.

    Returns ``{"study.name": [old, new], ...}`` (empty when nothing changed).
    """
    out: dict[str, list[Any]] = {}
    os_, ns = old.get("study") or {}, new.get("study") or {}
    for key in ("name", "description"):
        if os_.get(key) != ns.get(key):
            out[f"study.{key}"] = [os_.get(key), ns.get(key)]
    if (old.get("report") or {}) != (new.get("report") or {}):
        out["report"] = [old.get("report") or {}, new.get("report") or {}]
    return out


def open_run_manifest(folder: Path, config_hash: str, resume: bool,
                      fresh: Callable[[], dict[str, Any]]) -> dict[str, Any]:
    """The manifest a run continues (``resume``) or starts (``fresh()``); refuses to mix runs.

    Raises
    ------
    StudyError
        The folder holds results and ``resume`` is off; the stored config hash differs; the
        folder holds Parquet parts without a manifest; the manifest is corrupt.
    """
    if (folder / MANIFEST).exists():
        old = read_manifest(folder)
        name = study_name(old)
        if not resume:
            raise StudyError([f"{folder}: already holds results of study {name!r}; use --resume to continue "
                              f"it, --force to discard them, or --out to choose another folder"])
        if old.get("config_hash") != config_hash:
            raise StudyError([f"{folder}: --resume refused: the study's config hash {config_hash} differs from "
                              f"the stored run's {old.get('config_hash')} (parameters, sweep, seed or models "
                              f"changed); use another --out"])
        old.setdefault("runs", [])
        return old
    if folder.exists() and any(folder.glob("part-*.parquet")):
        raise StudyError([f"{folder}: holds Parquet parts but no {MANIFEST}; refusing to mix results"])
    return fresh()


def finish_run(folder: Path, manifest: dict[str, Any], run_rec: dict[str, Any], store: ResultStore,
               bar: Any, t0: float) -> None:
    """Flush the store, close the progress bar and record the run's end in the manifest.

    Called from a ``finally`` block, so an interrupted run still leaves a consistent folder.
    """
    try:
        store.close()
    finally:
        if bar is not None:
            bar.close()
        run_rec["end"] = utc_now()
        run_rec["wall_time"] = round(time.perf_counter() - t0, 3)
        _write_manifest(folder, manifest)


def _outcome(exc: BaseException | None) -> str:
    if exc is None:
        return "completed"
    if isinstance(exc, KeyboardInterrupt):
        return f"interrupted ({type(exc).__name__})"
    return f"stopped: {type(exc).__name__}: {str(exc)[:300]}"


@dataclass
class RunSession:
    """One run of a study into a result folder (see the module docstring); use :meth:`open`.

    Attributes
    ----------
    folder : Path
    manifest : dict
        The folder's manifest (written at open, on flushes and at close).
    run_rec : dict
        This run's record in ``manifest["runs"]``.
    store : ResultStore
    todo : list of Unit
        What this run computes: per case (expansion order) the models still to run.
    lock : FolderLock
    progress : Progress
    flush_each : bool
        Make every unit's rows survive a crash of this process at once (the in-process executor):
        they are journaled as they come (:class:`~workbench.study.store.ResultStore` ``journal``)
        and the next run of the folder stores what a crash left in the journal.
    n_ok, n_failed : int
        Cases of this run whose rows are all ``ok`` / not all ``ok``.
    """

    folder: Path
    manifest: dict[str, Any]
    run_rec: dict[str, Any]
    store: ResultStore
    todo: list[Unit]
    lock: FolderLock
    progress: Progress
    flush_each: bool = False
    t0: float = field(default_factory=time.perf_counter)
    n_ok: int = 0
    n_failed: int = 0
    _failed_ids: set = field(default_factory=set)
    _stop: threading.Event = field(default_factory=threading.Event)
    _timer: threading.Thread | None = None
    _closed: bool = False
    _pending: dict = field(default_factory=dict)  # case id -> models not recorded yet (what is computing)

    @property
    def bar(self) -> Any:
        return self.progress.bar

    @classmethod
    def open(cls, folder: str | Path, spec: Any, cases: Sequence[Any], param_rows: Iterable[Mapping[str, Any]],
             executor_name: str, config: RunConfig = RunConfig(), *, models: Sequence[str] = (),
             separable: bool = True, lock: FolderLock | None = None, flush_each: bool = False,
             limits: CaseLimits | None = None) -> "RunSession":
        """Open (or continue) the run of ``cases`` of ``spec`` in ``folder``.

        Parameters
        ----------
        folder : path-like
        spec : object
            The validated study: ``path``, ``name``, ``config_hash``, ``overrides`` and
            ``resolved()`` are recorded.
        cases : sequence of Case
        param_rows : iterable of dict
            The flattened ``p.*`` parameters of every case (fix the column types).
        executor_name : str
        config : RunConfig
            ``resume``, ``retry_failed``, ``force``, ``progress``, ``progress_seconds``,
            ``flush_rows`` (``None``: 256) and ``flush_seconds`` are used here.
        models : sequence of str
            The models every case writes a row for (``kind.models(spec)``).
        separable : bool
            Models of a case can be computed one by one (sweeps); ``False``: a case is
            recomputed whole (series-parallel).
        lock : FolderLock, optional
            A lock the caller already holds (else taken here); released by :meth:`close`.
        flush_each : bool
            Journal every unit's rows at once (an executor without isolation).
        limits : CaseLimits, optional
            Recorded in the run record.

        Raises
        ------
        StudyError
            Locked folder, folder/resume mismatch, corrupt manifest or part, other column types.
        """
        folder = Path(folder)
        lock = lock if lock is not None and lock.held else FolderLock(folder).acquire(utc_now())
        try:
            return cls._open_locked(folder, spec, cases, param_rows, executor_name, config, tuple(models),
                                    separable, lock, flush_each, limits or CaseLimits())
        except BaseException:
            lock.release(remove_folder=True)
            raise

    @classmethod
    def _open_locked(cls, folder, spec, cases, param_rows, executor_name, config, models, separable, lock,
                     flush_each, limits):
        resume, retry_failed = config.resume, config.retry_failed
        flush_rows = 256 if config.flush_rows is None else config.flush_rows
        if config.force:
            _discard_results(folder)
        config_hash = spec.config_hash
        resolved = spec.resolved()
        manifest = open_run_manifest(folder, config_hash, resume, lambda: {
            "study": resolved, "study_file": spec.path, "config_hash": config_hash,
            "n_cases": len(cases), "versions": package_versions(), "git": git_commit(), "runs": [],
        })
        changes = presentation_changes(manifest.get("study") or {}, resolved) if manifest["runs"] else {}
        try:
            store = ResultStore(folder, param_rows, flush_rows, config.flush_seconds, journal=flush_each)
            store.cleanup_temporaries()
            store.recover_journal()  # rows of an in-process run that died between its flushes
            stored = store.stored_rows()
        except SchemaMismatch as e:
            raise StudyError([f"{folder}: --resume refused: {e} (the folder was written by another workbench "
                              f"version that recorded these parameters differently); use another --out"]) from None
        except CorruptPart as e:
            raise StudyError([f"{e.path}: unreadable Parquet part ({e.reason}); move it out of {folder} (--resume "
                              f"then recomputes its cases) or use another --out"]) from None
        plan = plan_units(cases, models, stored, retry_failed=retry_failed, separable=separable)
        store.remove_rows(plan.remove)
        run_rec = {"host": socket.gethostname(), "pid": os.getpid(), "platform": platform.platform(),
                   "executor": executor_name, "start": utc_now(), "end": None, "outcome": None,
                   "cases_to_run": len(plan.units), "cases_done": 0,
                   "limits": {"max_case_seconds": limits.seconds, "max_case_memory": limits.memory},
                   "study_file": spec.path}
        if plan.retried:
            run_rec["retried"] = plan.retried
        if spec.overrides:
            run_rec["overrides"] = list(spec.overrides)
        if changes:
            run_rec["changed"] = changes
            manifest["study"] = {**manifest["study"], "study": {**manifest["study"].get("study", {}),
                                                                 **{k: resolved["study"].get(k) for k in
                                                                    ("name", "description")}},
                                 "report": resolved.get("report", {})}
        if lock.stale:
            run_rec["stale_lock"] = lock.stale
        manifest["runs"].append(run_rec)
        if resume:
            manifest["versions"] = package_versions()
            manifest["git"] = git_commit()
        _write_manifest(folder, manifest)
        bar = Progress(len(plan.units), spec.name, config.progress, every_seconds=config.progress_seconds)
        session = cls(folder=folder, manifest=manifest, run_rec=run_rec, store=store, todo=plan.units, lock=lock,
                      progress=bar, flush_each=flush_each)
        session._pending = {u.case.case_id: list(u.models) for u in plan.units}
        session._start_timer()
        return session

    # -- running ------------------------------------------------------------------------------
    def _start_timer(self) -> None:
        wait = min(0.5, self.progress.every_seconds)

        def loop() -> None:
            while not self._stop.wait(wait):
                try:
                    if self.store.flush_if_due() is not None:
                        self._write_manifest()
                except Exception:  # noqa: BLE001 - the main thread flushes again and reports
                    pass
                self.progress.tick(self.in_progress())

        self._timer = threading.Thread(target=loop, name="workbench-flush", daemon=True)
        self._timer.start()

    def _write_manifest(self) -> None:
        with self.store._lock:  # one writer of the manifest at a time (timer thread, main thread)
            _write_manifest(self.folder, self.manifest)

    def in_progress(self) -> str:
        """What is still computing: the first case not finished (in submission order), its models
        not recorded yet, and how many cases follow it (the progress log's timer line)."""
        pending = dict(self._pending)  # (the timer thread reads it while record() changes it)
        if not pending:
            return "finishing"
        cid, models = next(iter(pending.items()))
        return f"in progress: case {cid} (models {', '.join(models)}), {len(pending) - 1} more to go"

    def record(self, case_id: str, rows: list[dict[str, Any]], complete: bool = True) -> None:
        """Store the rows of one unit of case ``case_id``; ``complete``: no more units of it follow.

        A row without a ``failure`` cell gets one (``""`` when ok, else ``"model"``).
        """
        for r in rows:
            if not r.get("failure"):
                r["failure"] = "" if r.get("status") == "ok" else "model"
        self.store.add(rows)  # flush_each: journaled at once (ResultStore(journal=True)), a part per batch
        if any(r.get("status") != "ok" for r in rows):
            self._failed_ids.add(case_id)
        if not complete:
            done = {r.get("model") for r in rows}
            if case_id in self._pending:
                self._pending[case_id] = [m for m in self._pending[case_id] if m not in done]
            return
        self._pending.pop(case_id, None)
        if case_id in self._failed_ids:
            self.n_failed += 1
        else:
            self.n_ok += 1
        self.run_rec["cases_done"] += 1
        self.progress.update(self.n_ok, self.n_failed)

    def close(self, exc: BaseException | None = None) -> None:
        """Flush the store, stop the timer, record end, wall time and outcome, release the lock."""
        if self._closed:
            return
        self._closed = True
        self._stop.set()
        if self._timer is not None:
            self._timer.join(timeout=10)
        self.run_rec["outcome"] = _outcome(exc)
        try:
            finish_run(self.folder, self.manifest, self.run_rec, self.store, None, self.t0)
        finally:
            self.progress.close()
            self.lock.release()

    def __enter__(self) -> "RunSession":
        return self

    def __exit__(self, exc_type: Any, exc: BaseException | None, tb: Any) -> None:
        self.close(exc)


def _discard_results(folder: Path) -> None:
    """``--force``: remove the stored parts, schema and manifest (under the lock)."""
    from .store import JOURNAL, SCHEMA_FILE

    for p in folder.glob("part-*.parquet"):
        p.unlink()
    for name in (SCHEMA_FILE, MANIFEST, JOURNAL):
        (folder / name).unlink(missing_ok=True)
