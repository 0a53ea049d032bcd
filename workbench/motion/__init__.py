"""Motion studies of Huang et al.'s flexible series-parallel trunk (single module and stacks).

A sibling of :mod:`workbench.study` for models driven by platform poses rather than by
``run(robot, load, options)``: :func:`load_motion_study` (strict TOML validation, one-line
:class:`~workbench.study.spec.StudyError` messages), :func:`expand_motions` (stable case ids),
:func:`evaluate_motion_case` (pure worker: IK, FK check, CC fit) and :func:`run_motion_study`
(same result store, manifest and row schema as the generic runner).
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
