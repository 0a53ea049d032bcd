"""Result-table rows: a model's result as one row, failed rows, and the one non-finite rule.

Every study kind writes the row schema of ``docs/architecture.md`` ("Result table"): the keys
``case_id``, ``model``, the case's ``p.*`` parameters, ``status`` (``ok`` | ``failed``),
``error`` (the reason), ``failure`` (why: :data:`~workbench.study.outcomes.FAILURE_KINDS`, empty
when ok), ``wall_time`` and the results.  The same rule marks a row failed for
both kinds (:func:`fail_non_finite`): a non-finite number in ``positions``, ``tip_frame``,
``length_change``, ``tip_twist``, a ``series.*`` or an ``x.*`` cell, or tendon tensions that are
partly NaN (all-NaN means "this model predicts no forces", e.g. CC kinematics in length mode).
The discretisation-error estimate's cells (``x.disc_*``) are exempt: NaN there means "no
estimate" and ``disc_status`` says why (:mod:`workbench.study.estimate`).

Checked by ``tests/study/test_evaluate.py`` (NaN results -> failed rows), ``tests/study/test_rows.py``
and ``tests/motion/test_motion_run.py`` (failed IK rows).
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

import numpy as np

from .params import flatten_params

__all__ = ["failed_rows", "fail_non_finite", "non_finite_cells", "row_from_result"]


def _base_row(case_id: str, model: str, params: Mapping[str, Any], flat: Mapping[str, Any] | None = None
              ) -> dict[str, Any]:
    return {"case_id": case_id, "model": model, **(flat if flat is not None else flatten_params(params))}


def failed_rows(case_id: str, params: Mapping[str, Any], models: Sequence[str], reason: str,
                wall_time: float = float("nan"), flat: Mapping[str, Any] | None = None,
                extra: Mapping[str, Any] | None = None, failure: str = "model") -> list[dict[str, Any]]:
    """One failed row per model (a case that could not be built, a crashed worker, a failed target).

    Parameters
    ----------
    case_id : str
    params : dict
        The case's parameters (flattened into ``p.*`` unless ``flat`` is given).
    models : sequence of str
    reason : str
        The ``error`` cell.
    wall_time : float
        Seconds spent (NaN: unknown, e.g. the worker died).
    flat : dict, optional
        ``flatten_params(params)``, when the caller has it already.
    extra : dict, optional
        Further cells of every row (e.g. ``robot_length``).
    failure : str
        The ``failure`` cell: one of :data:`~workbench.study.outcomes.FAILURE_KINDS`.
    """
    flat = flatten_params(params) if flat is None else flat
    return [{**_base_row(case_id, m, params, flat), **(extra or {}), "status": "failed", "error": reason,
             "failure": failure, "wall_time": wall_time} for m in models]


def _not_finite(cell: Any) -> bool:
    if cell is None:
        return False
    if type(cell) is list:
        try:  # the cells are flat lists of floats: their sum is finite iff every term is (a NaN or
            # an infinity propagates; finite terms overflow only beyond ~1e308, and then the exact check runs)
            if math.isfinite(sum(cell)):
                return False
        except TypeError:  # not numbers (nested lists, None): the exact check decides
            pass
    return not np.isfinite(np.asarray(cell, dtype=float)).all()


def non_finite_cells(row: Mapping[str, Any]) -> list[str]:
    """The result cells of ``row`` that break the finite-result rule (module docstring), in message order.

    Order: ``positions``, ``tip_frame``, ``tendon_tensions``, ``length_change``, ``tip_twist``,
    then the ``series.*`` and ``x.*`` cells in row order.  Cells the row does not have are skipped.
    """
    bad = [k for k in ("positions", "tip_frame") if _not_finite(row.get(k))]
    tens = row.get("tendon_tensions")
    if tens is not None:
        t = np.asarray(tens, dtype=float)
        if t.size and not np.isfinite(t).all() and not np.isnan(t).all():
            bad.append("tendon_tensions")
    bad += [k for k in ("length_change", "tip_twist") if k in row and not math.isfinite(row[k])]
    series: list[str] = []
    extras: list[str] = []
    for k in row:  # one pass over the (mostly ``p.*``) keys: a row has ~140 of them
        if not isinstance(k, str) or k[:1] not in "sx":
            continue
        if k.startswith("series."):
            if _not_finite(row[k]):
                series.append(k)
        elif k.startswith("x.") and not k.startswith("x.disc_") and not math.isfinite(float(row[k])):
            extras.append(k)
    return bad + series + extras


def fail_non_finite(row: dict[str, Any]) -> dict[str, Any]:
    """Mark an ``ok`` row failed (``"non-finite result in <cells>"``) when :func:`non_finite_cells` finds any.

    A row that has failed already keeps its reason.  Returns ``row`` (changed in place).
    """
    if row.get("status") == "ok":
        bad = non_finite_cells(row)
        if bad:
            row["status"] = "failed"
            row["error"] = f"non-finite result in {', '.join(bad)}"
            row["failure"] = "model"
    return row


def _arr(x) -> list[float] | None:
    if x is None:
        return None
    return np.asarray(x, dtype=float).reshape(-1).tolist()


def _tip_world(T: np.ndarray, robot) -> dict[str, float]:
    """``tip_world_x/y/z``: the tip position in the world frame (``robot.base_rotation``/``base_position``)."""
    from ..robot.frames import base_points_to_world

    w = base_points_to_world(T[:3, 3], robot.base_rotation, robot.base_position)
    return {"tip_world_x": float(w[0]), "tip_world_y": float(w[1]), "tip_world_z": float(w[2])}


def row_from_result(res, case_id: str, model: str, params: Mapping[str, Any], robot,
                    wall_time: float, flat: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Flatten a :class:`~workbench.models.PhysicsResult` into a row of the sweep kind.

    Non-finite numbers make the row ``failed`` (:func:`fail_non_finite`), then a solver that did
    not converge (``"not converged: <message>"``).  The private key ``_shapes`` carries the array
    shapes to the store (:class:`~workbench.study.store.ResultStore` pops it).
    """
    T = np.asarray(res.tip_frame, dtype=float)
    row = {
        **_base_row(case_id, model, params, flat),
        "status": "ok",
        "error": "",
        "failure": "",
        "wall_time": float(wall_time),
        "robot_length": float(robot.length),
        "robot_gravity": float(np.linalg.norm(robot.gravity)),
        "tip_x": float(T[0, 3]), "tip_y": float(T[1, 3]), "tip_z": float(T[2, 3]),  # base frame
        **_tip_world(T, robot),
        "tip_frame": _arr(T),
        "length_change": float(res.length_change),
        "tip_twist": float(res.tip_twist),
        "converged": bool(res.solver.converged),
        "iterations": int(res.solver.iterations),
        "path_steps": int(res.solver.path_steps),
        "path_event": str(res.solver.path_event),
        "path_event_fraction": float(res.solver.path_event_fraction),
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
    fail_non_finite(row)
    if row["status"] == "ok" and not res.solver.converged:
        row["status"] = "failed"
        row["error"] = f"not converged: {res.solver.message}".rstrip(": ")
        row["failure"] = "model"
    return row
