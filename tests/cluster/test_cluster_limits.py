"""The per-case limit and task size a batch-job worker can finish (:func:`cluster_limits`), and the dry run showing them.

A worker lives ``walltime - lifetime_margin - stagger`` seconds at least (stagger: ``--lifetime-stagger``,
a quarter of the margin, at most 60 s, whole seconds).  Dask reruns the task of a worker that retired in
time without counting it as a failure, so a case or a task longer than that would be rerun for ever;
the limit is lowered to half a worker's life (a case started in the first half ends in time) and a task
holds no more cases than fit in that half.
"""

from __future__ import annotations

import pytest

from workbench.study.cluster import cluster_limits, job_kwargs
from workbench.study.cluster_config import resolve_cluster
from workbench.study.outcomes import CaseLimits


def _cfg(walltime: str, margin: float):
    return resolve_cluster("slurm", {"lifetime_margin": margin}, "c.toml", {"walltime": walltime})


def test_a_limit_within_a_worker_life_is_kept_and_tasks_fit_in_it():
    cfg = _cfg("01:00:00", 300)  # life 3600 - 300 - 60 = 3240 s, half of it 1620 s
    limits, chunk, note = cluster_limits(cfg, CaseLimits(50.0, 2e9), 32)
    assert (limits, chunk, note) == (CaseLimits(50.0, 2e9), 32, "")
    limits, chunk, note = cluster_limits(cfg, CaseLimits(600.0), 32)
    assert limits.seconds == 600.0 and chunk == 2  # 2 x 600 s <= 1620 s < 3 x 600 s
    assert note.startswith("2 case(s) per task instead of 32")


def test_a_limit_longer_than_a_worker_life_is_lowered_to_it():
    cfg = _cfg("01:00:00", 300)
    limits, chunk, note = cluster_limits(cfg, CaseLimits(3600.0, 1e9), 8)  # the default max_case_seconds
    assert limits == CaseLimits(1620.0, 1e9) and chunk == 1
    assert "max_case_seconds = 3600 s is more than half a worker's life (3240 s" in note
    assert "cases are stopped after 1620 s" in note
    limits, chunk, _ = cluster_limits(cfg, CaseLimits(None), 1)  # no limit at all
    assert limits.seconds == 1620.0 and chunk == 1


def test_the_life_matches_the_job_script_lifetime_and_stagger():
    cfg = _cfg("00:01:00", 20)  # --lifetime 40s, --lifetime-stagger 5s -> at least 35 s
    args = job_kwargs(cfg)["worker_extra_args"]
    assert args == ["--lifetime", "40s", "--lifetime-stagger", "5s"]
    assert cluster_limits(cfg, CaseLimits(3600.0), 4)[0].seconds == 17.5
    no_margin = _cfg("00:01:00", 0)  # no --lifetime: the walltime itself
    assert job_kwargs(no_margin)["worker_extra_args"] == []
    assert cluster_limits(no_margin, CaseLimits(3600.0), 4)[0].seconds == 30.0


@pytest.mark.parametrize("seconds", [0.5, 7.0, 1619.0, 3239.0])
def test_a_task_never_outlives_a_worker(seconds):
    cfg = _cfg("01:00:00", 300)
    limits, chunk, _ = cluster_limits(cfg, CaseLimits(seconds), 32)
    assert chunk >= 1 and chunk * limits.seconds <= 1620.0
