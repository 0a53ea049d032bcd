"""Cojocaru's whole arm with passive upper sections (workbench/experiments/wire_delay/arm.py, scenario, figures_arm).

The passive wires' path changes against the paper's Eq 4-11 of section 1's own wires and the small-angle
form; what CC kinematics makes of the held / compensated commands on a cylindrical arm (analytic: held
bends section 2 back by exactly -theta, compensated keeps the upper sections straight); (slow) beam3d.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from workbench.experiments.wire_delay.analysis import wire_delay_commands
from workbench.experiments.wire_delay.arm import arm_commands, passive_wire_changes
from workbench.experiments.wire_delay.figures_arm import decoupled_target_tip, matches
from workbench.experiments.wire_delay.scenario import wire_delay_arm
from workbench.models.cc import arc_from_actuation
from workbench.robot import TendonActuation
from workbench.robot.presets import build_preset

Q = math.pi / 4


def test_upper_wires_share_section_1s_cone_so_their_path_changes_are_its_wire_changes():
    robot = build_preset("cojocaru_tronconic", n_sections=3)
    c = passive_wire_changes(robot, Q, Q)
    first = wire_delay_commands(robot, theta=Q, alpha=Q, move_time=4.0, delay=0.0, delayed_wire=0).length_changes
    # every wire runs on the same cone rim (100 -> 40 mm over the arm): in section 1 all are 50 -> 40 mm
    np.testing.assert_allclose(c[:3], first, atol=1e-15)
    np.testing.assert_allclose(c[3:], first, atol=1e-15)
    # a cylindrical arm: every wire changes by exactly -d theta cos(sigma - phi) (Eq 19)
    cyl = build_preset("cojocaru_tronconic", n_sections=3, disk_diameter_step=0.0)
    sig = np.asarray(cyl.sections[1].tendons.angles)
    for theta in (1e-3, Q):
        np.testing.assert_allclose(passive_wire_changes(cyl, theta, Q)[:3], -0.05 * theta * np.cos(sig - (Q + math.pi)),
                                   rtol=1e-9, atol=1e-15)


def test_arm_commands_per_passive_mode():
    robot = build_preset("cojocaru_tronconic", n_sections=3)
    c = passive_wire_changes(robot, Q, Q)
    kw = dict(theta=Q, alpha=Q, move_time=4.0, delay=3.0, delayed_wire=0, slack_margin=2e-3)
    held = arm_commands(robot, passive="held", **kw)
    np.testing.assert_array_equal(held.length_changes[3:], 0.0)
    np.testing.assert_array_equal(arm_commands(robot, passive="compensated", **kw).length_changes[3:], c)
    np.testing.assert_array_equal(arm_commands(robot, passive="slack", **kw).length_changes[3:], np.maximum(c, 0) + 2e-3)
    assert held.start_delays == (3.0, 0.0, 0.0) + (0.0,) * 6 and held.ramp_durations == (4.0,) * 9
    with pytest.raises(ValueError, match="passive must be one of held, compensated, slack"):
        arm_commands(robot, passive="free", **kw)
    out = wire_delay_arm(robot, delay=3.0, passive="compensated")
    assert out["duration"] == 8.0 and out["analysis"] == "dynamic" and len(out["length_changes"]) == 9
    with pytest.raises(ValueError, match="scenario wire_delay_arm: the arm needs two or more sections"):
        wire_delay_arm(build_preset("cojocaru_tronconic", n_sections=1))


def _cc_arcs(robot, passive: str):
    out = wire_delay_arm(robot, passive=passive)
    return arc_from_actuation(robot, TendonActuation("length", tuple(out["length_changes"])))


def test_cc_kinematics_of_the_passive_commands_on_a_cylindrical_arm():
    """Held: section 2 bends back by exactly -theta (section 3 straight); compensated: both straight."""
    robot = build_preset("cojocaru_tronconic", n_sections=3, disk_diameter_step=0.0)
    H = robot.sections[0].length
    kappa, phi, _ = _cc_arcs(robot, "held")
    assert kappa[0] * H == pytest.approx(Q, rel=2e-3)  # the CC map's linear wire model vs Eq 4-11 (2nd order)
    assert kappa[1] == pytest.approx(kappa[0], rel=1e-9) and abs(math.cos(phi[1] - phi[0]) + 1) < 1e-9
    assert kappa[2] * H < 1e-9
    kappa, phi, _ = _cc_arcs(robot, "compensated")
    assert kappa[0] * H == pytest.approx(Q, rel=2e-3) and np.all(kappa[1:] * H < 1e-9)
    # the decoupled target: section 1's arc, the upper sections straight along its end tangent
    tip = decoupled_target_tip(robot, Q, Q + math.pi)
    R = H / Q
    end = R * (1 - math.cos(Q)) * np.array([math.cos(Q + math.pi), math.sin(Q + math.pi), 0.0]) + [0, 0, R * math.sin(Q)]
    t = np.array([math.sin(Q) * math.cos(Q + math.pi), math.sin(Q) * math.sin(Q + math.pi), math.cos(Q)])
    np.testing.assert_allclose(tip, end + 2 * H * t, atol=1e-12)


def test_matches_only_arm_studies():
    ok = pd.DataFrame({"model": ["cc"], "p.scenario.name": ["wire_delay_arm"]})
    assert matches(SimpleNamespace(ok=ok))
    assert not matches(SimpleNamespace(ok=ok.assign(**{"p.scenario.name": ["wire_delay"]})))


@pytest.mark.slow  # two beam3d dynamics of the 3-section arm: ~1-2 min
def test_beam3d_held_wires_bend_the_upper_sections_back_compensated_keep_them_straight():
    from workbench.models import SolverOptions, get_model
    from workbench.study.build import build_load

    robot = build_preset("cojocaru_tronconic", n_sections=3)
    opts = SolverOptions(n_elements=6, tendon_model="eyelets", time_step=1e-2, n_stations=25)
    tips = {}
    for passive in ("held", "compensated"):
        f = {**wire_delay_arm(robot, move_time=2.0, settle_time=0.5, passive=passive), "pretension": 20.0}
        tips[passive] = get_model("beam3d")(robot, build_load(robot, f), opts).tip_position
    target = decoupled_target_tip(robot, Q, Q + math.pi)
    assert np.linalg.norm(tips["compensated"] - target) < 0.05 < np.linalg.norm(tips["held"] - target)
