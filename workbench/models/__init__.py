"""Model registry: every model is ``run(robot, load, options) -> PhysicsResult``.

Models are looked up by name and imported lazily, so using the CC model never imports
Exudyn.  A model signals an untrustworthy solve by raising
:class:`~workbench.models.result.ModelFailure` (or ``exudyn.SolverError``).
"""

from __future__ import annotations

from typing import Callable, Protocol

from .. import registry
from ..robot import LoadCase, Robot
from ._console import quiet_if_loaded
from .result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions

__all__ = [
    "MODEL_NAMES",
    "Model",
    "ModelFailure",
    "PhysicsResult",
    "SolverInfo",
    "SolverOptions",
    "get_model",
    "quiet_if_loaded",
]


class Model(Protocol):
    def __call__(self, robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult: ...


# name -> "module:function" (the rows of workbench.registry.MODELS); resolved on demand by get_model
# (no import work here).
_MODEL_PATHS: dict[str, str] = {n: m.target for n, m in registry.MODELS.items()}

MODEL_NAMES: tuple[str, ...] = tuple(_MODEL_PATHS)


def get_model(name: str) -> Callable[[Robot, LoadCase, SolverOptions], PhysicsResult]:
    """Return the model function registered under ``name``.

    Raises
    ------
    KeyError
        Unknown name (the message lists the known ones).
    """
    try:
        path = _MODEL_PATHS[name]
    except KeyError:
        raise KeyError(f"unknown model {name!r}; known models: {', '.join(MODEL_NAMES)}") from None
    return registry.resolve(path)
