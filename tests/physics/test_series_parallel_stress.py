"""Leg stresses of the series-parallel module against hand formulas and the solved rod's own curvature."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from workbench.physics.series_parallel import ModuleGeometry, module_inverse, pose_from_xyz_rotvec
from workbench.physics.series_parallel.stress import leg_stress, module_leg_stress

D = 0.006
A = math.pi * D**2 / 4
W = math.pi * D**3 / 32  # I / c


def _straight(n=9, L=0.5):
    return np.column_stack([np.zeros(n), np.zeros(n), np.linspace(0.0, L, n)])


def test_straight_leg_under_axial_load_is_F_over_A():
    s = leg_stress(_straight(), [0.0, 0.0, -150.0], [0.0, 0.0, 0.0], D)
    assert s == pytest.approx(np.full(9, 150.0 / A), rel=1e-12)


def test_cantilevered_leg_under_tip_force_and_moment():
    # lateral tip force F_x and tip moment M_y on a straight leg along z: M(s) = M_y + F (L - s)
    F, My, L = 3.0, 0.2, 0.5
    p = _straight(L=L)
    s = leg_stress(p, [F, 0.0, 40.0], [0.0, My, 0.0], D)
    M = np.abs(My + F * (L - p[:, 2]))  # m(s) = m(L) + (p(L) - p(s)) x n: y-component (L - s) F
    assert s == pytest.approx(40.0 / A + M / W, rel=1e-12)
    assert s[0] == pytest.approx(40.0 / A + (My + F * L) / W, rel=1e-12)


def test_solved_module_stress_matches_the_rods_curvature():
    """Statics of the distal part (what leg_stress uses) vs E I kappa of the solved centreline."""
    geo = ModuleGeometry(height=0.5, rod_diameter=D)
    ik = module_inverse(geo, pose_from_xyz_rotvec([0.05, 0.0, 0.5], [0.0, 0.0, 0.0]), n_elements=16)
    assert ik.success
    E, I = geo.youngs_modulus, math.pi * D**4 / 64
    for i in range(6):
        p = np.asarray(ik.leg_positions[i])
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
        spl = CubicSpline(s, p)
        kappa = np.linalg.norm(np.cross(spl(s, 1), spl(s, 2)), axis=1) / np.linalg.norm(spl(s, 1), axis=1) ** 3
        n, m = np.asarray(ik.tip_forces[i]), np.asarray(ik.tip_moments[i])
        t = spl(s, 1) / np.linalg.norm(spl(s, 1), axis=1, keepdims=True)
        mom = m[None, :] + np.cross(p[-1] - p, n)
        mb = np.linalg.norm(mom - np.sum(mom * t, axis=1, keepdims=True) * t, axis=1)
        inner = slice(2, -2)  # spline end effects
        assert mb[inner] == pytest.approx(E * I * kappa[inner], rel=0.05, abs=0.02 * np.max(mb))
    worst = module_leg_stress(geo, [ik])
    per_leg = [np.max(leg_stress(ik.leg_positions[i], ik.tip_forces[i], ik.tip_moments[i], D)) for i in range(6)]
    assert worst == pytest.approx(max(per_leg)) and worst > 0
