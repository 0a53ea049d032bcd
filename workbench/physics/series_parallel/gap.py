"""Leg interference: the smallest surface gap between the six legs of a module.

Checked by ``test_segment_distance_is_exact`` and ``test_min_leg_gap``
(``tests/physics/test_series_parallel.py``).
"""

from __future__ import annotations

import math

import numpy as np


def segment_distances(P0, P1, Q0, Q1) -> np.ndarray:
    """Minimum distances between segments ``P0-P1`` and ``Q0-Q1``, broadcast over leading axes.

    Closest points of two segments: minimise ``|P(s) - Q(t)|`` over ``s, t in [0, 1]``.  The
    unconstrained optimum ``s`` is clamped, then ``t``, ``s`` and ``t`` are each re-optimised for
    the other one and clamped.  The first steps are the exact closest-point construction for
    segments (Ericson, Real-Time Collision Detection, 2005, sec 5.1.9), and each further step can
    only lower the distance, so the result is the minimum (parallel segments: ``s = 0`` first).
    """
    d1, d2, r = P1 - P0, Q1 - Q0, P0 - Q0
    a = np.einsum("...i,...i", d1, d1)
    e = np.einsum("...i,...i", d2, d2)
    b = np.einsum("...i,...i", d1, d2)
    c = np.einsum("...i,...i", d1, r)
    f = np.einsum("...i,...i", d2, r)
    den = a * e - b * b
    tiny = 1e-300
    s = np.where(den > 1e-14 * a * e, (b * f - c * e) / np.maximum(den, tiny), 0.0)
    s = np.clip(s, 0.0, 1.0)
    t = np.clip((b * s + f) / np.maximum(e, tiny), 0.0, 1.0)
    s = np.clip((b * t - c) / np.maximum(a, tiny), 0.0, 1.0)
    t = np.clip((b * s + f) / np.maximum(e, tiny), 0.0, 1.0)
    diff = r + s[..., None] * d1 - t[..., None] * d2
    return np.linalg.norm(diff, axis=-1)


def min_leg_gap(leg_positions, rod_diameter: float) -> tuple[float, tuple[int, int]]:
    """Smallest surface-to-surface gap between the legs of one module [m] (the paper's "no interference").

    Parameters
    ----------
    leg_positions : array_like, shape (6, N+1, 3)
        Leg node positions of one module [m] (e.g. ``ModulePose.leg_positions``).
    rod_diameter : float
        d [m].

    Returns
    -------
    gap : float
        ``min_{i<j} dist(centreline_i, centreline_j) - d`` with the centrelines taken as the polylines
        through the element nodes (chord error of a node interval of length ``l_e`` at curvature
        ``kappa``: at most ``kappa l_e^2 / 8``); negative means the rods intersect.
    pair : (int, int)
        The two legs (0-based) where it occurs.
    """
    X = np.asarray(leg_positions, dtype=float)
    if X.ndim != 3 or X.shape[0] != 6 or X.shape[1] < 2 or X.shape[2] != 3:
        raise ValueError(f"leg_positions must have shape (6, N+1, 3), got {X.shape}")
    if not np.all(np.isfinite(X)):
        raise ValueError("leg_positions must be finite")
    A0, A1 = X[:, :-1], X[:, 1:]  # (6, N, 3) segments
    best, pair = math.inf, (0, 1)
    for i in range(6):
        for j in range(i + 1, 6):
            dmin = float(np.min(segment_distances(A0[i][:, None], A1[i][:, None], A0[j][None], A1[j][None])))
            if dmin < best:
                best, pair = dmin, (i, j)
    return best - float(rod_diameter), pair
