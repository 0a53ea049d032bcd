"""Deprecated: import from ``workbench.experiments.series_parallel.figures``.

The series-parallel figures are the ``registry.FIGURES["series_parallel"]`` set.  This shim
resolves the old names lazily through registry strings (a generic package never imports
``workbench.experiments``).
"""

from __future__ import annotations

from typing import Any

from .. import registry

__all__ = ["motion_figures", "motion_overview_figure", "motion_legs_figure"]

_TARGET = "workbench.experiments.series_parallel.figures"


def __getattr__(name: str) -> Any:
    if name in __all__:
        return registry.resolve(f"{_TARGET}:{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
