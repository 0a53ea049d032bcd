"""Modules in series (Eq 29-32): stack forward kinematics in one system, stack inverse top-down.

Module k's base frame is module k-1's platform frame times a constant mount transform.  The
extraction's Eq 30/31 (``R_k = R'_k R_{k-1}^{b_k} R_{k-1}``) is implemented as the valid frame
chain ``T_k = T_{k-1} M T'_k`` (homogeneous transforms global <- platform, ``M`` the mount
platform k-1 <- base k, ``T'_k`` the module-local pose, Eq 29); inverse ``T'_k = (T_{k-1} M)^{-1} T_k``
(Eq 31).  Forward: all modules in one Exudyn system, so loads above a module are carried exactly;
if the solve from the predictor fails, the lengths are walked from the home configuration with a
secant predictor.  Inverse: module by module from the top down, each module's hole reactions
applied to the platform below (exact because every platform pose is given).  One module's
forward kinematics, :func:`module_forward`, is a one-module stack.  Checked by the
three-module round trips of ``tests/physics/test_series_parallel.py``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from scipy.spatial.transform import Rotation

from .._stepping import continuation
from ._systems import LegShape, ModuleSpec, StaticOutcome, solve_stack
from .geometry import (
    ModuleGeometry,
    check_geometries,
    check_gravity,
    check_lengths,
    check_n_elements,
    check_pose,
    check_wrench,
    attachment_points,
    hole_frames,
    home_pose,
)
from .leg import LegSolution, hole_reaction, leg_static
from .module import module_inverse
from .newton import resnorm
from .predictor import leg_shape, pose_from_lengths_hermite


@dataclass(frozen=True)
class ModulePose:
    """Forward kinematics of one module (static equilibrium, Eq 21-24).

    Parameters
    ----------
    pose : ndarray, shape (4, 4)
        Platform pose in the module base frame (base <- platform).
    tip_forces, tip_moments : ndarray, shape (6, 3)
        ``n_i(L_i)``, ``m_i(L_i)``: force [N] and moment [N m] the platform exerts on each rod
        tip, module base frame.
    leg_positions : ndarray, shape (6, N+1, 3)
        Leg node positions [m], hole first.
    converged : bool
    iterations : int
        Newton iterations of the static solve.
    residual : float
        Max-norm of the platform balance Eq 22 recomputed from the leg tip wrenches (forces in N,
        moments divided by the platform radius, in N): an independent equilibrium check.
    reason : str
        Failure reason, "" when converged.
    wall_time : float
        Seconds.
    """

    pose: np.ndarray
    tip_forces: np.ndarray
    tip_moments: np.ndarray
    leg_positions: np.ndarray
    converged: bool
    iterations: int
    residual: float
    reason: str = ""
    wall_time: float = 0.0


@dataclass(frozen=True)
class StackPose:
    """Forward kinematics of n modules in series (Eq 29-30).

    Parameters
    ----------
    poses : ndarray, shape (n, 4, 4)
        Platform poses in the stack base frame (global <- platform k).
    local_poses : ndarray, shape (n, 4, 4)
        Platform k in module k's base frame (Eq 29).
    leg_positions : ndarray, shape (n, 6, N+1, 3)
        Leg node positions, stack base frame [m].
    converged, iterations, residual, reason, wall_time
        As in :class:`ModulePose`; ``residual`` is the worst platform balance over the stack.
    """

    poses: np.ndarray
    local_poses: np.ndarray
    leg_positions: np.ndarray
    converged: bool
    iterations: int
    residual: float
    reason: str = ""
    wall_time: float = 0.0


@dataclass(frozen=True)
class StackIK:
    """Inverse kinematics of n modules in series (Eq 31-32).

    Parameters
    ----------
    lengths : ndarray, shape (n, 6)
        Insertion lengths per module [m].
    success : bool
    iterations : ndarray, shape (n,)
        Newton iterations per module.
    residual : float
        Worst module residual (see :class:`ModuleIK`).
    reason : str
    modules : tuple of ModuleIK
        Per-module results (module base frames).
    wall_time : float
    """

    lengths: np.ndarray
    success: bool
    iterations: np.ndarray
    residual: float
    reason: str
    modules: tuple
    wall_time: float = 0.0


def _spec(geometry: ModuleGeometry, L: np.ndarray) -> ModuleSpec:
    P, R = hole_frames(geometry)
    return ModuleSpec(
        hole_positions=P,
        hole_rotations=R,
        attachments=attachment_points(geometry),
        lengths=np.asarray(L, float),
        rod=geometry.rod_params(),
        platform_mass=geometry.platform_mass,
        platform_inertia=geometry.platform_inertia(),
        mount=geometry.mount_transform(),
    )


def stack_forward(
    geometries: Sequence[ModuleGeometry],
    lengths_per_module,
    wrench=None,
    gravity=None,
    *,
    base_pose=None,
    n_elements: int = 8,
    initial_poses=None,
    tolerance: float = 1e-10,
    max_iterations: int = 50,
    continuation: bool = True,
    _return_legs: bool = False,
):
    """Forward kinematics of n modules in series (Eq 29-30), one static equilibrium.

    All modules are solved together: module k's holes sit on platform k-1 (through the constant
    mount transform of module k-1), so the weight of the modules above and the tip wrench are
    carried exactly.  Without loads this equals the paper's recursion ``T_k = T_{k-1} M T'_k``
    with each ``T'_k = F(L_k)`` (Eq 29-30).

    Parameters
    ----------
    geometries : sequence of n ModuleGeometry
        Module 1 (at the base) first.
    lengths_per_module : array_like, shape (n, 6)
        Insertion lengths [m].
    wrench : array_like, shape (6,), optional
        External force/moment at the last platform's origin, stack base frame [N, N m].
    gravity : array_like, shape (3,), optional
        Gravitational acceleration, stack base frame [m/s^2].
    base_pose : array_like, shape (4, 4), optional
        Pose of module 1's base in the stack base frame (default identity).
    n_elements : int
        GE beam elements per leg.
    initial_poses : array_like, shape (n, 4, 4), optional
        Module-local starting guesses for the geometric predictor (default home poses).
    tolerance, max_iterations
        Newton settings.
    continuation : bool
        If the solve from the geometric predictor fails, start from the home poses (their
        insertion lengths by :func:`module_inverse`) and walk the lengths to the requested ones,
        warm-starting every step from the previous equilibrium and halving the step on failure.

    Returns
    -------
    StackPose
    """
    t_start = time.perf_counter()
    gs = check_geometries(geometries)
    n = len(gs)
    Ls = np.asarray(lengths_per_module, dtype=float)
    if Ls.shape != (n, 6):
        raise ValueError(f"lengths_per_module must have shape ({n}, 6), got {Ls.shape}")
    for k in range(n):
        check_lengths(Ls[k])
    w = check_wrench(wrench)
    g = check_gravity(gravity)
    n_el = check_n_elements(n_elements)
    B = np.eye(4) if base_pose is None else check_pose(base_pose, "base_pose")
    guesses, shapes = _predict_stack(gs, Ls, B, initial_poses, g, n_el)
    specs = [_spec(geo, Ls[k]) for k, geo in enumerate(gs)]
    wr = None if w is None else (w[:3], w[3:])
    out, poses, F, M, (legpos, legrot) = solve_stack(specs, B, guesses, shapes, g, wr, tolerance, max_iterations, 1)
    if not out.converged and continuation:
        out, poses, F, M, (legpos, legrot) = _stack_continuation(gs, Ls, B, g, wr, n_el, tolerance, max_iterations, out)
    if not out.converged:
        nanT = np.full((n, 4, 4), np.nan)
        res = StackPose(nanT, nanT, np.full((n, 6, n_el + 1, 3), np.nan), False, out.iterations, float("nan"),
                        out.reason or "static solve failed", time.perf_counter() - t_start)
        return (res, np.full((n, 6, 3), np.nan), np.full((n, 6, 3), np.nan), None) if _return_legs else res
    local = _local_poses(gs, B, poses)
    worst = _worst_platform_balance(gs, Ls, poses, F, M, legpos, g, w)
    res = StackPose(poses, local, legpos, True, out.iterations, worst, "", time.perf_counter() - t_start)
    return (res, F, M, legrot) if _return_legs else res


def module_forward(
    geometry: ModuleGeometry,
    insertion_lengths,
    wrench=None,
    gravity=None,
    *,
    n_elements: int = 8,
    initial_pose=None,
    tolerance: float = 1e-10,
    max_iterations: int = 50,
) -> ModulePose:
    """Forward kinematics of one module: static equilibrium for given insertion lengths (Eq 21-24).

    One Exudyn static solve of six GE-beam legs and the free platform.  The start is a geometric
    predictor: the platform pose whose cubic-Hermite legs have the given lengths.

    Parameters
    ----------
    geometry : ModuleGeometry
    insertion_lengths : array_like, shape (6,)
        Free leg lengths hole -> platform L_i [m].
    wrench : array_like, shape (6,), optional
        External force [N] and moment [N m] on the platform at its origin, base frame.
    gravity : array_like, shape (3,), optional
        Gravitational acceleration in the base frame [m/s^2], e.g. ``(0, 0, -9.81)``; None = off.
    n_elements : int
        GE beam elements per leg.
    initial_pose : array_like, shape (4, 4), optional
        Starting guess for the predictor (default: home pose).
    tolerance : float
        Newton relative tolerance on the step size.
    max_iterations : int
        Newton iteration cap.

    Returns
    -------
    ModulePose
    """
    L = check_lengths(insertion_lengths)
    st = stack_forward(
        [geometry], L[None, :], wrench=wrench, gravity=gravity, n_elements=n_elements,
        initial_poses=None if initial_pose is None else check_pose(initial_pose, "initial_pose")[None],
        tolerance=tolerance, max_iterations=max_iterations, _return_legs=True,
    )
    res, F, M, _ = st
    return ModulePose(
        pose=res.poses[0], tip_forces=F[0], tip_moments=M[0], leg_positions=res.leg_positions[0],
        converged=res.converged, iterations=res.iterations, residual=res.residual, reason=res.reason,
        wall_time=res.wall_time,
    )


def _predict_stack(gs, Ls, B, initial_poses, g, n_el):
    """Geometric predictor, module by module (Eq 30 recursion): global platform poses ``(n, 4, 4)``
    and, per module, six leg shapes, each leg in equilibrium with its platform held at the
    predicted pose (the Hermite shape alone is too far off for Newton on the whole module)."""
    n = len(gs)
    guesses = np.empty((n, 4, 4))
    shapes = []
    Tb = B.copy()
    for k, geo in enumerate(gs):
        Tk0 = home_pose(geo) if initial_poses is None else check_pose(np.asarray(initial_poses)[k], "initial_poses[k]")
        Tloc = pose_from_lengths_hermite(geo, Ls[k], Tk0)
        guesses[k] = Tb @ Tloc
        P0, R0 = hole_frames(geo)
        A = attachment_points(geo)
        legs = []
        for i in range(6):
            pb = Tb[:3, :3] @ P0[i] + Tb[:3, 3]
            Rb = Tb[:3, :3] @ R0[i]
            pt = guesses[k][:3, :3] @ A[i] + guesses[k][:3, 3]
            Tt = np.eye(4)
            Tt[:3, :3] = guesses[k][:3, :3]
            Tt[:3, 3] = pt
            leg = leg_static(geo, pb, Rb, Ls[k, i], tip_pose=Tt, gravity=g, n_elements=n_el)
            if leg.converged:
                legs.append(LegShape(positions=leg.positions, rotations=leg.rotations))
            else:
                legs.append(leg_shape(pb, Rb, Ls[k, i], pt, guesses[k][:3, :3], n_el, True))
        shapes.append(legs)
        Tb = guesses[k] @ geo.mount_transform()
    return guesses, shapes


def _local_poses(gs, B, poses):
    """Platform k in module k's base frame (Eq 31), ``(n, 4, 4)``."""
    local = np.empty_like(poses)
    Tb = B.copy()
    for k, geo in enumerate(gs):
        local[k] = np.linalg.solve(Tb, poses[k])
        Tb = poses[k] @ geo.mount_transform()
    return local


def _worst_platform_balance(gs, Ls, poses, F, M, legpos, g, w):
    """Worst platform balance over the stack (see :class:`StackPose`), stack base frame.

    Forces on platform k: its legs' tips, the next module's holes (that module's hole reactions),
    gravity, and the tip wrench on the last platform.
    """
    n = len(gs)
    worst = 0.0
    for k, geo in enumerate(gs):
        Tk = poses[k]
        A = attachment_points(geo)
        pa = (Tk[:3, :3] @ A.T).T + Tk[:3, 3]
        Fs = -F[k].sum(axis=0)
        Ms = -np.sum(np.cross(pa - Tk[:3, 3], F[k]) + M[k], axis=0)
        if g is not None:
            Fs = Fs + geo.platform_mass * g
        if k + 1 < n:
            geo_n = gs[k + 1]
            Tbn = Tk @ geo.mount_transform()
            P0, _ = hole_frames(geo_n)
            for i in range(6):
                hole = Tbn[:3, :3] @ P0[i] + Tbn[:3, 3]
                n0, m0 = hole_reaction(legpos[k + 1, i], F[k + 1, i], M[k + 1, i], hole, Ls[k + 1, i],
                                        geo_n.rod_params().weight_per_length, g)
                Fs = Fs + n0
                Ms = Ms + m0 + np.cross(hole - Tk[:3, 3], n0)
        elif w is not None:
            Fs = Fs + w[:3]
            Ms = Ms + w[3:]
        worst = max(worst, resnorm(geo, np.concatenate([Fs, Ms])))
    return worst


def _extrapolate_rot(R_prev, R_curr, c):
    """``R_curr exp(c log(R_prev^T R_curr))`` for stacks of rotations (..., 3, 3)."""
    shp = R_curr.shape
    a = Rotation.from_matrix(R_prev.reshape(-1, 3, 3))
    b = Rotation.from_matrix(R_curr.reshape(-1, 3, 3))
    d = (a.inv() * b).as_rotvec()
    return (b * Rotation.from_rotvec(c * d)).as_matrix().reshape(shp)


def _presolve_legs(gs, Ls, B, poses, g, n_el, guess_pos, guess_rot):
    """Leg shapes for a stack solve: each leg in equilibrium with its platform held at ``poses``."""
    shapes = []
    Tb = B.copy()
    for k, geo in enumerate(gs):
        P0, R0 = hole_frames(geo)
        A = attachment_points(geo)
        legs = []
        for i in range(6):
            pb = Tb[:3, :3] @ P0[i] + Tb[:3, 3]
            Rb = Tb[:3, :3] @ R0[i]
            Tt = np.eye(4)
            Tt[:3, :3] = poses[k][:3, :3]
            Tt[:3, 3] = poses[k][:3, :3] @ A[i] + poses[k][:3, 3]
            guess = LegSolution(guess_pos[k, i], guess_rot[k, i], np.zeros(3), np.zeros(3), True, 0)
            leg = leg_static(geo, pb, Rb, Ls[k, i], tip_pose=Tt, gravity=g, n_elements=n_el, initial_guess=guess,
                             continuation=False)
            if leg.converged:
                legs.append(LegShape(positions=leg.positions, rotations=leg.rotations))
            else:
                legs.append(LegShape(positions=guess_pos[k, i], rotations=guess_rot[k, i]))
        shapes.append(legs)
        Tb = poses[k] @ geo.mount_transform()
    return shapes


def _stack_home(gs, B, n_el, tol, max_it):
    """Home configuration of the stack (no loads): lengths by IK of each home pose, then the FK
    (predictor + leg equilibria); ``(L_home, poses, leg positions, leg rotations)`` or None."""
    n = len(gs)
    L_home = np.empty((n, 6))
    for k, geo in enumerate(gs):
        ik = module_inverse(geo, home_pose(geo), n_elements=n_el)
        if not ik.success:
            return None
        L_home[k] = ik.lengths
    res = stack_forward(gs, L_home, base_pose=B, n_elements=n_el, tolerance=tol, max_iterations=max_it,
                        continuation=False, _return_legs=True)
    if not res[0].converged:
        return None
    return L_home, res[0].poses, res[0].leg_positions, res[3]


def _secant_guess(prev, lam, lt, poses, legpos, legrot):
    """Platform poses and leg states at ``lt`` extrapolated from the last two accepted states."""
    if prev is None:
        return poses, legpos, legrot
    c = (lt - lam) / (lam - prev[0])
    g_poses = poses.copy()
    g_poses[:, :3, 3] += c * (poses[:, :3, 3] - prev[1][:, :3, 3])
    g_poses[:, :3, :3] = _extrapolate_rot(prev[1][:, :3, :3], poses[:, :3, :3], c)
    g_pos = legpos + c * (legpos - prev[2])
    g_rot = _extrapolate_rot(prev[3], legrot, c)
    return g_poses, g_pos, g_rot


def _stack_continuation(gs, Ls, B, g, wr, n_el, tol, max_it, last_out, min_step=1.0 / 256):
    """Length continuation from the home configuration for :func:`stack_forward`.

    Lengths, gravity and tip wrench go linearly from home (no loads) to the requested ones
    (:func:`workbench.physics._stepping.continuation`: first step 1/4, doubling up to 1/2, stall below ``min_step``),
    each step started from a secant predictor with every leg pre-solved at its new length.
    """
    home = _stack_home(gs, B, n_el, tol, max_it)
    if home is None:
        return last_out, None, None, None, (None, None)
    L_home, poses, legpos, legrot = home
    out = last_out
    F = M = None
    prev = None  # (lam, poses, legpos, legrot) of the step before: secant predictor

    def step(lam, lt):
        nonlocal out, prev, poses, F, M, legpos, legrot
        Lt = L_home + lt * (Ls - L_home)
        specs = [_spec(geo, Lt[k]) for k, geo in enumerate(gs)]
        g_poses, g_pos, g_rot = _secant_guess(prev, lam, lt, poses, legpos, legrot)
        # every leg pre-solved with its new length at the predicted platform pose, warm-started from
        # the previous equilibrium: the old leg shapes with the new stress-free lengths carry an
        # axial misfit (EA dL / L, ~kN for 0.1 mm) that Newton on the whole module does not survive
        shapes = _presolve_legs(gs, Lt, B, g_poses, g if g is None else lt * g, n_el, g_pos, g_rot)
        out, P_, F_, M_, (lp, lr) = solve_stack(specs, B, g_poses, shapes, g if lt == 1.0 or g is None else lt * g,
                                                     None if wr is None else (lt * wr[0], lt * wr[1]), tol, max_it, 1)
        if out.converged:
            prev = (lam, poses, legpos, legrot)
            poses, F, M, legpos, legrot = P_, F_, M_, lp, lr
        return out.converged

    walk = continuation(step, first=0.25, max_step=0.5, min_step=min_step)
    if not walk.completed:
        reason = f"length continuation from home stalled at {walk.reached:.3f}: {out.reason}"
        return StaticOutcome(False, out.iterations, out.residual, reason, out.wall_time), None, None, None, (None, None)
    return out, poses, F, M, (legpos, legrot)


def stack_inverse(
    geometries: Sequence[ModuleGeometry],
    platform_poses,
    wrench=None,
    gravity=None,
    *,
    base_pose=None,
    n_elements: int = 8,
    length_tolerance: float = 1e-10,
    max_iterations: int = 20,
) -> StackIK:
    """Inverse kinematics of n modules in series for given platform poses (Eq 31-32).

    The paper's "configuration planning" gives every platform pose; then each module's local
    target is ``T'_k = (T_{k-1} M_{k-1})^{-1} T_k`` (Eq 31) and ``L_k = f(T'_k)`` (Eq 32).  With
    loads, the modules are solved from the top down: the force and moment each rod of module k+1
    exerts on its hole (from its IK solution) are applied to platform k, which is exact because
    all platform poses are prescribed.

    Parameters
    ----------
    geometries : sequence of n ModuleGeometry
    platform_poses : array_like, shape (n, 4, 4)
        Desired platform poses in the stack base frame.
    wrench : array_like, shape (6,), optional
        External force/moment at the last platform origin, stack base frame.
    gravity : array_like, shape (3,), optional
        Stack base frame [m/s^2].
    base_pose : array_like, shape (4, 4), optional
        Module 1's base in the stack base frame (default identity).
    n_elements, length_tolerance, max_iterations
        Passed to :func:`module_inverse`.

    Returns
    -------
    StackIK
    """
    t_start = time.perf_counter()
    gs = check_geometries(geometries)
    n = len(gs)
    Tp = np.asarray(platform_poses, dtype=float)
    if Tp.shape != (n, 4, 4):
        raise ValueError(f"platform_poses must have shape ({n}, 4, 4), got {Tp.shape}")
    for k in range(n):
        check_pose(Tp[k], f"platform_poses[{k}]")
    w = check_wrench(wrench)
    g = check_gravity(gravity)
    B = np.eye(4) if base_pose is None else check_pose(base_pose, "base_pose")
    bases = [B] + [Tp[k] @ gs[k].mount_transform() for k in range(n - 1)]
    results: list = [None] * n
    home_cache: dict = {}  # the branch check's home reference, shared by modules with equal geometry and loads
    # global wrench acting on the current platform from above, as (F, M about global origin)
    # the wrench is given about the last platform origin; M_above_o is about the stack origin
    F_above = np.zeros(3) if w is None else w[:3].copy()
    M_above_o = np.zeros(3) if w is None else w[3:] + np.cross(Tp[-1][:3, 3], w[:3])
    Bg = g
    for k in range(n - 1, -1, -1):
        Tb = bases[k]
        Rb = Tb[:3, :3]
        local = np.linalg.solve(Tb, Tp[k])
        # wrench at platform k origin, module-k base frame
        pk = Tp[k][:3, 3]
        M_pk = M_above_o - np.cross(pk, F_above)
        wk = np.concatenate([Rb.T @ F_above, Rb.T @ M_pk])
        gk = None if Bg is None else Rb.T @ Bg
        r = module_inverse(gs[k], local, wrench=wk if np.any(wk) else None, gravity=gk, n_elements=n_elements,
                           length_tolerance=length_tolerance, max_iterations=max_iterations, home_cache=home_cache)
        results[k] = r
        if not r.success:
            return StackIK(np.stack([x.lengths if x is not None else np.full(6, np.nan) for x in results]), False,
                           np.array([x.iterations if x is not None else 0 for x in results]), r.residual,
                           f"module {k + 1}: {r.reason}", tuple(results), time.perf_counter() - t_start)
        # module k's rods act on its base (platform k-1): forces n_i(0), moments m_i(0) about the holes
        P0, _ = hole_frames(gs[k])
        holes = (Rb @ P0.T).T + Tb[:3, 3]
        Fg = (Rb @ r.base_forces.T).T
        Mg = (Rb @ r.base_moments.T).T
        F_above = Fg.sum(axis=0)
        M_above_o = np.sum(Mg + np.cross(holes, Fg), axis=0)
    L = np.stack([x.lengths for x in results])
    return StackIK(L, True, np.array([x.iterations for x in results]), max(x.residual for x in results), "",
                   tuple(results), time.perf_counter() - t_start)
