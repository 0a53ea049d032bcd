"""Units and frames of the result-table columns (what the store writes into the Parquet field metadata).

:data:`COLUMNS` names the result columns the runner writes (``docs/architecture.md``, "Result
tables"); each takes its unit from the one unit table (:func:`workbench.units.unit_of`; ``""``
dimensionless, ``None`` a category or text).  :data:`FRAMES` names the frame of the vector
columns (``"base"`` / ``"world"``).  :func:`column_meta` also knows ``series.<name>`` (same unit
and frame as the column of that name, sampled at ``time``) and the ``p.load.*`` /
``p.solver.*`` parameters whose unit the study format fixes (dimensionless ones carry none).  Robot and scenario parameters are preset-specific and
``x.*`` extras study-specific: the field metadata leaves their units open (:func:`workbench.results.load` takes them from the
unit table).  Checked by ``tests/study/test_results.py``.
"""

from __future__ import annotations

from ..units import unit_of

__all__ = ["COLUMNS", "FRAMES", "column_meta", "field_metadata"]

#: the result columns the runner writes (the study kinds' own columns are not described here)
COLUMNS = (
    "case_id", "model", "status", "error", "failure", "wall_time", "robot_length", "robot_gravity",
    "tip_x", "tip_y", "tip_z", "tip_world_x", "tip_world_y", "tip_world_z", "tip_frame", "length_change",
    "tip_twist", "converged", "iterations", "path_steps", "path_event", "path_event_fraction", "stations", "positions", "tendon_tensions", "joint_angles", "time",
    "tip_position", "commands", "tendon_stretch", "tendon_lengths", "backbone", "backbone_time",
)

#: the frame of each vector-valued result column (the tip transform: base <- tip)
FRAMES: dict[str, str] = {
    "tip_x": "base", "tip_y": "base", "tip_z": "base", "tip_world_x": "world", "tip_world_y": "world",
    "tip_world_z": "world", "tip_frame": "base", "positions": "base", "tip_position": "base", "backbone": "base",
}


def column_meta(name: str) -> tuple[str | None, str | None]:
    """``(unit, frame)`` of column ``name`` (``(None, None)`` when not known here)."""
    if name.startswith("series."):
        return column_meta(name[len("series."):])
    if name.startswith(("p.load.", "p.solver.")):
        return unit_of(name) or None, ("base" if name.endswith(("tip_force", "tip_torque")) else None)
    if name not in COLUMNS:  # preset, scenario and study-specific keys: left open
        return None, None
    return unit_of(name), FRAMES.get(name)


def field_metadata(name: str) -> dict[bytes, bytes] | None:
    """The Parquet field metadata of column ``name``: ``{b"unit": ..., b"frame": ...}`` (``None``: nothing known)."""
    unit, frame = column_meta(name)
    meta = {}
    if unit is not None:
        meta[b"unit"] = unit.encode()
    if frame is not None:
        meta[b"frame"] = frame.encode()
    return meta or None
