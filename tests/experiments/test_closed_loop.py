"""Closed-loop control on the physics (workbench/experiments/closed_loop, physics/spring_link/session.py).

The physics check of the issue: with a CC plant the controller is exact (the closed loop is the open
loop, on the line to the solver's precision); the loop removes a plant's model error; the
warm-started spring-link session gives the equilibria of fresh solves; the study kind end to end.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from workbench.experiments.closed_loop.controller import (
    ControllerSettings,
    base_from_planar,
    cc_plan,
    control_step,
    planar_from_base,
    run_closed_loop,
    run_open_loop,
    start_configuration,
)
from workbench.experiments.closed_loop.plants import ConsistentCCPlant, hw_cable_map, model_plant
from workbench.experiments.closed_loop.scenario import closed_loop
from workbench.experiments.closed_loop.worker import _SessionPlant, row_models
from workbench.kinematics import line_path, planar_forward_kinematics, planar_inverse_kinematics
from workbench.models import SolverOptions, get_model
from workbench.robot.presets import build_preset
from workbench.study import RunConfig, SerialExecutor, StudyError, get_kind, kind_of, run_cases

LINE = line_path(np.array([0.25, 0.0, 0.70]), np.array([0.35, 0.0, 0.60]), 6)
GRASP = np.array([-0.3, 0.3, 1.0, 1.6])
EYELETS = SolverOptions(n_elements=16, tendon_model="eyelets", n_stations=17)


def test_settings_and_frames():
    with pytest.raises(ValueError, match="gain must lie in"):
        ControllerSettings(gain=2.0)
    with pytest.raises(ValueError, match="steps_per_sample"):
        ControllerSettings(steps_per_sample=0)
    with pytest.raises(ValueError, match="noise must be finite"):
        ControllerSettings(noise=-1e-3)
    p = np.array([[0.1, 0.7], [-0.2, 0.3]])
    np.testing.assert_array_equal(planar_from_base(base_from_planar(p)), p)
    # the planar FK in base coordinates: kappa > 0 bends towards base +x
    assert base_from_planar(planar_forward_kinematics([2.0, 0, 0, 0], np.full(4, 0.2))[:2, 3])[0] > 0


def test_control_step_is_the_resolved_rate_iteration_of_eq11():
    ell = build_preset("hannan_walker").section_lengths
    q0 = np.array([0.5, 0.4, 0.9, 0.2])
    target = np.array([-0.3, 0.62])
    y = planar_forward_kinematics(q0, ell)[:2, 3]
    one = planar_inverse_kinematics(target, q0, ell, max_iter=1)
    np.testing.assert_allclose(control_step(q0, y, target, ell, ControllerSettings()), one.q, rtol=0, atol=1e-15)
    kd = GRASP / ell
    one = planar_inverse_kinematics(target, q0, ell, kappa_d=kd, max_iter=1)
    np.testing.assert_allclose(control_step(q0, y, target, ell, ControllerSettings(), kd), one.q, rtol=0, atol=1e-15)


@pytest.mark.parametrize("kappa_d", [None, GRASP])
def test_with_a_cc_plant_the_controller_is_exact(kappa_d):
    """The issue's physics check: on the controller's own CC model the closed loop is the open loop."""
    robot = build_preset("hannan_walker")
    ell = robot.section_lengths
    kd = None if kappa_d is None else kappa_d / ell
    plant, cables = ConsistentCCPlant(robot), hw_cable_map(robot)
    st = ControllerSettings()
    opened, closed = run_open_loop(plant, cables, LINE, ell, st, kd), run_closed_loop(plant, cables, LINE, ell, st, kd)
    np.testing.assert_allclose(closed.kappa, opened.kappa, atol=1e-12)
    np.testing.assert_allclose(closed.tip, opened.tip, atol=1e-12)
    # and the plan is on the line (the null-space task costs ~1e-7 m at 3 steps per sample)
    assert opened.error.max() < (1e-9 if kappa_d is None else 1e-6)
    assert closed.plant_solves == 1 + 6 * st.steps_per_sample and opened.plant_solves == 6
    plan, _ = cc_plan(LINE, ell, st, kd)
    np.testing.assert_array_equal(plan, opened.kappa)
    if kappa_d is not None:  # the null-space task moved the configuration towards q_d
        q0 = start_configuration(LINE[0], ell)
        assert np.linalg.norm(plan[-1] - kd) < np.linalg.norm(q0 - kd)


def test_the_loop_removes_the_plant_model_error_and_noise_sets_its_floor():
    """The cc model reads Eq 1 commands through the CC tendon map: ~1.5 mm off open loop, exact in the loop."""
    robot = build_preset("hannan_walker")
    ell, cables = robot.section_lengths, hw_cable_map(robot)
    plant = model_plant(get_model("cc"), robot, EYELETS, 20.0)
    st = ControllerSettings()
    opened, closed = run_open_loop(plant, cables, LINE, ell, st), run_closed_loop(plant, cables, LINE, ell, st)
    assert 1e-3 < opened.error.min() and opened.error.max() < 2e-3
    assert closed.error.max() < 1e-6
    # measurement noise: with gain 1 the error after a step is the last measurement's noise
    sigma = 1e-3
    long = line_path(LINE[0], LINE[-1], 30)
    noisy = run_closed_loop(ConsistentCCPlant(robot), cables, long, ell, ControllerSettings(noise=sigma, steps_per_sample=1))
    rms = float(np.sqrt(np.mean(noisy.error[1:] ** 2)))
    assert 0.6 * sigma * np.sqrt(2) < rms < 1.5 * sigma * np.sqrt(2)
    again = run_closed_loop(ConsistentCCPlant(robot), cables, long, ell, ControllerSettings(noise=sigma, steps_per_sample=1))
    np.testing.assert_array_equal(again.tip, noisy.tip)  # seeded


def test_session_plant_gives_the_equilibria_of_fresh_solves():
    robot = build_preset("hannan_walker", base_orientation="horizontal", tendon_stiffness=1.6e4, payload_mass=0.5)
    ell, cables = robot.section_lengths, hw_cable_map(robot)
    st = ControllerSettings()
    fresh = run_open_loop(model_plant(get_model("spring_link"), robot, EYELETS, 20.0), cables, LINE[:3], ell, st)
    warm = run_open_loop(_SessionPlant(robot, EYELETS, 20.0), cables, LINE[:3], ell, st)
    np.testing.assert_allclose(warm.tip, fresh.tip, atol=1e-9)
    assert fresh.error.min() > 0.03  # soft cables + payload: 3-4 cm off open loop
    closed = run_closed_loop(_SessionPlant(robot, EYELETS, 20.0), cables, LINE[:3], ell, st)
    assert closed.error.max() < 2e-4  # the loop corrects it


STUDY = """
[study]
kind = "closed_loop"
name = "cl_tiny"
models = ["cc"]
[robot]
preset = "hannan_walker"
[scenario]
name = "closed_loop"
n_samples = 3
[load]
mode = "length"
pretension = 20.0
[solver]
n_stations = 9
[sweep]
product = { "scenario.shape" = ["line", "grasp"] }
"""


def _write(tmp_path, text: str):
    p = tmp_path / "cl.toml"
    p.write_text(text.replace('n_samples = 3', 'n_samples = 3\ngrasp_bend_angles = [-0.3, 0.3, 1.0, 1.6]'))
    return p


def test_kind_loads_validates_and_runs(tmp_path):
    p = _write(tmp_path, STUDY)
    assert kind_of(p) == "closed_loop"
    kind = get_kind("closed_loop")
    spec = kind.load(p)
    assert kind.models(spec) == row_models(["cc"]) == ("plan", "cc", "cc_closed_loop")
    assert spec.resolved()["study"]["kind"] == "closed_loop" and spec.resolved()["report"]["reference"] == "plan"
    summary = run_cases(kind, spec, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    assert (summary.n_cases, summary.n_ok) == (2, 2)
    df = pd.read_parquet(tmp_path / "out")
    assert set(df["model"]) == {"plan", "cc", "cc_closed_loop"} and (df["status"] == "ok").all()
    cl = df[df["model"] == "cc_closed_loop"]
    # 7 cm per sample on this coarse path: 3 steps bring the loop to 1e-7 (line) / 8e-6 m (grasp)
    assert (cl["x.max_tracking_error"] < 2e-5).all() and (df[df["model"] == "cc"]["x.max_tracking_error"] > 1e-3).all()
    assert (cl["x.plant_solves"] == 10).all()
    # the recorded load is the plan's last cables (the scenario)
    robot = build_preset("hannan_walker")
    last = closed_loop(robot, n_samples=3)
    row = df[(df["model"] == "plan") & (df["p.scenario.shape"] == "line")].iloc[0]
    np.testing.assert_allclose(json.loads(row["p.load.length_changes"]), last["length_changes"], rtol=0, atol=1e-15)
    from workbench.report.build import build_report

    html = build_report(tmp_path / "out", tmp_path / "rep", formats=("png",)).read_text()
    for name in ("closed_loop_sweep", "closed_loop_path", "closed_loop_shapes"):
        assert f"data-figure='{name}'" in html
    assert "Question: is constant curvature" in html and "Findings:" in html and "Assumptions:" in html


def test_kind_refuses_other_scenarios_row_names_and_references(tmp_path):
    kind = get_kind("closed_loop")
    bad = STUDY.replace('name = "closed_loop"', 'name = "hannan_walker_line"').replace('models = ["cc"]', 'models = ["plan"]')
    with pytest.raises(StudyError) as e:
        kind.load(_write(tmp_path, bad + '[report]\nreference = "nope"\n'))
    text = "\n".join(e.value.problems)
    assert "scenario.name: a closed_loop study runs the 'closed_loop' scenario" in text
    assert "study.models[0]: unknown model 'plan'" in text
    with pytest.raises(StudyError, match="report.reference: 'nope' is not one of the rows"):
        kind.load(_write(tmp_path, STUDY + '[report]\nreference = "nope"\n'))


def _failing_lookup(name):
    def run(robot, load, options):
        raise RuntimeError("plant exploded")
    return run


def test_a_failing_plant_fails_its_rows_with_the_place(tmp_path, monkeypatch):
    import workbench.models

    monkeypatch.setattr(workbench.models, "get_model", _failing_lookup)  # the plants the worker looks up
    kind = get_kind("closed_loop")
    spec = kind.load(_write(tmp_path, STUDY))
    summary = run_cases(kind, spec, tmp_path / "out", SerialExecutor(), RunConfig(progress=False))
    assert summary.n_failed == 2
    df = pd.read_parquet(tmp_path / "out")
    assert (df[df["model"] == "plan"]["status"] == "ok").all()
    err = df[df["model"] == "cc_closed_loop"]["error"].iloc[0]
    assert "PlantFailure: closed loop, start configuration: RuntimeError: plant exploded" in err
    assert "open loop, sample 0" in df[df["model"] == "cc"]["error"].iloc[0]
