"""Deprecated: import from ``workbench.experiments.series_parallel.worker``."""

from ..experiments.series_parallel.worker import (
    MODELS,
    evaluate_motion_batch,
    evaluate_motion_case,
    module_target,
    stack_targets,
)

__all__ = ["stack_targets", "module_target", "evaluate_motion_case", "evaluate_motion_batch", "MODELS"]
