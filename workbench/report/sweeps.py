"""Generic report figures over the swept axes: tip error against each axis, and the validity map.

:func:`error_vs_parameter_figures`: with one axis, tip / orientation / shape error of every model
pair against it; with two or more, the tip error against each of the first two axes, one line
per value of the other.  :func:`validity_map_figures`: a heat map of the CC tip error over the
first two axes with contour lines at :data:`~.style.THRESHOLDS` (% of L), one panel per
baseline pair (and per value of a small categorical third axis).  Each figure's summary states
where the error stays below the thresholds.  Checked by ``tests/report/test_report_build.py``
and the report tier of ``tests/regression``.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import pandas as pd
from matplotlib import colormaps, patheffects
from matplotlib.cm import ScalarMappable
from matplotlib.colors import LogNorm, Normalize
from matplotlib.figure import Figure

from .load import ResultSet, numeric
from .units import label_of, unit_depends_on, unit_groups
from .style import (
    THRESHOLDS,
    ReportFigure,
    category_ticks,
    is_geometric,
    log_worthy,
    baseline_pairs,
    slug,
    axis_value,
    axis_label,
    fmt,
    model_color,
    pair_label,
    point_links,
    short_label,
    value_text,
)

__all__ = ["error_vs_parameter_figures", "validity_map_figures"]

_ONE_AXIS_METRICS = [
    ("tip_error_pct", "tip position error [% L]"),
    ("orientation_error_deg", "tip orientation error [deg]"),
    ("shape_error_rms_pct", "RMS shape error [% L]"),
]


# --------------------------------------------------------------------------------------
# error vs swept parameter
# --------------------------------------------------------------------------------------
def _below_statement(x: np.ndarray, err: np.ndarray, xname: str, what: str, cats: Sequence[str] | None = None,
                     val=fmt) -> str:
    """'stays below 1 % of L for x <= a' style statement (worst error per x value, x ascending).

    For a categorical axis (``cats``: names of the codes in ``x``) the errors are listed.
    ``val`` formats an x value (with its unit)."""
    # worst error per x value (other parameters vary too): independent of the row order
    xu = np.unique(x)
    err = np.array([np.max(err[x == v]) for v in xu])
    x = xu
    if cats:
        return f"{what}: " + ", ".join(f"{cats[int(c)]} {fmt(e)} % of L" for c, e in zip(x, err)) + "."
    bounds: list[tuple[list[float], int | None]] = []  # (thresholds, last index below them; None = all)
    for t in THRESHOLDS:
        below = err < t
        if not below[0]:
            continue
        k = None if below.all() else int(np.argmin(below)) - 1
        if bounds and bounds[-1][1] == k:
            bounds[-1][0].append(t)
        else:
            bounds.append(([t], k))
        if k is None:
            break
    parts = []
    for ts, k in bounds:
        tt = " and ".join(fmt(t) for t in ts)
        if k is None:
            parts.append(f"stays below {tt} % of L over the whole sweep")
        elif k == 0:
            parts.append(f"stays below {tt} % of L only at the smallest {xname} swept ({val(x[0])})")
        else:
            parts.append(f"stays below {tt} % of L for {xname} ≤ {val(x[k])}")
    if not parts:
        parts.append(f"exceeds {fmt(THRESHOLDS[-1])} % of L already at {xname} = {val(x[0])}")
    i = int(np.nanargmax(err))
    return f"{what} " + "; ".join(parts) + f" (max {fmt(err[i])} % at {xname} = {val(x[i])})."


def _pair_rows(cmp: pd.DataFrame, ref: str, m: str) -> pd.DataFrame:
    return cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]


def _metric_panel(ax, study: ResultSet, cmp: pd.DataFrame, a: str, pairs, col: str, texts: list,
                  points: list | None = None) -> None:
    """One metric against axis ``a``, a line per model pair (the baseline pairs solid)."""
    allv = []
    cat = a in study.categories
    for k, (ref, m) in enumerate(pairs):
        sub = _pair_rows(cmp, ref, m)
        x, y = numeric(sub[a]), numeric(sub[col])
        o = np.argsort(x, kind="mergesort")
        x, y = x[o], y[o]
        is_ref = ref == study.baseline
        if cat:  # categories: grouped markers side by side, never a line between two categories
            x = x + 0.12 * (k - (len(pairs) - 1) / 2)
        ax.plot(x, y, marker="o" if is_ref else "s", ms=4.5 if cat else 3.5 if is_ref else 3,
                color=model_color(m, study.models) if is_ref else "0.45",
                ls="none" if cat else "-" if is_ref else (":", "-.", "--")[len(allv) % 3], label=pair_label(ref, m))
        if points is not None:
            ids = sub["case_id"].to_numpy()[o]
            points += point_links(ax, x, y, ids, [m] * len(ids), [f"{pair_label(ref, m)}, case {str(c)[:8]}" for c in ids])
        allv.append(y)
        if col == "tip_error_pct" and is_ref and np.isfinite(y).any():
            good = np.isfinite(y)
            xs = numeric(sub[a])[o]
            texts.append(_below_statement(xs[good], y[good], short_label(a, study.labels), f"{pair_label(ref, m)}: tip error",
                                          study.categories.get(a), val=lambda v: value_text(a, v, study.labels)))
    v = np.concatenate(allv) if allv else np.array([])
    if log_worthy(v):
        ax.set_yscale("log")
    elif np.isfinite(v).any() and np.nanmin(v) >= 0:
        ax.set_ylim(bottom=0, top=1.08 * np.nanmax(v) if np.nanmax(v) > 0 else 1)
    if is_geometric(numeric(cmp[a])):
        ax.set_xscale("log")
    ax.set_xlabel(axis_label(a, study.labels))
    category_ticks(ax, study, a, "x")


def _dependent_unit_column(cmp: pd.DataFrame, a: str) -> str | None:
    """The column that sets the unit of axis ``a`` (:func:`.units.unit_depends_on`), if the table has it."""
    dep = unit_depends_on(a)
    if dep is None:
        return None
    return next((c for c in (dep.column, f"p.{dep.column}") if c in cmp.columns), None)


def _line_keys(g: pd.DataFrame, a: str, dep_col: str) -> pd.Series:
    """One line per ``dep_col`` value and per value of the other parameters that vary with it (e.g. a pivot)."""
    others = [c for c in g.columns if str(c).startswith("p.") and c not in (a, dep_col)
              and g[c].astype(str).nunique() > 1 and g.groupby(g[dep_col].astype(str))[c].nunique(dropna=False).max() > 1]
    key = g[dep_col].astype(str)
    for c in others:
        v = g[c]
        key = key + np.where(v.isna(), "", ", " + short_label(c, {}) + " " + v.astype(str))
    return key


def _errors_by_unit(study: ResultSet, cmp: pd.DataFrame, a: str, pairs, metrics, dep_col: str) -> ReportFigure:
    """One row of panels per unit of ``a`` (never two units on one axis), a colour per ``dep_col`` value."""
    groups = {u: idx for u, idx in unit_groups(cmp, a).items() if len(idx)}
    main = [p for p in pairs if p[0] == study.baseline] or pairs[:1]
    fig = Figure(figsize=(3.6 * len(metrics) + 1.6, 3.0 * len(groups) + 0.6), layout="constrained")
    axs = fig.subplots(len(groups), len(metrics), squeeze=False)
    styles = ["-", "--", ":", "-."]
    palette = colormaps["tab10"]
    texts = []
    for i, (unit, idx) in enumerate(groups.items()):
        g = cmp.loc[idx]
        keys = _line_keys(g, a, dep_col)
        values = list(dict.fromkeys(keys))
        for j, (col, lab) in enumerate(metrics):
            ax = axs[i, j]
            for k, (ref, m) in enumerate(main):
                for c, v in enumerate(values):
                    sub = _pair_rows(g[keys == v], ref, m).sort_values(a, kind="mergesort")
                    ax.plot(numeric(sub[a]), numeric(sub[col]), marker="o", ms=3, ls=styles[k % 4],
                            color=palette(c % 10), label=v if k == 0 else None)
                    if col == "tip_error_pct" and k == 0 and len(sub):
                        texts.append(f"{v}: max {fmt(np.nanmax(numeric(sub[col])))} % of L")
            ax.set_xlabel(label_of(a, study.labels, unit=unit or "?"))
            ax.set_ylabel(lab)
            if log_worthy(numeric(g[col])):
                ax.set_yscale("log")
        handles, labs = axs[i, 0].get_legend_handles_labels()
        if len(main) > 1:
            from matplotlib.lines import Line2D

            handles += [Line2D([], [], color="0.3", ls=styles[k % 4]) for k in range(len(main))]
            labs += [pair_label(r, m) for r, m in main]
        axs[i, -1].legend(handles, labs, frameon=False, fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    pair_txt = " and ".join(pair_label(r, m) for r, m in main)
    summary = (f"Errors of {pair_txt} against {short_label(a, study.labels)}, one row per unit "
               f"({', '.join(u or 'unknown unit' for u in groups)}), one colour per {short_label(dep_col, study.labels)}"
               + (", line style per comparison" if len(main) > 1 else "") + f". {pair_label(*main[0])} tip error: "
               + "; ".join(texts) + ".")
    return ReportFigure(f"error_vs_{slug(a)}", f"Errors vs {short_label(a, study.labels)}", fig, summary)


def _errors_one_axis(study: ResultSet, cmp: pd.DataFrame, a: str, pairs) -> ReportFigure:
    metrics = [m for m in _ONE_AXIS_METRICS if m[0] in cmp and np.isfinite(numeric(cmp[m[0]])).any()]
    dep_col = _dependent_unit_column(cmp, a)
    if dep_col is not None:
        return _errors_by_unit(study, cmp, a, pairs, metrics, dep_col)
    fig = Figure(figsize=(3.6 * len(metrics) + 0.4, 3.5), layout="constrained")
    axs = np.atleast_1d(fig.subplots(1, len(metrics), squeeze=False)[0])
    texts: list[str] = []
    points: list = []
    for ax, (col, lab) in zip(axs, metrics):
        _metric_panel(ax, study, cmp, a, pairs, col, texts, points)
        ax.set_ylabel(lab)
    axs[0].legend(frameon=False)
    return ReportFigure(f"error_vs_{slug(a)}", f"Errors vs {short_label(a, study.labels)}", fig,
                        " ".join(texts) or "Errors of each model pair along the sweep.", points=tuple(points))


def _colour_lines(axs, study: ResultSet, cmp: pd.DataFrame, x_ax: str, c_ax: str, main, norm, cmap,
                  points: list | None = None) -> np.ndarray:
    """Tip error against ``x_ax``, one line per ``c_ax`` value (worst over the rest); all plotted values."""
    allv = []
    x_cat, c_cat = x_ax in study.categories, c_ax in study.categories
    for ax, (ref, m) in zip(axs, main):
        sub = _pair_rows(cmp, ref, m)
        g = sub.assign(_x=numeric(sub[x_ax]), _c=numeric(sub[c_ax]), _e=numeric(sub["tip_error_pct"])).dropna(subset=["_e"])
        g = g.loc[g.groupby(["_c", "_x"])["_e"].idxmax()]  # the worst case over the other axes, with its case id
        n_c = g["_c"].nunique()
        for k, (cv, gg) in enumerate(g.groupby("_c")):
            gg = gg.sort_values("_x")
            # a categorical x: grouped markers side by side (no line between categories)
            x = gg["_x"] + (0.6 * (k - (n_c - 1) / 2) / max(n_c, 1) if x_cat else 0.0)
            color = colormaps["tab10"](int(cv) % 10) if c_cat else cmap(norm(cv))
            label = study.categories[c_ax][int(cv)] if c_cat else None
            ax.plot(x, gg["_e"], marker="o", ms=4 if x_cat else 3, ls="none" if x_cat else "-", color=color, label=label)
            allv.append(gg["_e"].to_numpy())
            if points is not None:
                points += point_links(ax, x, gg["_e"], gg["case_id"], [m] * len(gg),
                                      [f"{pair_label(ref, m)}, case {str(c)[:8]}" for c in gg["case_id"]])
        ax.set_title(pair_label(ref, m))
        ax.set_xlabel(axis_label(x_ax, study.labels))
        category_ticks(ax, study, x_ax, "x")
        if is_geometric(numeric(cmp[x_ax])):
            ax.set_xscale("log")
    return np.concatenate(allv) if allv else np.array([])


def _two_axes_summary(study: ResultSet, cmp: pd.DataFrame, x_ax: str, c_ax: str, main, axes) -> str:
    texts = []
    for ref, m in main:
        sub = _pair_rows(cmp, ref, m)
        lo_c = np.nanmin(numeric(sub[c_ax]))
        s2 = sub[numeric(sub[c_ax]) == lo_c]
        x, y = numeric(s2[x_ax]), numeric(s2["tip_error_pct"])
        good = np.isfinite(x) & np.isfinite(y)
        if good.any():
            lo_txt = study.categories[c_ax][int(lo_c)] if c_ax in study.categories else value_text(c_ax, lo_c, study.labels)
            texts.append(_below_statement(x[good], y[good], short_label(x_ax, study.labels),
                                          f"{pair_label(ref, m)} at {short_label(c_ax, study.labels)} = {lo_txt}: tip error",
                                          study.categories.get(x_ax), val=lambda v: value_text(x_ax, v, study.labels)))
    rest = [short_label(a, study.labels) for a in axes[2:]]
    worst = f" (worst case over {', '.join(rest)})" if rest else ""
    what = "one marker group per category of" if x_ax in study.categories else "one line per value of"
    return (f"Tip error vs {short_label(x_ax, study.labels)}, {what} "
            f"{short_label(c_ax, study.labels)} (colour){worst}; dotted lines at 1, 5, 10 % of L. " + " ".join(texts))


def _errors_two_axes(study: ResultSet, cmp: pd.DataFrame, x_ax: str, c_ax: str, main, axes) -> ReportFigure:
    n = len(main)
    fig = Figure(figsize=(3.7 * n + 1.0, 3.5), layout="constrained")
    axs = np.atleast_1d(fig.subplots(1, n, squeeze=False)[0])
    cvals = np.unique(numeric(cmp[c_ax])[np.isfinite(numeric(cmp[c_ax]))])
    norm = (LogNorm if is_geometric(cvals) else Normalize)(vmin=cvals.min(), vmax=cvals.max())
    cmap = colormaps["viridis"]
    points: list = []
    v = _colour_lines(axs, study, cmp, x_ax, c_ax, main, norm, cmap, points)
    for ax in axs:
        if log_worthy(v):
            ax.set_yscale("log")
        elif np.isfinite(v).any() and np.nanmin(v) >= 0:
            ax.set_ylim(bottom=0)
        for t in THRESHOLDS:
            ax.axhline(t, color="0.5", lw=0.7, ls=":")
    axs[0].set_ylabel("tip position error [% L]")
    if c_ax in study.categories:  # categories: a legend, not a colour bar
        axs[-1].legend(title=axis_label(c_ax, study.labels), frameon=False, fontsize=8, loc="upper left",
                       bbox_to_anchor=(1.02, 1.0))
    else:
        cb = fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=list(axs), shrink=0.9)
        cb.set_label(axis_label(c_ax, study.labels))
    summary = _two_axes_summary(study, cmp, x_ax, c_ax, main, axes)
    return ReportFigure(f"error_vs_{slug(x_ax)}", f"Tip error vs {short_label(x_ax, study.labels)}", fig, summary,
                        points=tuple(points))


def error_vs_parameter_figures(study: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    """One ``error_vs_<axis>`` figure for one swept axis, two (one per axis) for more."""
    axes = list(study.axes)
    pairs = baseline_pairs(cmp, study.baseline)
    if not axes or not pairs or cmp.empty:
        return []
    if len(axes) == 1:
        return [_errors_one_axis(study, cmp, axes[0], pairs)]
    # two or more axes: one figure per plotted axis, lines for the other axis' values
    a0, a1 = axes[0], axes[1]
    main = [p for p in pairs if p[0] == study.baseline] or pairs
    return [_errors_two_axes(study, cmp, x_ax, c_ax, main, axes) for x_ax, c_ax in ((a0, a1), (a1, a0))]


# --------------------------------------------------------------------------------------
# validity map
# --------------------------------------------------------------------------------------
def _facet_axis(study: ResultSet, axes: Sequence[str]) -> str | None:
    """A categorical third axis with a few values: one validity-map panel per category."""
    if len(axes) >= 3 and axes[2] in study.categories and 2 <= len(study.categories[axes[2]]) <= 4:
        return axes[2]
    return None


def _contours(ax, xs, ys, E, Em) -> None:
    if xs.size >= 2 and ys.size >= 2 and np.isfinite(E).sum() >= 4:
        levels = [t for t in THRESHOLDS if np.nanmin(E) < t < np.nanmax(E)]
        if levels:
            cs = ax.contour(xs, ys, Em, levels=levels, colors="white", linewidths=1.5)
            cs.set(path_effects=[patheffects.withStroke(linewidth=3.0, foreground="black")])
            for t in ax.clabel(cs, fmt=lambda v: f"{v:g} %", fontsize=8.5, colors="black"):
                t.set_path_effects([patheffects.withStroke(linewidth=2.5, foreground="white")])


def _mark_missing(ax, xs, ys, E) -> bool:
    """Cross out failed / missing grid cells; True when there were any."""
    if not np.isnan(E).any():
        return False
    yy, xx = np.nonzero(np.isnan(E))
    ax.plot(xs[xx], ys[yy], "x", color="0.3", ms=7, mew=1.5)
    for x_, y_ in zip(xs[xx], ys[yy]):
        ax.annotate("failed", (x_, y_), xytext=(0, 7), textcoords="offset points", ha="center",
                    va="bottom", fontsize=7.5, color="0.3")
    return True


def _validity_text(study: ResultSet, ref: str, m: str, where: str, xs, ys, E, a0: str, a1: str) -> str:
    tot = np.isfinite(E).sum()
    frac = [100.0 * np.sum(E[np.isfinite(E)] < t) / tot for t in THRESHOLDS]
    iy, ix = np.unravel_index(np.nanargmax(E), E.shape)
    return (
        f"{pair_label(ref, m)}{where}: CC tip error is below 1 % of L in {fmt(frac[0])} % of the {tot} swept points, "
        f"below 5 % in {fmt(frac[1])} %, below 10 % in {fmt(frac[2])} %; worst {fmt(E[iy, ix])} % at "
        f"{short_label(a0, study.labels)} = {axis_value(study, a0, xs[ix])}, {short_label(a1, study.labels)} = {axis_value(study, a1, ys[iy])}."
        + _region_statement(xs, ys, E, a0, a1, study)
    )


def _validity_panel(ax, study: ResultSet, cmp: pd.DataFrame, panel, facet, a0: str, a1: str, norm):
    """Draw one heat map; return ``(mesh, sentence, missing cells?, point links)`` or ``None`` for an empty panel."""
    ref, m, fv = panel
    sub = _pair_rows(cmp, ref, m)
    where = ""
    if facet is not None:
        sub = sub[numeric(sub[facet]) == fv]
        where = f" ({study.categories[facet][int(fv)]})"
    g = pd.DataFrame({"x": numeric(sub[a0]), "y": numeric(sub[a1]), "e": numeric(sub["tip_error_pct"])})
    g = g.dropna().groupby(["y", "x"])["e"].max().unstack("x")  # worst over other axes
    if g.empty:
        ax.set_axis_off()
        return None
    xs, ys, E = g.columns.to_numpy(float), g.index.to_numpy(float), g.to_numpy(float)
    Em = np.ma.masked_invalid(E)
    mesh = ax.pcolormesh(xs, ys, Em, shading="nearest", cmap="magma_r", norm=norm)
    _contours(ax, xs, ys, E, Em)
    ax.set_xscale("log" if is_geometric(xs) else "linear")
    ax.set_yscale("log" if is_geometric(ys) else "linear")
    ax.grid(False)
    ax.set_xlabel(axis_label(a0, study.labels))
    category_ticks(ax, study, a0, "x")
    category_ticks(ax, study, a1, "y")
    ax.set_title(pair_label(ref, m) + where)
    missing = _mark_missing(ax, xs, ys, E)
    # every cell links to its worst case (the maximum over the other axes)
    c = pd.DataFrame({"x": numeric(sub[a0]), "y": numeric(sub[a1]), "e": numeric(sub["tip_error_pct"]),
                      "case_id": sub["case_id"].to_numpy()}).dropna(subset=["x", "y", "e"])
    worst = c.loc[c.groupby(["y", "x"])["e"].idxmax()]
    points = point_links(ax, worst["x"], worst["y"], worst["case_id"], [m] * len(worst),
                         [f"{pair_label(ref, m)}{where}: {fmt(e)} % of L, case {str(k)[:8]}"
                          for e, k in zip(worst["e"], worst["case_id"])])
    return mesh, _validity_text(study, ref, m, where, xs, ys, E, a0, a1), missing, points


def validity_map_figures(study: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The ``validity_map`` figure (needs two swept axes)."""
    axes = list(study.axes)
    if len(axes) < 2 or cmp.empty:
        return []
    a0, a1 = axes[0], axes[1]
    pairs = [p for p in baseline_pairs(cmp, study.baseline) if p[0] == study.baseline] or baseline_pairs(cmp, study.baseline)
    if not pairs:
        return []
    facet = _facet_axis(study, axes)
    facet_vals: list[float | None] = (list(range(len(study.categories[facet]))) if facet else [None])
    panels = [(ref, m, fv) for ref, m in pairs for fv in facet_vals]
    n = len(panels)
    fig = Figure(figsize=(4.0 * n + 1.2, 3.8), layout="constrained")
    axs = np.atleast_1d(fig.subplots(1, n, squeeze=False, sharey=True)[0])
    allv = numeric(cmp["tip_error_pct"])
    allv = allv[np.isfinite(allv) & (allv > 0)]
    if allv.size == 0:
        return []
    use_log = allv.max() / allv.min() > 20
    norm = LogNorm(vmin=allv.min(), vmax=allv.max()) if use_log else Normalize(vmin=0, vmax=allv.max())
    texts = []
    mesh = None
    missing_note = False
    points: list = []
    for ax, panel in zip(axs, panels):
        drawn = _validity_panel(ax, study, cmp, panel, facet, a0, a1, norm)
        if drawn is not None:
            mesh, text, missing, pts = drawn
            points += pts
            texts.append(text)
            missing_note = missing_note or missing
    if mesh is None:
        return []
    axs[0].set_ylabel(axis_label(a1, study.labels))
    cb = fig.colorbar(mesh, ax=list(axs), shrink=0.95)
    cb.set_label("CC tip position error [% L]")
    if missing_note:
        texts.append("Blank cells marked × are failed or missing cases (excluded).")
    rest = [a for a in axes[2:] if a != facet]
    extra = f" (maximum over {', '.join(short_label(a, study.labels) for a in rest)})" if rest else ""
    per = f", one panel per {short_label(facet, study.labels)}" if facet else ""
    summary = "Validity map: heat map of the tip error, contour lines at 1 %, 5 % and 10 % of L" + per + extra + ". " + " ".join(texts)
    return [ReportFigure("validity_map", "Validity map of constant curvature", fig, summary, points=tuple(points))]


def _region_statement(xs, ys, E, a0, a1, study: ResultSet) -> str:
    """'below 1 % for all y when x <= ...' from the full-column criterion."""
    labels = study.labels
    if a0 in study.categories or a1 in study.categories:
        return ""
    col_ok = np.all(np.where(np.isfinite(E), E < THRESHOLDS[0], True), axis=0)
    if col_ok.any() and not col_ok.all() and col_ok[0]:
        k = int(np.argmin(col_ok))
        return (f" Below 1 % for every {short_label(a1, labels)} in the sweep as long as "
                f"{short_label(a0, labels)} ≤ {fmt(xs[k - 1])}.")
    row_ok = np.all(np.where(np.isfinite(E), E < THRESHOLDS[0], True), axis=1)
    if row_ok.any() and not row_ok.all() and row_ok[0]:
        k = int(np.argmin(row_ok))
        return (f" Below 1 % for every {short_label(a0, labels)} in the sweep as long as "
                f"{short_label(a1, labels)} ≤ {fmt(ys[k - 1])}.")
    return ""
