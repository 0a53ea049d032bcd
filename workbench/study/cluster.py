"""Dask workers as batch jobs through dask-jobqueue: the job script and the executor of ``--cluster``.

:func:`job_script` is the script the batch scheduler receives for one worker job (``workbench run
--cluster slurm --dry-run`` prints it); :class:`JobQueueExecutor` is a
:class:`~workbench.study.executors.DaskExecutor` whose workers are batch jobs: it starts the
dask-jobqueue cluster (``SLURMCluster``, ``PBSCluster``, ``SGECluster``, ``LSFCluster``) in this
process, keeps ``min_jobs``..``max_jobs`` jobs with Dask's adaptive scaling (a job that ends is
replaced), and waits at most ``queue_timeout`` seconds for workers.

Failure semantics (``docs/architecture.md``, "Scale-out on a batch scheduler"): rows are stored as
cases finish, in this process, so a job that ends loses only the cases it was running; Dask
reruns those on other workers (``allowed_failures`` lost workers per task); workers retire
``lifetime_margin`` seconds before their walltime, and a case that would outlive a worker is
stopped by the per-case limit (``[solver] max_case_seconds``, at most half a worker's life, and
tasks no longer than that: :func:`cluster_limits`); a queue that starts no job, or a cluster left without
workers for ``queue_timeout``, ends the run with one line (:class:`ClusterError`, exit 3) and the
jobs cancelled.  A job SLURM refuses (``sbatch --test-only``: bad partition, account, ...) is
:class:`ClusterRefused` (exit 2, nothing ran); on other schedulers a refused submission ends the
run as soon as it happens, with the scheduler's own message.

Checked by ``tests/cluster/test_job_scripts.py`` (scripts of every scheduler) and
``tests/cluster/test_slurm.py`` (a real single-node SLURM, a worker job cancelled mid-run).
"""

from __future__ import annotations

import logging
import os
import shlex
import shutil
import signal
import subprocess
import sys
import time
from typing import Any

from .cluster_config import ClusterConfig
from .executors import DaskExecutor
from .outcomes import CaseLimits, ExecutorStartError, InfrastructureError

__all__ = ["ClusterError", "ClusterRefused", "JobQueueExecutor", "PLACEHOLDER_ADDRESS", "cluster_class",
           "cluster_limits", "job_kwargs", "job_script"]

#: The scheduler address in a dry run's job script (the real one exists only once the run starts).
PLACEHOLDER_ADDRESS = "tcp://SCHEDULER-ADDRESS:PORT"

_CLASSES = {"slurm": "SLURMCluster", "pbs": "PBSCluster", "sge": "SGECluster", "lsf": "LSFCluster"}
_ACCOUNT_KEY = {"slurm": "account", "pbs": "account", "sge": "project", "lsf": "project"}
_SUBMIT = {"slurm": "sbatch", "pbs": "qsub", "sge": "qsub", "lsf": "bsub"}
_LOGGERS = ("distributed.deploy.spec", "distributed.deploy.adaptive", "distributed.deploy.adaptive_core",
            "dask_jobqueue", "distributed.utils", "asyncio", "tornado.application")


class ClusterError(InfrastructureError):
    """The batch system failed the run (not a case): one line, e.g. a queue that starts no job (exit 3)."""


class ClusterRefused(ExecutorStartError):
    """The batch system refuses the job (bad partition, account, no submit command): nothing ran (exit 2)."""


def cluster_class(scheduler: str):
    """The dask-jobqueue cluster class of ``scheduler`` (``SLURMCluster``, ...).

    The only place dask-jobqueue is imported (by the job script of a dry run or a SLURM preflight, and
    by :class:`JobQueueExecutor` when it starts the cluster), through :func:`_import_jobqueue`, so the
    process's Ctrl-C behaviour stays as it was.
    """
    return getattr(_import_jobqueue(), _CLASSES[scheduler])


def _import_jobqueue():
    """The ``dask_jobqueue`` package, imported with the process's SIGINT handler kept.

    dask-jobqueue's ``runner`` module (imported by the package, 0.8-0.9) installs
    ``signal.signal(SIGINT, lambda *_: sys.exit())`` at import: a Ctrl-C then raises ``SystemExit``
    in whatever runs (under pytest it fails the running test and the suite carries on) instead of
    ``KeyboardInterrupt``.  The handler found before the import is put back right after it.
    Checked by ``tests/cluster/test_sigint.py``.
    """
    previous = signal.getsignal(signal.SIGINT)
    try:
        import dask_jobqueue
    finally:
        if previous is not None and signal.getsignal(signal.SIGINT) is not previous:
            signal.signal(signal.SIGINT, previous)
    return dask_jobqueue


def job_kwargs(cfg: ClusterConfig) -> dict[str, Any]:
    """Keyword arguments of the dask-jobqueue cluster (and job) class for ``cfg``.

    One thread per worker process (the models are single-threaded, as in the local executors);
    workers retire ``cfg.lifetime_margin`` before the walltime (``--lifetime``, staggered by at
    most 60 s); a ``PYTHONPATH`` of this process is exported in the script so the workers import
    the same workbench.  Keys not given here come from dask-jobqueue's own configuration
    (``~/.config/dask/jobqueue.yaml``), as in any dask-jobqueue deployment.
    """
    prologue = list(cfg.prologue)
    if os.environ.get("PYTHONPATH"):
        prologue.append(f"export PYTHONPATH={shlex.quote(os.environ['PYTHONPATH'])}")
    extra_args: list[str] = []
    if cfg.lifetime_margin > 0:
        extra_args = ["--lifetime", f"{int(cfg.worker_lifetime)}s", "--lifetime-stagger", f"{int(_stagger(cfg))}s"]
    kw: dict[str, Any] = {
        "cores": cfg.cores, "processes": cfg.processes, "memory": cfg.memory, "walltime": cfg.walltime,
        "queue": cfg.queue, "job_name": cfg.job_name, "job_extra_directives": list(cfg.job_extra),
        "job_script_prologue": prologue, "worker_extra_args": extra_args, "interface": cfg.interface,
        "local_directory": cfg.local_directory, "log_directory": cfg.log_directory,
        "python": cfg.python or sys.executable, "death_timeout": 60,
    }
    if cfg.account is not None:
        kw[_ACCOUNT_KEY[cfg.scheduler]] = cfg.account
    return kw


def job_script(cfg: ClusterConfig, scheduler_address: str = PLACEHOLDER_ADDRESS) -> str:
    """The batch script of one worker job (what ``sbatch`` / ``qsub`` / ``bsub`` receives).

    Built by dask-jobqueue's job class from :func:`job_kwargs`, so it is the script a run
    submits for its first job (``<job_name>-0``; later jobs count up), with ``scheduler_address``
    in place of the address the run's scheduler gets.  Nothing is started or submitted.
    """
    job_cls = cluster_class(cfg.scheduler).job_cls
    kw = job_kwargs(cfg)
    if cfg.scheduler == "lsf":
        kw.setdefault("lsf_units", None)
    return job_cls(scheduler=scheduler_address, name=f"{cfg.job_name}-0", **kw).job_script()


def _stagger(cfg: ClusterConfig) -> float:
    """[s] by which a worker's lifetime is staggered (``--lifetime-stagger``; 0 without a margin)."""
    return float(int(min(60.0, cfg.lifetime_margin / 4))) if cfg.lifetime_margin > 0 else 0.0


def cluster_limits(cfg: ClusterConfig, limits: CaseLimits, chunk_size: int) -> tuple[CaseLimits, int, str]:
    """The per-case limit and cases per task a batch-job worker can finish: ``(limits, chunk, note)``.

    A worker lives at least ``life = walltime - lifetime_margin - stagger`` seconds.  A case still
    running when its worker retires is rerun elsewhere, and Dask does not count that as a failure,
    so a case (or a task of several) that cannot end within a worker's life would be rerun for
    ever.  Hence the case limit is at most ``life / 2`` -- a case started in the first half of a
    worker's life ends or is stopped by the limit (stored ``failure = "timeout"``) before the worker
    retires -- and a task holds at most ``(life / 2) // limit`` cases.  ``note`` says what changed
    ("" when nothing did).  Checked by ``tests/cluster/test_cluster_limits.py`` and
    ``tests/cluster/test_slurm.py::test_a_case_longer_than_a_worker_life_is_stopped_by_the_case_limit``.
    """
    usable = max(1.0, float(int(cfg.worker_lifetime)) - _stagger(cfg)) / 2
    seconds = limits.seconds if limits.seconds is not None else float("inf")
    notes = []
    if seconds > usable:
        notes.append(f"max_case_seconds = {'none' if limits.seconds is None else f'{seconds:g} s'} is more than half "
                     f"a worker's life ({2 * usable:g} s: walltime {cfg.walltime} - lifetime_margin "
                     f"{cfg.lifetime_margin:g} s - stagger {_stagger(cfg):g} s): cases are stopped after {usable:g} s")
        seconds = usable
    chunk = max(1, min(int(chunk_size), int(usable // seconds)))
    if chunk < chunk_size:
        notes.append(f"{chunk} case(s) per task instead of {chunk_size} (a task must end within half a worker's "
                     f"life; a smaller max_case_seconds allows more)")
    return CaseLimits(seconds, limits.memory), chunk, "; ".join(notes)


class _Errors(logging.Handler):
    """Collects the error records dask-jobqueue's background submission logs (a refused job)."""

    def __init__(self) -> None:
        super().__init__(logging.ERROR)
        self.lines: list[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        exc = record.exc_info[1] if record.exc_info else None
        text = str(exc) if exc is not None else record.getMessage()
        self.lines.append(text)


def _refusal(text: str) -> str:
    """The scheduler's own words from a dask-jobqueue submission error (its stderr), one line."""
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    if "stderr:" in lines:
        tail = lines[lines.index("stderr:") + 1:]
        if tail:
            return " ".join(tail)[:300]
    return " ".join(lines)[:300]


def _job_of(worker_name: str, job_names: set[str]) -> str | None:
    """The job a worker belongs to: ``name`` (one process per job) or ``name-<i>`` (several)."""
    if worker_name in job_names:
        return worker_name
    head, _, tail = worker_name.rpartition("-")
    return head if tail.isdigit() and head in job_names else None


class _JobKeeper:
    """Replaces the cluster's ended jobs (walltime, pre-emption, ``scancel``), on the cluster's event loop.

    Dask's adaptive scaling keeps a job in its plan after the job's workers are gone (it then
    counts as running), so a fixed-size cluster would never be topped up again (dask-jobqueue
    issue 611).  Every ``interval`` seconds this forgets jobs whose workers had joined and have
    all left, and asks the cluster to start what its plan lacks.
    """

    def __init__(self, cluster, log, interval: float = 2.0) -> None:
        self.cluster, self.log = cluster, log
        self.joined: set[str] = set()
        self.replaced = 0
        from tornado.ioloop import PeriodicCallback

        self._pc = PeriodicCallback(self._check, interval * 1000)
        cluster.loop.add_callback(self._pc.start)

    def stop(self) -> None:
        self.cluster.loop.add_callback(self._pc.stop)

    async def _check(self) -> None:
        c = self.cluster
        jobs = dict(c.workers)
        present = {_job_of(str(w["name"]), set(map(str, jobs))) for w in c.scheduler_info["workers"].values()}
        ended = []
        for name, job in jobs.items():
            if str(name) in present:
                self.joined.add(str(name))
            elif str(name) in self.joined:
                ended.append((name, job))
        for name, job in ended:
            self.joined.discard(str(name))
            c.workers.pop(name, None)
            await job.close()  # cancels it if the batch system still has it
            self.log(f"cluster: job {job.job_id} ({name}) ended; a replacement is submitted")
        if ended or set(c.worker_spec) - set(c.workers):
            self.replaced += len(ended)
            c.scale(jobs=len(c.worker_spec))  # the plan is unchanged: this only starts what is missing


class JobQueueExecutor(DaskExecutor):
    """Dask workers submitted as batch jobs (see the module docstring).

    Parameters
    ----------
    config : ClusterConfig
        Resources, scaling, timeouts (:func:`~workbench.study.cluster_config.resolve_cluster`).
    log : callable, optional
        ``log(line)`` for progress lines (default: print to stderr).
    """

    def __init__(self, config: ClusterConfig, log=None) -> None:
        super().__init__(allowed_failures=config.allowed_failures, lost_timeout=config.queue_timeout,
                         cluster=self._make_cluster)
        self.config = config
        self.name = config.describe()
        self._log = log or (lambda line: print(line, file=sys.stderr, flush=True))
        self._errors = _Errors()
        self._keeper = None
        self._preflight_done = False

    @property
    def slots(self) -> int:
        """Worker processes at full scale (``max_jobs * processes``; for batch sizing)."""
        return self.config.max_jobs * self.config.processes

    def preflight(self) -> None:
        """Fail fast, before anything is written: the submit command exists; SLURM accepts the job.

        SLURM: ``sbatch --test-only`` of the job script, so a bad partition, account or resource
        request ends the run in one line with the scheduler's own reason.  Called on entry when
        the caller has not (the CLI calls it before the result folder is created).

        Raises
        ------
        ClusterRefused
        """
        cfg = self.config
        submit = _SUBMIT[cfg.scheduler]
        if shutil.which(submit) is None:
            raise ClusterRefused(f"--cluster {cfg.scheduler}: {submit!r} not found on PATH (run on a login node "
                               f"of the {cfg.scheduler.upper()} cluster)")
        if cfg.scheduler == "slurm":
            _sbatch_test_only(job_script(cfg))
        self._preflight_done = True

    def _make_cluster(self):
        cfg = self.config
        cls = cluster_class(cfg.scheduler)
        # no dashboard (its HTTP server on a free local port: no clash with another run's 8787)
        cluster = cls(**job_kwargs(cfg), name=cfg.job_name, silence_logs=logging.CRITICAL,
                      scheduler_options={"dashboard": False, "dashboard_address": "127.0.0.1:0"})
        cluster.adapt(minimum_jobs=cfg.min_jobs, maximum_jobs=cfg.max_jobs)
        self._keeper = _JobKeeper(cluster, self._log)
        return cluster

    def __enter__(self) -> "JobQueueExecutor":
        if not self._preflight_done:
            self.preflight()  # before Dask starts: a refusal is ClusterRefused, not a start error
        for name in _LOGGERS:
            logging.getLogger(name).addHandler(self._errors)
        try:
            super().__enter__()
            self._wait_for_first_worker()
        except BaseException:
            self.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc: Any) -> None:
        try:
            if self._keeper is not None:
                self._keeper.stop()
                self._keeper = None
            if self._cluster is not None:
                from distributed.core import Status

                for job in list(self._cluster.workers.values()):
                    if job.status == Status.created:  # its submission failed (refused): nothing to cancel
                        job.status = Status.failed
            super().__exit__(*exc)  # closes the cluster: cancels its jobs
        except Exception as e:  # noqa: BLE001 - do not hide the error that ended the run
            self._log(f"cluster: closing the cluster failed: {type(e).__name__}: {e}")
            self._client = self._cluster = None
            if self._cfg is not None:
                self._cfg.__exit__(None, None, None)
                self._cfg = None
        finally:
            for name in _LOGGERS:
                logging.getLogger(name).removeHandler(self._errors)

    def job_ids(self) -> list[str]:
        """The batch-system ids of the cluster's current jobs (submitted, not yet ended)."""
        if self._cluster is None:
            return []
        return [str(j.job_id) for j in list(self._cluster.workers.values()) if getattr(j, "job_id", None)]

    def _check_refused(self, error=ClusterError) -> None:
        refused = [ln for ln in self._errors.lines if "exit code" in ln.lower() or "error" in ln.lower()]
        if refused:
            raise error(f"--cluster {self.config.scheduler}: a worker job was refused: {_refusal(refused[0])}")

    def _wait_for_first_worker(self) -> None:
        cfg = self.config
        self._log(f"cluster: {cfg.describe()}; waiting for the first worker (at most {cfg.queue_timeout:g} s)")
        t0 = time.monotonic()
        while not self._client.scheduler_info().get("workers"):
            self._check_refused(ClusterRefused)  # the first job refused: nothing ran (exit 2)
            if time.monotonic() - t0 > cfg.queue_timeout:
                state = _queue_state(cfg.scheduler, self.job_ids())
                raise ClusterError(
                    f"--cluster {cfg.scheduler}: no worker job started within {cfg.queue_timeout:g} s"
                    f"{f' ({state})' if state else ''}; its jobs were cancelled (wait longer: --queue-timeout)")
            time.sleep(0.5)
        self._log(f"cluster: first worker after {time.monotonic() - t0:.1f} s (jobs {', '.join(self.job_ids())})")

    def imap_unordered(self, fn, payloads, limits: CaseLimits = CaseLimits(), chunk_size: int = 1,
                       max_chunk: int | None = None):
        """As :meth:`DaskExecutor.imap_unordered`, with the case limit and task size a worker's life allows.

        (:func:`cluster_limits`; what changed is logged once.)  A cluster left without workers for
        ``queue_timeout`` raises :class:`ClusterError` naming the jobs' state.
        """
        limits, chunk_size, note = cluster_limits(self.config, limits, chunk_size)
        if note:
            self._log(f"cluster: {note}")
        if max_chunk is not None:  # adaptive chunks stay within a worker's life too
            max_chunk = cluster_limits(self.config, limits, max_chunk)[1]
        try:
            yield from super().imap_unordered(fn, payloads, limits, chunk_size, max_chunk)
        except InfrastructureError as e:
            if isinstance(e, ClusterError) or "no workers" not in str(e):
                raise
            state = _queue_state(self.config.scheduler, self.job_ids())
            raise ClusterError(f"--cluster {self.config.scheduler}: no worker for {self.config.queue_timeout:g} s"
                               f"{f' ({state})' if state else ''}; its jobs were cancelled") from None


def _sbatch_test_only(script: str) -> None:
    """``sbatch --test-only`` of ``script``: SLURM checks it (partition, account, resources), submits nothing."""
    import tempfile

    with tempfile.NamedTemporaryFile("w", suffix=".sh", delete=False) as f:
        f.write(script)
    try:
        r = subprocess.run(["sbatch", "--test-only", f.name], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise ClusterRefused(f"--cluster slurm: sbatch --test-only did not answer: {e}") from None
    finally:
        os.unlink(f.name)
    if r.returncode != 0:
        msg = " ".join((r.stderr or r.stdout).split())[:300]
        raise ClusterRefused(f"--cluster slurm: the job was refused: {msg}")


def _queue_state(scheduler: str, job_ids: list[str]) -> str:
    """What the scheduler says about ``job_ids`` (SLURM: ``squeue`` state and reason), best effort."""
    if not job_ids:
        return ""
    if scheduler != "slurm" or shutil.which("squeue") is None:
        return f"jobs {', '.join(job_ids)}"
    try:
        r = subprocess.run(["squeue", "-h", "-j", ",".join(job_ids), "-o", "%i %T %r"], capture_output=True,
                           text=True, timeout=20)
    except (OSError, subprocess.TimeoutExpired):
        return f"jobs {', '.join(job_ids)}"
    rows = [" ".join(ln.split()) for ln in r.stdout.splitlines() if ln.strip()]
    return "; ".join(f"job {row}" for row in rows) if rows else f"jobs {', '.join(job_ids)}"
