"""One result row per (model, fold) of a calibration study: calibrate, predict the held-out rows, measure the errors.

:func:`calibration_row` runs one model's calibration on one fold (:mod:`.calibrate`, :mod:`.predict`)
and returns the row of ``docs/measurements.md`` ("Result rows"): the calibrated values with their
intervals (``calib.*``), the tip errors on the training rows, on the held-out rows and on the
fold's ``physics_test`` rows that every model predicts (``err.*``), every evaluated sample
(``sample.*``) and up to :data:`VIEW_SAMPLES` held-out backbones for the 3-D viewer (``view.*``).

Samples: CC is fitted on every training row of the fold and predicts every test row; a physics
model is fitted on ``physics_train`` and predicts ``physics_test``.  The viewer's samples are taken
from ``physics_test`` for every model (so CC and the physics models draw the same samples): a
farthest-point spread over the command space (:func:`spread_samples`).

Store layout: arrays are flat lists of floats with their shapes in the private ``_shapes`` key
(:class:`~workbench.study.store.ResultStore`); lists of strings (``calib.names``, ``calib.units``,
``calib.sources``) are JSON strings (the store has no list-of-string columns); booleans are
stored as 1.0 / 0.0.  A calibration that failed (a model evaluation failed) is a failed row with the
reason (``failure = "model"``); one that stopped at ``max_evaluations`` is an ok row with
``calib.converged`` false and scipy's message.

Checked by ``tests/measure/test_measure_kind.py``.
"""

from __future__ import annotations

import json
import time
from typing import Any, Mapping

import numpy as np

from ..study.rows import failed_rows
from .calibrate import CalibrationResult, calibrate_on, diff_step, evaluation_noise
from .predict import PredictionFailure, Predictor, model_options
from .types import SPLIT_CODES, CalibrationStudy, FoldRows

__all__ = ["VIEW_SAMPLES", "calibration_row", "error_stats", "spread_samples"]

#: held-out samples drawn in the 3-D viewer per row
VIEW_SAMPLES = 12


def error_stats(errors: np.ndarray, prefix: str) -> dict[str, float]:
    """``{prefix}_rms``, ``_median``, ``_p95``, ``_max`` of the tip errors ``errors`` (n,) [m] (NaN: none)."""
    e = np.asarray(errors, dtype=float)
    if e.size == 0:
        return {f"{prefix}_{k}": float("nan") for k in ("rms", "median", "p95", "max")}
    return {f"{prefix}_rms": float(np.sqrt(np.mean(e**2))), f"{prefix}_median": float(np.median(e)),
            f"{prefix}_p95": float(np.percentile(e, 95)), f"{prefix}_max": float(e.max())}


def spread_samples(commands: np.ndarray, k: int) -> np.ndarray:
    """Positions (into ``commands``) of up to ``k`` samples spread over the command space.

    Farthest-point sampling on the commands scaled by their spread per column, from the sample
    with the largest command; deterministic.  Returned sorted.
    """
    c = np.asarray(commands, dtype=float)
    n = c.shape[0]
    if n == 0 or k <= 0:
        return np.zeros(0, dtype=int)
    span = np.ptp(c, axis=0)
    c = c / np.where(span > 0, span, 1.0)
    pick = [int(np.argmax(np.linalg.norm(c, axis=1)))]
    d = np.linalg.norm(c - c[pick[0]], axis=1)
    while len(pick) < min(k, n):
        j = int(np.argmax(d))
        if d[j] <= 0:
            break
        pick.append(j)
        d = np.minimum(d, np.linalg.norm(c - c[j], axis=1))
    return np.sort(np.asarray(pick, dtype=int))


def _parameter_cells(study: CalibrationStudy) -> dict[str, Any]:
    ps = study.calibration.parameters
    return {
        "calib.names": json.dumps([p.name for p in ps]), "calib.units": json.dumps([p.unit for p in ps]),
        "calib.sources": json.dumps([p.source for p in ps]),
        "calib.initial": [float(p.initial) for p in ps], "calib.lower": [float(p.lower) for p in ps],
        "calib.upper": [float(p.upper) for p in ps], "calib.confidence": float(study.calibration.confidence),
    }


def _result_cells(res: CalibrationResult, seconds_per_evaluation: float) -> dict[str, Any]:
    return {
        "calib.converged": bool(res.success), "calib.message": res.message, "calib.evaluations": int(res.evaluations),
        "calib.seconds_per_evaluation": float(seconds_per_evaluation), "calib.values": res.values.tolist(),
        "calib.ci_low": res.ci_low.tolist(), "calib.ci_high": res.ci_high.tolist(),
        "calib.at_bound": [bool(b) for b in res.at_bound], "calib.residual_sd": float(res.sigma),
        "calib.covariance": (res.covariance if res.covariance is not None
                             else np.full((res.values.size,) * 2, np.nan)).reshape(-1).tolist(),
    }


def _view_cells(study: CalibrationStudy, predictor: Predictor, x: np.ndarray, rows: FoldRows,
                backbones: dict[int, np.ndarray] | None) -> tuple[dict[str, Any], dict[str, list[int]]]:
    """``view.*`` cells: up to :data:`VIEW_SAMPLES` ``physics_test`` samples and their predicted backbones."""
    m = study.measurements
    view = np.asarray(rows.physics_test, dtype=int)[spread_samples(m.commands[rows.physics_test], VIEW_SAMPLES)]
    if backbones is None:
        pts = predictor.predict(x, view, backbones=True)[1]
    else:
        pts = np.stack([backbones[int(i)] for i in view]) if view.size else np.zeros((0, 2, 3))
    n_st = int(pts.shape[1]) if pts.ndim == 3 and pts.shape[0] else 0
    measured = m.backbone[view] if m.backbone is not None and view.size else np.zeros((0, 0, 3))
    cells = {"view.file_row": [int(r) for r in m.file_rows[view]], "view.positions": pts.reshape(-1).tolist(),
             "view.measured_backbone": measured.reshape(-1).tolist()}
    shapes = {"view.positions": [-1, n_st, 3]} if n_st else {}
    if measured.size:
        shapes["view.measured_backbone"] = [-1, int(measured.shape[1]), 3]
    return cells, shapes


def calibration_row(case_id: str, model: str, study: CalibrationStudy, rows: FoldRows,
                    flat: Mapping[str, Any]) -> dict[str, Any]:
    """Calibrate ``model`` on fold ``rows`` of ``study`` and return its result row (module docstring).

    ``flat`` are the row's ``p.*`` cells.  Never raises for a model: a failed model evaluation is
    a failed row with its reason.
    """
    t0 = time.perf_counter()
    m = study.measurements
    settings = study.calibration
    base = {"case_id": case_id, "model": model, **flat, "fold": int(rows.fold),
            "robot_length": float(_nominal_length(study)), **_parameter_cells(study)}
    tables = {"robot": study.robot, "load": study.load, "solver": study.solver}
    names = tuple(p.name for p in settings.parameters)
    predictor = Predictor(model, tables, names, m)
    cc = model == "cc"
    train = np.asarray(rows.train if cc else rows.physics_train, dtype=int)
    test = np.asarray(rows.test if cc else rows.physics_test, dtype=int)
    tau = model_options(study.solver, model).newton_tolerance
    res = calibrate_on(predictor, settings.parameters, m.tip_position, train, settings.confidence,
                       settings.max_evaluations, diff_step(model, tau), evaluation_noise(model, tau))
    per_eval = predictor.timing.seconds / max(1, predictor.timing.calls if cc else predictor.timing.samples)
    if not np.isfinite(res.values).all():
        return failed_rows(case_id, {}, [model], f"calibration failed: {res.message}", time.perf_counter() - t0,
                           flat=base, extra=_result_cells(res, per_eval))[0]
    idx = np.union1d(train, test)
    try:
        predicted, bb = predictor.predict(res.values, idx, backbones=not cc)
        view, view_shapes = _view_cells(study, predictor, res.values, rows,
                                        None if cc else {int(i): bb[k] for k, i in enumerate(idx)})
    except PredictionFailure as e:
        return failed_rows(case_id, {}, [model], f"prediction at the calibrated values failed: {e}",
                           time.perf_counter() - t0, flat=base, extra=_result_cells(res, per_eval))[0]
    err = np.linalg.norm(predicted - m.tip_position[idx], axis=1)
    in_train = np.isin(idx, train)
    common = np.isin(idx, rows.physics_test)
    row = {
        **base, "status": "ok", "error": "", "failure": "", **_result_cells(res, per_eval),
        **error_stats(err[in_train], "err.train"), **error_stats(err[~in_train], "err.test"),
        "err.common_test_rms": error_stats(err[common], "c")["c_rms"],
        "sample.file_row": [int(r) for r in m.file_rows[idx]],
        "sample.split": [SPLIT_CODES["train"] if t else SPLIT_CODES["test"] for t in in_train],
        "sample.commands": m.commands[idx].reshape(-1).tolist(),
        "sample.measured": m.tip_position[idx].reshape(-1).tolist(),
        "sample.predicted": predicted.reshape(-1).tolist(), **view,
        "_shapes": {"sample.commands": [-1, int(m.commands.shape[1])], "sample.measured": [-1, 3],
                    "sample.predicted": [-1, 3], "calib.covariance": [len(res.values), -1], **view_shapes},
    }
    row["wall_time"] = time.perf_counter() - t0
    return row


def _nominal_length(study: CalibrationStudy) -> float:
    from ..study.build import build_robot

    return float(build_robot(study.robot).length)
