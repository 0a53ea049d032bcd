"""Deprecated: import from ``workbench.experiments.series_parallel`` (the series-parallel study kind).

``workbench.motion`` was the sibling pipeline of the series-parallel platform-pose studies; the
study kind now lives in ``workbench/experiments/series_parallel/`` (``spec``, ``expand``,
``worker``, ``kind``) and runs on the one study pipeline (:func:`workbench.study.run_cases`).
This package keeps every name it had (``MotionStudy`` is
:class:`~workbench.experiments.series_parallel.spec.SeriesParallelStudy`).
"""

from .expand import expand_motions, motion_values
from .runner import run_loaded_motion_study, run_motion_study
from .spec import MotionStudy, is_motion_study, load_motion_study
from .worker import evaluate_motion_case, module_target, stack_targets

__all__ = [
    "MotionStudy",
    "load_motion_study",
    "is_motion_study",
    "expand_motions",
    "motion_values",
    "evaluate_motion_case",
    "module_target",
    "stack_targets",
    "run_motion_study",
    "run_loaded_motion_study",
]
