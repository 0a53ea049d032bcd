"""Failure isolation: raising, NaN, non-converged, os._exit, hanging and memory-eating cases are
recorded as failed (blamed on the right case and model, with their failure kind) and the sweep
completes -- serial (in-process and isolated child) and Dask (one LocalCluster shared by this
module)."""

from __future__ import annotations

import logging
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import study_fakes as fakes
from workbench.study import DaskExecutor, IsolatedExecutor, RunConfig, SerialExecutor, load_study, run_cases
from workbench.study.outcomes import CaseLimits, ExecutorStartError

HERE = Path(__file__).parent
ROOT = HERE.parents[1]

TENSIONS = [1.0, fakes.RAISE, 2.0, fakes.NAN, 3.0, fakes.EXIT, 4.0, fakes.NOCONV, 8.0, 9.0]
EXPECTED_FAILED = {fakes.RAISE: "RuntimeError: fake model exploded", fakes.NAN: "non-finite result",
                   fakes.EXIT: "worker process", fakes.NOCONV: "not converged"}
KIND = {fakes.RAISE: "model", fakes.NAN: "model", fakes.EXIT: "crash", fakes.NOCONV: "model"}


def _study(write_study, tensions=None, with_exit=True):
    from study_fakes import GOOD

    ts = tensions or [t for t in TENSIONS if with_exit or t != fakes.EXIT]
    axis = ", ".join(f"[{t}, 0.0]" for t in ts)
    return load_study(write_study(f"""
        [sweep]
        product = {{ "load.tensions" = [{axis}] }}
        """, base=GOOD))


def _t0(df):
    return df["p.load.tensions"].map(lambda s: float(s.strip("[]").split(",")[0]))


def _check(folder, with_exit=True):
    df = pd.read_parquet(folder)
    df["t0"] = _t0(df)
    assert not df.duplicated(["case_id", "model"]).any()
    expected = {t for t in EXPECTED_FAILED if with_exit or t != fakes.EXIT}
    failed = df[df["status"] != "ok"]
    assert set(failed["t0"]) == expected
    assert len(failed) == 2 * len(expected)  # both models of each bad case (the fakes fail for every model)
    for t, reason in EXPECTED_FAILED.items():
        if t in expected:
            rows = failed[failed["t0"] == t]
            assert rows["error"].str.contains(reason, regex=False).all(), (t, failed)
            assert (rows["failure"] == KIND[t]).all(), (t, rows["failure"])
    ok = df[df["status"] == "ok"]
    assert set(ok["t0"]) == {t for t in TENSIONS if t not in EXPECTED_FAILED}
    assert ok["tip_x"].notna().all() and (ok["failure"] == "").all()
    return df


def test_serial_in_process_isolates_exceptions(tmp_path, write_study):
    s = run_cases(fakes.sweep_kind(fakes.lookup),
                  _study(write_study, with_exit=False), tmp_path / "o", SerialExecutor(),
                  RunConfig(progress=False))
    assert s.exit_code == 1 and s.n_failed == 3 and s.n_ok == 6
    _check(tmp_path / "o", with_exit=False)


def test_serial_isolated_survives_os_exit(tmp_path, write_study):
    s = run_cases(fakes.sweep_kind(fakes.lookup), _study(write_study), tmp_path / "o", IsolatedExecutor(),
                  RunConfig(progress=False))
    assert s.exit_code == 1 and s.n_failed == 4 and s.n_ok == 6
    df = _check(tmp_path / "o")
    crashed = df[df["t0"] == fakes.EXIT].set_index("model")["error"]
    # the crash is blamed on the model that was running; the next model ran again in a fresh process
    assert crashed["cc"] == "worker process exited with status 3 while computing model 'cc'"
    assert crashed["ancf"] == "worker process exited with status 3 while computing model 'ancf'"


def test_a_crashing_model_keeps_the_other_models_rows(tmp_path, write_study):
    """ancf kills its process in every case: cc's rows (computed first, streamed) are all kept."""
    study = _study(write_study, tensions=[1.0, 2.0, 3.0])
    s = run_cases(fakes.sweep_kind(fakes.lookup_ancf_exits), study, tmp_path / "o", IsolatedExecutor(),
                  RunConfig(progress=False))
    df = pd.read_parquet(tmp_path / "o").set_index(["model"])
    assert s.n_failed == 3 and len(df) == 6
    assert (df.loc["cc", "status"] == "ok").all() and df.loc["cc", "tip_x"].notna().all()
    assert (df.loc["ancf", "failure"] == "crash").all()
    assert df.loc["ancf", "error"].str.fullmatch("worker process exited with status 4 while computing model 'ancf'").all()


def test_isolated_executor_streams_rows_and_reports_signal():
    with IsolatedExecutor() as ex:
        out = dict(ex.imap_unordered(fakes.die_on_one, [0, 1, 2]))
    assert out[0].rows == [0, 0] and out[2].rows == [2, 4] and out[0].crash is None
    assert out[1].rows == [1]  # yielded before the kill: kept
    assert out[1].crash.kind == "killed" and "SIGKILL" in out[1].crash.reason


@pytest.mark.parametrize("executor", ["serial", "isolated", "dask"])
def test_a_hanging_case_is_stopped_by_the_time_limit(tmp_path, write_study, executor, request):
    """max_case_seconds: the hanging case (an hour of sleep) is stored as a timeout; the others finish."""
    ex = {"serial": SerialExecutor, "isolated": IsolatedExecutor}.get(executor)
    ex = ex() if ex else DaskExecutor(scheduler=request.getfixturevalue("dask_scheduler"))
    study = _study(write_study, tensions=[1.0, fakes.HANG, 2.0])
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "o", ex,
                  RunConfig(progress=False, limits=CaseLimits(seconds=2.0), batch_size=3))
    df = pd.read_parquet(tmp_path / "o")
    df["t0"] = _t0(df)
    hung = df[df["t0"] == fakes.HANG]
    assert s.n_ok == 2 and s.n_failed == 1 and s.exit_code == 1
    assert len(hung) == 2 and (hung["failure"] == "timeout").all()
    assert hung["error"].str.startswith("stopped after max_case_seconds = 2 s").all()
    assert (df[df["t0"] != fakes.HANG]["status"] == "ok").all()


def test_a_case_over_the_memory_cap_fails_with_memory(tmp_path, write_study):
    study = _study(write_study, tensions=[1.0, fakes.HOG])
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "o", IsolatedExecutor(),
                  RunConfig(progress=False, limits=CaseLimits(memory=4 * 2**30)))
    df = pd.read_parquet(tmp_path / "o")
    df["t0"] = _t0(df)
    hog = df[df["t0"] == fakes.HOG]
    assert s.n_ok == 1 and (hog["failure"] == "memory").all() and hog["error"].str.contains("MemoryError").all()


@pytest.fixture(scope="module")
def dask_scheduler():
    import dask
    from distributed import LocalCluster

    with dask.config.set({"distributed.scheduler.worker-saturation": 1.0,
                          "distributed.scheduler.allowed-failures": 1,
                          "distributed.scheduler.work-stealing": False}):
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                               scheduler_kwargs={"dashboard": False}, silence_logs=logging.CRITICAL)
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()


def test_dask_isolates_failures_and_os_exit(tmp_path, write_study, dask_scheduler):
    s = run_cases(fakes.sweep_kind(fakes.lookup),
                  _study(write_study), tmp_path / "o", DaskExecutor(scheduler=dask_scheduler),
                  RunConfig(progress=False))
    assert s.exit_code == 1 and s.n_failed == 4 and s.n_ok == 6
    df = _check(tmp_path / "o")
    crashed = df[df["t0"] == fakes.EXIT]["error"]
    assert crashed.str.fullmatch(r"worker process exited with status 3 while computing model '(cc|ancf)'").all()


def test_dask_matches_serial_table(tmp_path, write_study, dask_scheduler):
    study = _study(write_study, with_exit=False)
    run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "a", SerialExecutor(), RunConfig(progress=False))
    run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "b", DaskExecutor(scheduler=dask_scheduler),
              RunConfig(progress=False))
    a = pd.read_parquet(tmp_path / "a").drop(columns="wall_time").sort_values(["case_id", "model"])
    b = pd.read_parquet(tmp_path / "b").drop(columns="wall_time").sort_values(["case_id", "model"])
    assert a.reset_index(drop=True).map(repr).equals(b.reset_index(drop=True).map(repr))


def test_dask_reads_allowed_failures_from_the_scheduler(dask_scheduler):
    with DaskExecutor(scheduler=dask_scheduler, allowed_failures=7) as ex:
        assert ex.allowed_failures == 1  # the scheduler's setting, not the local argument
        assert "lost 2 time(s) (the scheduler's allowed-failures = 1)" in ex._lost().reason


def test_dask_unreachable_scheduler_is_one_start_error(tmp_path):
    import socket

    with socket.socket() as sk:  # a port nobody listens on
        sk.bind(("127.0.0.1", 0))
        port = sk.getsockname()[1]
    ex = DaskExecutor(scheduler=f"tcp://127.0.0.1:{port}", connect_timeout=1.0)
    with pytest.raises(ExecutorStartError) as ei:
        ex.__enter__()
    assert "\n" not in str(ei.value) and f"127.0.0.1:{port}" in str(ei.value)


@pytest.mark.slow
def test_cli_local_cluster_with_os_exit(tmp_path, write_study):
    """The CLI's own LocalCluster (--workers 2), end to end, plus `workbench show`."""
    study = _study(write_study)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(HERE)]))
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, str(HERE / "fake_workbench.py"), "study_fakes:lookup", "run", study.path,
                        "--out", str(out), "--workers", "2", "--no-report"], env=env, capture_output=True, text=True,
                       timeout=300, cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    _check(out)
    r = subprocess.run([sys.executable, "-m", "workbench", "show", str(out)], env=env, capture_output=True,
                       text=True, timeout=60, cwd=tmp_path)
    assert r.returncode == 1 and "ok 6, failed 4" in r.stdout, r.stdout


@pytest.mark.slow
def test_a_lost_dask_worker_is_retried_by_dask_with_identical_results(tmp_path, write_study, monkeypatch):
    """The 2 N case kills its Dask worker once: Dask reruns the task on a new worker (allowed-failures 1)."""
    monkeypatch.setenv("WB_KILL_ONCE", str(tmp_path / "killed-once"))
    study = _study(write_study, tensions=[1.0, 2.0, 3.0])
    s = run_cases(fakes.sweep_kind(fakes.lookup_kills_worker_once), study, tmp_path / "o", DaskExecutor(n_workers=2),
                  RunConfig(progress=False, batch_size=1))
    assert (tmp_path / "killed-once").exists() and s.n_ok == 3 and s.exit_code == 0
    run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "ref", SerialExecutor(), RunConfig(progress=False))
    from runs_util import same_table

    assert same_table(pd.read_parquet(tmp_path / "o"), pd.read_parquet(tmp_path / "ref"))


@pytest.mark.slow
def test_a_case_that_keeps_killing_workers_is_stored_lost_and_exits_3(tmp_path, write_study):
    study = _study(write_study, tensions=[1.0, 2.0, 3.0])
    s = run_cases(fakes.sweep_kind(fakes.lookup_kills_worker_always), study, tmp_path / "o", DaskExecutor(n_workers=2),
                  RunConfig(progress=False, batch_size=1))
    df = pd.read_parquet(tmp_path / "o")
    lost = df[df["status"] != "ok"]
    assert s.n_ok == 2 and s.exit_code == 3 and len(lost) == 2 and (lost["failure"] == "lost").all()
    assert lost["error"].str.contains(r"lost 2 time\(s\) \(the scheduler's allowed-failures = 1\)").all()


def test_a_cluster_without_workers_is_an_infrastructure_error(tmp_path, write_study):
    """No worker for lost_timeout seconds: the run stops with one line (exit 3 in the CLI), nothing hangs."""
    from distributed import LocalCluster

    from workbench.study.outcomes import InfrastructureError

    cluster = LocalCluster(n_workers=0, dashboard_address=":0", scheduler_kwargs={"dashboard": False},
                           silence_logs=logging.CRITICAL)
    try:
        with pytest.raises(InfrastructureError, match="has had no workers for 2 s"):
            run_cases(fakes.sweep_kind(fakes.lookup), _study(write_study, tensions=[1.0]), tmp_path / "o",
                      DaskExecutor(scheduler=cluster.scheduler_address, lost_timeout=2.0), RunConfig(progress=False))
    finally:
        cluster.close()
    assert (tmp_path / "o" / "_manifest.json").exists()  # the run was recorded (and can be resumed)


@pytest.mark.parametrize("kind", ["isolated", "dask"])
def test_crash_inside_a_batch_is_blamed_on_its_case(tmp_path, write_study, kind, request):
    """Units grouped 4 per task: only the crashing case fails."""
    ex = IsolatedExecutor() if kind == "isolated" else DaskExecutor(
        scheduler=request.getfixturevalue("dask_scheduler"))
    s = run_cases(fakes.sweep_kind(fakes.lookup), _study(write_study), tmp_path / "o", ex,
                  RunConfig(progress=False, batch_size=4))
    assert s.n_failed == 4 and s.n_ok == 6
    _check(tmp_path / "o")


def test_progress_bar_counts(tmp_path, write_study, capsys):
    run_cases(fakes.sweep_kind(fakes.lookup), _study(write_study, with_exit=False), tmp_path / "o", SerialExecutor(),
              RunConfig(progress=True, batch_size=1))
    err = capsys.readouterr().err
    assert "9/9" in err and "ok=6 failed=3" in err


def test_adaptive_dask_chunks_run_every_case_once_with_the_serial_results(tmp_path, write_study, dask_scheduler):
    """40 cases, chunks re-sized after every task (a tiny target time per task): nothing lost or run twice."""
    study = _study(write_study, tensions=[1.0 + 0.1 * k for k in range(40)])
    run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "a", SerialExecutor(), RunConfig(progress=False))
    ex = DaskExecutor(scheduler=dask_scheduler)
    ex.task_seconds = 0.003
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "b", ex, RunConfig(progress=False))
    b = pd.read_parquet(tmp_path / "b")
    assert s.n_ok == 40 and len(b) == 80 and not b.duplicated(["case_id", "model"]).any()
    from runs_util import same_table

    assert same_table(pd.read_parquet(tmp_path / "a"), b)


@pytest.mark.slow
def test_a_lost_chunk_is_retried_unit_by_unit_so_only_the_killer_is_lost(tmp_path, write_study):
    """The 2 N case kills every worker that runs it: its chunk of 3 is rerun one case per task."""
    study = _study(write_study, tensions=[1.0, 2.0, 3.0])
    s = run_cases(fakes.sweep_kind(fakes.lookup_kills_worker_always), study, tmp_path / "o", DaskExecutor(n_workers=2),
                  RunConfig(progress=False, batch_size=3))
    df = pd.read_parquet(tmp_path / "o")
    df["t0"] = _t0(df)
    assert s.n_ok == 2 and s.exit_code == 3
    assert set(df[df["status"] != "ok"]["t0"]) == {2.0} and (df[df["t0"] != 2.0]["status"] == "ok").all()
