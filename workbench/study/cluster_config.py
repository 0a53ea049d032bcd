"""Job resources of a batch-scheduler run (``workbench run --cluster slurm|pbs|sge|lsf``), validated.

The resources of the worker jobs come from three places, later ones winning: the defaults here,
the ``[cluster]`` table of a user config file (``--cluster-config FILE``, else
``$XDG_CONFIG_HOME/workbench/cluster.toml`` = ``~/.config/workbench/cluster.toml`` when it exists)
with optional per-scheduler tables (``[cluster.slurm]``, ``[cluster.pbs]``, ... override the
common keys for that scheduler), and the command line (``--jobs``, ``--cores``, ...).  Every
problem is reported before anything is submitted, one line each, in the style of study files:
``<file>: cluster.<key>: <reason>`` or ``--<option>: <reason>`` (:class:`~workbench.study.messages.StudyError`).

Scaling: ``jobs = N`` keeps N worker jobs (a job that ends -- walltime, pre-emption, ``scancel``
-- is replaced); ``min_jobs`` / ``max_jobs`` let Dask's adaptive scaling choose between them.
Each job runs ``processes`` single-threaded Dask workers (default: one per core) that retire
``lifetime_margin`` seconds before the walltime, so a worker is not killed mid-case by the
scheduler in the normal course of things.  The key table is in ``docs/architecture.md``
("Scale-out on a batch scheduler").  Nothing here imports Dask.

Checked by ``tests/cluster/test_cluster_config.py`` (the corpus ``tests/cluster/bad_cluster_configs``).
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from .messages import StudyError, pydantic_problems, read_toml, suggest

__all__ = ["SCHEDULER_KINDS", "ClusterConfig", "ClusterSection", "default_config_path", "format_walltime",
           "load_cluster_config", "parse_memory", "parse_walltime", "resolve_cluster"]

#: The batch schedulers a run can submit its workers to (dask-jobqueue's clusters).
SCHEDULER_KINDS = ("slurm", "pbs", "sge", "lsf")

_CFG = ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)
_MEMORY = re.compile(r"^\s*(\d+(?:\.\d+)?)\s*([kKMGTP]i?B|B)\s*$")
_WALLTIME = re.compile(r"^(?:(\d+)-)?(\d+):([0-5]\d)(?::([0-5]\d))?$")
_UNIT = {"B": 1, "kB": 1e3, "KB": 1e3, "MB": 1e6, "GB": 1e9, "TB": 1e12, "PB": 1e15,
         "KiB": 2**10, "kiB": 2**10, "MiB": 2**20, "GiB": 2**30, "TiB": 2**40, "PiB": 2**50}


def parse_memory(text: str) -> int:
    """``"4GB"`` -> 4e9 bytes (decimal ``kB``..``PB`` and binary ``KiB``..``PiB`` units).

    Raises
    ------
    ValueError
        Not an amount of memory, or zero.
    """
    m = _MEMORY.match(text) if isinstance(text, str) else None
    if not m or m.group(2) not in _UNIT:
        raise ValueError(f"must be an amount of memory such as '4GB' or '500MB', got {text!r}")
    n = int(float(m.group(1)) * _UNIT[m.group(2)])
    if n <= 0:
        raise ValueError(f"must be > 0, got {text!r}")
    return n


def parse_walltime(text: str) -> int:
    """``"[D-]HH:MM[:SS]"`` -> seconds (``"01:30:00"`` -> 5400, ``"2-00:00"`` -> 172800).

    Raises
    ------
    ValueError
        Not a walltime, or zero.
    """
    m = _WALLTIME.match(text) if isinstance(text, str) else None
    if not m:
        raise ValueError(f"must be a walltime '[D-]HH:MM:SS' such as '01:00:00', got {text!r}")
    d, h, mi, s = (int(g) if g else 0 for g in m.groups())
    total = ((d * 24 + h) * 60 + mi) * 60 + s
    if total <= 0:
        raise ValueError(f"must be > 0, got {text!r}")
    return total


def format_walltime(seconds: int, scheduler: str) -> str:
    """The walltime as the scheduler writes it: ``HH:MM:SS`` (LSF: ``HH:MM``, rounded down, >= 1 min)."""
    h, rest = divmod(int(seconds), 3600)
    m, s = divmod(rest, 60)
    if scheduler == "lsf":
        return f"{h:02d}:{max(m, 1 if h == 0 else 0):02d}"
    return f"{h:02d}:{m:02d}:{s:02d}"


class ClusterSection(BaseModel):
    """The keys of a ``[cluster]`` table (each also allowed in ``[cluster.<scheduler>]``)."""

    model_config = _CFG
    jobs: int | None = Field(default=None, ge=1, le=100_000)
    min_jobs: int | None = Field(default=None, ge=0, le=100_000)
    max_jobs: int | None = Field(default=None, ge=1, le=100_000)
    cores: int | None = Field(default=None, ge=1, le=4096)
    processes: int | None = Field(default=None, ge=1, le=4096)
    memory: str | None = None
    walltime: str | None = None
    queue: str | None = Field(default=None, min_length=1)
    account: str | None = Field(default=None, min_length=1)
    job_name: str | None = Field(default=None, pattern=r"^[A-Za-z0-9_.-]+$", max_length=64)
    job_extra: list[str] | None = None
    prologue: list[str] | None = None
    interface: str | None = Field(default=None, min_length=1)
    local_directory: str | None = Field(default=None, min_length=1)
    log_directory: str | None = Field(default=None, min_length=1)
    python: str | None = Field(default=None, min_length=1)
    queue_timeout: float | None = Field(default=None, gt=0)
    lifetime_margin: float | None = Field(default=None, ge=0)
    allowed_failures: int | None = Field(default=None, ge=0, le=10)

    @field_validator("memory")
    @classmethod
    def _memory(cls, v: str | None) -> str | None:
        if v is not None:
            parse_memory(v)
        return v

    @field_validator("walltime")
    @classmethod
    def _walltime(cls, v: str | None) -> str | None:
        if v is not None:
            parse_walltime(v)
        return v


#: Defaults of the keys a run always has (memory: 2 GB per core).
DEFAULTS: dict[str, Any] = {"cores": 1, "walltime": "01:00:00", "job_name": "workbench", "job_extra": [],
                            "prologue": [], "queue_timeout": 600.0, "lifetime_margin": 300.0,
                            "allowed_failures": 2}
_SCALING = ("jobs", "min_jobs", "max_jobs")


@dataclass(frozen=True)
class ClusterConfig:
    """The resolved resources of one batch-scheduler run (see the module docstring).

    Attributes
    ----------
    scheduler : str
        One of :data:`SCHEDULER_KINDS`.
    min_jobs, max_jobs : int
        Worker jobs kept between (equal: a fixed number, a lost job replaced).
    cores, processes : int
        Cores per job; single-threaded Dask worker processes per job.
    memory : str
        Memory per job as written (``"4GB"``); ``memory_bytes`` the same in bytes.
    walltime_seconds : int
        Walltime per job [s].
    queue, account : str or None
        Queue (SLURM: partition) and account (SGE / LSF: project).
    queue_timeout : float
        [s] the run ends with a one-line error when no worker has joined for this long.
    lifetime_margin : float
        [s] workers retire this long before the walltime.
    allowed_failures : int
        Lost workers (pre-emption, walltime, node failure) a task survives before its cases are
        recorded as failed.
    source : str or None
        The config file read (``None``: command line and defaults only).
    """

    scheduler: str
    min_jobs: int
    max_jobs: int
    cores: int
    processes: int
    memory: str
    memory_bytes: int
    walltime_seconds: int
    queue: str | None
    account: str | None
    job_name: str
    job_extra: tuple[str, ...]
    prologue: tuple[str, ...]
    interface: str | None
    local_directory: str | None
    log_directory: str | None
    python: str | None
    queue_timeout: float
    lifetime_margin: float
    allowed_failures: int
    source: str | None = None

    @property
    def adaptive(self) -> bool:
        """Whether Dask chooses the job count (``min_jobs < max_jobs``)."""
        return self.min_jobs < self.max_jobs

    @property
    def walltime(self) -> str:
        """The walltime as the scheduler receives it."""
        return format_walltime(self.walltime_seconds, self.scheduler)

    @property
    def worker_lifetime(self) -> float:
        """[s] how long a worker serves before it retires (walltime minus the margin)."""
        return self.walltime_seconds - self.lifetime_margin

    def describe(self) -> str:
        """One line: scheduler, job count, resources (recorded as the run's executor)."""
        jobs = f"{self.min_jobs}-{self.max_jobs} jobs (adaptive)" if self.adaptive else f"{self.max_jobs} job(s)"
        where = "".join(f", {k} {v}" for k, v in (("queue", self.queue), ("account", self.account)) if v)
        return (f"dask-jobqueue {self.scheduler}: {jobs} x {self.cores} core(s), {self.processes} worker(s), "
                f"{self.memory}, walltime {self.walltime}{where}")


def default_config_path() -> Path:
    """``$XDG_CONFIG_HOME/workbench/cluster.toml`` (``~/.config/workbench/cluster.toml``)."""
    base = os.environ.get("XDG_CONFIG_HOME") or os.path.join(os.path.expanduser("~"), ".config")
    return Path(base) / "workbench" / "cluster.toml"


def load_cluster_config(path: str | Path) -> dict[str, Any]:
    """The ``[cluster]`` table of a user config file (``{}`` without one).

    Raises
    ------
    StudyError
        The file cannot be read, is not TOML, or has keys outside ``[cluster]``.
    """
    raw = read_toml(path)
    extra = [k for k in raw if k != "cluster"]
    if extra:
        raise StudyError([f"{path}: {k}: unknown section; a cluster config file holds only [cluster]"
                          f"{suggest(k, ['cluster'])}" for k in extra])
    table = raw.get("cluster", {})
    if not isinstance(table, dict):
        raise StudyError([f"{path}: cluster: must be a table [cluster], got {type(table).__name__}"])
    return table


def _check_table(table: Mapping[str, Any], where: str, prefix: tuple, bad: set[str]) -> tuple[dict[str, Any], list[str]]:
    """Validate one table key by key (common keys or a scheduler's); ``(valid keys, problems)``.

    Key by key, so every bad key is reported (and added to ``bad``) and the good ones still take
    part in the checks between keys.
    """
    values, problems = {}, []
    for key, val in table.items():
        try:
            values.update(ClusterSection.model_validate({key: val}).model_dump(exclude_unset=True))
        except ValidationError as e:
            problems += [f"{where}{p}" for p in pydantic_problems(e, prefix, ClusterSection)]
            bad.add(key)
    return values, problems


def _file_values(table: Mapping[str, Any], path: str, scheduler: str,
                 bad: set[str]) -> tuple[dict[str, Any], list[str]]:
    common = {k: v for k, v in table.items() if k not in SCHEDULER_KINDS}
    values, problems = _check_table(common, f"{path}: ", ("cluster",), bad)
    for kind in SCHEDULER_KINDS:
        sub = table.get(kind)
        if sub is None:
            continue
        if not isinstance(sub, dict):
            problems.append(f"{path}: cluster.{kind}: must be a table [cluster.{kind}], got {type(sub).__name__}")
            continue
        own, p = _check_table(sub, f"{path}: ", ("cluster", kind), bad)
        problems += p
        if kind == scheduler:
            if any(k in own for k in _SCALING):
                values = {k: v for k, v in values.items() if k not in _SCALING}
            values.update(own)
    return values, problems


def _cli_values(overrides: Mapping[str, Any], bad: set[str]) -> tuple[dict[str, Any], list[str]]:
    given = {k: v for k, v in overrides.items() if v is not None}
    values, problems = _check_table(given, "", (), bad)
    # "cores: must be >= 1, got 0" -> "--cores: must be >= 1, got 0"
    return values, [re.sub(r"^(\w+)", lambda m: "--" + m.group(1).replace("_", "-"), p) for p in problems]


def _cross_checks(v: Mapping[str, Any], where: Mapping[str, str], bad: set[str]) -> list[str]:
    """Checks between keys; ``where[key]`` names the place a key was given; keys in ``bad`` already failed."""
    out = []
    if {"cores", "processes", "walltime", "lifetime_margin", "min_jobs", "max_jobs", "jobs"} & bad:
        return out
    if v.get("jobs") is not None and (v.get("min_jobs") is not None or v.get("max_jobs") is not None):
        out.append(f"{where['jobs']}: give either jobs (a fixed number) or min_jobs/max_jobs (adaptive), not both")
    lo, hi = v.get("min_jobs"), v.get("max_jobs")
    if lo is not None and hi is not None and lo > hi:
        out.append(f"{where['min_jobs']}: must be <= max_jobs ({hi}), got {lo}")
    if v.get("processes") is not None and v["processes"] > v["cores"]:
        out.append(f"{where['processes']}: must be <= cores ({v['cores']}): each worker process is "
                   f"single-threaded, got {v['processes']}")
    wall = parse_walltime(v["walltime"])
    if v["lifetime_margin"] >= wall:
        out.append(f"{where['lifetime_margin']}: must be < the walltime ({wall} s), got {v['lifetime_margin']:g} s")
    return out


def resolve_cluster(scheduler: str, file_table: Mapping[str, Any] | None = None, file_path: str | None = None,
                    overrides: Mapping[str, Any] | None = None) -> ClusterConfig:
    """Defaults, then the file's ``[cluster]`` (and ``[cluster.<scheduler>]``), then the command line.

    Parameters
    ----------
    scheduler : str
        One of :data:`SCHEDULER_KINDS`.
    file_table : dict, optional
        What :func:`load_cluster_config` returned; ``file_path`` names it in messages.
    overrides : dict, optional
        Command-line values by key (``None`` = not given).  Any of ``jobs`` / ``min_jobs`` /
        ``max_jobs`` given here replaces the file's scaling keys as a whole.

    Raises
    ------
    StudyError
        Every problem, one line each (file problems name the file and ``cluster.<key>``,
        command-line problems the option).
    """
    if scheduler not in SCHEDULER_KINDS:
        raise StudyError([f"--cluster: must be one of {', '.join(SCHEDULER_KINDS)}, got {scheduler!r}"])
    path = str(file_path) if file_path else "<cluster config>"
    bad: set[str] = set()
    from_file, problems = _file_values(file_table or {}, path, scheduler, bad)
    from_cli, p = _cli_values(overrides or {}, bad)
    problems += p
    if any(k in from_cli for k in _SCALING):
        from_file = {k: v for k, v in from_file.items() if k not in _SCALING}
    v = {**DEFAULTS, **from_file, **from_cli}
    where = {k: (f"--{k.replace('_', '-')}" if k in from_cli else f"{path}: cluster.{k}") for k in v}
    where.update({k: f"--{k.replace('_', '-')}" for k in _SCALING + ("processes",) if k not in where})
    problems += _cross_checks(v, where, bad)
    if problems:
        raise StudyError(problems)
    lo, hi = v.get("min_jobs"), v.get("max_jobs")
    if v.get("jobs") is not None:
        lo = hi = v["jobs"]
    elif hi is None:
        lo, hi = (1, 1) if lo is None else (lo, max(lo, 1))
    elif lo is None:
        lo = min(1, hi)
    memory = v.get("memory") or f"{2 * v['cores']}GB"
    return ClusterConfig(
        scheduler=scheduler, min_jobs=lo, max_jobs=hi, cores=v["cores"], processes=v.get("processes") or v["cores"],
        memory=memory, memory_bytes=parse_memory(memory), walltime_seconds=parse_walltime(v["walltime"]),
        queue=v.get("queue"), account=v.get("account"), job_name=v["job_name"], job_extra=tuple(v["job_extra"]),
        prologue=tuple(v["prologue"]), interface=v.get("interface"), local_directory=v.get("local_directory"),
        log_directory=v.get("log_directory"), python=v.get("python"), queue_timeout=float(v["queue_timeout"]),
        lifetime_margin=float(v["lifetime_margin"]), allowed_failures=v["allowed_failures"],
        source=str(file_path) if file_path else None)
