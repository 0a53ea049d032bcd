"""What the controller drives: the Hannan & Walker cable map and the plants (physics or CC).

* :func:`hw_cable_map` -- the robot's cable commands of a CC configuration: equal joint angles per
  section (Eq. 2-3) and Eq. 1 summed over the joints every cable passes
  (:func:`..hannan_walker.replay.cable_changes_from_joint_angles`);
* :func:`model_plant` -- a registered ``run(robot, load, options)`` model as the plant: one static
  solve from the straight reference per call (the choice of a co-simulation by static re-solves:
  ``docs/models.md``, "Closed loop");
* :class:`ConsistentCCPlant` -- the controller's own model as the plant: the cables are read back
  through Eq. 1 (:func:`..hannan_walker.replay.joint_angles_from_cable_changes`) into CC arcs.  With
  it the closed loop must equal the open loop (``tests/experiments/test_closed_loop.py``).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from ...kinematics import forward_kinematics, joint_angle_from_curvature
from ...models.result import PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot, TendonActuation
from ..hannan_walker.replay import cable_changes_from_joint_angles, joint_angles_from_cable_changes

__all__ = ["hw_cable_map", "model_plant", "ConsistentCCPlant", "cc_result"]


def hw_cable_map(robot: Robot, n_links: int = 16) -> Callable[[np.ndarray], np.ndarray]:
    """``kappa (n_sections,) -> cable changes (n_tendons,)`` [m] of the jointed robot (Eq. 1-3)."""
    ell = np.asarray(robot.section_lengths, dtype=float)
    per = int(n_links) // robot.n_sections

    def cables(kappa: np.ndarray) -> np.ndarray:
        q = np.repeat(joint_angle_from_curvature(np.asarray(kappa, dtype=float), ell, per), per)
        return cable_changes_from_joint_angles(q, robot, n_links)

    return cables


def model_plant(run: Callable, robot: Robot, options: SolverOptions, pretension: float) -> Callable:
    """``cable changes -> PhysicsResult`` of model ``run`` (static, length control, ``pretension`` [N])."""

    def plant(cables: np.ndarray) -> PhysicsResult:
        act = TendonActuation("length", tuple(float(c) for c in cables), pretension=pretension)
        return run(robot, LoadCase(actuation=act), options)

    return plant


def cc_result(kappa, robot: Robot, n_stations: int, model: str = "plan") -> PhysicsResult:
    """The CC shape of planar curvatures ``kappa`` (towards base +x for > 0) as a result, base frame."""
    k = np.asarray(kappa, dtype=float)
    ell = np.asarray(robot.section_lengths, dtype=float)
    phi = np.zeros_like(k)
    s = np.linspace(0.0, robot.length, int(n_stations))
    frames = forward_kinematics(k, phi, ell, s=s)
    return PhysicsResult(model=model, stations=s, positions=frames[:, :3, 3], tip_frame=forward_kinematics(k, phi, ell),
                         length_change=0.0, tendon_tensions=np.full(robot.n_tendons, np.nan), tip_twist=0.0,
                         solver=SolverInfo(converged=True))


class ConsistentCCPlant:
    """The controller's own CC model as a plant: cables -> Eq. 1 inverse -> equal joint angles -> CC arcs."""

    def __init__(self, robot: Robot, n_links: int = 16, n_stations: int = 17) -> None:
        self.robot, self.n_links, self.n_stations = robot, int(n_links), int(n_stations)

    def __call__(self, cables: np.ndarray) -> PhysicsResult:
        theta = joint_angles_from_cable_changes(cables, self.robot, self.n_links)
        per = self.n_links // self.robot.n_sections
        kappa = theta * per / np.asarray(self.robot.section_lengths)  # Eq. 2-3: k = N theta / s
        return cc_result(kappa, self.robot, self.n_stations, model="cc_consistent")
