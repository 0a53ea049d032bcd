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
    """

    target: str | None
    label: str
    color: str | None = None


@dataclass(frozen=True)
class FigureSet:
    """A study-specific set of report figures: ``matches(results) -> bool`` and ``figures(...)``."""

    matches: str
    figures: str


MODELS: Mapping[str, ModelInfo] = {
    "cc": ModelInfo("workbench.models.cc:run", "CC", "#222222"),
    "ancf": ModelInfo("workbench.physics.ancf:run", "ANCF", "#1f77b4"),
    "beam3d": ModelInfo("workbench.physics.beam3d:run", "GE beam", "#d62728"),
    "ancf3d": ModelInfo("workbench.physics.ancf3d:run", "ANCF 3-D", "#9467bd"),
    "spring_link": ModelInfo("workbench.physics.spring_link:run", "spring-link", "#2ca02c"),
    "spring_link_cardan": ModelInfo("workbench.physics.spring_link.cardan:run", "spring-link, 2-DOF joints",
                                    "#17becf"),
    # rows of the series-parallel study kind (not run(robot, load, options) models)
    "series_parallel": ModelInfo(None, "series-parallel"),
    # rows of the closed-loop study kind: the controller's CC plan, the closed loop on a plant
    "plan": ModelInfo(None, "CC plan (open loop)", "#7f7f7f"),
    "spring_link_closed_loop": ModelInfo(None, "spring-link, closed loop", "#98df8a"),
    "ancf_closed_loop": ModelInfo(None, "ANCF, closed loop", "#aec7e8"),
    "cc_closed_loop": ModelInfo(None, "CC tendon map, closed loop", "#c7c7c7"),
}

PRESETS: Mapping[str, str] = {
    "steel_rod": "workbench.robot.presets.steel_rod:steel_rod",
    "hannan_walker": "workbench.robot.presets.hannan_walker:hannan_walker",
    "cojocaru_tronconic": "workbench.robot.presets.cojocaru:cojocaru_tronconic",
    "shao_harvester": "workbench.robot.presets.shao:shao_harvester",
    "hannan_walker_3d": "workbench.robot.presets.hannan_walker_3d:hannan_walker_3d",
}

#: ``[scenario] name`` -> function ``(robot, **parameters) -> load fields``.
SCENARIOS: Mapping[str, str] = {
    "wire_delay": "workbench.experiments.wire_delay.scenario:wire_delay",
    "hannan_walker_line": "workbench.experiments.hannan_walker.scenario:hannan_walker_line",
    "hannan_walker_spatial": "workbench.experiments.hannan_walker.scenario:hannan_walker_spatial",
    "closed_loop": "workbench.experiments.closed_loop.scenario:closed_loop",
    "wire_delay_arm": "workbench.experiments.wire_delay.scenario:wire_delay_arm",
}

#: ``[study] kind`` -> the :class:`~workbench.study.kinds.StudyKind` object that loads, expands and runs it.
KINDS: Mapping[str, str] = {
    "sweep": "workbench.study.kinds:SWEEP",
    "series_parallel": "workbench.experiments.series_parallel.kind:KIND",
    "closed_loop": "workbench.experiments.closed_loop.kind:KIND",
}

#: Study-specific figures, in report order (before the generic figures).
FIGURES: Mapping[str, FigureSet] = {
    "wire_delay_arm": FigureSet("workbench.experiments.wire_delay.figures_arm:matches",
                                "workbench.experiments.wire_delay.figures_arm:figures"),
    "wire_delay": FigureSet("workbench.experiments.wire_delay.figures:matches",
                            "workbench.experiments.wire_delay.figures:figures"),
    "hannan_walker": FigureSet("workbench.experiments.hannan_walker.figures:matches",
                               "workbench.experiments.hannan_walker.figures:figures"),
    "hannan_walker_3d": FigureSet("workbench.experiments.hannan_walker.figures_3d:matches",
                                  "workbench.experiments.hannan_walker.figures_3d:figures"),
    "closed_loop": FigureSet("workbench.experiments.closed_loop.figures:matches",
                             "workbench.experiments.closed_loop.figures:figures"),
    "fruit_harvester": FigureSet("workbench.experiments.fruit_harvester.figures:matches",
                                 "workbench.experiments.fruit_harvester.figures:figures"),
    "series_parallel_s_shape": FigureSet("workbench.experiments.series_parallel.figures_s_shape:matches",
                                         "workbench.experiments.series_parallel.figures_s_shape:figures"),
    "series_parallel": FigureSet("workbench.experiments.series_parallel.figures:matches",
                                 "workbench.experiments.series_parallel.figures:figures"),
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
