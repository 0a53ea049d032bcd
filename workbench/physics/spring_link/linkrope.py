"""Continuum tendons of the 3-D kinematic tree as ropes through every link eyelet (pure numpy).

A frictionless tendon with tension ``T`` through eyelets ``p_0`` (base plate) ... ``p_m`` (its
terminating link eyelet) pulls eyelet ``i`` with ``T (u_i - u_{i-1})`` (``u_i`` the unit vector
from ``p_i`` to ``p_{i+1}``) and the last one with ``-T u_{m-1}``: exactly the constant-force rope
segments of :func:`.routing.add_eyelet_rope`, evaluated from the current geometry.  On the tree a
revolute joint with axis ``a`` at ``o`` receives the generalised force ``a . sum (p - o) x F`` of
the forces distal to it, accumulated from the tip in ``O(N)``; length mode uses the reeving law
``T = EA_t (L - L_0) / L_0`` (0 when slack) with the polygon length ``L``.  The tendon routed
continuously is the limit as the links grow (chord lever arm ``O(ds^2)``).  Faster than rope
connectors on tree markers, whose every segment evaluates the tree's kinematics.  Checked by
``tests/physics/test_spring_link_crossexam.py`` (equals the rope connectors; converges to the
Cosserat rod under tendon + tip force and gravity).
"""

from __future__ import annotations

import math

import numpy as np

from .geometry import ChainGeometry
from .routing import TendonRoute

__all__ = ["axis_rotation", "eyelet_points", "generalised_forces", "rope_forces", "tree_kinematics"]

_UNIT = {"X": np.array([1.0, 0.0, 0.0]), "Y": np.array([0.0, 1.0, 0.0]), "Z": np.array([0.0, 0.0, 1.0])}


def axis_rotation(axis: str, angle: float) -> np.ndarray:
    """``(3, 3)`` rotation by ``angle`` [rad] about the body axis ``"X"``, ``"Y"`` or ``"Z"`` (a tree joint's)."""
    c, s = math.cos(angle), math.sin(angle)
    if axis == "X":
        return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    if axis == "Y":
        return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def tree_kinematics(q: np.ndarray, geo: ChainGeometry, axes: list[tuple[str, ...]]) -> tuple[np.ndarray, ...]:
    """Joint positions ``(N, 3)``, link rotations ``(N, 3, 3)`` and every tree joint's world axis
    ``(n, 3)`` for tree coordinates ``q`` (``axes[k]``: the revolute axes of chain joint ``k``)."""
    N = geo.n_links
    P, R, A = np.zeros((N, 3)), np.zeros((N, 3, 3)), []
    Rk, pk, i = np.eye(3), np.array([0.0, 0.0, geo.joints[0]]), 0
    for k in range(N):
        if k > 0:
            pk = pk + geo.link_lengths[k - 1] * Rk[:, 2]
        for ax in axes[k]:
            A.append(Rk @ _UNIT[ax])
            Rk = Rk @ axis_rotation(ax, float(q[i]))
            i += 1
        P[k], R[k] = pk, Rk
    return P, R, np.asarray(A)


def eyelet_points(t: TendonRoute, P: np.ndarray, R: np.ndarray) -> np.ndarray:
    """World positions ``(m + 1, 3)`` of tendon ``t``'s link eyelets (eyelet 0 on the base plate)."""
    u = np.array([math.cos(t.sigma), math.sin(t.sigma), 0.0])
    loc = t.eye_d[:, None] * u[None, :] + np.outer(t.eye_z, [0.0, 0.0, 1.0])
    pts = loc.copy()
    on = t.eye_link >= 0
    k = t.eye_link[on]
    pts[on] = P[k] + np.einsum("nij,nj->ni", R[k], loc[on])
    return pts


def rope_forces(pts: np.ndarray, tension: float) -> np.ndarray:
    """Forces ``(m + 1, 3)`` of a rope with ``tension`` on its eyelets ``pts`` (row 0: the base)."""
    seg = np.diff(pts, axis=0)
    u = seg / np.linalg.norm(seg, axis=1)[:, None]
    F = np.zeros_like(pts)
    F[:-1] += tension * u
    F[1:] -= tension * u
    return F


def generalised_forces(geo: ChainGeometry, axes: list[tuple[str, ...]], q: np.ndarray,
                       tendons: list[TendonRoute], tension_of) -> np.ndarray:  # noqa: ANN001
    """Tree generalised forces ``(n,)`` of the ropes: ``tension_of(i, length)`` gives rope ``i``'s
    tension from its current polygon length."""
    P, R, A = tree_kinematics(q, geo, axes)
    N = geo.n_links
    Fl, Ml = np.zeros((N, 3)), np.zeros((N, 3))   # force and moment about the origin per link
    for i, t in enumerate(tendons):
        pts = eyelet_points(t, P, R)
        T = float(tension_of(i, float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1)))))
        if T == 0.0:
            continue
        F = rope_forces(pts, T)
        on = t.eye_link >= 0
        np.add.at(Fl, t.eye_link[on], F[on])
        np.add.at(Ml, t.eye_link[on], np.cross(pts[on], F[on]))
    Fd = np.cumsum(Fl[::-1], axis=0)[::-1]        # force distal to (and on) link k
    Md = np.cumsum(Ml[::-1], axis=0)[::-1]
    Q = np.zeros(len(A))
    i = 0
    for k in range(N):
        M = Md[k] - np.cross(P[k], Fd[k])
        for _ in axes[k]:
            Q[i] = A[i] @ M
            i += 1
    return Q
