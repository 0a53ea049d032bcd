"""The discretisation-error columns of a sweep-study row (the pipeline side of the estimator).

:func:`discretization_columns` decides whether a model's row gets an estimate and computes it:
every physics model with a declared order (``workbench.registry.table("models")[name].order``) by
:func:`workbench.models.discretization.estimate_discretization` (coarser meshes, Richardson), and
every model whose accuracy is a solver tolerance (``MODELS[name].accuracy == "tolerance"``, e.g.
``cosserat``: no mesh, shooting to ``newton_tolerance``) by :func:`tolerance_estimate` (the same
case re-solved at a tighter tolerance; the error bar is the change, stored in the same ``x.disc_*``
columns, orders NaN, ``disc_status`` starting with :data:`TOLERANCE_STATUS`);
none of them when ``[solver] error_estimate = "none"``; CC rows carry none.  A model listed in ``[solver] error_estimate_exempt`` (its
discretisation is the robot's structure, e.g. one spring-link link per physical joint) carries
``x.disc_tip_error = 0`` and a ``disc_status`` saying so: nothing to refine, and its CC comparison
is judged as exact in that respect.  A
dynamic estimate needs the CC tip history of the same commands: the ``cc`` model of
``model_lookup``, run once per case (:class:`LazyCCResult`).  Imports no Exudyn.  Checked by
``tests/study/test_estimate.py``.
"""

from __future__ import annotations

from typing import Any, Callable

__all__ = ["LazyCCResult", "EXEMPT_STATUS", "TIGHTER", "TIGHTEST", "TOLERANCE_STATUS", "estimates_model", "tolerance_estimate",
           "discretization_columns"]


class LazyCCResult:
    """The CC result of one case, computed on first use: what a dynamic estimate compares the refined run with."""

    def __init__(self, model_lookup: Callable[[str], Callable], robot, load, options):
        self._args = (model_lookup, robot, load, options)
        self._result: Any = None
        self._error: str | None = None

    def set(self, result) -> None:
        """Use the CC row's own result (the case runs ``cc`` as a model)."""
        self._result = result

    def get(self):
        """The CC ``PhysicsResult``; raises ``ValueError`` naming why it is unavailable."""
        if self._result is None and self._error is None:
            lookup, robot, load, options = self._args
            try:
                self._result = lookup("cc")(robot, load, options)
            except Exception as e:  # noqa: BLE001 - reported in the estimate's status
                self._error = f"{type(e).__name__}: {e}"
        if self._error is not None:
            raise ValueError(f"no CC reference for the dynamic estimate ({self._error})")
        return self._result


def _order(name: str) -> float | None:
    from .. import registry

    info = registry.table("models").get(name)
    return None if info is None else info.order


def _tolerance_limited(name: str) -> bool:
    from .. import registry

    info = registry.table("models").get(name)
    return info is not None and info.accuracy == "tolerance"


def estimates_model(name: str, pipeline) -> bool:
    """True if rows of model ``name`` get an estimate under ``pipeline`` (a
    :class:`~workbench.study.build.PipelineOptions`; see the module docstring)."""
    if name == "cc" or pipeline.error_estimate == "none":
        return False
    return _order(name) is not None or _tolerance_limited(name)


#: :func:`tolerance_estimate` re-solves at ``min(newton_tolerance / TIGHTER, TIGHTEST)``: at least 100x
#: tighter, and at 1e-12 or below.  The Cosserat shooting integrates at a tenth of its tolerance with an
#: integration floor of 1e-13 (``physics/cosserat/shooting.py``), so 1e-12 is the tightest tolerance that
#: still tightens its solve.  Only 100x tighter under-estimated a loose solve: a ``steel_rod`` bend at
#: 1e-6 moved by 1.5e-8 m at 1e-8 but was 9e-8 m from the 1e-12 solution (``tests/study/test_estimate.py``).
TIGHTER = 100.0
TIGHTEST = 1e-12
#: Start of the ``disc_status`` of a tolerance estimate (reports tell it from a mesh estimate by it).
TOLERANCE_STATUS = "tolerance"


def tolerance_estimate(run: Callable, robot, load, options, result) -> dict[str, Any]:
    """Error bar of a model without a mesh: the change when the case is re-solved at a tighter tolerance.

    The case is solved again with ``tight = min(newton_tolerance / TIGHTER, TIGHTEST)``; the tighter
    solution stands in for the exact one, so ``|q(tol) - q(tight)|`` estimates the error of the result
    at ``tol`` for the tip position (``x.disc_tip_error`` [m]), the largest tendon tension
    (``x.disc_tension_error`` [N]) and the length change (``x.disc_length_change_error`` [m]).
    Orders are NaN (no mesh).  A failed tighter solve gives NaN bars and its reason in
    ``disc_status``.  Checked by ``tests/study/test_estimate.py`` (cosserat: the bar bounds the
    distance to an independent tighter solve; the report quotes it).
    """
    import dataclasses

    import numpy as np

    from ..models.discretization import secondary_quantities

    tight = dataclasses.replace(options, newton_tolerance=min(options.newton_tolerance / TIGHTER, TIGHTEST))
    nan = float("nan")
    out = {"x.disc_tip_error": nan, "x.disc_order_observed": nan, "x.disc_order": nan}
    how = f"{TOLERANCE_STATUS}: |q - q at newton_tolerance {tight.newton_tolerance:.3g}| (no mesh)"
    if options.newton_tolerance <= TIGHTEST:
        how += f"; at or below {TIGHTEST:g} the solve is at its integration floor: the bar is round-off"
    try:
        res = run(robot, load, tight)
    except Exception as e:  # noqa: BLE001 - ModelFailure, SolverError: the bars stay NaN, the reason is recorded
        msg = str(e).strip().replace("\n", " ")[:200]
        return {**out, "disc_status": f"{TOLERANCE_STATUS}: the tighter solve failed: {type(e).__name__}: {msg}"}
    out["x.disc_tip_error"] = float(np.linalg.norm(np.asarray(result.tip_position, float)
                                                   - np.asarray(res.tip_position, float)))
    a, b = secondary_quantities(result, False), secondary_quantities(res, False)
    for key, col in (("tension", "x.disc_tension_error"), ("length_change", "x.disc_length_change_error")):
        if key in a and key in b:
            out[col] = abs(a[key] - b[key])
    return {**out, "disc_status": how}


#: ``disc_status`` of an exempt model's rows.
EXEMPT_STATUS = "exempt: the discretisation is the robot's structure ([solver] error_estimate_exempt)"


def discretization_columns(name: str, run: Callable, robot, load, options, result,
                           cc_result: LazyCCResult | None, pipeline) -> dict[str, Any]:
    """The ``x.disc_*`` and ``disc_status`` cells of one ok row (``{}`` when the model gets none);
    ``pipeline``: the case's :class:`~workbench.study.build.PipelineOptions`."""
    from ..models.discretization import estimate_columns, estimate_discretization

    if not estimates_model(name, pipeline):
        return {}
    if name in pipeline.error_estimate_exempt:
        return {"x.disc_tip_error": 0.0, "x.disc_order_observed": float("nan"), "x.disc_order": float("nan"),
                "disc_status": EXEMPT_STATUS}
    if _order(name) is None:  # estimates_model: the accuracy is a tolerance
        return tolerance_estimate(run, robot, load, options, result)
    ref = None
    if load.analysis == "dynamic":
        try:
            ref = cc_result.get() if cc_result is not None else None
        except ValueError as e:
            return {**estimate_columns(estimate_discretization(run, robot, load, options, result, float("nan"))),
                    "disc_status": str(e)}
    secondary: dict = {}
    est = estimate_discretization(run, robot, load, options, result, _order(name), ref, secondary)
    return estimate_columns(est, secondary)
