"""Resolved-rate IK with null-space task (Hannan & Walker Eq. 10-11)."""

import dataclasses

import numpy as np
import pytest

from workbench.kinematics import (
    IKResult,
    follow_path,
    forward_kinematics,
    line_path,
    planar_forward_kinematics,
    planar_inverse_kinematics,
    planar_jacobian,
    spatial_inverse_kinematics,
)

ELL = np.full(4, 0.8382 / 4)  # the Hannan & Walker trunk: 83.82 cm, 4 sections


def _null_projector(J):
    return np.eye(J.shape[1]) - np.linalg.pinv(J) @ J


@pytest.mark.parametrize("seed", [40, 41, 42])
def test_planar_ik_round_trip(seed):
    rng = np.random.default_rng(seed)
    for _ in range(5):
        k_true = rng.uniform(-4, 4, 4)
        x = planar_forward_kinematics(k_true, ELL)[:2, 3]
        res = planar_inverse_kinematics(x, rng.uniform(-1, 1, 4), ELL)
        assert isinstance(res, IKResult)
        assert res.success and res.reason == "converged", res
        np.testing.assert_allclose(planar_forward_kinematics(res.q, ELL)[:2, 3], x, atol=1e-10)
        assert res.residual <= 1e-10


def test_null_space_task_reaches_constrained_optimum():
    """With q_d the solution satisfies the task and the KKT condition N (q - q_d) = 0, and is
    closer to q_d than the solution without the secondary task."""
    rng = np.random.default_rng(43)
    for _ in range(4):
        x = planar_forward_kinematics(rng.uniform(-4, 4, 4), ELL)[:2, 3]
        q0 = rng.uniform(-1, 1, 4)
        q_d = rng.uniform(-2, 2, 4)
        plain = planar_inverse_kinematics(x, q0, ELL)
        sec = planar_inverse_kinematics(x, q0, ELL, kappa_d=q_d, max_iter=3000)
        assert sec.success and sec.reason == "converged", sec
        N = _null_projector(planar_jacobian(sec.q, ELL))
        np.testing.assert_allclose(N @ (sec.q - q_d), 0.0, atol=1e-7)
        assert np.linalg.norm(sec.q - q_d) <= np.linalg.norm(plain.q - q_d) + 1e-12


def test_unreachable_target_fails_gracefully():
    res = planar_inverse_kinematics([0.0, 1.0], np.full(4, 0.5), ELL)  # beyond 0.8382 m
    assert not res.success and res.reason in ("stalled", "max_iterations")
    assert np.all(np.isfinite(res.q))
    # it cannot beat the closest reachable point (straight robot, 1 - 0.8382 m away) and gets
    # near it (convergence towards the straight, singular configuration is slow)
    assert 1.0 - ELL.sum() - 1e-12 <= res.residual <= 1.0 - ELL.sum() + 1e-2


def test_singular_straight_start_is_damped_not_nan():
    # straight robot: J has rank 1 (no motion along the backbone); target off the axis
    x = planar_forward_kinematics(np.array([1.0, -1.0, 2.0, 0.5]), ELL)[:2, 3]
    res = planar_inverse_kinematics(x, np.zeros(4), ELL)
    assert np.all(np.isfinite(res.q))
    assert res.success, res


@pytest.mark.parametrize("seed", [44, 45])
def test_spatial_ik_round_trip(seed):
    rng = np.random.default_rng(seed)
    for _ in range(4):
        k_true = rng.uniform(-4, 4, 3)
        p_true = rng.uniform(-np.pi, np.pi, 3)
        ell = rng.uniform(0.15, 0.3, 3)
        x = forward_kinematics(k_true, p_true, ell)[:3, 3]
        res = spatial_inverse_kinematics(x, np.full(3, 0.5), rng.uniform(-np.pi, np.pi, 3), ell)
        assert res.success, res
        assert res.q.shape == (2, 3)
        np.testing.assert_allclose(forward_kinematics(res.q[0], res.q[1], ell)[:3, 3], x, atol=1e-10)


def test_spatial_ik_null_space_and_straight_start():
    rng = np.random.default_rng(46)
    ell = np.full(3, 0.25)
    x = forward_kinematics(np.array([2.0, -1.0, 3.0]), np.array([0.3, 1.2, -2.0]), ell)[:3, 3]
    res = spatial_inverse_kinematics(x, np.zeros(3), np.zeros(3), ell)  # straight, phi = 0
    assert np.all(np.isfinite(res.q))
    assert res.success, res
    kd = rng.uniform(-1, 1, 3)
    sec = spatial_inverse_kinematics(x, res.q[0], res.q[1], ell, kappa_d=kd, max_iter=3000)
    assert sec.success
    np.testing.assert_allclose(forward_kinematics(sec.q[0], sec.q[1], ell)[:3, 3], x, atol=1e-10)


def test_follow_straight_line_planar_hannan_walker():
    """Paper Sec. 5 example: end point on a straight line, Eq. 10 with q0 = 0 (no secondary
    task), and again with a null-space task."""
    k0 = np.array([2.0, 1.5, 1.0, 1.0])
    start = planar_forward_kinematics(k0, ELL)[:2, 3]  # (-0.494, 0.623), |x| = 0.79 m
    end = planar_forward_kinematics(np.array([-1.0, 2.0, 0.5, -1.0]), ELL)[:2, 3]  # (-0.076, 0.823)
    path = line_path(start, end, 25)
    res = follow_path(path, k0, ELL)
    assert res.success and res.error.max() <= 1e-10
    assert res.q.shape == (25, 4) and res.tip.shape == (25, 2)
    # continuous configurations along a continuous path
    assert np.max(np.abs(np.diff(res.q, axis=0))) < 1.0
    res2 = follow_path(path, k0, ELL, kappa_d=np.zeros(4))
    assert res2.success
    assert np.linalg.norm(res2.q[-1]) <= np.linalg.norm(res.q[-1])
    with pytest.raises(dataclasses.FrozenInstanceError):
        res.success = False  # type: ignore[misc]


def test_follow_path_spatial():
    ell = np.full(3, 0.25)
    k0, p0 = np.array([1.0, 2.0, 1.0]), np.array([0.0, 1.0, 2.0])
    start = forward_kinematics(k0, p0, ell)[:3, 3]
    path = line_path(start, start + [0.05, -0.05, -0.02], 10)
    res = follow_path(path, k0, ell, phi0=p0)
    assert res.success and res.q.shape == (10, 2, 3)


def test_validation():
    with pytest.raises(ValueError, match=r"shape \(2,\)"):
        planar_inverse_kinematics([0.1, 0.2, 0.3], np.zeros(4), ELL)
    with pytest.raises(ValueError, match="kappa_d must have shape"):
        planar_inverse_kinematics([0.1, 0.2], np.zeros(4), ELL, kappa_d=np.zeros(3))
    with pytest.raises(ValueError, match=r"\(m, 2\).*\(m, 3\)"):
        follow_path(np.zeros((5, 4)), np.zeros(4), ELL)
    with pytest.raises(ValueError, match="needs phi0"):
        follow_path(np.zeros((5, 3)), np.zeros(4), ELL)
    with pytest.raises(ValueError, match="n_samples"):
        line_path([0, 0], [1, 1], 1)
