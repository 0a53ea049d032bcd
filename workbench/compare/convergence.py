"""Discretisation error bars of a comparison and the "not converged" rule (pure functions).

Each physics row carries the estimate of its own discretisation error (``x.disc_tip_error``,
:mod:`workbench.models.discretization`).  For one compared pair of rows:

``judged_error`` [m]
    The error the comparison reports: the tip error, or for dynamic cases the peak over time of
    the tip error (``tip_error_max_over_time``, the quantity a dynamic report headlines).
``disc_error`` [m]
    Its discretisation error bar: for a pair with a CC model (``cc``, ``cc_fit``) the physics
    row's estimate (its ``x.disc_cc_error`` when the model provides the estimate of the CC error
    itself, as the series-parallel worker does); for two physics models the sum of both; NaN when
    a physics row has no estimate.
``disc_exempt``
    True when a side of the pair is exempt from the estimate (its ``disc_status`` starts with
    ``exempt``: ``[solver] error_estimate_exempt``, the discretisation *is* the robot, e.g. a
    jointed trunk's links); its part of ``disc_error`` is 0, and reports say "exempt" rather
    than "± 0".
``not_converged`` (CC pairs only)
    ``disc_error > 0.1 judged_error`` (the error bar exceeds 10 % of the error it judges), unless
    ``judged_error + disc_error <= floor`` with the agreement floor :data:`AGREEMENT_FLOOR` x L: then
    CC and the model agree to within the floor whatever the mesh (where CC is exact, e.g. a
    continuum tendon without gravity, the computed error *is* discretisation error and cannot be
    10 times larger than it); also not converged without an estimate.  Comparisons between physics
    models get the error bar but no mark: their difference is allowed to be discretisation error.

Checked by ``tests/compare/test_convergence.py``.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

__all__ = ["CC_MODELS", "AGREEMENT_FLOOR", "CONVERGED_FRACTION", "is_cc_pair", "convergence_metrics"]

#: Models that are the constant-curvature prediction (the comparisons the rule judges).
CC_MODELS = ("cc", "cc_fit")
#: An error plus its error bar below this fraction of the robot length is agreement (0.001 % of L,
#: far below the per-cent levels the studies judge CC at).
AGREEMENT_FLOOR = 1e-5
#: A comparison is converged when its discretisation error is at most this fraction of its error.
CONVERGED_FRACTION = 0.1


def is_cc_pair(baseline: str, model: str) -> bool:
    """True when one side of the pair is a CC model."""
    return str(baseline) in CC_MODELS or str(model) in CC_MODELS


def _disc(row: Mapping[str, Any], cc_pair: bool) -> float:
    if str(row.get("model")) in CC_MODELS or str(row.get("model")) == "target":
        return 0.0  # CC and commanded targets have no discretisation
    for key in (("x.disc_cc_error", "x.disc_tip_error") if cc_pair else ("x.disc_tip_error",)):
        v = row.get(key)
        if v is not None and not (isinstance(v, float) and math.isnan(v)):
            return float(v)
    return float("nan")


def _exempt(row: Mapping[str, Any]) -> bool:
    return str(row.get("disc_status") or "").startswith("exempt")


def convergence_metrics(ref: Mapping[str, Any], row: Mapping[str, Any], metrics: Mapping[str, float]) -> dict[str, Any]:
    """``judged_error``, ``disc_error`` [m], ``disc_error_pct`` [% L], ``disc_fraction``, ``disc_exempt`` and ``not_converged``
    of one compared pair (see the module docstring); ``metrics`` are the pair's tip errors."""
    cc_pair = is_cc_pair(ref.get("model"), row.get("model"))
    peak = metrics.get("tip_error_max_over_time", float("nan"))
    judged = float(peak) if peak is not None and math.isfinite(float(peak)) else float(metrics.get("tip_error", float("nan")))
    disc = _disc(ref, cc_pair) + _disc(row, cc_pair)
    L = float(ref.get("robot_length", float("nan")))
    frac = disc / judged if math.isfinite(disc) and math.isfinite(judged) and judged > 0 else float("nan")
    if math.isfinite(disc) and judged == 0.0:
        frac = 0.0 if disc == 0.0 else float("inf")
    agree = math.isfinite(disc) and math.isfinite(judged) and judged + disc <= AGREEMENT_FLOOR * L
    converged = agree or (math.isfinite(frac) and frac <= CONVERGED_FRACTION)
    return {
        "judged_error": judged,
        "disc_error": disc,
        "disc_error_pct": 100.0 * disc / L if math.isfinite(L) and L > 0 else float("nan"),
        "disc_fraction": frac,
        "disc_exempt": _exempt(ref) or _exempt(row),
        "not_converged": bool(cc_pair and not converged),
    }
