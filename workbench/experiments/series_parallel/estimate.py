"""Discretisation error and leg stresses of one series-parallel case (the worker's extras).

The IK is solved again with 1/2 and 1/4 of the leg elements; by construction FK(IK) meets the
target at any mesh, so the mesh shows in the insertion lengths, not in the platform poses.  The
estimates (:func:`workbench.models.discretization.estimate_from_values`, the GE beam's order 2):

``x.disc_length_error`` [m]
    Richardson estimate of the error of the insertion lengths ``L`` (largest over the legs).
``x.disc_tip_error`` [m]
    The platform (tip) position error those lengths cause: the tip of the fine-mesh FK of the
    coarse lengths, ``FK_N(L_N')``, against ``FK_N(L_N)`` (the target), Richardson-extrapolated.
``x.disc_cc_error`` [m]
    The same for the CC-vs-physics tip error (FK tip to the tip of the CC arc fitted through the FK
    platforms): how much the judged comparison would move with converged lengths.
``x.disc_order_observed``, ``x.disc_order``, ``disc_status``
    As in :func:`workbench.models.discretization.estimate_columns` (orders from the lengths).

``x.max_stress_backbone`` [Pa] is the largest leg stress (:mod:`workbench.physics.series_parallel.stress`)
and ``x.stress_ratio`` its ratio to ``ModuleGeometry.yield_strength``.  Checked by the
regression tier (``tests/regression/golden/series_parallel.csv`` holds these columns).
"""

from __future__ import annotations

from typing import Any, Callable, Mapping

import numpy as np

__all__ = ["stress_columns", "discretization_columns"]


def stress_columns(geo, modules) -> dict[str, float]:
    """``x.max_stress_backbone`` (legs) and ``x.stress_ratio`` of the fine IK's module solutions."""
    from ...physics.series_parallel.stress import module_leg_stress

    s = module_leg_stress(geo, [m for m in modules if m is not None])
    return {"x.max_stress_backbone": s, "x.stress_ratio": s / geo.yield_strength}


def _cc_tip_error(poses: np.ndarray) -> float:
    """Distance of the top platform to the tip of the CC arc fitted through the platforms [m]."""
    from ...physics.series_parallel import arc_points, fit_constant_curvature

    fit = fit_constant_curvature(poses)
    pa, _ = arc_points(fit.curvature, fit.phi, fit.arc_lengths)
    return float(np.linalg.norm(poses[-1, :3, 3] - pa[-1]))


def discretization_columns(geo, targets: np.ndarray, sol: Mapping[str, Any], n: int, lengths: np.ndarray,
                           fk_poses: np.ndarray, inverse: Callable) -> dict[str, Any]:
    """The ``x.disc_*`` cells of the ``series_parallel`` row (see the module docstring).

    ``inverse(geo, targets, n, sol)`` is the worker's IK (``(lengths, success, reason, ...)``);
    ``lengths`` and ``fk_poses`` the fine solution.  A failed coarse IK or FK limits the estimate
    (``disc_status`` says which); nothing raises.
    """
    from ... import registry
    from ...models.discretization import estimate_columns, estimate_from_values
    from ...physics.series_parallel import stack_forward

    n_el = int(sol["n_elements"])
    order = registry.LABELS["series_parallel"].order
    noise = 10.0 * max(float(sol["length_tolerance"]), float(sol["fk_tolerance"]) * n * geo.height)
    L_vals, tips, ccs, res = [np.asarray(lengths).reshape(-1)], [fk_poses[-1, :3, 3]], [_cc_tip_error(fk_poses)], [n_el]
    status = "ok"
    for factor in (2, 4):
        m = n_el // factor
        if m < 1 or m >= res[-1]:
            status = f"cannot coarsen {n_el} leg elements by {factor}" if factor == 2 else "ok (no quarter-resolution mesh)"
            break
        L, ok, reason = inverse(geo, targets, n, {**sol, "n_elements": m})[:3]
        fk = stack_forward([geo] * n, L, n_elements=n_el, tolerance=sol["fk_tolerance"]) if ok else None
        if fk is None or not fk.converged:
            why = f"IK with {m} leg elements failed: {reason}" if not ok else f"FK of the {m}-element lengths: {fk.reason}"
            status = why if factor == 2 else f"ok (quarter-resolution solve failed: {why})"
            break
        L_vals.append(np.asarray(L).reshape(-1))
        tips.append(fk.poses[-1, :3, 3])
        ccs.append(_cc_tip_error(fk.poses))
        res.append(m)
    est_L = estimate_from_values(L_vals, res, order, noise, status)
    cols = estimate_columns(est_L)
    p = est_L.order_used
    ratio = res[0] / res[1] if len(res) > 1 else np.nan
    if len(res) > 1:
        cols["x.disc_tip_error"] = float(np.linalg.norm(tips[1] - tips[0])) / (ratio**p - 1.0)
        cols["x.disc_cc_error"] = abs(ccs[1] - ccs[0]) / (ratio**p - 1.0)
        cols["x.disc_length_error"] = float(np.max(np.abs(L_vals[1] - L_vals[0]))) / (ratio**p - 1.0)
    else:
        cols.update({"x.disc_tip_error": float("nan"), "x.disc_cc_error": float("nan"),
                     "x.disc_length_error": float("nan")})
    return cols
