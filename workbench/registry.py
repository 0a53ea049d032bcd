"""The one table of plug-ins: models, robot presets, scenarios, study kinds and figure sets.

Data only.  Every entry names its code as a ``"module:attribute"`` string that
:func:`resolve` imports when it is first used, so reading this table imports nothing (neither
Exudyn nor any experiment).  Generic layers find experiment code only through these rows; a
new study is a folder under ``workbench/experiments/`` plus its rows here
(``docs/architecture.md``, "Where to add things").

Checked by ``tests/test_architecture.py`` (every row resolves; nothing here imports workbench).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any, Mapping

__all__ = ["FIGURES", "FigureSet", "KINDS", "MODELS", "ModelInfo", "PRESETS", "SCENARIOS", "resolve"]


@dataclass(frozen=True)
class ModelInfo:
    """A row model name -> code and presentation.

    Attributes
    ----------
    target : str or None
        ``"module:function"`` of ``run(robot, load, options) -> PhysicsResult``; ``None`` for a
        label-only row (the rows another study kind writes, such as ``"target"``).
    label : str
        Name in figures and tables.
    color : str or None
        Line colour in figures (``None``: a fallback colour is picked per report).
    order : float or None
        Convergence order of the model's discretisation error in the element / link count
        (measured by its validation tests, ``docs/models.md``); the discretisation-error estimate
        of the study pipeline uses it (:mod:`workbench.models.discretization`).  ``None``: no
        discretisation (CC) or not declared.
    """

    target: str | None
    label: str
    color: str | None = None
    order: float | None = None


@dataclass(frozen=True)
class FigureSet:
    """A study-specific set of report figures: ``matches(results) -> bool`` and ``figures(...)``.

    ``findings`` (optional): ``"module:function"`` of ``findings(results, cmp) -> [str]``, the
    study-specific sentences of the report's Findings section (numbers from the data).
    """

    matches: str
    figures: str
    findings: str | None = None


MODELS: Mapping[str, ModelInfo] = {
    "cc": ModelInfo("workbench.models.cc:run", "CC", "#222222"),
    # orders: measured on the tip-load elastica and the pure-moment arc (tests/models/test_discretization.py):
    # ancf and ancf3d (cubic Hermite cables) ~4, beam3d 2, spring_link 2
    "ancf": ModelInfo("workbench.physics.ancf:run", "ANCF", "#1f77b4", order=4.0),
    "beam3d": ModelInfo("workbench.physics.beam3d:run", "GE beam", "#d62728", order=2.0),
    "ancf3d": ModelInfo("workbench.physics.ancf3d:run", "ANCF 3-D", "#9467bd", order=4.0),
    "spring_link": ModelInfo("workbench.physics.spring_link:run", "spring-link", "#2ca02c", order=2.0),
    # planar ANCF with a rigid circle (without an object: equal to ancf with continuum tendons); no
    # declared order (penalty contact: not measured), so its rows carry no estimate
    "contact": ModelInfo("workbench.physics.contact:run", "ANCF + contact", "#ff7f0e"),
    # rows of the series-parallel study kind (not run(robot, load, options) models); its GE-beam
    # legs converge at order 2 (test_series_parallel.py, against the Cosserat shooting solver)
    "series_parallel": ModelInfo(None, "series-parallel", order=2.0),
}

PRESETS: Mapping[str, str] = {
    "steel_rod": "workbench.robot.presets.steel_rod:steel_rod",
    "hannan_walker": "workbench.robot.presets.hannan_walker:hannan_walker",
    "cojocaru_tronconic": "workbench.robot.presets.cojocaru:cojocaru_tronconic",
    "shao_harvester": "workbench.robot.presets.shao:shao_harvester",
}

#: ``[scenario] name`` -> function ``(robot, **parameters) -> load fields``.
SCENARIOS: Mapping[str, str] = {
    "wire_delay": "workbench.experiments.wire_delay.scenario:wire_delay",
    "hannan_walker_line": "workbench.experiments.hannan_walker.scenario:hannan_walker_line",
    "whole_arm_wrap": "workbench.experiments.whole_arm_grasp.scenario:whole_arm_wrap",
    "harvester_scoop": "workbench.experiments.fruit_harvester.scoop:harvester_scoop",
}

#: ``[study] kind`` -> the :class:`~workbench.study.kinds.StudyKind` object that loads, expands and runs it.
KINDS: Mapping[str, str] = {
    "sweep": "workbench.study.kinds:SWEEP",
    "series_parallel": "workbench.experiments.series_parallel.kind:KIND",
    "grasp": "workbench.experiments.whole_arm_grasp.kind:KIND",
}

#: Study-specific figures, in report order (before the generic figures).
FIGURES: Mapping[str, FigureSet] = {
    "wire_delay": FigureSet("workbench.experiments.wire_delay.figures:matches",
                            "workbench.experiments.wire_delay.figures:figures",
                            "workbench.experiments.wire_delay.findings:findings"),
    "hannan_walker": FigureSet("workbench.experiments.hannan_walker.figures:matches",
                               "workbench.experiments.hannan_walker.figures:figures"),
    "fruit_harvester": FigureSet("workbench.experiments.fruit_harvester.figures:matches",
                                 "workbench.experiments.fruit_harvester.figures:figures"),
    "series_parallel": FigureSet("workbench.experiments.series_parallel.figures:matches",
                                 "workbench.experiments.series_parallel.figures:figures",
                                 "workbench.experiments.series_parallel.findings:findings"),
    "whole_arm_grasp": FigureSet("workbench.experiments.whole_arm_grasp.figures:matches",
                                 "workbench.experiments.whole_arm_grasp.figures:figures"),
    "fruit_harvester_scoop": FigureSet("workbench.experiments.fruit_harvester.scoop_figures:matches",
                                       "workbench.experiments.fruit_harvester.scoop_figures:figures"),
}


def resolve(target: str) -> Any:
    """Import ``"package.module:attribute"`` and return the attribute.

    Raises
    ------
    ValueError
        ``target`` is not of the form ``"module:attribute"``.
    ImportError, AttributeError
        The module or attribute does not exist (a broken registry row).
    """
    module, sep, attr = target.partition(":")
    if not sep or not module or not attr:
        raise ValueError(f"registry target must be 'module:attribute', got {target!r}")
    obj: Any = importlib.import_module(module)
    for part in attr.split("."):
        obj = getattr(obj, part)
    return obj
