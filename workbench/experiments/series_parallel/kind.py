"""The series-parallel study kind: Huang's trunk driven by platform poses, on the one study pipeline.

:data:`KIND` is the :class:`~workbench.study.kinds.StudyKind` that ``workbench.registry.KINDS``
names for ``[study] kind = "series_parallel"``: it loads the file (:mod:`.spec`), expands the
motions into cases (:mod:`.expand`) and evaluates one case per task (:mod:`.worker`; each case
costs seconds, so batching would only unbalance the workers).  Each case writes the rows
``target``, ``series_parallel`` and ``cc_fit``, computed together (``separable_models = False``:
the CC fit needs the FK result).  Everything else -- run session, manifest, store,
executors, crash handling, CLI and report -- is the generic pipeline's
(:func:`workbench.study.runner.run_cases`).

Checked by ``tests/experiments/series_parallel/test_run.py`` and ``tests/study/test_kinds.py``.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any, Sequence

from ...assumptions import Assumption
from ...study.expand import Case
from ...study.kinds import StudyKind
from ...study.outcomes import CaseLimits
from .expand import expand_poses
from .spec import KIND_NAME, SeriesParallelStudy, load_series_parallel_study
from .worker import MODELS, evaluate_pose_rows

__all__ = ["KIND", "SeriesParallelKind"]


class SeriesParallelKind(StudyKind):
    """The series-parallel study kind (see the module docstring)."""

    name = KIND_NAME
    flush_rows = 64
    separable_models = False
    task = staticmethod(evaluate_pose_rows)

    def load(self, path: str | Path, max_cases: int | None = None, overrides: Sequence[str] = ()
             ) -> SeriesParallelStudy:
        return replace(load_series_parallel_study(path, max_cases=max_cases, overrides=overrides),
                       overrides=tuple(overrides))

    def expand(self, spec: SeriesParallelStudy) -> list[Case]:
        return expand_poses(spec)

    def models(self, spec: SeriesParallelStudy) -> tuple[str, ...]:
        return MODELS

    def recorded_params(self, spec: SeriesParallelStudy, case: Case) -> dict[str, Any]:
        """The case's parameters: nothing is derived from them before a case runs."""
        return case.params

    def payload(self, spec: SeriesParallelStudy, case: Case, models: Sequence[str]
                ) -> tuple[str, dict]:
        """``(case_id, params)``: a case is computed whole (every model), whatever ``models`` says."""
        return case.case_id, case.params

    def limits(self, spec: SeriesParallelStudy) -> CaseLimits:
        return spec.limits


#: The series-parallel study kind (``registry.KINDS["series_parallel"]``).
KIND = SeriesParallelKind()

#: What the paper does not give (Huang et al. state no dimensions or materials): the assumed module,
#: as data for the report's Assumptions section (keys ``"geometry.<ModuleGeometry field>"``).
ASSUMED: tuple[Assumption, ...] = (
    Assumption("geometry.height", "0.5 m module (the paper gives no dimensions); sized so one module reaches the "
                                  "Fig 6 translations (+-200 mm) and twists (+-30 deg)"),
    Assumption("geometry.base_radius", "0.12 m hole circle (not given)"),
    Assumption("geometry.platform_radius", "0.12 m attachment circle (not given)"),
    Assumption("geometry.base_angles_deg", "Stewart-like hole pairs at 120 k +- 15 deg (not given)"),
    Assumption("geometry.platform_angles_deg", "6-6 crossing, legs 2k / 2k+1 to 120 k -+ 45 deg (not given)"),
    Assumption("geometry.rod_diameter", "leg rod diameter (not given); bending stresses scale with it, the "
                                        "kinematics hardly do (no external load)"),
    Assumption("geometry.youngs_modulus", "spring steel, 200 GPa (the paper: flexible rods, no material)"),
    Assumption("geometry.yield_strength", "hardened and tempered spring steel 52CrMoV4 (EN 10089): Rp0.2 >= 1200 "
                                          "MPa (Saarstahl data sheet)"),
    Assumption("geometry.platform_mass", "0.5 kg (only with gravity; the studies run without)"),
)
