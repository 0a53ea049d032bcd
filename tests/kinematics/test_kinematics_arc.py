"""Identities of the spatial constant-curvature model (workbench.kinematics.arc)."""

import numpy as np
import pytest

from workbench.kinematics import _series
from workbench.kinematics import backbone_points, forward_kinematics, jacobian, section_transform


def _rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def _rot_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


def _random_config(rng, n, batch=()):
    kappa = rng.uniform(-8.0, 8.0, batch + (n,))
    phi = rng.uniform(-np.pi, np.pi, batch + (n,))
    ell = rng.uniform(0.05, 0.4, batch + (n,))
    return kappa, phi, ell


# ------------------------------------------------------------------ series helpers
def test_series_helpers_match_closed_forms_and_are_continuous():
    x = np.concatenate([np.linspace(-3, 3, 601), [0.2995, 0.3005, -0.3, 0.3]])
    x = x[np.abs(x) > 0.02]  # closed forms are accurate here
    np.testing.assert_allclose(_series.sinc(x), np.sin(x) / x, rtol=1e-13)
    np.testing.assert_allclose(_series.dsinc(x), (x * np.cos(x) - np.sin(x)) / x**2, rtol=2e-10, atol=1e-13)
    np.testing.assert_allclose(_series.versinc(x), (1 - np.cos(x)) / x, rtol=1e-12)
    np.testing.assert_allclose(
        _series.dversinc(x), (x * np.sin(x) - 1 + np.cos(x)) / x**2, rtol=2e-10, atol=1e-13
    )
    # limits at 0 and continuity across the branch switch
    assert _series.sinc(np.array(0.0)) == 1.0
    assert _series.dsinc(np.array(0.0)) == 0.0
    assert _series.dversinc(np.array(0.0)) == 0.5
    for f in (_series.sinc, _series.dsinc, _series.versinc, _series.dversinc):
        for t in (1e-4, 0.3):
            # jump across the branch switch, after removing the smooth slope (from outside)
            lo, hi = f(np.array(t * (1 - 1e-12))), f(np.array(t * (1 + 1e-12)))
            slope = (f(np.array(t * 1.01)) - f(np.array(t * 0.99))) / (0.02 * t)
            assert abs((hi - lo) - slope * 2e-12 * t) < 2e-15


def test_series_helpers_accurate_near_zero():
    """Against 25-term Taylor sums (math.fsum) for |x| <= 1: covers both sides of every branch."""
    from math import factorial, fsum

    def ref(x, kind):
        terms = []
        for k in range(25):
            if kind == "sinc":
                terms.append((-1) ** k * x ** (2 * k) / factorial(2 * k + 1))
            elif kind == "dsinc" and k >= 1:
                terms.append((-1) ** k * 2 * k * x ** (2 * k - 1) / factorial(2 * k + 1))
            elif kind == "versinc" and k >= 1:
                terms.append((-1) ** (k + 1) * x ** (2 * k - 1) / factorial(2 * k))
            elif kind == "dversinc" and k >= 1:
                terms.append((-1) ** (k + 1) * (2 * k - 1) * x ** (2 * k - 2) / factorial(2 * k))
        return fsum(terms)

    xs = np.concatenate([np.geomspace(1e-8, 1.0, 200), -np.geomspace(1e-8, 1.0, 50)])
    for kind in ("sinc", "dsinc", "versinc", "dversinc"):
        f = getattr(_series, kind)
        got = f(xs)
        want = np.array([ref(float(x), kind) for x in xs])
        np.testing.assert_allclose(got, want, rtol=2e-14, err_msg=kind)


# ------------------------------------------------------------------ section transform
def test_section_transform_equals_webster_jones_product():
    rng = np.random.default_rng(1)
    for _ in range(20):
        k, f, l = rng.uniform(-6, 6), rng.uniform(-np.pi, np.pi), rng.uniform(0.05, 1.0)
        th = k * l
        inner = np.eye(4)
        inner[:3, :3] = _rot_y(th)
        inner[:3, 3] = [(1 - np.cos(th)) / k, 0.0, np.sin(th) / k]
        A, B = np.eye(4), np.eye(4)
        A[:3, :3] = _rot_z(f)
        B[:3, :3] = _rot_z(-f)
        np.testing.assert_allclose(section_transform(k, f, l), A @ inner @ B, atol=1e-13)


def test_section_transform_broadcasts():
    k = np.linspace(-3, 3, 5)[:, None]
    f = np.array([0.0, 1.0, 2.0])
    T = section_transform(k, f, 0.2)
    assert T.shape == (5, 3, 4, 4)
    np.testing.assert_allclose(T[4, 2], section_transform(3.0, 2.0, 0.2), atol=1e-15)
    # forward_kinematics broadcasts per-section arrays too: (2, 1, n) with (n,)
    F = forward_kinematics(np.ones((2, 1, 3)), np.zeros(3), np.full(3, 0.1))
    assert F.shape == (2, 1, 4, 4)


def test_section_transform_is_rigid_and_tip_on_circle():
    rng = np.random.default_rng(2)
    k, f, l = _random_config(rng, 1, (500,))
    T = section_transform(k[:, 0], f[:, 0], l[:, 0])
    R = T[:, :3, :3]
    np.testing.assert_allclose(R @ np.swapaxes(R, 1, 2), np.broadcast_to(np.eye(3), R.shape), atol=1e-13)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-13)
    # tip at distance 1/|kappa| from the centre of curvature (cos phi, sin phi, 0)/kappa
    centre = np.stack([np.cos(f[:, 0]), np.sin(f[:, 0]), 0 * f[:, 0]], -1) / k
    np.testing.assert_allclose(np.linalg.norm(T[:, :3, 3] - centre, axis=-1), 1 / np.abs(k[:, 0]), rtol=1e-12)


def test_zero_curvature_is_straight_rod_and_continuous():
    l, f = 0.37, 0.8
    T0 = section_transform(0.0, f, l)
    expected = np.eye(4)
    expected[2, 3] = l
    np.testing.assert_array_equal(T0, expected)
    for eps in (1e-9, -1e-9):
        np.testing.assert_allclose(section_transform(eps, f, l), T0, atol=1e-9)
    # smooth: first-order change is (dx/dkappa) = ell^2/2 along the bending direction
    d = (section_transform(1e-6, f, l)[:3, 3] - section_transform(-1e-6, f, l)[:3, 3]) / 2e-6
    np.testing.assert_allclose(d, [l**2 / 2 * np.cos(f), l**2 / 2 * np.sin(f), 0.0], atol=1e-10)
    # multi-section straight chain
    T = forward_kinematics(np.zeros(3), [0.1, 2.0, -1.0], [0.1, 0.2, 0.3])
    np.testing.assert_allclose(T[:3, 3], [0, 0, 0.6], atol=1e-15)


def test_full_circle_returns_to_base():
    rng = np.random.default_rng(3)
    for _ in range(10):
        ell = rng.uniform(0.1, 2.0)
        T = section_transform(2 * np.pi / ell, rng.uniform(-np.pi, np.pi), ell)
        np.testing.assert_allclose(T, np.eye(4), atol=1e-12)


def test_negative_curvature_equals_flipped_plane():
    rng = np.random.default_rng(4)
    k, f, l = _random_config(rng, 4, (50,))
    np.testing.assert_allclose(forward_kinematics(-k, f, l), forward_kinematics(k, f + np.pi, l), atol=1e-12)


def test_forward_kinematics_is_product_of_sections_and_batched():
    rng = np.random.default_rng(5)
    k, f, l = _random_config(rng, 4, (7, 3))
    T = forward_kinematics(k, f, l)
    assert T.shape == (7, 3, 4, 4)
    for a in range(7):
        for b in range(3):
            P = np.eye(4)
            for i in range(4):
                P = P @ section_transform(k[a, b, i], f[a, b, i], l[a, b, i])
            np.testing.assert_allclose(T[a, b], P, atol=1e-13)


def test_backbone_frames_at_stations():
    rng = np.random.default_rng(6)
    k, f, l = _random_config(rng, 3, (4,))
    total = l.sum(-1).min()
    s = np.linspace(0, total, 11)
    F = forward_kinematics(k, f, l, s)
    assert F.shape == (4, 11, 4, 4)
    np.testing.assert_allclose(F[:, 0], np.broadcast_to(np.eye(4), (4, 4, 4)), atol=1e-15)
    # stations equal to section ends reproduce the chained transforms
    for b in range(4):
        ends = np.cumsum(l[b])
        Fe = forward_kinematics(k[b], f[b], l[b], ends)
        for i in range(3):
            np.testing.assert_allclose(Fe[i], forward_kinematics(k[b, : i + 1], f[b, : i + 1], l[b, : i + 1]), atol=1e-13)
        # any station = FK of the truncated robot
        s1 = 0.5 * (ends[0] + ends[1])
        trunc = forward_kinematics(k[b, :2], f[b, :2], [l[b, 0], s1 - ends[0]])
        np.testing.assert_allclose(forward_kinematics(k[b], f[b], l[b], [s1])[0], trunc, atol=1e-13)
    P = backbone_points(k, f, l, s)
    np.testing.assert_allclose(P, F[..., :3, 3])
    # backbone is arc-length parametrised: |dp/ds| = 1
    b = 0
    ss = np.linspace(0, l[b].sum(), 4001)
    pts = backbone_points(k[b], f[b], l[b], ss)
    np.testing.assert_allclose(np.linalg.norm(np.diff(pts, axis=0), axis=-1) / np.diff(ss), 1.0, atol=1e-6)


# ------------------------------------------------------------------ Jacobian
def _fd_jacobian(kappa, phi, ell, h=1e-6):
    n = len(kappa)
    q = np.stack([kappa, phi, ell], -1).ravel()

    def fk(q):
        q = q.reshape(n, 3)
        return forward_kinematics(q[:, 0], q[:, 1], q[:, 2])

    T = fk(q)
    J = np.zeros((6, 3 * n))
    for i in range(3 * n):
        dq = np.zeros(3 * n)
        dq[i] = h
        Tp, Tm = fk(q + dq), fk(q - dq)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        W = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ T[:3, :3].T
        J[3:, i] = [W[2, 1], W[0, 2], W[1, 0]]
    return J


@pytest.mark.parametrize("seed", [10, 11, 12])
@pytest.mark.parametrize("n", [1, 3, 5])
def test_jacobian_matches_central_differences(seed, n):
    rng = np.random.default_rng(seed)
    k, f, l = _random_config(rng, n)
    np.testing.assert_allclose(jacobian(k, f, l), _fd_jacobian(k, f, l), atol=2e-8)


def test_jacobian_near_and_at_zero_curvature():
    rng = np.random.default_rng(13)
    k, f, l = _random_config(rng, 3)
    for k0 in (0.0, 1e-9, -1e-9, 1e-3, 0.2999 / 0.4, 0.3001 / 0.4):
        kk = k.copy()
        kk[1] = k0
        kk[2] = -k0
        np.testing.assert_allclose(jacobian(kk, f, l), _fd_jacobian(kk, f, l), atol=2e-8)
    # continuity across kappa = 0 (all sections straight)
    Js = [jacobian(np.full(3, e), f, l) for e in (-1e-9, 0.0, 1e-9)]
    np.testing.assert_allclose(Js[0], Js[1], atol=1e-8)
    np.testing.assert_allclose(Js[2], Js[1], atol=1e-8)


def test_jacobian_batched_shape_and_consistency():
    rng = np.random.default_rng(14)
    k, f, l = _random_config(rng, 2, (5, 2))
    J = jacobian(k, f, l)
    assert J.shape == (5, 2, 6, 6)
    np.testing.assert_allclose(J[3, 1], jacobian(k[3, 1], f[3, 1], l[3, 1]))


# ------------------------------------------------------------------ validation
def test_input_validation_messages():
    with pytest.raises(ValueError, match=r"\(\.\.\., n_sections\)"):
        forward_kinematics(1.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="do not broadcast"):
        forward_kinematics(np.zeros(3), np.zeros(2), np.ones(3))
    with pytest.raises(ValueError, match="ell must be >= 0"):
        jacobian([1.0], [0.0], [-1.0])
    with pytest.raises(ValueError, match="finite"):
        section_transform(np.nan, 0.0, 1.0)
    with pytest.raises(ValueError, match=r"1-D.*\(m,\)"):
        forward_kinematics([1.0], [0.0], [1.0], s=[[0.1]])
    with pytest.raises(ValueError, match="sum\\(ell\\)"):
        forward_kinematics([1.0], [0.0], [1.0], s=[1.5])
    with pytest.raises(ValueError, match=">= 0"):
        backbone_points([1.0], [0.0], [1.0], s=[-0.1])
    with pytest.raises(TypeError, match="kappa"):
        section_transform("abc", 0.0, 1.0)
