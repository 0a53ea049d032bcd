"""What a shape figure or the 3-D view draws of one case: frame, gravity, disks and tendons.

:func:`case_scene` rebuilds the case's robot from its ``p.robot.*`` cells (the recorded
parameters rebuild the robot that ran, ``docs/architecture.md``) and keeps what drawing needs:
the base pose (world <- base), gravity in the world frame, disk stations and tendon routing.
A row without a rebuildable robot (e.g. a series-parallel stack, whose module base *is* the
world frame, z up; or a preset rebuild that raises ``KeyError`` / ``TypeError`` / ``ValueError``)
gets the identity pose and ``known = False``; other errors of the rebuild propagate.  :func:`to_frame` maps base-frame
points into the figure's frame (the 3-D viewer places disks and tendons on the drawn backbone
itself, ``assets/viewer.js``).  Checked by ``tests/report/test_viewer.py`` (world frame, gravity
along world -z, base frame on request) and ``tests/robot/test_frames.py``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Mapping

import numpy as np

from ..robot.frames import base_points_to_world, base_vectors_to_world
from ..study.build import build_robot
from ..study.params import section_params

__all__ = ["CaseScene", "case_scene", "to_frame", "gravity_in", "base_vectors_in"]


@dataclass(frozen=True)
class CaseScene:
    """Drawing data of one case (arrays in SI units; ``rotation`` world <- base)."""

    rotation: np.ndarray
    position: np.ndarray
    gravity_world: np.ndarray
    disk_s: np.ndarray
    disk_radius: np.ndarray
    tendons: tuple[tuple[float, float, float, float], ...]
    """``(sigma [rad], offset at the base [m], offset at its end [m], end arc length [m])`` per tendon."""
    known: bool


_IDENTITY = CaseScene(np.eye(3), np.zeros(3), np.zeros(3), np.zeros(0), np.zeros(0), (), False)


@lru_cache(maxsize=512)
def _scene_from_json(robot_json: str) -> CaseScene:
    try:
        robot = build_robot(json.loads(robot_json))
    except (KeyError, TypeError, ValueError):
        # the rebuild's documented errors (unknown preset, a parameter it does not take, an invalid
        # value): draw in the base frame with known = False; anything else is a bug and propagates
        return _IDENTITY
    tendons = []
    ends = robot.section_ends
    for j, sigma, group in robot.tendon_table():
        tendons.append((float(sigma), float(group.offset), float(group.offset_at(1.0)), float(ends[j])))
    disk_s = robot.disk_stations()
    radius = np.array([max([t[1] + (t[2] - t[1]) * min(s / t[3], 1.0) for t in tendons if s <= t[3] + 1e-12] or [0.0])
                       for s in disk_s])
    radius = np.where(radius > 0, 1.25 * radius, 0.0)
    return CaseScene(np.asarray(robot.base_rotation, float), np.asarray(robot.base_position, float),
                     np.asarray(robot.gravity, float), disk_s, radius, tuple(tendons), True)


def case_scene(row: Mapping[str, Any]) -> CaseScene:
    """The :class:`CaseScene` of a result row (cached per robot parameter set)."""
    params = section_params(row, "robot")
    if "preset" not in params:
        return _IDENTITY
    return _scene_from_json(json.dumps(params, sort_keys=True, default=str))


def to_frame(points_base, scene: CaseScene, frame: str) -> np.ndarray:
    """Base-frame points ``(..., 3)`` in ``frame`` ("world" or "base") [m]."""
    if frame == "base":
        return np.asarray(points_base, dtype=float)
    return base_points_to_world(points_base, scene.rotation, scene.position)


def gravity_in(scene: CaseScene, frame: str) -> np.ndarray:
    """Gravity ``(3,)`` [m/s^2] in ``frame``."""
    if frame == "world":
        return scene.gravity_world
    return scene.gravity_world @ scene.rotation  # world -> base


def base_vectors_in(v, scene: CaseScene, frame: str) -> np.ndarray:
    """Free vectors given in the base frame, in ``frame``."""
    return np.asarray(v, float) if frame == "base" else base_vectors_to_world(v, scene.rotation)
