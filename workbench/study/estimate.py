"""The discretisation-error columns of a sweep-study row (the pipeline side of the estimator).

:func:`discretization_columns` decides whether a model's row gets an estimate and computes it
with :func:`workbench.models.discretization.estimate_discretization`: every physics model with
a declared order (``workbench.registry.MODELS[name].order``) unless ``[solver] error_estimate =
"none"``; CC rows carry none.  A model listed in ``[solver] error_estimate_exempt`` (its
discretisation is the robot's structure, e.g. one spring-link link per physical joint) carries
``x.disc_tip_error = 0`` and a ``disc_status`` saying so: nothing to refine, and its CC comparison
is judged as exact in that respect.  A
dynamic estimate needs the CC tip history of the same commands: the ``cc`` model of
``model_lookup``, run once per case (:class:`LazyCCResult`).  Imports no Exudyn.  Checked by
``tests/study/test_estimate.py``.
"""

from __future__ import annotations

from typing import Any, Callable

__all__ = ["LazyCCResult", "EXEMPT_STATUS", "estimates_model", "discretization_columns"]


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

    info = registry.MODELS.get(name)
    return None if info is None else info.order


def estimates_model(name: str, pipeline) -> bool:
    """True if rows of model ``name`` get an estimate under ``pipeline`` (a
    :class:`~workbench.study.build.PipelineOptions`; see the module docstring)."""
    if name == "cc" or pipeline.error_estimate == "none":
        return False
    return _order(name) is not None


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
