"""What a shape figure or the 3-D view draws of one case: frame, gravity, disks and tendons.

:func:`case_scene` rebuilds the case's robot from its ``p.robot.*`` cells (the recorded
parameters rebuild the robot that ran, ``docs/architecture.md``) and keeps what drawing needs:
the base pose (world <- base), gravity in the world frame, disk stations and tendon routing.
A row without a rebuildable robot (e.g. a series-parallel stack, whose module base *is* the
world frame, z up) gets the identity pose and ``known = False``.  :func:`to_frame` maps base-frame
points into the figure's frame; :func:`disk_rings` and :func:`tendon_paths` place disks and
tendons on a drawn backbone with a rotation-minimising frame (the backbone's twist is not
stored, so tendon paths are drawn without it).  Checked by ``tests/report/test_scene.py``.
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

__all__ = ["CaseScene", "case_scene", "to_frame", "gravity_in", "disk_rings", "tendon_paths"]


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
    except Exception:  # noqa: BLE001 - any rebuild failure: draw in the base frame, say so
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


def _rm_frames(P: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tangents and a rotation-minimising normal pair along a polyline ``(m, 3)`` (base x transported)."""
    d = np.gradient(P, axis=0)
    t = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-15)
    e1 = np.zeros_like(P)
    e = np.array([1.0, 0.0, 0.0])
    for i in range(len(P)):
        e = e - np.dot(e, t[i]) * t[i]
        n = np.linalg.norm(e)
        e = e / n if n > 1e-12 else np.cross(t[i], [0.0, 1.0, 0.0])
        e1[i] = e
    return t, e1, np.cross(t, e1)


def _on_backbone(P: np.ndarray, stations: np.ndarray, s: np.ndarray):
    t, e1, e2 = _rm_frames(P)
    c = np.stack([np.interp(s, stations, P[:, k]) for k in range(3)], -1)
    a = np.stack([np.interp(s, stations, e1[:, k]) for k in range(3)], -1)
    b = np.stack([np.interp(s, stations, e2[:, k]) for k in range(3)], -1)
    return c, a, b


def disk_rings(P, stations, scene: CaseScene, n: int = 20) -> np.ndarray:
    """Disk outlines on a base-frame backbone: ``(n_disks, n + 1, 3)`` base-frame points [m]."""
    P, st = np.asarray(P, float), np.asarray(stations, float)
    keep = (scene.disk_radius > 0) & (scene.disk_s <= st[-1] + 1e-9)
    if not keep.any() or len(P) < 2:
        return np.zeros((0, n + 1, 3))
    c, a, b = _on_backbone(P, st, scene.disk_s[keep])
    u = np.linspace(0, 2 * np.pi, n + 1)
    r = scene.disk_radius[keep][:, None, None]
    return c[:, None, :] + r * (np.cos(u)[None, :, None] * a[:, None, :] + np.sin(u)[None, :, None] * b[:, None, :])


def tendon_paths(P, stations, scene: CaseScene) -> list[np.ndarray]:
    """One base-frame polyline per tendon, through its disks from the base plate to its end [m]."""
    P, st = np.asarray(P, float), np.asarray(stations, float)
    out = []
    for sigma, d0, d1, s_end in scene.tendons:
        s = np.r_[0.0, scene.disk_s[scene.disk_s <= s_end + 1e-12]]
        s = s[s <= st[-1] + 1e-9]
        if s.size < 2:
            continue
        c, a, b = _on_backbone(P, st, s)
        d = (d0 + (d1 - d0) * s / s_end)[:, None]
        out.append(c + d * (np.cos(sigma) * a + np.sin(sigma) * b))
    return out


def base_vectors_in(v, scene: CaseScene, frame: str) -> np.ndarray:
    """Free vectors given in the base frame, in ``frame``."""
    return np.asarray(v, float) if frame == "base" else base_vectors_to_world(v, scene.rotation)
