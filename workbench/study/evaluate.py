"""Per-case evaluation, run inside workers from plain data only.

:func:`evaluate_case` builds the :class:`~workbench.robot.Robot`, the
:class:`~workbench.robot.LoadCase` and the :class:`~workbench.models.SolverOptions` of a case
(:mod:`workbench.study.build`), calls every model (each in its own ``try``: one model failing
does not stop the others) and turns each :class:`~workbench.models.PhysicsResult` into one
result-table row (:mod:`workbench.study.rows`).  :func:`iter_case_rows` yields the rows one
model at a time; :func:`evaluate_rows` is the task function of the sweep study kind
(:data:`workbench.study.kinds.SWEEP`): the executors stream each row to the parent as soon as
it exists, so a model that crashes the process does not take the finished models' rows with
it.  With ``[solver] warm_start = true`` each model starts from the state of the nearest case of the
same model, robot and options solved before in this process (:data:`WARM`, a
:class:`~workbench.models.warm.WarmPool`); the row records that case's id in ``warm_from`` (``""``:
solved cold).  Robots are memoised per process (:data:`ROBOTS`, a bounded :class:`RobotMemo`: robots are
frozen values; the sweep kind's recorded parameters use the same memo).  Nothing here imports
Exudyn; models are looked up (and imported) lazily through ``model_lookup`` (default
:func:`workbench.models.get_model`).

Checked by ``tests/study/test_evaluate.py`` and ``tests/study/test_executors.py``.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import replace
from typing import Any, Callable, Iterator, Mapping, Sequence

from ..models.warm import WarmPool, warm_key
from .by_model import BY_MODEL, solver_for_model
from .build import build_load, build_options, build_pipeline_options, resolve_case
from .estimate import LazyCCResult, discretization_columns
from .params import flatten_params
from .rows import failed_rows, row_from_result

__all__ = ["ROBOTS", "RobotMemo", "WARM", "evaluate_batch", "evaluate_case", "evaluate_payload", "evaluate_rows",
           "iter_case_rows"]


def _reason(e: BaseException) -> str:
    msg = str(e).strip().replace("\n", " ")
    where = traceback.extract_tb(e.__traceback__)[-1] if e.__traceback__ else None
    loc = f" (at {where.filename.rsplit('/', 1)[-1]}:{where.lineno})" if where else ""
    return f"{type(e).__name__}: {msg[:500]}{loc}"


def evaluate_case(case_id: str, params: Mapping[str, Any], models: Sequence[str],
                  model_lookup: Callable[[str], Callable] | None = None,
                  robot_cache: dict[str, Any] | None = None) -> list[dict[str, Any]]:
    """Evaluate one case for every model; returns one row per model (never raises).

    Parameters
    ----------
    case_id : str
    params : dict
        Resolved case parameters (see :class:`~workbench.study.expand.Case`).
    models : sequence of str
    model_lookup : callable, optional
        ``name -> run(robot, load, options)``; default :func:`workbench.models.get_model` (the
        registry).  A caller's own models (tests: ``tests/study/study_fakes.py``).
    robot_cache : dict, optional
        Memo of built robots (and the parameters they were built with) keyed by their
        parameters (robots are frozen); default: this process's memo.

    Returns
    -------
    list of dict
        One row per model (:mod:`workbench.study.rows`); ok physics rows carry the
        discretisation-error estimate (``x.disc_*``, :mod:`workbench.study.estimate`; its coarse
        solves are not in ``wall_time``).  Its ``p.*`` cells are the parameters
        the case ran with (:func:`~workbench.study.build.resolve_case`): ``p.robot.*`` rebuild
        the robot that ran (``p.robot.gravity`` derived from ``derived.gravity_parameter``),
        ``p.load.*`` the load (a scenario's fields applied); ``case_id`` stays the hash of the
        parameters as configured.
    """
    return list(iter_case_rows(case_id, params, models, model_lookup, robot_cache))


class RobotMemo(dict):
    """Built robots keyed by their parameters; forgets everything once it holds ``maxsize`` entries.

    The argument ``robot_cache`` of :func:`~workbench.study.build.resolve_case`; checked by
    ``tests/study/test_evaluate.py``.
    """

    maxsize = 256

    def __setitem__(self, key: str, value: Any) -> None:
        if len(self) >= self.maxsize:
            self.clear()
        super().__setitem__(key, value)


#: This process's memo of built robots (workers build a robot once per parameter set).
ROBOTS = RobotMemo()
#: This process's solved states for warm starts (``[solver] warm_start = true``).
WARM = WarmPool()
_FLAT_ROBOTS: dict[int, tuple] = {}  # flat ``p.robot.*`` cells of the memoised robots' parameters (flatten_params)


def iter_case_rows(case_id: str, params: Mapping[str, Any], models: Sequence[str],
                   model_lookup: Callable[[str], Callable] | None = None,
                   robot_cache: dict[str, Any] | None = None) -> Iterator[dict[str, Any]]:
    """The rows of :func:`evaluate_case`, yielded one model at a time (never raises for a model)."""
    from ..models import quiet_if_loaded

    if model_lookup is None:
        from ..models import get_model as model_lookup
    try:
        # the rows record the parameters the case runs with (derived gravity, scenario load
        # fields applied); the case id stays the hash of the parameters as configured
        robot, ran = resolve_case(params, ROBOTS if robot_cache is None else robot_cache)
        load = build_load(robot, ran["load"])
        options = build_options(ran["solver"])
        pipeline = build_pipeline_options(ran["solver"])
    except Exception as e:  # noqa: BLE001 - recorded as the case's failure reason
        yield from failed_rows(case_id, params, models, f"building the case failed: {_reason(e)}")
        return
    flat = flatten_params(ran, _FLAT_ROBOTS)  # a memoised robot's cells are converted once
    cc_result = LazyCCResult(model_lookup, robot, load, _model_resolution("cc", options, ran, flat)[0])
    for name in models:
        t0 = time.perf_counter()
        opts, ran_m, flat_m = _model_resolution(name, options, ran, flat)
        try:
            fn = model_lookup(name)
            key, source, run_opts = _warm_options(name, robot, load, opts, pipeline.warm_start)
            with quiet_if_loaded():
                res = fn(robot, load, run_opts)
            wall = time.perf_counter() - t0
            row = row_from_result(res, case_id, name, ran_m, robot, wall, flat_m)
            if pipeline.warm_start:
                row["warm_from"] = source if res.extras.get("warm_started") == 1.0 else ""
                if row["status"] == "ok":
                    WARM.add(key, load, case_id, res.warm_state)
            if name == "cc":
                cc_result.set(res)
            if row["status"] == "ok":  # the discretisation-error estimate (study/estimate.py)
                with quiet_if_loaded():
                    row.update(discretization_columns(name, fn, robot, load, opts, res, cc_result, pipeline))
        except Exception as e:  # noqa: BLE001 - ModelFailure, exudyn.SolverError, bugs: all recorded
            kind = "memory" if isinstance(e, MemoryError) else "model"
            row = failed_rows(case_id, ran_m, [name], _reason(e), time.perf_counter() - t0, flat_m, failure=kind)[0]
            if pipeline.warm_start:
                row["warm_from"] = ""
        yield row


def _warm_options(name: str, robot, load, opts, warm: bool):  # noqa: ANN001, ANN202
    """``(key, source case id, options)`` of a solve: with ``warm``, the options carry the state of
    the nearest solved case in :data:`WARM` (:func:`~workbench.models.warm.warm_key`)."""
    if not warm:
        return None, "", opts
    key = warm_key(name, robot, load, opts)
    hit = WARM.nearest(key, load)
    if hit is None:
        return key, "", opts
    return key, hit[0], replace(opts, warm_state=hit[1])


def _model_resolution(name: str, options, ran: Mapping[str, Any], flat: Mapping[str, Any]):
    """Options, parameters and flat ``p.*`` cells of model ``name``: its ``[solver.by_model.<name>]``
    table applied (:func:`~workbench.study.by_model.solver_for_model`), so its rows record the
    settings it ran with (``p.solver.*``)."""
    own = (ran["solver"].get(BY_MODEL) or {}).get(name)
    if not own:
        return options, ran, flat
    solver = solver_for_model(ran["solver"], name)
    ran_m = {**ran, "solver": solver}
    return build_options(solver), ran_m, {**flat, **flatten_params({"solver": dict(own)})}


def evaluate_rows(payload: tuple) -> Iterator[dict[str, Any]]:
    """The sweep kind's task: ``payload = (case_id, params, models)``; yields rows (the registry's models)."""
    case_id, params, models = payload
    return iter_case_rows(case_id, params, models)


def evaluate_payload(payload: tuple) -> list[dict[str, Any]]:
    """``evaluate_case(*payload)``: a picklable task function for one case."""
    return evaluate_case(*payload)


def evaluate_batch(batch: tuple) -> list[list[dict[str, Any]]]:
    """Several cases, one list of rows per case (the task function before units; kept for callers).

    ``batch = (cases, models, model_lookup)`` with ``cases`` a list of ``(case_id, params)``
    (``model_lookup``: see :func:`evaluate_case`).  Batching amortises the per-task cost of
    process executors; robots are built once per distinct robot parameter set within the batch.
    """
    cases, models, model_lookup = batch
    cache: dict[str, Any] = {}
    return [evaluate_case(cid, params, models, model_lookup, cache) for cid, params in cases]
