"""Deprecated: import from ``workbench.experiments.series_parallel.spec``.

``MotionStudy``, ``load_motion_study`` and ``is_motion_study`` are the old names of
``SeriesParallelStudy``, ``load_series_parallel_study`` and ``is_series_parallel_study``;
``KIND`` is the kind's name ``"series_parallel"`` (``KIND_NAME`` there).
"""

from ..experiments.series_parallel.spec import GEOMETRY_KEYS, KIND_NAME
from ..experiments.series_parallel.spec import SeriesParallelStudy as MotionStudy
from ..experiments.series_parallel.spec import is_series_parallel_study as is_motion_study
from ..experiments.series_parallel.spec import load_series_parallel_study as load_motion_study

__all__ = ["MotionStudy", "load_motion_study", "is_motion_study", "KIND", "GEOMETRY_KEYS"]

KIND = KIND_NAME
