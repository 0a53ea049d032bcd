"""The CC model adapter: arc <-> tendon command maps and the model's result."""

import math

import numpy as np
import pytest

from workbench.models import SolverOptions, get_model
from workbench.models.cc import actuation_from_arc, arc_from_actuation
from workbench.robot import LoadCase, TendonActuation
from workbench.robot.presets import build_preset


@pytest.mark.parametrize("tendon_count, n_sections", [(2, 1), (3, 1), (3, 2), (4, 3), (6, 2)])
@pytest.mark.parametrize("mode", ["tension", "length"])
def test_arc_command_round_trip(tendon_count, n_sections, mode):
    robot = build_preset("steel_rod", tendon_count=tendon_count, n_sections=n_sections)
    rng = np.random.default_rng(10 * tendon_count + n_sections)
    for _ in range(5):
        kappa = rng.uniform(0.0, 4.0, n_sections)
        phi = np.zeros(n_sections) if tendon_count == 2 else rng.uniform(-np.pi, np.pi, n_sections)
        act = actuation_from_arc(robot, kappa, phi, mode)
        k2, p2, l2 = arc_from_actuation(robot, act)
        np.testing.assert_allclose(k2, kappa, atol=1e-12)
        dphi = np.angle(np.exp(1j * (p2 - phi)))
        np.testing.assert_allclose(dphi[kappa > 1e-9], 0.0, atol=1e-11)
        np.testing.assert_allclose(l2, robot.section_lengths, atol=1e-13)
        if mode == "tension":
            assert min(act.values) >= 0.0


def test_single_tendon_tension_gives_td_over_ei():
    robot = build_preset("steel_rod", tendon_count=3, tendon_offset=0.015)
    T = 12.0
    k, p, _ = arc_from_actuation(robot, TendonActuation("tension", (0.0, T, 0.0)))
    EI = robot.sections[0].cross_section.EI
    assert k[0] == pytest.approx(T * 0.015 / EI, rel=1e-14)
    assert p[0] == pytest.approx(2 * math.pi / 3, abs=1e-14)


def test_length_commands_match_closed_form():
    # one section: delta l_i = -ell kappa d cos(sigma_i - phi)  (tendon on the inside shortens)
    robot = build_preset("steel_rod", tendon_count=4, tendon_offset=0.01, length=0.5)
    act = actuation_from_arc(robot, [3.0], [0.7], "length")
    sig = np.arange(4) * np.pi / 2
    np.testing.assert_allclose(act.values, -0.5 * 3.0 * 0.01 * np.cos(sig - 0.7), atol=1e-15)


def test_antagonistic_pair_cannot_bend_out_of_plane():
    robot = build_preset("steel_rod", tendon_count=2)
    with pytest.raises(ValueError, match="cannot produce the bending moment"):
        actuation_from_arc(robot, [1.0], [np.pi / 2], "tension")


def test_cc_model_result_is_the_arc():
    robot = build_preset("steel_rod", tendon_count=3, gravity=9.81)  # CC ignores gravity
    kappa, phi = 2 * np.pi / robot.length, 0.4  # a full circle: tip back at the base
    act = actuation_from_arc(robot, [kappa], [phi], "tension")
    res = get_model("cc")(robot, LoadCase(actuation=act), SolverOptions(n_stations=21))
    assert res.positions.shape == (21, 3)
    np.testing.assert_allclose(res.tip_position, 0.0, atol=1e-13)
    np.testing.assert_allclose(res.positions[-1], res.tip_position, atol=1e-15)
    # every station lies on the circle of radius 1/kappa around (cos phi, sin phi, 0)/kappa
    centre = np.array([np.cos(phi), np.sin(phi), 0.0]) / kappa
    np.testing.assert_allclose(np.linalg.norm(res.positions - centre, axis=1), 1 / kappa, rtol=1e-12)
    assert res.length_change == 0.0 and res.solver.converged


def test_cc_model_dynamic_series_follow_the_ramps():
    robot = build_preset("steel_rod", tendon_count=2)
    act = actuation_from_arc(robot, [1.0], [0.0], "length")
    load = LoadCase(actuation=act, analysis="dynamic", duration=2.0, ramp_time=1.0)
    res = get_model("cc")(robot, load, SolverOptions(time_step=0.1))
    assert res.time.shape == (21,) and res.series["tip_position"].shape == (21, 3)
    np.testing.assert_allclose(res.series["tip_position"][0], [0, 0, robot.length], atol=1e-15)
    np.testing.assert_allclose(res.series["tip_position"][-1], res.tip_position, atol=1e-14)
    assert np.all(np.isnan(res.tendon_tensions))  # CC predicts no forces in length mode


def test_tapered_tendons_use_their_mean_offset_per_section():
    # two sections; the outer group's offset tapers 0.03 -> 0.01 over its whole routed length
    from workbench.robot import CrossSection, Robot, Section, TendonGroup

    rod = CrossSection.circular(6e-3)
    inner = TendonGroup.evenly_spaced(3, 0.03, offset_tip=0.02)
    outer = TendonGroup.evenly_spaced(3, 0.03, offset_tip=0.01)
    robot = Robot(sections=(Section(0.5, rod, inner), Section(0.5, rod, outer)))
    kappa, phi = np.array([1.0, 2.0]), np.array([0.3, -1.0])
    act = actuation_from_arc(robot, kappa, phi, "length")
    # outer tendon 0 (sigma = 0): mean offset 0.025 over section 0 and 0.015 over section 1
    expected = -0.5 * 1.0 * 0.025 * np.cos(0.0 - 0.3) - 0.5 * 2.0 * 0.015 * np.cos(0.0 + 1.0)
    assert act.values[3] == pytest.approx(expected, abs=1e-15)
    k2, p2, _ = arc_from_actuation(robot, act)
    np.testing.assert_allclose(k2, kappa, atol=1e-12)
    np.testing.assert_allclose(p2, phi, atol=1e-12)


@pytest.mark.parametrize("name", ["cc", "ancf", "beam3d", "ancf3d", "spring_link"])
def test_every_model_rejects_wrong_argument_types(name):
    robot = build_preset("steel_rod")
    with pytest.raises(TypeError, match="robot must be a workbench.Robot"):
        get_model(name)({"length": 0.8}, LoadCase(), SolverOptions())
    with pytest.raises(Exception, match="robot has 2 tendons"):
        get_model(name)(robot, LoadCase(actuation=TendonActuation("tension", (1.0, 0.0, 0.0))), SolverOptions())
