"""Cosserat shooting reference (Huang et al. Eq 18-20) against analytic solutions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from workbench.reference.cosserat import (
    RodStiffness,
    integrate_cosserat_rod,
    rotation_log,
    solve_rod_tip_pose,
    solve_rod_tip_wrench,
)

# steel rod, d = 6 mm, L = 0.5 m (the default leg of the series-parallel module)
K = RodStiffness.circular(0.006, 200e9, 200e9 / 2.6)
L = 0.5


def test_circular_section_stiffness():
    d, E, G = 0.006, 200e9, 200e9 / 2.6
    assert K.EA == pytest.approx(E * math.pi * d**2 / 4, rel=1e-14)
    assert K.EI == pytest.approx(E * math.pi * d**4 / 64, rel=1e-14)
    assert K.GJ == pytest.approx(G * math.pi * d**4 / 32, rel=1e-14)
    assert K.GA == pytest.approx(G * math.pi * d**2 / 4, rel=1e-14)


@pytest.mark.parametrize("angle", [math.pi / 3, math.pi, 1.5 * math.pi])
@pytest.mark.parametrize("axis_deg", [0.0, 37.0])
def test_pure_tip_moment_gives_circular_arc(angle, axis_deg):
    """Moment M about an in-plane axis: circle of radius EI/M (exact, any angle)."""
    a = math.radians(axis_deg)
    axis = np.array([math.cos(a), math.sin(a), 0.0])
    M = angle * K.EI / L
    R0 = np.eye(3)
    sol = solve_rod_tip_wrench(np.zeros(3), R0, L, K, tip_moment=M * axis)
    assert sol.converged
    rho = L / angle
    # a positive moment about `axis` turns the tangent z towards b = axis x z
    b = np.cross(axis, [0.0, 0.0, 1.0])
    s = sol.s
    expected = rho * np.sin(s / rho)[:, None] * np.array([0, 0, 1.0]) + rho * (1 - np.cos(s / rho))[:, None] * b
    np.testing.assert_allclose(sol.positions, expected, atol=1e-9 * L)
    # tip frame = rotation by `angle` about `axis`
    R_exp = Rotation.from_rotvec(angle * axis).as_matrix()
    assert np.max(np.abs(rotation_log(sol.tip_rotation.T @ R_exp))) < 1e-9


def test_small_tip_load_matches_euler_bernoulli():
    """alpha = P L^2 / EI = 0.01: tip deflection P L^3 / (3 EI) (+ shear P L / GA)."""
    P = 0.01 * K.EI / L**2
    sol = solve_rod_tip_wrench(np.zeros(3), np.eye(3), L, K, tip_force=[P, 0.0, 0.0])
    assert sol.converged
    delta_lin = P * L**3 / (3 * K.EI) + P * L / K.GA
    # geometric nonlinearity is O(alpha^2) relative: < 1e-4 for alpha = 0.01
    assert sol.tip_position[0] == pytest.approx(delta_lin, rel=2e-4)
    assert abs(sol.tip_position[1]) < 1e-15
    # slope at the tip P L^2 / (2 EI)
    slope = math.atan2(sol.tip_rotation[0, 2], sol.tip_rotation[2, 2])
    assert slope == pytest.approx(P * L**2 / (2 * K.EI), rel=2e-4)


def test_large_tip_load_matches_inextensible_elastica():
    """alpha = 3: tip deflection / L = 0.60325 (inextensible elastica, facts note)."""
    P = 3.0 * K.EI / L**2
    sol = solve_rod_tip_wrench(np.zeros(3), np.eye(3), L, K, tip_force=[P, 0.0, 0.0], n_steps=3)
    assert sol.converged
    # extensibility/shear of this slender rod change it by ~ P/EA ~ 1e-5 relative
    assert sol.tip_position[0] / L == pytest.approx(0.60325, abs=5e-5)


def test_distributed_load_is_integrated():
    """n' = -f: n(s) = (L - s) f, zero at the free tip."""
    f = np.array([0.0, -2.0, 0.0])
    sol = solve_rod_tip_wrench(np.zeros(3), np.eye(3), L, K, distributed_force=f)
    assert sol.converged
    np.testing.assert_allclose(sol.forces, (L - sol.s)[:, None] * f[None, :], atol=1e-9)
    # small self-weight-like sag: q L^4 / (8 EI)
    assert -sol.tip_position[1] == pytest.approx(2.0 * L**4 / (8 * K.EI), rel=5e-3)


def test_tip_pose_problem_recovers_the_wrench():
    """Solve a 3-D cantilever, then the clamped-clamped problem to its tip pose: same tip wrench."""
    w = np.array([30.0, -20.0, 10.0, 3.0, 5.0, 2.0])
    cant = solve_rod_tip_wrench(np.zeros(3), np.eye(3), L, K, w[:3], w[3:], n_steps=2)
    assert cant.converged
    # start 20 % off the true base wrench (the pose problem has other, buckled branches)
    guess = np.concatenate([cant.forces[0], cant.moments[0]]) * 1.2
    bvp = solve_rod_tip_pose(
        np.zeros(3), np.eye(3), L, K, cant.tip_position, cant.tip_rotation, free_base_twist=False, initial_guess=guess
    )
    assert bvp.converged
    np.testing.assert_allclose(bvp.forces[-1], w[:3], atol=1e-6)
    np.testing.assert_allclose(bvp.moments[-1], w[3:], atol=1e-7)


def test_twist_free_base_has_no_torsional_moment():
    """Hole condition (Eq 21): m(0) . t(0) = 0 and the base section turns freely."""
    w = np.array([30.0, -20.0, 10.0, 3.0, 5.0, 2.0])
    cant = solve_rod_tip_wrench(np.zeros(3), np.eye(3), L, K, w[:3], w[3:], n_steps=2)
    m0 = cant.moments[0]
    guess = np.concatenate([cant.forces[0], m0[:2], [0.0]])
    bvp = solve_rod_tip_pose(np.zeros(3), np.eye(3), L, K, cant.tip_position, cant.tip_rotation, initial_guess=guess)
    assert bvp.converged
    assert abs(bvp.moments[0] @ bvp.rotations[0][:, 2]) < 1e-12
    assert abs(bvp.base_twist) > 1e-3  # the tip twist moment M_z was released at the base
    np.testing.assert_allclose(bvp.tip_position, cant.tip_position, atol=1e-10)


def test_integration_keeps_rotations_orthonormal():
    sol = integrate_cosserat_rod(np.zeros(3), np.eye(3), [1.0, 2.0, -50.0], [0.5, -0.3, 0.2], L, K)
    for R in sol.rotations:
        np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-12)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(p0=np.zeros(2)), "shape \\(3,\\)"),
        (dict(R0=np.ones((3, 3))), "proper rotation"),
        (dict(length=-1.0), "length"),
    ],
)
def test_bad_input_is_rejected(kwargs, match):
    args = dict(p0=np.zeros(3), R0=np.eye(3), n0=np.zeros(3), m0=np.zeros(3), length=L, stiffness=K)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        integrate_cosserat_rod(**args)


def test_bad_stiffness_is_rejected():
    with pytest.raises(ValueError, match="EI"):
        RodStiffness(EA=1.0, GA=1.0, EI=0.0, GJ=1.0)
