"""Constant-curvature arc fitted through the platform poses of a stack (the CC comparison).

Checked by ``test_cc_fit_recovers_an_exact_arc`` and ``test_cc_fit_reports_error_for_a_translated_stack``
(``tests/physics/test_series_parallel.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from .geometry import check_pose


@dataclass(frozen=True)
class ArcFit:
    """Constant-curvature arc fitted through platform poses.

    The arc starts at the stack base origin, tangent to the base z axis (the CC assumption for a
    single section): ``p(s) = ((1 - cos ks)/k cos phi, (1 - cos ks)/k sin phi, sin(ks)/k)``.

    Parameters
    ----------
    curvature : float
        k [1/m] (>= 0).
    phi : float
        Bending-plane angle from base x [rad].
    arc_lengths : ndarray, shape (n,)
        Arc-length parameter of each platform on the fitted arc [m].
    position_errors : ndarray, shape (n,)
        Distance of each platform origin from its arc point [m].
    tangent_errors : ndarray, shape (n,)
        Angle between each platform z axis and the arc tangent at its arc point [rad].
    rms_position_error, max_position_error : float
        [m].
    max_tangent_error : float
        [rad].
    """

    curvature: float
    phi: float
    arc_lengths: np.ndarray
    position_errors: np.ndarray
    tangent_errors: np.ndarray
    rms_position_error: float
    max_position_error: float
    max_tangent_error: float


def arc_points(k, phi, s):
    """Points and unit tangents of the constant-curvature arc of :class:`ArcFit`, stable for k -> 0.

    Parameters
    ----------
    k : float
        Curvature [1/m].
    phi : float
        Bending-plane angle from base x [rad].
    s : ndarray, shape (n,)
        Arc-length parameters [m].

    Returns
    -------
    points, tangents : ndarray, shape (n, 3)
        ``p(s)`` [m] (see :class:`ArcFit`) and ``p'(s)``, base frame.
    """
    x = k * s
    # (1 - cos x)/k = s * (1 - cos x)/x ; sin x / k = s * sin x / x
    small = np.abs(x) < 1e-6
    xs = np.where(small, 1.0, x)
    c1 = np.where(small, x / 2.0 - x**3 / 24.0, (1.0 - np.cos(xs)) / xs)
    c2 = np.where(small, 1.0 - x**2 / 6.0, np.sin(xs) / xs)
    P = np.stack([s * c1 * np.cos(phi), s * c1 * np.sin(phi), s * c2], axis=-1)
    t = np.stack([np.sin(x) * np.cos(phi), np.sin(x) * np.sin(phi), np.cos(x)], axis=-1)
    return P, t


def fit_constant_curvature(platform_poses, base_pose=None) -> ArcFit:
    """Least-squares constant-curvature arc through the platform origins of a stack.

    Unknowns: curvature k, plane angle phi and one arc-length parameter per platform; the
    objective is the sum of squared distances between the platform origins and their arc points
    (positions only; the platform-z vs arc-tangent angle is reported, not fitted).  A stack that
    bends like one CC section (e.g. the paper's Fig 10 "bending") fits closely; translation and
    S-shapes do not, which is the point of the comparison.

    Parameters
    ----------
    platform_poses : array_like, shape (n, 4, 4)
        Platform poses in the stack base frame.
    base_pose : array_like, shape (4, 4), optional
        Frame the arc starts in (default identity); poses are expressed in it first.

    Returns
    -------
    ArcFit
    """
    T = np.asarray(platform_poses, dtype=float)
    if T.ndim != 3 or T.shape[1:] != (4, 4) or T.shape[0] < 1:
        raise ValueError(f"platform_poses must have shape (n, 4, 4) with n >= 1, got {T.shape}")
    B = np.eye(4) if base_pose is None else check_pose(base_pose, "base_pose")
    T = np.einsum("ij,njk->nik", np.linalg.inv(B), T)
    P = T[:, :3, 3]
    Z = T[:, :3, 2]
    tip = P[-1]
    phi0 = math.atan2(tip[1], tip[0]) if np.hypot(tip[0], tip[1]) > 1e-12 else 0.0
    s0 = np.cumsum(np.linalg.norm(np.diff(np.vstack([np.zeros(3), P]), axis=0), axis=1))
    r_xy = np.hypot(tip[0], tip[1])
    d2 = float(tip @ tip)
    k0 = 2.0 * r_xy / d2 if d2 > 0 else 0.0

    def res(x):
        Pa, _ = arc_points(x[0], x[1], x[2:])
        return (Pa - P).ravel()

    best = None
    for kk in (k0, 0.0, 0.5 * k0, 2.0 * k0):
        sol = least_squares(res, np.concatenate([[kk, phi0], s0]), method="lm", xtol=1e-14, ftol=1e-14)
        if best is None or sol.cost < best.cost:
            best = sol
    k, phi, s = best.x[0], best.x[1], best.x[2:]
    if k < 0:  # same arc, opposite plane
        k, phi = -k, phi + math.pi
    phi = math.atan2(math.sin(phi), math.cos(phi))
    Pa, ta = arc_points(k, phi, s)
    e = np.linalg.norm(Pa - P, axis=1)
    ang = np.arccos(np.clip(np.sum(ta * Z, axis=1), -1.0, 1.0))
    return ArcFit(float(k), float(phi), s, e, ang, float(np.sqrt(np.mean(e**2))), float(e.max()), float(ang.max()))

