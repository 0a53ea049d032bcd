"""The ``grasp`` study kind: sweep studies whose cases are CC grasp plans run through the contact physics.

A grasp study file is a sweep study file (``docs/study-format.md``: ``[robot]``, ``[load]``,
``[solver]``, ``[scenario]``, ``[sweep]``, ``[report]``) with ``[study] kind = "grasp"``; it is
validated by the sweep loader (every problem one line, each case dry-run), plus three rules:
``[scenario] name`` must be a grasp scenario (:data:`PLANS`), ``study.models`` a subset of
``cc`` (the plan) and ``contact`` (the physics), and ``load.analysis`` static.  The scenario's
parameters describe the object, the plan and the task; its load fields (the CC tendon tensions)
are what the rows record.  Each case is one task (a grasp costs seconds); rows: :mod:`.worker`.

:data:`~.worker.PLANS` maps a scenario to its ``(robot, params) -> (GraspPlan, GraspTask)`` function:
``whole_arm_wrap`` (H&W-style tendon wrap, :mod:`.scenario`) and ``harvester_scoop`` (Shao's
fluidic section, ``workbench/experiments/fruit_harvester/scoop.py``).  Checked by
``tests/experiments/test_whole_arm_grasp.py`` and ``tests/study/test_kinds.py``.
"""

from __future__ import annotations

from pathlib import Path
from dataclasses import replace
from typing import Any, Sequence

from ...study.build import parameters_as_run
from ...study.expand import Case, count_cases, expand
from ...study.kinds import StudyKind
from ...study.messages import StudyError, read_toml
from ...study.outcomes import CaseLimits
from ...study.overrides import apply_overrides, unapplied_overrides
from ...study.spec import Study, parse_study
from .worker import PLANS, evaluate_grasp_rows

__all__ = ["KIND", "GraspKind", "PLANS", "KIND_NAME", "MODELS"]

KIND_NAME = "grasp"
#: The rows a grasp case can write.
MODELS = ("cc", "contact")


def load_grasp_study(path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()) -> Study:
    """Read and validate a grasp study file (module docstring) with the command-line ``key=value``
    ``overrides`` applied (:mod:`workbench.study.overrides`); :class:`StudyError` lists every problem."""
    raw = apply_overrides(read_toml(path), overrides)
    source = str(Path(path))
    st = raw.get("study")
    problems = []
    if isinstance(st, dict):
        st = dict(st)
        if st.pop("kind", None) != KIND_NAME:
            problems.append(f'study.kind: must be "{KIND_NAME}" for this loader')
        raw = {**raw, "study": st}
        for i, m in enumerate(st.get("models", []) if isinstance(st.get("models"), list) else []):
            if m not in MODELS:
                problems.append(f"study.models[{i}]: a grasp study writes the rows {', '.join(MODELS)}, not {m!r}")
    scen = raw.get("scenario")
    name = scen.get("name") if isinstance(scen, dict) else None
    if name not in PLANS:
        problems.append(f"scenario.name: a grasp study needs a grasp scenario ({', '.join(PLANS)}), got {name!r}")
    load = raw.get("load")
    if isinstance(load, dict) and load.get("analysis", "static") != "static":
        problems.append("load.analysis: grasp studies are quasi-static (analysis = \"static\")")
    if problems:
        raise StudyError([f"{source}: {p}" for p in problems])
    # the grasp tasks compute the rows (not the models' run()): their capability rows do not apply
    study = parse_study(raw, source=source, max_cases=max_cases, run_models=False)
    idle = unapplied_overrides(overrides, study.sweep, study.base["solver"], study.models)
    if idle:
        raise StudyError([f"{source}: {p}" for p in idle])
    return replace(study, overrides=tuple(overrides))


class GraspKind(StudyKind):
    """The grasp study kind (module docstring)."""

    name = KIND_NAME
    flush_rows = 16
    #: the ``cc`` row (the plan) and the ``contact`` row (the physics) are computed independently
    separable_models = True
    task = staticmethod(evaluate_grasp_rows)

    def load(self, path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()) -> Study:
        return load_grasp_study(path, max_cases=max_cases, overrides=overrides)

    def expand(self, spec: Study) -> list[Case]:
        return expand(spec)

    def count(self, spec: Study) -> int:
        """Number of cases, without expanding them."""
        return count_cases(spec)

    def models(self, spec: Study) -> tuple[str, ...]:
        return tuple(spec.models)

    def recorded_params(self, spec: Study, case: Case) -> dict[str, Any]:
        """:func:`~workbench.study.build.parameters_as_run` (the scenario's tensions in ``p.load.*``)."""
        return parameters_as_run(case.params)

    def payload(self, spec: Study, case: Case, models: Sequence[str]) -> tuple:
        """``(case_id, params, models)``: one case, the models still to compute."""
        return case.case_id, case.params, tuple(models)

    def limits(self, spec: Study) -> CaseLimits:
        """``[solver] max_case_seconds`` / ``max_case_memory`` of the study (the sweep loader's)."""
        return spec.limits


#: The grasp study kind (``registry.KINDS["grasp"]``).
KIND = GraspKind()
