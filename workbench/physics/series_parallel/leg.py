"""One flexible leg: static equilibrium of an Exudyn GE-beam rod between its hole and its tip.

:func:`leg_static` solves a leg with a prescribed tip pose (the inverse-kinematics leg problem,
Eq 21, 25, 26; continuation from the straight leg when Newton fails) or a dead tip wrench
(cantilever).  :func:`leg_solve` is the leg solve of the module IK (warm start, then a homotopy
from the neighbouring state).  Checked against the Cosserat shooting solver
(``workbench.reference.cosserat``) in ``tests/physics/test_series_parallel.py``
(``test_leg_matches_shooting_solver_*``, ``test_leg_with_hole_condition_matches_shooting_solver``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

from .._stepping import continuation
from ._systems import LegShape, StaticOutcome, solve_leg_tip_pose, solve_leg_tip_wrench
from .geometry import (
    ModuleGeometry,
    check_gravity,
    check_n_elements,
    check_pose,
    check_wrench,
    attachment_points,
    hole_frames,
)
from .predictor import GL_U, GL_W, hermite_curve, leg_shape


@dataclass(frozen=True)
class LegSolution:
    """Static state of one leg (Exudyn GE beam).

    Parameters
    ----------
    positions : ndarray, shape (N+1, 3)
        Node positions [m], hole first.
    rotations : ndarray, shape (N+1, 3, 3)
        Section frames (column 3 = material tangent; Cosserat convention).
    tip_force, tip_moment : ndarray, shape (3,)
        ``n(L)``, ``m(L)``: force [N] and moment [N m] the tip support exerts on the rod, global
        frame (NaN when not converged; for a tip-wrench problem: the applied wrench).
    converged : bool
    iterations : int
        Newton iterations.
    reason : str
        Failure reason ("" when converged).
    """

    positions: np.ndarray
    rotations: np.ndarray
    tip_force: np.ndarray
    tip_moment: np.ndarray
    converged: bool
    iterations: int
    reason: str = ""


def leg_static(
    geometry: ModuleGeometry,
    base_position,
    base_rotation,
    length: float,
    *,
    tip_pose=None,
    tip_wrench=None,
    free_base_twist: bool = True,
    gravity=None,
    n_elements: int = 8,
    tolerance: float = 1e-10,
    max_iterations: int = 50,
    n_load_steps: int = 10,
    initial_guess: "LegSolution | None" = None,
    continuation: bool = True,
) -> LegSolution:
    """Static equilibrium of one flexible leg (GE beam) for given end conditions.

    Exactly one of ``tip_pose`` (both ends prescribed: the inverse-kinematics leg problem,
    Eq 21, 25, 26) and ``tip_wrench`` (cantilever with a dead tip load; base clamped,
    ``free_base_twist`` must be False) is given.

    Parameters
    ----------
    geometry : ModuleGeometry
        Supplies the rod section and material (``rod_diameter``, ``youngs_modulus``, ...).
    base_position : array_like, shape (3,)
        Hole position [m].
    base_rotation : array_like, shape (3, 3)
        Rod frame at the hole (column 3 = hole axis).
    length : float
        Free length hole -> tip [m] (the insertion length L_i).
    tip_pose : array_like, shape (4, 4), optional
        Prescribed tip frame (column 3 of the rotation = rod tangent).
    tip_wrench : array_like, shape (6,), optional
        Dead tip force and moment, global frame [N, N m].
    free_base_twist : bool
        Hole condition (revolute about the hole axis) if True, full clamp if False.
    gravity : array_like, shape (3,), optional
        Gravitational acceleration [m/s^2]; rod weight lumped at the nodes.
    n_elements : int
        Beam elements of the leg.
    tolerance : float
        Newton relative tolerance on the step size.
    max_iterations : int
        Newton iteration cap per load step.
    n_load_steps : int
        Load steps of a tip-wrench problem (adaptive halving on failure); a tip-pose problem is
        solved in one step (constraints are not ramped by Exudyn).
    initial_guess : LegSolution, optional
        Converged state of a nearby problem (same ``n_elements``) to start Newton from, instead
        of the length-matched cubic-Hermite shape.
    continuation : bool
        Tip-pose problems: if Newton fails from the start shape, walk from the straight leg to
        the target (tip pose interpolated on SE(3), leg length following the Hermite length of
        each intermediate pose and blending into ``length``), warm-starting every step and
        halving the step on failure.

    Returns
    -------
    LegSolution
    """
    p0 = np.asarray(base_position, dtype=float)
    R0 = np.asarray(base_rotation, dtype=float)
    if p0.shape != (3,) or R0.shape != (3, 3):
        raise ValueError(f"base_position must be (3,) and base_rotation (3, 3), got {p0.shape}, {R0.shape}")
    L = float(length)
    if not (math.isfinite(L) and L > 0):
        raise ValueError(f"length must be finite and > 0, got {length!r}")
    if (tip_pose is None) == (tip_wrench is None):
        raise ValueError("give exactly one of tip_pose and tip_wrench")
    n_el = check_n_elements(n_elements)
    g = check_gravity(gravity)
    rod = geometry.rod_params()
    if tip_pose is not None:
        T = check_pose(tip_pose, "tip_pose")
        if initial_guess is not None and initial_guess.converged and initial_guess.positions.shape == (n_el + 1, 3):
            shape = LegShape(positions=initial_guess.positions.copy(), rotations=initial_guess.rotations.copy())
            shape.positions[-1] = T[:3, 3]
            shape.rotations[-1] = T[:3, :3]
        else:
            shape = leg_shape(p0, R0, L, T[:3, 3], T[:3, :3], n_el, free_base_twist)
        out, F, M, P, R = solve_leg_tip_pose(  # one step: nothing to ramp
            rod, p0, R0, L, T[:3, 3], T[:3, :3], shape, g, tolerance, max_iterations, free_base_twist
        )
        if not out.converged and continuation:
            out, F, M, P, R = _leg_pose_continuation(
                rod, p0, R0, L, T, n_el, g, tolerance, max_iterations, free_base_twist, out
            )
    else:
        if free_base_twist:
            raise ValueError("a tip-wrench leg needs a clamped base (free_base_twist=False): the twist would be a free mode")
        w = check_wrench(tip_wrench)
        s = np.linspace(0.0, L, n_el + 1)
        shape = LegShape(positions=p0 + s[:, None] * R0[:, 2], rotations=np.tile(R0, (n_el + 1, 1, 1)))
        out, P, R = solve_leg_tip_wrench(rod, p0, R0, L, w[:3], w[3:], shape, g, tolerance, max_iterations, n_load_steps)
        F, M = (w[:3], w[3:]) if out.converged else (None, None)
    if not out.converged:
        nan = np.full(3, np.nan)
        return LegSolution(np.full((n_el + 1, 3), np.nan), np.full((n_el + 1, 3, 3), np.nan), nan, nan, False, out.iterations, out.reason)
    return LegSolution(P, R, np.asarray(F, float), np.asarray(M, float), True, out.iterations, "")


def _leg_pose_continuation(rod, p0, R0, L, T, n_el, g, tol, max_it, free_twist, last_out, min_step=1.0 / 512):
    """Continuation fallback of :func:`leg_static` for a prescribed tip pose (see there)."""

    def hlen(pt, Rt):
        _, D = hermite_curve(p0, R0[:, 2], pt, Rt[:, 2], GL_U)
        return float(np.sum(GL_W * np.linalg.norm(D, axis=1)))

    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([R0, T[:3, :3]])))
    p_start = p0 + L * R0[:, 2]
    dL = L - hlen(T[:3, 3], T[:3, :3])
    s_nodes = np.linspace(0.0, 1.0, n_el + 1)
    P = p0 + np.outer(s_nodes * L, R0[:, 2])
    R = np.tile(R0, (n_el + 1, 1, 1))
    out = last_out
    F = M = None

    def step(lam, lt):
        nonlocal out, P, R, F, M
        pt = (1.0 - lt) * p_start + lt * T[:3, 3]
        Rt = slerp([lt]).as_matrix()[0]
        Lt = hlen(pt, Rt) + lt * dL
        Pg = P + np.outer(s_nodes, pt - P[-1])
        Rg = R.copy()
        Rg[-1] = Rt
        out, Ft, Mt, Pt, Rr = solve_leg_tip_pose(
            rod, p0, R0, Lt, pt, Rt, LegShape(positions=Pg, rotations=Rg), g, tol, max_it, free_twist
        )
        if out.converged:
            P, R, F, M = Pt, Rr, Ft, Mt
        return out.converged

    walk = continuation(step, first=0.125, max_step=0.25, min_step=min_step)
    if not walk.completed:
        reason = f"continuation stalled at {walk.reached:.3f} of the way to the tip pose: {out.reason}"
        return StaticOutcome(False, out.iterations, out.residual, reason, out.wall_time), None, None, None, None
    return out, F, M, P, R


def leg_solve(geometry, i, Li, T, gravity, n_el, tol, max_it, guess=None, guess_length=None):
    P0, R0 = hole_frames(geometry)
    A = attachment_points(geometry)
    Tt = np.eye(4)
    Tt[:3, :3] = T[:3, :3]
    Tt[:3, 3] = T[:3, :3] @ A[i] + T[:3, 3]
    kw = dict(tip_pose=Tt, free_base_twist=True, gravity=gravity, n_elements=n_el, tolerance=tol, max_iterations=max_it,
              continuation=False)  # the IK continues on the platform pose instead (cheaper)
    leg = leg_static(geometry, P0[i], R0[i], Li, initial_guess=guess, **kw)
    if not leg.converged and guess is not None and guess.converged and guess_length is not None:
        leg = _leg_homotopy(geometry, P0[i], R0[i], guess, float(guess_length), Li, Tt, kw)
    if not leg.converged and guess is not None:
        leg = leg_static(geometry, P0[i], R0[i], Li, **kw)
    return leg


def _leg_homotopy(geometry, p0, R0, guess, L_start, L_end, T_end, kw, min_step=1.0 / 64):
    """Walk one leg from a converged state (``guess`` at length ``L_start``) to (``L_end``, ``T_end``).

    Tip position, tip rotation (slerp) and length are interpolated together, every step
    warm-started from the last.  Needed where the legs are strongly S-bent (large platform
    rotations): one Newton solve from the neighbouring state then diverges although the leg
    problem is regular, because the change of the stress-free length enters through the stiff
    axial direction (``EA dL / L``).
    """
    Tg = np.eye(4)
    Tg[:3, :3] = guess.rotations[-1]
    Tg[:3, 3] = guess.positions[-1]
    slerp = Slerp([0.0, 1.0], Rotation.from_matrix(np.stack([Tg[:3, :3], T_end[:3, :3]])))
    cur = last = guess
    kw = dict(kw)
    kw.pop("tip_pose")

    def step(lam, lt):
        nonlocal cur, last
        Tt = np.eye(4)
        Tt[:3, :3] = slerp([lt]).as_matrix()[0]
        Tt[:3, 3] = (1.0 - lt) * Tg[:3, 3] + lt * T_end[:3, 3]
        last = leg_static(geometry, p0, R0, (1.0 - lt) * L_start + lt * L_end, tip_pose=Tt, initial_guess=cur, **kw)
        if last.converged:
            cur = last
        return last.converged

    walk = continuation(step, first=0.25, max_step=0.5, min_step=min_step)
    return cur if walk.completed else last


def base_reaction_lumped(geometry, i, leg: LegSolution, Li, gravity):
    """``n_i(0)``, ``m_i(0)`` (about the hole): force and moment rod i exerts on the base.

    Exact for the discrete model: equilibrium of the whole leg under the tip wrench and the rod
    weight lumped at the nodes (as in ``_systems._add_leg``).
    """
    P0, _ = hole_frames(geometry)
    return hole_reaction(leg.positions, leg.tip_force, leg.tip_moment, P0[i], Li,
                          geometry.rod_params().weight_per_length, gravity)


def hole_reaction(positions, tip_force, tip_moment, hole, length, weight_per_length, gravity):
    """Force and moment (about ``hole``) a leg exerts at its hole, from its tip wrench and weight.

    ``positions`` ``(N+1, 3)`` are the leg nodes (hole first), ``tip_force``/``tip_moment`` the
    wrench the tip support exerts on the leg, ``weight_per_length`` [kg/m] times ``gravity``
    [m/s^2] lumped at the nodes (half weight at both ends), as in ``_systems._add_leg``.
    """
    n0 = tip_force.copy()
    m0 = tip_moment + np.cross(positions[-1] - hole, tip_force)
    if gravity is not None:
        N = positions.shape[0] - 1
        wts = np.full(N + 1, length / N)
        wts[0] *= 0.5
        wts[-1] *= 0.5
        f = wts[:, None] * (weight_per_length * gravity)[None, :]
        n0 = n0 + f.sum(axis=0)
        m0 = m0 + np.sum(np.cross(positions - hole, f), axis=0)
    return n0, m0
