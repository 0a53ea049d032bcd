"""Hannan & Walker preset, Eq. (1) cable geometry and the CC -> spring-link replay."""

from __future__ import annotations

import numpy as np
import pytest

from workbench.models.result import SolverOptions
from workbench.experiments.hannan_walker.replay import (
    cable_changes_from_joint_angles,
    joint_angles_from_cable_changes,
    replay_hannan_walker,
)
from workbench.robot import LoadCase, TendonActuation
from workbench.robot.presets import build_preset


def test_preset_geometry_matches_paper():
    r = build_preset("hannan_walker")
    assert r.name == "hannan_walker"
    assert r.length == pytest.approx(0.8382)
    assert r.n_sections == 4
    assert [s.cross_section.diameter for s in r.sections] == pytest.approx([0.1016, 0.0889, 0.0762, 0.0635])
    assert [s.tendons.offset for s in r.sections] == pytest.approx([0.0508, 0.04445, 0.0381, 0.03175])
    assert r.n_tendons == 8 and build_preset("hannan_walker", planar=False).n_tendons == 16
    # joint spring k = EI / ds with ds = l / 4: the chain of 16 links has the preset's springs
    from workbench.physics.spring_link.geometry import chain_geometry_from_robot

    geo = chain_geometry_from_robot(r, 16)
    assert geo.stiffness == pytest.approx(np.repeat([120.0, 80.0, 50.0, 25.0], 4))
    assert np.sum(geo.mass) + 0.0 == pytest.approx(2.15 - 0.8 / 8)  # base plate carries half a link
    with pytest.raises(ValueError, match="4 values"):
        build_preset("hannan_walker", diameters=(0.1, 0.1))


def test_cable_map_small_angle_and_round_trip():
    robot = build_preset("hannan_walker")
    q = np.full(16, 1e-7)
    dl = cable_changes_from_joint_angles(q, robot)
    # small angles: dl = -/+ w * (sum of the joint angles the cable passes)
    w = np.repeat([0.0508, 0.04445, 0.0381, 0.03175], 2)
    n_joints = np.repeat([4, 8, 12, 16], 2)
    sign = np.tile([-1.0, 1.0], 4)
    assert dl == pytest.approx(sign * w * 1e-7 * n_joints, rel=1e-5)
    with pytest.raises(ValueError, match="shape"):
        cable_changes_from_joint_angles(np.zeros(5), robot, 16)


def test_cable_map_equals_chain_geometry():
    """Eq. (1) summed over joints equals the rope length measured on the Exudyn chain's eyelets."""
    from workbench.models.result import SolverInfo
    from workbench.physics.spring_link.driver import static_ramp
    from workbench.physics.spring_link.params import SpringLinkParams
    from workbench.physics.spring_link.planar import PlanarChain
    from workbench.physics.spring_link.geometry import chain_geometry_from_robot

    robot = build_preset("hannan_walker", gravity=0.0)
    T = np.array([300.0, 0, 0, 100.0, 200.0, 0, 0, 50.0])
    load = LoadCase(actuation=TendonActuation("tension", tuple(T)))
    opts = SolverOptions(n_elements=16, tendon_model="eyelets")
    model = PlanarChain(robot, load, opts, chain_geometry_from_robot(robot, 16))

    def apply(lam):
        model.set_external(lam)
        model.set_tendons(lam * T, lam)

    static_ramp(model, opts, SpringLinkParams(), apply)
    q = model.result(SolverInfo(True)).joint_angles[:, 0]
    assert np.abs(q).max() > 0.02  # a real bend, both directions
    measured = model.tendon_lengths() - np.array([t.reference_length for t in model.tendons])
    assert cable_changes_from_joint_angles(q, robot) == pytest.approx(measured, abs=1e-12)
    # and the sequential inverse recovers equal-per-section angles
    qeq = np.repeat([0.05, -0.02, 0.08, 0.03], 4)
    th = joint_angles_from_cable_changes(cable_changes_from_joint_angles(qeq, robot), robot, 16)
    assert th == pytest.approx([0.05, -0.02, 0.08, 0.03], abs=1e-12)


def test_replay_short_line_without_and_with_gravity():
    line = ((0.25, 0.70), (0.35, 0.60))
    rep0 = replay_hannan_walker(build_preset("hannan_walker", gravity=0.0), *line, 2, pretension=20.0)
    # the controller tracks the line in CC
    assert np.abs(rep0.cc_tip - rep0.target).max() < 1e-8
    assert rep0.cable_changes.shape == (2, 8) and rep0.joint_angles.shape == (2, 16)
    # no gravity: the stiff length-controlled cables hold (almost) the CC shape; the residual is
    # the joint springs stretching the cables (EA_t finite) - observed 1.9-2.6 mm
    assert np.all(rep0.tip_error < 5e-3)
    assert np.all(rep0.tensions >= 0)
    # every section keeps (nearly) the CC bending angle
    cc_sec = rep0.cc_joint_angles.reshape(2, 4, 4).sum(axis=2)
    ph_sec = rep0.joint_angles.reshape(2, 4, 4).sum(axis=2)
    assert np.abs(ph_sec - cc_sec).max() < 0.05
    repg = replay_hannan_walker(build_preset("hannan_walker", gravity=9.81, base_orientation="horizontal"), *line, 2,
                                pretension=20.0)
    # gravity across the bending plane of a horizontal trunk changes the error
    assert np.all(np.abs(repg.tip_error - rep0.tip_error) > 1e-4)


def test_spatial_preset_bends_out_of_plane_with_cardan_joints():
    from workbench.physics.spring_link import SpringLinkParams, solve

    robot = build_preset("hannan_walker", planar=False, gravity=0.0)
    T = np.zeros(16)
    T[1] = 40.0  # section 1, sigma = pi/2: bends towards +y
    res = solve(robot, LoadCase(actuation=TendonActuation("tension", tuple(T))),
                SolverOptions(n_elements=16, tendon_model="continuum"), SpringLinkParams(torsion="locked"))
    assert res.extras["dimension"] == 3.0 and res.joint_angles.shape == (16, 2)
    assert res.tip_position[1] > 0.01 and abs(res.tip_position[0]) < 1e-12
    # section 1 joints all turn by theta about -x (towards +y): the continuum tendon is a rope
    # through every link eyelet, whose chord passes joint k at the lever arm
    # d cos(theta/2) + (ds/2) sin(theta/2) (eyelets ds/2 either side, bent towards the tendon):
    # k theta = T * lever arm
    from scipy.optimize import brentq

    ds = robot.length / 16
    theta = brentq(lambda th: 120.0 * th - 40.0 * (0.0508 * np.cos(th / 2) + ds / 2 * np.sin(th / 2)), 0.0, 1.0)
    assert res.joint_angles[:4, 0] == pytest.approx(-theta, rel=1e-9)
