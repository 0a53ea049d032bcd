"""Shao centre-of-arc kinematics (Eq. 1-5) and its k = 0 singularity."""

import numpy as np
import pytest

from workbench.kinematics import (
    SingularConfiguration,
    backbone_points,
    centre_of_arc_jacobian,
    centre_of_arc_pose,
)


def test_pose_is_centre_of_the_arc():
    rng = np.random.default_rng(60)
    for _ in range(20):
        s, k, phi = rng.uniform(0.1, 0.4), rng.uniform(-10, 10), rng.uniform(-np.pi, np.pi)
        T = centre_of_arc_pose(s, k, phi)
        R = T[:3, :3]
        np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-14)
        assert np.linalg.det(R) == pytest.approx(1.0)
        pts = backbone_points([k], [phi], [s], np.linspace(0, s, 9))
        np.testing.assert_allclose(np.linalg.norm(pts - T[:3, 3], axis=-1), 1 / abs(k), rtol=1e-12)
        # x_1 points from the arc midpoint to the centre; z_1 is normal to the bending plane
        mid = backbone_points([k], [phi], [s], [s / 2])[0]
        d = T[:3, 3] - mid
        # (for k < 0 the centre lies on the other side: x_1 = sign(k) (O_1 - a)/|O_1 - a|)
        np.testing.assert_allclose(R[:, 0], np.sign(k) * d / np.linalg.norm(d), atol=1e-12)
        np.testing.assert_allclose(R[:, 2] @ (pts[1] - pts[0]), 0.0, atol=1e-14)


def _fd(s, k, phi, h=1e-6):
    q = np.array([s, k, phi])
    T = centre_of_arc_pose(*q)
    J = np.zeros((6, 3))
    for i in range(3):
        dq = np.zeros(3)
        dq[i] = h
        Tp, Tm = centre_of_arc_pose(*(q + dq)), centre_of_arc_pose(*(q - dq))
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        W = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ T[:3, :3].T
        J[3:, i] = [W[2, 1], W[0, 2], W[1, 0]]
    return J


@pytest.mark.parametrize("seed", [61, 62, 63])
def test_jacobian_vs_finite_differences(seed):
    rng = np.random.default_rng(seed)
    for _ in range(5):
        s, k, phi = rng.uniform(0.1, 0.4), rng.uniform(1, 10) * rng.choice([-1, 1]), rng.uniform(-np.pi, np.pi)
        np.testing.assert_allclose(centre_of_arc_jacobian(s, k, phi), _fd(s, k, phi), rtol=1e-7, atol=1e-8)
        assert np.linalg.matrix_rank(centre_of_arc_jacobian(s, k, phi)) == 3


def test_printed_jv_phi_column_is_wrong():
    s, k, phi = 0.3, 4.0, 0.7
    assert np.linalg.norm(_fd(s, k, phi)[:3, 2]) == pytest.approx(1 / k, rel=1e-6)  # printed: 0


def test_singularity_reported():
    with pytest.raises(SingularConfiguration, match="k\\| <= 0") as ei:
        centre_of_arc_pose([0.3, 0.3, 0.3], [1.0, 0.0, 2.0], 0.0)
    assert isinstance(ei.value, ValueError)
    assert ei.value.indices[0].tolist() == [1]
    with pytest.raises(SingularConfiguration):
        centre_of_arc_jacobian(0.3, 0.0, 0.0)
    with pytest.raises(SingularConfiguration):
        centre_of_arc_pose(0.3, 1e-6, 0.0, k_tol=1e-3)
    T = centre_of_arc_pose([0.3, 0.3], [1.0, 0.0], 0.0, on_singular="nan")
    assert np.all(np.isfinite(T[0])) and np.all(np.isnan(T[1, :3, 3]))
    np.testing.assert_allclose(T[1, :3, :3].T @ T[1, :3, :3], np.eye(3), atol=1e-15)  # orientation defined
    J = centre_of_arc_jacobian([0.3, 0.3], [1.0, 0.0], 0.0, on_singular="nan")
    assert np.all(np.isnan(J[1, :3])) and np.all(np.isfinite(J[1, 3:])) and np.all(np.isfinite(J[0]))
    with pytest.raises(ValueError, match="on_singular"):
        centre_of_arc_pose(0.3, 1.0, 0.0, on_singular="ignore")
