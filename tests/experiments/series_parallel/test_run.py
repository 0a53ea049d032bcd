"""A tiny series-parallel study end to end: rows in the architecture's schema, round trip, failures, resume."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from workbench.experiments.series_parallel.expand import expand_poses
from workbench.experiments.series_parallel.kind import KIND
from workbench.experiments.series_parallel.spec import load_series_parallel_study
from workbench.experiments.series_parallel.worker import evaluate_pose_case
from workbench.study.run_config import RunConfig
from workbench.study.runner import run_cases
from workbench.study.spec import StudyError
from workbench.study.store import MANIFEST


def run_study_file(path, out, **kw):
    """Validate the series-parallel study file ``path`` and run it into ``out`` on the study pipeline."""
    return run_cases(KIND, load_series_parallel_study(path), out, config=RunConfig(**kw))

TINY = """
[study]
kind = "series_parallel"
name = "tiny"
[solver]
n_elements = 4
[motions]
module = [ { axis = "rz", amplitude = 0.1, samples = 1 } ]
[report]
reference = "target"
"""


def run_motion_study(path, out, resume=False):
    return run_cases(KIND, KIND.load(path), out, resume=resume)


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("motion")
    p = d / "tiny.toml"
    p.write_text(TINY)
    summary = run_study_file(p, d / "out")
    return p, d / "out", summary


def test_tiny_study_rows_and_round_trip(tiny_run):
    p, out, summary = tiny_run
    assert summary.n_cases == 1 and summary.n_ok == 1 and summary.exit_code == 0
    df = pd.read_parquet(out)
    assert sorted(df["model"]) == ["cc_fit", "series_parallel", "target"]
    assert (df["status"] == "ok").all()
    rows = {r["model"]: r for _, r in df.iterrows()}
    sp, tg, cc = rows["series_parallel"], rows["target"], rows["cc_fit"]
    # target: the home pose (height 0.5) twisted by 0.1 rad
    assert tg["tip_z"] == pytest.approx(0.5) and tg["tip_twist"] == pytest.approx(0.1)
    # FK of the IK lengths returns to the target (independent static solve with the platform free)
    assert sp["x.fk_position_error"] < 1e-6 and sp["x.fk_rotation_error"] < 1e-6
    assert sp["tip_twist"] == pytest.approx(0.1, abs=1e-6)
    assert np.array(sp["tip_frame"]).reshape(4, 4)[3].tolist() == [0, 0, 0, 1]
    # D3 symmetry: a twist about the axis changes the two leg families differently, legs 1, 3, 5 equal
    L = [sp[f"x.L1_{i}"] for i in range(1, 7)]
    assert np.ptp(L[0::2]) < 1e-8 and np.ptp(L[1::2]) < 1e-8 and abs(L[0] - L[1]) > 1e-4
    # platform balance Eq 22 at the IK lengths [N]: legs carry O(100 N), Newton stops on dL < 1e-10 m
    assert sp["x.ik_residual"] < 1e-3
    # positions: base origin + platform origin
    assert np.asarray(sp["positions"]).reshape(-1, 3).shape == (2, 3)
    # CC through one platform on the axis: straight (curvature 0), exact position
    assert cc["x.cc_curvature"] < 1e-6 and cc["x.cc_max_error"] < 1e-9
    assert {c for c in df.columns if c.startswith("p.pose.")} >= {"p.pose.shape", "p.pose.value"}
    man = json.loads((out / MANIFEST).read_text())
    assert man["study"]["study"]["kind"] == "series_parallel" and man["n_cases"] == 1


def test_resume_skips_and_refuses_overwrite(tiny_run):
    p, out, _ = tiny_run
    with pytest.raises(StudyError, match="already holds results"):
        run_study_file(p, out)
    s = run_study_file(p, out, resume=True)
    assert s.n_run == 0 and s.n_skipped == 1
    assert len(pd.read_parquet(out)) == 3


def test_failed_ik_is_a_failed_row_with_reason(monkeypatch, tmp_path):
    """An unreachable pose: the physics row fails with the IK reason, the CC fit has nothing to fit,
    the target row stays (and nothing raises)."""
    import workbench.physics.series_parallel as sp
    from workbench.experiments.series_parallel import worker

    p = tmp_path / "t.toml"
    p.write_text(TINY)
    case = expand_poses(load_series_parallel_study(p))[0]

    def failing(*a, **k):
        return sp.ModuleIK(np.full(6, np.nan), False, 3, float("nan"), "leg 2 static solve failed (test)",
                           *(np.full((6, 3), np.nan),) * 4, np.full((6, 5, 3), np.nan))

    monkeypatch.setattr(worker, "module_inverse", failing)
    rows = {r["model"]: r for r in evaluate_pose_case(case.case_id, case.params)}
    assert rows["target"]["status"] == "ok"
    assert rows["series_parallel"]["status"] == "failed"
    assert rows["series_parallel"]["error"] == "IK: leg 2 static solve failed (test)"
    assert rows["cc_fit"]["status"] == "failed"


def test_report_of_a_series_parallel_study_has_the_overview_figure(tiny_run, tmp_path):
    from workbench.report.build import build_report

    html = build_report(tiny_run[1], tmp_path / "report").read_text()
    assert 'id="motion_overview"' in html or "motion_overview" in html
    assert (tmp_path / "report" / "figures" / "motion_overview.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_report_legs_figure_names_the_extremes_of_the_table(tiny_run, tmp_path):
    """The legs figure's sentence quotes the largest compression ratio and smallest gap of the table."""
    from workbench.experiments.series_parallel.figures import pose_figures

    df = pd.read_parquet(tiny_run[1])
    figs = {f.name: f for f in pose_figures(df)}
    assert "motion_legs" in figs
    sp = df[(df["model"] == "series_parallel") & (df["status"] == "ok")]
    text = figs["motion_legs"].summary
    assert f"{sp['x.buckling_ratio'].max():.2f} x the clamped-clamped Euler load" in text
    assert f"Smallest gap between two legs: {1e3 * sp['x.min_leg_gap'].min():.1f} mm" in text
    assert 0.0 < sp["x.min_leg_gap"].min() < 0.1  # rz 0.1 rad: legs apart, less than the module size
