"""Inextensible planar elastica of a clamped rod: an independent reference (numpy/scipy only).

The rod is clamped at ``s = 0`` at the origin of a 2-D plane with its tangent at angle
``theta0`` (default 0, along the plane's first axis ``a``); the second axis ``b`` completes
a right-handed plane (rotation angle measured from ``a`` towards ``b``).  It carries

* a tip force ``F = (F_a, F_b)`` [N] (fixed direction, any direction),
* a tip moment ``M`` [N m] (positive rotates ``a`` towards ``b``),
* a distributed load ``q = (q_a, q_b)`` [N/m] per unit (undeformed) length, fixed in
  direction (self-weight at any angle to the rod),

and has bending stiffness ``EI(s)`` (constant or a callable, e.g. a tapered rod).

Equations (Kirchhoff rod, inextensible, unshearable; e.g. Antman, *Nonlinear Problems of
Elasticity*, ch. 4)::

    a'(s) = cos(theta),   b'(s) = sin(theta),   theta'(s) = m(s) / EI(s),
    n(s)  = F + q (L - s)                    (force the distal part [s, L] carries)
    m'(s) = -(a' n_b - b' n_a)               (moment balance of the distal part)

with boundary conditions ``a(0) = b(0) = 0``, ``theta(0) = theta0``, ``m(L) = M``.
The boundary-value problem is solved with :func:`scipy.integrate.solve_bvp` and a
continuation in the load factor from the unloaded straight rod (which selects the stable
branch that a quasi-static loading reaches).

Checks (``tests/reference/test_elastica.py``): the tabulated tip deflections of the
project's facts note (tip load ``alpha = P L^2/EI``: 1 -> 0.30172, 3 -> 0.60325,
10 -> 0.81061; self-weight ``gamma = q L^3/EI``: 1 -> 0.123471, 4 -> 0.425159,
8 -> 0.640631, all ``delta_b / L``), the closed-form circular arc under a pure end moment,
and Euler-Bernoulli for small loads.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import solve_bvp

__all__ = ["ElasticaSolution", "clamped_elastica", "tip_load_deflection"]


@dataclass(frozen=True)
class ElasticaSolution:
    """Shape of a clamped planar elastica.

    Parameters
    ----------
    stations : ndarray, shape (m,)
        Arc-length stations [m], ``0..L``.
    positions : ndarray, shape (m, 2)
        Centreline points ``(a, b)`` at the stations [m].
    angles : ndarray, shape (m,)
        Tangent angle ``theta`` [rad] at the stations.
    moments : ndarray, shape (m,)
        Bending moment ``m = EI theta'`` [N m] at the stations.
    max_residual : float
        Largest relative residual reported by ``solve_bvp``.
    """

    stations: np.ndarray
    positions: np.ndarray
    angles: np.ndarray
    moments: np.ndarray
    max_residual: float

    @property
    def tip(self) -> np.ndarray:
        """``(2,)`` tip position [m]."""
        return self.positions[-1]


def _as_pair(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if arr.shape != (2,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be a finite pair (shape (2,)), got {value!r}")
    return arr


def clamped_elastica(
    length: float,
    bending_stiffness: float | Callable[[np.ndarray], np.ndarray],
    *,
    tip_force=(0.0, 0.0),
    tip_moment: float = 0.0,
    distributed_load=(0.0, 0.0),
    theta0: float = 0.0,
    stations: int | np.ndarray = 33,
    n_continuation: int = 8,
    tol: float = 1e-10,
    max_nodes: int = 200_000,
) -> ElasticaSolution:
    """Solve the clamped inextensible planar elastica.

    Parameters
    ----------
    length : float
        Rod length L [m] (> 0).
    bending_stiffness : float or callable
        ``EI`` [N m^2] (> 0), or a function ``EI(s)`` of arc length ``(k,) -> (k,)``.
    tip_force : (2,) array_like
        Tip force ``(F_a, F_b)`` [N], fixed in direction.
    tip_moment : float
        Tip moment [N m], positive rotating ``a`` towards ``b``.
    distributed_load : (2,) array_like
        Load per unit length ``(q_a, q_b)`` [N/m], fixed in direction (self-weight:
        ``mass_per_length * g``).
    theta0 : float
        Clamp angle [rad] of the tangent at ``s = 0``.
    stations : int or (m,) array_like
        Number of equally spaced stations, or the stations themselves [m] in ``[0, L]``.
    n_continuation : int
        Load-factor continuation steps (each solve starts from the previous shape).
    tol : float
        ``solve_bvp`` tolerance.
    max_nodes : int
        ``solve_bvp`` mesh limit.

    Returns
    -------
    ElasticaSolution

    Raises
    ------
    ValueError
        Bad input.
    RuntimeError
        ``solve_bvp`` did not converge.
    """
    L = float(length)
    if not (math.isfinite(L) and L > 0):
        raise ValueError(f"length must be finite and > 0, got {length!r}")
    F = _as_pair("tip_force", tip_force)
    q = _as_pair("distributed_load", distributed_load)
    M = float(tip_moment)
    if not math.isfinite(M):
        raise ValueError(f"tip_moment must be finite, got {tip_moment!r}")
    if callable(bending_stiffness):
        EI = bending_stiffness
    else:
        ei = float(bending_stiffness)
        if not (math.isfinite(ei) and ei > 0):
            raise ValueError(f"bending_stiffness must be finite and > 0, got {bending_stiffness!r}")

        def EI(s, _ei=ei):
            return np.full_like(np.asarray(s, dtype=float), _ei)

    if np.isscalar(stations):
        m = int(stations)
        if m < 2:
            raise ValueError(f"stations must be >= 2, got {stations!r}")
        st = np.linspace(0.0, L, m)
    else:
        st = np.asarray(stations, dtype=float).reshape(-1)
        if st.size < 1 or np.any(st < -1e-12 * L) or np.any(st > L * (1 + 1e-12)):
            raise ValueError(f"stations must lie in [0, {L}], got {stations!r}")
        st = np.clip(st, 0.0, L)
    c0 = math.cos(theta0)
    s0 = math.sin(theta0)

    def make_fun(lam: float):
        Fl, ql, Ml = lam * F, lam * q, lam * M

        def fun(s, y):
            a, b, th, mo = y
            ca, sa = np.cos(th), np.sin(th)
            na = Fl[0] + ql[0] * (L - s)
            nb = Fl[1] + ql[1] * (L - s)
            return np.vstack([ca, sa, mo / EI(s), -(ca * nb - sa * na)])

        def bc(ya, yb):
            return np.array([ya[0], ya[1], ya[2] - theta0, yb[3] - Ml])

        return fun, bc

    mesh = np.linspace(0.0, L, 101)
    y = np.vstack([mesh * c0, mesh * s0, np.full_like(mesh, theta0), np.zeros_like(mesh)])
    sol = None
    n_cont = max(1, int(n_continuation))
    for k in range(1, n_cont + 1):
        fun, bc = make_fun(k / n_cont)
        sol = solve_bvp(fun, bc, mesh, y, tol=tol, max_nodes=max_nodes)
        if sol.status != 0:
            raise RuntimeError(f"elastica BVP did not converge at load factor {k}/{n_cont}: {sol.message}")
        mesh, y = sol.x, sol.y
    Y = sol.sol(st)
    return ElasticaSolution(
        stations=st,
        positions=np.column_stack([Y[0], Y[1]]),
        angles=Y[2].copy(),
        moments=Y[3].copy(),
        max_residual=float(np.max(sol.rms_residuals)),
    )


def tip_load_deflection(alpha: float) -> float:
    """Tip deflection ``delta_b / L`` of a clamped rod under a transverse tip load.

    Parameters
    ----------
    alpha : float
        Load parameter ``P L^2 / EI`` [-] (force perpendicular to the undeformed rod).

    Returns
    -------
    float
        Transverse tip deflection over length [-] (0.30172 for ``alpha = 1``).
    """
    return float(clamped_elastica(1.0, 1.0, tip_force=(0.0, alpha), stations=2).tip[1])
