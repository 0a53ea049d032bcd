"""The CC cable plan shared by the hannan_walker_line scenario and replay_hannan_walker.

workbench/experiments/hannan_walker/replay.py: cc_cable_plan; scenario.py; figures.matches.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from workbench.experiments.hannan_walker.figures import matches
from workbench.experiments.hannan_walker.replay import cable_changes_from_joint_angles, cc_cable_plan
from workbench.experiments.hannan_walker.scenario import hannan_walker_line
from workbench.robot.presets import build_preset


@pytest.mark.parametrize("shape", ["line", "grasp"])
def test_scenario_sample_is_the_plan_row(shape):
    robot = build_preset("hannan_walker")
    grasp = [-0.3, 0.3, 1.0, 1.6]
    kappa_d = np.asarray(grasp) / robot.section_lengths if shape == "grasp" else None
    plan = cc_cable_plan(robot, (0.25, 0.70), (0.35, 0.60), 6, kappa_d=kappa_d)
    assert plan.success and plan.cable_changes.shape == (6, robot.n_tendons) and plan.joint_angles.shape == (6, 16)
    for k in range(6):
        out = hannan_walker_line(robot, shape=shape, n_samples=6, sample=k, grasp_bend_angles=grasp)
        one = cc_cable_plan(robot, (0.25, 0.70), (0.35, 0.60), 6, kappa_d=kappa_d, sample=k)
        assert out == {"mode": "length", "length_changes": [float(v) for v in one.cable_changes]}
        np.testing.assert_array_equal(one.cable_changes, plan.cable_changes[k])


def test_plan_is_equal_joint_angles_and_eq1_cables():
    robot = build_preset("hannan_walker")
    plan = cc_cable_plan(robot, (0.25, 0.70), (0.35, 0.60), 3)
    per = 16 // robot.n_sections
    q = plan.joint_angles.reshape(3, robot.n_sections, per)
    np.testing.assert_array_equal(q, np.repeat(q[..., :1], per, axis=-1))  # Eq 2-3: equal per section
    np.testing.assert_allclose(q[..., 0], plan.kappa * robot.section_lengths / per, rtol=1e-14)
    np.testing.assert_array_equal(plan.cable_changes, cable_changes_from_joint_angles(plan.joint_angles, robot, 16))
    np.testing.assert_allclose(plan.path[[0, -1]], [[-0.25, 0.70], [-0.35, 0.60]], atol=1e-15)  # planar (-x, z)


def test_unreachable_line_gives_no_commands_and_each_caller_its_wording():
    robot = build_preset("hannan_walker")
    plan = cc_cable_plan(robot, (0.25, 0.70), (2.0, 0.1), 4)
    assert not plan.success and plan.cable_changes is None and plan.joint_angles is None
    assert plan.tracking_error.max() > 1e-3
    with pytest.raises(ValueError, match="scenario hannan_walker_line: the CC resolved-rate controller did not "
                                         "track the line .*the line is out of reach"):
        hannan_walker_line(robot, end_x=2.0, end_z=0.1, n_samples=4)


def test_matches_only_hannan_walker_scenario_studies():
    ok = pd.DataFrame({"model": ["cc"], "p.scenario.name": ["hannan_walker_line"]})
    assert matches(SimpleNamespace(ok=ok))
    assert not matches(SimpleNamespace(ok=ok.assign(**{"p.scenario.name": ["wire_delay"]})))
    assert not matches(SimpleNamespace(ok=ok.drop(columns="p.scenario.name")))
