"""Inverse kinematics of one module (Eq 25-28).

Newton over ``L`` (``newton.py``), with a fallback continuation along the SE(3) path
from the home pose and a check that the solution stays on the IK branch connected to home
(``branch.py``).  The forward kinematics of one module is a one-module stack
(:func:`workbench.physics.series_parallel.stack.module_forward`).  Checked by
``tests/physics/test_series_parallel.py`` (FK o IK round trips, the fold and home-cache tests).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .branch import branch_sign, BranchCheckError, home_reference, walk_from_home
from .geometry import (
    ModuleGeometry,
    check_gravity,
    check_lengths,
    check_n_elements,
    check_pose,
    check_wrench,
    home_pose,
)
from .leg import base_reaction_lumped
from .newton import ik_newton, resnorm
from .predictor import hermite_lengths


@dataclass(frozen=True)
class ModuleIK:
    """Inverse kinematics of one module (Eq 25-28).

    Parameters
    ----------
    lengths : ndarray, shape (6,)
        Insertion lengths L_i [m] (NaN when the IK failed: no partial answer is passed off as one).
    success : bool
        Newton converged (length update below ``length_tolerance``) and every leg solve converged.
    iterations : int
        Newton iterations over L.
    residual : float
        Max-norm of the platform balance Eq 22 at the returned L (forces in N, moments / platform
        radius in N).
    reason : str
        Failure reason, "" on success.
    tip_forces, tip_moments : ndarray, shape (6, 3)
        ``n_i(L_i)``, ``m_i(L_i)`` at the solution, module base frame.
    base_forces, base_moments : ndarray, shape (6, 3)
        Force and moment (about the hole) each rod exerts on the base platform, ``n_i(0)``,
        ``m_i(0)``, module base frame (what stack IK passes to the module below).
    leg_positions : ndarray, shape (6, N+1, 3)
        Leg node positions [m].
    leg_solves : int
        Number of single-leg static solves used.
    wall_time : float
        Seconds.
    """

    lengths: np.ndarray
    success: bool
    iterations: int
    residual: float
    reason: str
    tip_forces: np.ndarray
    tip_moments: np.ndarray
    base_forces: np.ndarray
    base_moments: np.ndarray
    leg_positions: np.ndarray
    leg_solves: int = 0
    wall_time: float = 0.0


def module_inverse(
    geometry: ModuleGeometry,
    target_pose,
    wrench=None,
    gravity=None,
    *,
    n_elements: int = 8,
    initial_lengths=None,
    length_tolerance: float = 1e-10,
    max_iterations: int = 20,
    leg_tolerance: float = 1e-11,
    fd_step: float = 1e-7,
    path_steps: int | None = None,
    check_branch: bool = True,
    home_cache: dict | None = None,
) -> ModuleIK:
    """Inverse kinematics of one module: insertion lengths that hold the platform at a pose (Eq 25-28).

    With the platform pose prescribed, each leg is an independent two-point boundary-value
    problem (hole condition Eq 21 at the base, clamp Eq 25-26 at the platform), solved with
    Exudyn.  Newton over ``L`` drives the platform balance Eq 22 to zero; the Jacobian
    ``d(balance)/dL`` is built column by column by forward differences (leg i depends on L_i
    only, so a column costs one leg solve), reused (chord Newton) while the length updates
    contract by at least a factor 4, with a backtracking line search on the balance residual.
    Large motions fall back to continuation along the path from the home pose.

    Parameters
    ----------
    geometry : ModuleGeometry
    target_pose : array_like, shape (4, 4)
        Desired platform pose in the module base frame.
    wrench : array_like, shape (6,), optional
        External force and moment on the platform at its origin, base frame [N, N m].
    gravity : array_like, shape (3,), optional
        Gravitational acceleration, base frame [m/s^2].
    n_elements : int
        GE beam elements per leg.
    initial_lengths : array_like, shape (6,), optional
        Start (default: cubic-Hermite leg lengths of the target pose).
    length_tolerance : float
        Converged when the max length update is below this [m].
    max_iterations : int
        Newton iteration cap.
    leg_tolerance : float
        Newton tolerance of each leg solve.
    fd_step : float
        Finite-difference step on L_i [m].
    path_steps : int, optional
        If Newton from the start fails, continue along the SE(3) path from the home pose to the
        target in this many steps (adaptive halving; default: about one step per 40 mm and
        0.1 rad); 0 disables the fallback.
    check_branch : bool
        Accept only solutions on the IK solution branch connected to the home pose (under the same
        loads): the sign of ``det d(balance)/dL`` must equal its sign at home, at the solution and
        at every continuation step (one extra Jacobian, six leg solves, per check).  A sign change
        marks a fold or bifurcation of the branch (measured for the default module: rx 26.8 deg
        about the platform centre); beyond it the legs only close on other branches (buckled,
        looped legs), so the IK fails there with that reason instead of returning them.
    home_cache : dict, optional
        Caller-owned dict in which the home-pose reference of the branch check is kept, keyed by
        geometry, loads and solver settings; pass the same dict to repeated calls (a sweep, the
        modules of a stack) to solve the home pose once instead of per call (its values are
        :class:`~workbench.physics.series_parallel.branch.HomeReference` tuples).

    Returns
    -------
    ModuleIK
    """
    t_start = time.perf_counter()
    T = check_pose(target_pose, "target_pose")
    w = check_wrench(wrench)
    g = check_gravity(gravity)
    n_el = check_n_elements(n_elements)
    L0 = hermite_lengths(geometry, T) if initial_lengths is None else check_lengths(initial_lengths).copy()
    counter = [0]
    kw = dict(w=w, g=g, n_el=n_el, length_tolerance=length_tolerance, leg_tolerance=leg_tolerance, fd_step=fd_step,
              counter=counter)
    direct_cap = max_iterations if path_steps == 0 else min(max_iterations, 8)
    L, legs, ok, total_its, r, msg = ik_newton(geometry, T, L0, None, max_iterations=direct_cap, **kw)
    cache = {} if home_cache is None else home_cache  # the home reference is solved at most once per call

    def home():
        return home_reference(geometry, kw, max(max_iterations, 20), cache)

    at_home = bool(np.allclose(T, home_pose(geometry), rtol=0.0, atol=1e-12))
    direct_off_branch = False
    try:
        if ok and check_branch and not at_home and branch_sign(geometry, T, L, legs, kw, counter) != home().sign:
            ok, msg, direct_off_branch = False, "", True
    except BranchCheckError as e:
        ok, msg, path_steps = False, str(e), 0
    if not ok and path_steps != 0:
        walk = walk_from_home(geometry, T, kw, home=home if check_branch else None, path_steps=path_steps,
                              max_iterations=max_iterations)
        total_its += walk.iterations
        msg = walk.reason
        if walk.success:
            L, legs, ok, r = walk.lengths, walk.legs, True, walk.residual
    if not ok and direct_off_branch:
        msg = ((msg + "; ") if msg else "") + ("direct Newton converged on another IK solution branch (sign of det "
                                               "d(balance)/dL differs from home's: buckled or looped legs), rejected")
    return _module_ik(geometry, L, legs, ok, total_its, r, msg, g, n_el, counter[0], t_start)


def _module_ik(geometry, L, legs, ok, iterations, r, msg, g, n_el, leg_solves, t_start) -> ModuleIK:
    """The :class:`ModuleIK` of a solve: reactions at the holes on success, NaN everywhere on failure."""
    if not ok or legs is None or any(lg is None or not lg.converged for lg in legs):
        nan = np.full((6, 3), np.nan)
        return ModuleIK(np.full(6, np.nan), False, iterations, float("nan") if r is None else resnorm(geometry, r),
                        msg or "IK failed", nan, nan, nan, nan, np.full((6, n_el + 1, 3), np.nan), leg_solves,
                        time.perf_counter() - t_start)
    F = np.stack([lg.tip_force for lg in legs])
    M = np.stack([lg.tip_moment for lg in legs])
    base = [base_reaction_lumped(geometry, i, legs[i], L[i], g) for i in range(6)]
    return ModuleIK(
        lengths=L, success=True, iterations=iterations, residual=resnorm(geometry, r), reason="",
        tip_forces=F, tip_moments=M,
        base_forces=np.stack([b[0] for b in base]), base_moments=np.stack([b[1] for b in base]),
        leg_positions=np.stack([lg.positions for lg in legs]), leg_solves=leg_solves,
        wall_time=time.perf_counter() - t_start,
    )
