"""The 32-DOF Hannan & Walker trunk: preset, Eq. 1 per plane, the spatial plan, the two-DOF-joint model.

workbench/robot/presets/hannan_walker_3d.py, workbench/experiments/hannan_walker/spatial.py,
scenario.hannan_walker_spatial, figures_3d.matches, workbench/physics/spring_link/cardan.py.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from workbench.experiments.hannan_walker.figures_3d import gravity_label, matches
from workbench.experiments.hannan_walker.replay import cable_changes_from_joint_angles, cc_cable_plan
from workbench.experiments.hannan_walker.scenario import hannan_walker_spatial
from workbench.experiments.hannan_walker.spatial import (
    cable_changes_from_cardan_angles,
    cardan_angles_from_arcs,
    cc_spatial_cable_plan,
)
from workbench.kinematics import forward_kinematics
from workbench.models import ModelFailure, SolverOptions
from workbench.physics.spring_link import cardan
from workbench.robot import LoadCase, TendonActuation
from workbench.robot.presets import build_preset

EYELETS = SolverOptions(n_elements=16, tendon_model="eyelets")


def _planar_to_spatial(dl8: np.ndarray) -> np.ndarray:
    """8 planar cable commands (sigma 0, pi per section) -> 16 (sigma 0, pi/2, pi, 3pi/2), y-plane unchanged."""
    out = np.zeros(16)
    out[0::4], out[2::4] = dl8[0::2], dl8[1::2]
    return out


def test_preset_is_the_16_cable_robot_with_gravity_in_any_direction():
    r = build_preset("hannan_walker_3d", base_orientation="horizontal", gravity_direction=[0.0, 2.0, -2.0])
    assert r.n_tendons == 16 and r.n_sections == 4 and r.name == "hannan_walker_3d"
    assert [s for _, s, _ in r.tendon_table()[:4]] == pytest.approx([0.0, np.pi / 2, np.pi, 1.5 * np.pi])
    np.testing.assert_allclose(r.gravity, 9.81 * np.array([0.0, 1.0, -1.0]) / np.sqrt(2.0), rtol=1e-15)
    # horizontal mount, rolled 45 deg: gravity between the two cable planes, in the base frame
    np.testing.assert_allclose(r.gravity_in_base(), 9.81 * np.array([-1.0, -1.0, 0.0]) / np.sqrt(2.0), atol=1e-14)
    assert gravity_label({"p.robot.gravity": 9.81, "p.robot.gravity_direction": "[0, 1, -1]",
                          "p.robot.base_orientation": "horizontal"}) == "g along base (-0.71, -0.71, 0)"
    # everything else is the planar preset's
    p = build_preset("hannan_walker")
    assert [s.cross_section for s in r.sections] == [s.cross_section for s in p.sections]
    with pytest.raises(ValueError, match="gravity_direction must be 3 finite numbers"):
        build_preset("hannan_walker_3d", gravity_direction=[0.0, 0.0, 0.0])


def test_eq1_per_plane_reduces_to_the_planar_map():
    robot3, robot2 = build_preset("hannan_walker_3d"), build_preset("hannan_walker")
    rng = np.random.default_rng(3)
    b = rng.uniform(-0.15, 0.15, (5, 16))
    q = np.stack([np.zeros_like(b), b], axis=-1)  # bending towards +-x only
    dl3 = cable_changes_from_cardan_angles(q, robot3)
    np.testing.assert_array_equal(dl3[:, 0::4], cable_changes_from_joint_angles(b, robot2)[:, 0::2])
    np.testing.assert_array_equal(dl3[:, 2::4], cable_changes_from_joint_angles(b, robot2)[:, 1::2])
    np.testing.assert_allclose(dl3[:, 1::2], 0.0, atol=1e-15)  # y-plane cables see no joint angle (round-off)
    # a y-plane bend is the x-plane bend turned by 90 deg: towards +y is Cardan a < 0
    qy = np.stack([-b, np.zeros_like(b)], axis=-1)
    np.testing.assert_allclose(cable_changes_from_cardan_angles(qy, robot3)[:, 1::4], dl3[:, 0::4], rtol=0, atol=0)
    with pytest.raises(ValueError, match="x-z or y-z plane"):
        cable_changes_from_cardan_angles(q, build_preset("steel_rod", n_sections=1, tendon_count=3))


def _solve_tree_tensions(robot, T):
    """The Exudyn Cardan tree under cable tensions ``T``: (Cardan angles (16, 2), measured rope changes)."""
    from workbench.models.result import SolverInfo
    from workbench.physics.spring_link import chain_geometry_from_robot
    from workbench.physics.spring_link.driver import static_ramp
    from workbench.physics.spring_link.tree import TreeChain

    load = LoadCase(actuation=TendonActuation("tension", tuple(T)))
    model = TreeChain(robot, load, EYELETS, chain_geometry_from_robot(robot, 16), spatial=True)

    def apply(lam):
        model.set_external(lam)
        model.set_tendons(lam * np.asarray(T), lam)

    static_ramp(model, EYELETS, cardan.CARDAN, apply)
    q = model.result(SolverInfo(True)).joint_angles
    measured = model.tendon_lengths() - np.array([t.reference_length for t in model.tendons])
    return q, measured


@pytest.mark.slow  # three tension-rope solves on the 3-D tree: ~5 s alone
def test_eq1_per_plane_is_the_exudyn_rope_length_in_the_bending_plane_and_second_order_off_it():
    """Per-plane Eq. 1 against the rope lengths measured on the Exudyn Cardan chain's eyelets."""
    from workbench.physics.spring_link import chain_geometry_from_robot

    robot = build_preset("hannan_walker_3d", gravity=0.0)
    h = 0.5 * np.diff(chain_geometry_from_robot(robot, 16).eyelets)
    T = np.zeros(16)
    T[[1, 5, 13]] = [300.0, 150.0, 60.0]  # y-plane cables only: a bend in the y-z plane
    q, measured = _solve_tree_tensions(robot, T)
    assert np.abs(q[:, 0]).max() > 0.05 and np.abs(q[:, 1]).max() < 1e-12
    eq1 = cable_changes_from_cardan_angles(q, robot)
    np.testing.assert_allclose(eq1[1::2], measured[1::2], atol=1e-12)  # the cables of the bending plane: exact
    # the x-plane cables lie on the bend's neutral line: each joint shortens their span to the chord
    # 2 h cos(a/2), second order in a, which Eq. 1 per plane (angle 0 in their plane) does not see
    for i, (j, _, _) in enumerate(robot.tendon_table()):
        if i % 2 == 0:
            m = 4 * (j + 1)
            assert measured[i] == pytest.approx(-np.sum(2 * h[:m] * (1 - np.cos(q[:m, 0] / 2))), abs=1e-12)
            assert abs(eq1[i]) < 1e-15 and measured[i] < -1e-3
    # an oblique bend: the gap is second order in the joint angles (~4x per halving of the load)
    gaps = []
    for scale in (1.0, 0.5):
        T = np.zeros(16)
        T[[0, 1, 8, 9]] = scale * np.array([200.0, 200.0, 80.0, 80.0])
        q, measured = _solve_tree_tensions(robot, T)
        gaps.append(np.abs(cable_changes_from_cardan_angles(q, robot) - measured).max())
    assert gaps[0] > 1e-4 and 3.0 < gaps[0] / gaps[1] < 5.0


@pytest.mark.parametrize("gravity, orientation", [(0.0, "vertical"), (9.81, "horizontal")])
def test_planar_motions_of_the_32_dof_chain_equal_the_planar_chain(gravity, orientation):
    """The issue's physics check: a planar plan on 16 two-DOF joints / 16 cables = 16 joints / 8 cables."""
    from workbench.physics.spring_link import solve

    r2 = build_preset("hannan_walker", gravity=gravity, base_orientation=orientation)
    r3 = build_preset("hannan_walker_3d", gravity=gravity, base_orientation=orientation)
    plan = cc_cable_plan(r2, (0.25, 0.70), (0.35, 0.60), 3, sample=2)
    for pretension in (0.0, 20.0):
        a = solve(r2, LoadCase(actuation=TendonActuation("length", tuple(plan.cable_changes), pretension=pretension)),
                  EYELETS)
        b = cardan.run(r3, LoadCase(actuation=TendonActuation("length", tuple(_planar_to_spatial(plan.cable_changes)),
                                                               pretension=pretension)), EYELETS)
        assert a.extras["dimension"] == 2.0 and b.extras["dimension"] == 3.0 and b.joint_angles.shape == (16, 2)
        np.testing.assert_allclose(b.tip_position, a.tip_position, atol=1e-9)
        np.testing.assert_allclose(b.positions, a.positions, atol=1e-9)
        np.testing.assert_allclose(b.joint_angles[:, 1], a.joint_angles[:, 0], atol=1e-9)
        # the bend shortens the y-plane cable paths by more than the pretension stretched them: slack
        np.testing.assert_array_equal(b.tendon_tensions[1::2], 0.0)


def test_spatial_plan_tracks_the_line_and_the_scenario_is_its_sample():
    robot = build_preset("hannan_walker_3d")
    line = ((0.25, -0.10, 0.70), (0.15, 0.25, 0.60))
    plan = cc_spatial_cable_plan(robot, *line, 4)
    assert plan.success and plan.tracking_error.max() < 1e-9 and plan.cable_changes.shape == (4, 16)
    tips = forward_kinematics(plan.kappa, plan.phi, robot.section_lengths)[:, :3, 3]
    np.testing.assert_allclose(tips, plan.path, atol=1e-9)
    assert np.ptp(plan.phi) > 0.3  # a spatial line: the bending planes turn along it
    np.testing.assert_array_equal(plan.cardan, cardan_angles_from_arcs(plan.kappa, plan.phi, robot.section_lengths, 4))
    out = hannan_walker_spatial(robot, n_samples=4, sample=3)
    assert out == {"mode": "length", "length_changes": [float(v) for v in plan.cable_changes[3]]}
    grasp = hannan_walker_spatial(robot, shape="grasp", n_samples=4, sample=3, grasp_bend_angles=[-0.3, 0.3, 1.0, 1.6])
    assert np.abs(np.asarray(grasp["length_changes"]) - out["length_changes"]).max() > 1e-3
    with pytest.raises(ValueError, match="needs grasp_bend_angles with 4 entries"):
        hannan_walker_spatial(robot, shape="grasp")
    with pytest.raises(ValueError, match="out of reach"):
        hannan_walker_spatial(robot, end_x=2.0)


def test_cardan_model_bends_out_of_plane_and_refuses_overstretched_cables(monkeypatch):
    robot = build_preset("hannan_walker_3d", gravity=0.0)
    out = hannan_walker_spatial(robot, n_samples=4, sample=3)
    res = cardan.run(robot, LoadCase(actuation=TendonActuation("length", tuple(out["length_changes"]),
                                                               pretension=20.0)), EYELETS)
    assert res.tip_position[1] > 0.2 and np.all(res.tendon_tensions >= 0)
    assert res.tendon_tensions.max() / 1.6e5 < cardan.MAX_CABLE_STRAIN
    folded = SimpleNamespace(tendon_tensions=np.full(16, 1.7e5))
    monkeypatch.setattr(cardan, "solve", lambda *a, **k: folded)
    with pytest.raises(ModelFailure, match=r"cable 0 at 1\.7e\+05 N, strain 1\.06 > 0\.02"):
        cardan.run(robot, LoadCase(actuation=TendonActuation("length", tuple(out["length_changes"]))), EYELETS)


def test_matches_only_spatial_scenario_studies():
    ok = pd.DataFrame({"model": ["cc"], "p.scenario.name": ["hannan_walker_spatial"]})
    assert matches(SimpleNamespace(ok=ok))
    assert not matches(SimpleNamespace(ok=ok.assign(**{"p.scenario.name": ["hannan_walker_line"]})))


def test_study_file_loads_with_signed_gravity_directions(tmp_path):
    """A direction vector's components have either sign; gravity's magnitude must still be >= 0."""
    from pathlib import Path

    from workbench.study import StudyError, load_study

    study = Path(__file__).resolve().parents[2] / "tests" / "regression" / "studies" / "hannan_walker_3d.toml"
    assert load_study(study).name == "hannan_walker_3d"  # 2 cases: the full study is checked in tests/study
    bad = tmp_path / "bad.toml"
    bad.write_text(study.read_text().replace('"robot.base_orientation" = "vertical",',
                                             '"robot.gravity" = -9.81, "robot.base_orientation" = "vertical",', 1))
    with pytest.raises(StudyError, match=r"robot.gravity.*must be >= 0"):
        load_study(bad)
