"""Backbone shape of a solved chain from its link states (pure numpy).

Positions at reference stations interpolated along the straight links, the tip frame at the end
of the last link, joint angles and the tip twist.  Joint angles: planar ``(N, 1)``, the bending
angle of each joint towards base +x (rotation about base +y); 3-D with sprung torsion ``(N, 3)``,
the relative rotation vector of each joint in the proximal link's frame; 3-D with locked torsion
``(N, 2)``, the Cardan angles ``(a, b)`` of ``R_rel = Rx(a) Ry(b)``.  ``tip_twist`` (3-D): rotation
of the tip frame about the tangent relative to the frame parallel-transported along the links.
Checked by ``tests/physics/test_spring_link.py`` (CC limit, 2-D = 3-D, torsion and Cardan twist).
"""

from __future__ import annotations

import math

import numpy as np

from .geometry import ChainGeometry

__all__ = ["planar_shape", "spatial_shape", "points_on_links", "rotation_vectors", "twist_vs_parallel_transport"]


def planar_shape(geo: ChainGeometry, stations: np.ndarray, P: np.ndarray,
                 beta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Shape of a planar chain from joint positions ``P`` (N, 3) and link angles ``beta`` (N,).

    Returns
    -------
    positions : ndarray, shape (m, 3)
    tip_frame : ndarray, shape (4, 4)
    joint_angles : ndarray, shape (N, 1)
    axes : ndarray, shape (N, 2)
        Link axes in the plane (base x, z), for the axial joint gaps.
    """
    link_axes = np.stack([np.sin(beta), np.zeros_like(beta), np.cos(beta)], axis=1)
    pos = points_on_links(geo, stations, np.asarray(P, dtype=float), link_axes)
    b = beta[-1]
    T = np.eye(4)
    T[:3, 0] = [math.cos(b), 0.0, -math.sin(b)]
    T[:3, 1] = [0.0, 1.0, 0.0]
    T[:3, 2] = [math.sin(b), 0.0, math.cos(b)]
    T[:3, 3] = P[-1] + geo.link_lengths[-1] * T[:3, 2]
    pos[-1] = T[:3, 3]
    joint = np.diff(np.concatenate([[0.0], beta]))[:, None]
    axes = np.stack([np.sin(beta), np.cos(beta)], axis=1)
    return pos, T, joint, axes


def spatial_shape(geo: ChainGeometry, stations: np.ndarray, P: np.ndarray, R: np.ndarray,
                  torsion: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Shape of a 3-D chain from joint positions ``P`` (N, 3) and link rotations ``R`` (N, 3, 3).

    Returns
    -------
    positions : ndarray, shape (m, 3)
    tip_frame : ndarray, shape (4, 4)
    joint_angles : ndarray, shape (N, 2) for ``torsion="locked"`` (Cardan angles), else (N, 3)
    """
    pos = points_on_links(geo, stations, np.asarray(P, dtype=float), R[:, :, 2])
    T = np.eye(4)
    T[:3, :3] = R[-1]
    T[:3, 3] = P[-1] + geo.link_lengths[-1] * R[-1][:, 2]
    pos[-1] = T[:3, 3]
    Rprev = np.concatenate([np.eye(3)[None], R[:-1]])
    Rrel = np.einsum("kji,kjl->kil", Rprev, R)
    if torsion == "locked":
        # Cardan joint: relative rotation Rx(a) Ry(b) -> (a, b)
        b = np.arcsin(np.clip(Rrel[:, 0, 2], -1.0, 1.0))
        a = np.arctan2(-Rrel[:, 1, 2], Rrel[:, 2, 2])
        joint = np.stack([a, b], axis=1)
    else:
        joint = rotation_vectors(Rrel)
    return pos, T, joint


def points_on_links(geo: ChainGeometry, stations: np.ndarray, P: np.ndarray, link_axes: np.ndarray) -> np.ndarray:
    """Backbone points ``(m, 3)`` at reference arc lengths ``stations`` on a chain of straight links.

    ``P[k]`` is the position of joint ``k`` (at reference arc length ``geo.joints[k]``) and
    ``link_axes[k]`` the unit axis of the link after it; before the first joint the backbone is
    the clamped base segment along +z.
    """
    pos = np.zeros((stations.size, 3))
    for i, s in enumerate(stations):
        if s < geo.joints[0]:
            pos[i] = [0.0, 0.0, s]
            continue
        k = int(np.searchsorted(geo.joints, s, side="right") - 1)
        pos[i] = P[k] + (s - geo.joints[k]) * link_axes[k]
    return pos


def rotation_vectors(R: np.ndarray) -> np.ndarray:
    """Rotation vectors (k, 3) of rotation matrices (k, 3, 3) (angles below pi)."""
    c = np.clip((np.trace(R, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    ang = np.arccos(c)
    w = np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = np.sin(ang)
    f = np.where(s > 1e-12, ang / np.where(s > 1e-12, 2.0 * s, 1.0), 0.5)
    return w * f[:, None]


def twist_vs_parallel_transport(R: np.ndarray) -> float:
    """Rotation of the last link frame about its axis relative to the frame parallel-transported
    (minimal rotations between successive link axes) from the base."""
    F = np.eye(3)
    t_prev = np.array([0.0, 0.0, 1.0])
    for Rk in R:
        t = Rk[:, 2]
        v = np.cross(t_prev, t)
        c = float(np.dot(t_prev, t))
        s = float(np.linalg.norm(v))
        if s > 1e-15:
            K = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]]) / s
            Q = np.eye(3) + s * K + (1 - c) * K @ K
            F = Q @ F
        t_prev = t
    x_pt, x = F[:, 0], R[-1][:, 0]
    return float(math.atan2(np.dot(np.cross(x_pt, x), R[-1][:, 2]), np.dot(x_pt, x)))
