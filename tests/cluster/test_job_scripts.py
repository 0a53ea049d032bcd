"""The job script each supported batch scheduler receives (no scheduler needed: nothing is submitted)."""

from __future__ import annotations

import re
import sys

import pytest

from workbench.study.cluster import PLACEHOLDER_ADDRESS, cluster_class, job_kwargs, job_script
from workbench.study.cluster_config import resolve_cluster

OPTS = {"jobs": 3, "cores": 4, "memory": "16GB", "walltime": "02:30:00", "queue": "short", "account": "lab42"}
FILE = {"prologue": ["module load python/3.11"], "job_extra": [], "job_name": "sweep"}

#: (scheduler, the directive lines its script must hold for OPTS)
EXPECTED = {
    "slurm": ["#SBATCH -J sweep", "#SBATCH -p short", "#SBATCH -A lab42", "#SBATCH -n 1",
              "#SBATCH --cpus-per-task=4", "#SBATCH --mem=15G", "#SBATCH -t 02:30:00"],
    "pbs": ["#PBS -N sweep", "#PBS -q short", "#PBS -A lab42", "#PBS -l select=1:ncpus=4:mem=15GB",
            "#PBS -l walltime=02:30:00"],
    "sge": ["#$ -N sweep", "#$ -q short", "#$ -P lab42", "#$ -l h_rt=02:30:00", "#$ -cwd", "#$ -j y"],
    "lsf": ["#BSUB -J sweep", "#BSUB -q short", '#BSUB -P "lab42"', "#BSUB -n 4", '#BSUB -R "span[hosts=1]"',
            "#BSUB -M 16000", "#BSUB -W 02:30"],
}
EXTRA = {"slurm": "--qos=short", "pbs": "-m abe", "sge": "-pe smp 4", "lsf": "-x"}
PREFIX = {"slurm": "#SBATCH", "pbs": "#PBS", "sge": "#$", "lsf": "#BSUB"}


def _cfg(scheduler, **over):
    table = dict(FILE, job_extra=[EXTRA[scheduler]])
    if scheduler == "lsf":
        table["python"] = sys.executable
    return resolve_cluster(scheduler, table, "c.toml", {**OPTS, **over})


@pytest.mark.parametrize("scheduler", list(EXPECTED))
def test_job_script_of_each_scheduler(scheduler, monkeypatch):
    monkeypatch.setenv("PYTHONPATH", "/opt/wb")
    if scheduler == "lsf":
        monkeypatch.setenv("LSF_ENVDIR", "/nonexistent")  # no lsf.conf: dask-jobqueue's default unit (kB)
    text = job_script(_cfg(scheduler))
    lines = text.splitlines()
    assert lines[0] == "#!/usr/bin/env bash"
    for directive in EXPECTED[scheduler]:
        if scheduler == "lsf" and directive.startswith("#BSUB -M"):
            assert re.search(r"^#BSUB -M \d+$", text, re.M), text  # the unit depends on the site's lsf.conf
            continue
        assert directive in lines, f"{directive!r} missing from\n{text}"
    assert f"{PREFIX[scheduler]} {EXTRA[scheduler]}" in lines  # job_extra: the scheduler's own directives
    assert "module load python/3.11" in lines and "export PYTHONPATH=/opt/wb" in lines  # prologue, then the path
    worker = next(ln for ln in lines if "distributed.cli.dask_worker" in ln)
    assert worker.startswith(f"{sys.executable} -m distributed.cli.dask_worker {PLACEHOLDER_ADDRESS} ")
    # 4 single-threaded workers per job; they retire 300 s (the default margin) before the 9000 s walltime
    assert "--nthreads 1" in worker and "--nworkers 4" in worker and "--nanny" in worker
    assert "--lifetime 8700s --lifetime-stagger 60s" in worker
    assert "--death-timeout 60" in worker  # workers leave when the run's process is gone


def test_one_process_per_job_and_no_lifetime(monkeypatch):
    monkeypatch.delenv("PYTHONPATH", raising=False)
    cfg = resolve_cluster("slurm", {"lifetime_margin": 0}, "c.toml", {"cores": 2, "processes": 1})
    text = job_script(cfg, scheduler_address="tcp://10.0.0.1:8786")
    worker = next(ln for ln in text.splitlines() if "dask_worker" in ln)
    assert "tcp://10.0.0.1:8786" in worker and "--nworkers" not in worker and "--lifetime" not in worker
    assert "PYTHONPATH" not in text


def test_account_keyword_per_scheduler():
    assert job_kwargs(_cfg("slurm"))["account"] == "lab42"
    assert job_kwargs(_cfg("pbs"))["account"] == "lab42"
    assert job_kwargs(_cfg("sge"))["project"] == "lab42"
    assert job_kwargs(_cfg("lsf"))["project"] == "lab42"


@pytest.mark.parametrize("scheduler", ["slurm", "pbs"])
def test_dry_run_script_is_the_submitted_one(scheduler, monkeypatch):
    """The script dask-jobqueue's cluster would submit equals job_script() with the real address."""
    import logging

    monkeypatch.setenv("PYTHONPATH", "/opt/wb")
    cfg = _cfg(scheduler)
    cluster = cluster_class(scheduler)(**job_kwargs(cfg), name=cfg.job_name, silence_logs=logging.CRITICAL,
                                        scheduler_options={"dashboard": False, "dashboard_address": "127.0.0.1:0"})
    try:
        real = cluster.job_script()
        addr = cluster.scheduler_address
    finally:
        cluster.close()
    assert real.replace("--name dummy-name", f"--name {cfg.job_name}-0") == job_script(cfg, addr)
