"""Centreline / tendon-path geometry helpers against independent numerical references."""

import numpy as np

from workbench.physics import _ancf_geometry as geo


def _state(n=6, L=0.8, seed=0):
    rng = np.random.default_rng(seed)
    s = np.linspace(0, L, n + 1)
    th = 1.3 * s / L + 0.2 * np.sin(5 * s)  # a smooth curled shape, slopes slightly stretched
    q = np.zeros((n + 1, 4))
    stretch = 1 + 1e-3 * rng.standard_normal(n + 1)
    q[:, 2] = stretch * np.cos(th)
    q[:, 3] = stretch * np.sin(th)
    q[:, 0] = np.concatenate([[0], np.cumsum(np.diff(s) * np.cos(th[:-1]))])
    q[:, 1] = np.concatenate([[0], np.cumsum(np.diff(s) * np.sin(th[:-1]))])
    return s, q


def _polyline_length(pts):
    return np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1))


def test_arc_length_vs_polyline():
    s_nodes, q = _state()
    s = np.linspace(0, s_nodes[-1], 200001)
    r, _ = geo.centreline(q, s_nodes, s)
    assert abs(geo.arc_length(q, s_nodes, n_gauss=8) - _polyline_length(r)) < 1e-9


def test_offset_curve_length_vs_polyline_constant_and_tapered():
    s_nodes, q = _state()
    end = s_nodes[4]
    s = np.linspace(0, end, 200001)
    for y0, y1 in ((0.02, 0.02), (-0.03, -0.01)):
        y = lambda x: y0 + (y1 - y0) * np.asarray(x) / end  # noqa: E731
        dy = lambda x: np.full_like(np.asarray(x, dtype=float), (y1 - y0) / end)  # noqa: E731
        pts = geo.offset_points(q, s_nodes, s, y(s))
        ref = _polyline_length(pts)
        assert abs(geo.offset_curve_length(q, s_nodes, end, y, dy, n_gauss=8) - ref) < 1e-8


def test_vectorised_over_leading_axes():
    s_nodes, q = _state()
    Q = np.stack([q, q * 1.0])
    assert np.allclose(geo.arc_length(Q, s_nodes), geo.arc_length(q, s_nodes))
    r, t = geo.centreline(Q, s_nodes, np.array([0.1, 0.5]))
    assert r.shape == (2, 2, 2) and np.allclose(np.linalg.norm(t, axis=-1), 1.0)
