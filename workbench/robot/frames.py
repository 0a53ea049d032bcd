"""Base frame <-> world frame: the conversions every world-frame result and figure uses.

A robot is described and solved in its **base frame** (backbone along base +z, see
:mod:`workbench.robot.description`); a person looks at it in the **world frame**, where gravity
points along world -z for every preset.  ``Robot.base_rotation`` (world <- base) and
``Robot.base_position`` (base origin in world coordinates) relate the two:
``x_world = R @ x_base + p``.  Pure numpy; checked by ``tests/robot/test_frames.py`` (a
horizontal rod's sag points along world -z).
"""

from __future__ import annotations

import numpy as np

__all__ = ["world_from_base", "base_points_to_world", "base_vectors_to_world", "world_vectors_to_base"]


def world_from_base(rotation, position=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Homogeneous transform world <- base, shape (4, 4).

    Parameters
    ----------
    rotation : array_like, shape (3, 3)
        Rotation world <- base (columns: the base axes in world coordinates).
    position : array_like, shape (3,)
        Base origin in the world frame [m].
    """
    T = np.eye(4)
    T[:3, :3] = np.asarray(rotation, dtype=float)
    T[:3, 3] = np.asarray(position, dtype=float)
    return T


def base_points_to_world(points, rotation, position=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Points in the base frame -> world frame, ``(..., 3) -> (..., 3)`` [m]."""
    P = np.asarray(points, dtype=float)
    return P @ np.asarray(rotation, dtype=float).T + np.asarray(position, dtype=float)


def base_vectors_to_world(vectors, rotation) -> np.ndarray:
    """Free vectors (forces, directions) in the base frame -> world frame, ``(..., 3) -> (..., 3)``."""
    return np.asarray(vectors, dtype=float) @ np.asarray(rotation, dtype=float).T


def world_vectors_to_base(vectors, rotation) -> np.ndarray:
    """Free vectors in the world frame -> base frame (e.g. gravity), ``(..., 3) -> (..., 3)``."""
    return np.asarray(vectors, dtype=float) @ np.asarray(rotation, dtype=float)
