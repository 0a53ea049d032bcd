"""Report figures: ``matplotlib.figure.Figure`` objects (never pyplot), one style.

Each builder returns a list of :class:`ReportFigure` (name, title, figure, generated text
summary).  Failed rows never reach a figure: builders take the ok rows and the comparison
table of :func:`workbench.compare.compare_table`.
"""

from __future__ import annotations

import math
import re
import textwrap
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd
from matplotlib import patheffects
from matplotlib.colors import LogNorm, Normalize
from matplotlib.figure import Figure

from ..compare.table import DERIVED_LABELS, array_cell, row_positions
from .load import Study, numeric

__all__ = [
    "STYLE",
    "ReportFigure",
    "model_label",
    "pair_label",
    "axis_label",
    "shape_overlay_figures",
    "error_vs_parameter_figures",
    "validity_map_figures",
    "time_series_figures",
    "compression_split_figures",
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

_MODEL_LABELS = {
    "cc": "CC",
    "ancf": "ANCF",
    "ancf3d": "ANCF 3-D",
    "beam3d": "GE beam",
    "spring_link": "spring-link",
    "series_parallel": "series-parallel",
}
_MODEL_COLORS = {
    "cc": "#222222",
    "ancf": "#1f77b4",
    "ancf3d": "#9467bd",
    "beam3d": "#d62728",
    "spring_link": "#2ca02c",
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


def model_label(m: str) -> str:
    return _MODEL_LABELS.get(m, m)


def model_color(m: str, models: Sequence[str] = ()) -> str:
    if m in _MODEL_COLORS:
        return _MODEL_COLORS[m]
    unknown = [x for x in models if x not in _MODEL_COLORS] or [m]
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
    return col[2:] if col.startswith("p.") else col


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
    return col[2:] if col.startswith("p.") else col


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


def _log_worthy(values: np.ndarray) -> bool:
    v = values[np.isfinite(values)]
    return v.size > 1 and np.all(v > 0) and v.max() / v.min() > 20


def _is_geometric(values: np.ndarray) -> bool:
    v = np.unique(values[np.isfinite(values)])
    if v.size < 3 or np.any(v <= 0):
        return False
    r = v[1:] / v[:-1]
    return bool(np.allclose(r, r[0], rtol=0.05) and r[0] > 1.5 and v[-1] / v[0] >= 10)


def _ref_pairs(cmp: pd.DataFrame, reference: str) -> list[tuple[str, str]]:
    if cmp.empty:
        return []
    pairs = list(dict.fromkeys(zip(cmp["reference"], cmp["model"])))
    first = [p for p in pairs if p[0] == reference]
    return first + [p for p in pairs if p[0] != reference]


def _case_title(row: Mapping[str, Any], axes: Sequence[str], labels) -> str:
    parts = [f"{short_label(a, labels)} = {fmt(float(row[a])) if _isnum(row[a]) else row[a]}"
             for a in axes[:3] if a in row and row[a] is not None]
    return ", ".join(parts) if parts else f"case {str(row.get('case_id', ''))[:8]}"


def _isnum(v: Any) -> bool:
    try:
        return np.isfinite(float(v))
    except (TypeError, ValueError):
        return False


# --------------------------------------------------------------------------------------
# backbone shape overlays
# --------------------------------------------------------------------------------------
def _representative_cases(study: Study, cmp: pd.DataFrame) -> tuple[list[str], str]:
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


def shape_overlay_figures(study: Study, cmp: pd.DataFrame) -> list[ReportFigure]:
    ok = study.ok
    ids, how = _representative_cases(study, cmp)
    if not ids:
        return []
    models = [m for m in study.models if m in set(ok["model"])]
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
    if not data:
        return []
    allpts = np.vstack([p for _, _, per in data for p in per.values()])
    L = float(np.nanmax(numeric(ok["robot_length"]))) if "robot_length" in ok else float(np.ptp(allpts[:, 2]))
    spatial = bool(np.nanmax(np.abs(allpts[:, 1])) > 1e-6 * max(L, 1e-12))
    views = [(0, 2, "x [m]", "z [m]")] + ([(1, 2, "y [m]", "z [m]")] if spatial else [])
    ncol = len(data)
    lo = np.minimum(allpts.min(axis=0), 0.0)
    hi = np.maximum(allpts.max(axis=0), 0.0)
    pad = 0.06 * max(float(np.max(hi - lo)), 1e-9)
    # panel width from the data aspect ratio (equal axis scaling without wasted space)
    aspect = max((hi[a] - lo[a] + 2 * pad) / (hi[b] - lo[b] + 2 * pad) for a, b, _, _ in views)
    panel_h = 3.2
    panel_w = float(np.clip(panel_h * aspect + 0.7, 2.2, 5.5))
    fig = Figure(figsize=(panel_w * ncol + 0.4, (panel_h + 0.9) * len(views) + 0.4), layout="constrained")
    axs = np.atleast_2d(fig.subplots(len(views), ncol, squeeze=False))
    for j, (cid, row0, per) in enumerate(data):
        for i, (a, b, la, lb) in enumerate(views):
            ax = axs[i, j]
            phys = [x for x in models if x != study.reference]
            for m in models:
                if m not in per:
                    continue
                p = per[m]
                ref = m == study.reference
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
            ax.plot([0], [0], marker="s", color="0.4", ms=5)
            ax.set_xlim(lo[a] - pad, hi[a] + pad)
            ax.set_ylim(lo[b] - pad, hi[b] + pad)
            ax.set_aspect("equal", adjustable="box")
            ax.set_xlabel(la)
            if j == 0:
                ax.set_ylabel(lb)
            if i == 0:
                ax.set_title(textwrap.fill(_case_title(row0, study.axes, study.labels), width=36), fontsize=9.5)
    handles, labs = axs[0, 0].get_legend_handles_labels()
    for ax in axs.flat:
        h, lab = ax.get_legend_handles_labels()
        for hh, ll in zip(h, lab):
            if ll not in labs:
                handles.append(hh)
                labs.append(ll)
    fig.legend(handles, labs, loc="outside lower center", ncol=max(1, len(labs)), frameon=False)
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
    return [ReportFigure("shapes", "Backbone shapes", fig, summary)]


# --------------------------------------------------------------------------------------
# error vs swept parameter
# --------------------------------------------------------------------------------------
def _below_statement(x: np.ndarray, err: np.ndarray, xname: str, what: str, cats: Sequence[str] | None = None) -> str:
    """'stays below 1 % of L for x <= a' style statement (x sorted ascending).

    For a categorical axis (``cats``: names of the codes in ``x``) the errors are listed."""
    order = np.argsort(x)
    x, err = x[order], err[order]
    if cats:
        return f"{what}: " + ", ".join(f"{cats[int(c)]} {fmt(e)} % of L" for c, e in zip(x, err)) + "."
    parts = []
    for t in THRESHOLDS:
        below = err < t
        if below.all():
            parts.append(f"stays below {fmt(t)} % of L over the whole sweep")
            break
        if not below[0]:
            continue
        k = int(np.argmin(below))  # first index at/above threshold
        parts.append(f"stays below {fmt(t)} % of L for {xname} ≤ {fmt(x[k - 1])}")
    if not parts:
        parts.append(f"exceeds {fmt(THRESHOLDS[-1])} % of L already at {xname} = {fmt(x[0])}")
    i = int(np.nanargmax(err))
    return f"{what} " + "; ".join(parts) + f" (max {fmt(err[i])} % at {xname} = {fmt(x[i])})."


def error_vs_parameter_figures(study: Study, cmp: pd.DataFrame) -> list[ReportFigure]:
    axes = list(study.axes)
    pairs = _ref_pairs(cmp, study.reference)
    if not axes or not pairs or cmp.empty:
        return []
    out = []
    if len(axes) == 1:
        a = axes[0]
        metrics = [
            ("tip_error_pct", "tip position error [% L]"),
            ("orientation_error_deg", "tip orientation error [deg]"),
            ("shape_error_rms_pct", "RMS shape error [% L]"),
        ]
        metrics = [m for m in metrics if m[0] in cmp and np.isfinite(numeric(cmp[m[0]])).any()]
        fig = Figure(figsize=(3.6 * len(metrics) + 0.4, 3.5), layout="constrained")
        axs = np.atleast_1d(fig.subplots(1, len(metrics), squeeze=False)[0])
        texts = []
        for ax, (col, lab) in zip(axs, metrics):
            allv = []
            for ref, m in pairs:
                sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]
                x, y = numeric(sub[a]), numeric(sub[col])
                o = np.argsort(x)
                x, y = x[o], y[o]
                is_ref = ref == study.reference
                ax.plot(x, y, marker="o" if is_ref else "s", ms=3.5 if is_ref else 3,
                        color=model_color(m, study.models) if is_ref else "0.45",
                        ls="-" if is_ref else (":", "-.", "--")[len(allv) % 3], label=pair_label(ref, m))
                allv.append(y)
                if col == "tip_error_pct" and is_ref and np.isfinite(y).any():
                    good = np.isfinite(y)
                    texts.append(_below_statement(x[good], y[good], short_label(a, study.labels), f"{pair_label(ref, m)}: tip error",
                                                  study.categories.get(a)))
            v = np.concatenate(allv) if allv else np.array([])
            if _log_worthy(v):
                ax.set_yscale("log")
            elif np.isfinite(v).any() and np.nanmin(v) >= 0:
                ax.set_ylim(bottom=0, top=1.08 * np.nanmax(v) if np.nanmax(v) > 0 else 1)
            if _is_geometric(numeric(cmp[a])):
                ax.set_xscale("log")
            ax.set_xlabel(axis_label(a, study.labels))
            _category_ticks(ax, study, a, "x")
            ax.set_ylabel(lab)
        axs[0].legend(frameon=False)
        out.append(ReportFigure(f"error_vs_{_slug(a)}", f"Errors vs {short_label(a, study.labels)}", fig,
                                " ".join(texts) or "Errors of each model pair along the sweep."))
        return out
    # two or more axes: one figure per plotted axis, lines for the other axis' values
    a0, a1 = axes[0], axes[1]
    main = [p for p in pairs if p[0] == study.reference] or pairs
    for x_ax, c_ax in ((a0, a1), (a1, a0)):
        n = len(main)
        fig = Figure(figsize=(3.7 * n + 1.0, 3.5), layout="constrained")
        axs = np.atleast_1d(fig.subplots(1, n, squeeze=False)[0])
        cvals = np.unique(numeric(cmp[c_ax])[np.isfinite(numeric(cmp[c_ax]))])
        norm = (LogNorm if _is_geometric(cvals) else Normalize)(vmin=cvals.min(), vmax=cvals.max())
        from matplotlib import colormaps

        cmap = colormaps["viridis"]
        allv = []
        for ax, (ref, m) in zip(axs, main):
            sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]
            g = sub.assign(_x=numeric(sub[x_ax]), _c=numeric(sub[c_ax]), _e=numeric(sub["tip_error_pct"]))
            g = g.groupby(["_c", "_x"], as_index=False)["_e"].max()
            for cv, gg in g.groupby("_c"):
                gg = gg.sort_values("_x")
                ax.plot(gg["_x"], gg["_e"], marker="o", ms=3, color=cmap(norm(cv)))
                allv.append(gg["_e"].to_numpy())
            ax.set_title(pair_label(ref, m))
            ax.set_xlabel(axis_label(x_ax, study.labels))
            _category_ticks(ax, study, x_ax, "x")
            if _is_geometric(numeric(cmp[x_ax])):
                ax.set_xscale("log")
        v = np.concatenate(allv) if allv else np.array([])
        for ax in axs:
            if _log_worthy(v):
                ax.set_yscale("log")
            elif np.isfinite(v).any() and np.nanmin(v) >= 0:
                ax.set_ylim(bottom=0)
            for t in THRESHOLDS:
                ax.axhline(t, color="0.5", lw=0.7, ls=":")
        axs[0].set_ylabel("tip position error [% L]")
        from matplotlib.cm import ScalarMappable

        cb = fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=list(axs), shrink=0.9)
        cb.set_label(axis_label(c_ax, study.labels))
        if c_ax in study.categories:
            cb.set_ticks(range(len(study.categories[c_ax])), labels=study.categories[c_ax])
        texts = []
        for ref, m in main:
            sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]
            lo_c = np.nanmin(numeric(sub[c_ax]))
            s2 = sub[numeric(sub[c_ax]) == lo_c]
            x, y = numeric(s2[x_ax]), numeric(s2["tip_error_pct"])
            good = np.isfinite(x) & np.isfinite(y)
            if good.any():
                lo_txt = study.categories[c_ax][int(lo_c)] if c_ax in study.categories else fmt(lo_c)
                texts.append(_below_statement(x[good], y[good], short_label(x_ax, study.labels),
                                              f"{pair_label(ref, m)} at {short_label(c_ax, study.labels)} = {lo_txt}: tip error",
                                              study.categories.get(x_ax)))
        rest = [short_label(a, study.labels) for a in axes[2:]]
        worst = f" (worst case over {', '.join(rest)})" if rest else ""
        summary = (f"Tip error vs {short_label(x_ax, study.labels)}, one line per value of "
                   f"{short_label(c_ax, study.labels)} (colour){worst}; dotted lines at 1, 5, 10 % of L. " + " ".join(texts))
        out.append(ReportFigure(f"error_vs_{_slug(x_ax)}", f"Tip error vs {short_label(x_ax, study.labels)}", fig, summary))
    return out


def _val(study: Study, col: str, v: float) -> str:
    """A plotted axis value as text (category name for categorical axes)."""
    cats = study.categories.get(col)
    if cats and np.isfinite(v) and 0 <= int(v) < len(cats):
        return cats[int(v)]
    return fmt(v)


def _category_ticks(ax, study: Study, col: str, which: str) -> None:
    """Label a categorical axis (values coded 0..n-1 by :func:`code_categories`)."""
    cats = study.categories.get(col)
    if cats:
        getattr(ax, f"set_{which}ticks")(range(len(cats)), cats)


def code_categories(study: Study, table: pd.DataFrame) -> pd.DataFrame:
    """Copy of ``table`` with the categorical axes replaced by their codes 0..n-1."""
    out = table.copy()
    for col, cats in study.categories.items():
        if col in out:
            out[col] = out[col].astype(str).map({c: i for i, c in enumerate(cats)}).astype(float)
    return out


def _slug(col: str) -> str:
    s = col[2:] if col.startswith("p.") else col
    return "".join(ch if ch.isalnum() else "_" for ch in s).strip("_")


# --------------------------------------------------------------------------------------
# validity map
# --------------------------------------------------------------------------------------
def _facet_axis(study: Study, axes: Sequence[str]) -> str | None:
    """A categorical third axis with a few values: one validity-map panel per category."""
    if len(axes) >= 3 and axes[2] in study.categories and 2 <= len(study.categories[axes[2]]) <= 4:
        return axes[2]
    return None


def validity_map_figures(study: Study, cmp: pd.DataFrame) -> list[ReportFigure]:
    axes = list(study.axes)
    if len(axes) < 2 or cmp.empty:
        return []
    a0, a1 = axes[0], axes[1]
    pairs = [p for p in _ref_pairs(cmp, study.reference) if p[0] == study.reference] or _ref_pairs(cmp, study.reference)
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
    for ax, (ref, m, fv) in zip(axs, panels):
        sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]
        where = ""
        if facet is not None:
            sub = sub[numeric(sub[facet]) == fv]
            where = f" ({study.categories[facet][int(fv)]})"
        g = pd.DataFrame({"x": numeric(sub[a0]), "y": numeric(sub[a1]), "e": numeric(sub["tip_error_pct"])})
        g = g.dropna().groupby(["y", "x"])["e"].max().unstack("x")  # worst over other axes
        if g.empty:
            ax.set_axis_off()
            continue
        xs, ys, E = g.columns.to_numpy(float), g.index.to_numpy(float), g.to_numpy(float)
        Em = np.ma.masked_invalid(E)
        mesh = ax.pcolormesh(xs, ys, Em, shading="nearest", cmap="magma_r", norm=norm)
        if xs.size >= 2 and ys.size >= 2 and np.isfinite(E).sum() >= 4:
            levels = [t for t in THRESHOLDS if np.nanmin(E) < t < np.nanmax(E)]
            if levels:
                cs = ax.contour(xs, ys, Em, levels=levels, colors="white", linewidths=1.5)
                cs.set(path_effects=[patheffects.withStroke(linewidth=3.0, foreground="black")])
                for t in ax.clabel(cs, fmt=lambda v: f"{v:g} %", fontsize=8.5, colors="black"):
                    t.set_path_effects([patheffects.withStroke(linewidth=2.5, foreground="white")])
        ax.set_xscale("log" if _is_geometric(xs) else "linear")
        ax.set_yscale("log" if _is_geometric(ys) else "linear")
        ax.grid(False)
        ax.set_xlabel(axis_label(a0, study.labels))
        _category_ticks(ax, study, a0, "x")
        _category_ticks(ax, study, a1, "y")
        ax.set_title(pair_label(ref, m) + where)
        # failed / missing grid cells
        if np.isnan(E).any():
            yy, xx = np.nonzero(np.isnan(E))
            ax.plot(xs[xx], ys[yy], "x", color="0.3", ms=7, mew=1.5)
            for x_, y_ in zip(xs[xx], ys[yy]):
                ax.annotate("failed", (x_, y_), xytext=(0, 7), textcoords="offset points", ha="center",
                            va="bottom", fontsize=7.5, color="0.3")
            missing_note = True
        tot = np.isfinite(E).sum()
        frac = [100.0 * np.sum(E[np.isfinite(E)] < t) / tot for t in THRESHOLDS]
        iy, ix = np.unravel_index(np.nanargmax(E), E.shape)
        texts.append(
            f"{pair_label(ref, m)}{where}: CC tip error is below 1 % of L in {fmt(frac[0])} % of the {tot} swept points, "
            f"below 5 % in {fmt(frac[1])} %, below 10 % in {fmt(frac[2])} %; worst {fmt(E[iy, ix])} % at "
            f"{short_label(a0, study.labels)} = {_val(study, a0, xs[ix])}, {short_label(a1, study.labels)} = {_val(study, a1, ys[iy])}."
            + _region_statement(xs, ys, E, a0, a1, study)
        )
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
    return [ReportFigure("validity_map", "Validity map of constant curvature", fig, summary)]


def _region_statement(xs, ys, E, a0, a1, study: Study) -> str:
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


# --------------------------------------------------------------------------------------
# time series (dynamic studies)
# --------------------------------------------------------------------------------------
_SERIES_LABELS = {
    "tip_position": "tip position [m]",
    "tendon_lengths": "tendon length change [mm]",
    "tendon_tensions": "tendon tension [N]",
    "length_change": "backbone length change [mm]",
}
_MM_SERIES = {"tendon_lengths", "length_change"}


_SERIES_TITLES = {"length_change": "backbone length change (compression < 0)"}


def _row_series(row: Mapping[str, Any], name: str) -> tuple[np.ndarray, np.ndarray] | None:
    t = array_cell(row.get("time"))
    v = array_cell(row.get(f"series.{name}"))
    if t is None or v is None or v.size % t.size:
        return None
    return t, v.reshape(t.size, -1)


def time_series_figures(study: Study, cmp: pd.DataFrame, max_cases: int = 2) -> list[ReportFigure]:
    if not study.is_dynamic:
        return []
    ok = study.ok
    dyn = ok[ok["time"].map(lambda v: array_cell(v) is not None)]
    names = [c[len("series."):] for c in dyn.columns
             if str(c).startswith("series.") and dyn[c].map(lambda v: array_cell(v) is not None).any()]
    order = ["tendon_lengths", "tendon_tensions", "length_change"]
    has_tip = "tip_position" in names
    names = [n for n in order if n in names] + [n for n in names if n not in order and n != "tip_position"]
    case_ids = list(dict.fromkeys(dyn.sort_values(list(study.axes)) ["case_id"])) if study.axes else list(dict.fromkeys(dyn["case_id"]))
    if len(case_ids) > max_cases:
        case_ids = [case_ids[0], case_ids[-1]]
    out = []
    for cid in case_ids:
        rows = {str(r["model"]): r.to_dict() for _, r in dyn[dyn["case_id"] == cid].iterrows()}
        tip_err = has_tip and study.reference in rows and len(rows) > 1
        panels = [n for n in names if n != "tip_position"] + (["tip_error"] if tip_err else ["tip_position"] if has_tip else [])
        if not panels:
            continue
        ncol = min(2, len(panels))
        nrow = math.ceil(len(panels) / ncol)
        fig = Figure(figsize=(4.4 * ncol + 0.4, 2.8 * nrow + 0.5), layout="constrained")
        axs = np.atleast_1d(fig.subplots(nrow, ncol, squeeze=False).ravel())
        texts = []
        for ax, name in zip(axs, panels):
            if name == "tip_error":
                ref = _row_series(rows[study.reference], "tip_position")
                for m, r in rows.items():
                    if m == study.reference:
                        continue
                    sm = _row_series(r, "tip_position")
                    if ref is None or sm is None:
                        continue
                    pm = np.stack([np.interp(ref[0], sm[0], sm[1][:, k]) for k in range(3)], -1)
                    L = float(r.get("robot_length", np.nan))
                    e = 100 * np.linalg.norm(pm - ref[1], axis=1) / L
                    ax.plot(ref[0], e, color=model_color(m, study.models), label=pair_label(study.reference, m))
                    i = int(np.argmax(e))
                    texts.append(f"{pair_label(study.reference, m)} tip error peaks at {fmt(e[i])} % of L at t = {fmt(ref[0][i])} s and ends at {fmt(e[-1])} %.")
                ax.set_ylabel("tip error [% L]")
                ax.set_title("tip position error")
            else:
                for m, r in rows.items():
                    s = _row_series(r, name)
                    if s is None:
                        continue
                    t, v = s
                    if name in _MM_SERIES:
                        v = 1e3 * v
                    styles = ["-", "--", ":", "-."]
                    comp = ("x", "y", "z") if name == "tip_position" and v.shape[1] == 3 else None
                    for k in range(v.shape[1]):
                        ax.plot(t, v[:, k], color=model_color(m, study.models), ls=styles[k % 4],
                                lw=2.0 if m == study.reference else 1.5,
                                label=model_label(m) + (f" {comp[k]}" if comp else f" #{k}" if v.shape[1] > 1 else ""))
                    if name == "length_change":
                        L = float(r.get("robot_length", np.nan))
                        texts.append(f"{model_label(m)}: final backbone length change {fmt(v[-1, 0])} mm ({fmt(0.1 * v[-1, 0] / L)} % of L).")
                ax.set_ylabel(_SERIES_LABELS.get(name, name))
                ax.set_title(_SERIES_TITLES.get(name, name.replace("_", " ")))
            ax.set_xlabel("time [s]")
            if ax.get_legend_handles_labels()[0]:
                ax.legend(frameon=False, fontsize=7.5)
        for ax in axs[len(panels):]:
            ax.set_visible(False)
        row0 = next(iter(rows.values()))
        title = _case_title(row0, study.axes, study.labels)
        fig.suptitle(title)
        out.append(ReportFigure(f"timeseries_{str(cid)[:12]}", f"Time series, {title}", fig,
                                f"Time histories for {title}; line style distinguishes tendons, colour the model. " + " ".join(texts)))
    return out


# --------------------------------------------------------------------------------------
# compression split (wire-delay studies)
# --------------------------------------------------------------------------------------
def compression_split_figures(study: Study, cmp: pd.DataFrame) -> list[ReportFigure]:
    cols = ["compression_backbone", "compression_tendon_stretch", "compression_shape"]
    if cmp.empty or not all(c in cmp for c in cols):
        return []
    sub = cmp[np.isfinite(numeric(cmp["compression_virtual"]))]
    sub = sub[np.abs(numeric(sub["compression_virtual"])) > 0]
    if sub.empty:
        return []
    pairs = list(dict.fromkeys(zip(sub["reference"], sub["model"])))
    n = len(pairs)
    fig = Figure(figsize=(4.2 * n + 0.4, 3.4), layout="constrained")
    axs = np.atleast_1d(fig.subplots(1, n, squeeze=False)[0])
    colors = ["#4c72b0", "#dd8452", "#55a868"]
    names = ["backbone compression", "tendon stretch", "shape distortion"]
    texts = []
    for ax, (ref, m) in zip(axs, pairs):
        s = sub[(sub["reference"] == ref) & (sub["model"] == m)]
        if study.axes and study.axes[0] in s:
            s = s.sort_values(study.axes[0])
            ticks = [fmt(float(v)) for v in numeric(s[study.axes[0]])]
            ax.set_xlabel(axis_label(study.axes[0], study.labels))
        else:
            ticks = [str(c)[:6] for c in s["case_id"]]
            ax.set_xlabel("case")
        x = np.arange(len(s))
        pos_base = np.zeros(len(s))
        neg_base = np.zeros(len(s))
        for c, col, nm in zip(colors, cols, names):
            v = 1e3 * numeric(s[col])
            base = np.where(v >= 0, pos_base, neg_base)
            ax.bar(x, v, bottom=base, color=c, label=nm, width=0.7)
            pos_base += np.where(v >= 0, v, 0)
            neg_base += np.where(v < 0, v, 0)
        ax.plot(x, 1e3 * numeric(s["compression_virtual"]), "k_", ms=18, mew=2, label="CC virtual compression")
        ax.set_xticks(x, ticks)
        ax.axhline(0, color="0.3", lw=0.7)
        ax.set_title(pair_label(ref, m))
        tot = numeric(s["compression_virtual"])
        share = {nm: 100 * np.nansum(numeric(s[col])) / np.nansum(tot) for col, nm in zip(cols, names)}
        texts.append(f"{pair_label(ref, m)}: of the CC virtual compression, " +
                     ", ".join(f"{fmt(v)} % is {k}" for k, v in share.items()) + " (summed over the cases).")
    axs[0].set_ylabel("length change [mm]")
    axs[0].legend(frameon=False, fontsize=7.5)
    return [ReportFigure("compression_split", "Where the CC virtual compression goes", fig,
                         "Split of the CC virtual compression into backbone compression, tendon stretch and shape distortion (residual). " + " ".join(texts))]
