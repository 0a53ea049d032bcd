"""Hannan & Walker's trunk as built: 16 two-DOF joints (32 DOF), 16 cables, gravity in any direction.

The paper's robot (papers/000_, Sec. 3) has 16 two-DOF joints in 4 sections and, per section, two
antagonistic cable pairs 90 degrees apart terminating on the section's last segment: 16 cables.
This preset is the spatial counterpart of the preset ``hannan_walker`` (the planar experiments'
8-cable reading): the same sections, springs, masses and cable offsets, all four cables per section
(sigma = 0, pi/2, pi, 3pi/2), and gravity along any direction ``gravity_direction`` of the world
frame.  Its parameters (defaults, units, sources) are data in ``hannan_walker_3d.toml``
(``docs/robot-format.md``, "Presets"); this module holds the formula :func:`derive` and
``build_preset("hannan_walker_3d")``, the preset itself.

The joints' two degrees of freedom are a property of the model, not of the description: the
Exudyn chain of two-DOF (Cardan, torsion-locked) joints is the registered model
``spring_link_cardan`` (:mod:`workbench.physics.spring_link.cardan`).  Checked by
``tests/experiments/test_hannan_walker_3d.py``.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Sequence

from ..description import Robot
from .data import FILES

__all__ = ["derive"]


def _direction(values: Sequence[float]) -> tuple[float, float, float]:
    v = tuple(float(x) for x in values)
    n = math.sqrt(sum(x * x for x in v)) if len(v) == 3 and all(math.isfinite(x) for x in v) else 0.0
    if len(v) != 3 or not n > 0:
        raise ValueError(f"gravity_direction must be 3 finite numbers, not all zero (world frame), got {list(values)}")
    return (v[0] / n, v[1] / n, v[2] / n)


def derive(
    *,
    total_length: float,
    diameters: Sequence[float],
    joint_stiffness: Sequence[float],
    section_masses: Sequence[float],
    tendon_stiffness: float,
    gravity: float,
    gravity_direction: Sequence[float],
    base_orientation: str,
    payload_mass: float,
    axial_stiffness: float,
) -> Robot:
    """The 32-DOF, 16-cable Hannan & Walker trunk (the formula of ``hannan_walker_3d.toml``).

    The preset ``hannan_walker`` (``FILES.hannan_walker``) with ``planar=False`` (its cable area and
    strength at their defaults) and gravity along ``gravity_direction``; the parameters, their
    defaults, units and sources are data in ``hannan_walker_3d.toml``.

    Parameters
    ----------
    total_length, diameters, joint_stiffness, section_masses, tendon_stiffness, payload_mass, axial_stiffness
        As in :func:`.hannan_walker.derive` (the paper's length and diameters; assumed
        springs, masses and cable stiffness).
    gravity : float
        Magnitude of gravity [m/s^2].
    gravity_direction : sequence of 3 float
        Direction of gravity in the **world** frame (normalised here).  With
        ``base_orientation`` it sets gravity in the base frame, e.g. ``"horizontal"`` and
        ``(0, 1, -1)`` is a horizontal trunk with gravity at 45 degrees to both cable planes.
    base_orientation : {"vertical", "horizontal", "upside_down"}
        Mounting (see :func:`~workbench.robot.orientation.base_rotation_for`).

    Returns
    -------
    Robot
        Four sections of four joints, four cables per section at the segment radius (tendon
        table order per section: sigma = 0, pi/2, pi, 3pi/2), name ``"hannan_walker_3d"``.
    """
    d = _direction(gravity_direction)
    robot = FILES.hannan_walker(total_length=total_length, diameters=diameters, joint_stiffness=joint_stiffness,
                                section_masses=section_masses, tendon_stiffness=tendon_stiffness,
                                planar=False, gravity=gravity, base_orientation=base_orientation,
                                payload_mass=payload_mass, axial_stiffness=axial_stiffness)
    g = float(gravity)
    return replace(robot, gravity=(g * d[0], g * d[1], g * d[2]), name="hannan_walker_3d")
