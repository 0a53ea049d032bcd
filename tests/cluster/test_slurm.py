"""A study on a real single-node SLURM cluster through ``workbench run --cluster slurm``.

The sweep (16 cases x cc/ancf, real models, each call slowed by 0.4 s: ``cluster_models.py``)
runs with 2 worker jobs; once both jobs run and some cases are stored, one job is cancelled with
``scancel``.  The run must finish with every case, a replacement job, and a table equal bit for bit
(wall times aside) to the serial in-process run.  Also: a partition the scheduler refuses ends
with one line and exit code 2 before anything is written; a job that never starts ends the run
after the wait with one line and exit code 3.  The cluster: ``conftest.py``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pandas as pd
import pytest

from tests.regression.diff_runs import diff_tables
from workbench.study import RunConfig, SerialExecutor, load_study, run_study

pytestmark = pytest.mark.slurm

HERE = Path(__file__).parent
ROOT = HERE.parents[1]
FAKES = ROOT / "tests" / "study"  # fake_workbench.py, study_fakes
N_CASES = 16

STUDY = textwrap.dedent("""\
    [study]
    name = "slurm_test"
    seed = 1
    models = ["cc", "ancf"]

    [robot]
    preset = "steel_rod"
    base_orientation = "horizontal"

    [load]
    mode = "tension"
    bend_angle = 1.0

    [solver]
    n_elements = 8
    n_stations = 9

    [derived]
    gravity_parameter = 0.1

    [sweep]
    product = { "load.bend_angle" = [0.5, 1.0, 2.0, 3.0], "derived.gravity_parameter" = [0.01, 0.1, 1.0, 10.0] }
    """)


def _env(slurm: dict, tmp_path: Path) -> dict:
    return dict(os.environ, **slurm, XDG_CONFIG_HOME=str(tmp_path / "xdg"),
                PYTHONPATH=os.pathsep.join([str(ROOT), str(HERE), str(FAKES)]))


def _run_cmd(study: Path, out: Path, config: Path, *extra: str) -> list[str]:
    """``workbench run`` on the cluster with the real models slowed down (``cluster_models:slow_lookup``)."""
    return [sys.executable, str(FAKES / "fake_workbench.py"), "cluster_models:slow_lookup", "run", str(study),
            "--out", str(out), "--cluster", "slurm", "--cluster-config", str(config), "--no-report", "--progress",
            "off", *extra]


def _jobs(env: dict, name: str) -> dict[str, str]:
    r = subprocess.run(["squeue", "-h", "-n", name, "-o", "%i %T"], env=env, capture_output=True, text=True,
                       timeout=20)
    return dict(line.split() for line in r.stdout.splitlines() if line.strip())


def _stored_cases(folder: Path) -> int:
    try:
        return pd.read_parquet(folder, columns=["case_id"])["case_id"].nunique()
    except Exception:  # noqa: BLE001 - not written yet
        return 0


def _config(tmp_path: Path, name: str, extra: str = "") -> Path:
    p = tmp_path / "cluster.toml"
    p.write_text(f'[cluster]\njob_name = "{name}"\nlog_directory = "{tmp_path / "logs"}"\n'
                 f'memory = "1GB"\nwalltime = "00:10:00"\nlifetime_margin = 60\n{extra}')
    return p


def test_cancelled_worker_job_loses_nothing_and_matches_serial(local_slurm, tmp_path):
    study = tmp_path / "study.toml"
    study.write_text(STUDY)
    name = f"wbtest{os.getpid()}"
    env, out = _env(local_slurm, tmp_path), tmp_path / "slurm"
    cmd = _run_cmd(study, out, _config(tmp_path, name), "--jobs", "2", "--queue-timeout", "90",
                   "--flush-rows", "1")
    proc = subprocess.Popen(cmd, env=env, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    killed, stored_at_kill = None, None
    try:
        deadline = time.monotonic() + 120
        while proc.poll() is None and time.monotonic() < deadline and killed is None:
            running = [j for j, st in _jobs(env, name).items() if st == "RUNNING"]
            stored = _stored_cases(out)
            if len(running) == 2 and stored >= 3:
                killed, stored_at_kill = running[0], stored
                subprocess.run(["scancel", killed], env=env, check=True, timeout=20)
            time.sleep(0.1)
        stdout, stderr = proc.communicate(timeout=150)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert killed is not None, f"never saw 2 running jobs with cases stored; rc {proc.returncode}\n{stderr}"
    assert 0 < stored_at_kill < N_CASES, stored_at_kill  # the job was cancelled mid-run
    assert proc.returncode == 0, stderr
    assert f"job {killed} " in stderr and "a replacement is submitted" in stderr, stderr
    assert "cases 16: ok 16, failed 0" in stdout, stdout
    run = json.loads((out / "_manifest.json").read_text())["runs"][-1]
    assert run["executor"].startswith("dask-jobqueue slurm: 2 job(s)") and run["cases_done"] == N_CASES

    serial = tmp_path / "serial"
    run_study(load_study(study), serial, SerialExecutor(), RunConfig(progress=False))
    assert diff_tables(serial, out) == []
    assert len(pd.read_parquet(out)) == 2 * N_CASES  # no duplicate rows from the retried case
    assert not _jobs(env, name), "the run left jobs in the queue"


def test_refused_partition_is_one_line(local_slurm, tmp_path):
    study = tmp_path / "study.toml"
    study.write_text(STUDY)
    env = _env(local_slurm, tmp_path)
    r = subprocess.run(_run_cmd(study, tmp_path / "o", _config(tmp_path, "wbrefused"), "--queue", "nosuch"),
                       env=env, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    # the study's plausibility warnings (issue 16, printed before the submission) are not the error
    lines = [ln for ln in r.stderr.strip().splitlines() if not ln.startswith("warning: ")]
    assert len(lines) == 1 and lines[0].startswith("--cluster slurm: the job was refused:"), r.stderr
    assert "invalid partition" in lines[0] and "nosuch" in lines[0], r.stderr
    assert not (tmp_path / "o").exists()  # refused before the result folder is created


def test_queue_that_never_starts_a_job_ends_after_the_wait(local_slurm, tmp_path):
    study = tmp_path / "study.toml"
    study.write_text(STUDY)
    env, name = _env(local_slurm, tmp_path), f"wbpending{os.getpid()}"
    config = _config(tmp_path, name, 'job_extra = ["--begin=now+3600"]\n')  # held for an hour
    t0 = time.monotonic()
    r = subprocess.run(_run_cmd(study, tmp_path / "o", config, "--queue-timeout", "5"), env=env, cwd=tmp_path,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 3, r.stderr
    last = r.stderr.strip().splitlines()[-1]
    assert "no worker job started within 5 s" in last and "PENDING" in last, r.stderr
    assert time.monotonic() - t0 < 60
    assert not _jobs(env, name), "the pending job was not cancelled"


def _walltime_run(local_slurm, tmp_path, margin: int, delay: float):
    study = tmp_path / "study.toml"
    study.write_text(STUDY)
    name = f"wbwall{os.getpid()}"
    env = dict(_env(local_slurm, tmp_path), WORKBENCH_TEST_DELAY=str(delay))
    cfg = _config(tmp_path, name).read_text().replace('walltime = "00:10:00"', 'walltime = "00:01:00"')
    cfg = cfg.replace("lifetime_margin = 60", f"lifetime_margin = {margin}")
    (tmp_path / "cluster.toml").write_text(cfg)
    out = tmp_path / "slurm"
    r = subprocess.run(_run_cmd(study, out, tmp_path / "cluster.toml", "--jobs", "1", "--queue-timeout", "90"),
                       env=env, cwd=tmp_path, capture_output=True, text=True, timeout=400)
    assert r.returncode == 0, r.stderr
    assert "cases 16: ok 16, failed 0" in r.stdout, r.stdout
    serial = tmp_path / "serial"
    run_study(load_study(study), serial, SerialExecutor(), RunConfig(progress=False))
    assert diff_tables(serial, out) == []
    return r.stderr


@pytest.mark.slow
def test_job_killed_at_its_walltime_is_replaced_and_its_case_rerun(local_slurm, tmp_path):
    """No lifetime margin: SLURM kills the only job at its 1-minute walltime in the middle of a case.

    SLURM enforces time limits on a periodic sweep (up to ~30 s late), so the cases last 96 s.
    """
    err = _walltime_run(local_slurm, tmp_path, margin=0, delay=3.0)  # 16 x 2 x 3 s = 96 s of cases
    assert err.count("a replacement is submitted") >= 1, err


@pytest.mark.slow
def test_workers_retire_before_the_walltime(local_slurm, tmp_path):
    """A 40 s margin: the worker retires after 20 +- 10 s, a new job takes over; nothing is lost.

    (Half the shortest life, 5 s, is the per-case limit there (``cluster_limits``): above a case's 2 s.)
    """
    err = _walltime_run(local_slurm, tmp_path, margin=40, delay=1.0)  # 32 s of cases > the longest life
    assert err.count("a replacement is submitted") >= 1, err
    logs = "".join(p.read_text(errors="replace") for p in (tmp_path / "logs").glob("*"))
    assert "worker-lifetime-reached" in logs


@pytest.mark.slow
def test_a_case_longer_than_a_worker_life_is_stopped_by_the_case_limit(local_slurm, tmp_path):
    """A case that would outlive every worker job is stopped by the per-case limit, not rerun for ever.

    Walltime 1 min, lifetime_margin 10 s: a worker retires after 50 +- 2 s, so the default
    ``max_case_seconds`` (1 h) becomes half of 48 s (``cluster_limits``).  Without that, the hanging
    case's worker would retire, Dask would rerun the case on the replacement job (a retirement is no
    failure), and the run would never end.  The hanging case is stored ``failure = "timeout"``;
    the other cases match the serial run.
    """
    study = tmp_path / "study.toml"
    study.write_text(STUDY.replace('"load.bend_angle" = [0.5, 1.0, 2.0, 3.0], ', ""))  # 4 cases: gravity only
    name = f"wbhang{os.getpid()}"
    env = dict(_env(local_slurm, tmp_path), WORKBENCH_TEST_HANG_ABOVE_GRAVITY="500")  # gamma = 10 only
    cfg = _config(tmp_path, name).read_text().replace('walltime = "00:10:00"', 'walltime = "00:01:00"')
    (tmp_path / "cluster.toml").write_text(cfg.replace("lifetime_margin = 60", "lifetime_margin = 10"))
    out = tmp_path / "slurm"
    t0 = time.monotonic()
    r = subprocess.run(_run_cmd(study, out, tmp_path / "cluster.toml", "--jobs", "1", "--queue-timeout", "90"),
                       env=env, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert r.returncode == 1, r.stderr  # one case failed
    assert "cases are stopped after 24 s" in r.stderr, r.stderr
    assert time.monotonic() - t0 < 200
    table = pd.read_parquet(out)
    g = table["p.robot.gravity"]  # recorded for failed rows too
    hung = table[g > 500]
    assert len(hung) == 2 and (hung["status"] == "failed").all() and (hung["failure"] == "timeout").all(), hung
    assert hung["error"].str.contains("max_case_seconds = 24 s").all(), hung["error"].tolist()
    assert (table[g <= 500]["status"] == "ok").all() and len(table) == 8
    serial = tmp_path / "serial"
    run_study(load_study(study), serial, SerialExecutor(), RunConfig(progress=False))
    ok_serial = pd.read_parquet(serial).query("`p.robot.gravity` <= 500")
    ok_slurm = table[g <= 500].copy()
    for c in ok_serial.columns:  # the failed rows' NaN made int columns float: back, only where exact
        if ok_slurm[c].dtype != ok_serial[c].dtype and ok_slurm[c].notna().all():
            cast = ok_slurm[c].astype(ok_serial[c].dtype)
            assert (cast.astype(ok_slurm[c].dtype) == ok_slurm[c]).all(), c
            ok_slurm[c] = cast
    for name_, t in (("a", ok_serial), ("b", ok_slurm)):
        (tmp_path / name_).mkdir()
        t.to_parquet(tmp_path / name_ / "part.parquet")
    assert diff_tables(tmp_path / "a", tmp_path / "b") == []  # the finished cases, bit for bit
    assert not _jobs(env, name), "the run left jobs in the queue"
