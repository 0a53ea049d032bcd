"""Generic report figures of dynamic studies and of the compression split.

:func:`time_series_figures`: for the first and last dynamic case, the time histories of every
``series.*`` column per model (tendon commands and tensions, backbone length change) and the tip
error against the baseline model.  :func:`compression_split_figures`: the CC virtual compression of
each case split into backbone compression, tendon stretch and shape distortion (the columns
:func:`workbench.compare.compare_table` adds when the baseline is ``cc``).  Checked by
``tests/report/test_report_build.py`` and the report tier of ``tests/regression``.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ..compare.table import array_cell
from .load import ResultSet, numeric
from .units import label_of
from .style import ReportFigure, case_title, axis_value, axis_label, fmt, model_color, model_label, pair_label

__all__ = ["time_series_figures", "compression_split_figures"]


# --------------------------------------------------------------------------------------
# time series (dynamic studies)
# --------------------------------------------------------------------------------------
_SERIES_LABELS = {
    "tip_position": "tip position [m]",
    "tendon_lengths": "tendon length change [mm]",
    "tendon_tensions": "tendon tension [N]",
    "length_change": "backbone length change [mm]",
    "tendon_stretch": "tendon stretch [mm]",
}
_MM_SERIES = {"tendon_lengths", "length_change", "tendon_stretch"}
#: series that are no time history of a scalar (the 3-D viewer's backbone frames)
_NOT_PLOTTED = {"backbone", "backbone_time"}


_SERIES_TITLES = {"length_change": "backbone length change (compression < 0)"}


def _row_series(row: Mapping[str, Any], name: str) -> tuple[np.ndarray, np.ndarray] | None:
    t = array_cell(row.get("time"))
    v = array_cell(row.get(f"series.{name}"))
    if t is None or v is None or v.size % t.size:
        return None
    return t, v.reshape(t.size, -1)


def _series_names(dyn: pd.DataFrame) -> tuple[list[str], bool]:
    """The ``series.*`` names with values, in panel order, and whether ``tip_position`` is one."""
    names = [c[len("series."):] for c in dyn.columns
             if str(c).startswith("series.") and c[len("series."):] not in _NOT_PLOTTED
             and dyn[c].map(lambda v: array_cell(v) is not None).any()]
    order = ["tendon_lengths", "tendon_tensions", "length_change"]
    has_tip = "tip_position" in names
    names = [n for n in order if n in names] + [n for n in names if n not in order and n != "tip_position"]
    return names, has_tip


def _tip_error_panel(ax, rows: Mapping[str, Mapping[str, Any]], study: ResultSet, texts: list) -> None:
    ref = _row_series(rows[study.baseline], "tip_position")
    for m, r in rows.items():
        if m == study.baseline:
            continue
        sm = _row_series(r, "tip_position")
        if ref is None or sm is None:
            continue
        pm = np.stack([np.interp(ref[0], sm[0], sm[1][:, k]) for k in range(3)], -1)
        L = float(r.get("robot_length", np.nan))
        e = 100 * np.linalg.norm(pm - ref[1], axis=1) / L
        ax.plot(ref[0], e, color=model_color(m, study.models), label=pair_label(study.baseline, m))
        i = int(np.argmax(e))
        texts.append(f"{pair_label(study.baseline, m)} tip error peaks at {fmt(e[i])} % of L at t = {fmt(ref[0][i])} s and ends at {fmt(e[-1])} %.")
    ax.set_ylabel("tip error [% L]")
    ax.set_title("tip position error")


def _series_panel(ax, rows: Mapping[str, Mapping[str, Any]], name: str, study: ResultSet, texts: list) -> None:
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
                    lw=2.0 if m == study.baseline else 1.5,
                    label=model_label(m) + (f" {comp[k]}" if comp else f" #{k}" if v.shape[1] > 1 else ""))
        if name == "length_change":
            L = float(r.get("robot_length", np.nan))
            texts.append(f"{model_label(m)}: final backbone length change {fmt(v[-1, 0])} mm ({fmt(0.1 * v[-1, 0] / L)} % of L).")
    ax.set_ylabel(_SERIES_LABELS.get(name) or label_of(name))
    ax.set_title(_SERIES_TITLES.get(name, name.replace("_", " ")))


def _case_figure(study: ResultSet, cid, rows, names: list[str], has_tip: bool) -> ReportFigure | None:
    tip_err = has_tip and study.baseline in rows and len(rows) > 1
    panels = [n for n in names if n != "tip_position"] + (["tip_error"] if tip_err else ["tip_position"] if has_tip else [])
    if not panels:
        return None
    ncol = min(2, len(panels))
    nrow = math.ceil(len(panels) / ncol)
    fig = Figure(figsize=(4.4 * ncol + 0.4, 2.8 * nrow + 0.5), layout="constrained")
    axs = np.atleast_1d(fig.subplots(nrow, ncol, squeeze=False).ravel())
    texts: list[str] = []
    for ax, name in zip(axs, panels):
        if name == "tip_error":
            _tip_error_panel(ax, rows, study, texts)
        else:
            _series_panel(ax, rows, name, study, texts)
        ax.set_xlabel("time [s]")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(frameon=False, fontsize=7.5)
    for ax in axs[len(panels):]:
        ax.set_visible(False)
    row0 = next(iter(rows.values()))
    title = case_title(row0, study.axes, study.labels)
    fig.suptitle(title)
    return ReportFigure(f"timeseries_{str(cid)[:12]}", f"Time series, {title}", fig,
                        f"Time histories for {title}; line style distinguishes tendons, colour the model. " + " ".join(texts),
                        cases=(str(cid),))


def time_series_figures(study: ResultSet, cmp: pd.DataFrame, max_cases: int = 2) -> list[ReportFigure]:
    """One ``timeseries_<case>`` figure for the first and last dynamic case (``[]`` for static studies)."""
    if not study.is_dynamic:
        return []
    ok = study.ok
    dyn = ok[ok["time"].map(lambda v: array_cell(v) is not None)]
    names, has_tip = _series_names(dyn)
    case_ids = list(dict.fromkeys(dyn["case_id"]))  # rows are in canonical (parameter) order
    if len(case_ids) > max_cases:
        case_ids = [case_ids[0], case_ids[-1]]
    out = []
    for cid in case_ids:
        rows = {str(r["model"]): r.to_dict() for _, r in dyn[dyn["case_id"] == cid].iterrows()}
        f = _case_figure(study, cid, rows, names, has_tip)
        if f is not None:
            out.append(f)
    return out


# --------------------------------------------------------------------------------------
# compression split (CC baseline, length-controlled tendons)
# --------------------------------------------------------------------------------------
def compression_split_figures(study: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    cols = ["compression_backbone", "compression_tendon_stretch", "compression_shape"]
    if cmp.empty or not all(c in cmp for c in cols):
        return []
    sub = cmp[np.isfinite(numeric(cmp["compression_virtual"]))]
    sub = sub[np.abs(numeric(sub["compression_virtual"])) > 0]
    if sub.empty:
        return []
    pairs = list(dict.fromkeys(zip(sub["reference"], sub["model"])))
    n = len(pairs)
    n_bars = max(len(sub[(sub["reference"] == r) & (sub["model"] == m)]) for r, m in pairs)
    n_lines = max(1, len([a for a in study.axes if a in sub]))
    fig = Figure(figsize=(max(4.2, 0.55 * n_bars + 1.0) * n + 0.4, 3.2 + 0.25 * n_lines), layout="constrained")
    axs = np.atleast_1d(fig.subplots(1, n, squeeze=False)[0])
    colors = ["#4c72b0", "#dd8452", "#55a868"]
    names = ["backbone compression", "tendon stretch", "shape distortion"]
    texts = []
    for ax, (ref, m) in zip(axs, pairs):
        s = sub[(sub["reference"] == ref) & (sub["model"] == m)]
        axes = [a for a in study.axes if a in s]
        if axes:
            # every case its own bar: ticks name each swept value (categories by name), one line per axis
            s = s.sort_values(axes, kind="mergesort")
            ticks = ["\n".join(axis_value(study, a, float(v)) for a, v in zip(axes, vals))
                     for vals in zip(*(numeric(s[a]) for a in axes))]
            ax.set_xlabel(" / ".join(axis_label(a, study.labels) for a in axes) if len(axes) > 1
                          else axis_label(axes[0], study.labels))
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
    fig.legend(*axs[0].get_legend_handles_labels(), loc="outside lower center", ncol=4, frameon=False, fontsize=8)
    return [ReportFigure("compression_split", "Where the CC virtual compression goes", fig,
                         "Split of the CC virtual compression into backbone compression, tendon stretch and shape distortion (residual). " + " ".join(texts))]
