"""The report's per-case table: one row per case x model, with its parameters, errors and links.

:func:`case_table` builds the JSON that ``assets/table.js`` renders (sortable, filterable):
the case id, model, status, the swept parameters and the other parameters that vary (with
units from :mod:`.units`), the errors against the baseline model (tip position [% L] and
[mm], orientation [deg], RMS shape [% L]), every ``x.disc_*`` column (the discretisation error
bars of a model, when the study records them), wall time and the failure reason; each row links
to the figures that draw its case and, when the 3-D view has the case, to the view.  Rows follow
the canonical order (:func:`.load.canonical_order`).  Checked by ``tests/report/test_casetable.py``
and the browser tests (one table row per case x model).
"""

from __future__ import annotations

from typing import Any, Iterable, Sequence

import numpy as np
import pandas as pd

from .load import DIMENSIONLESS_AXES, ResultSet
from .units import label_of
from .style import ReportFigure

__all__ = ["MAX_PARAM_COLUMNS", "case_table"]

#: parameter columns shown at most (swept axes first)
MAX_PARAM_COLUMNS = 10

_ERRORS = [
    ("tip_error_pct", "tip error [% L]", 1.0),
    ("tip_error", "tip error [mm]", 1e3),
    ("orientation_error_deg", "orientation error [deg]", 1.0),
    ("shape_error_rms_pct", "RMS shape error [% L]", 1.0),
]


def _scalar(v: Any) -> Any:
    """A JSON-ready cell: finite float, int, str or ``None``."""
    if v is None:
        return None
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v) if np.isfinite(v) else None
    if isinstance(v, (list, tuple, np.ndarray)):
        return None
    s = str(v)
    return s if len(s) <= 60 else s[:57] + "..."


def _param_columns(study: ResultSet) -> list[str]:
    res = study.results
    cols = [a for a in study.axes if a in res.columns]
    # a raw parameter plotted as its dimensionless group (bend angle as kappa L) is shown once
    shown_as = {raw for raw, dimless in DIMENSIONLESS_AXES.items() if dimless in cols}
    for c in res.columns:
        if c in shown_as:
            continue
        if len(cols) >= MAX_PARAM_COLUMNS:
            break
        if not str(c).startswith("p.") or c in cols:
            continue
        v = res[c].dropna()
        if v.empty or isinstance(v.iloc[0], (list, tuple, np.ndarray)):
            continue
        if v.astype(str).nunique() > 1 and v.astype(str).str.len().max() <= 60:
            cols.append(c)
    return cols


def _errors_by_row(study: ResultSet, cmp: pd.DataFrame) -> dict[tuple[str, str], dict[str, Any]]:
    """``(case_id, model) -> {error column: value}`` against the study's baseline model."""
    out: dict[tuple[str, str], dict[str, Any]] = {}
    if cmp.empty:
        return out
    sub = cmp[cmp["reference"].astype(str) == study.baseline]
    for r in sub.to_dict("records"):
        out[(str(r["case_id"]), str(r["model"]))] = {k: _scalar(r.get(k) * f if r.get(k) is not None else None)
                                                     for k, _, f in _ERRORS if k in r}
    return out


def _disc_columns(res: pd.DataFrame) -> list[str]:
    return [c for c in res.columns if str(c).startswith("x.disc_")]


def case_table(study: ResultSet, cmp: pd.DataFrame, figures: Sequence[ReportFigure],
               viewer_ids: Iterable[str] = ()) -> dict[str, Any]:
    """``{"columns": [{key, label, num}], "rows": [{cells, case, figures, view}]}`` (JSON-ready)."""
    res = study.results
    params = _param_columns(study)
    discs = _disc_columns(res)
    errs = _errors_by_row(study, cmp)
    in_view = set(map(str, viewer_ids))
    fig_of: dict[str, list[str]] = {}
    for f in figures:
        for cid in f.cases:
            fig_of.setdefault(str(cid), []).append(f.name)
    cols = [{"key": "case", "label": "case", "num": False}, {"key": "model", "label": "model", "num": False},
            {"key": "status", "label": "status", "num": False}]
    for c in params:
        num = pd.to_numeric(res[c], errors="coerce").notna().sum() == res[c].notna().sum()
        label = study.labels.get(c) or label_of(c)  # plain text: no mathtext in the table
        cols.append({"key": c, "label": label, "num": bool(num)})
    shown_errors = [(k, lab) for k, lab, _ in _ERRORS if not cmp.empty and k in cmp.columns]
    cols += [{"key": k, "label": lab, "num": True} for k, lab in shown_errors]
    cols += [{"key": c, "label": f"± {c[len('x.disc_'):]} (discretisation)", "num": True} for c in discs]
    cols += [{"key": "wall_time", "label": "wall time [s]", "num": True}, {"key": "error", "label": "reason", "num": False}]
    rows = []
    for r in res.to_dict("records"):
        cid, m = str(r["case_id"]), str(r["model"])
        cells = {"case": cid[:8], "model": m, "status": str(r.get("status")), "wall_time": _scalar(r.get("wall_time")),
                 "error": _scalar(r.get("error")) or ""}
        cells.update({c: _scalar(r.get(c)) for c in params + discs})
        cells.update(errs.get((cid, m), {}))
        rows.append({"cells": cells, "case": cid, "figures": fig_of.get(cid, []),
                     "view": cid in in_view and str(r.get("status")) == "ok"})
    return {"columns": cols, "rows": rows}
