"""Per-case evaluation of a closed-loop study: plain data in, result-table rows out.

A case is one robot / load / controller configuration run along the whole path (the ``closed_loop``
scenario's line or grasp approach).  Rows (the row schema of ``docs/architecture.md``):

``plan``
    The controller on its own CC model (:func:`.controller.cc_plan`): the CC shape at the last
    sample; ``series.tip_error`` is the plan's own tracking error.
``<plant>`` (each model of ``study.models``)
    The open-loop replay: the plan's cables pushed through the plant, one static solve per sample.
``<plant>_closed_loop``
    The controller in the loop on that plant (:func:`.controller.run_closed_loop`).

Every row's standard cells are the plant's (or the plan's) state at the last sample, base frame;
``series.target``, ``series.tip_position`` (m, 3) [m], ``series.tip_error`` (m,) [m],
``series.kappa`` (m, n) [1/m], ``series.cable_changes`` (m, n_tendons) [m], for the closed loop also
``series.step_error`` (m * steps,) [m]; extras ``x.max_tracking_error``, ``x.rms_tracking_error``,
``x.final_tracking_error`` [m], ``x.max_tension`` [N], ``x.plant_solves`` (``wall_time``: the time in the plant).  A
plant failure fails its row with the sample and step it happened at; the other rows go on.

Discretisation error (cells ``x.disc_tip_error`` [m], ``x.disc_order_observed``,
``x.disc_order``, ``disc_status``, :func:`disc_columns`): the co-simulation is a sequence of static
equilibria, so there is no time step to refine; what remains is the plant's mesh.  The ``plan`` row
and the ``cc`` plant's rows are closed-form arcs (error 0).  A plant listed in ``[solver]
error_estimate_exempt`` (the 16-joint spring-link chain: one link per physical joint, the robot's
own structure, as in the hannan_walker study) gets 0 and the exemption as its status; any other
plant gets no estimate (NaN, and the status says so), so the report does not certify it.

Plants: ``spring_link`` runs in a warm-started :class:`workbench.physics.spring_link.session.StaticSession`
(the same equilibria as fresh solves, in a fraction of the time: ``docs/models.md``, "Closed loop");
every other model is called fresh per control step through its registered ``run``.  Checked by
``tests/experiments/test_closed_loop.py``.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import replace
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from ...study.build import build_load, build_options, build_pipeline_options, resolve_case
from ...study.params import flatten_params
from ...study.rows import failed_rows, row_from_result
from .controller import ControllerSettings, LoopTrace, cc_plan, run_closed_loop, run_open_loop
from .plants import cc_result, hw_cable_map, model_plant
from .scenario import CONTROLLER_KEYS, joint_count, loop_path, null_space_target

__all__ = ["PLAN", "CLOSED_SUFFIX", "CLOSED_FORM_STATUS", "row_models", "disc_columns", "evaluate_closed_loop_case",
           "evaluate_closed_loop_rows"]

PLAN = "plan"
CLOSED_SUFFIX = "_closed_loop"


#: ``disc_status`` of the rows computed from closed-form CC arcs (the plan, the ``cc`` plant).
CLOSED_FORM_STATUS = "closed form: CC arcs, no discretisation"


def disc_columns(row_model: str, pipeline) -> dict[str, Any]:
    """The discretisation-error cells of one row of this kind (module docstring)."""
    from ...study.estimate import EXEMPT_STATUS

    plant = row_model[: -len(CLOSED_SUFFIX)] if row_model.endswith(CLOSED_SUFFIX) else row_model
    nan = float("nan")
    if plant in (PLAN, "cc"):
        return {"x.disc_tip_error": 0.0, "x.disc_order_observed": nan, "x.disc_order": nan,
                "disc_status": CLOSED_FORM_STATUS}
    if plant in pipeline.error_estimate_exempt:
        return {"x.disc_tip_error": 0.0, "x.disc_order_observed": nan, "x.disc_order": nan,
                "disc_status": EXEMPT_STATUS}
    return {"x.disc_tip_error": nan, "x.disc_order_observed": nan, "x.disc_order": nan,
            "disc_status": f"no estimate: the closed-loop kind re-solves no {plant!r} plant at a coarser mesh "
                           f"(exempt it in [solver] error_estimate_exempt only if its mesh is the robot's structure)"}


def row_models(plants: Sequence[str]) -> tuple[str, ...]:
    """The rows every case writes: ``plan``, then per plant its open- and closed-loop rows."""
    out = [PLAN]
    for m in plants:
        out += [m, m + CLOSED_SUFFIX]
    return tuple(out)


class _SessionPlant:
    """``spring_link`` as a warm-started plant (first call builds the chain)."""

    def __init__(self, robot, options, pretension: float) -> None:
        self.robot, self.options, self.pretension, self.session = robot, options, pretension, None

    def __call__(self, cables: np.ndarray):
        from ...physics.spring_link.session import StaticSession
        from ...robot import LoadCase, TendonActuation

        if self.session is None:
            act = TendonActuation("length", tuple(float(c) for c in cables), pretension=self.pretension)
            self.session = StaticSession(self.robot, LoadCase(actuation=act), self.options)
            return self.session.result
        return self.session.solve(cables)


def _plant(name: str, robot, options, pretension: float, model_lookup: Callable | None) -> Callable:
    if name == "spring_link" and model_lookup is None:
        return _SessionPlant(robot, options, pretension)
    if model_lookup is None:
        from ...models import get_model as model_lookup
    return model_plant(model_lookup(name), robot, options, pretension)


def _series(trace_tip, error, kappa, cables, path) -> dict[str, np.ndarray]:
    return {"target": np.asarray(path), "tip_position": np.asarray(trace_tip), "tip_error": np.asarray(error),
            "kappa": np.asarray(kappa), "cable_changes": np.asarray(cables)}


def _extras(error: np.ndarray, tensions: np.ndarray | None = None) -> dict[str, float]:
    out = {"max_tracking_error": float(np.max(error)), "rms_tracking_error": float(np.sqrt(np.mean(error ** 2))),
           "final_tracking_error": float(error[-1])}
    t = None if tensions is None else np.asarray(tensions, dtype=float)
    if t is not None and np.isfinite(t).any():  # CC rows predict no tensions (all NaN): no extra
        out["max_tension"] = float(np.nanmax(t))
    return out


def _trace_row(trace: LoopTrace, name: str, ctx: Mapping[str, Any], cable_map: Callable, closed: bool) -> dict:
    last = trace.results[-1]
    cables = np.array([cable_map(k) for k in trace.kappa])
    series = _series(trace.tip, trace.error, trace.kappa, cables, ctx["path"])
    if closed:
        series["step_error"] = trace.step_error
    tens = np.array([r.tendon_tensions for r in trace.results])
    extras = {**_extras(trace.error, tens), "plant_solves": float(trace.plant_solves)}
    res = replace(last, model=name, series=series, extras=extras,
                  solver=replace(last.solver, iterations=trace.plant_solves, wall_time=trace.plant_time))
    return row_from_result(res, ctx["case_id"], name, ctx["ran"], ctx["robot"], trace.plant_time, ctx["flat"])


def _loop_row(name: str, run_loop: Callable, plant: Callable, ctx: Mapping[str, Any], cable_map: Callable,
              closed: bool) -> dict:
    t0 = time.perf_counter()
    try:
        trace = run_loop(plant, cable_map, ctx["path"], ctx["ell"], ctx["settings"], ctx["kappa_d"])
        return _trace_row(trace, name, ctx, cable_map, closed)
    except Exception as e:  # noqa: BLE001 - PlantFailure, bugs: a failed row with the reason
        where = traceback.format_exc(limit=1).splitlines()[-1]
        return failed_rows(ctx["case_id"], ctx["ran"], [name], f"{type(e).__name__}: {e} ({where})"[:600],
                           time.perf_counter() - t0, ctx["flat"])[0]


def _plan_row(ctx: Mapping[str, Any], cable_map: Callable) -> dict:
    t0 = time.perf_counter()
    kappa, _ = cc_plan(ctx["path"], ctx["ell"], ctx["settings"], ctx["kappa_d"])
    robot = ctx["robot"]
    tips = np.array([cc_result(k, robot, 2).tip_position for k in kappa])
    error = np.linalg.norm(tips - ctx["path"], axis=1)
    res = cc_result(kappa[-1], robot, ctx["options"].n_stations)
    res = replace(res, series=_series(tips, error, kappa, np.array([cable_map(k) for k in kappa]), ctx["path"]),
                  extras={**_extras(error), "control_steps": float(kappa.shape[0] * ctx["settings"].steps_per_sample)})
    return row_from_result(res, ctx["case_id"], PLAN, ctx["ran"], robot, time.perf_counter() - t0, ctx["flat"])


def evaluate_closed_loop_case(case_id: str, params: Mapping[str, Any], plants: Sequence[str],
                              model_lookup: Callable | None = None) -> list[dict[str, Any]]:
    """The rows of one case (see the module docstring); never raises."""
    models = row_models(plants)
    try:
        robot, ran = resolve_case(params)
        load = build_load(robot, ran["load"])
        sc = ran["scenario"]
        ctx = {"case_id": case_id, "ran": ran, "robot": robot, "flat": flatten_params(ran),
               "options": build_options(ran["solver"]), "pipeline": build_pipeline_options(ran["solver"]),
               "path": loop_path(sc), "ell": robot.section_lengths,
               "settings": ControllerSettings(**{k: sc[k] for k in CONTROLLER_KEYS}),
               "kappa_d": null_space_target(robot, sc)}
        pretension = float(load.actuation.pretension)
        cable_map = hw_cable_map(robot, joint_count(robot))
    except Exception as e:  # noqa: BLE001 - recorded as the case's failure reason
        return failed_rows(case_id, params, models, f"building the case failed: {type(e).__name__}: {e}")
    try:
        rows = [_plan_row(ctx, cable_map)]
    except Exception as e:  # noqa: BLE001
        rows = failed_rows(case_id, ctx["ran"], [PLAN], f"plan: {type(e).__name__}: {e}", flat=ctx["flat"])
    for m in plants:
        for name, loop, closed in ((m, run_open_loop, False), (m + CLOSED_SUFFIX, run_closed_loop, True)):
            plant = _plant(m, robot, ctx["options"], pretension, model_lookup)
            rows.append(_loop_row(name, loop, plant, ctx, cable_map, closed))
    for r in rows:
        if r.get("status") == "ok" and ctx["pipeline"].error_estimate != "none":
            r.update(disc_columns(str(r["model"]), ctx["pipeline"]))
    return rows


def evaluate_closed_loop_rows(payload: tuple) -> list[dict[str, Any]]:
    """The kind's task: ``(case_id, params, plants)`` -> the rows of that case."""
    case_id, params, plants = payload
    return evaluate_closed_loop_case(case_id, params, plants)
