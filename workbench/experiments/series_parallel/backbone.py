"""How well a stack of series-parallel modules imitates a commanded backbone curve (Huang's S-shape).

Huang et al. (papers/004_, Sec. 4.2, Fig 10d-e) find that three modules "complete the s-shaped
orientation roughly" and deduce that "it would be imitated better if it has more sections".  The
inverse kinematics puts every platform exactly on the commanded curve (``stack_targets``); between
the platforms the trunk is whatever the flexible legs do.  Measured here:

* the **module centreline**: at every leg node index ``j`` the mean of the six legs' nodes (each
  leg's node ``j`` sits at the fraction ``j / N`` of its own length, hole to platform); with the
  symmetric default hole and attachment circles it runs from the module's base centre to its
  platform centre (:func:`module_centrelines`);
* ``x.backbone_max_error`` / ``x.backbone_rms_error`` [m]: the distance of those points from the
  commanded continuous curve (:func:`commanded_curve`: one arc for ``bending``, two arcs of
  opposite curvature for ``s_shape``); ``x.polygon_max_error`` [m]: the same for the straight
  chords between the platform centres (the geometric reference: how far a chain of rigid links
  through the same platforms would be off).  The report divides them by the trunk length ``n h``.

Pure numpy.  Checked by ``tests/experiments/test_series_parallel_backbone.py``.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

__all__ = ["CURVE_SHAPES", "commanded_curve", "module_centrelines", "distance_to_curve", "backbone_errors"]

#: Stack shapes with a commanded continuous backbone (``translation`` commands only platform poses).
CURVE_SHAPES = ("bending", "s_shape")

_N_CURVE = 4000


def commanded_curve(stack_targets: Callable, shape: str, value: float, n_modules: int, height: float,
                    plane: float = 0.0, n_points: int = _N_CURVE) -> np.ndarray:
    """``(m + 1, 3)`` points of the commanded backbone from the base, stack base frame [m].

    ``stack_targets`` is the platform-pose function of the motions (:func:`.worker.stack_targets`,
    passed in: the worker imports this module); its curve (``bending``: one arc of total angle
    ``value``; ``s_shape``: tangent angle ``value`` at mid-length, top parallel to the base) is
    sampled as ``n_points`` (rounded up to a multiple of ``n_modules``, so the platforms are samples)
    platforms of a trunk of the same length ``n_modules * height``.  The polyline through the samples
    is within ``(S / n_points)^2 kappa / 8`` of the curve (~1e-8 m for the study's trunks).
    """
    if shape not in CURVE_SHAPES:
        raise ValueError(f"shape {shape!r} has no commanded backbone curve (one of {', '.join(CURVE_SHAPES)})")
    n = int(n_modules)
    m = n * -(-int(n_points) // n)
    S = n * float(height)
    pts = stack_targets(shape, value, m, S / m, plane)[:, :3, 3]
    return np.vstack([np.zeros(3), pts])


def module_centrelines(leg_positions) -> np.ndarray:
    """``(n, N + 1, 3)`` centreline of every module: the mean of its six legs at each node index."""
    legs = np.asarray(leg_positions, dtype=float)
    if legs.ndim != 4 or legs.shape[1] != 6 or legs.shape[-1] != 3:
        raise ValueError(f"leg_positions must have shape (n, 6, N + 1, 3), got {legs.shape}")
    return legs.mean(axis=1)


def distance_to_curve(points, curve) -> np.ndarray:
    """``(m,)`` distance of each point ``(m, 3)`` from the polyline ``curve`` ``(p, 3)`` [m]."""
    P = np.asarray(points, dtype=float).reshape(-1, 3)
    C = np.asarray(curve, dtype=float)
    a, ab = C[:-1], np.diff(C, axis=0)
    L2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    out = np.empty(P.shape[0])
    for i, p in enumerate(P):
        t = np.clip(np.einsum("ij,ij->i", p - a, ab) / L2, 0.0, 1.0)
        out[i] = np.min(np.linalg.norm(a + t[:, None] * ab - p, axis=1))
    return out


def backbone_errors(stack_targets: Callable, shape: str, value: float, n_modules: int, height: float, plane: float,
                    leg_positions, platform_positions) -> dict[str, float]:
    """``x.backbone_max_error``, ``x.backbone_rms_error`` and ``x.polygon_max_error`` [m] (module docstring).

    Parameters
    ----------
    stack_targets, shape, value, n_modules, height, plane
        The stack motion (see :func:`commanded_curve`).
    leg_positions : array_like, shape (n, 6, N + 1, 3)
        Leg node positions of the solved stack, stack base frame [m].
    platform_positions : array_like, shape (n, 3)
        Platform origins of the solved stack [m].
    """
    curve = commanded_curve(stack_targets, shape, value, n_modules, height, plane)
    d = distance_to_curve(module_centrelines(leg_positions), curve)
    chain = np.vstack([np.zeros(3), np.asarray(platform_positions, dtype=float)])
    t = np.linspace(0.0, 1.0, 41)[:, None]
    chords = np.vstack([(1 - t) * chain[k] + t * chain[k + 1] for k in range(len(chain) - 1)])
    return {"x.backbone_max_error": float(d.max()), "x.backbone_rms_error": float(np.sqrt(np.mean(d ** 2))),
            "x.polygon_max_error": float(distance_to_curve(chords, curve).max())}
