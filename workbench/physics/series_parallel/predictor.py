"""Geometric predictor: cubic-Hermite legs for a platform pose, and start shapes for Newton.

Each leg is approximated by the cubic Hermite curve from its hole (tangent = base z) to its
attachment (tangent = platform z).  Not an equilibrium: only the starting guess of the inverse
kinematics (lengths for a pose), of the forward kinematics (a pose for lengths, inverted by least
squares) and of each leg solve (node positions and parallel-transported frames).  Checked through
the round-trip tests of ``tests/physics/test_series_parallel.py``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from ._systems import LegShape
from .geometry import ModuleGeometry, check_pose, rot_z, attachment_points, hole_frames, pose_from_xyz_rotvec


_GL_X, GL_W = np.polynomial.legendre.leggauss(24)
GL_U = 0.5 * (_GL_X + 1.0)
GL_W = 0.5 * GL_W


def hermite_curve(p0, t0, p1, t1, u, scale=None):
    """Cubic Hermite curve with end tangents scaled by ``scale`` (default: the chord); points and derivatives."""
    c = np.linalg.norm(p1 - p0) if scale is None else scale
    u = np.asarray(u)[:, None]
    h00 = 2 * u**3 - 3 * u**2 + 1
    h10 = u**3 - 2 * u**2 + u
    h01 = -2 * u**3 + 3 * u**2
    h11 = u**3 - u**2
    P = h00 * p0 + h10 * c * t0 + h01 * p1 + h11 * c * t1
    d00 = 6 * u**2 - 6 * u
    d10 = 3 * u**2 - 4 * u + 1
    d01 = -6 * u**2 + 6 * u
    d11 = 3 * u**2 - 2 * u
    D = d00 * p0 + d10 * c * t0 + d01 * p1 + d11 * c * t1
    return P, D


def leg_lengths_from_pose_hermite(geometry: ModuleGeometry, pose) -> np.ndarray:
    """Geometric predictor: arc lengths of cubic Hermite legs for a platform pose.

    Each leg is approximated by the cubic Hermite curve from its hole (tangent = base z) to its
    attachment (tangent = platform z), tangents scaled by the chord.  Not an equilibrium: used
    only as the starting guess of the inverse kinematics and, inverted, of the forward
    kinematics.

    Parameters
    ----------
    geometry : ModuleGeometry
    pose : array_like, shape (4, 4)
        Platform pose in the module base frame.

    Returns
    -------
    ndarray, shape (6,)
        Predicted insertion lengths [m].
    """
    T = check_pose(pose)
    return hermite_lengths(geometry, T)


def hermite_lengths(geometry, T):
    P0, R0 = hole_frames(geometry)
    A = attachment_points(geometry)
    out = np.empty(6)
    for i in range(6):
        p1 = T[:3, :3] @ A[i] + T[:3, 3]
        _, D = hermite_curve(P0[i], R0[i][:, 2], p1, T[:3, 2], GL_U)
        out[i] = np.sum(GL_W * np.linalg.norm(D, axis=1))
    return out


def pose_from_lengths_hermite(geometry, L, T_guess):
    def res(x):
        T = T_guess @ pose_from_xyz_rotvec(x[:3], x[3:])
        return (hermite_lengths(geometry, T) - L) / geometry.height

    sol = least_squares(res, np.zeros(6), method="lm", xtol=1e-14, ftol=1e-14)
    return T_guess @ pose_from_xyz_rotvec(sol.x[:3], sol.x[3:])


def _tangent_scale_for_length(p0, t0, p1, t1, length):
    """Tangent scale of the Hermite leg whose arc length equals ``length`` (secant iteration).

    Falls back to the chord-scaled curve when no scale reaches the length (leg shorter than
    the chord would require stretching).
    """
    c = float(np.linalg.norm(p1 - p0))

    def arc(a):
        _, D = hermite_curve(p0, t0, p1, t1, GL_U, a)
        return float(np.sum(GL_W * np.linalg.norm(D, axis=1)))

    a0, a1 = c, 1.1 * c
    f0, f1 = arc(a0) - length, arc(a1) - length
    for _ in range(30):
        if abs(f1) < 1e-13 * length or f1 == f0:
            break
        a0, a1, f0 = a1, max(a1 - f1 * (a1 - a0) / (f1 - f0), 1e-3 * c), f1
        f1 = arc(a1) - length
    return a1 if abs(f1) < 1e-9 * length else c


def leg_shape(p0, R0, length, p1, R1, n_elements, free_twist=True) -> LegShape:
    """Node positions (equal arc length along the Hermite curve) and parallel-transported frames."""
    u = np.linspace(0.0, 1.0, 401)
    scale = _tangent_scale_for_length(p0, R0[:, 2], p1, R1[:, 2], length)
    P, D = hermite_curve(p0, R0[:, 2], p1, R1[:, 2], u, scale)
    sp = np.linalg.norm(D, axis=1)
    s = np.concatenate([[0.0], np.cumsum(0.5 * (sp[1:] + sp[:-1]) * np.diff(u))])
    tan = D / sp[:, None]
    frames = np.empty((u.size, 3, 3))
    frames[0] = R0
    for j in range(1, u.size):
        a, b = tan[j - 1], tan[j]
        ax = np.cross(a, b)
        sn, cs = np.linalg.norm(ax), float(np.dot(a, b))
        Rm = np.eye(3) if sn < 1e-15 else Rotation.from_rotvec(ax / sn * math.atan2(sn, cs)).as_matrix()
        frames[j] = Rm @ frames[j - 1]
    # twist mismatch at the tip about the tangent
    rel = frames[-1].T @ R1
    phi = math.atan2(rel[1, 0], rel[0, 0])
    s_nodes = np.linspace(0.0, s[-1], n_elements + 1)
    u_nodes = np.interp(s_nodes, s, u)
    idx = np.clip(np.searchsorted(u, u_nodes), 0, u.size - 1)
    Pn, _ = hermite_curve(p0, R0[:, 2], p1, R1[:, 2], u_nodes, scale)
    Rn = np.empty((n_elements + 1, 3, 3))
    for j in range(n_elements + 1):
        frac = 1.0 if free_twist else s_nodes[j] / s[-1]
        Fj = frames[idx[j]]
        # re-align with the exact tangent at u_nodes[j]
        _, Dj = hermite_curve(p0, R0[:, 2], p1, R1[:, 2], [u_nodes[j]], scale)
        tj = Dj[0] / np.linalg.norm(Dj[0])
        ax = np.cross(Fj[:, 2], tj)
        sn = np.linalg.norm(ax)
        if sn > 1e-15:
            Fj = Rotation.from_rotvec(ax / sn * math.asin(min(sn, 1.0))).as_matrix() @ Fj
        Rn[j] = Fj @ rot_z(frac * phi)
    Rn[-1] = R1 if free_twist else Rn[-1]
    Pn[-1] = p1
    return LegShape(positions=Pn, rotations=Rn)
