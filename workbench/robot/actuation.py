"""How a robot is driven and loaded: tendon commands, tip loads, static or dynamic analysis.

Per-tendon arrays follow the global tendon order of :meth:`workbench.robot.Robot.tendon_table`
(section by section, within a section in the order of ``TendonGroup.angles``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, Sequence

import numpy as np

from .description import Robot, RobotDescriptionError, checked_vector

__all__ = ["TendonActuation", "LoadCase"]


def _floats(name: str, values: Sequence[float] | None, n: int | None = None) -> tuple[float, ...] | None:
    if values is None:
        return None
    arr = np.asarray(values, dtype=float).reshape(-1)
    if n is not None and arr.size != n:
        raise RobotDescriptionError(f"{name} must have {n} entries (one per tendon), got {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise RobotDescriptionError(f"{name} must be finite, got {arr.tolist()}")
    return tuple(float(x) for x in arr)


@dataclass(frozen=True)
class TendonActuation:
    """Commands for every tendon of a robot.

    Parameters
    ----------
    mode : {"tension", "length"}
        ``"tension"``: each tendon is pulled with a prescribed force ``values[i]`` [N]
        (>= 0; a tendon cannot push).  ``"length"``: a motor changes the free length of
        each tendon by ``values[i]`` [m] (negative = reeled in / shortened); the tendon's
        own axial stiffness ``EA_t`` lies between the motor and the robot, and a tendon
        that goes slack carries no force.
    values : tuple of float
        One final command per tendon (global tendon order).
    start_times : tuple of float, optional
        Dynamic analysis only: the time [s] at which each tendon's motor starts moving
        (Cojocaru's wire delay).  Default: all 0.
    ramp_durations : tuple of float, optional
        Dynamic analysis only: how long [s] each motor takes to reach its final command,
        moving at constant speed.  Default: all equal to :attr:`LoadCase.ramp_time`.
    pretension : float
        Length mode: tension [N] in every tendon in the reference (straight) configuration,
        realised by shortening each tendon's rest length by ``pretension / EA_t`` of its
        length.  Keeps tendons taut.  Default 0.
    """

    mode: Literal["tension", "length"]
    values: tuple[float, ...]
    start_times: tuple[float, ...] | None = None
    ramp_durations: tuple[float, ...] | None = None
    pretension: float = 0.0

    def __post_init__(self) -> None:
        if self.mode not in ("tension", "length"):
            raise RobotDescriptionError(f"TendonActuation.mode must be 'tension' or 'length', got {self.mode!r}")
        vals = _floats("TendonActuation.values", self.values)
        if not vals:
            raise RobotDescriptionError("TendonActuation.values must hold one value per tendon")
        if self.mode == "tension" and min(vals) < 0:
            raise RobotDescriptionError(f"tendon tensions must be >= 0 (a tendon cannot push), got {list(vals)}")
        object.__setattr__(self, "values", vals)
        st = _floats("TendonActuation.start_times", self.start_times, len(vals))
        if st is not None and min(st) < 0:
            raise RobotDescriptionError("TendonActuation.start_times must be >= 0")
        object.__setattr__(self, "start_times", st)
        rd = _floats("TendonActuation.ramp_durations", self.ramp_durations, len(vals))
        if rd is not None and min(rd) < 0:
            raise RobotDescriptionError("TendonActuation.ramp_durations must be >= 0")
        object.__setattr__(self, "ramp_durations", rd)
        p = float(self.pretension)
        if not math.isfinite(p) or p < 0:
            raise RobotDescriptionError(f"TendonActuation.pretension must be finite and >= 0, got {p}")
        object.__setattr__(self, "pretension", p)

    def check_against(self, robot: Robot) -> None:
        """Raise :class:`RobotDescriptionError` unless there is one value per tendon of ``robot``."""
        if len(self.values) != robot.n_tendons:
            raise RobotDescriptionError(
                f"actuation has {len(self.values)} values but the robot has {robot.n_tendons} tendons"
            )

    def command_at(self, t: float | np.ndarray, default_ramp: float) -> np.ndarray:
        """Commanded value of every tendon at time(s) ``t``: constant-speed ramps.

        Returns ``(n_tendons,)`` for scalar ``t`` or ``(len(t), n_tendons)``.
        """
        t = np.asarray(t, dtype=float)
        v = np.asarray(self.values)
        t0 = np.zeros_like(v) if self.start_times is None else np.asarray(self.start_times)
        T = np.full_like(v, default_ramp) if self.ramp_durations is None else np.asarray(self.ramp_durations)
        tt = t[..., None]
        frac = np.where(T > 0, np.clip((tt - t0) / np.where(T > 0, T, 1.0), 0.0, 1.0), (tt >= t0).astype(float))
        return frac * v

    def command_function(self, default_ramp: float):
        """:meth:`command_at` for one scalar ``t`` at a time, in plain floats: ``f(t) -> (n_tendons,)``.

        The same arithmetic, so the same bits, without numpy's per-call overhead (most of the Python
        cost of a dynamic step's pre-step user function).  Checked bit for bit against
        :meth:`command_at` by ``tests/physics/test_beam3d.py``.
        """
        n = len(self.values)
        t0 = self.start_times or (0.0,) * n
        T = self.ramp_durations or (float(default_ramp),) * n
        terms = tuple(zip(self.values, t0, T))

        def command(t: float) -> np.ndarray:
            t = float(t)
            return np.array([v * (min(max((t - a) / d, 0.0), 1.0) if d > 0 else float(t >= a)) for v, a, d in terms])

        return command


@dataclass(frozen=True)
class LoadCase:
    """Everything applied to a robot in one simulation.

    Parameters
    ----------
    actuation : TendonActuation, optional
        Tendon commands (``None``: tendons absent or untouched).
    tip_force : tuple of 3 float
        External force at the tip [N], in the robot's **base frame** (backbone along base +z),
        not the world frame: on a horizontal robot (``base_orientation = "horizontal"``) a
        force "down" in the world is ``(-f, 0, 0)`` here, and ``(0, 0, -f)`` is an axial push.
        Convert with :func:`workbench.robot.world_vectors_to_base`.
    tip_torque : tuple of 3 float
        External torque at the tip [N m], base frame (as ``tip_force``).
    analysis : {"static", "dynamic"}
        Static equilibrium for the final commands, or a time simulation.
    duration : float
        Simulated time for a dynamic analysis [s].
    ramp_time : float
        Default duration of each tendon's constant-speed ramp [s] (dynamic analysis).
    """

    actuation: TendonActuation | None = None
    tip_force: tuple[float, float, float] = (0.0, 0.0, 0.0)
    tip_torque: tuple[float, float, float] = (0.0, 0.0, 0.0)
    analysis: Literal["static", "dynamic"] = "static"
    duration: float = 0.0
    ramp_time: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "tip_force", checked_vector("LoadCase.tip_force", self.tip_force))
        object.__setattr__(self, "tip_torque", checked_vector("LoadCase.tip_torque", self.tip_torque))
        if self.analysis not in ("static", "dynamic"):
            raise RobotDescriptionError(f"LoadCase.analysis must be 'static' or 'dynamic', got {self.analysis!r}")
        for name in ("duration", "ramp_time"):
            v = float(getattr(self, name))
            if not math.isfinite(v) or v < 0:
                raise RobotDescriptionError(f"LoadCase.{name} must be finite and >= 0, got {v}")
            object.__setattr__(self, name, v)
        if self.analysis == "dynamic" and self.duration <= 0:
            raise RobotDescriptionError("LoadCase.duration must be > 0 for a dynamic analysis")
        if self.actuation is not None and not isinstance(self.actuation, TendonActuation):
            raise RobotDescriptionError("LoadCase.actuation must be a TendonActuation or None")
