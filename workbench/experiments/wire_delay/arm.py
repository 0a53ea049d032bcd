"""Cojocaru's whole arm: the wire-delay move of the first section with the two upper sections passive.

The paper's arm (papers/001_, Sec. 5.2) has three tronconic sections, more than 1 m, three wires each,
all motors in the base; its kinematics are "decoupled": "the three segments are controlled
separately, without considering the interaction between them" (Sec. 3), and the experiment of
Sec. 5.1 moves one segment.  Here segment 1 (the base section) makes that move -- every wire at
constant speed to (theta, alpha), one wire started late -- while segments 2 and 3 are *passive*:
not commanded to move.  Their wires, however, run through segment 1 (on the same cone rim, offsets
tapering along their whole path), so what "passive" means for the motors decides what happens:

``"held"``
    the decoupled controller's command: the upper segments' own (theta, alpha) stay (0, 0), so their
    motors hold the wire lengths (change 0) while the wires' paths through the bent segment 1 change;
``"compensated"``
    the coupled command: each upper wire is paid out / reeled in by the change of its own path through
    segment 1 (:func:`passive_wire_changes`, Eq 4-11 of that path), at the same constant speed, so the
    upper segments stay straight in CC kinematics;
``"slack"``
    released motors: every upper wire is paid out beyond any path increase (by ``slack_margin``), so
    it carries no tension and the upper segments are held by the rod alone.

Used by the scenario ``wire_delay_arm`` (:mod:`.scenario`) and the arm figures (:mod:`.figures_arm`).
Pure numpy.  Checked by ``tests/experiments/test_wire_delay_arm.py``.
"""

from __future__ import annotations

import math

import numpy as np

from ...robot import Robot
from .analysis import wire_delay_commands, wire_lengths_tronconic_workbench

__all__ = ["PASSIVE_MODES", "passive_wire_changes", "ArmCommands", "arm_commands"]

PASSIVE_MODES = ("held", "compensated", "slack")


def passive_wire_changes(robot: Robot, theta: float, alpha: float) -> np.ndarray:
    """Change of every upper wire's path through the first section bent to ``(theta, alpha)`` [m].

    Each upper wire runs through section 1 from offset ``offset_at(0)`` to ``offset_at(H_1 / l_w)``
    (``l_w`` its routed length: its group's taper); its path there is Cojocaru's Eq 4-11 wire of that
    tronconic piece (:func:`.analysis.wire_lengths_tronconic_workbench`, direction ``phi = alpha + pi``).

    Returns
    -------
    ndarray, shape (n_tendons - 3,)
        In :meth:`Robot.tendon_table` order after the first section's three wires (> 0: the path grows).
    """
    H = robot.sections[0].length
    ends = robot.section_ends
    out = []
    for j, sigma, grp in robot.tendon_table():
        if j == 0:
            continue
        f = H / ends[j]
        d0, d1 = grp.offset_at(0.0), grp.offset_at(f)
        sig = np.asarray(grp.angles, dtype=float)
        i = int(np.argmin(np.abs(np.angle(np.exp(1j * (sig - sigma))))))
        bent = wire_lengths_tronconic_workbench(theta, alpha + math.pi, H, d0, d1, sig)[i]
        straight = wire_lengths_tronconic_workbench(0.0, 0.0, H, d0, d1, sig)[i]
        out.append(float(bent - straight))
    return np.asarray(out)


class ArmCommands:
    """Motor commands of the whole arm (every array in tendon-table order, shape (n_tendons,)).

    Attributes
    ----------
    length_changes : ndarray
        Final change of every wire's free length [m].
    start_delays, ramp_durations : tuple of float
        Start of every wire's constant-speed move and its duration [s].
    """

    def __init__(self, length_changes, start_delays, ramp_durations) -> None:
        self.length_changes = np.asarray(length_changes, dtype=float)
        self.start_delays = tuple(float(v) for v in start_delays)
        self.ramp_durations = tuple(float(v) for v in ramp_durations)


def arm_commands(robot: Robot, *, theta: float, alpha: float, move_time: float, delay: float, delayed_wire: int,
                 passive: str, slack_margin: float) -> ArmCommands:
    """Section 1's wire-delay move (:func:`.analysis.wire_delay_commands`) plus the passive upper wires.

    Raises
    ------
    ValueError
        Unknown ``passive`` mode, fewer than two sections, or a section without three wires.
    """
    if passive not in PASSIVE_MODES:
        raise ValueError(f"passive must be one of {', '.join(PASSIVE_MODES)}, got {passive!r}")
    if robot.n_sections < 2 or any(s.tendons is None or s.tendons.count != 3 for s in robot.sections):
        raise ValueError(f"the arm needs two or more sections with three wires each, got {robot.n_sections} "
                         f"sections and {robot.n_tendons} wires")
    first = wire_delay_commands(robot, theta=theta, alpha=alpha, move_time=move_time, delay=delay,
                                delayed_wire=delayed_wire)
    c = passive_wire_changes(robot, theta, alpha)
    upper = {"held": np.zeros_like(c), "compensated": c, "slack": np.maximum(c, 0.0) + slack_margin}[passive]
    n_up = c.size
    return ArmCommands(np.concatenate([first.length_changes, upper]), first.start_delays + (0.0,) * n_up,
                       first.ramp_durations + (float(move_time),) * n_up)
