"""The generic report figures: ``matplotlib.figure.Figure`` objects (never pyplot), one style.

Each builder ``builder(results, cmp) -> [ReportFigure]`` (name, title, figure, generated text
summary) takes a :class:`~.load.ResultSet` and the comparison table of
:func:`workbench.compare.compare_table`; failed rows never reach a figure.
:data:`GENERIC_FIGURES` lists them in report order (after the study-specific figure sets of
``workbench.registry.table("figures")``).  A new generic figure: a builder in its own module here plus
its entry in :data:`GENERIC_FIGURES`.  The shared style and label helpers are in :mod:`.style`.
"""

from __future__ import annotations

from .dynamics import compression_split_figures, time_series_figures
from .errorbars import error_bar_figures
from .shapes import shape_overlay_figures
from .sweeps import error_vs_parameter_figures, validity_map_figures

__all__ = ["GENERIC_FIGURES"]

#: The generic figure builders, in report order.
GENERIC_FIGURES = (
    error_bar_figures,
    shape_overlay_figures,
    error_vs_parameter_figures,
    validity_map_figures,
    compression_split_figures,
    time_series_figures,
)
