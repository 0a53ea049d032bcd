"""Tendon-actuation helpers shared by the Exudyn models (pure numpy; no Exudyn import).

* :func:`tendon_rest_lengths` -- rest length of each tendon from its reference path
  length, the length command and the pretension.
* :func:`tension_from_stretch` -- unilateral (slack-capable) linear rope law.
* :func:`tendon_path_compliance` -- linear (small-deflection) compliance ``dl/dT`` of
  continuum tendons on a rod, the quasi-Newton matrix of the length-controlled solve.
* :func:`solve_length_controlled` -- solve ``T = EA_t max(0, (l(T) - l0) / l0)`` for the
  tensions around any tension-controlled equilibrium solver (semismooth quasi-Newton with
  Broyden updates).

Length convention (``docs/architecture.md``): ``TendonActuation.values[i]`` is the change of
the free length of tendon ``i`` relative to its straight reference configuration
(negative = reeled in).  Pretension ``p`` shortens the rest length so that an
inextensible straight rod would carry exactly ``p``: ``l0 = l_ref / (1 + p / EA_t)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = [
    "tendon_rest_lengths",
    "tension_from_stretch",
    "tendon_path_compliance",
    "LengthSolveInfo",
    "solve_length_controlled",
]


def tendon_rest_lengths(reference_lengths, commands, pretension, axial_stiffness) -> np.ndarray:
    """Rest (unstretched) tendon lengths for length-controlled actuation.

    ``l0 = l_ref / (1 + p / EA_t) + delta_l``: the pretension ``p`` stretches the tendon by
    ``p / EA_t`` of its rest length in the straight reference configuration; the command
    ``delta_l`` changes the free length (negative = reeled in).

    Parameters
    ----------
    reference_lengths : (..., n) array_like
        Tendon path lengths in the straight reference configuration [m].
    commands : (..., n) array_like
        Free-length changes ``delta_l`` [m].
    pretension : float or (..., n) array_like
        Tension in the straight reference configuration [N] (>= 0).
    axial_stiffness : float or (..., n) array_like
        Tendon axial stiffness ``EA_t`` [N] (> 0).

    Returns
    -------
    ndarray, shape (..., n)
        Rest lengths [m].

    Raises
    ------
    ValueError
        A rest length is not positive (command reels in more than the whole tendon).
    """
    lref = np.asarray(reference_lengths, dtype=float)
    dl = np.asarray(commands, dtype=float)
    p = np.asarray(pretension, dtype=float)
    ea = np.asarray(axial_stiffness, dtype=float)
    if np.any(ea <= 0) or np.any(p < 0):
        raise ValueError("axial_stiffness must be > 0 and pretension >= 0")
    l0 = lref / (1.0 + p / ea) + dl
    if np.any(~np.isfinite(l0)) or np.any(l0 <= 0):
        raise ValueError(f"tendon rest lengths must be finite and > 0, got {np.asarray(l0).tolist()}")
    return l0


def tension_from_stretch(path_lengths, rest_lengths, axial_stiffness) -> np.ndarray:
    """Unilateral linear rope law ``T = EA_t max(0, (l - l0) / l0)``.

    Parameters
    ----------
    path_lengths, rest_lengths : (..., n) array_like
        Current path length and rest length [m].
    axial_stiffness : float or (..., n) array_like
        ``EA_t`` [N].

    Returns
    -------
    ndarray, shape (..., n)
        Tensions [N]; 0 for a slack tendon (a rope cannot push).
    """
    l = np.asarray(path_lengths, dtype=float)
    l0 = np.asarray(rest_lengths, dtype=float)
    return np.asarray(axial_stiffness, dtype=float) * np.maximum(0.0, (l - l0) / l0)


def tendon_path_compliance(s, bending_stiffness, axial_stiffness, lateral_offsets, path_ends) -> np.ndarray:
    """Small-deflection compliance ``C[i, j] = d l_i / d T_j`` of planar continuum tendons.

    For a straight rod loaded only by continuum tendons (moment ``T_j y_j`` and compression
    ``T_j`` over ``[0, e_j]``), ``kappa = sum_j T_j y_j / EI`` and ``eps = -sum_j T_j / EA``,
    and a tendon at lateral offset ``y_i`` has ``dl_i = int_0^{e_i} (eps - y_i kappa) ds``,
    so ``C[i, j] = -int_0^{min(e_i, e_j)} (y_i y_j / EI + 1 / EA) ds`` (exact to first order;
    the exact Jacobian when there are no other loads and offsets are constant).

    Parameters
    ----------
    s : (k,) array_like
        Quadrature grid of arc length [m], increasing from 0.
    bending_stiffness, axial_stiffness : (k,) array_like
        ``EI(s)`` [N m^2] and ``EA(s)`` [N] on the grid.
    lateral_offsets : (n, k) array_like
        Signed lateral offset ``y_i(s)`` of each tendon on the grid [m] (values beyond
        the tendon's end are not used).
    path_ends : (n,) array_like
        Arc length where each tendon terminates [m].

    Returns
    -------
    ndarray, shape (n, n)
        Compliance [m/N] (symmetric, negative semidefinite).
    """
    s = np.asarray(s, dtype=float)
    EI = np.asarray(bending_stiffness, dtype=float)
    EA = np.asarray(axial_stiffness, dtype=float)
    y = np.atleast_2d(np.asarray(lateral_offsets, dtype=float))
    e = np.asarray(path_ends, dtype=float).reshape(-1)
    if y.shape != (e.size, s.size):
        raise ValueError(f"lateral_offsets must have shape ({e.size}, {s.size}), got {y.shape}")
    n = e.size
    C = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            f = y[i] * y[j] / EI + 1.0 / EA
            F = np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(s))])
            C[i, j] = -np.interp(min(e[i], e[j]), s, F)
    return C


@dataclass(frozen=True)
class LengthSolveInfo:
    """Outcome of :func:`solve_length_controlled`."""

    tensions: np.ndarray
    path_lengths: np.ndarray
    iterations: int
    equilibrium_solves: int
    residual: float


def solve_length_controlled(
    equilibrium: Callable[[np.ndarray], np.ndarray],
    rest_lengths,
    axial_stiffness,
    compliance,
    *,
    initial_tensions=None,
    tol: float = 1e-9,
    length_tol: float = 1e-10,
    max_iterations: int = 50,
) -> LengthSolveInfo:
    """Tensions of length-controlled, slack-capable tendons around a tension-controlled solver.

    Solves ``r(T) = T - EA_t max(0, (l(T) - l0) / l0) = 0`` where ``l(T)`` are the tendon
    path lengths at the equilibrium for prescribed tensions ``T``
    (``equilibrium(T) -> l``).  Semismooth quasi-Newton: the Jacobian
    ``I - diag(a EA_t / l0) C`` (``a`` = 1 for taut, 0 for slack tendons) is rebuilt every
    iteration from the compliance ``C ~ dl/dT``, which starts from the supplied estimate
    and is improved by Broyden rank-one updates (the compliance is smooth, so the secant
    information survives changes of the slack/taut set -- updating the residual Jacobian
    instead cycles between slack and taut for stiff tendons); tensions are projected onto
    ``T >= 0``; steps are backtracked (halved, at most 8 times) until the residual in length
    units ``|r l0 / EA_t|`` decreases.  A step that does not halve that residual rebuilds the
    compliance by forward differences (:func:`_fd_compliance`, ``n`` more equilibria): stiff
    antagonistic tendons that are both taut otherwise creep for hundreds of solves (Hannan &
    Walker's trunk at ``EA_t = 1.6e6 N``: 50 iterations, 226 equilibria, not converged).  With
    no external loads and the exact compliance (:func:`tendon_path_compliance`, continuum
    tendon) the first step is exact.

    Parameters
    ----------
    equilibrium : callable
        ``(n,) tensions [N] -> (n,) path lengths [m]``; raises on a failed solve (a trial step
        whose solve fails is halved like one that does not decrease the residual; the error
        propagates when the eighth halving fails too).
    rest_lengths : (n,) array_like
        ``l0`` [m].
    axial_stiffness : (n,) array_like
        ``EA_t`` [N].
    compliance : (n, n) array_like
        Initial ``dl/dT`` estimate [m/N].
    initial_tensions : (n,) array_like, optional
        Start value (default 0).
    tol : float
        Convergence: ``|r_i| <= tol * (1 + T_i)`` [N] for all tendons, or
    length_tol : float
        ... every taut tendon's length mismatch ``|l - l0 (1 + T/EA_t)| <= length_tol * l0``
        and every slack tendon's ``l <= l0``.
    max_iterations : int
        Cap on iterations.

    Returns
    -------
    LengthSolveInfo

    Raises
    ------
    RuntimeError
        No convergence within ``max_iterations``.
    """
    l0 = np.asarray(rest_lengths, dtype=float).reshape(-1)
    ea = np.broadcast_to(np.asarray(axial_stiffness, dtype=float), l0.shape)
    C = np.asarray(compliance, dtype=float)
    n = l0.size
    T = np.zeros(n) if initial_tensions is None else np.maximum(0.0, np.asarray(initial_tensions, dtype=float))
    l = equilibrium(T)
    solves = 1
    C = C.copy()
    for it in range(1, max_iterations + 1):
        stretch = (l - l0) / l0
        r = T - ea * np.maximum(0.0, stretch)
        # length mismatch of taut tendons [m]; stiff tendons cannot meet a force tolerance
        # better than EA_t times the path-length accuracy, so either criterion suffices
        gap = np.where(T > 0, l - l0 * (1.0 + T / ea), 0.0)
        force_ok = np.abs(r) <= tol * (1.0 + np.abs(T))
        # per tendon: the force residual, or (taut) the length mismatch, or (slack) a tension
        # at round-off level -- the projection max(0, T + a dT) can leave 1e-28 N on a slack
        # tendon, which must not count as taut
        taut_ok = (T > 0) & (stretch > 0) & (np.abs(gap) <= length_tol * l0)
        slack_ok = (stretch <= 0) & (T <= tol)
        if np.all(force_ok) or np.all(force_ok | taut_ok | slack_ok):
            return LengthSolveInfo(T, l, it - 1, solves, float(np.max(np.abs(r), initial=0.0)))
        active = (stretch > 0).astype(float)
        J = np.eye(n) - (active * ea / l0)[:, None] * C
        dT = np.linalg.solve(J, -r)
        merit = np.linalg.norm(r * l0 / ea)  # residual in length units [m]
        alpha = 1.0
        failure: Exception | None = None
        for _ in range(8):  # backtracking on the merit (stiff antagonistic tendons overshoot)
            T_new = np.maximum(0.0, T + alpha * dT)
            try:
                l_new = equilibrium(T_new)
            except Exception as err:  # noqa: BLE001 - no equilibrium for so large a step: a shorter one
                failure, alpha = err, 0.5 * alpha
                solves += 1
                continue
            failure = None
            solves += 1
            s = T_new - T
            if np.dot(s, s) > 0:
                # Broyden update of the compliance dl/dT (smooth, unlike the residual's kink at slack)
                C = C + np.outer((l_new - l) - C @ s, s) / np.dot(s, s)
            r_new = T_new - ea * np.maximum(0.0, (l_new - l0) / l0)
            if np.linalg.norm(r_new * l0 / ea) < (1.0 - 1e-4 * alpha) * merit:
                break
            alpha *= 0.5
        if failure is not None:  # even the shortest step had no equilibrium
            raise failure
        if np.linalg.norm(r_new * l0 / ea) > 0.5 * merit:
            # poor contraction (stiff co-contracting tendons: the secant compliance misses the stiff
            # mode and the iteration creeps): the compliance anew by forward differences at T_new
            C = _fd_compliance(equilibrium, T_new, l_new)
            solves += n + 1
            l_new = equilibrium(T_new)  # the system back in the state the loop continues from
        T, l = T_new, l_new
    raise RuntimeError(
        f"length-controlled tendon solve did not converge in {max_iterations} iterations "
        f"(tensions {T.tolist()} N)"
    )


def _fd_compliance(equilibrium: Callable[[np.ndarray], np.ndarray], T: np.ndarray, l: np.ndarray) -> np.ndarray:
    """``dl/dT`` [m/N] at tensions ``T`` (path lengths ``l``) by forward differences, one equilibrium per tendon.

    The step is ``1e-4 (1 + T_i)`` N (``T + h >= 0`` always; the lengths are smooth in the
    prescribed tensions)."""
    C = np.empty((l.size, T.size))
    for i in range(T.size):
        h = 1e-4 * (1.0 + T[i])
        Th = T.copy()
        Th[i] += h
        C[:, i] = (equilibrium(Th) - l) / h
    return C
