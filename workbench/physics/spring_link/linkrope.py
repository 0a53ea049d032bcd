"""Tendons of the 3-D kinematic tree as ropes through their eyelets, and its tip loads (pure numpy, vectorised).

A frictionless tendon with tension ``T`` through eyelets ``p_0`` (base plate) ... ``p_m`` (its
terminating eyelet) pulls eyelet ``i`` with ``T (u_i - u_{i-1})`` (``u_i`` the unit vector from
``p_i`` to ``p_{i+1}``) and the last one with ``-T u_{m-1}``: exactly the constant-force rope
segments of :func:`.routing.add_eyelet_rope`, evaluated from the current geometry.  On the tree a
revolute joint with axis ``a`` at ``o`` receives the generalised force ``a . sum (p - o) x F`` of
the forces distal to it, accumulated from the tip; length mode uses the reeving law
``T = EA_t (L - L_0) / L_0`` (0 when slack) with the polygon length ``L``.  The same code serves
continuum tendons (an eyelet at every link eyelet; the continuous routing is the limit as the links
grow, chord lever arm ``O(ds^2)``) and eyelet tendons (the disk eyelets of
:func:`.routing.route_tendons`).  The tip force (at the tip point) and tip torque enter the same sums, so
their Jacobian comes with the ropes' (Exudyn's numerical Jacobian of loads on tree markers was the
larger cost).

The tree (:mod:`.tree`) applies them as an ``ObjectGenericODE2`` on its node: :func:`generalised_forces`
is its force user function and :func:`generalised_force_jacobian` its Jacobian user function (Exudyn
would otherwise difference a user function one coordinate per call).  One call is one pass of
whole-array operations over all joints and eyelets (:class:`RopeLayout` holds the constant index arrays;
the joint rotations are chained by a log-depth prefix product), and the Jacobian evaluates all its
perturbed geometries in one batch.  Much faster than rope connectors on tree markers, whose every
segment Jacobian evaluates the tree's kinematics (measured in ``docs/models.md``, "Spring-link").
Checked by ``tests/physics/test_spring_link_linkrope.py`` (equals a plain loop implementation and
the rope connectors) and ``tests/physics/test_spring_link_crossexam.py`` (converges to the Cosserat
rod under tendon + tip force and gravity).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .geometry import ChainGeometry
from .routing import TendonRoute

__all__ = ["RopeLayout", "axis_rotation", "generalised_force_jacobian", "generalised_forces", "rope_layout",
           "tree_kinematics"]

_UNIT = {"X": np.array([1.0, 0.0, 0.0]), "Y": np.array([0.0, 1.0, 0.0]), "Z": np.array([0.0, 0.0, 1.0])}


def axis_rotation(axis: str, angle: float) -> np.ndarray:
    """``(3, 3)`` rotation by ``angle`` [rad] about the body axis ``"X"``, ``"Y"`` or ``"Z"`` (a tree joint's)."""
    c, s = math.cos(angle), math.sin(angle)
    if axis == "X":
        return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    if axis == "Y":
        return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class RopeLayout:
    """Constant index arrays of the tree joints and of every tendon's eyelets (:func:`rope_layout`).

    Attributes
    ----------
    unit : ndarray (n, 3)
        Each tree joint's axis in its own frame.
    cross : ndarray (n, 3, 3)
        ``[unit]_x`` (cross-product matrices, for Rodrigues' formula).
    outer : ndarray (n, 3, 3)
        ``[unit]_x^2``.
    joint_link : ndarray (n,) int
        Chain link (joint) ``k`` of each tree joint.
    last : ndarray (N,) int
        Index of the last tree joint of each chain joint (its rotation is the link's).
    first_joint : float
        Axial position of the first joint [m].
    lengths : ndarray (N,)
        Link lengths [m].
    loc : ndarray (M, 3)
        Every eyelet of every tendon in its link frame (base plate: in the base frame), tendon by tendon,
        and last the tip point (where the tip force acts).
    eye_link : ndarray (M,) int
        Link of each eyelet (-1: the base plate).
    seg_sum : ndarray (M - 1, n_tendons)
        1 where a segment between consecutive eyelets belongs to a tendon (0 across two tendons).
    distal : ndarray (N, M)
        1 where eyelet ``e`` sits on link ``k`` or beyond (sums the forces distal to joint ``k``).
    eye_moves, point_moves, axis_moves : ndarray (n, M), (n, N), (n, n) bool
        Whether tree joint ``j`` moves each eyelet, each joint point and each joint axis.
    """

    unit: np.ndarray
    cross: np.ndarray
    outer: np.ndarray
    joint_link: np.ndarray
    last: np.ndarray
    first_joint: float
    lengths: np.ndarray
    loc: np.ndarray
    eye_link: np.ndarray
    seg_sum: np.ndarray
    distal: np.ndarray
    eye_moves: np.ndarray
    point_moves: np.ndarray
    axis_moves: np.ndarray


def _skew(v: np.ndarray) -> np.ndarray:
    """Cross-product matrices ``(n, 3, 3)`` of the vectors ``v`` ``(n, 3)``."""
    S = np.zeros((len(v), 3, 3))
    S[:, 0, 1], S[:, 0, 2], S[:, 1, 2] = -v[:, 2], v[:, 1], -v[:, 0]
    return S - S.transpose(0, 2, 1)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross products along the last axis of ``(..., 3)`` arrays (``np.cross`` without its axis handling)."""
    return a[..., [1, 2, 0]] * b[..., [2, 0, 1]] - a[..., [2, 0, 1]] * b[..., [1, 2, 0]]


def rope_layout(geo: ChainGeometry, axes: list[tuple[str, ...]], tendons: list[TendonRoute]) -> RopeLayout:
    """The :class:`RopeLayout` of the tree with revolute ``axes[k]`` at chain joint ``k`` and ``tendons``."""
    unit = np.array([_UNIT[a] for ax in axes for a in ax])
    joint_link = np.array([k for k, ax in enumerate(axes) for _ in ax], dtype=int)
    last = np.cumsum([len(ax) for ax in axes]) - 1
    S = _skew(unit)
    locs, links, segs = [], [], []
    for i, t in enumerate(tendons):
        u = np.array([math.cos(t.sigma), math.sin(t.sigma), 0.0])
        locs.append(t.eye_d[:, None] * u[None, :] + np.outer(t.eye_z, [0.0, 0.0, 1.0]))
        links.append(np.asarray(t.eye_link, dtype=int))
        segs.append(np.full(len(t.eye_link), i))
    N, n = len(axes), len(unit)
    locs.append(np.array([[0.0, 0.0, float(geo.link_lengths[-1])]]))  # the tip point, last row
    links.append(np.array([N - 1]))
    segs.append(np.array([-1]))
    tid = np.concatenate(segs)
    eye_link = np.concatenate(links)
    seg_sum = ((tid[1:] == tid[:-1])[:, None] & (tid[:-1, None] == np.arange(len(tendons))[None, :])).astype(float)
    return RopeLayout(unit, S, S @ S, joint_link, last, float(geo.joints[0]),
                      np.asarray(geo.link_lengths, dtype=float), np.concatenate(locs), eye_link, seg_sum,
                      (eye_link[None, :] >= np.arange(N)[:, None]).astype(float),
                      eye_link[None, :] >= joint_link[:, None], np.arange(N)[None, :] > joint_link[:, None],
                      np.arange(n)[None, :] > np.arange(n)[:, None])


def _prefix_products(M: np.ndarray) -> np.ndarray:
    """``C[i] = M[0] @ M[1] @ ... @ M[i]`` for ``M`` ``(n, 3, 3)``, in ``ceil(log2 n)`` batched products."""
    C = M.copy()
    d = 1
    while d < len(C):
        C[d:] = C[:-d] @ C[d:]
        d *= 2
    return C


def tree_kinematics(q: np.ndarray, lay: RopeLayout) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Joint positions ``(N, 3)``, link rotations ``(N, 3, 3)`` and every tree joint's world axis
    ``(n, 3)`` for tree coordinates ``q`` (Rodrigues' rotation about each joint's axis, chained)."""
    q = np.asarray(q, dtype=float)
    Rj = np.eye(3) + np.sin(q)[:, None, None] * lay.cross + (1.0 - np.cos(q))[:, None, None] * lay.outer
    C = _prefix_products(Rj)
    before = np.concatenate([np.eye(3)[None], C[:-1]])       # the rotation up to (not incl.) each joint
    A = np.einsum("nij,nj->ni", before, lay.unit)
    R = C[lay.last]
    P = np.zeros((len(lay.last), 3))
    P[:, 2] = lay.first_joint
    P[1:] += np.cumsum(lay.lengths[:-1, None] * R[:-1, :, 2], axis=0)
    return P, R, A


def _eyelet_positions(lay: RopeLayout, P: np.ndarray, R: np.ndarray) -> np.ndarray:
    """World positions ``(M, 3)`` of every eyelet (base-plate eyelets stay at their base position)."""
    on = lay.eye_link >= 0
    k = lay.eye_link[on]
    pts = lay.loc.copy()
    pts[on] = P[k] + np.einsum("nij,nj->ni", R[k], lay.loc[on])
    return pts


def _forces(lay: RopeLayout, pts: np.ndarray, P: np.ndarray, A: np.ndarray, tensions, tip: tuple) -> np.ndarray:  # noqa: ANN001
    """Generalised forces ``(..., n)`` from eyelet positions ``(..., M, 3)``, joint positions
    ``(..., N, 3)`` and joint axes ``(..., n, 3)`` (any leading batch axes); ``tip``: the tip force and
    torque (base frame)."""
    seg = pts[..., 1:, :] - pts[..., :-1, :]
    length = np.sqrt(np.sum(seg * seg, axis=-1))
    T = tensions(length @ lay.seg_sum)                      # (..., n_tendons) from the polygon lengths
    Fs = ((T @ lay.seg_sum.T) / np.where(length > 0.0, length, 1.0))[..., None] * seg  # T u (0 across tendons)
    F = np.zeros_like(pts)
    F[..., :-1, :] += Fs
    F[..., 1:, :] -= Fs
    F[..., -1, :] += tip[0]
    Fd = lay.distal @ F                                      # force distal to (and on) link k
    Md = lay.distal @ _cross(pts, F) - _cross(P, Fd) + tip[1]  # its moment about joint k
    return np.sum(A * Md[..., lay.joint_link, :], axis=-1)


_NO_TIP = (np.zeros(3), np.zeros(3))


def generalised_forces(lay: RopeLayout, q: np.ndarray, tensions, tip: tuple = _NO_TIP) -> np.ndarray:  # noqa: ANN001
    """Tree generalised forces ``(n,)`` of the ropes and the tip loads at tree coordinates ``q``:
    ``tensions(L)`` gives the ropes' tensions ``(..., n_tendons)`` from their polygon lengths
    ``(..., n_tendons)``; ``tip`` is the tip force and torque ``(3,), (3,)`` in the base frame."""
    P, R, A = tree_kinematics(q, lay)
    return _forces(lay, _eyelet_positions(lay, P, R), P, A, tensions, tip)


def _rodrigues(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotations ``(n, 3, 3)`` by ``angle`` about the unit ``axis`` rows ``(n, 3)``."""
    S = _skew(axis)
    return np.eye(3) + math.sin(angle) * S + (1.0 - math.cos(angle)) * (S @ S)


def generalised_force_jacobian(lay: RopeLayout, q: np.ndarray, tensions, tip: tuple = _NO_TIP,  # noqa: ANN001
                               h: float = 1e-6) -> np.ndarray:
    """``dQ/dq`` ``(n, n)`` of :func:`generalised_forces` by central differences, all columns at once.

    Turning tree joint ``j`` by ``+-h`` rotates everything distal to it rigidly about its world
    axis ``a_j`` through its joint point ``o_j``: the eyelets on links ``>= k(j)``, the joint points
    of links ``> k(j)`` and the axes of joints ``> j``.  So the ``2 n`` perturbed geometries are exact
    rigid rotations of the current one (no re-chaining), evaluated in one batched :func:`_forces`;
    the truncation error is ``O(h^2)`` (~1e-12 relative at ``h = 1e-6``).
    """
    P, R, A = tree_kinematics(q, lay)
    pts = _eyelet_positions(lay, P, R)
    o = P[lay.joint_link]                                    # (n, 3) the point of each tree joint
    n = len(o)
    cols = []
    for sign in (1.0, -1.0):
        Rh = _rodrigues(A, sign * h)                         # (n, 3, 3)

        def turn(X: np.ndarray, moves: np.ndarray, about: np.ndarray | None) -> np.ndarray:
            """``X`` (m, 3) seen from each perturbation ``(n, m, 3)``; ``moves`` (n, m) masks the distal rows."""
            if about is None:
                Y = np.einsum("jab,mb->jma", Rh, X)
            else:
                Y = about[:, None, :] + np.einsum("jab,jmb->jma", Rh, X[None, :, :] - about[:, None, :])
            return np.where(moves[..., None], Y, X[None, :, :])

        cols.append(_forces(lay, turn(pts, lay.eye_moves, o), turn(P, lay.point_moves, o),
                            turn(A, lay.axis_moves, None), tensions, tip))
    return ((cols[0] - cols[1]) / (2.0 * h)).T.reshape(n, n)
