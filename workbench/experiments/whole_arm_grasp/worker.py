"""The worker of the ``grasp`` study kind: one case -> a ``cc`` row (the plan) and a ``contact`` row (the physics).

Runs in the executor's worker processes from plain data (case id and resolved parameters).  The
case's scenario names its plan function in :data:`PLANS`; the ``cc`` row is
:func:`.tasks.cc_result` of the plan, the ``contact`` row :func:`.tasks.run_task`.  With the
scenario's ``error_estimate`` (default on) the physics runs a second time at half the elements and
``x.disc_<name>`` holds ``|value(n) - value(n/2)|`` for the grasp outputs: a conservative
(first-order) discretisation-error bar, because the grasp quantities (a fold of the pull path,
contact arcs made of segments) do not converge smoothly enough for a Richardson estimate
(measured: ``docs/models.md``, "Whole-arm grasp").  The tip of the held state -- the position the
CC comparison judges -- gets the estimate every physics row of a sweep study gets
(:func:`workbench.models.discretization.estimate_from_values`): the half-mesh run and a
quarter-mesh run of the held state alone (close and release, no pull-out, carry or control) give
``x.disc_tip_error`` (Richardson with the contact model's declared order, ``registry.MODELS
["contact"].order``, lowered to the observed order of the three meshes when that is smaller),
``x.disc_order_observed``, ``x.disc_order`` and ``disc_status``.  With ``penalty_estimate`` (default on) it runs
once more at a tenth of the contact penalty: ``x.pen_<name> = |value(k) - value(k/10)|``, the
contact model's share of the error bar (the penalty results do not converge monotonically in k).
Every failure is a failed row with its reason; a failed estimate run only leaves its bars out.
Checked by ``tests/experiments/test_whole_arm_grasp.py`` (rows of a small study).
"""

from __future__ import annotations

import math
import time

import numpy as np
from dataclasses import replace
from typing import Any, Mapping, Sequence

from ... import registry
from ...study.build import build_options, resolve_case
from ...study.params import flatten_params
from ...study.rows import failed_rows, row_from_result

__all__ = ["evaluate_grasp_case", "evaluate_grasp_rows", "DISC_KEYS", "PLANS"]

#: grasp scenario -> "module:function" of its (robot, scenario params) -> (GraspPlan, GraspTask)
PLANS = {
    "whole_arm_wrap": "workbench.experiments.whole_arm_grasp.scenario:grasp_case",
    "harvester_scoop": "workbench.experiments.fruit_harvester.scoop:grasp_case",
}

#: Outputs that get a discretisation-error bar ``x.disc_<key>``.
DISC_KEYS = ("holding_force", "settle_dx", "settle_dz", "arc", "normal_force", "closed_normal_force",
             "carry_max_error", "carry_move_error", "grasp_centre_error", "grasp_centre_error_initial",
             "grasp_centre_error_x", "grasp_centre_error_z")


def _reason(e: BaseException) -> str:
    return f"{type(e).__name__}: {str(e).strip().replace(chr(10), ' ')[:500]}"


def plan_function(scenario_name: str):
    """The ``(robot, scenario params) -> (GraspPlan, GraspTask)`` function of a grasp scenario."""
    return registry.resolve(PLANS[scenario_name])


def _estimate(res, other, prefix: str, extras: dict) -> None:
    for k in DISC_KEYS:
        if k in res.extras and k in other.extras:
            d = abs(res.extras[k] - other.extras[k])
            if math.isfinite(d):
                extras[f"{prefix}_{k}"] = d


def _held_only(task):
    """The task without pull-out, carry and control: the held state (the row's shape) only."""
    return replace(task, pull_distance=0.0, carry=(), control=None)


def _tip_estimate(robot, plan, task, options, res, half) -> dict[str, Any]:
    """``x.disc_tip_error``, ``x.disc_order_observed``, ``x.disc_order`` and ``disc_status`` of the
    contact row ``res`` (module docstring); ``half`` is the half-mesh result or the reason it is missing."""
    from ...models.discretization import coarsened_options, estimate_columns, estimate_from_values
    from .tasks import run_task

    values, resolutions = [res.tip_position], [options.n_elements]
    status = "ok"
    quarter = coarsened_options(options, robot.n_sections, 4, dynamic=False)
    if isinstance(half, str):
        status = half
    else:
        values.append(half.tip_position)
        resolutions.append(coarsened_options(options, robot.n_sections, 2, dynamic=False).n_elements)
        if quarter is None or quarter.n_elements >= resolutions[-1]:
            status = "ok (no quarter-resolution mesh)"
        else:
            try:
                values.append(run_task(robot, plan, _held_only(task), quarter).tip_position)
                resolutions.append(quarter.n_elements)
            except Exception as e:  # noqa: BLE001 - a failed coarse solve limits the estimate only
                status = f"ok (quarter-resolution solve failed: {_reason(e)[:200]})"
    order = registry.table("models")["contact"].order
    est = estimate_from_values(values, resolutions, float("nan") if order is None else order,
                               10.0 * options.newton_tolerance * max(robot.length, 1e-3), status)
    return estimate_columns(est)


def _physics(robot, plan, task, options, error_estimate: bool, soft=None):
    """The contact row and its estimate cells; with ``error_estimate`` also the half-mesh run
    (``x.disc_*``, and with a quarter-mesh held state the tip estimate, :func:`_tip_estimate`), with
    ``soft`` (the case's ``(plan, task)`` at a tenth of the contact penalty) the penalty run
    (``x.pen_*``, and ``x.pen_tip = |tip(k) - tip(k/10)|`` [m]).  An estimate run that fails leaves
    its bars out and sets ``x.disc_failed`` / ``x.pen_failed`` (the tip estimate's status says why)."""
    from ...models.discretization import coarsened_options
    from .tasks import run_task

    res = run_task(robot, plan, task, options)
    extras = dict(res.extras)
    cols: dict[str, Any] = {}
    runs = []
    half_opt = coarsened_options(options, robot.n_sections, 2, dynamic=False)
    if error_estimate and half_opt is not None:
        runs.append(("disc", plan, task, half_opt))
    elif error_estimate:
        cols = _tip_estimate(robot, plan, task, options, res, f"cannot coarsen {options.n_elements} elements by 2 "
                                                             f"({robot.n_sections} section(s))")
    if soft is not None:
        runs.append(("pen", soft[0], soft[1], options))
    for prefix, p, t, opt in runs:
        try:
            other = run_task(robot, p, t, opt)
        except Exception as e:  # noqa: BLE001 - ModelFailure, SolverError: the bars are left out
            extras[f"{prefix}_failed"] = 1.0
            if prefix == "disc":
                cols = _tip_estimate(robot, plan, task, options, res,
                                     f"coarse solve ({opt.n_elements} elements) failed: {_reason(e)[:200]}")
            continue
        _estimate(res, other, prefix, extras)
        if prefix == "disc":
            cols = _tip_estimate(robot, plan, task, options, res, other)
        else:
            extras["pen_tip"] = float(np.linalg.norm(np.asarray(res.tip_position) - np.asarray(other.tip_position)))
    return replace(res, extras=extras), cols


def evaluate_grasp_case(case_id: str, params: Mapping[str, Any], models: Sequence[str]) -> list[dict[str, Any]]:
    """Rows of one case (never raises): ``cc`` and/or ``contact`` (module docstring)."""
    from ...models import quiet_if_loaded
    from .tasks import cc_result

    try:
        robot, ran = resolve_case(params)
        options = build_options(ran["solver"])
        scen = dict(ran["scenario"])
        error_estimate = bool(scen.pop("error_estimate", True))
        penalty_estimate = bool(scen.pop("penalty_estimate", True))
        make = plan_function(scen["name"])
        plan, task = make(robot, scen)
        soft = None
        if penalty_estimate and "contact" in models:
            soft = make(robot, {**scen, "contact_stiffness": 0.1 * task.law.stiffness})
    except Exception as e:  # noqa: BLE001 - recorded as the case's failure
        return failed_rows(case_id, params, models, f"building the case failed: {_reason(e)}")
    flat = flatten_params(ran)
    rows = []
    for name in models:
        t0 = time.perf_counter()
        try:
            with quiet_if_loaded():
                if name == "cc":
                    res, cols = cc_result(robot, plan, options), {}
                else:
                    res, cols = _physics(robot, plan, task, options, error_estimate, soft)
            rows.append(row_from_result(res, case_id, name, ran, robot, time.perf_counter() - t0, flat))
            if name != "cc" and rows[-1]["status"] == "ok":
                rows[-1].update(cols)
        except Exception as e:  # noqa: BLE001 - ModelFailure, SolverError, bugs: recorded
            rows.append(failed_rows(case_id, ran, [name], _reason(e), time.perf_counter() - t0, flat)[0])
    return rows


def evaluate_grasp_rows(payload: tuple) -> list[dict[str, Any]]:
    """The task function of the grasp kind: the rows of one unit ``payload = (case_id, params, models)``."""
    case_id, params, models = payload
    return evaluate_grasp_case(case_id, params, models)
