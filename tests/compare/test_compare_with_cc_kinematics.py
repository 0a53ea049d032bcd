"""Metrics on backbones from the project's constant-curvature kinematics (workbench.kinematics)."""

import numpy as np
import pytest

kin = pytest.importorskip("workbench.kinematics")
if not hasattr(kin, "backbone_points"):
    pytest.skip("workbench.kinematics has no backbone_points yet", allow_module_level=True)

from workbench.compare import (  # noqa: E402
    orientation_error_deg,
    out_of_plane_distance,
    section_curvatures,
    shape_error,
    tip_position_error,
)

KAPPA = np.array([2.0, -3.0, 1.5])
PHI = np.array([0.0, 0.7, 2.0])
ELL = np.array([0.2, 0.15, 0.1])


def test_section_curvatures_recover_cc_parameters():
    s = np.linspace(0.0, ELL.sum(), 91)
    pts = kin.backbone_points(KAPPA, PHI, ELL, s=s)
    got = section_curvatures(s, pts, np.cumsum(ELL))
    np.testing.assert_allclose(got, np.abs(KAPPA), rtol=1e-8)
    assert out_of_plane_distance(pts) > 1e-3  # three bending planes: a spatial backbone


def test_rigid_base_rotation_errors():
    """Adding a to every bending plane turns the backbone rigidly about the base z axis by a
    (the tip frame additionally twists about its own z axis, so only positions are compared
    with the kinematics; the frame test uses the rigidly rotated frame Rz(a) T0)."""
    a = np.radians(20.0)
    s = np.linspace(0.0, ELL.sum(), 46)
    p0 = kin.backbone_points(KAPPA, PHI, ELL, s=s)
    p1 = kin.backbone_points(KAPPA, PHI + a, ELL, s=s)
    T0 = kin.forward_kinematics(KAPPA, PHI, ELL)
    T1 = kin.forward_kinematics(KAPPA, PHI + a, ELL)
    Rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    np.testing.assert_allclose(p1, p0 @ Rz.T, atol=1e-12)
    assert orientation_error_deg(T0[:3, :3], Rz @ T0[:3, :3]) == pytest.approx(20.0, abs=1e-8)
    r = np.hypot(p0[-1, 0], p0[-1, 1])
    assert tip_position_error(T0[:3, 3], T1[:3, 3]) == pytest.approx(2 * r * np.sin(a / 2), rel=1e-10)
    radial = np.hypot(p0[:, 0], p0[:, 1])
    mx, rms = shape_error(p0, p1)
    assert mx == pytest.approx(2 * np.sin(a / 2) * radial.max(), rel=1e-10)
    assert rms == pytest.approx(2 * np.sin(a / 2) * np.sqrt(np.mean(radial**2)), rel=1e-10)
