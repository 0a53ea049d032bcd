"""Deprecated: the study-specific figures moved to ``workbench/experiments/<study>/figures.py``.

Deprecated: import ``circle_fit`` and ``HARVESTER_LIMITS`` from
``workbench.experiments.fruit_harvester.envelope``; the figure sets are rows of
``workbench.registry.FIGURES``.  This shim resolves those names lazily through registry strings
(a generic package never imports ``workbench.experiments``).  :func:`study_figures` runs the
registered figure sets of the wire-delay, Hannan & Walker and fruit-harvester studies.
"""

from __future__ import annotations

from typing import Any

from .. import registry

__all__ = ["study_figures", "circle_fit", "HARVESTER_LIMITS"]

_MOVED = {
    "circle_fit": "workbench.experiments.fruit_harvester.envelope:circle_fit",
    "HARVESTER_LIMITS": "workbench.experiments.fruit_harvester.envelope:HARVESTER_LIMITS",
}

#: The figure sets this module's ``study_figures`` used to dispatch between.
_SETS = ("wire_delay", "hannan_walker", "fruit_harvester")


def study_figures(study, cmp) -> list:
    """Deprecated: figures of the first matching set among the wire-delay, Hannan & Walker and
    fruit-harvester figure sets of ``workbench.registry.FIGURES`` (else ``[]``)."""
    for name in _SETS:
        fs = registry.FIGURES[name]
        if registry.resolve(fs.matches)(study):
            return registry.resolve(fs.figures)(study, cmp)
    return []


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        return registry.resolve(_MOVED[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
