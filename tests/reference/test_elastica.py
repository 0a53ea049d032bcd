"""The elastica reference against tabulated values, closed forms and Euler-Bernoulli."""

import numpy as np
import pytest

from workbench.reference.elastica import clamped_elastica, tip_load_deflection


@pytest.mark.parametrize("alpha, expected", [(1.0, 0.30172), (3.0, 0.60325), (10.0, 0.81061)])
def test_tip_load_table(alpha, expected):
    # facts-note values, given to 5 digits
    assert abs(tip_load_deflection(alpha) - expected) < 6e-6


@pytest.mark.parametrize("gamma, expected", [(1.0, 0.123471), (4.0, 0.425159), (8.0, 0.640631)])
def test_self_weight_table(gamma, expected):
    sol = clamped_elastica(1.0, 1.0, distributed_load=(0.0, gamma), stations=2)
    assert abs(sol.tip[1] - expected) < 6e-7


def test_scaling_with_length_and_stiffness():
    # alpha = P L^2 / EI = 3 with L = 0.8, EI = 13.36
    L, EI = 0.8, 13.36
    P = 3.0 * EI / L**2
    sol = clamped_elastica(L, EI, tip_force=(0.0, P), stations=2)
    assert abs(sol.tip[1] / L - tip_load_deflection(3.0)) < 1e-9


def test_pure_moment_is_circular_arc():
    L, EI, M = 0.8, 13.36, 13.36 * np.pi / 0.8  # theta_tip = pi
    sol = clamped_elastica(L, EI, tip_moment=M, stations=17)
    k = M / EI
    s = sol.stations
    exact = np.column_stack([np.sin(k * s) / k, (1 - np.cos(k * s)) / k])
    assert np.max(np.abs(sol.positions - exact)) < 1e-9 * L
    assert np.allclose(sol.angles, k * s, atol=1e-9)


def test_small_loads_match_euler_bernoulli():
    L, EI = 0.8, 13.36
    q = 1e-4 * EI / L**3
    sol = clamped_elastica(L, EI, distributed_load=(0.0, q), stations=9)
    s = sol.stations
    w = q * s**2 * (6 * L**2 - 4 * L * s + s**2) / (24 * EI)  # EB cantilever, uniform load
    assert np.max(np.abs(sol.positions[:, 1] - w)) < 1e-6 * np.max(w)
    P = 1e-4 * EI / L**2
    sol = clamped_elastica(L, EI, tip_force=(0.0, P), stations=9)
    w = P * s**2 * (3 * L - s) / (6 * EI)
    assert np.max(np.abs(sol.positions[:, 1] - w)) < 1e-6 * np.max(w)


def test_load_at_an_angle_is_rotation_invariant():
    # the same problem with the clamp and the loads rotated by 0.7 rad gives the rotated shape
    L, EI, a = 0.8, 13.36, 0.7
    R = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    F, q = np.array([-5.0, 40.0]), np.array([3.0, -20.0])
    s1 = clamped_elastica(L, EI, tip_force=F, distributed_load=q, tip_moment=2.0, stations=9)
    s2 = clamped_elastica(L, EI, tip_force=R @ F, distributed_load=R @ q, tip_moment=2.0,
                          theta0=a, stations=9)
    assert np.allclose(s2.positions, s1.positions @ R.T, atol=1e-9)


def test_tapered_stiffness_small_load():
    # EI(s) linear taper; EB tip deflection by the unit-load integral  w = int M m / EI ds
    L, EI0, EI1, P = 0.8, 20.0, 5.0, 1e-4
    EI = lambda s: EI0 + (EI1 - EI0) * np.asarray(s) / L
    sol = clamped_elastica(L, EI, tip_force=(0.0, P), stations=2)
    s = np.linspace(0, L, 20001)
    w = np.trapezoid(P * (L - s) ** 2 / EI(s), s)
    assert abs(sol.tip[1] - w) < 1e-5 * w


def test_bad_input():
    with pytest.raises(ValueError, match="length"):
        clamped_elastica(-1.0, 1.0)
    with pytest.raises(ValueError, match="shape"):
        clamped_elastica(1.0, 1.0, tip_force=(1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="bending_stiffness"):
        clamped_elastica(1.0, 0.0)
