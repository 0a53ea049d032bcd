"""The closed-loop study kind: sweep-format files whose cases run a controller along a path.

A closed-loop study file is a sweep study file (``docs/study-format.md``: ``[robot]``, ``[load]``,
``[solver]``, ``[sweep]``, ...) with ``[study] kind = "closed_loop"`` and the ``closed_loop``
scenario (:mod:`.scenario`: path and controller, sweepable as ``scenario.<key>``).
``study.models`` names the *plants*, registered ``run`` models; every case writes the rows
:func:`.worker.row_models` (``plan``, and per plant its open- and closed-loop rows).  The file is
validated by the sweep loader (:func:`workbench.study.spec.parse_study`: every problem one line,
every case dry-built, i.e. every plan computed); ``report.reference`` (default ``plan``) must be
one of the rows.  One case per task (a case is a whole path, seconds to minutes).  Run session,
manifest, store, executors, CLI and report are the generic pipeline's.

Checked by ``tests/experiments/test_closed_loop.py``.
"""

from __future__ import annotations

import copy
import hashlib
from dataclasses import dataclass
from pathlib import Path
from dataclasses import replace
from typing import Any, Sequence

from ...study.build import parameters_as_run
from ...study.expand import Case, count_cases, expand
from ...study.kinds import StudyKind
from ...study.messages import StudyError, read_toml
from ...study.outcomes import CaseLimits
from ...study.overrides import apply_overrides, unapplied_overrides
from ...study.params import canonical_json
from ...study.spec import Study, parse_study
from .worker import CLOSED_SUFFIX, PLAN, evaluate_closed_loop_rows, row_models

__all__ = ["KIND", "KIND_NAME", "ClosedLoopKind", "ClosedLoopStudy", "load_closed_loop_study"]

KIND_NAME = "closed_loop"
SCENARIO = "closed_loop"


@dataclass(frozen=True)
class ClosedLoopStudy:
    """A validated closed-loop study: the sweep-format :class:`~workbench.study.spec.Study` and its reference row."""

    study: Study
    reference: str = PLAN

    path = property(lambda self: self.study.path)
    name = property(lambda self: self.study.name)
    seed = property(lambda self: self.study.seed)
    max_cases = property(lambda self: self.study.max_cases)
    overrides = property(lambda self: self.study.overrides)
    notes = property(lambda self: self.study.notes)
    warnings = property(lambda self: self.study.warnings)

    @property
    def plants(self) -> tuple[str, ...]:
        """The ``run`` models the controller drives (``study.models``)."""
        return tuple(self.study.models)

    @property
    def models(self) -> tuple[str, ...]:
        return row_models(self.plants)

    def resolved(self) -> dict[str, Any]:
        """The sweep study's resolved spec with the kind, the plants, the row models and the reference."""
        out = copy.deepcopy(self.study.resolved())
        out["study"].update(kind=KIND_NAME, plants=list(self.plants), models=list(self.models))
        out["report"] = {**out.get("report", {}), "reference": self.reference}
        return out

    @property
    def config_hash(self) -> str:
        payload = {"kind": KIND_NAME, "sweep_hash": self.study.config_hash}
        return hashlib.sha256(canonical_json(payload).encode()).hexdigest()[:16]


def load_closed_loop_study(path: str | Path, *, max_cases: int | None = None,
                           overrides: Sequence[str] = ()) -> ClosedLoopStudy:
    """Read and validate a closed-loop study file with the command-line ``key=value`` ``overrides``
    applied (:mod:`workbench.study.overrides`); :class:`StudyError` lists every problem, one line each."""
    src = str(Path(path))
    data = copy.deepcopy(apply_overrides(read_toml(path), overrides))
    problems: list[str] = []
    if isinstance(data.get("study"), dict):
        data["study"].pop("kind", None)
    reference = PLAN
    if isinstance(data.get("report"), dict) and "reference" in data["report"]:
        reference = data["report"].pop("reference")
    sc = data.get("scenario")
    if not isinstance(sc, dict) or sc.get("name") != SCENARIO:
        got = sc.get("name") if isinstance(sc, dict) else None
        problems.append(f"{src}: scenario.name: a closed_loop study runs the {SCENARIO!r} scenario (path and "
                        f"controller), got {got!r}")
    study = None
    try:
        study = parse_study(data, source=src, max_cases=max_cases)
    except StudyError as e:
        problems += e.problems
    if study is not None:
        problems += [f"{src}: {p}" for p in unapplied_overrides(overrides, study.sweep, study.base["solver"], ())]
        if study.base["solver"].get("by_model"):
            problems.append(f"{src}: solver.by_model: a closed_loop study runs every plant with the [solver] options; "
                            f"per-model settings would not apply")
        bad = [m for m in study.models if m == PLAN or m.endswith(CLOSED_SUFFIX)]
        problems += [f"{src}: study.models: {m!r} is a row name of this kind, not a plant" for m in bad]
        if reference not in row_models(study.models):
            problems.append(f"{src}: report.reference: {reference!r} is not one of the rows "
                            f"({', '.join(row_models(study.models))})")
    if problems:
        raise StudyError(problems)
    return ClosedLoopStudy(replace(study, overrides=tuple(overrides)), str(reference))


class ClosedLoopKind(StudyKind):
    """The closed-loop study kind (see the module docstring)."""

    name = KIND_NAME
    flush_rows = 64
    separable_models = False  # the plan row and the loops of a case come from one controller run
    task = staticmethod(evaluate_closed_loop_rows)

    def load(self, path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()
             ) -> ClosedLoopStudy:
        return load_closed_loop_study(path, max_cases=max_cases, overrides=overrides)

    def expand(self, spec: ClosedLoopStudy) -> list[Case]:
        return expand(spec.study)

    def count(self, spec: ClosedLoopStudy) -> int:
        """Number of cases, without expanding them."""
        return count_cases(spec.study)

    def models(self, spec: ClosedLoopStudy) -> tuple[str, ...]:
        return spec.models

    def recorded_params(self, spec: ClosedLoopStudy, case: Case) -> dict[str, Any]:
        """:func:`~workbench.study.build.parameters_as_run` (the scenario's final plan cables applied)."""
        return parameters_as_run(case.params)

    def payload(self, spec: ClosedLoopStudy, case: Case, models: Sequence[str]) -> tuple:
        """``(case_id, params, plants)``: a case is computed whole, whatever ``models`` says."""
        return case.case_id, case.params, spec.plants

    def limits(self, spec: ClosedLoopStudy) -> CaseLimits:
        return spec.study.limits


#: The closed-loop study kind (``registry.KINDS["closed_loop"]``).
KIND = ClosedLoopKind()
