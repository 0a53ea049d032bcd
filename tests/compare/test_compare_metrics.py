"""Metric unit tests on synthetic backbones with known answers (closed-form arcs)."""

import numpy as np
import pytest

from workbench.compare import (
    best_fit_curvature,
    compression_split,
    orientation_error_deg,
    out_of_plane_distance,
    resample_backbone,
    section_curvatures,
    shape_error,
    tendon_stretch_from_tension,
    tip_position_error,
)


def arc(kappa, L, n=33, phi=0.0):
    """Constant-curvature arc from the origin along +z bending towards phi (closed form)."""
    s = np.linspace(0.0, L, n)
    if kappa == 0:
        r, z = np.zeros(n), s
    else:
        r, z = (1 - np.cos(kappa * s)) / kappa, np.sin(kappa * s) / kappa
    return s, np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def rot_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def test_tip_position_error_known_distance():
    assert tip_position_error([0, 0, 1], [0.3, 0.4, 1]) == pytest.approx(0.5)
    e = tip_position_error(np.zeros((4, 3)), np.tile([1.0, 2.0, 2.0], (4, 1)))
    np.testing.assert_allclose(e, 3.0)


def test_tip_position_error_bad_shape():
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        tip_position_error([0, 0], [0, 0])


@pytest.mark.parametrize("angle_deg", [0.0, 1e-5, 0.5, 37.0, 90.0, 179.0, 180.0])
def test_orientation_error_known_angle(angle_deg):
    R0 = rot_z(0.3) @ rot_y(0.2)
    axis_rot = rot_y(np.radians(angle_deg))
    got = orientation_error_deg(R0, R0 @ axis_rot)
    assert got == pytest.approx(angle_deg, abs=1e-9)


def test_orientation_error_accepts_transforms_and_batches():
    T0 = np.eye(4)
    T1 = np.eye(4)
    T1[:3, :3] = rot_z(np.radians(25.0))
    T1[:3, 3] = [1, 2, 3]  # translation must not matter
    assert orientation_error_deg(T0, T1) == pytest.approx(25.0)
    Rs = np.stack([rot_y(np.radians(a)) for a in (10, 20, 30)])
    np.testing.assert_allclose(orientation_error_deg(np.eye(3), Rs), [10, 20, 30])
    with pytest.raises(ValueError, match="3, 3"):
        orientation_error_deg(np.eye(2), np.eye(2))


def test_shape_error_arc_vs_shifted_arc():
    s, p = arc(4.0, 0.5)
    shift = np.array([0.003, -0.004, 0.0])  # |shift| = 5 mm
    mx, rms = shape_error(p, p + shift)
    assert mx == pytest.approx(0.005)
    assert rms == pytest.approx(0.005)


def test_shape_error_arc_vs_straight_known_profile():
    # straight rod vs arc: distance at s is sqrt(r^2 + (s - z)^2), compared pointwise
    L, k = 0.6, 2.0
    s, p_arc = arc(k, L, n=41)
    _, p_line = arc(0.0, L, n=41)
    d = np.hypot((1 - np.cos(k * s)) / k, s - np.sin(k * s) / k)
    mx, rms = shape_error(p_line, p_arc)
    assert mx == pytest.approx(d.max(), rel=1e-12)
    assert rms == pytest.approx(np.sqrt(np.mean(d**2)), rel=1e-12)


def test_shape_error_matches_stations_by_interpolation():
    # same arc reported at different station sets: dense sampling -> error ~ chord sag only
    L, k = 0.5, 3.0
    s1, p1 = arc(k, L, n=17)
    s2, p2 = arc(k, L, n=161)
    mx, rms = shape_error(p1, p2, s1, s2)
    # linear interpolation error bound: kappa h^2 / 8 with h = L / 160
    assert mx <= k * (L / 160) ** 2 / 8 * 1.01
    with pytest.raises(ValueError, match="same shape"):
        shape_error(p1, p2)
    with pytest.raises(ValueError, match="both"):
        shape_error(p1, p2, s1, None)


def test_resample_backbone_rejects_extrapolation():
    s, p = arc(1.0, 0.5)
    with pytest.raises(ValueError, match="no extrapolation"):
        resample_backbone(s, p, [0.0, 0.6])
    np.testing.assert_allclose(resample_backbone(s, p, s), p)


@pytest.mark.parametrize("kappa", [0.0, 1e-4, 0.7, 4.0, 12.0])
@pytest.mark.parametrize("phi", [0.0, 1.1])
def test_best_fit_curvature_exact_on_arcs(kappa, phi):
    _, p = arc(kappa, 0.5, phi=phi)
    # arbitrary rigid motion must not change the curvature
    R = rot_z(0.4) @ rot_y(-0.9)
    q = p @ R.T + np.array([0.1, -0.2, 0.3])
    assert best_fit_curvature(q) == pytest.approx(kappa, rel=1e-7, abs=1e-9)


def test_best_fit_curvature_straight_line_is_zero_and_short_arc_is_stable():
    p = np.outer(np.linspace(0, 1, 10), [1.0, 2.0, -0.5])
    assert best_fit_curvature(p) == pytest.approx(0.0, abs=1e-12)
    _, q = arc(1e-3, 0.01, n=5)  # nearly straight 1 cm segment
    assert best_fit_curvature(q) == pytest.approx(1e-3, rel=1e-3)


def test_best_fit_curvature_noisy_arc():
    rng = np.random.default_rng(1)
    _, p = arc(3.0, 0.5, n=101)
    noisy = p + 2e-5 * rng.standard_normal(p.shape)
    assert best_fit_curvature(noisy) == pytest.approx(3.0, rel=5e-3)


def test_best_fit_curvature_rejects_too_few_points():
    with pytest.raises(ValueError, match=r"\(m, 3\) with m >= 3"):
        best_fit_curvature(np.zeros((2, 3)))


def test_section_curvatures_two_section_backbone():
    # section 1: arc kappa1 over L1; section 2: arc kappa2 continuing tangentially
    L1, L2, k1, k2 = 0.3, 0.2, 2.0, -5.0
    s1 = np.linspace(0, L1, 31)
    s2 = np.linspace(0, L2, 21)[1:]
    p1 = np.column_stack([(1 - np.cos(k1 * s1)) / k1, np.zeros_like(s1), np.sin(k1 * s1) / k1])
    local = np.column_stack([(1 - np.cos(k2 * s2)) / k2, np.zeros_like(s2), np.sin(k2 * s2) / k2])
    p2 = p1[-1] + local @ rot_y(k1 * L1).T
    s = np.concatenate([s1, L1 + s2])
    p = np.vstack([p1, p2])
    got = section_curvatures(s, p, [L1, L1 + L2])
    np.testing.assert_allclose(got, [abs(k1), abs(k2)], rtol=1e-7)


def test_out_of_plane_distance():
    _, p = arc(3.0, 0.5, phi=0.8)
    assert out_of_plane_distance(p) == pytest.approx(0.0, abs=1e-12)
    t = np.linspace(0, 2 * np.pi, 200)
    helix = np.column_stack([np.cos(t), np.sin(t), 0.1 * t])
    assert out_of_plane_distance(helix) > 0.1


def test_compression_split_sums_and_signs():
    sp = compression_split(-0.02, -0.005, 0.003)
    assert sp.backbone == -0.005
    assert sp.tendon_stretch == -0.003
    assert sp.shape == pytest.approx(-0.012)
    assert sp.backbone + sp.tendon_stretch + sp.shape == pytest.approx(sp.virtual)
    with pytest.raises(ValueError, match="finite"):
        compression_split(np.nan, 0, 0)


def test_tendon_stretch_hooke():
    np.testing.assert_allclose(tendon_stretch_from_tension([10.0, 0.0], 0.5, 1e4), [5e-4, 0.0])
    with pytest.raises(ValueError, match="axial_stiffness"):
        tendon_stretch_from_tension([1.0], 1.0, 0.0)
