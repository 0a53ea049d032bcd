"""What ``workbench robot show`` reports about a robot: its derived quantities, the gravity parameter and
the stresses at a stated command.

Builds on :mod:`workbench.robot.derived` (stiffness, mass, tendons, first bending frequency) and adds
what needs the layers above the robot description:

* the gravity parameter ``gamma = q L^3 / EI`` with ``q = m' |g|`` the backbone weight per length,
  defined, as for ``[derived] gravity_parameter``, for a uniform robot only (disks and payload not in
  ``q``); computed through :func:`workbench.study.build.gravity_from_parameter` (the gravity of
  ``gamma = 1`` is ``EI / (m' L^3)``, so ``gamma = |g| / that``), not a second copy of the formula;
* the stresses at a command in constant curvature (:mod:`workbench.models.cc`): the tendon tensions
  are either those that bend every section by 90 deg in the plane of the first tendon
  (:func:`~workbench.models.cc.actuation_from_arc`: the smallest non-negative tensions giving
  ``EI_j kappa_j``, ``kappa_j = (pi / 2) / L_j``) or given by the user (one tension on the first
  tendon of every group, or one per tendon); the arc follows from the moment balance
  (:func:`~workbench.models.cc.arc_from_actuation`) and the stresses from
  :func:`~workbench.models.cc.arc_stresses`: backbone ``sum T / A + EI |kappa| / W`` at mid-section,
  tendon ``T / A_t`` (:mod:`workbench.models.stress`), each judged against its strength.

Gravity, payload and tip loads are not part of the command's stresses (CC ignores them).  Checked by
``tests/robot/test_derived.py`` (gamma and the 90 deg stresses of steel_rod by hand).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..robot import Robot
from ..robot.derived import (BendingFrequency, SectionProperties, TendonProperties, first_bending_frequency,
                             is_uniform, section_properties, tendon_properties, total_mass)
from .build import gravity_from_parameter

__all__ = ["STANDARD_GRAVITY", "CommandStresses", "RobotSummary", "gravity_parameter", "command_tensions",
           "command_stresses", "summarize_robot"]

#: Standard gravity [m/s^2] (CGPM 1901), for gamma of a robot whose own gravity is zero.
STANDARD_GRAVITY = 9.80665


def gravity_parameter(robot: Robot, gravity: float | None = None) -> float | None:
    """``gamma = m' |g| L^3 / EI`` [-] of a uniform robot (``None``: not uniform or massless).

    Parameters
    ----------
    gravity : float, optional
        ``|g|`` [m/s^2]; default the magnitude of ``robot.gravity``.
    """
    cs = robot.sections[0].cross_section
    if not is_uniform(robot) or cs.mass_per_length <= 0.0:
        return None
    g = float(np.linalg.norm(robot.gravity)) if gravity is None else float(gravity)
    return g / gravity_from_parameter(1.0, cs.EI, cs.mass_per_length, robot.length)


@dataclass(frozen=True)
class CommandStresses:
    """Stresses of the CC arc of one command (:func:`command_stresses`).

    Attributes
    ----------
    command : str
        The command in words.
    tensions : tuple of float
        Tendon tensions [N], ``robot.tendon_table()`` order.
    bend_angles : tuple of float
        ``kappa_j L_j`` per section [rad].
    backbone, backbone_strength : tuple of float or None
        Backbone stress at mid-section and its strength per section [Pa] (NaN strength: unknown;
        ``None``: no stress geometry).
    tendon, tendon_strength : tuple of float or None
        Tendon stress and strength [Pa] per tendon (``None``: a tendon without area).
    """

    command: str
    tensions: tuple[float, ...]
    bend_angles: tuple[float, ...]
    backbone: tuple[float, ...] | None
    backbone_strength: tuple[float, ...] | None
    tendon: tuple[float, ...] | None
    tendon_strength: tuple[float, ...] | None

    @staticmethod
    def _ratio(stress, strength) -> float | None:
        if stress is None:
            return None
        s, y = np.asarray(stress, float), np.asarray(strength, float)
        known = np.isfinite(y)
        return float(np.max(s[known] / y[known])) if known.any() else None

    @property
    def backbone_ratio(self) -> float | None:
        """Largest backbone stress / strength [-] (``None``: unknown)."""
        return self._ratio(self.backbone, self.backbone_strength)

    @property
    def tendon_ratio(self) -> float | None:
        """Largest tendon stress / strength [-] (``None``: unknown)."""
        return self._ratio(self.tendon, self.tendon_strength)


def command_tensions(robot: Robot, tension: float | Sequence[float] | None = None) -> tuple[np.ndarray, str]:
    """The tendon tensions [N] of a command and the command in words.

    ``None``: every section bent by 90 deg in the plane of the first tendon (module docstring);
    a number: that tension on the first tendon of every group, the others slack; a sequence: one
    tension per tendon (``robot.tendon_table()`` order).

    Raises
    ------
    ValueError
        The robot has no tendons, a sequence of the wrong length, a negative or non-finite tension,
        or tendons that cannot bend the robot by 90 deg in that plane (one line each).
    """
    from ..models.cc import actuation_from_arc

    table = robot.tendon_table()
    if not table:
        raise ValueError("the robot has no tendons")
    if tension is None:
        phi = table[0][1]
        kappa = (math.pi / 2.0) / robot.section_lengths
        act = actuation_from_arc(robot, kappa, phi, "tension")
        return np.asarray(act.values, float), f"90 deg per section in CC, plane phi = {math.degrees(phi):.4g} deg"
    if np.ndim(tension) == 0:
        T = float(tension)
        values = np.zeros(len(table))
        starts = [i for i, (sec, _, _) in enumerate(table) if i == 0 or table[i - 1][0] != sec]
        values[starts] = T
        words = f"{T:g} N on the first tendon of every section"
    else:
        values = np.asarray(tension, dtype=float).reshape(-1)
        if values.size != len(table):
            raise ValueError(f"give one tension per tendon: the robot has {len(table)}, got {values.size}")
        words = "tensions " + ", ".join(f"{v:g}" for v in values) + " N"
    if not (np.all(np.isfinite(values)) and np.all(values >= 0)):
        raise ValueError(f"tensions must be finite and >= 0 N, got {values.tolist()}")
    return values, words


def command_stresses(robot: Robot, tension: float | Sequence[float] | None = None) -> CommandStresses:
    """Stresses of the CC arc of a command (:func:`command_tensions`; ValueError as there)."""
    from ..models.cc import arc_from_actuation, arc_stresses
    from ..robot import TendonActuation

    T, words = command_tensions(robot, tension)
    kappa, _phi, ell = arc_from_actuation(robot, TendonActuation("tension", tuple(T)))
    parts = arc_stresses(robot, kappa, T)

    def tup(a):
        return None if a is None else tuple(float(x) for x in a)

    return CommandStresses(words, tup(T), tup(kappa * ell), tup(parts.backbone), tup(parts.yield_strength),
                           tup(parts.tendon), tup(parts.tendon_strength))


@dataclass(frozen=True)
class RobotSummary:
    """Everything ``workbench robot show`` prints about a robot (:func:`summarize_robot`).

    ``gamma`` is at the robot's own gravity, ``gamma_standard`` at :data:`STANDARD_GRAVITY`
    (both ``None`` for a non-uniform or massless robot); ``stresses`` is ``None`` with
    ``stress_problem`` saying why when the command cannot be applied.
    """

    robot: Robot
    sections: tuple[SectionProperties, ...]
    tendons: tuple[TendonProperties, ...]
    total_mass: float
    gamma: float | None
    gamma_standard: float | None
    frequency: BendingFrequency | None
    stresses: CommandStresses | None
    stress_problem: str | None = None


def summarize_robot(robot: Robot, tension: float | Sequence[float] | None = None) -> RobotSummary:
    """The :class:`RobotSummary` of ``robot`` with the stresses at the command ``tension`` (:func:`command_tensions`).

    A user-given ``tension`` that does not fit the robot raises ValueError (bad input); the default
    90 deg command that the robot's tendons cannot produce is reported in ``stress_problem``.
    """
    if tension is not None:
        stresses, problem = command_stresses(robot, tension), None
    else:
        try:
            stresses, problem = command_stresses(robot), None
        except ValueError as e:
            stresses, problem = None, str(e)
    return RobotSummary(robot, section_properties(robot), tendon_properties(robot), total_mass(robot),
                        gravity_parameter(robot), gravity_parameter(robot, STANDARD_GRAVITY),
                        first_bending_frequency(robot), stresses, problem)
