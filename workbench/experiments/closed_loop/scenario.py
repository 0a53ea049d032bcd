"""The ``closed_loop`` scenario: the path and controller of a closed-loop case, and the plan's final cables.

Registered as ``registry.SCENARIOS["closed_loop"]`` (format: :mod:`workbench.study.scenarios`).  Its
keyword parameters are the case's path (a straight tip line in the base x-z plane, or the
approach in a grasp configuration, as in ``hannan_walker_line``) and controller
(:class:`.controller.ControllerSettings`); the returned load is the open-loop plan's cable
commands at the last sample (what the rows record as ``p.load.length_changes``, and what the
study's validation dry-builds).  The closed-loop study kind (:mod:`.kind`) reads the same
parameters to run the loops.  Pure numpy.  Checked by ``tests/experiments/test_closed_loop.py``.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from ...kinematics import line_path
from .controller import ControllerSettings, cc_plan, start_configuration
from .plants import hw_cable_map

__all__ = ["closed_loop", "CONTROLLER_KEYS", "loop_path", "null_space_target", "joint_count"]

#: Scenario parameters that are :class:`.controller.ControllerSettings` fields.
CONTROLLER_KEYS = ("steps_per_sample", "gain", "null_gain", "noise", "noise_seed")


def loop_path(sc: Mapping[str, Any]) -> np.ndarray:
    """``(n_samples, 3)`` tip targets of the scenario's line, base frame [m]."""
    a = np.array([float(sc["start_x"]), 0.0, float(sc["start_z"])])
    b = np.array([float(sc["end_x"]), 0.0, float(sc["end_z"])])
    return line_path(a, b, int(sc["n_samples"]))


def null_space_target(robot, sc: Mapping[str, Any]) -> np.ndarray | None:
    """Eq. 11's ``q_d`` [1/m] for ``shape = "grasp"`` (bend angles / section lengths), else ``None``."""
    if sc["shape"] == "line":
        return None
    return np.asarray(sc["grasp_bend_angles"], dtype=float) / np.asarray(robot.section_lengths, dtype=float)


def joint_count(robot) -> int:
    """Joints of the jointed robot: one per disk (Hannan & Walker: 4 per section, 16)."""
    return int(sum(s.n_disks for s in robot.sections))


def closed_loop(
    robot,
    *,
    shape: str = "line",
    start_x: float = 0.25,
    start_z: float = 0.70,
    end_x: float = 0.35,
    end_z: float = 0.60,
    n_samples: int = 6,
    grasp_bend_angles: list | None = None,
    steps_per_sample: int = 3,
    gain: float = 1.0,
    null_gain: float = 0.2,
    noise: float = 0.0,
    noise_seed: int = 0,
) -> dict[str, Any]:
    """The open-loop plan's cable commands at the path's last sample.

    Parameters
    ----------
    robot : Robot
        A planar jointed robot (cables at sigma in {0, pi}; ``hannan_walker``).
    shape : {"line", "grasp"}
        ``"line"``: no null-space task; ``"grasp"``: Eq 11's null-space term pulls the section bend
        angles towards ``grasp_bend_angles`` (``kappa_i l_i`` [rad], > 0 towards base +x).
    start_x, start_z, end_x, end_z : float
        The tip line in the base x-z plane [m].
    n_samples : int
        Path samples (>= 2), both ends included.
    steps_per_sample, gain, null_gain, noise, noise_seed
        :class:`.controller.ControllerSettings` (noise [m]: the closed loop's tip measurement).

    Returns
    -------
    dict
        ``mode = "length"``, ``length_changes`` (n_tendons,) [m].
    """
    if shape not in ("line", "grasp"):
        raise ValueError(f"scenario closed_loop: shape must be 'line' or 'grasp', got {shape!r}")
    if n_samples < 2:
        raise ValueError(f"scenario closed_loop needs n_samples >= 2, got {n_samples}")
    if shape == "grasp" and (grasp_bend_angles is None or len(grasp_bend_angles) != robot.n_sections):
        raise ValueError(f"scenario closed_loop: shape = 'grasp' needs grasp_bend_angles with {robot.n_sections} "
                         f"entries (one bend angle per section) [rad], got {grasp_bend_angles!r}")
    sc = {"shape": shape, "start_x": start_x, "start_z": start_z, "end_x": end_x, "end_z": end_z,
          "n_samples": n_samples, "grasp_bend_angles": grasp_bend_angles}
    path = loop_path(sc)
    try:
        settings = ControllerSettings(steps_per_sample=steps_per_sample, gain=gain, null_gain=null_gain, noise=noise,
                                      noise_seed=noise_seed)
        start_configuration(path[-1], robot.section_lengths)  # the line's end is in reach
        kappa, _ = cc_plan(path, robot.section_lengths, settings, null_space_target(robot, sc))
    except ValueError as e:
        raise ValueError(f"scenario closed_loop: {e}") from None
    cables = hw_cable_map(robot, joint_count(robot))(kappa[-1])
    return {"mode": "length", "length_changes": [float(v) for v in cables]}
