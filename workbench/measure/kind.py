"""The calibration study kind: calibrate each listed model on each fold of a robot's measured data.

:data:`KIND` is the :class:`~workbench.study.kinds.StudyKind` that ``workbench.registry.KINDS``
names for ``[study] kind = "calibration"`` (``docs/measurements.md``).  It loads the file
(:func:`workbench.measure.spec.load_calibration_study`), expands it into one case per fold and, in
the worker, calibrates each model of the study on that fold and yields one row per model
(:func:`workbench.measure.rows.calibration_row`).

Why a case is a fold, not a (model, fold) pair: the run pipeline plans every case as a row for
each of ``models(spec)`` (:func:`workbench.study.plan.plan_units`), so a case must write a row for
every model.  The models of a fold are computed one after the other in one task
(``separable_models``: a crash keeps the finished models' rows and reruns the others); the
folds run in parallel on the executors, Dask and batch clusters.  Running models in parallel
too needs per-case model lists in the planner.

A case's id is the first 16 hex digits of the SHA-256 of ``{"fold", "config_hash"}``: stable across
runs of the same file; any change of the file (data, parameters, models) gives new ids.  Its
recorded parameters (``p.*``) are the fold (``p.calibration.fold``) and the nominal ``[robot]``,
``[load]`` and ``[solver]`` tables (the calibrated values are in ``calib.values``).

Checked by ``tests/measure/test_measure_kind.py`` and ``tests/study/test_kind_contract.py``.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import replace
from pathlib import Path
from typing import Any, Iterator, Sequence

from ..study.expand import Case
from ..study.kinds import StudyKind
from ..study.outcomes import CaseLimits
from ..study.params import case_id_for, flatten_params
from ..study.rows import failed_rows
from ..study.schema import DEFAULT_MAX_CASE_SECONDS, LIMIT_KEYS
from .rows import calibration_row
from .types import CalibrationStudy, FoldRows

__all__ = ["KIND", "KIND_NAME", "CalibrationKind", "calibration_rows", "fold_count", "folds_of"]

#: the ``[study] kind`` value
KIND_NAME = "calibration"


def fold_count(study: CalibrationStudy) -> int:
    """Number of folds: 1 with ``test_fraction``, else ``folds``."""
    split = study.calibration.split
    return 1 if split.test_fraction is not None else int(split.folds)


def folds_of(study: CalibrationStudy) -> list[FoldRows]:
    """The seeded folds of ``study`` (:func:`workbench.measure.split.fold_rows`)."""
    from .split import fold_rows

    return fold_rows(study.measurements.n, study.calibration.split)


def _reason(e: BaseException) -> str:
    where = traceback.extract_tb(e.__traceback__)[-1] if e.__traceback__ else None
    loc = f" (at {where.filename.rsplit('/', 1)[-1]}:{where.lineno})" if where else ""
    return f"{type(e).__name__}: {' '.join(str(e).split())[:500]}{loc}"


def calibration_rows(payload: tuple) -> Iterator[dict[str, Any]]:
    """The task: ``payload = (case_id, params, models, study, fold_rows)``; yields one row per model
    (never raises for a model: an unexpected error is that model's failed row with the reason)."""
    case_id, params, models, study, rows = payload
    flat = flatten_params(params)
    for model in models:
        t0 = time.perf_counter()
        try:
            row = calibration_row(case_id, model, study, rows, flat)
        except Exception as e:  # noqa: BLE001 - recorded as the model's failure
            row = failed_rows(case_id, params, [model], f"calibration failed: {_reason(e)}",
                              time.perf_counter() - t0, flat=flat, extra={"fold": int(rows.fold)})[0]
        yield row


class CalibrationKind(StudyKind):
    """The calibration study kind (module docstring)."""

    name = KIND_NAME
    flush_rows = 8
    separable_models = True
    task = staticmethod(calibration_rows)

    def load(self, path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()
             ) -> CalibrationStudy:
        from .spec import load_calibration_study

        return replace(load_calibration_study(path, max_cases=max_cases, overrides=tuple(overrides)),
                       overrides=tuple(overrides))

    def expand(self, spec: CalibrationStudy) -> list[Case]:
        return [Case(case_id=case_id_for({"fold": f, "config_hash": spec.config_hash}), index=f,
                     params=self._params(spec, f), swept={"calibration.fold": f}) for f in range(fold_count(spec))]

    def count(self, spec: CalibrationStudy) -> int:
        return fold_count(spec)

    def models(self, spec: CalibrationStudy) -> tuple[str, ...]:
        return tuple(spec.calibration.models)

    @staticmethod
    def _params(spec: CalibrationStudy, fold: int) -> dict[str, dict[str, Any]]:
        solver = {k: v for k, v in spec.solver.items() if k not in LIMIT_KEYS}
        return {"calibration": {"fold": fold}, "robot": dict(spec.robot), "load": dict(spec.load), "solver": solver}

    def recorded_params(self, spec: CalibrationStudy, case: Case) -> dict[str, Any]:
        """The fold and the nominal robot, load and solver tables (module docstring)."""
        return case.params

    def payload(self, spec: CalibrationStudy, case: Case, models: Sequence[str]) -> tuple:
        """``(case_id, params, models, study, fold rows)``: :func:`calibration_rows`'s argument."""
        fold = case.params["calibration"]["fold"]
        return case.case_id, case.params, tuple(models), spec, folds_of(spec)[fold]

    def limits(self, spec: CalibrationStudy) -> CaseLimits:
        return CaseLimits(float(spec.solver.get("max_case_seconds", DEFAULT_MAX_CASE_SECONDS)),
                          spec.solver.get("max_case_memory"))


#: The calibration study kind (``registry.KINDS["calibration"]``).
KIND = CalibrationKind()
