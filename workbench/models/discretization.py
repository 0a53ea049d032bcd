"""Discretisation error of one physics result: re-solve coarser, Richardson-extrapolate.

A result at resolution ``N`` (elements / links, time step ``h`` for dynamics) is re-solved at
``N/2`` (``2 h``) and ``N/4`` (``4 h``).  With the model's known convergence order ``p``
(``workbench.registry.table("models")[name].order``; at most 2 in dynamics, the order of generalised-alpha)
the error of the fine result is estimated as ``|q_N - q_N/2| / (r^p - 1)`` (Richardson,
refinement ratio ``r = N / N'``).  The three resolutions also give the observed order
``log(|q_N/4 - q_N/2| / |q_N/2 - q_N|) / log 2``; when it is lower than ``p`` (not yet in the
asymptotic range) the estimate uses it instead (never below 1), so the estimate is never less
conservative than the known order alone.  The headline quantity ``q`` is the tip position
(statics) or the peak over time of the tip's distance to the constant-curvature tip of the same
commands (dynamics: the number a dynamic report headlines); the same solves also estimate the
largest tendon tension and the backbone length change (:func:`secondary_quantities`).

Pure numpy; the models are passed in as functions.  Used by the study pipeline
(:func:`workbench.study.evaluate.evaluate_case`) and the series-parallel worker.  Checked by
``tests/models/test_discretization.py`` (estimate vs the true error on the elastica and the
pure-moment arc, every model, two resolutions; a coarse case is flagged).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from .result import PhysicsResult, SolverOptions

__all__ = [
    "DYNAMIC_ORDER", "DiscretizationEstimate", "coarsened_options", "richardson_error", "observed_order",
    "effective_order", "peak_distance", "estimate_from_values", "secondary_quantities", "estimate_discretization",
    "estimate_columns",
]

#: Convergence order of the time integrator (implicit generalised-alpha) used by every dynamic model.
DYNAMIC_ORDER = 2.0


@dataclass(frozen=True)
class DiscretizationEstimate:
    """The discretisation error estimate of one result.

    Attributes
    ----------
    error : float
        Estimated error of the fine result's headline quantity [m] (NaN: no estimate, see ``status``).
    order_known : float
        Order the model declares (NaN if it declares none: then 1 is assumed).
    order_observed : float
        Order seen over the three resolutions (NaN: fewer than three, or differences at solver precision).
    order_used : float
        Order of the Richardson estimate (:func:`effective_order`).
    differences : tuple of float
        ``|q_N - q_N/2|`` and, if solved, ``|q_N/2 - q_N/4|`` [m].
    resolutions : tuple of int
        The element / link counts solved, finest first.
    status : str
        ``"ok"``, or why the estimate is missing or limited.
    wall_time : float
        Seconds spent in the coarse solves.
    """

    error: float
    order_known: float
    order_observed: float
    order_used: float
    differences: tuple[float, ...]
    resolutions: tuple[int, ...]
    status: str
    wall_time: float = 0.0


def coarsened_options(options: SolverOptions, n_sections: int, factor: int, dynamic: bool) -> SolverOptions | None:
    """Options at ``1/factor`` of the resolution, or ``None`` if the mesh cannot be coarsened.

    ``n_elements`` becomes ``n_elements // factor`` rounded down to a multiple of ``n_sections``
    (every model needs at least one element / link per section); dynamics also multiply
    ``time_step`` by the realised ratio ``n_elements / n_coarse``.
    """
    n = options.n_elements // int(factor)
    n -= n % max(1, n_sections)
    if n < max(1, n_sections) or n >= options.n_elements:
        return None
    ratio = options.n_elements / n
    return replace(options, n_elements=n, time_step=options.time_step * ratio if dynamic else options.time_step)


def richardson_error(difference: float, ratio: float, order: float) -> float:
    """Richardson estimate ``difference / (ratio^order - 1)`` of the finer solution's error."""
    return float(difference) / (float(ratio) ** float(order) - 1.0)


def observed_order(d_fine: float, d_coarse: float, r_fine: float = 2.0, r_coarse: float = 2.0) -> float:
    """Order ``p`` with ``d_coarse / d_fine = r_f^p (r_c^p - 1) / (r_f^p - 1)`` (``log2(d_c / d_f)`` for ratios 2).

    ``d_fine = |q_N - q_N'|``, ``d_coarse = |q_N' - q_N''|`` with ``r_fine = N / N'``,
    ``r_coarse = N' / N''``.  NaN when a difference is zero or not finite; values below 0 mean
    the differences grow under refinement (outside the asymptotic range).
    """
    if not (np.isfinite(d_fine) and np.isfinite(d_coarse) and d_fine > 0 and d_coarse > 0):
        return float("nan")
    target = d_coarse / d_fine
    if abs(r_fine - 2.0) < 1e-12 and abs(r_coarse - 2.0) < 1e-12:
        return math.log2(target)

    def g(p: float) -> float:
        if abs(p) < 1e-9:
            return math.log(r_coarse) / math.log(r_fine) - target
        return r_fine**p * (r_coarse**p - 1.0) / (r_fine**p - 1.0) - target

    lo, hi = -10.0, 20.0
    if g(lo) * g(hi) > 0:
        return float("nan")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def effective_order(known: float, observed: float) -> float:
    """``min(known, max(observed, 1))`` when the observed order is finite, else ``known``.

    A declared order of NaN counts as 1 (no claim: the most conservative Richardson factor).
    """
    k = 1.0 if not np.isfinite(known) else float(known)
    if not np.isfinite(observed):
        return k
    return min(k, max(float(observed), 1.0))


def peak_distance(time_a, points_a, time_b, points_b) -> float:
    """Largest distance over time between two point histories [m].

    ``points_b`` (shape ``(k_b, 3)`` at ``time_b``) is linearly interpolated onto the times of
    ``points_a`` (shape ``(k_a, 3)``) inside their common interval.
    """
    ta, pa = np.asarray(time_a, float), np.asarray(points_a, float).reshape(-1, 3)
    tb, pb = np.asarray(time_b, float), np.asarray(points_b, float).reshape(-1, 3)
    sel = (ta >= tb[0] - 1e-12) & (ta <= tb[-1] + 1e-12)
    if not np.any(sel):
        return float("nan")
    pb_on_a = np.stack([np.interp(ta[sel], tb, pb[:, k]) for k in range(3)], axis=-1)
    return float(np.max(np.linalg.norm(pa[sel] - pb_on_a, axis=1)))


def estimate_from_values(values: list, resolutions: list[int], order_known: float, noise: float,
                         status: str = "ok", wall_time: float = 0.0) -> DiscretizationEstimate:
    """Estimate from the headline quantity at two or three resolutions (finest first).

    ``values`` are arrays (tip positions) or scalars; differences are Euclidean norms.
    ``noise`` [m]: differences below it are solver precision (no observed order from them).
    """
    vals = [np.atleast_1d(np.asarray(v, dtype=float)) for v in values]
    if len(vals) < 2:
        return DiscretizationEstimate(float("nan"), order_known, float("nan"), float("nan"), (), tuple(resolutions),
                                      status, wall_time)
    diffs = tuple(float(np.linalg.norm(a - b)) for a, b in zip(vals[:-1], vals[1:]))
    ratios = [resolutions[i] / resolutions[i + 1] for i in range(len(resolutions) - 1)]
    p_obs = float("nan")
    if len(diffs) == 2 and min(diffs) > noise:
        p_obs = observed_order(diffs[0], diffs[1], ratios[0], ratios[1])
    p = effective_order(order_known, p_obs)
    if np.isfinite(p_obs) and p_obs < 1.0 and status == "ok":
        status = (f"observed order {p_obs:.2g} < 1 (outside the asymptotic range): the estimate is "
                  f"|q_N - q_N/2| itself")
    return DiscretizationEstimate(richardson_error(diffs[0], ratios[0], p), order_known, p_obs, p, diffs,
                                  tuple(resolutions), status, wall_time)


def _quantity(res: PhysicsResult, dynamic: bool, reference: PhysicsResult | None):
    if not dynamic:
        return res.tip_position
    tip = res.series.get("tip_position") if res.series else None
    ref = reference.series.get("tip_position") if reference is not None and reference.series else None
    if tip is None or ref is None or res.time is None or reference.time is None:
        raise ValueError("a dynamic estimate needs tip_position series of the model and of the CC reference")
    return peak_distance(res.time, tip, reference.time, ref)


def secondary_quantities(res: PhysicsResult, dynamic: bool) -> dict[str, float]:
    """The other quantities a report quotes: the largest tendon tension [N] and the backbone length
    change [m] (dynamics: the largest tension and the most negative length change over time)."""
    out = {}
    T = res.series.get("tendon_tensions") if dynamic and res.series else res.tendon_tensions
    T = np.asarray(T if T is not None else [], dtype=float)
    if T.size and np.all(np.isfinite(T)):
        out["tension"] = float(T.max())
    dl = res.series.get("length_change") if dynamic and res.series else None
    out["length_change"] = float(np.min(dl)) if dl is not None and np.size(dl) else float(res.length_change)
    return out


def estimate_discretization(run: Callable, robot, load, options: SolverOptions, fine: PhysicsResult,
                            order_known: float, reference: PhysicsResult | None = None,
                            secondary: dict | None = None) -> DiscretizationEstimate:
    """Re-solve ``run(robot, load, options')`` at 1/2 and 1/4 of the resolution and estimate (module docstring).

    Parameters
    ----------
    run : callable
        The model, ``run(robot, load, options) -> PhysicsResult``.
    robot, load, options
        The case as it ran (``fine`` is ``run(robot, load, options)``).
    fine : PhysicsResult
    order_known : float
        The model's declared order (NaN: none); dynamics use ``min(order_known, DYNAMIC_ORDER)``.
    reference : PhysicsResult, optional
        Dynamics: the CC result of the same case (its tip series defines the peak quantity).

    secondary : dict, optional
        If given, filled with the :class:`DiscretizationEstimate` of every
        :func:`secondary_quantities` entry (same solves).

    Returns
    -------
    DiscretizationEstimate
        Never raises for a failed coarse solve: the reason is in ``status`` (error NaN when the
        half-resolution solve fails, observed order NaN when only the quarter one does).
    """
    dynamic = load.analysis == "dynamic"
    p = float(order_known) if order_known is not None else float("nan")
    if dynamic:
        p = min(p, DYNAMIC_ORDER) if np.isfinite(p) else DYNAMIC_ORDER
    t0 = time.perf_counter()
    try:
        values = [_quantity(fine, dynamic, reference)]
    except ValueError as e:
        return DiscretizationEstimate(float("nan"), p, float("nan"), float("nan"), (), (options.n_elements,), str(e))
    resolutions = [options.n_elements]
    others = [secondary_quantities(fine, dynamic)]
    status = "ok"
    for k, factor in enumerate((2, 4)):
        opt = coarsened_options(options, robot.n_sections, factor, dynamic)
        if opt is None or opt.n_elements >= resolutions[-1]:
            status = (f"cannot coarsen {options.n_elements} elements by {factor} "
                      f"({robot.n_sections} section(s))") if k == 0 else "ok (no quarter-resolution mesh)"
            break
        try:
            res = run(robot, load, opt)
            values.append(_quantity(res, dynamic, reference))
            others.append(secondary_quantities(res, dynamic))
            resolutions.append(opt.n_elements)
        except Exception as e:  # noqa: BLE001 - a failed coarse solve limits the estimate, it is not a failure
            msg = str(e).strip().replace("\n", " ")[:200]
            status = (f"coarse solve ({opt.n_elements} elements) failed: {type(e).__name__}: {msg}" if k == 0 else
                      f"ok (quarter-resolution solve failed: {type(e).__name__}: {msg})")
            break
    noise = 10.0 * options.newton_tolerance * max(robot.length, 1e-3)
    if secondary is not None:
        for key in others[0]:
            vals = [o.get(key, float("nan")) for o in others]
            scale = max(abs(vals[0]), 1.0) if key == "tension" else max(robot.length, 1e-3)
            secondary[key] = estimate_from_values(vals, resolutions, p, 10.0 * options.newton_tolerance * scale, status)
    return estimate_from_values(values, resolutions, p, noise, status, time.perf_counter() - t0)


def estimate_columns(est: DiscretizationEstimate, secondary: dict | None = None) -> dict:
    """The result-table cells of an estimate: ``x.disc_tip_error`` [m], ``x.disc_order_observed``,
    ``x.disc_order`` (order used) and the text cell ``disc_status`` (``wall_time`` is not stored:
    result tables hold no timing noise beyond the model's own ``wall_time``); with ``secondary``
    (:func:`estimate_discretization`) also ``x.disc_tension_error`` [N] and
    ``x.disc_length_change_error`` [m]."""
    out = {"x.disc_tip_error": float(est.error), "x.disc_order_observed": float(est.order_observed),
           "x.disc_order": float(est.order_used), "disc_status": est.status}
    for key, name in (("tension", "x.disc_tension_error"), ("length_change", "x.disc_length_change_error")):
        if secondary and key in secondary:
            out[name] = float(secondary[key].error)
    return out
