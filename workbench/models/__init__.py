"""Model registry: every model is ``run(robot, load, options) -> PhysicsResult``.

Models (the rows of ``workbench.registry.table("models")``, built-in and plug-in) are looked up
by name and imported lazily, so using the CC model never imports Exudyn.  A model signals an
untrustworthy solve by raising :class:`~workbench.models.result.ModelFailure` (or ``exudyn.SolverError``).
"""

from __future__ import annotations

from typing import Callable, Protocol

from .. import registry
from ..robot import LoadCase, Robot
from ._console import quiet_if_loaded
from .result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions

__all__ = [
    "Model",
    "ModelFailure",
    "PhysicsResult",
    "SolverInfo",
    "SolverOptions",
    "get_model",
    "model_names",
    "quiet_if_loaded",
]


class Model(Protocol):
    def __call__(self, robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult: ...


def model_names() -> tuple[str, ...]:
    """The registered model names: built-in and plug-in rows of ``registry.table("models")``."""
    return tuple(registry.table("models"))


def get_model(name: str) -> Callable[[Robot, LoadCase, SolverOptions], PhysicsResult]:
    """Return the model function registered under ``name``.

    Raises
    ------
    KeyError
        Unknown name (the message lists the known ones).
    """
    rows = registry.table("models")
    if name not in rows:
        raise KeyError(f"unknown model {name!r}; known models: {', '.join(rows)}")
    return registry.resolve(rows[name].target)
