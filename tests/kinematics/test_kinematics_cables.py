"""Hannan & Walker cable geometry (Eq. 1-3) and Cojocaru tronconic wires (Eq. 4-30)."""

import numpy as np
import pytest

from workbench.kinematics import (
    WireMove,
    cable_change_from_joint_angle,
    curvature_from_cable_change,
    curvature_from_joint_angle,
    joint_angle_from_cable_change,
    joint_angle_from_curvature,
    plan_constant_speed_move,
    tendon_lengths_from_arc,
    virtual_compression,
    wire_length_jacobian,
    wire_lengths_tronconic_paper,
)

DEG = np.pi / 180


# ------------------------------------------------------------------ Hannan & Walker Eq. 1-3
def _span_by_construction(theta, w, h):
    """Distance between the hole exits (w, -h) and Rot(-theta) (w, h): independent geometry."""
    c, s = np.cos(-theta), np.sin(-theta)
    b = np.array([c * w - s * h, s * w + c * h])
    return np.hypot(b[0] - w, b[1] + h)


@pytest.mark.parametrize("w,h", [(0.0508, 0.02), (0.0508, 0.08), (0.03175, 0.03175)])
def test_eq1_against_construction_and_round_trip(w, h):
    psi0 = 2 * np.arctan(h / w)
    thetas = np.linspace(psi0 - np.pi + 1e-6, psi0 - 1e-6, 101)
    dl = np.array([2 * h - _span_by_construction(t, w, h) for t in thetas])
    np.testing.assert_allclose(joint_angle_from_cable_change(dl, w, h), thetas, atol=1e-7)
    np.testing.assert_allclose(cable_change_from_joint_angle(thetas, w, h), dl, atol=1e-14)
    np.testing.assert_allclose(
        joint_angle_from_cable_change(cable_change_from_joint_angle(thetas, w, h), w, h), thetas, atol=1e-7
    )
    assert joint_angle_from_cable_change(0.0, w, h) == 0.0
    # pulling the cable bends towards it, releasing bends away
    assert joint_angle_from_cable_change(1e-3, w, h) > 0 > joint_angle_from_cable_change(-1e-3, w, h)


def test_eq1_plain_arctan_fails_where_atan2_is_needed():
    """The printed Eq. 1 (plain arctan) is wrong for h > w already at dl = 0."""
    w, h = 0.03, 0.05
    r2 = w * w + h * h
    c = 2 * h
    printed = np.pi - 2 * np.arctan(w / h) - np.arctan(np.sqrt(4 * r2**2 - (2 * r2 - c * c) ** 2) / (2 * r2 - c * c))
    assert abs(printed) > 1.0  # off by pi
    assert joint_angle_from_cable_change(0.0, w, h) == 0.0


def test_eq2_eq3_curvature():
    # 4 joints of theta: total bend 4 theta = k s, chord angle phi = 2 theta (Eq. 3)
    s = 0.8382 / 4
    np.testing.assert_allclose(curvature_from_joint_angle(0.1, s), 0.4 / s)
    np.testing.assert_allclose(joint_angle_from_curvature(curvature_from_joint_angle(0.1, s), s), 0.1)
    # chained: section cable change split over 4 joints
    w, h = 0.0508, 0.02
    dls = 4 * cable_change_from_joint_angle(0.07, w, h)
    np.testing.assert_allclose(curvature_from_cable_change(dls, w, h, s), 4 * 0.07 / s, rtol=1e-9)


def test_hw_validation():
    with pytest.raises(ValueError, match="joint limit"):
        joint_angle_from_cable_change(-1.0, 0.05, 0.02)
    with pytest.raises(ValueError, match="joint range"):
        cable_change_from_joint_angle(3.0, 0.05, 0.02)
    with pytest.raises(ValueError, match="w must be > 0"):
        joint_angle_from_cable_change(0.0, 0.0, 0.02)


# ------------------------------------------------------------------ Cojocaru Eq. 4-12
def _paper_eq_4_11(theta, alpha, H, D1, D2):
    """Literal Eq. 4-11 (needs theta != 0)."""
    R = H / theta
    out = []
    for an in (-alpha, 120 * DEG - alpha, 240 * DEG - alpha):
        L1 = R + D1 / 2 * np.cos(an)
        L2 = R + D2 / 2 * np.cos(an)
        A = np.sqrt(L1**2 + L2**2 - 2 * L1 * L2 * np.cos(theta))
        out.append(A / (2 * np.sin(theta / 2)) * theta)
    return np.array(out)


def test_wire_lengths_match_paper_equations_and_are_stable_at_zero():
    rng = np.random.default_rng(50)
    for _ in range(50):
        th, al = rng.uniform(-2.5, 2.5), rng.uniform(-np.pi, np.pi)
        D1, D2 = rng.uniform(0.05, 0.12, 2)
        np.testing.assert_allclose(wire_lengths_tronconic_paper(th, al, 0.35, D1, D2), _paper_eq_4_11(th, al, 0.35, D1, D2), rtol=1e-12)
    # theta = 0: straight slanted wires, continuous
    L0 = wire_lengths_tronconic_paper(0.0, 0.3, 0.35, 0.1, 0.08)
    for e in (1e-9, -1e-9):
        np.testing.assert_allclose(wire_lengths_tronconic_paper(e, 0.3, 0.35, 0.1, 0.08), L0, atol=1e-10)
    cos_n = np.cos(np.array([0, 120, 240]) * DEG - 0.3)
    np.testing.assert_allclose(L0, np.sqrt(0.35**2 + (0.01 * cos_n) ** 2), rtol=1e-14)
    # alpha_1 = -alpha or +alpha: identical (only cos enters)
    assert wire_lengths_tronconic_paper(0.5, 0.4, 0.35, 0.1, 0.08)[0] == pytest.approx(_paper_eq_4_11(0.5, -0.4, 0.35, 0.1, 0.08)[0], rel=1e-14)


def test_cylinder_satisfies_eq12_and_matches_tendon_model():
    rng = np.random.default_rng(51)
    th = rng.uniform(-2.0, 2.0, 200)
    al = rng.uniform(-np.pi, np.pi, 200)
    L = wire_lengths_tronconic_paper(th, al, 0.35, 0.1, 0.1)
    np.testing.assert_allclose(virtual_compression(L, 0.35), 0.0, atol=1e-15)
    # L_n = H + D/2 theta cos(az_n - alpha) = tendon model with kappa = theta/H, phi = alpha + pi
    Lt = tendon_lengths_from_arc(th / 0.35, al + np.pi, 0.35, np.array([0, 120, 240]) * DEG, 0.05)
    np.testing.assert_allclose(L, Lt, atol=1e-15)


def test_tronconic_deviation_quantified():
    """Static virtual 'compression' of a tronconic segment. Writing L_n = sqrt(P_n^2 - Q_n) with
    P_n = H + (a_n + b_n) theta/2, Q_n = (a_n - b_n)^2 (theta^2/4 - 1/sinc(theta/2)^2), the
    leading order in dD = D1 - D2 is
    mean(L) - H = dD^2 K / 24 * sum_n cos^2(alpha_n) / (H + Dm theta cos(alpha_n) / 2),
    K = 1/sinc(theta/2)^2 - theta^2/4, Dm = (D1 + D2)/2 (~ dD^2 K / (16 H) for Dm theta << H).
    E.g. H = 0.35 m, D1 = 0.10 m, D2 = 0.08 m, theta = alpha = 45 deg: +67.0 um = +0.019 % of H
    (an extension, not a compression)."""
    H, D1, th = 0.35, 0.10, 45 * DEG
    vc = virtual_compression(wire_lengths_tronconic_paper(th, 45 * DEG, H, D1, 0.08), H)
    assert vc == pytest.approx(6.70e-5, rel=2e-3)
    sc = np.sin(th / 2) / (th / 2)
    K = 1 / sc**2 - th**2 / 4
    for al in (0.7, 45 * DEG):
        for dD in (0.02, 0.005, 0.001):
            Dm = D1 - dD / 2
            cn = np.cos(np.array([0, 120, 240]) * DEG - al)
            lead = dD**2 * K / 24 * np.sum(cn**2 / (H + Dm * th * cn / 2))
            vc = virtual_compression(wire_lengths_tronconic_paper(th, al, H, D1, D1 - dD), H)
            assert vc > 0
            assert abs(vc / lead - 1) < 1e-3 * (dD / 0.02) ** 2  # next order is O(dD^2)


def test_constant_speed_move_without_delay_has_no_compression_cylinder():
    mv = plan_constant_speed_move([0, 0], [45 * DEG, 45 * DEG], 4.0, H=0.35, D1=0.1, D2=0.1)
    assert isinstance(mv, WireMove)
    np.testing.assert_allclose(mv.virtual_compression, 0.0, atol=1e-15)  # Eq. 27
    np.testing.assert_allclose(mv.wire_lengths[0], mv.start_lengths)
    np.testing.assert_allclose(mv.wire_lengths[-1], mv.end_lengths)
    np.testing.assert_allclose(np.diff(mv.wire_lengths, axis=0) / np.diff(mv.t)[:, None], np.broadcast_to(mv.wire_speeds, (400, 3)), atol=1e-12)
    # implied pose: end pose reached; (theta cos alpha, theta sin alpha) moves on a straight line
    assert mv.theta[-1] == pytest.approx(45 * DEG) and mv.alpha[-1] == pytest.approx(45 * DEG)
    u = mv.theta * np.cos(mv.alpha)
    v = mv.theta * np.sin(mv.alpha)
    frac = np.clip(mv.t / 4.0, 0, 1)
    np.testing.assert_allclose(u, frac * u[-1], atol=1e-12)
    np.testing.assert_allclose(v, frac * v[-1], atol=1e-12)


def test_paper_experiment_wire1_delayed_3s():
    """Cojocaru Sec. 5.1: theta 0 -> 45 deg, alpha 0 -> 45 deg, wire 1 starts 3 s late ->
    'approximately 2 %' compression. The paper gives no geometry/duration; with a cylinder
    H = 0.35 m, D = 0.10 m the peak is |dL_1| min(3 s, T)/(3 T H): 2.64 % for T <= 3 s,
    1.98 % for T = 4 s."""
    H, D = 0.35, 0.10
    dL1 = D / 2 * 45 * DEG * np.cos(45 * DEG)  # wire 1 lengthens by 27.8 mm
    for T, expected in ((2.0, 0.02645), (3.0, 0.02645), (4.0, 0.01983), (6.0, 0.01322)):
        mv = plan_constant_speed_move([0, 0], [45 * DEG, 45 * DEG], T, H=H, D1=D, D2=D,
                                      delays=[3.0, 0, 0], t=np.linspace(0, T + 3, 6001))
        peak = mv.relative_compression.max()
        assert peak == pytest.approx(dL1 * min(3.0, T) / (3 * T * H), rel=1e-9)
        assert peak == pytest.approx(expected, abs=5e-5)
        assert mv.relative_compression.min() >= -1e-15  # never an extension
        np.testing.assert_allclose(mv.virtual_compression[-1], 0.0, atol=1e-15)  # consistent at the end
    # tronconic version of the same experiment: peak changes only by the static offset order
    mv_t = plan_constant_speed_move([0, 0], [45 * DEG, 45 * DEG], 4.0, H=H, D1=0.10, D2=0.08, delays=[3, 0, 0])
    assert mv_t.theta is None
    assert 0.015 < mv_t.relative_compression.max() < 0.02


@pytest.mark.parametrize("seed", [52, 53])
def test_wire_length_jacobian_vs_finite_differences(seed):
    rng = np.random.default_rng(seed)
    h = 1e-6
    for _ in range(10):
        th = rng.uniform(-2.0, 2.0)
        if _ == 0:
            th = 0.0  # smooth through theta = 0
        al = rng.uniform(-np.pi, np.pi)
        H, D1, D2 = 0.35, rng.uniform(0.05, 0.12), rng.uniform(0.05, 0.12)
        J = wire_length_jacobian(th, al, H, D1, D2)
        fd = np.stack([
            (wire_lengths_tronconic_paper(th + h, al, H, D1, D2) - wire_lengths_tronconic_paper(th - h, al, H, D1, D2)) / (2 * h),
            (wire_lengths_tronconic_paper(th, al + h, H, D1, D2) - wire_lengths_tronconic_paper(th, al - h, H, D1, D2)) / (2 * h),
        ], axis=-1)
        np.testing.assert_allclose(J, fd, atol=1e-9)
    # cylinder closed form
    th, al = 0.6, 0.2
    an = np.array([0, 120, 240]) * DEG - al
    np.testing.assert_allclose(wire_length_jacobian(th, al, 0.35, 0.1, 0.1),
                               np.stack([0.05 * np.cos(an), 0.05 * th * np.sin(an)], -1), atol=1e-15)


def test_cojocaru_validation():
    with pytest.raises(ValueError, match="disc radius"):
        wire_lengths_tronconic_paper(2.0, 0.0, 0.01, 0.1, 0.1)
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 3\)"):
        virtual_compression(np.ones(4), 0.3)
    with pytest.raises(ValueError, match=r"delays must have shape \(3,\)"):
        plan_constant_speed_move([0, 0], [1, 1], 4.0, H=0.3, D1=0.1, D2=0.1, delays=[3, 0])
    with pytest.raises(ValueError, match="duration must be > 0"):
        plan_constant_speed_move([0, 0], [1, 1], 0.0, H=0.3, D1=0.1, D2=0.1)
