"""Units and frames of the result-table columns (what the store writes into the Parquet field metadata).

:data:`COLUMNS` maps each result column the runner writes (``docs/architecture.md``, "Result
tables") to ``(unit, frame)``; ``unit`` ``""`` is dimensionless, ``None`` a category or text;
``frame`` ``"base"`` / ``"world"`` for vectors, ``None`` otherwise.  :func:`column_meta` also
knows ``series.<name>`` (same unit and frame as the column of that name, sampled at ``time``)
and the ``p.load.*`` / ``p.solver.*`` parameters whose unit the study format fixes
(:data:`workbench.study.messages.UNITS`).  Robot and scenario parameters are preset-specific:
their units are left open here (the report's unit table, ``workbench.report.units``, names the
known ones; :func:`workbench.results.load` uses both).  Checked by ``tests/study/test_results.py``.
"""

from __future__ import annotations

from .messages import UNITS

__all__ = ["COLUMNS", "column_meta", "field_metadata"]

COLUMNS: dict[str, tuple[str | None, str | None]] = {
    "case_id": (None, None), "model": (None, None), "status": (None, None), "error": (None, None),
    "failure": (None, None), "wall_time": ("s", None), "robot_length": ("m", None),
    "robot_gravity": ("m/s^2", None),
    "tip_x": ("m", "base"), "tip_y": ("m", "base"), "tip_z": ("m", "base"),
    "tip_world_x": ("m", "world"), "tip_world_y": ("m", "world"), "tip_world_z": ("m", "world"),
    "tip_frame": ("m", "base"),  # homogeneous base <- tip transform: rotation dimensionless, translation [m]
    "length_change": ("m", None), "tip_twist": ("rad", None), "converged": (None, None), "iterations": ("", None),
    "stations": ("m", None), "positions": ("m", "base"), "tendon_tensions": ("N", None),
    "joint_angles": ("rad", None), "time": ("s", None),
    "tip_position": ("m", "base"), "commands": (None, None), "tendon_stretch": ("m", None),
    "tendon_lengths": ("m", None), "backbone": ("m", "base"), "backbone_time": ("s", None),
}


def column_meta(name: str) -> tuple[str | None, str | None]:
    """``(unit, frame)`` of column ``name`` (``(None, None)`` when not known here)."""
    if name.startswith("series."):
        return COLUMNS.get(name[len("series."):], (None, None))
    if name.startswith(("p.load.", "p.solver.")):
        return UNITS.get(name.rsplit(".", 1)[1]), ("base" if name.endswith(("tip_force", "tip_torque")) else None)
    return COLUMNS.get(name, (None, None))


def field_metadata(name: str) -> dict[bytes, bytes] | None:
    """The Parquet field metadata of column ``name``: ``{b"unit": ..., b"frame": ...}`` (``None``: nothing known)."""
    unit, frame = column_meta(name)
    meta = {}
    if unit is not None:
        meta[b"unit"] = unit.encode()
    if frame is not None:
        meta[b"frame"] = frame.encode()
    return meta or None
