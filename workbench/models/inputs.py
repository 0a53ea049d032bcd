"""The one boundary check every model runs on its inputs."""

from __future__ import annotations

from ..robot import LoadCase, Robot
from .result import SolverOptions

__all__ = ["check_model_inputs"]


def check_model_inputs(robot: Robot, load: LoadCase, options: SolverOptions) -> None:
    """Raise ``TypeError`` for arguments of the wrong type and
    :class:`~workbench.robot.RobotDescriptionError` when the actuation does not have one
    command per tendon of ``robot``."""
    for name, value, cls in (("robot", robot, Robot), ("load", load, LoadCase), ("options", options, SolverOptions)):
        if not isinstance(value, cls):
            raise TypeError(f"{name} must be a {cls.__module__.split('.')[0]}.{cls.__name__}, got {type(value).__name__}")
    if load.actuation is not None:
        load.actuation.check_against(robot)
