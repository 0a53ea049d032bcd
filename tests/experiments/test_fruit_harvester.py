"""The fruit-harvester grasp envelope and circle fit (workbench/experiments/fruit_harvester/envelope.py)."""

from __future__ import annotations

import math

import numpy as np

from workbench.experiments.fruit_harvester.envelope import HARVESTER_LIMITS, circle_fit


def test_circle_fit_exact_on_an_arc():
    c0, R0 = np.array([0.127, -0.03]), 0.119
    a = np.linspace(0.2, 2.9, 17)  # an arc, not a full circle
    pts = c0 + R0 * np.stack([np.cos(a), np.sin(a)], -1)
    c, R = circle_fit(pts)
    np.testing.assert_allclose(c, c0, atol=1e-12)
    assert math.isclose(R, R0, rel_tol=1e-12)


def test_circle_fit_of_cc_backbone_is_the_centre_of_arc():
    # planar CC arc bending towards +x from the origin along +z: centre (1/kappa, 0)
    from workbench.kinematics.centre_of_arc import centre_of_arc_pose

    s, k = 0.4, math.pi / 0.4
    t = np.linspace(0.0, s, 33)
    pts = np.stack([(1 - np.cos(k * t)) / k, np.sin(k * t) / k], -1)
    c, R = circle_fit(pts)
    T = centre_of_arc_pose(s, k, 0.0)
    np.testing.assert_allclose([c[0], 0.0, c[1]], T[:3, 3], atol=1e-12)
    assert math.isclose(R, 1 / k, rel_tol=1e-12)


def test_harvester_envelope_reaches_the_papers_100_mm():
    lim = HARVESTER_LIMITS
    D = 0.06
    d_max = 2 * lim["s_max"] / lim["wrap_angle"] - D
    d_min = 2 / lim["kappa_max"] - D
    assert 0.1 <= d_max < 0.12 and 0 < d_min < d_max
