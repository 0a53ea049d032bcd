"""Tendon maps: geometric check against integrated tendon paths, round trips, validation."""

import numpy as np
import pytest

from workbench.kinematics import (
    arc_from_tendon_lengths,
    arcs_from_tendon_lengths,
    forward_kinematics,
    tendon_lengths_from_arc,
    tendon_lengths_from_arcs,
)


def _integrated_tendon_length(kappa, phi, ell, sigma, d, upto, n_pts=4001):
    """Polyline length of the tendon curve p(s) + R(s) d (cos sigma, sin sigma, 0) (independent
    of the closed form; uses the backbone frames of forward_kinematics)."""
    s = np.linspace(0.0, np.sum(ell[: upto + 1]), n_pts)
    F = forward_kinematics(kappa, phi, ell, s)
    dvec = np.array([d * np.cos(sigma), d * np.sin(sigma), 0.0, 1.0])
    pts = (F @ dvec)[:, :3]
    return np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1))


def test_inside_tendon_is_shorter_and_matches_geometry():
    kappa, phi, ell, d = 4.0, 0.7, 0.3, 0.02
    sig = np.array([phi, phi + np.pi, phi + np.pi / 2])
    L = tendon_lengths_from_arc(kappa, phi, ell, sig, d)
    assert L[0] < ell < L[1]
    np.testing.assert_allclose(L[2], ell)
    for i, sg in enumerate(sig):
        Li = _integrated_tendon_length(np.array([kappa]), np.array([phi]), np.array([ell]), sg, d, 0)
        np.testing.assert_allclose(L[i], Li, rtol=1e-6)


def test_multisection_matches_integrated_tendon_paths():
    rng = np.random.default_rng(30)
    n = 3
    kappa = rng.uniform(-5, 5, n)
    phi = rng.uniform(-np.pi, np.pi, n)
    ell = rng.uniform(0.1, 0.3, n)
    d = np.array([0.03, 0.025, 0.02])
    sigma = np.array([[0.0, 2.1, 4.2], [0.3, 2.4, 4.5], [0.6, 2.7, 4.8]])
    L = tendon_lengths_from_arcs(kappa, phi, ell, sigma, d)
    assert L.shape == (3, 3)
    # a tendon of section j is parallel to the backbone at offset d_i inside section i: only
    # possible with one d when d is equal across sections -> compare with d constant
    Lc = tendon_lengths_from_arcs(kappa, phi, ell, sigma, 0.02)
    for j in range(n):
        for k in range(3):
            ref = _integrated_tendon_length(kappa, phi, ell, sigma[j, k], 0.02, j, n_pts=6001)
            np.testing.assert_allclose(Lc[j, k], ref, rtol=1e-6)
    # per-section d: section-wise sums of the single-section formula
    for j in range(n):
        tot = sum(tendon_lengths_from_arc(kappa[i], phi[i], ell[i], sigma[j], d[i]) for i in range(j + 1))
        np.testing.assert_allclose(L[j], tot, rtol=1e-14)


@pytest.mark.parametrize("m", [3, 4, 5])
def test_round_trip_equally_spaced(m):
    rng = np.random.default_rng(31 + m)
    sigma = 0.3 + 2 * np.pi * np.arange(m) / m
    kappa = rng.uniform(0, 20, 200)
    phi = rng.uniform(-np.pi, np.pi, 200)
    ell = rng.uniform(0.05, 0.5, 200)
    L = tendon_lengths_from_arc(kappa, phi, ell, sigma, 0.01)
    k2, p2, l2, res = arc_from_tendon_lengths(L, sigma, 0.01, return_residual=True)
    np.testing.assert_allclose(k2, kappa, atol=1e-9)
    np.testing.assert_allclose(l2, ell, rtol=1e-12)
    np.testing.assert_allclose(np.angle(np.exp(1j * (p2 - phi))), 0.0, atol=1e-8)
    np.testing.assert_allclose(res, 0.0, atol=1e-14)


def test_round_trip_general_angles_and_straight():
    sigma = np.array([0.0, 1.0, 2.5, 4.0, 5.5])
    L = tendon_lengths_from_arc(3.0, -2.0, 0.2, sigma, 0.015)
    k, p, l = arc_from_tendon_lengths(L, sigma, 0.015)
    np.testing.assert_allclose([k, p, l], [3.0, -2.0, 0.2], atol=1e-10)
    # straight section: kappa = 0 up to rounding of cos(2 pi/3), no warnings
    k, p, l = arc_from_tendon_lengths(np.full(3, 0.2), [0, 2 * np.pi / 3, 4 * np.pi / 3], 0.01)
    assert k < 1e-12 and l == pytest.approx(0.2)
    # inconsistent lengths give a positive residual (least squares)
    _, _, _, r = arc_from_tendon_lengths(L + [0.001, 0, 0, 0, 0], sigma, 0.015, return_residual=True)
    assert r > 1e-4


def test_nearly_equally_spaced_angles_use_general_least_squares():
    # 120 deg rounded to 4 decimals in rad: not equally spaced -> the closed form would be
    # wrong by ~1e-5 relative; the general solver must still be exact
    sigma = [0.0, 2.0944, 4.1888]
    L = tendon_lengths_from_arc(5.0, 0.4, 0.2, sigma, 0.01)
    np.testing.assert_allclose(arc_from_tendon_lengths(L, sigma, 0.01), [5.0, 0.4, 0.2], rtol=1e-10)


def test_multisection_round_trip():
    rng = np.random.default_rng(35)
    kappa = rng.uniform(0.1, 10, (20, 4))
    phi = rng.uniform(-np.pi + 0.01, np.pi, (20, 4))
    ell = rng.uniform(0.1, 0.3, (20, 4))
    sigma = np.array([0, np.pi / 2, np.pi, 3 * np.pi / 2])
    d = np.array([0.05, 0.04, 0.035, 0.03])
    L = tendon_lengths_from_arcs(kappa, phi, ell, sigma, d)
    k2, p2, l2 = arcs_from_tendon_lengths(L, sigma, d)
    np.testing.assert_allclose(k2, kappa, rtol=1e-9)
    np.testing.assert_allclose(l2, ell, rtol=1e-12)
    np.testing.assert_allclose(np.angle(np.exp(1j * (p2 - phi))), 0.0, atol=1e-9)


def test_validation():
    with pytest.raises(ValueError, match=r"shape \(m,\)"):
        tendon_lengths_from_arc(1.0, 0.0, 0.1, [[0.0, 1.0]], 0.01)
    with pytest.raises(ValueError, match="centre of curvature"):
        tendon_lengths_from_arc(200.0, 0.0, 0.1, [0.0], 0.01)
    with pytest.raises(ValueError, match="d must be > 0"):
        tendon_lengths_from_arc(1.0, 0.0, 0.1, [0.0], 0.0)
    with pytest.raises(ValueError, match="at least 3 tendons"):
        arc_from_tendon_lengths([0.1, 0.1], [0.0, np.pi], 0.01)
    with pytest.raises(ValueError, match="3 angles but lengths has 4"):
        arc_from_tendon_lengths([0.1] * 4, [0.0, 1.0, 2.0], 0.01)
    with pytest.raises(ValueError, match="not all on one line"):
        arc_from_tendon_lengths([0.1, 0.1, 0.1], [0.0, np.pi, 2 * np.pi], 0.01)
    with pytest.raises(ValueError, match=r"\(n_sections, m\)"):
        tendon_lengths_from_arcs([1.0, 2.0], [0, 0], [0.1, 0.1], np.zeros((3, 3)), 0.01)
