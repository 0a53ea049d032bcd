"""The ``--cluster`` options of ``workbench run`` and its ``--dry-run``.

::

    workbench run STUDY --cluster slurm|pbs|sge|lsf [--jobs N | --min-jobs N --max-jobs M]
        [--cores N] [--processes N] [--memory 4GB] [--walltime HH:MM:SS] [--queue NAME]
        [--account NAME] [--queue-timeout S] [--cluster-config FILE] [--dry-run]

:func:`add_cluster_arguments` adds them to the ``run`` parser (``--cluster`` joins the executor
choices), :func:`cluster_from_args` resolves them with the user config file
(:func:`~workbench.study.cluster_config.resolve_cluster`) and :func:`dry_run_text` is what
``--dry-run`` prints: the plan and the job script, nothing written, nothing submitted.

Checked by ``tests/cluster/test_cluster_cli.py``.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any, Sequence

from .cluster_config import SCHEDULER_KINDS, ClusterConfig, default_config_path, load_cluster_config, resolve_cluster

__all__ = ["CLUSTER_OPTIONS", "add_cluster_arguments", "cluster_from_args", "dry_run_text"]

#: ``[cluster]`` keys that have a command-line option (``--min-jobs`` for ``min_jobs``, ...).
CLUSTER_OPTIONS = {
    "jobs": (int, "N", "keep N worker jobs (a job that ends is replaced)"),
    "min_jobs": (int, "N", "adaptive scaling: at least N worker jobs"),
    "max_jobs": (int, "N", "adaptive scaling: at most N worker jobs"),
    "cores": (int, "N", "cores per job (default 1)"),
    "processes": (int, "N", "single-threaded worker processes per job (default: one per core)"),
    "memory": (str, "SIZE", "memory per job, e.g. 4GB (default 2GB per core)"),
    "walltime": (str, "HH:MM:SS", "walltime per job (default 01:00:00)"),
    "queue": (str, "NAME", "queue (SLURM: partition)"),
    "account": (str, "NAME", "account to charge (SGE, LSF: project)"),
    "queue_timeout": (float, "S", "end the run when no worker has joined for S seconds (default 600)"),
}


def add_cluster_arguments(run: argparse.ArgumentParser, executors: Any) -> None:
    """Add ``--cluster`` to the mutually exclusive ``executors`` group and the job options to ``run``."""
    executors.add_argument("--cluster", choices=SCHEDULER_KINDS, metavar="KIND",
                           help=f"workers as batch jobs via dask-jobqueue ({', '.join(SCHEDULER_KINDS)})")
    g = run.add_argument_group("batch scheduler (with --cluster; defaults from the [cluster] table of "
                               "--cluster-config or ~/.config/workbench/cluster.toml)")
    for key, (typ, metavar, text) in CLUSTER_OPTIONS.items():
        flag = "--" + key.replace("_", "-")
        g.add_argument(flag, dest=f"cluster_{key}", type=typ, metavar=metavar, help=text)
    g.add_argument("--partition", dest="cluster_queue", metavar="NAME", help=argparse.SUPPRESS)
    g.add_argument("--cluster-config", metavar="FILE", help="user config file with a [cluster] table")
    run.add_argument("--dry-run", action="store_true",
                     help="validate, print the plan (and with --cluster the job script); run nothing")


def _given(args: argparse.Namespace) -> dict[str, Any]:
    return {k: getattr(args, f"cluster_{k}", None) for k in CLUSTER_OPTIONS}


def cluster_from_args(args: argparse.Namespace) -> ClusterConfig | None:
    """The resolved cluster of ``args`` (``None`` without ``--cluster``).

    Raises
    ------
    StudyError
        Job options without ``--cluster``, an unreadable config file, any bad value (one line each).
    """
    from .messages import StudyError

    given = {k: v for k, v in _given(args).items() if v is not None}
    if getattr(args, "cluster", None) is None:
        flags = [f"--{k.replace('_', '-')}" for k in given]
        if getattr(args, "cluster_config", None):
            flags.append("--cluster-config")
        if flags:
            raise StudyError([f"{flags[0]}: only with --cluster {'|'.join(SCHEDULER_KINDS)}"])
        return None
    path: Path | None = Path(args.cluster_config) if args.cluster_config else default_config_path()
    if args.cluster_config is None and not path.is_file():
        path = None
    table = load_cluster_config(path) if path is not None else {}
    return resolve_cluster(args.cluster, table, str(path) if path else None, given)


def dry_run_text(study_name: str, n_cases: int, models: Sequence[str], folder: Path, executor_name: str,
                 cluster: ClusterConfig | None, limits=None, chunk: int = 1) -> str:
    """What ``--dry-run`` prints: the plan, and with a cluster its config source, case limit and job script.

    ``limits``: the study's :class:`~workbench.study.outcomes.CaseLimits` and ``chunk`` the cases per
    task the runner would choose (shown, and for a cluster as
    :func:`~workbench.study.cluster.cluster_limits` adapts them to a worker's life).
    """
    lines = [f"dry run: study {study_name!r}, {n_cases} cases x {len(models)} models ({', '.join(models)})",
             f"  output folder: {folder}", f"  executor: {executor_name}"]
    if limits is not None:
        lines.append(f"  per case: {limits.describe()}")
    if cluster is not None:
        from .cluster import PLACEHOLDER_ADDRESS, cluster_limits, job_script

        if limits is not None:
            _, _, note = cluster_limits(cluster, limits, chunk)
            if note:
                lines.append(f"  on this cluster: {note}")

        lines += [f"  cluster config: {cluster.source or '(none: command line and defaults)'}",
                  f"  workers retire {cluster.lifetime_margin:g} s before the walltime; no worker for "
                  f"{cluster.queue_timeout:g} s ends the run; a task survives {cluster.allowed_failures} lost worker(s)",
                  f"  job script ({PLACEHOLDER_ADDRESS} is the address of this run's scheduler):", ""]
        lines.append(job_script(cluster).rstrip())
    lines.append("nothing was run or submitted (--dry-run)")
    return "\n".join(lines)
