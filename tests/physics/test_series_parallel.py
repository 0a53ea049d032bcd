"""Huang et al.'s flexible series-parallel module and stack (Exudyn GE-beam legs)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from workbench.physics.series_parallel import (
    ModuleGeometry,
    attachment_points,
    fit_constant_curvature,
    hole_frames,
    home_pose,
    leg_lengths_from_pose_hermite,
    leg_static,
    min_leg_gap,
    module_forward,
    module_inverse,
    pose_from_xyz_rotvec,
    stack_forward,
    stack_inverse,
)
from workbench.reference.cosserat import (
    RodStiffness,
    integrate_cosserat_rod,
    rotation_log,
    solve_rod_tip_pose,
    solve_rod_tip_wrench,
)

GEO = ModuleGeometry()
ROD = GEO.rod_params()
K = RodStiffness(ROD.EA, ROD.GA, ROD.EI, ROD.GJ)
L_LEG = 0.5


# ----------------------------------------------------------------------------- one leg


@pytest.fixture(scope="module")
def cantilever_reference():
    w = np.array([30.0, -20.0, 10.0, 3.0, 5.0, 2.0])  # large 3-D deflection with torsion
    ref = solve_rod_tip_wrench(np.zeros(3), np.eye(3), L_LEG, K, w[:3], w[3:], n_steps=2)
    assert ref.converged
    return w, ref


def test_leg_matches_shooting_solver_for_a_tip_wrench(cantilever_reference):
    """Same end conditions (clamped base, dead tip force + moment; the tip moves 0.13 m and twists):
    tip pose within 1e-4 L at 32 elements, converging at second order (8 -> 16 -> 32)."""
    w, ref = cantilever_reference
    errs = []
    for n in (8, 16, 32):
        leg = leg_static(GEO, np.zeros(3), np.eye(3), L_LEG, tip_wrench=w, free_base_twist=False, n_elements=n)
        assert leg.converged, leg.reason
        e_p = np.linalg.norm(leg.positions[-1] - ref.tip_position)
        e_r = np.linalg.norm(rotation_log(leg.rotations[-1].T @ ref.tip_rotation))
        errs.append((e_p, e_r))
    assert errs[-1][0] < 1e-4 * L_LEG
    assert errs[-1][1] < 1e-4
    # second-order convergence of the 2-node GE element (ratio 4 per halving)
    for (a, _), (b, _) in zip(errs[:-1], errs[1:]):
        assert 3.5 < a / b < 4.5


def test_leg_with_hole_condition_matches_shooting_solver():
    """Hole at the base (position + tangent fixed, free twist, Eq 21), tip clamped at a module pose
    (Eq 25-26): the GE-beam leg and the Cosserat shooting solution of the same BVP agree to
    < 1e-4 L along the whole rod at 16 elements, converging at second order; the tip wrench
    converges too (it is sensitive: the axial stiffness turns tiny shape errors into force)."""
    P0, R0 = hole_frames(GEO)
    A = attachment_points(GEO)
    T = pose_from_xyz_rotvec([0.05, -0.03, 0.55], [0.1, 0.2, 0.15])
    i = 0
    tip = np.eye(4)
    tip[:3, :3] = T[:3, :3]
    tip[:3, 3] = T[:3, :3] @ A[i] + T[:3, 3]
    Li = leg_lengths_from_pose_hermite(GEO, T)[i]  # a realistic S-bent leg (tip force ~ 60 N)
    sh = None
    errs = []
    for n in (8, 16):
        leg = leg_static(GEO, P0[i], R0[i], Li, tip_pose=tip, n_elements=n)
        assert leg.converged, leg.reason
        np.testing.assert_allclose(leg.rotations[0][:, 2], R0[i][:, 2], atol=1e-10)  # tangent held
        n0 = leg.tip_force
        m0 = leg.tip_moment + np.cross(leg.positions[-1] - P0[i], leg.tip_force)
        assert abs(m0 @ R0[i][:, 2]) < 1e-8 * np.linalg.norm(m0)  # no torsion at the hole
        if sh is None:
            # shooting from Exudyn's coarse answer, perturbed by 10 %, to stay on the same branch
            Rb = leg.rotations[0]
            theta = math.atan2(Rb[1, 0], Rb[0, 0]) - math.radians(GEO.base_angles_deg[i])
            guess = np.concatenate([1.1 * n0, 1.1 * (Rb.T @ m0)[:2], [theta]])
            sh = solve_rod_tip_pose(P0[i], R0[i], Li, K, tip[:3, 3], tip[:3, :3], initial_guess=guess)
            assert sh.converged
            assert abs(sh.moments[0] @ sh.rotations[0][:, 2]) < 1e-10
        ref = integrate_cosserat_rod(P0[i], sh.rotations[0], sh.forces[0], sh.moments[0], Li, K, n_eval=n + 1)
        e_shape = np.max(np.linalg.norm(ref.positions - leg.positions, axis=1))
        e_force = np.linalg.norm(sh.forces[-1] - leg.tip_force) / np.linalg.norm(sh.forces[-1])
        e_moment = np.linalg.norm(sh.moments[-1] - leg.tip_moment) / np.linalg.norm(sh.moments[-1])
        errs.append((e_shape, e_force, e_moment))
    assert errs[-1][0] < 1e-4 * Li
    assert errs[-1][2] < 1e-2
    for k in range(3):
        assert 3.0 < errs[0][k] / errs[1][k] < 5.0


# ----------------------------------------------------------------------------- one module


@pytest.fixture(scope="module")
def home_ik():
    ik = module_inverse(GEO, home_pose(GEO))
    assert ik.success, ik.reason
    return ik


def test_home_pose_has_equal_leg_lengths(home_ik):
    """D3-symmetric geometry: all six legs have the same length at the home pose."""
    L = home_ik.lengths
    assert np.ptp(L) < 1e-9
    # legs are S-bent (offset 2 r sin 15 deg), so longer than the platform height
    assert L[0] > GEO.height


def test_module_fk_ik_round_trip():
    """FK(IK(T)) = T to 1e-6 m for a general 6-DOF pose."""
    T = pose_from_xyz_rotvec([0.05, -0.03, 0.55], [0.1, 0.2, 0.15])
    ik = module_inverse(GEO, T)
    assert ik.success, ik.reason
    assert ik.residual < 1e-6
    fk = module_forward(GEO, ik.lengths)
    assert fk.converged, fk.reason
    assert np.max(np.abs(fk.pose[:3, 3] - T[:3, 3])) < 1e-6
    assert np.linalg.norm(rotation_log(fk.pose[:3, :3].T @ T[:3, :3])) < 1e-6
    # the FK equilibrium, recomputed from the leg tip wrenches (Eq 22), balances
    assert fk.residual < 1e-6


@pytest.mark.parametrize("axis, sign", [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)])
def test_fig6_tilts_of_45_degrees_about_mid_height_round_trip(axis, sign):
    """The paper's +-45 deg rotations about x / y (Fig 6 h-k), as tilts about the point at
    mid-height on the module axis: IK converges directly (no continuation needed), FK of those
    lengths returns the pose to 1e-6 m, and the legs stay in the mild-force regime (no leg near
    buckling: all axial forces < 1 kN, measured leg compression <= 0.41 kN; about the platform centre the IK
    branch folds at 26.8 deg, see test_rx_limit_is_a_fold_of_the_ik_branch)."""
    from workbench.experiments.series_parallel.worker import module_target

    T = module_target(GEO.height, ("rx", "ry")[axis], sign * math.radians(45.0), 0.5)
    assert T[2, 3] < GEO.height  # the platform swings down and sideways, as in bending
    ik = module_inverse(GEO, T)
    assert ik.success, ik.reason
    fk = module_forward(GEO, ik.lengths)
    assert fk.converged, fk.reason
    assert np.max(np.abs(fk.pose[:3, 3] - T[:3, 3])) < 1e-6
    assert np.linalg.norm(rotation_log(fk.pose[:3, :3].T @ T[:3, :3])) < 1e-6
    axial = np.einsum("ij,j->i", ik.tip_forces, T[:3, 2])
    assert np.max(np.abs(axial)) < 1000.0, axial


def test_segment_distance_is_exact():
    """Closed-form segment-segment distance: known cases, and never above a dense sampling of the
    two segments, nor more than its grid error below it (random, parallel and degenerate pairs)."""
    from workbench.physics.series_parallel import _segment_distances

    z = np.zeros(3)
    ex, ey, ez = np.eye(3)
    assert _segment_distances(z, ex, ey, ey + ex) == pytest.approx(1.0)  # parallel, offset 1
    assert _segment_distances(z, ex, 0.5 * ex + ez - ey, 0.5 * ex + ez + ey) == pytest.approx(1.0)  # skew, crossing
    assert _segment_distances(z, ex, 2 * ex, 3 * ex) == pytest.approx(1.0)  # collinear, end to end
    rng = np.random.default_rng(7)
    u = np.linspace(0.0, 1.0, 1001)
    for k in range(60):
        P0, P1, Q0, Q1 = rng.normal(size=(4, 3))
        if k % 3 == 0:
            Q1 = Q0 + 0.7 * (P1 - P0)
        if k % 5 == 0:
            Q1 = Q0.copy()
        d = float(_segment_distances(P0, P1, Q0, Q1))
        A, B = P0 + u[:, None] * (P1 - P0), Q0 + u[:, None] * (Q1 - Q0)
        brute = float(np.min(np.linalg.norm(A[:, None] - B[None], axis=-1)))
        grid = 1e-3 * (np.linalg.norm(P1 - P0) + np.linalg.norm(Q1 - Q0))
        assert d <= brute + 1e-12 and brute - d <= grid


def test_min_leg_gap(home_ik):
    """Straight vertical legs on the hole circle: the gap is the nearest holes' distance minus d;
    the S-bent legs at the home pose do not touch (the paper's 'no interference')."""
    P0, _ = hole_frames(GEO)
    straight = P0[:, None, :] + np.linspace(0.0, 0.5, 9)[None, :, None] * np.array([0.0, 0.0, 1.0])
    gap, pair = min_leg_gap(straight, 0.006)
    assert gap == pytest.approx(2 * GEO.base_radius * math.sin(math.radians(15.0)) - 0.006, rel=1e-12)
    assert pair in ((0, 1), (2, 3), (4, 5))
    gap_home, _ = min_leg_gap(home_ik.leg_positions, GEO.rod_diameter)
    assert 0.0 < gap_home < gap + 1e-9  # the legs converge towards the platform pairs
    with pytest.raises(ValueError, match=r"shape \(6, N\+1, 3\)"):
        min_leg_gap(straight[:5], 0.006)


def test_symmetric_extension_is_pure_translation(home_ik):
    """Equal extension of all legs: by the D3 symmetry (three mirror planes through the axis) the
    platform can only move along the module axis.  Lateral and rotational components are therefore
    zero up to the solver tolerance (Newton on 1e-10 relative step size: < 1e-9 m / rad)."""
    dz = []
    for delta in (-0.02, 0.03):
        fk = module_forward(GEO, home_ik.lengths + delta)
        assert fk.converged, fk.reason
        assert np.max(np.abs(fk.pose[:2, 3])) < 1e-9
        assert np.linalg.norm(rotation_log(fk.pose[:3, :3])) < 1e-9
        dz.append(fk.pose[2, 3] - GEO.height)
    # and the platform does move along the axis, in the direction of the extension
    assert dz[0] < -0.01 and dz[1] > 0.01


def test_gravity_and_wrench_round_trip():
    """Loads enter IK (per-leg lumped weight + platform balance) and FK (one system) consistently."""
    geo = ModuleGeometry(platform_mass=2.0)
    g = np.array([0.0, 0.0, -9.81])
    wrench = np.array([5.0, -3.0, -20.0, 0.4, 0.2, -0.3])
    T = pose_from_xyz_rotvec([0.02, 0.04, 0.48], [-0.1, 0.05, 0.1])
    ik = module_inverse(geo, T, wrench=wrench, gravity=g)
    assert ik.success, ik.reason
    ik0 = module_inverse(geo, T)
    assert np.max(np.abs(ik.lengths - ik0.lengths)) > 1e-7  # the load matters
    fk = module_forward(geo, ik.lengths, wrench=wrench, gravity=g)
    assert fk.converged, fk.reason
    assert np.max(np.abs(fk.pose[:3, 3] - T[:3, 3])) < 1e-6
    assert np.linalg.norm(rotation_log(fk.pose[:3, :3].T @ T[:3, :3])) < 1e-6


def test_bad_inputs_are_rejected():
    with pytest.raises(ValueError, match="shape \\(6,\\)"):
        module_forward(GEO, np.ones(5))
    with pytest.raises(ValueError, match="positive"):
        module_forward(GEO, -np.ones(6))
    with pytest.raises(ValueError, match="\\(4, 4\\)"):
        module_inverse(GEO, np.eye(3))
    with pytest.raises(ValueError, match="gravity"):
        module_forward(GEO, np.full(6, 0.5), gravity=[0, 0])
    with pytest.raises(ValueError, match="rod_diameter"):
        ModuleGeometry(rod_diameter=0.0)
    with pytest.raises(ValueError, match="6 finite angles"):
        ModuleGeometry(base_angles_deg=(0, 1, 2))
    with pytest.raises(ValueError, match="lengths_per_module"):
        stack_forward([GEO, GEO], np.full((3, 6), 0.5))


# ----------------------------------------------------------------------------- stack and CC


def _arc_poses(k, phi, s_list):
    """Frames on a CC arc (z = tangent), base-frame poses."""
    out = []
    for s in s_list:
        th = k * s
        ax = np.array([-math.sin(phi), math.cos(phi), 0.0])
        p = np.array([(1 - math.cos(th)) / k * math.cos(phi), (1 - math.cos(th)) / k * math.sin(phi), math.sin(th) / k])
        out.append(pose_from_xyz_rotvec(p, th * ax))
    return np.stack(out)


def test_cc_fit_recovers_an_exact_arc():
    poses = _arc_poses(1.3, 0.7, [0.5, 1.0, 1.5])
    fit = fit_constant_curvature(poses)
    assert fit.curvature == pytest.approx(1.3, rel=1e-8)
    assert fit.phi == pytest.approx(0.7, abs=1e-8)
    assert fit.max_position_error < 1e-10
    assert fit.max_tangent_error < 1e-7


def test_cc_fit_reports_error_for_a_translated_stack():
    """Platforms shifted sideways without rotation (Fig 10 b/c): not an arc from the base."""
    poses = np.stack([pose_from_xyz_rotvec([0.1 * (k + 1), 0, 0.5 * (k + 1)], [0, 0, 0]) for k in range(3)])
    fit = fit_constant_curvature(poses)
    assert fit.max_position_error > 1e-3
    assert fit.max_tangent_error > 0.1


@pytest.mark.slow
def test_three_module_round_trip_bending():
    """3 modules (paper n = 3): IK of platforms placed on a CC arc, then FK of the whole stack."""
    geos = [GEO] * 3
    poses = _arc_poses(0.6, 0.3, [0.5, 1.0, 1.5])
    ik = stack_inverse(geos, poses)
    assert ik.success, ik.reason
    fk = stack_forward(geos, ik.lengths)
    assert fk.converged, fk.reason
    assert np.max(np.abs(fk.poses[:, :3, 3] - poses[:, :3, 3])) < 1e-6
    fit = fit_constant_curvature(fk.poses)
    assert fit.curvature == pytest.approx(0.6, rel=1e-5)


def test_three_module_round_trip_with_gravity():
    """Stack IK top-down with the hole reactions passed down, then one FK system of all modules."""
    geos = [ModuleGeometry(platform_mass=1.0)] * 3
    g = np.array([0.0, 0.0, -9.81])
    poses = _arc_poses(0.4, -1.0, [0.5, 1.0, 1.5])
    ik = stack_inverse(geos, poses, gravity=g)
    assert ik.success, ik.reason
    fk = stack_forward(geos, ik.lengths, gravity=g)
    assert fk.converged, fk.reason
    assert np.max(np.abs(fk.poses[:, :3, 3] - poses[:, :3, 3])) < 1e-6
    assert fk.residual < 1e-6


def test_rx_limit_is_a_fold_of_the_ik_branch():
    """rx limit: the IK branch connected to home has a fold (turning point) at rx ~ 26.8 deg.

    Pose continuation along rx with a secant predictor in L; at every converged state the
    scaled IK Jacobian ``d(balance)/dL`` is built.  On the way to the fold its determinant keeps
    its sign and goes to zero linearly in the angle (a regular turning point), while the
    compression-side leg 1 (it buckles into a loop) lengthens ever faster (L ~ sqrt(theta* - theta)).
    A numerical stall (Newton losing a regular branch) would show neither.
    """
    from scipy.spatial.transform import Rotation

    from workbench.physics import series_parallel as sp

    H = home_pose(GEO)
    S = np.diag([1.0, 1.0, 1.0] + [1.0 / GEO.platform_radius] * 3)
    kw = dict(w=None, g=None, n_el=8, length_tolerance=1e-10, leg_tolerance=1e-11, fd_step=1e-7, counter=[0])
    lams = [0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.53, 0.56, 0.58, 0.585, 0.59, 0.5925, 0.595]
    angles = [0.785 * lam for lam in lams]
    L, legs, L_prev, a_prev, a_cur, T_cur = sp._hermite_lengths(GEO, H), None, None, None, 0.0, H
    dets, L1 = [], []
    for a in angles:
        T = H.copy()
        T[:3, :3] = Rotation.from_rotvec([a, 0.0, 0.0]).as_matrix()
        if L_prev is None:
            Lg = L + (sp._hermite_lengths(GEO, T) - sp._hermite_lengths(GEO, T_cur))
        else:
            Lg = L + (L - L_prev) * (a - a_cur) / (a_cur - a_prev)
        Ln, legs_n, ok, _, _, msg = sp._ik_newton(GEO, T, Lg, legs, legs0_L=L, max_iterations=30, **kw)
        assert ok, f"rx = {math.degrees(a):.2f} deg: {msg}"
        if legs is not None:
            L_prev, a_prev = L, a_cur
        L, legs, a_cur, T_cur = Ln, legs_n, a, T
        dets.append(np.linalg.det(S @ sp._ik_jacobian(GEO, T, L, legs)))
        L1.append(L[1])
    dets = np.array(dets)
    assert np.all(dets < 0), dets  # one branch, no sign change before the fold
    # linear extrapolation of det from the last two states: zero within 0.5 deg past the last one
    a_zero = angles[-1] - dets[-1] * (angles[-1] - angles[-2]) / (dets[-1] - dets[-2])
    assert angles[-1] < a_zero < angles[-1] + math.radians(0.5), math.degrees(a_zero)
    # |det| falls by > 3x over the last 0.45 deg (measured 4.2x)
    assert abs(dets[-1]) < 0.3 * abs(dets[-4])
    # leg 1 lengthens ever faster towards the fold
    rate = np.diff(L1) / np.diff(angles)
    assert rate[-1] > 2.0 * rate[-4] > 0  # measured 2.8x
    assert L1[-1] > 1.7 * GEO.height  # a 0.5 m module needs a > 0.85 m leg 1 here


@pytest.mark.slow
def test_ik_stops_at_the_fold_instead_of_changing_branch():
    """rx = 29 deg about the platform centre lies past the fold of the home branch (26.8 deg).
    Without the branch check the pose continuation jumps the fold and returns lengths of another
    branch (leg 1 a 0.95 m loop in a 0.5 m module); with it (default) the IK fails, says where
    (26.x deg) and that the IK Jacobian is nearly singular there (a fold, not a solver stall)."""
    import re

    T = pose_from_xyz_rotvec([0.0, 0.0, GEO.height], [math.radians(29.0), 0.0, 0.0])
    loose = module_inverse(GEO, T, check_branch=False)
    assert loose.success and loose.lengths[1] > 1.8 * GEO.height
    checked = module_inverse(GEO, T)
    assert not checked.success
    assert "rotation 26." in checked.reason, checked.reason
    ratio = float(re.search(r"smallest singular value of the IK Jacobian there ([0-9.e+-]+) x", checked.reason).group(1))
    assert ratio < 1e-2 and "near a fold" in checked.reason, checked.reason


def test_home_cache_gives_the_same_answer_with_fewer_leg_solves():
    """The branch check's home reference, kept in a caller-owned dict, is reused, not recomputed."""
    T = pose_from_xyz_rotvec([0.03, 0.0, 0.52], [0.0, 0.1, 0.0])
    cache: dict = {}
    first = module_inverse(GEO, T, home_cache=cache)
    second = module_inverse(GEO, T, home_cache=cache)
    plain = module_inverse(GEO, T)
    assert first.success and second.success and len(cache) == 1
    assert np.array_equal(first.lengths, second.lengths) and np.array_equal(first.lengths, plain.lengths)
    assert second.leg_solves < first.leg_solves == plain.leg_solves
