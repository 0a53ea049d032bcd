"""Per-case evaluation, run inside workers from plain data only.

:func:`evaluate_case` builds the :class:`~workbench.robot.Robot` from its preset, the
:class:`~workbench.robot.LoadCase`, the :class:`~workbench.models.SolverOptions`, calls every
model (each in its own ``try``: one model failing does not stop the others) and flattens each
:class:`~workbench.models.PhysicsResult` into one result-table row (``docs/architecture.md``).
Nothing here imports Exudyn; models are looked up (and imported) lazily through
``model_lookup`` (default :func:`workbench.models.get_model`).
"""

from __future__ import annotations

import contextlib
import math
import sys
import time
import traceback
from typing import Any, Callable, Iterator, Mapping, Sequence

import numpy as np

from .expand import flatten_params
from .spec import canonical_json

__all__ = [
    "build_robot",
    "build_load",
    "build_options",
    "evaluate_case",
    "evaluate_payload",
    "evaluate_batch",
    "failed_rows",
    "row_from_result",
    "gravity_from_parameter",
]


def gravity_from_parameter(gamma: float, EI: float, mass_per_length: float, length: float) -> float:
    """Gravity magnitude g [m/s^2] for the self-weight parameter ``gamma = q L^3 / EI``.

    ``q = m' g`` is the backbone weight per length, so ``g = gamma EI / (m' L^3)``.

    Raises
    ------
    ValueError
        ``mass_per_length`` is zero (gamma is then undefined) or inputs are not finite.
    """
    if not (math.isfinite(gamma) and gamma >= 0):
        raise ValueError(f"gravity_parameter must be finite and >= 0, got {gamma}")
    if not mass_per_length > 0:
        raise ValueError("gravity_parameter needs a backbone with mass (mass per length > 0)")
    return float(gamma) * float(EI) / (float(mass_per_length) * float(length) ** 3)


def build_robot(robot_params: Mapping[str, Any], derived: Mapping[str, Any] | None = None):
    """Robot from ``{"preset": name, **preset parameters}`` and the derived parameters.

    ``derived["gravity_parameter"]`` (gamma) sets the preset's ``gravity`` from the backbone of a
    uniform robot (every section the same cross-section, no taper); disks and payload are not
    part of ``q``.
    """
    from ..robot.presets import build_preset

    params = dict(robot_params)
    name = params.pop("preset")
    gamma = (derived or {}).get("gravity_parameter")
    robot = build_preset(name, **params)
    if gamma is not None:
        cs = robot.sections[0].cross_section
        if any(s.cross_section != cs or s.cross_section_tip is not None for s in robot.sections):
            raise ValueError("derived.gravity_parameter needs a uniform robot (same cross-section, no taper)")
        params["gravity"] = gravity_from_parameter(gamma, cs.EI, cs.mass_per_length, robot.length)
        robot = build_preset(name, **params)
    return robot


def build_load(robot, load: Mapping[str, Any], arc_actuation: Callable | None = None):
    """LoadCase from the ``[load]`` parameters of one case.

    ``bend_angle`` (total angle per section, scalar or per section) and ``bend_plane`` become
    ``kappa_j = bend_angle_j / L_j`` and ``phi_j`` and are translated into tendon commands by
    ``arc_actuation`` (default ``workbench.models.cc.actuation_from_arc``).
    """
    from dataclasses import replace

    from ..robot import LoadCase, TendonActuation

    mode = load["mode"]
    act = None
    if load.get("bend_angle") is not None:
        if arc_actuation is None:
            from ..models.cc import actuation_from_arc as arc_actuation
        ns = robot.n_sections
        kappa = np.broadcast_to(np.asarray(load["bend_angle"], float), (ns,)) / robot.section_lengths
        phi = np.broadcast_to(np.asarray(load.get("bend_plane", 0.0), float), (ns,)).copy()
        act = arc_actuation(robot, kappa, phi, mode, pretension=load.get("pretension", 0.0))
    elif load.get("tensions") is not None:
        act = TendonActuation("tension", tuple(load["tensions"]), pretension=load.get("pretension", 0.0))
    elif load.get("length_changes") is not None:
        act = TendonActuation("length", tuple(load["length_changes"]), pretension=load.get("pretension", 0.0))
    if act is not None:
        st, rd = load.get("start_delays"), load.get("ramp_durations")
        if st is not None or rd is not None:
            act = replace(act, start_times=None if st is None else tuple(st),
                          ramp_durations=None if rd is None else tuple(rd))
        act.check_against(robot)
    return LoadCase(
        actuation=act,
        tip_force=tuple(load.get("tip_force", (0.0, 0.0, 0.0))),
        tip_torque=tuple(load.get("tip_torque", (0.0, 0.0, 0.0))),
        analysis=load.get("analysis", "static"),
        duration=load.get("duration", 0.0),
        ramp_time=load.get("ramp_time", 1.0),
    )


def build_options(solver: Mapping[str, Any]):
    from ..models.result import SolverOptions

    return SolverOptions(**solver)


def _base_row(case_id: str, model: str, params: Mapping[str, Any], flat: Mapping[str, Any] | None = None
              ) -> dict[str, Any]:
    return {"case_id": case_id, "model": model, **(flat if flat is not None else flatten_params(params))}


def failed_rows(case_id: str, params: Mapping[str, Any], models: Sequence[str], reason: str,
                wall_time: float = float("nan"), flat: Mapping[str, Any] | None = None) -> list[dict[str, Any]]:
    """One failed row per model (used for build failures and for crashed workers)."""
    flat = flatten_params(params) if flat is None else flat
    return [{**_base_row(case_id, m, params, flat), "status": "failed", "error": reason, "wall_time": wall_time}
            for m in models]


def _arr(x) -> list[float] | None:
    if x is None:
        return None
    return np.asarray(x, dtype=float).reshape(-1).tolist()


def row_from_result(res, case_id: str, model: str, params: Mapping[str, Any], robot,
                    wall_time: float, flat: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Flatten a PhysicsResult into a row; non-finite numbers make the row ``failed``."""
    T = np.asarray(res.tip_frame, dtype=float)
    bad = [k for k, a in (("positions", res.positions), ("tip_frame", T)) if not np.isfinite(a).all()]
    # Tendon tensions: NaN means "this model predicts no forces" (CC kinematics in length mode)
    # and is allowed only when the whole vector is NaN; a partly NaN vector is a broken result.
    tens = np.asarray(res.tendon_tensions, dtype=float)
    if tens.size and not np.isfinite(tens).all() and not np.isnan(tens).all():
        bad.append("tendon_tensions")
    row = {
        **_base_row(case_id, model, params, flat),
        "status": "ok",
        "error": "",
        "wall_time": float(wall_time),
        "robot_length": float(robot.length),
        "robot_gravity": float(np.linalg.norm(robot.gravity)),
        "tip_x": float(T[0, 3]), "tip_y": float(T[1, 3]), "tip_z": float(T[2, 3]),
        "tip_frame": _arr(T),
        "length_change": float(res.length_change),
        "tip_twist": float(res.tip_twist),
        "converged": bool(res.solver.converged),
        "iterations": int(res.solver.iterations),
        "stations": _arr(res.stations),
        "positions": _arr(res.positions),
        "tendon_tensions": _arr(res.tendon_tensions),
        "joint_angles": _arr(res.joint_angles),
        "time": _arr(res.time),
    }
    shapes: dict[str, list[int]] = {"tip_frame": [4, 4], "positions": [-1, 3]}
    if res.joint_angles is not None:
        ja = np.asarray(res.joint_angles)
        shapes["joint_angles"] = [-1, *ja.shape[1:]]
    for name, s in dict(res.series).items():
        a = np.asarray(s, dtype=float)
        row[f"series.{name}"] = a.reshape(-1).tolist()
        shapes[f"series.{name}"] = [-1, *a.shape[1:]]
    for name, v in dict(res.extras).items():
        row[f"x.{name}"] = float(v)
    row["_shapes"] = shapes
    bad += [k for k in ("length_change", "tip_twist") if not math.isfinite(row[k])]
    bad += [f"series.{k}" for k, v in dict(res.series).items() if not np.isfinite(np.asarray(v, float)).all()]
    bad += [f"x.{k}" for k, v in dict(res.extras).items() if not math.isfinite(float(v))]
    if bad:
        row["status"] = "failed"
        row["error"] = f"non-finite result in {', '.join(bad)}"
    elif not res.solver.converged:
        row["status"] = "failed"
        row["error"] = f"not converged: {res.solver.message}".rstrip(": ")
    return row


@contextlib.contextmanager
def _quiet_exudyn_if_loaded() -> Iterator[None]:
    """Exudyn console output off (process-global flag: saved and restored), if Exudyn is loaded."""
    exu = sys.modules.get("exudyn")
    if exu is None:
        yield
        return
    old = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        yield
    finally:
        exu.config.printToConsole = old


def _reason(e: BaseException) -> str:
    msg = str(e).strip().replace("\n", " ")
    where = traceback.extract_tb(e.__traceback__)[-1] if e.__traceback__ else None
    loc = f" (at {where.filename.rsplit('/', 1)[-1]}:{where.lineno})" if where else ""
    return f"{type(e).__name__}: {msg[:500]}{loc}"


def evaluate_case(case_id: str, params: Mapping[str, Any], models: Sequence[str],
                  model_lookup: Callable[[str], Callable] | None = None,
                  arc_actuation: Callable | None = None,
                  robot_cache: dict[str, Any] | None = None) -> list[dict[str, Any]]:
    """Evaluate one case for every model; returns one row per model (never raises).

    Parameters
    ----------
    case_id : str
    params : dict
        Resolved case parameters (see :class:`~workbench.study.expand.Case`).
    models : sequence of str
    model_lookup : callable, optional
        ``name -> run(robot, load, options)``; default :func:`workbench.models.get_model`.
        Must be picklable (a module-level function) when used with process executors.
    arc_actuation : callable, optional
        Replaces ``workbench.models.cc.actuation_from_arc`` (tests).
    robot_cache : dict, optional
        Memo of built robots keyed by their parameters (robots are frozen), shared by the
        cases of one batch.
    """
    if model_lookup is None:
        from ..models import get_model as model_lookup
    try:
        if robot_cache is None:
            robot = build_robot(params["robot"], params.get("derived"))
        else:
            key = canonical_json([params["robot"], params.get("derived")])
            robot = robot_cache.get(key)
            if robot is None:
                robot = robot_cache[key] = build_robot(params["robot"], params.get("derived"))
        load_params = params["load"]
        if params.get("scenario"):
            from .scenarios import load_with_scenario

            load_params = load_with_scenario(robot, load_params, params["scenario"])
        load = build_load(robot, load_params, arc_actuation)
        options = build_options(params["solver"])
    except Exception as e:  # noqa: BLE001 - recorded as the case's failure reason
        return failed_rows(case_id, params, models, f"building the case failed: {_reason(e)}")
    flat = flatten_params(params)
    rows = []
    for name in models:
        t0 = time.perf_counter()
        try:
            fn = model_lookup(name)
            with _quiet_exudyn_if_loaded():
                res = fn(robot, load, options)
            wall = time.perf_counter() - t0
            rows.append(row_from_result(res, case_id, name, params, robot, wall, flat))
        except Exception as e:  # noqa: BLE001 - ModelFailure, exudyn.SolverError, bugs: all recorded
            rows.append(failed_rows(case_id, params, [name], _reason(e), time.perf_counter() - t0, flat)[0])
    return rows


def evaluate_payload(payload: tuple) -> list[dict[str, Any]]:
    """``evaluate_case(*payload)``: a picklable task function for one case."""
    return evaluate_case(*payload)


def evaluate_batch(batch: tuple) -> list[list[dict[str, Any]]]:
    """The task function the runner submits: several cases, one list of rows per case.

    ``batch = (cases, models, model_lookup, arc_actuation)`` with ``cases`` a list of
    ``(case_id, params)``.  Batching amortises the per-task cost of process executors; robots
    are built once per distinct robot parameter set within the batch.
    """
    cases, models, model_lookup, arc_actuation = batch
    cache: dict[str, Any] = {}
    return [evaluate_case(cid, params, models, model_lookup, arc_actuation, cache) for cid, params in cases]
