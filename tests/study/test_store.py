"""Store: atomic parts, schema union, manifest, SIGKILL mid-sweep + resume == uninterrupted run."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pyarrow.parquet as pq
import pytest

import study_fakes as fakes
from workbench.study import (ResultStore, RunConfig, SerialExecutor, StudyError, array_shapes, load_study,
                             read_manifest, run_cases)
from workbench.study.store import SCHEMA_FILE

from runs_util import KILL_STUDY

HERE = Path(__file__).parent
ROOT = HERE.parents[1]

SWEEP_STUDY = KILL_STUDY  # 30 cases, one of them (13 N) slow enough to be caught mid-run


def _canon(df: pd.DataFrame) -> pd.DataFrame:
    df = df.drop(columns=["wall_time"]).sort_values(["case_id", "model"]).reset_index(drop=True)
    return df[sorted(df.columns)]


def _assert_same_table(a: pd.DataFrame, b: pd.DataFrame) -> None:
    a, b = _canon(a), _canon(b)
    assert list(a.columns) == list(b.columns)
    assert len(a) == len(b)
    for col in a.columns:
        assert a[col].map(repr).tolist() == b[col].map(repr).tolist(), col


def test_schema_survives_failed_first_part(tmp_path):
    store = ResultStore(tmp_path, flush_rows=1)
    store.add([{"case_id": "a", "model": "cc", "status": "failed", "error": "boom", "wall_time": 0.1}])
    store.add([{"case_id": "b", "model": "cc", "status": "ok", "error": "", "wall_time": 0.1, "tip_x": 1.5,
                "positions": [0.0, 0.0, 1.0], "x.extra": 2.0, "series.s": [1.0, 2.0, 3.0, 4.0],
                "_shapes": {"series.s": [-1, 2]}}])
    df = pd.read_parquet(tmp_path)
    assert set(df["case_id"]) == {"a", "b"}
    assert "x.extra" in df.columns and "series.s" in df.columns
    assert df.set_index("case_id").loc["b", "tip_x"] == 1.5
    assert array_shapes(tmp_path)["series.s"] == [-1, 2]
    assert store.finished_case_ids() == {"a", "b"}
    assert not list(tmp_path.glob(".*"))  # no temporaries left


def test_manifest_and_example_run(tmp_path, write_study):
    study = load_study(write_study(SWEEP_STUDY.split("[sweep]")[0], base=""))
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    assert (s.n_cases, s.n_ok, s.n_failed, s.exit_code) == (1, 1, 0, 0)
    man = read_manifest(tmp_path / "out")
    assert man["config_hash"] == study.config_hash
    assert man["study"]["robot"]["preset"] == "steel_rod"
    for key in ("trunk-workbench", "exudyn", "numpy", "pyarrow", "dask", "python"):
        assert key in man["versions"]
    assert man["versions"]["numpy"]
    assert "commit" in man["git"]
    run = man["runs"][0]
    assert run["host"] and run["start"] and run["end"] and run["cases_done"] == 1
    df = pd.read_parquet(tmp_path / "out")
    assert len(df) == 2 and set(df["model"]) == {"cc", "ancf"}
    pos = df["positions"].iloc[0]
    assert len(pos) == 15  # 5 stations x 3, shape in metadata
    assert array_shapes(tmp_path / "out")["positions"] == [-1, 3]


def test_rerun_without_resume_and_changed_config_refused(tmp_path, write_study):
    p = write_study(SWEEP_STUDY, base="")
    study = load_study(p)
    out = tmp_path / "out"
    run_cases(fakes.sweep_kind(fakes.lookup), study, out, None, RunConfig(progress=False))
    with pytest.raises(StudyError, match="already holds results"):
        run_cases(fakes.sweep_kind(fakes.lookup), study, out, None, RunConfig(progress=False))
    changed = load_study(write_study(SWEEP_STUDY.replace("n_stations = 5", "n_stations = 7"), base=""))
    with pytest.raises(StudyError, match="config hash"):
        run_cases(fakes.sweep_kind(fakes.lookup), changed, out, None, RunConfig(resume=True, progress=False))
    # resuming a complete run runs nothing and keeps the table
    s = run_cases(fakes.sweep_kind(fakes.lookup), study, out, None, RunConfig(resume=True, progress=False))
    assert s.n_run == 0 and s.n_cases == 30 and s.n_failed == 5 and s.exit_code == 1


def _cli(study_path: Path, out: Path, *extra: str) -> list[str]:
    return [sys.executable, str(HERE / "fake_workbench.py"), "study_fakes:lookup_spin_20ms", "run", str(study_path),
            "--out", str(out), "--in-process", "--no-report", "--progress", "off", "--flush-rows", "4", *extra]


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), str(HERE), env.get("PYTHONPATH", "")])
    return env


def test_sigkill_mid_sweep_then_resume_equals_uninterrupted(tmp_path, write_study):
    study_path = write_study(SWEEP_STUDY, base="")
    study = load_study(study_path)
    ref = tmp_path / "ref"
    run_cases(fakes.sweep_kind(fakes.lookup), study, ref, SerialExecutor(), RunConfig(progress=False))

    out = tmp_path / "killed"
    kills = 0
    # kill the writer at different moments (30 cases x 2 models x 20 ms, a part every 2 cases)
    for delay_parts in (1, 4, 9):
        args = _cli(study_path, out, *(["--resume"] if out.exists() else []))
        proc = subprocess.Popen(args, env=_env(), cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        t_end = time.monotonic() + 60
        while time.monotonic() < t_end and proc.poll() is None:
            parts = [p for p in out.glob("part-*.parquet") if p.name != SCHEMA_FILE] if out.exists() else []
            if len(parts) >= delay_parts:
                time.sleep(0.013 * delay_parts)  # land somewhere inside the next part
                break
            time.sleep(0.002)
        if proc.poll() is None:
            proc.send_signal(signal.SIGKILL)
            kills += 1
        proc.wait(timeout=30)
        # after every kill the folder reads as a consistent table with whole cases
        df = pd.read_parquet(out)
        assert not df.duplicated(["case_id", "model"]).any()
        assert (df.groupby("case_id").size() == 2).all()
    assert kills >= 2, "the writer finished before it could be killed: test did not exercise SIGKILL"
    r = subprocess.run(_cli(study_path, out, "--resume"), env=_env(), cwd=tmp_path, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 1, r.stderr  # the 13 N cases fail (raise) by design
    _assert_same_table(pd.read_parquet(out), pd.read_parquet(ref))
    man = read_manifest(out)
    assert len(man["runs"]) == 4


def test_killed_writer_leaves_only_dot_temporaries(tmp_path):
    """A writer killed inside a part write leaves at most a dot-file that readers ignore."""
    code = f"""
import sys
sys.path.insert(0, {str(ROOT)!r})
from workbench.study.store import ResultStore
s = ResultStore({str(tmp_path)!r}, flush_rows=50)
i = 0
while True:
    s.add([{{"case_id": f"c{{i}}-{{k}}", "model": "cc", "status": "ok", "error": "", "wall_time": 0.0,
             "positions": [float(k)] * 300}} for k in range(50)])
    i += 1
    if i == 3:
        print("go", flush=True)
"""
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "go"
    time.sleep(0.05)
    proc.kill()
    proc.wait()
    df = pd.read_parquet(tmp_path)
    assert len(df) % 50 == 0 and len(df) >= 150
    assert not df.duplicated(["case_id"]).any()
    store = ResultStore(tmp_path)
    store.cleanup_temporaries()
    assert not list(tmp_path.glob(".*"))
    assert len(store.finished_case_ids()) == len(df)
    for p in store.part_files():
        assert pq.read_metadata(p).num_rows == 50


def test_resume_into_a_folder_with_other_column_types_is_refused_before_running(tmp_path):
    from workbench.study.store import SchemaMismatch

    # an older version recorded p.load.length_changes as null (-> double); this one records JSON strings
    ResultStore(tmp_path, [{"p.load.length_changes": None, "p.robot.length": 0.8}])
    with pytest.raises(SchemaMismatch, match=r"p\.load\.length_changes is double there, string now"):
        ResultStore(tmp_path, [{"p.load.length_changes": "[0.01,-0.01]", "p.robot.length": 0.8}])
    ResultStore(tmp_path, [{"p.load.length_changes": None, "p.robot.length": 0.9}])  # same types: fine
