"""Failure isolation: raising, NaN, non-converged and os._exit cases are recorded as failed
(blamed on the right case) and the sweep completes -- serial (in-process and isolated child)
and Dask (one LocalCluster shared by this module)."""

from __future__ import annotations

import logging
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import study_fakes as fakes
from workbench.study import (DaskExecutor, IsolatedExecutor, SerialExecutor, WorkerCrash,
                             load_study, run_study)

HERE = Path(__file__).parent
ROOT = HERE.parents[1]

TENSIONS = [1.0, fakes.RAISE, 2.0, fakes.NAN, 3.0, fakes.EXIT, 4.0, fakes.NOCONV, 8.0, 9.0]
EXPECTED_FAILED = {fakes.RAISE: "RuntimeError: fake model exploded", fakes.NAN: "non-finite result",
                   fakes.EXIT: "worker process", fakes.NOCONV: "not converged"}


def _study(write_study, with_exit=True):
    from study_fakes import GOOD

    ts = [t for t in TENSIONS if with_exit or t != fakes.EXIT]
    axis = ", ".join(f"[{t}, 0.0]" for t in ts)
    return load_study(write_study(f"""
        [sweep]
        product = {{ "load.tensions" = [{axis}] }}
        """, base=GOOD))


def _check(folder, with_exit=True):
    df = pd.read_parquet(folder)
    df["t0"] = df["p.load.tensions"].map(lambda s: float(s.strip("[]").split(",")[0]))
    assert not df.duplicated(["case_id", "model"]).any()
    expected = {t for t in EXPECTED_FAILED if with_exit or t != fakes.EXIT}
    failed = df[df["status"] != "ok"]
    assert set(failed["t0"]) == expected
    assert len(failed) == 2 * len(expected)  # both models of each bad case
    for t, reason in EXPECTED_FAILED.items():
        if t in expected:
            assert failed[failed["t0"] == t]["error"].str.contains(reason, regex=False).all(), (t, failed)
    ok = df[df["status"] == "ok"]
    assert set(ok["t0"]) == {t for t in TENSIONS if t not in EXPECTED_FAILED}
    assert ok["tip_x"].notna().all()
    return df


def test_serial_in_process_isolates_exceptions(tmp_path, write_study):
    s = run_study(_study(write_study, with_exit=False), tmp_path / "o", SerialExecutor(),
                  model_lookup=fakes.lookup, progress=False)
    assert s.exit_code == 1 and s.n_failed == 3 and s.n_ok == 6
    _check(tmp_path / "o", with_exit=False)


def test_serial_isolated_survives_os_exit(tmp_path, write_study):
    s = run_study(_study(write_study), tmp_path / "o", IsolatedExecutor(), model_lookup=fakes.lookup,
                  progress=False)
    assert s.exit_code == 1 and s.n_failed == 4 and s.n_ok == 6
    df = _check(tmp_path / "o")
    err = df[df["status"] != "ok"].set_index("model")["error"]
    assert (df[df["p.load.tensions"] == f"[{fakes.EXIT},0.0]"]["error"]
            == "worker process exited with status 3").all(), err


def test_isolated_executor_reports_signal():
    def payloads():
        return [0, 1, 2]

    with IsolatedExecutor() as ex:
        out = dict(ex.imap_unordered(fakes.die_on_one, payloads()))
    assert out[0] == 0 and out[2] == 4
    assert isinstance(out[1], WorkerCrash) and "SIGKILL" in out[1].reason


@pytest.fixture(scope="module")
def dask_scheduler():
    import dask
    from distributed import LocalCluster

    with dask.config.set({"distributed.scheduler.worker-saturation": 1.0,
                          "distributed.scheduler.allowed-failures": 1,
                          "distributed.scheduler.work-stealing": False}):
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                               silence_logs=logging.CRITICAL)
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()


def test_dask_isolates_failures_and_os_exit(tmp_path, write_study, dask_scheduler):
    s = run_study(_study(write_study), tmp_path / "o", DaskExecutor(scheduler=dask_scheduler),
                  model_lookup=fakes.lookup, progress=False)
    assert s.exit_code == 1 and s.n_failed == 4 and s.n_ok == 6
    df = _check(tmp_path / "o")
    crashed = df[df["p.load.tensions"] == f"[{fakes.EXIT},0.0]"]["error"]
    assert crashed.str.contains("worker process died while running this case").all()


def test_dask_matches_serial_table(tmp_path, write_study, dask_scheduler):
    study = _study(write_study, with_exit=False)
    run_study(study, tmp_path / "a", SerialExecutor(), model_lookup=fakes.lookup, progress=False)
    run_study(study, tmp_path / "b", DaskExecutor(scheduler=dask_scheduler), model_lookup=fakes.lookup,
              progress=False)
    a = pd.read_parquet(tmp_path / "a").drop(columns="wall_time").sort_values(["case_id", "model"])
    b = pd.read_parquet(tmp_path / "b").drop(columns="wall_time").sort_values(["case_id", "model"])
    assert a.reset_index(drop=True).map(repr).equals(b.reset_index(drop=True).map(repr))


@pytest.mark.slow
def test_cli_local_cluster_with_os_exit(tmp_path, write_study):
    """The CLI's own LocalCluster (--workers 2), end to end, plus `workbench show`."""
    study = _study(write_study)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(HERE)]))
    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-m", "workbench", "run", study.path, "--out", str(out), "--workers", "2",
                        "--no-report", "--model-lookup", "study_fakes:lookup"], env=env, capture_output=True, text=True,
                       timeout=300, cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    _check(out)
    r = subprocess.run([sys.executable, "-m", "workbench", "show", str(out)], env=env, capture_output=True,
                       text=True, timeout=60, cwd=tmp_path)
    assert r.returncode == 1 and "ok 6, failed 4" in r.stdout, r.stdout


@pytest.mark.parametrize("kind", ["isolated", "dask"])
def test_crash_inside_a_batch_is_blamed_on_its_case(tmp_path, write_study, kind, request):
    """A batch whose worker dies is rerun case by case: only the crashing case fails."""
    ex = IsolatedExecutor() if kind == "isolated" else DaskExecutor(
        scheduler=request.getfixturevalue("dask_scheduler"))
    s = run_study(_study(write_study), tmp_path / "o", ex, model_lookup=fakes.lookup, progress=False,
                  batch_size=4)
    assert s.n_failed == 4 and s.n_ok == 6
    _check(tmp_path / "o")


def test_progress_bar_counts(tmp_path, write_study, capsys):
    run_study(_study(write_study, with_exit=False), tmp_path / "o", SerialExecutor(), model_lookup=fakes.lookup,
              progress=True, batch_size=1)
    err = capsys.readouterr().err
    assert "9/9" in err and "ok=6 failed=3" in err
