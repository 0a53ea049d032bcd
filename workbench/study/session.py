"""The run session of one study run: manifest, run record, result store, progress bar, finish.

Every study kind runs through one :class:`RunSession` (:func:`workbench.study.runner.run_cases`):

1. :func:`open_run_manifest` continues (``resume``) or starts the folder's ``_manifest.json``
   (resolved spec, config hash, case count, package versions, git commit, runs) and refuses to
   mix runs of different studies;
2. the :class:`~workbench.study.store.ResultStore` is opened with every case's ``p.*``
   parameters (they fix the column types) and the cases already stored are skipped;
3. a run record (host, pid, platform, executor, start, cases to run) is appended; on resume the
   versions and git commit are refreshed to the code that continues the run;
4. :meth:`RunSession.record` stores the rows of finished cases and advances the progress bar;
5. :meth:`RunSession.close` (also on errors and interrupts: a ``with`` block) flushes the store,
   closes the bar and records the end and wall time, so an interrupted run leaves a consistent
   folder that ``--resume`` continues.

``open_run_manifest``, ``finish_run``, ``package_versions``, ``git_commit``, ``read_manifest``,
``_now`` and ``_write_manifest`` are re-exported by :mod:`workbench.study.runner` (their old home).

Checked by ``tests/study/test_store.py`` (resume, refusals), ``tests/study/test_cli.py`` and
``tests/study/test_session.py``.
"""

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
from typing import Any, Callable, Iterable, Mapping, Sequence

from .messages import StudyError
from .store import MANIFEST, ResultStore, SchemaMismatch, atomic_write_bytes

__all__ = ["RunSession", "finish_run", "git_commit", "open_run_manifest", "package_versions", "read_manifest",
           "study_name"]

_PACKAGES = ("trunk-workbench", "exudyn", "numpy", "scipy", "pandas", "pyarrow", "dask",
             "distributed", "dask-jobqueue", "pydantic", "tqdm")


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
    """The ``_manifest.json`` of a result folder."""
    return json.loads((Path(folder) / MANIFEST).read_text())


def study_name(manifest: Mapping[str, Any], default: Any = None) -> Any:
    """The study's name recorded in a manifest (``manifest["study"]["study"]["name"]``), else ``default``."""
    return ((manifest.get("study") or {}).get("study") or {}).get("name", default)


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
        name = study_name(old)
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


@dataclass
class RunSession:
    """One run of a study into a result folder (see the module docstring); use :meth:`open`.

    Attributes
    ----------
    folder : Path
    manifest : dict
        The folder's manifest (written at open and at close).
    run_rec : dict
        This run's record in ``manifest["runs"]``.
    store : ResultStore
    todo : list
        The cases of this run (those not stored yet), in expansion order.
    bar : tqdm or None
    t0 : float
        ``time.perf_counter()`` at the start.
    n_ok, n_failed : int
        Cases of this run whose rows are all ``ok`` / not all ``ok``.
    """

    folder: Path
    manifest: dict[str, Any]
    run_rec: dict[str, Any]
    store: ResultStore
    todo: list[Any]
    bar: Any = None
    t0: float = field(default_factory=time.perf_counter)
    n_ok: int = 0
    n_failed: int = 0

    @classmethod
    def open(cls, folder: str | Path, spec: Any, cases: Sequence[Any], param_rows: Iterable[Mapping[str, Any]],
             executor_name: str, *, resume: bool = False, progress: bool | None = None,
             flush_rows: int = 256, flush_seconds: float = 2.0) -> "RunSession":
        """Open (or continue) the run of ``cases`` of ``spec`` in ``folder``.

        Parameters
        ----------
        folder : path-like
        spec : object
            The validated study: ``path``, ``config_hash`` and ``resolved()`` are recorded.
        cases : sequence of Case
            Every case of the study (``case_id``, ``params``).
        param_rows : iterable of dict
            The flattened ``p.*`` parameters of every case (fix the column types).
        executor_name : str
            Recorded in the run record.
        resume, progress, flush_rows, flush_seconds
            See :func:`workbench.study.runner.run_cases`.

        Raises
        ------
        StudyError
            Folder/resume mismatch (:func:`open_run_manifest`).
        """
        folder = Path(folder)
        config_hash = spec.config_hash
        manifest = open_run_manifest(folder, config_hash, resume, lambda: {
            "study": spec.resolved(), "study_file": spec.path, "config_hash": config_hash,
            "n_cases": len(cases), "versions": package_versions(), "git": git_commit(), "runs": [],
        })
        folder.mkdir(parents=True, exist_ok=True)
        try:
            store = ResultStore(folder, param_rows, flush_rows, flush_seconds)
        except SchemaMismatch as e:
            raise StudyError([f"{folder}: --resume refused: {e} (the folder was written by another workbench "
                              f"version that recorded these parameters differently); use another --out"]) from None
        store.cleanup_temporaries()
        finished = store.finished_case_ids()
        todo = [c for c in cases if c.case_id not in finished]
        run_rec = {"host": socket.gethostname(), "pid": os.getpid(), "platform": platform.platform(),
                   "executor": executor_name, "start": _now(), "end": None, "cases_to_run": len(todo),
                   "cases_done": 0}
        manifest["runs"].append(run_rec)
        if resume:
            manifest["versions"] = package_versions()
            manifest["git"] = git_commit()
        _write_manifest(folder, manifest)
        show = progress if progress is not None else sys.stderr.isatty()
        session = cls(folder=folder, manifest=manifest, run_rec=run_rec, store=store, todo=todo)
        if todo and show:
            from tqdm import tqdm

            session.bar = tqdm(total=len(todo), unit="case", dynamic_ncols=True, file=sys.stderr)
        return session

    def record(self, rows_per_case: Iterable[list[dict[str, Any]]], n_cases: int) -> None:
        """Store the rows of ``n_cases`` finished cases (one row list per case)."""
        for rows in rows_per_case:
            self.store.add(rows)
            if all(r["status"] == "ok" for r in rows):
                self.n_ok += 1
            else:
                self.n_failed += 1
        self.run_rec["cases_done"] += n_cases
        if self.bar is not None:
            self.bar.set_postfix_str(f"ok={self.n_ok} failed={self.n_failed}", refresh=False)
            self.bar.update(n_cases)

    def close(self) -> None:
        """Flush the store, close the bar, record the end of the run (:func:`finish_run`)."""
        finish_run(self.folder, self.manifest, self.run_rec, self.store, self.bar, self.t0)

    def __enter__(self) -> "RunSession":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()
