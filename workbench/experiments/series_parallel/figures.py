"""Report figures of the series-parallel study (``[study] kind = "series_parallel"``).

Registered as ``registry.FIGURES["series_parallel"]``: :func:`matches` picks result tables with a
``p.pose.kind`` column, :func:`figures` returns :func:`pose_figures` of all rows (failed
included).  The generic figures plot errors against one numeric axis; a series-parallel study mixes pose
types (x/y/z translations, rx/ry/rz rotations, stack shapes), so the overview groups by
``p.pose.shape``: (a) the 3-module platform positions, target vs Exudyn FK vs the fitted CC
arc; (b) CC-fit position error vs amplitude per stack shape; (c) single-module IK->FK round-trip
error vs amplitude per axis, failed (unreached) poses marked with crosses.  A second figure shows
the legs along the single-module motions: compression relative to the Euler load, and clearance;
:mod:`.leg_figures` draws the legs themselves (Huang Figs 6 and 10).
Checked by ``tests/experiments/series_parallel/test_run.py`` and the report tier of ``tests/regression``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...report.style import ReportFigure

__all__ = ["matches", "figures", "pose_figures", "pose_overview_figure", "leg_load_figure"]


def pose_overview_figure(df: pd.DataFrame) -> Figure:
    """The three-panel overview of a series-parallel result table (all rows, failed included)."""
    fig = Figure(figsize=(13.5, 4.6), layout="constrained")
    axs = fig.subplots(1, 3, gridspec_kw={"width_ratios": [0.8, 1, 1.1]})
    # (a) stack shapes
    ax = axs[0]
    st = df[df["p.pose.kind"] == "stack"]
    colors = {"translation": "C0", "s_shape": "C1", "bending": "C2"}
    for (shape, value), g in st.groupby(["p.pose.shape", "p.pose.value"], sort=True):
        rows = {r["model"]: r for _, r in g.iterrows()}
        c = colors.get(shape, "k")
        for model, style in (("target", dict(ls="none", marker="o", mfc="none", ms=8)),
                             ("series_parallel", dict(ls="-", marker=".", lw=1.5)),
                             ("cc_fit", dict(ls=":", marker="x", lw=1.0))):
            r = rows.get(model)
            if r is None or r["status"] != "ok":
                continue
            P = np.asarray(r["positions"]).reshape(-1, 3)
            ax.plot(P[:, 0], P[:, 2], color=c, **style)
        sp = rows.get("series_parallel")
        if sp is not None and sp["status"] != "ok":
            T = np.asarray(rows["target"]["positions"]).reshape(-1, 3)
            ax.plot(T[-1, 0], T[-1, 2], "r+", ms=12)
    ax.set_aspect("equal")
    ax.set_xlabel("world x [m]")
    ax.set_ylabel("world z [m] (up)")
    ax.set_title("(a) 3 modules: target o, FK -, CC arc x", fontsize=10)
    for s, c in colors.items():
        ax.plot([], [], color=c, label=s)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), frameon=False, ncol=3)
    ax.grid(alpha=0.3)
    # (b) CC fit error vs amplitude (stack)
    ax = axs[1]
    cc = st[(st["model"] == "cc_fit") & (st["status"] == "ok")]
    for shape, g in cc.groupby("p.pose.shape"):
        g = g.sort_values("p.pose.value")
        amp = float(np.max(np.abs(g["p.pose.value"]))) or 1.0  # one unit per shape: amplitudes as fractions
        unit = "m" if shape == "translation" else "rad"
        ax.plot(g["p.pose.value"] / amp, 1e3 * g["x.cc_max_error"], "o-", color=colors.get(shape, "k"),
                label=f"{shape} (1 = {amp:g} {unit})")
    ax.set_xlabel("amplitude / largest amplitude of the shape")
    ax.set_ylabel("max platform distance from CC arc [mm]")
    ax.set_title("(b) CC arc fit through FK platforms", fontsize=10)
    if len(cc):
        ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    # (c) single-module round trip and reach
    ax = axs[2]
    for k, (label, amp, g) in enumerate(_module_curves(df)):
        ok = g[g["status"] == "ok"]
        c = f"C{k}"
        ax.semilogy(ok["p.pose.value"] / amp, np.maximum(ok["x.fk_position_error"], 1e-16), "o-", color=c,
                    label=label)
        bad = g[g["status"] != "ok"]
        if len(bad):
            ax.semilogy(bad["p.pose.value"] / amp, np.full(len(bad), 1e-17), "x", color=c, ms=10, mew=2)
    ax.set_xlabel("motion / Fig 6 amplitude")
    ax.set_ylabel("|FK(IK(T)) - T| [m]")
    ax.set_title("(c) one module: IK->FK round trip\n(x at 1e-17: IK failed)", fontsize=10)
    if ax.get_legend_handles_labels()[0]:  # a stack-only study has no module motions
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False)
    ax.grid(alpha=0.3)
    return fig


def _module_curves(df: pd.DataFrame):
    """Single-module series-parallel rows, one curve per motion: ``(label, amplitude, rows)``.

    rx / ry about another centre than the platform (``p.pose.pivot``) are their own curves.
    """
    md = df[(df["p.pose.kind"] == "module") & (df["model"] == "series_parallel")].copy()
    md["_curve"] = md["p.pose.shape"]
    if "p.pose.pivot" in md.columns:
        piv = md["p.pose.pivot"].notna()
        md.loc[piv, "_curve"] = [f"{a} @ {p:g} h" for a, p in zip(md.loc[piv, "p.pose.shape"], md.loc[piv, "p.pose.pivot"])]
    order = {"x": 0, "y": 1, "z": 2, "rx": 3, "ry": 4, "rz": 5}  # the paper's Fig 6 order, then pivot variants
    groups = sorted(md.groupby("_curve", sort=False), key=lambda ng: (" @ " in ng[0], order.get(ng[0][:2].strip(), 9), ng[0]))
    for name, g in groups:
        amp = float(np.max(np.abs(g["p.pose.value"]))) or 1.0
        unit = f"{np.degrees(amp):.0f} deg" if name.startswith("r") else f"{1e3 * amp:.0f} mm"
        yield f"{name} (1 = {unit})", amp, g.sort_values("p.pose.value")


def leg_load_figure(df: pd.DataFrame) -> tuple[Figure, str]:
    """Leg loading and clearance along the single-module motions, and a sentence on the extremes."""
    fig = Figure(figsize=(11.5, 3.8), layout="constrained")
    axs = fig.subplots(1, 2)
    worst_ratio, worst_gap = (-np.inf, ""), (np.inf, "")
    for k, (label, amp, g) in enumerate(_module_curves(df)):
        ok = g[g["status"] == "ok"]
        if not len(ok) or "x.buckling_ratio" not in ok or "x.min_leg_gap" not in ok:
            continue
        x = ok["p.pose.value"] / amp
        axs[0].plot(x, ok["x.buckling_ratio"], "o-", color=f"C{k}", label=label)
        axs[1].plot(x, 1e3 * ok["x.min_leg_gap"], "o-", color=f"C{k}", label=label)
        i, j = ok["x.buckling_ratio"].idxmax(), ok["x.min_leg_gap"].idxmin()
        where = lambda r: f"{label.split(' (')[0]} = {r['p.pose.value']:+.3g}"  # noqa: E731
        if ok.loc[i, "x.buckling_ratio"] > worst_ratio[0]:
            worst_ratio = (float(ok.loc[i, "x.buckling_ratio"]), where(ok.loc[i]))
        if ok.loc[j, "x.min_leg_gap"] < worst_gap[0]:
            worst_gap = (float(ok.loc[j, "x.min_leg_gap"]), where(ok.loc[j]))
    axs[0].axhline(1.0, color="k", lw=0.8, ls="--")
    axs[0].set_ylabel("max leg compression / (4π² EI / L²)")
    axs[0].set_title("(a) leg compression vs clamped Euler load", fontsize=10)
    axs[1].axhline(0.0, color="k", lw=0.8, ls="--")
    axs[1].set_ylabel("smallest gap between two legs [mm]")
    axs[1].set_title("(b) leg clearance (< 0: rods intersect)", fontsize=10)
    for ax in axs:
        ax.set_xlabel("motion / Fig 6 amplitude")
        ax.grid(alpha=0.3)
    if axs[1].get_legend_handles_labels()[0]:
        axs[1].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False)
    text = ""
    if np.isfinite(worst_ratio[0]):
        text = (f" Largest leg compression: {worst_ratio[0]:.2f} x the clamped-clamped Euler load of a straight rod of "
                f"the same length (at {worst_ratio[1]}; above 1 a straight rod would have buckled, but these legs are "
                f"S-bent already, so the ratio is a reference, not a stability limit: that is the fold of the IK "
                f"branch). Smallest gap between two legs: "
                f"{1e3 * worst_gap[0]:.1f} mm (at {worst_gap[1]}){' -- the rods would intersect' if worst_gap[0] < 0 else ''}.")
    return fig, text


def pose_figures(results: pd.DataFrame) -> list[ReportFigure]:
    """``[ReportFigure]`` for a series-parallel table, ``[]`` for any other study."""
    if "p.pose.kind" not in results.columns:
        return []
    fig = pose_overview_figure(results)
    summary = ("Series-parallel trunk (Huang et al.): (a) platform origins of the 3-module motions, target, "
               "Exudyn FK after IK and the constant-curvature arc fitted through them; (b) how far the platforms "
               "sit from that arc per motion amplitude; (c) single-module IK->FK round-trip error along each "
               "Fig 6 motion (crosses: poses the IK did not reach; 'rx @ 0.5 h': rotation about the point at "
               "half the module height instead of the platform centre).")
    figs = [ReportFigure("motion_overview", "Series-parallel motions and the CC arc fit", fig, summary)]
    if "x.buckling_ratio" in results.columns and "x.min_leg_gap" in results.columns:
        legs, text = leg_load_figure(results)
        figs.append(ReportFigure("motion_legs", "Series-parallel legs: compression and clearance", legs,
                                 "One module, along each Fig 6 motion: (a) the largest axial leg compression relative "
                                 "to 4 pi^2 EI / L^2; (b) the smallest surface gap between two legs (centreline "
                                 "polylines through the element nodes; contact is not modelled)." + text))
    return figs


def matches(results) -> bool:
    """True for a series-parallel study (its table has a ``p.pose.kind`` column)."""
    return "p.pose.kind" in results.results.columns


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """:func:`pose_figures` of all rows (failed included), then the leg shapes (Huang Figs 6 and 10)."""
    from .leg_figures import leg_shape_figures

    return pose_figures(results.results) + leg_shape_figures(results.results)
