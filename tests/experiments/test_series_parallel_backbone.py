"""Huang's n-module S-shape: the commanded curve, the centreline distance (series_parallel/backbone.py).

The geometry against closed forms (an arc's chord sagitta ``R (1 - cos(theta/2))``), the figure set's
matching, and (slow) the physics: more modules imitate the S-curve better.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from workbench.experiments.series_parallel.backbone import (
    backbone_errors,
    commanded_curve,
    distance_to_curve,
    module_centrelines,
)
from workbench.experiments.series_parallel.figures_s_shape import matches, s_shape_table
from workbench.experiments.series_parallel.worker import stack_targets


@pytest.mark.parametrize("shape, value", [("bending", 1.2), ("s_shape", 0.5)])
def test_commanded_curve_runs_through_the_platform_targets(shape, value):
    n, h = 3, 0.5
    C = commanded_curve(stack_targets, shape, value, n, h, plane=0.4)
    np.testing.assert_allclose(C[0], 0.0)
    assert np.sum(np.linalg.norm(np.diff(C, axis=0), axis=1)) == pytest.approx(n * h, rel=1e-6)  # arc length
    platforms = stack_targets(shape, value, n, h, 0.4)[:, :3, 3]
    assert distance_to_curve(platforms, C).max() < 1e-12  # the platforms are curve points
    with pytest.raises(ValueError, match="no commanded backbone curve"):
        commanded_curve(stack_targets, "translation", 0.1, n, h)


def test_distance_to_a_polyline():
    C = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0]])
    P = np.array([[0.3, 0.0, 0.5], [0.5, 0.2, 1.0], [0.0, 0.0, -2.0], [2.0, 0.0, 1.0]])
    np.testing.assert_allclose(distance_to_curve(P, C), [0.3, 0.2, 2.0, 1.0], atol=1e-15)


def _legs_on(points: np.ndarray, radius: float = 0.1) -> np.ndarray:
    """Six legs around the points (n, N+1, 3) at +-radius in x and y: their mean is the points."""
    offs = radius * np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [1, 1, 0], [-1, -1, 0]], dtype=float)
    return np.stack([points + o for o in offs], axis=1)


def test_backbone_errors_against_the_arc_sagitta():
    """A bending stack whose centrelines are the chords: the error is the chord's sagitta."""
    n, h, value = 4, 0.5, 1.6
    P = stack_targets("bending", value, n, h)[:, :3, 3]
    chain = np.vstack([np.zeros(3), P])
    t = np.linspace(0.0, 1.0, 9)[:, None]
    chords = np.stack([(1 - t) * chain[k] + t * chain[k + 1] for k in range(n)])  # (n, 9, 3)
    np.testing.assert_allclose(module_centrelines(_legs_on(chords)), chords, atol=1e-15)
    err = backbone_errors(stack_targets, "bending", value, n, h, 0.0, _legs_on(chords), P)
    R, theta = n * h / value, value / n
    sagitta = R * (1 - np.cos(theta / 2))
    assert err["x.backbone_max_error"] == pytest.approx(sagitta, rel=1e-5)
    assert err["x.polygon_max_error"] == pytest.approx(sagitta, rel=1e-5)
    # centrelines on the curve itself: no error
    C = commanded_curve(stack_targets, "bending", value, n, h, n_points=4 * 8)
    on = C[1:].reshape(n, 8, 3)
    on = np.concatenate([np.vstack([np.zeros(3), P[:-1]])[:, None], on], axis=1)
    err = backbone_errors(stack_targets, "bending", value, n, h, 0.0, _legs_on(on), P)
    assert err["x.backbone_max_error"] < 1e-6 and err["x.backbone_rms_error"] < 1e-6


def test_matches_and_table():
    ok = pd.DataFrame({"model": ["series_parallel"] * 2, "p.pose.shape": ["s_shape"] * 2,
                       "p.pose.n_modules": [3, 5], "p.pose.value": [0.5, 0.5], "robot_length": [1.5, 2.5],
                       "x.backbone_max_error": [1e-3, 6e-4], "x.backbone_rms_error": [4e-4, 2e-4],
                       "x.polygon_max_error": [2e-2, 1.2e-2]})
    assert matches(SimpleNamespace(ok=ok)) and not matches(SimpleNamespace(ok=ok.iloc[:1]))
    t = s_shape_table(ok)
    np.testing.assert_allclose(t["backbone_rel"], [1e-3 / 1.5, 6e-4 / 2.5])


@pytest.mark.slow  # two stack IK + FK solves: ~1 min
def test_more_modules_imitate_the_s_shape_better():
    from workbench.physics.series_parallel import ModuleGeometry, stack_forward, stack_inverse

    geo, rel = ModuleGeometry(), []
    for n in (3, 5):
        T = stack_targets("s_shape", 0.25, n, geo.height)
        ik = stack_inverse([geo] * n, T, n_elements=4)
        assert ik.success
        fk = stack_forward([geo] * n, ik.lengths, n_elements=4)
        assert fk.converged
        e = backbone_errors(stack_targets, "s_shape", 0.25, n, geo.height, 0.0, fk.leg_positions, fk.poses[:, :3, 3])
        rel.append(e["x.backbone_max_error"] / (n * geo.height))
        assert e["x.backbone_max_error"] < e["x.polygon_max_error"]  # flexible legs beat straight chords
    assert rel[1] < 0.6 * rel[0]
