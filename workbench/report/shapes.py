"""Generic report figure: the backbone shapes of a few representative cases, every model overlaid.

:func:`shape_overlay_figures` picks the cases with the smallest, median and largest tip error of
the first model pair (or the first, middle and last case of the sweep) and draws their backbones
with equal axis scaling: the x-z projection, plus the y-z projection for spatial results.
Checked by ``tests/report/test_report_build.py`` and the report tier of ``tests/regression``.
"""

from __future__ import annotations

import textwrap

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ..compare.table import row_positions
from .load import ResultSet, numeric
from .style import ReportFigure, _case_title, _ref_pairs, fmt, model_color, model_label, pair_label

__all__ = ["shape_overlay_figures"]

#: ``(linewidth, alpha, linestyle)`` of the physics models, thick-and-light to thin.
_PHYS_STYLES = [(5.0, 0.4, "-"), (1.8, 1.0, "-"), (1.5, 1.0, (0, (5, 2))), (1.3, 1.0, ":")]


def _representative_cases(study: ResultSet, cmp: pd.DataFrame) -> tuple[list[str], str]:
    ok = study.ok
    pairs = _ref_pairs(cmp, study.reference)
    if pairs:
        ref, m = pairs[0]
        sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)].sort_values("tip_error_pct")
        ids = list(sub["case_id"])
        how = f"cases with the smallest, median and largest {pair_label(ref, m)} tip error"
    else:
        cases = ok.drop_duplicates("case_id")
        if study.axes:
            cases = cases.sort_values(list(study.axes))
        ids = list(cases["case_id"])
        how = "first, middle and last case of the sweep"
    if not ids:
        return [], how
    picks = list(dict.fromkeys([ids[0], ids[len(ids) // 2], ids[-1]]))
    if len(picks) == 1:
        how = "only case" if len(ids) == 1 else how
    elif len(picks) == 2:
        how = how.replace("smallest, median and largest", "smallest and largest").replace("first, middle and last", "first and last")
    return picks, how


_PHYS_STYLES = [(5.0, 0.4, "-"), (1.8, 1.0, "-"), (1.5, 1.0, (0, (5, 2))), (1.3, 1.0, ":")]


def _case_backbones(ok: pd.DataFrame, ids) -> list:
    """``[(case_id, first row, {model: positions (m, 3)})]`` of the cases with a backbone."""
    data = []
    for cid in ids:
        rows = ok[ok["case_id"] == cid]
        per = {}
        for _, r in rows.iterrows():
            bp = row_positions(r.to_dict())
            if bp is not None:
                per[str(r["model"])] = bp[1]
        if per:
            data.append((cid, rows.iloc[0].to_dict(), per))
    return data


def _layout(ok: pd.DataFrame, allpts: np.ndarray):
    """Views, common limits and panel size of the overlay: ``(spatial, views, lo, hi, pad, panel_w, panel_h)``."""
    L = float(np.nanmax(numeric(ok["robot_length"]))) if "robot_length" in ok else float(np.ptp(allpts[:, 2]))
    spatial = bool(np.nanmax(np.abs(allpts[:, 1])) > 1e-6 * max(L, 1e-12))
    views = [(0, 2, "x [m]", "z [m]")] + ([(1, 2, "y [m]", "z [m]")] if spatial else [])
    lo = np.minimum(allpts.min(axis=0), 0.0)
    hi = np.maximum(allpts.max(axis=0), 0.0)
    pad = 0.06 * max(float(np.max(hi - lo)), 1e-9)
    # panel width from the data aspect ratio (equal axis scaling without wasted space)
    aspect = max((hi[a] - lo[a] + 2 * pad) / (hi[b] - lo[b] + 2 * pad) for a, b, _, _ in views)
    panel_h = 3.2
    panel_w = float(np.clip(panel_h * aspect + 0.7, 2.2, 5.5))
    return spatial, views, lo, hi, pad, panel_w, panel_h


def _draw_backbones(ax, per, models, reference: str, a: int, b: int) -> None:
    phys = [x for x in models if x != reference]
    for m in models:
        if m not in per:
            continue
        p = per[m]
        ref = m == reference
        # physics models drawn thick-and-light to thin so coinciding backbones stay visible
        lw, alpha, ls = (2.0, 1.0, "--") if ref else _PHYS_STYLES[phys.index(m) % len(_PHYS_STYLES)]
        ax.plot(
            p[:, a], p[:, b],
            color=model_color(m, models),
            ls=ls,
            lw=lw,
            alpha=alpha,
            marker=None if p.shape[0] > 12 else "o",
            ms=3,
            label=model_label(m),
            zorder=3 if ref else 2,
        )
        ax.plot(p[-1, a], p[-1, b], "o", color=model_color(m, models), ms=4, zorder=4)


def _figure_legend(fig, axs) -> None:
    """One legend below the panels with every label of any panel, first seen first."""
    handles, labs = axs[0, 0].get_legend_handles_labels()
    for ax in axs.flat:
        h, lab = ax.get_legend_handles_labels()
        for hh, ll in zip(h, lab):
            if ll not in labs:
                handles.append(hh)
                labs.append(ll)
    fig.legend(handles, labs, loc="outside lower center", ncol=max(1, len(labs)), frameon=False)


def _summary(study: ResultSet, cmp: pd.DataFrame, how: str, spatial: bool) -> str:
    proj = " Top row: x-z projection, bottom row: y-z projection." if spatial else " Projection on the bending (x-z) plane."
    summary = f"Backbones of the {how}; equal axis scaling, base at the grey square, tips dotted.{proj}"
    pairs = _ref_pairs(cmp, study.reference)
    if pairs:
        ref, m = pairs[0]
        sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]
        worst = sub.loc[sub["tip_error_pct"].idxmax()]
        summary += (
            f" Largest {pair_label(ref, m)} tip error shown: {fmt(worst['tip_error_pct'])} % of L "
            f"({fmt(1e3 * worst['tip_error'])} mm)."
        )
    return summary


def shape_overlay_figures(study: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The ``shapes`` figure (``[]`` when no case has a backbone)."""
    ok = study.ok
    ids, how = _representative_cases(study, cmp)
    if not ids:
        return []
    models = [m for m in study.models if m in set(ok["model"])]
    data = _case_backbones(ok, ids)
    if not data:
        return []
    allpts = np.vstack([p for _, _, per in data for p in per.values()])
    spatial, views, lo, hi, pad, panel_w, panel_h = _layout(ok, allpts)
    ncol = len(data)
    fig = Figure(figsize=(panel_w * ncol + 0.4, (panel_h + 0.9) * len(views) + 0.4), layout="constrained")
    axs = np.atleast_2d(fig.subplots(len(views), ncol, squeeze=False))
    for j, (cid, row0, per) in enumerate(data):
        for i, (a, b, la, lb) in enumerate(views):
            ax = axs[i, j]
            _draw_backbones(ax, per, models, study.reference, a, b)
            ax.plot([0], [0], marker="s", color="0.4", ms=5)
            ax.set_xlim(lo[a] - pad, hi[a] + pad)
            ax.set_ylim(lo[b] - pad, hi[b] + pad)
            ax.set_aspect("equal", adjustable="box")
            ax.set_xlabel(la)
            if j == 0:
                ax.set_ylabel(lb)
            if i == 0:
                ax.set_title(textwrap.fill(_case_title(row0, study.axes, study.labels), width=36), fontsize=9.5)
    _figure_legend(fig, axs)
    return [ReportFigure("shapes", "Backbone shapes", fig, _summary(study, cmp, how, spatial))]
