"""What the generic report needs of a series-parallel result: the legs in the 3-D view, the pose axes.

Registered as the ``lines`` and ``axes`` hooks of the ``series_parallel`` row of
``workbench.registry.KINDS`` (:class:`workbench.registry.KindInfo`): :func:`leg_lines` gives
the leg centrelines of the stored ``legs`` column as extra polylines of the report's 3-D view;
:func:`pose_columns` names the commanded-pose parameters that vary the cases (the study file
has no ``[sweep]``).  Checked by ``tests/report/test_viewer.py`` and the series-parallel report
(regression tier).
"""

from __future__ import annotations

from typing import Any, Callable, Mapping, Sequence

import numpy as np

from ...compare.table import array_cell
from ...study.store import MANIFEST, array_shapes

__all__ = ["leg_lines", "pose_columns"]


def _leg_nodes(folder) -> int | None:
    """Nodes per leg (the ``legs`` column's stored shape ``(modules, legs, nodes, 3)``), if the folder has legs."""
    if not (folder / MANIFEST).exists():
        return None
    try:
        shape = array_shapes(folder).get("legs")
    except Exception:  # noqa: BLE001 - a folder without the schema part: no leg shapes
        return None
    return int(shape[2]) if shape and len(shape) == 4 else None


def leg_lines(study) -> Callable[[Mapping[str, Mapping[str, Any]]], list[tuple[str, np.ndarray]]]:
    """For one case's rows ``{model: row}``: ``[(model, legs (k, nodes, 3)), ...]`` in the base frame."""
    n_nodes = _leg_nodes(study.path)

    def lines(rows: Mapping[str, Mapping[str, Any]]) -> list[tuple[str, np.ndarray]]:
        out = []
        for m, r in rows.items():
            legs = array_cell(r.get("legs"))
            if legs is not None and n_nodes:
                out.append((m, legs.reshape(-1, n_nodes, 3)))
        return out

    return lines


def pose_columns(columns: Sequence[str]) -> list[str]:
    """The commanded-pose parameter columns (``p.pose.*``) among ``columns``."""
    return [c for c in columns if str(c).startswith("p.pose.")]
