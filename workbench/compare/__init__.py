"""CC-vs-physics comparison metrics (pure functions; no plotting, no Exudyn).

Array level (:mod:`workbench.compare.metrics`): :func:`tip_position_error`,
:func:`orientation_error_deg`, :func:`shape_error`, :func:`best_fit_curvature`,
:func:`section_curvatures`, :func:`out_of_plane_distance`, :func:`compression_split`, ...

Table level (:mod:`workbench.compare.table`): :func:`compare_table` turns a study result
table (one row per ``(case_id, model)``) into one metric row per case and model pair.
"""

from .metrics import (
    CompressionSplit,
    best_fit_curvature,
    best_fit_plane,
    compression_split,
    orientation_error_deg,
    out_of_plane_distance,
    polyline_length,
    resample_backbone,
    section_curvatures,
    shape_error,
    tendon_stretch_from_tension,
    tip_position_error,
)
from .table import (
    DERIVED_LABELS,
    add_derived_columns,
    array_cell,
    compare_table,
    ok_rows,
    row_positions,
    row_tip_frame,
)

__all__ = [
    "CompressionSplit",
    "DERIVED_LABELS",
    "add_derived_columns",
    "array_cell",
    "best_fit_curvature",
    "best_fit_plane",
    "compare_table",
    "compression_split",
    "ok_rows",
    "orientation_error_deg",
    "out_of_plane_distance",
    "polyline_length",
    "resample_backbone",
    "row_positions",
    "row_tip_frame",
    "section_curvatures",
    "shape_error",
    "tendon_stretch_from_tension",
    "tip_position_error",
]
