"""How the report shows a key: its readable label with its unit, from the one unit table.

A study's ``[report] labels`` win; otherwise :func:`label_of` looks the key up in
:func:`workbench.units.quantity` (``p.`` prefix optional; the generic table plus the keys a
study kind or figure set registers).  A key without a readable name keeps its name, with the
unit left open (never a guessed unit).  A key whose unit is set by another column (a pose
amplitude: metres for a translation, radians for a rotation) has :func:`unit_depends_on`;
figures never put two units on one axis (:func:`unit_groups`).  Checked by
``tests/report/test_units.py``.
"""

from __future__ import annotations

from typing import Mapping

import pandas as pd

from ..units import UnitBy, quantity

__all__ = ["label_of", "shown_unit", "unit_depends_on", "unit_groups"]


def _named(col: str):
    """The table's entry of ``col`` when it has a readable name (what the report shows), else ``None``."""
    q = quantity(col)
    return q if q is not None and q.name is not None else None


def shown_unit(col: str) -> str | None:
    """The unit the report shows for ``col`` ("" dimensionless, ``None`` unknown, categorical or set per row)."""
    q = _named(col)
    return q.unit if q is not None and isinstance(q.unit, str) else None


def unit_depends_on(col: str) -> UnitBy | None:
    """``(column, {value: unit})`` when another column's value sets the unit of ``col``, else ``None``."""
    q = _named(col)
    return q.unit if q is not None and isinstance(q.unit, UnitBy) else None


def label_of(col: str, labels: Mapping[str, str] | None = None, unit: str | None = None) -> str:
    """Axis label of ``col``: the study's label, else ``"name [unit]"`` from the unit table, else the key.

    ``unit`` overrides the table's unit (for keys with :func:`unit_depends_on`, per group).
    """
    if labels and col in labels:
        return labels[col]
    q = _named(col)
    name = q.name if q is not None else (col[2:] if col.startswith("p.") else col)
    u = unit if unit is not None else shown_unit(col)
    return f"{name} [{u}]" if u else name


def unit_groups(df: pd.DataFrame, col: str) -> dict[str | None, pd.Index]:
    """Row index of ``df`` per unit of ``col``: one group unless the unit depends on another column.

    Rows whose unit the table does not know form the group ``None``.
    """
    dep = unit_depends_on(col)
    if dep is None:
        return {shown_unit(col): df.index}
    other, units = dep
    oc = other if other in df.columns else f"p.{other}"
    if oc not in df.columns:
        return {None: df.index}
    u = df[oc].astype(str).map(units)
    return {k: df.index[(u == k) if k is not None else u.isna()] for k in dict.fromkeys(u.where(u.notna(), None))}
