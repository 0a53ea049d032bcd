"""Deprecated: import from ``workbench.experiments.series_parallel.expand``."""

from ..experiments.series_parallel.expand import expand_motions, motion_values

__all__ = ["expand_motions", "motion_values"]
