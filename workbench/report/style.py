"""What every report figure shares: the style, model and axis labels, number formatting.

Model labels and colours come from ``workbench.registry.table("models")`` (a model without a colour
gets a fallback colour per report).  Pure presentation helpers, no figure builders (those are in
:mod:`.shapes`, :mod:`.sweeps`, :mod:`.dynamics`, listed by :mod:`.figures`).  Checked by
``tests/report/test_report_build.py`` and the report tier of ``tests/regression``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ..compare.table import DERIVED_LABELS
from ..registry import row_info
from .load import ResultSet, category_label
from .units import label_of, shown_unit, unit_depends_on

__all__ = [
    "STYLE",
    "THRESHOLDS",
    "ReportFigure",
    "model_label",
    "model_color",
    "pair_label",
    "axis_label",
    "short_label",
    "fmt",
    "code_categories",
    "value_text",
    "point_links",
]

#: rcParams used for every report figure (applied with ``matplotlib.rc_context``).
STYLE: dict[str, Any] = {
    "font.size": 9.5,
    "axes.titlesize": 10,
    "axes.labelsize": 9.5,
    "legend.fontsize": 8.5,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.6,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "lines.linewidth": 1.6,
    "figure.dpi": 110,
    "savefig.dpi": 110,
    "svg.fonttype": "none",
}

_FALLBACK = ["#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"]
THRESHOLDS = (1.0, 5.0, 10.0)


@dataclass(frozen=True)
class ReportFigure:
    """One report figure: ``name`` is the file stem and HTML id."""

    name: str
    title: str
    figure: Figure
    summary: str
    cases: tuple[str, ...] = ()
    """``case_id`` of every case the figure draws (the per-case table links to the figure)."""
    points: tuple[tuple[Any, float, float, str, str, str], ...] = ()
    """Clickable points ``(axes, x, y, case_id, model, tooltip)`` in data coordinates: the page puts a link to
    that case's table row over each (:func:`point_links`)."""


def point_links(ax, x, y, case_ids, models, tips) -> list[tuple[Any, float, float, str, str, str]]:
    """``ReportFigure.points`` entries for plotted points (finite ones only)."""
    out = []
    for xi, yi, c, m, t in zip(x, y, case_ids, models, tips):
        if np.isfinite(xi) and np.isfinite(yi):
            out.append((ax, float(xi), float(yi), str(c), str(m), str(t)))
    return out


def model_label(m: str) -> str:
    """Display name of model ``m`` (its registry label, :func:`~workbench.registry.row_info`; unknown names as they are)."""
    info = row_info(m)
    return info.label if info is not None else m


def _color_of(m: str) -> str | None:
    info = row_info(m)
    return info.color if info is not None else None


def model_color(m: str, models: Sequence[str] = ()) -> str:
    """Line colour of model ``m``: its registry colour, else a fallback colour.

    Fallback colours go, in order, to the models of ``models`` without a registry colour, so
    every such model of one report gets its own colour.
    """
    color = _color_of(m)
    if color is not None:
        return color
    unknown = [x for x in models if _color_of(x) is None] or [m]
    i = unknown.index(m) if m in unknown else 0
    return _FALLBACK[i % len(_FALLBACK)]


def pair_label(ref: str, model: str) -> str:
    return f"{model_label(ref)} vs {model_label(model)}"


_PARAM_LABELS = {
    "p.load.bend_angle": r"bending angle $\theta$ [rad]",
    "kappaL": DERIVED_LABELS["kappaL"],
    "gamma": DERIVED_LABELS["gamma"],
    "d_over_L": DERIVED_LABELS["d_over_L"],
}
_SHORT = {"kappaL": r"$\kappa L$", "gamma": r"$\gamma$", "d_over_L": r"$d/L$", "p.load.bend_angle": r"$\theta$"}


def axis_label(col: str, labels: Mapping[str, str] | None = None) -> str:
    if labels and col in labels:
        return labels[col]
    if col in _PARAM_LABELS:
        return _PARAM_LABELS[col]
    return label_of(col)


def short_label(col: str, labels: Mapping[str, str] | None = None) -> str:
    """Symbol-like label for text summaries (plain text, mathtext stripped)."""
    plain = {"kappaL": "κL", "gamma": "γ", "d_over_L": "d/L", "p.load.bend_angle": "θ"}
    if col in plain:
        return plain[col]
    if labels and col in labels:
        # the symbol part of a user label: "eyelet spacing ds/L (0 = continuous)" -> "eyelet spacing ds/L",
        # "gravity parameter γ = qL³/EI" -> "gravity parameter γ"
        short = re.split(r"\s+[(\[]|\s+=\s+", labels[col], maxsplit=1)[0].strip()
        return short or labels[col]
    return re.split(r"\s+=\s+", label_of(col, unit=""), maxsplit=1)[0]


def fmt(x: float) -> str:
    """Compact number formatting for summaries and titles."""
    if x is None or not np.isfinite(x):
        return "n/a"
    if x == 0:
        return "0"
    if float(x).is_integer() and abs(x) < 1e4:
        return str(int(x))
    a = abs(x)
    if a >= 1e4 or a < 1e-3:
        return f"{x:.2e}"
    if a >= 100:
        return f"{x:.0f}"
    if a >= 10:
        return f"{x:.1f}"
    return f"{x:.3g}"


def log_worthy(values: np.ndarray) -> bool:
    v = values[np.isfinite(values)]
    return v.size > 1 and np.all(v > 0) and v.max() / v.min() > 20


def is_geometric(values: np.ndarray) -> bool:
    v = np.unique(values[np.isfinite(values)])
    if v.size < 3 or np.any(v <= 0):
        return False
    r = v[1:] / v[:-1]
    return bool(np.allclose(r, r[0], rtol=0.05) and r[0] > 1.5 and v[-1] / v[0] >= 10)


def baseline_pairs(cmp: pd.DataFrame, baseline: str) -> list[tuple[str, str]]:
    """The ``(reference column, model)`` pairs of a comparison table, those against ``baseline`` first."""
    if cmp.empty:
        return []
    pairs = list(dict.fromkeys(zip(cmp["reference"], cmp["model"])))
    first = [p for p in pairs if p[0] == baseline]
    return first + [p for p in pairs if p[0] != baseline]


def value_text(col: str, v: Any, labels: Mapping[str, str] | None = None, row: Mapping[str, Any] | None = None) -> str:
    """``v`` with its unit (``0.1 kg``, ``line``); the unit from the study label or :mod:`.units`."""
    if not _isnum(v):
        return str(v)
    unit = None
    if labels and col in labels:
        m = re.search(r"\[([^\]]+)\]", labels[col])
        unit = m.group(1) if m else ""
    if unit is None:
        unit = shown_unit(col) or ""
        dep = unit_depends_on(col)
        if dep is not None and row is not None:
            other = row.get(dep.column, row.get(f"p.{dep.column}"))
            unit = dep.units.get(str(other), "")
    return f"{fmt(float(v))} {unit}".strip()


def case_title(row: Mapping[str, Any], axes: Sequence[str], labels) -> str:
    parts = [f"{short_label(a, labels)} = {value_text(a, row[a], labels, row)}"
             for a in axes[:3] if a in row and row[a] is not None]
    return ", ".join(parts) if parts else f"case {str(row.get('case_id', ''))[:8]}"


def _isnum(v: Any) -> bool:
    try:
        return np.isfinite(float(v))
    except (TypeError, ValueError):
        return False


def axis_value(study: ResultSet, col: str, v: float) -> str:
    """A plotted axis value as text (category name for categorical axes)."""
    cats = study.categories.get(col)
    if cats and np.isfinite(v) and 0 <= int(v) < len(cats):
        return cats[int(v)]
    return fmt(v)


def category_ticks(ax, study: ResultSet, col: str, which: str) -> None:
    """Label a categorical axis (values coded 0..n-1 by :func:`code_categories`)."""
    cats = study.categories.get(col)
    if cats:  # long labels (swept vectors) slanted, so neighbours do not overlap
        slant = {"rotation": 30, "ha": "right"} if which == "x" and max(map(len, cats)) > 8 else {}
        getattr(ax, f"set_{which}ticks")(range(len(cats)), cats, **slant)


def code_categories(study: ResultSet, table: pd.DataFrame) -> pd.DataFrame:
    """Copy of ``table`` with the categorical axes replaced by their codes 0..n-1."""
    out = table.copy()
    for col, cats in study.categories.items():
        if col in out:
            out[col] = out[col].map(category_label).map({c: i for i, c in enumerate(cats)}).astype(float)
    return out


def slug(col: str) -> str:
    s = col[2:] if col.startswith("p.") else col
    return "".join(ch if ch.isalnum() else "_" for ch in s).strip("_")

