"""Centreline geometry of a chain of planar ANCF cable elements (pure numpy, vectorised).

``ObjectANCFCable2D`` interpolates the position with cubic Hermite polynomials in the
element's reference coordinate ``x in [0, le]``; each node carries ``(r_x, r_y, r'_x, r'_y)``
with the slope ``r' = dr/dx`` (Gerstmayr & Irschik 2008; Exudyn theory manual,
ObjectANCFCable2D).  Coordinates here are the *absolute* node coordinates, shape
``(..., n_nodes, 4)``.

A rigid marker at ``(x, y)`` on an element (``MarkerBodyRigid`` with ``localPosition
= [x, y, 0]``) sits at ``r(x) + y n(x)`` with ``n`` the unit normal (tangent rotated by
+90 deg); ``tests/physics/test_ancf.py`` checks this against Exudyn.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "locate", "hermite", "centreline", "offset_points", "gauss_points", "element_lengths", "arc_length",
    "offset_curve_length",
]


def locate(s_nodes: np.ndarray, s) -> tuple[np.ndarray, np.ndarray]:
    """Element index and local coordinate ``x`` of arc-length stations.

    Parameters
    ----------
    s_nodes : (n + 1,) ndarray
        Reference arc length of the nodes [m], increasing.
    s : (m,) array_like
        Stations [m] in ``[0, s_nodes[-1]]``.

    Returns
    -------
    elem : (m,) int ndarray
    x : (m,) ndarray
        Local coordinate in the element [m].
    """
    s = np.clip(np.asarray(s, dtype=float), s_nodes[0], s_nodes[-1])
    elem = np.clip(np.searchsorted(s_nodes, s, side="right") - 1, 0, len(s_nodes) - 2)
    return elem, s - s_nodes[elem]


def hermite(q: np.ndarray, s_nodes: np.ndarray, elem: np.ndarray, x: np.ndarray):
    """Position, first and second derivative of the centreline.

    Parameters
    ----------
    q : (..., n + 1, 4) ndarray
        Node coordinates ``(r_x, r_y, r'_x, r'_y)``.
    s_nodes : (n + 1,) ndarray
        Reference arc length of the nodes [m].
    elem, x : (m,) ndarray
        Element index and local coordinate [m] (:func:`locate`).

    Returns
    -------
    r, dr, ddr : (..., m, 2) ndarray
        ``r``, ``dr/dx``, ``d^2 r/dx^2``.
    """
    le = (s_nodes[1:] - s_nodes[:-1])[elem]
    xi = x / le
    q0 = q[..., elem, :]
    q1 = q[..., elem + 1, :]
    r0, t0, r1, t1 = q0[..., :2], q0[..., 2:], q1[..., :2], q1[..., 2:]
    c = lambda a: a[:, None]  # noqa: E731  (m,) -> (m, 1) for broadcasting over xy
    S1 = 1 - 3 * xi**2 + 2 * xi**3
    S2 = le * (xi - 2 * xi**2 + xi**3)
    S3 = 3 * xi**2 - 2 * xi**3
    S4 = le * (-(xi**2) + xi**3)
    r = c(S1) * r0 + c(S2) * t0 + c(S3) * r1 + c(S4) * t1
    d1 = (-6 * xi + 6 * xi**2) / le
    d2 = 1 - 4 * xi + 3 * xi**2
    d3 = (6 * xi - 6 * xi**2) / le
    d4 = -2 * xi + 3 * xi**2
    dr = c(d1) * r0 + c(d2) * t0 + c(d3) * r1 + c(d4) * t1
    e1 = (-6 + 12 * xi) / le**2
    e2 = (-4 + 6 * xi) / le
    e3 = (6 - 12 * xi) / le**2
    e4 = (-2 + 6 * xi) / le
    ddr = c(e1) * r0 + c(e2) * t0 + c(e3) * r1 + c(e4) * t1
    return r, dr, ddr


def centreline(q: np.ndarray, s_nodes: np.ndarray, s) -> tuple[np.ndarray, np.ndarray]:
    """Centreline points and unit tangents at stations ``s``: ``(..., m, 2)`` each."""
    elem, x = locate(s_nodes, s)
    r, dr, _ = hermite(q, s_nodes, elem, x)
    return r, dr / np.linalg.norm(dr, axis=-1, keepdims=True)


def offset_points(q: np.ndarray, s_nodes: np.ndarray, s, y) -> np.ndarray:
    """Points at signed lateral offset ``y`` (along the unit normal) at stations ``s``.

    Returns ``(..., m, 2)`` [m]; the position of ``MarkerBodyRigid`` at ``[x, y]``.
    """
    r, t = centreline(q, s_nodes, s)
    n = np.stack([-t[..., 1], t[..., 0]], axis=-1)
    return r + np.asarray(y, dtype=float)[:, None] * n


def gauss_points(s_nodes: np.ndarray, n_gauss: int = 6):
    """Gauss-Legendre points of every element: ``(elem, x, weight)``, each ``(n * n_gauss,)``.

    Precompute once per mesh and pass as ``quad`` to the length functions (computing the
    Gauss rule dominates the cost of a single evaluation otherwise).
    """
    return _gauss(np.asarray(s_nodes, dtype=float), int(n_gauss))


def _gauss(s_nodes: np.ndarray, n_gauss: int):
    g, w = np.polynomial.legendre.leggauss(n_gauss)
    le = s_nodes[1:] - s_nodes[:-1]
    x = (0.5 * (g[None, :] + 1.0) * le[:, None]).reshape(-1)
    elem = np.repeat(np.arange(le.size), n_gauss)
    wt = (0.5 * w[None, :] * le[:, None]).reshape(-1)
    return elem, x, wt


def element_lengths(q: np.ndarray, s_nodes: np.ndarray, n_gauss: int = 6, quad=None) -> np.ndarray:
    """Deformed length ``int |r'| dx`` of every element (Gauss-Legendre), ``(..., n)`` [m]."""
    elem, x, w = _gauss(s_nodes, n_gauss) if quad is None else quad
    _, dr, _ = hermite(q, s_nodes, elem, x)
    n_el = len(s_nodes) - 1
    vals = np.linalg.norm(dr, axis=-1) * w
    return vals.reshape(vals.shape[:-1] + (n_el, -1)).sum(axis=-1)


def arc_length(q: np.ndarray, s_nodes: np.ndarray, n_gauss: int = 6, quad=None) -> np.ndarray:
    """Deformed centreline length ``int |r'| dx`` (Gauss-Legendre per element), ``(...)`` [m]."""
    return element_lengths(q, s_nodes, n_gauss, quad).sum(axis=-1)


def offset_curve_length(q, s_nodes, end, y_fun, dy_fun, n_gauss: int = 6, quad=None) -> np.ndarray:
    """Length of the curve ``r(s) + y(s) n(s)`` for ``s in [0, end]`` (continuum tendon path).

    ``end`` must be a node position.  With ``t = r'/|r'|`` and ``n = R90 t``:
    ``(r + y n)' = r' + y' n + y R90 t'`` and
    ``t' = (r'' |r'|^2 - r' (r' . r'')) / |r'|^3``.

    Parameters
    ----------
    q : (..., n + 1, 4) ndarray
        Node coordinates.
    s_nodes : (n + 1,) ndarray
        Node arc lengths [m].
    end : float
        Arc length where the tendon terminates [m] (a node).
    y_fun, dy_fun : callable
        ``y(s)`` [m] and ``dy/ds`` [-], vectorised.
    n_gauss : int
        Gauss points per element (ignored when ``quad`` is given).
    quad : tuple, optional
        Precomputed :func:`gauss_points`.

    Returns
    -------
    ndarray, shape (...)
        Path length [m].
    """
    elem, x, w = _gauss(s_nodes, n_gauss) if quad is None else quad
    s = s_nodes[elem] + x
    keep = s <= end + 1e-12
    elem, x, w, s = elem[keep], x[keep], w[keep], s[keep]
    _, dr, ddr = hermite(q, s_nodes, elem, x)
    nr2 = np.sum(dr * dr, axis=-1, keepdims=True)
    nr = np.sqrt(nr2)
    t = dr / nr
    tp = (ddr * nr2 - dr * np.sum(dr * ddr, axis=-1, keepdims=True)) / (nr2 * nr)
    n = np.stack([-t[..., 1], t[..., 0]], axis=-1)
    rot_tp = np.stack([-tp[..., 1], tp[..., 0]], axis=-1)
    y = y_fun(s)[:, None]
    yp = dy_fun(s)[:, None]
    d = dr + yp * n + y * rot_tp
    return np.sum(np.linalg.norm(d, axis=-1) * w, axis=-1)
