"""Deprecated: run series-parallel studies with ``workbench.study.run_cases(KIND, ...)``.

``KIND`` is ``workbench.experiments.series_parallel.kind.KIND``; the two functions below are the
old entry points, now thin wrappers over the one study pipeline.
"""

from __future__ import annotations

from pathlib import Path

from ..experiments.series_parallel.kind import KIND
from ..experiments.series_parallel.spec import SeriesParallelStudy, is_series_parallel_study, load_series_parallel_study
from ..study.executors import Executor
from ..study.run_config import RunConfig
from ..study.runner import RunSummary, run_cases

__all__ = ["run_motion_study", "run_loaded_motion_study", "is_motion_study"]

is_motion_study = is_series_parallel_study


def run_motion_study(path: str | Path, out_dir: str | Path, executor: Executor | None = None,
                     resume: bool = False, *, progress: bool | None = None) -> RunSummary:
    """Validate the series-parallel study file ``path`` and run it into ``out_dir`` (one case per task).

    Raises :class:`~workbench.study.messages.StudyError` for an invalid file or a folder/resume
    mismatch; ``exit_code`` of the summary is 1 when any case failed.
    """
    return run_loaded_motion_study(load_series_parallel_study(path), out_dir, executor, resume=resume,
                                   progress=progress)


def run_loaded_motion_study(study: SeriesParallelStudy, out_dir: str | Path, executor: Executor | None = None, *,
                            resume: bool = False, progress: bool | None = None, flush_rows: int = 64) -> RunSummary:
    """:func:`run_motion_study` for a validated study: ``run_cases(KIND, study, ..., RunConfig(...))``."""
    return run_cases(KIND, study, out_dir, executor, RunConfig(resume=resume, progress=progress, flush_rows=flush_rows))
