"""Backbone shape from the link states of a solved chain (pure numpy)."""

from __future__ import annotations

import math

import numpy as np

from .geometry import ChainGeometry

__all__: list[str] = []


def _points_on_links(geo: ChainGeometry, stations: np.ndarray, P: np.ndarray, link_axes: np.ndarray) -> np.ndarray:
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

def _rotation_vectors(R: np.ndarray) -> np.ndarray:
    """Rotation vectors (k, 3) of rotation matrices (k, 3, 3) (angles below pi)."""
    c = np.clip((np.trace(R, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    ang = np.arccos(c)
    w = np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], axis=1)
    s = np.sin(ang)
    f = np.where(s > 1e-12, ang / np.where(s > 1e-12, 2.0 * s, 1.0), 0.5)
    return w * f[:, None]


def _twist_vs_parallel_transport(R: np.ndarray) -> float:
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
