"""Generic report figure: the backbone shapes of a few representative cases, every model overlaid.

:func:`shape_overlay_figures` picks the cases with the smallest, median and largest tip error of
the first model pair (or the first, middle and last case of the sweep; ties broken by the
canonical row order of :func:`.load.canonical_order`, so the pick never depends on how the rows
were stored) and draws them **in parameter order**, in the study's frame (``world`` by default:
vertical axis = world z, gravity drawn as an arrow; ``[report] frame = "base"`` on request), with
equal axis scaling: the x-z projection, plus the y-z projection for spatial results.  A dynamic
study draws each case twice, at the time of its peak tip error and at the end, from the stored
backbone frames (``series.backbone``).  Checked by ``tests/report/test_report_build.py``,
``tests/report/test_report_order.py`` and the report tier of ``tests/regression``.
"""

from __future__ import annotations

import textwrap

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ..compare.table import array_cell, row_positions
from .load import ResultSet, numeric
from .scene import case_scene, gravity_in, to_frame
from .style import ReportFigure, case_title, baseline_pairs, fmt, model_color, model_label, pair_label, point_links

__all__ = ["shape_overlay_figures", "backbone_frames", "peak_error_time"]

#: ``(linewidth, alpha, linestyle)`` of the physics models, thick-and-light to thin.
_PHYS_STYLES = [(5.0, 0.4, "-"), (1.8, 1.0, "-"), (1.5, 1.0, (0, (5, 2))), (1.3, 1.0, ":")]


def _representative_cases(study: ResultSet, cmp: pd.DataFrame) -> tuple[list[str], str]:
    ok = study.ok
    pairs = baseline_pairs(cmp, study.baseline)
    order = {c: i for i, c in enumerate(dict.fromkeys(ok["case_id"]))}  # canonical (parameter) order
    if pairs:
        ref, m = pairs[0]
        sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]
        sub = sub.assign(_o=sub["case_id"].map(order)).sort_values(["tip_error_pct", "_o"], kind="mergesort")
        ids = list(sub["case_id"])
        how = f"cases with the smallest, median and largest {pair_label(ref, m)} tip error"
    else:
        ids = list(order)
        how = "first, middle and last case of the sweep"
    if not ids:
        return [], how
    picks = list(dict.fromkeys([ids[0], ids[len(ids) // 2], ids[-1]]))
    if len(picks) == 1:
        how = "only case" if len(ids) == 1 else how
    elif len(picks) == 2:
        how = how.replace("smallest, median and largest", "smallest and largest").replace("first, middle and last", "first and last")
    return sorted(picks, key=lambda c: order.get(c, 0)), how


def backbone_frames(row) -> tuple[np.ndarray, np.ndarray] | None:
    """``(times (k,), positions (k, m, 3))`` of a dynamic row's stored backbone frames, base frame."""
    t = array_cell(row.get("series.backbone_time"))
    p = array_cell(row.get("series.backbone"))
    if t is None or p is None or t.size == 0 or p.size % (3 * t.size):
        return None
    return t, p.reshape(t.size, -1, 3)


def peak_error_time(rows: dict, baseline: str) -> float | None:
    """Time of the largest tip distance between any model and the baseline model (``series.tip_position``)."""
    ref = rows.get(baseline)
    if ref is None:
        return None
    tr, pr = array_cell(ref.get("time")), array_cell(ref.get("series.tip_position"))
    if tr is None or pr is None or pr.size != 3 * tr.size:
        return None
    pr = pr.reshape(-1, 3)
    best, t_best = -1.0, None
    for m, r in rows.items():
        tm, pm = array_cell(r.get("time")), array_cell(r.get("series.tip_position"))
        if m == baseline or tm is None or pm is None or pm.size != 3 * tm.size:
            continue
        pm = pm.reshape(-1, 3)
        e = np.linalg.norm(np.stack([np.interp(tm, tr, pr[:, k]) for k in range(3)], -1) - pm, axis=1)
        i = int(np.argmax(e))
        if e[i] > best:
            best, t_best = float(e[i]), float(tm[i])
    return t_best


def _at_time(row, t: float | None):
    """Base-frame backbone of ``row`` at the stored frame nearest ``t`` (final shape for ``None``)."""
    fr = backbone_frames(row)
    if t is None or fr is None:
        bp = row_positions(row)
        return None if bp is None else bp[1]
    return fr[1][int(np.argmin(np.abs(fr[0] - t)))]


def _panels(study: ResultSet, ids) -> list:
    """``[(case_id, first row, {model: frame positions (m, 3)}, subtitle, gravity (3,))]``."""
    ok = study.ok
    out = []
    for cid in ids:
        rows = {str(r["model"]): r.to_dict() for _, r in ok[ok["case_id"] == cid].iterrows()}
        if not rows:
            continue
        row0 = next(iter(rows.values()))
        scene = case_scene(row0)
        times = [(None, "")]
        if study.is_dynamic:
            t_pk = peak_error_time(rows, study.baseline)
            t_end = max((float(array_cell(r.get("time"))[-1]) for r in rows.values() if array_cell(r.get("time")) is not None),
                        default=None)
            if t_pk is not None and any(backbone_frames(r) is not None for r in rows.values()):
                times = [(t_pk, f"at peak error, t = {fmt(t_pk)} s"), (None, f"at the end, t = {fmt(t_end)} s")]
            else:
                times = [(None, f"at the end, t = {fmt(t_end)} s")]
        for t, sub in times:
            per = {}
            for m, r in rows.items():
                p = _at_time(r, t)
                if p is not None:
                    per[m] = to_frame(p, scene, study.frame)
            if per:
                out.append((cid, row0, per, sub, gravity_in(scene, study.frame), scene.known))
    return out


def _layout(study: ResultSet, allpts: np.ndarray):
    """Views, common limits and panel size of the overlay: ``(spatial, views, lo, hi, pad, panel_w, panel_h)``."""
    ok = study.ok
    L = float(np.nanmax(numeric(ok["robot_length"]))) if "robot_length" in ok else float(np.ptp(allpts[:, 2]))
    spatial = bool(np.nanmax(np.abs(allpts[:, 1])) > 1e-6 * max(L, 1e-12))
    f = study.frame
    views = [(0, 2, f"{f} x [m]", f"{f} z [m]")] + ([(1, 2, f"{f} y [m]", f"{f} z [m]")] if spatial else [])
    lo = np.minimum(allpts.min(axis=0), 0.0)
    hi = np.maximum(allpts.max(axis=0), 0.0)
    pad = 0.08 * max(float(np.max(hi - lo)), 1e-9)
    aspect = max((hi[a] - lo[a] + 2 * pad) / (hi[b] - lo[b] + 2 * pad) for a, b, _, _ in views)
    panel_h = 3.2
    panel_w = float(np.clip(panel_h * aspect + 0.7, 2.4, 5.5))
    return spatial, views, lo, hi, pad, panel_w, panel_h


def _draw_backbones(ax, per, models, baseline: str, a: int, b: int) -> None:
    phys = [x for x in models if x != baseline]
    for m in models:
        if m not in per:
            continue
        p = per[m]
        ref = m == baseline
        # physics models drawn thick-and-light to thin so coinciding backbones stay visible
        lw, alpha, ls = (2.0, 1.0, "--") if ref else _PHYS_STYLES[phys.index(m) % len(_PHYS_STYLES)]
        ax.plot(p[:, a], p[:, b], color=model_color(m, models), ls=ls, lw=lw, alpha=alpha,
                marker=None if p.shape[0] > 12 else "o", ms=3, label=model_label(m), zorder=3 if ref else 2)
        ax.plot(p[-1, a], p[-1, b], "o", color=model_color(m, models), ms=4, zorder=4)


def _gravity_arrow(ax, g: np.ndarray, a: int, b: int) -> None:
    """Gravity as an arrow in the panel's upper right corner (or "g = 0"), axes coordinates."""
    n = float(np.linalg.norm(g))
    if n == 0:
        ax.text(0.97, 0.96, "g = 0", transform=ax.transAxes, ha="right", va="top", fontsize=8, color="0.35")
        return
    d = np.array([g[a], g[b]]) / n
    if np.hypot(*d) < 1e-9:
        ax.text(0.97, 0.96, "g ⊥ view", transform=ax.transAxes, ha="right", va="top", fontsize=8, color="0.35")
        return
    tip = np.array([0.9, 0.78]) + 0.09 * d
    ax.annotate("", xy=tip, xytext=tip - 0.16 * d, xycoords="axes fraction",
                arrowprops={"arrowstyle": "-|>", "color": "#3060c0", "lw": 1.6})
    ax.text(0.9, 0.97, f"g {fmt(n)} m/s²", transform=ax.transAxes, ha="center", va="top", fontsize=7.5, color="#3060c0")


def _gravity_legend(data) -> tuple[list, list]:
    """World frame: gravity is world -z in every panel, so it is one legend entry (an arrow)."""
    from matplotlib.lines import Line2D

    gs = sorted({round(float(np.linalg.norm(g)), 6) for *_, g, _ in data})
    if gs == [0.0]:
        return [Line2D([], [], ls="none")], ["no gravity"]
    txt = ", ".join(fmt(x) for x in gs if x > 0)
    return ([Line2D([], [], ls="none", marker=r"$\downarrow$", ms=12, color="#3060c0")],
            [f"gravity (world −z), {txt} m/s²"])


def _figure_legend(fig, axs, extra=([], [])) -> None:
    """One legend below the panels with every label of any panel, first seen first, then ``extra``."""
    handles, labs = [], []
    for ax in axs.flat:
        for hh, ll in zip(*ax.get_legend_handles_labels()):
            if ll not in labs:
                handles.append(hh)
                labs.append(ll)
    handles += list(extra[0])
    labs += list(extra[1])
    fig.legend(handles, labs, loc="outside lower center", ncol=max(1, len(labs)), frameon=False)


def _summary(study: ResultSet, cmp: pd.DataFrame, how: str, spatial: bool, known: bool, gravity: bool) -> str:
    f = study.frame
    proj = f" Top row: {f} x-z projection, bottom row: {f} y-z projection." if spatial else f" Projection on the {f} x-z plane."
    frame_txt = ("World frame: z up, no gravity in these cases." if f == "world" and known and not gravity else
                 "World frame: z up, gravity along world −z (legend)." if f == "world" and known else
                 "World frame = the study's base frame (no mounting given)." if f == "world" else
                 "Base frame (backbone along base +z), gravity arrow in base coordinates.")
    summary = (f"Backbones of the {how}, in parameter order; equal axis scaling, base at the grey square, tips dotted. "
               f"{frame_txt}{proj}")
    if study.is_dynamic:
        summary += " Dynamic cases: the shape at the stored frame nearest the peak tip error, and at the end."
    pairs = baseline_pairs(cmp, study.baseline)
    if pairs:
        ref, m = pairs[0]
        sub = cmp[(cmp["reference"] == ref) & (cmp["model"] == m)]
        worst = sub.loc[sub["tip_error_pct"].idxmax()]
        summary += (f" Largest {pair_label(ref, m)} tip error shown: {fmt(worst['tip_error_pct'])} % of L "
                    f"({fmt(1e3 * worst['tip_error'])} mm, final state).")
    return summary


def shape_overlay_figures(study: ResultSet, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The ``shapes`` figure (``[]`` when no case has a backbone)."""
    ids, how = _representative_cases(study, cmp)
    if not ids:
        return []
    models = [m for m in study.models if m in set(study.ok["model"])]
    data = _panels(study, ids)
    if not data:
        return []
    allpts = np.vstack([p for _, _, per, _, _, _ in data for p in per.values()])
    spatial, views, lo, hi, pad, panel_w, panel_h = _layout(study, allpts)
    ncol = len(data)
    fig = Figure(figsize=(panel_w * ncol + 0.4, (panel_h + 1.0) * len(views) + 0.5), layout="constrained")
    axs = np.atleast_2d(fig.subplots(len(views), ncol, squeeze=False))
    points = []
    for j, (cid, row0, per, sub, g, _) in enumerate(data):
        for i, (a, b, la, lb) in enumerate(views):
            ax = axs[i, j]
            _draw_backbones(ax, per, models, study.baseline, a, b)
            points += point_links(ax, [p[-1, a] for p in per.values()], [p[-1, b] for p in per.values()],
                                  [cid] * len(per), list(per), [f"{model_label(m)} tip, case {str(cid)[:8]}" for m in per])
            base = next(iter(per.values()))[0]
            ax.plot([base[a]], [base[b]], marker="s", color="0.4", ms=5)
            ax.set_xlim(lo[a] - pad, hi[a] + pad)
            ax.set_ylim(lo[b] - pad, hi[b] + (2.2 if study.frame == "base" else 1.0) * pad)
            ax.set_aspect("equal", adjustable="box")
            ax.set_xlabel(la)
            if study.frame == "base" or not data[j][5]:
                _gravity_arrow(ax, g, a, b)
            if j == 0:
                ax.set_ylabel(lb)
            if i == 0:
                title = case_title(row0, study.axes, study.labels) + (f"\n{sub}" if sub else "")
                ax.set_title("\n".join(textwrap.fill(t, width=34) for t in title.split("\n")), fontsize=9)
    known = all(k for *_, k in data)
    _figure_legend(fig, axs, _gravity_legend(data) if study.frame == "world" and known else ([], []))
    return [ReportFigure("shapes", f"Backbone shapes ({study.frame} frame)", fig,
                         _summary(study, cmp, how, spatial, known, any(np.linalg.norm(d[4]) > 0 for d in data)),
                         cases=tuple(dict.fromkeys(d[0] for d in data)), points=tuple(points))]
