"""Hannan & Walker planar model: App. A, Eq. 9 / App. B erratum, planar == spatial."""

import numpy as np
import pytest

from workbench.kinematics import (
    forward_kinematics,
    jacobian,
    planar_forward_kinematics,
    planar_from_spatial_transform,
    planar_jacobian,
    spatial_from_planar,
)

ELL_HW = np.full(4, 0.8382 / 4)  # 83.82 cm robot, 4 equal sections


def _appendix_a(k, l):
    """App. A as printed (1/kappa form, needs kappa != 0)."""
    w = k * l
    W = np.concatenate([[0.0], np.cumsum(w)])
    A14 = sum((np.cos(W[j + 1]) - np.cos(W[j])) / k[j] for j in range(4))
    A24 = sum((np.sin(W[j + 1]) - np.sin(W[j])) / k[j] for j in range(4))
    return np.array([[np.cos(W[4]), -np.sin(W[4]), A14], [np.sin(W[4]), np.cos(W[4]), A24]])


def _appendix_b_as_printed(k, l):
    """App. B transcribed literally from the paper (contains sign errors)."""
    w1, w2, w3, w4 = k * l
    k1, k2, k3, k4 = k
    l1, l2, l3, l4 = l
    S, C = np.sin, np.cos
    W1, W2, W3, W4 = w1, w1 + w2, w1 + w2 + w3, w1 + w2 + w3 + w4
    J = np.zeros((2, 4))
    J[0, 0] = (-l1 * S(W1) / k1 + l1 * (-S(W2) + S(W1)) / k2 + l1 * (-S(W3) + S(W2)) / k3
               + l1 * (-S(W4) + S(W3)) / k4 - (C(W1) - 1) / k1**2)
    J[0, 1] = ((-C(W2) - C(W1)) / k2**2 - l2 * S(W2) / k2 + l2 * (-S(W3) + S(W2)) / k3
               + l2 * (-S(W4) + S(W3)) / k4)
    J[0, 2] = -l3 * S(W3) / k3 + l3 * (-S(W4) + S(W3)) / k4 - (C(W3) - C(W2)) / k3**2
    J[0, 3] = -l4 * S(W4) / k4 - (C(W4) - C(W3)) / k4**2
    J[1, 0] = (-S(W1) / k1**2 - l1 * C(W1) / k1 + l1 * (C(W2) - C(W1)) / k2
               + l1 * (C(W3) - C(W2)) / k3 + l1 * (C(W4) - C(W3)) / k4)
    J[1, 1] = ((-S(W2) - S(W1)) / k2**2 + l2 * C(W2) / k2 + l2 * (C(W3) - C(W2)) / k3
               + l2 * (C(W4) - C(W3)) / k4)
    J[1, 2] = l3 * C(W3) / k3 + l3 * (C(W4) - C(W3)) / k4 - (S(W3) - S(W2)) / k3**2
    J[1, 3] = l4 * C(W4) / k4 - (S(W4) - S(W3)) / k4**2
    return J


def _fd(k, l, h=1e-6):
    J = np.zeros((2, len(k)))
    for i in range(len(k)):
        d = np.zeros(len(k))
        d[i] = h
        J[:, i] = (planar_forward_kinematics(k + d, l)[:2, 3] - planar_forward_kinematics(k - d, l)[:2, 3]) / (2 * h)
    return J


def test_matches_appendix_a():
    rng = np.random.default_rng(20)
    for _ in range(20):
        k = rng.uniform(-6, 6, 4)
        A = planar_forward_kinematics(k, ELL_HW)
        np.testing.assert_allclose(A[:2, [0, 1, 3]], _appendix_a(k, ELL_HW), atol=1e-12)
        np.testing.assert_allclose(A[2], [0, 0, 1, 0])


def test_straight_and_continuity():
    A = planar_forward_kinematics(np.zeros(4), ELL_HW)
    np.testing.assert_allclose(A[:2, 3], [0.0, ELL_HW.sum()], atol=1e-15)
    for e in (1e-9, -1e-9):
        np.testing.assert_allclose(planar_forward_kinematics(np.full(4, e), ELL_HW), A, atol=1e-9)
    # a full circle in one section returns to its base
    np.testing.assert_allclose(planar_forward_kinematics([2 * np.pi / 0.3], [0.3]), np.eye(4), atol=1e-12)


@pytest.mark.parametrize("seed", [21, 22, 23, 24])
def test_planar_jacobian_vs_finite_differences(seed):
    rng = np.random.default_rng(seed)
    k = rng.uniform(-6, 6, 4)
    np.testing.assert_allclose(planar_jacobian(k, ELL_HW), _fd(k, ELL_HW), atol=1e-8)


def test_planar_jacobian_smooth_at_zero_curvature():
    rng = np.random.default_rng(25)
    k = rng.uniform(-6, 6, 4)
    for z in (0.0, 1e-9, -1e-9):
        kk = k.copy()
        kk[[0, 2]] = z
        np.testing.assert_allclose(planar_jacobian(kk, ELL_HW), _fd(kk, ELL_HW), atol=1e-8)
    J0 = planar_jacobian(np.zeros(4), ELL_HW)
    np.testing.assert_allclose(planar_jacobian(np.full(4, 1e-9), ELL_HW), J0, atol=1e-8)


def test_appendix_b_erratum_exactly_three_entries_wrong():
    """The literal App. B differs from finite differences only in J12, J21, J22; fixing the
    three signs stated in :func:`planar_jacobian` makes it agree."""
    rng = np.random.default_rng(26)
    for _ in range(10):
        k = rng.uniform(0.5, 6, 4) * rng.choice([-1, 1], 4)
        printed = _appendix_b_as_printed(k, ELL_HW)
        ref = _fd(k, ELL_HW)
        ok = np.isclose(printed, ref, atol=1e-7)
        assert not ok[0, 1] and not ok[1, 0] and not ok[1, 1]
        ok[0, 1] = ok[1, 0] = ok[1, 1] = True
        assert ok.all()
        w = k * ELL_HW
        W1 = w[0]
        fixed = printed.copy()
        fixed[0, 1] += 2 * np.cos(W1) / k[1] ** 2
        fixed[1, 0] += 2 * ELL_HW[0] * np.cos(W1) / k[0]
        fixed[1, 1] += 2 * np.sin(W1) / k[1] ** 2
        np.testing.assert_allclose(fixed, ref, atol=1e-7)
        np.testing.assert_allclose(planar_jacobian(k, ELL_HW), fixed, atol=1e-9)


def test_planar_equals_spatial_with_phi_in_0_pi():
    rng = np.random.default_rng(27)
    k = rng.uniform(-6, 6, (50, 4))
    l = rng.uniform(0.05, 0.3, (50, 4))
    A = planar_forward_kinematics(k, l)
    ks, ps, ls = spatial_from_planar(k, l)
    np.testing.assert_allclose(planar_from_spatial_transform(forward_kinematics(ks, ps, ls)), A, atol=1e-12)
    # mixed representation: per section either (kappa, pi) or (-kappa, 0)
    flip = rng.random((50, 4)) < 0.5
    T = forward_kinematics(np.where(flip, -k, k), np.where(flip, 0.0, np.pi), l)
    np.testing.assert_allclose(planar_from_spatial_transform(T), A, atol=1e-12)
    # the spatial motion stays in the spatial x-z plane
    assert np.allclose(T[..., 1, 3], 0.0, atol=1e-14)


def test_planar_jacobian_equals_spatial_curvature_columns():
    """Planar J = rows (x_p, y_p) = (x_s, z_s) of the spatial kappa-columns at phi = pi."""
    rng = np.random.default_rng(28)
    k = rng.uniform(-6, 6, (20, 4))
    Js = jacobian(*spatial_from_planar(k, np.broadcast_to(ELL_HW, k.shape)))
    Jp = planar_jacobian(k, ELL_HW)
    np.testing.assert_allclose(Jp, Js[:, [0, 2]][:, :, 0::3], atol=1e-12)


def test_validation():
    with pytest.raises(ValueError, match="n_sections"):
        planar_forward_kinematics(1.0, 1.0)
    with pytest.raises(ValueError, match="ell must be >= 0"):
        planar_jacobian([1.0, 2.0], [0.1, -0.1])
    with pytest.raises(ValueError, match=r"\(\.\.\., 4, 4\)"):
        planar_from_spatial_transform(np.eye(3))
