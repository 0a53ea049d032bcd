"""Newton over the six insertion lengths for a fixed platform pose (Eq 22 with Eq 25-26).

With the platform pose prescribed every leg is an independent two-point boundary-value problem;
Newton over ``L`` drives the platform wrench balance (Eq 22) to zero.  Eq 22 as implemented (the
extraction lost symbols): ``sum_i n_i(L_i) - F = 0`` and
``sum_i (p_i(L_i) x n_i(L_i) + m_i(L_i)) - p_c x F - M = 0``, ``n_i(L_i)`` the force the platform
exerts on rod i.  Checked by the IK round trips of ``tests/physics/test_series_parallel.py``.
"""

from __future__ import annotations

import numpy as np

from .geometry import attachment_points
from .leg import leg_solve


def platform_balance(geometry, T, F_legs, M_legs, wrench, gravity):
    """Platform balance Eq 22 in the module base frame, returns the (6,) residual [N, N m]."""
    A = attachment_points(geometry)
    p = T[:3, :3] @ A.T + T[:3, 3:4]  # (3, 6)
    F_tot = np.zeros(3)
    M_ext = np.zeros(3)
    if wrench is not None:
        F_tot = F_tot + wrench[:3]
        M_ext = M_ext + wrench[3:]
    if gravity is not None:
        F_tot = F_tot + geometry.platform_mass * gravity
    rf = F_legs.sum(axis=0) - F_tot
    rm = np.sum(np.cross(p.T, F_legs) + M_legs, axis=0) - np.cross(T[:3, 3], F_tot) - M_ext
    return np.concatenate([rf, rm])


def resnorm(geometry, r):
    return float(max(np.max(np.abs(r[:3])), np.max(np.abs(r[3:])) / geometry.platform_radius))


def ik_newton(geometry, T, L, legs0, *, legs0_L=None, w, g, n_el, length_tolerance, leg_tolerance, fd_step, max_iterations, counter):
    """Newton over L for a fixed platform pose (Eq 22 with Eq 25-26), backtracking on the residual.

    Returns (L, legs, success, iterations, residual vector, message).
    """

    def evaluate(Lv, guess_legs, only=None, base_legs=None, guess_L=None):
        legs = list(base_legs) if base_legs is not None else [None] * 6
        for i in range(6) if only is None else only:
            gl = None if guess_legs is None else guess_legs[i]
            gL = None if guess_L is None else guess_L[i]
            legs[i] = leg_solve(geometry, i, Lv[i], T, g, n_el, leg_tolerance, 50, guess=gl, guess_length=gL)
            counter[0] += 1
            if not legs[i].converged:
                return None, legs, f"leg {i} static solve failed at L = {Lv[i]:.6g} m: {legs[i].reason}"
        F = np.stack([lg.tip_force for lg in legs])
        M = np.stack([lg.tip_moment for lg in legs])
        return platform_balance(geometry, T, F, M, w, g), legs, ""

    r, legs, msg = evaluate(L, legs0, guess_L=legs0_L)
    if r is None:
        return L, None, False, 0, None, msg
    J = None
    last_step = np.inf
    for it in range(1, max_iterations + 1):
        fresh = J is None
        if J is None:
            J = np.empty((6, 6))
            for i in range(6):
                Lp = L.copy()
                Lp[i] += fd_step
                rp, _, msg = evaluate(Lp, legs, only=[i], base_legs=legs, guess_L=L)
                if rp is None:
                    return L, legs, False, it, r, "Jacobian: " + msg
                J[:, i] = (rp - r) / fd_step
        try:
            dL = -np.linalg.solve(J, r)
        except np.linalg.LinAlgError:
            return L, legs, False, it, r, "singular IK Jacobian d(balance)/dL (module at a singular pose)"
        # backtracking: accept the first fraction that lowers the scaled balance residual
        r0 = resnorm(geometry, r)
        for frac in (1.0, 0.5, 0.25, 0.125):
            Ln = L + frac * dL
            if np.any(Ln <= 0):
                continue
            rn, legs_n, msg = evaluate(Ln, legs, guess_L=L)
            if rn is not None and (resnorm(geometry, rn) < r0 or frac * np.max(np.abs(dL)) < length_tolerance):
                break
        else:
            if not fresh:  # the reused (chord) Jacobian is stale: rebuild it before giving up
                J = None
                continue
            return L, legs, False, it, r, msg or "line search failed to reduce the platform balance residual"
        L, r, legs = Ln, rn, legs_n
        step = float(np.max(np.abs(frac * dL)))
        if step < length_tolerance:
            return L, legs, True, it, r, ""
        if frac < 1.0 or step > 0.25 * last_step:
            J = None  # slow contraction or damped step: refresh the Jacobian
        last_step = step
    return L, legs, False, max_iterations, r, f"no convergence in {max_iterations} Newton iterations (last update {step:.3g} m)"
