"""Key figure of a series-parallel motion study (``[study] kind = "series_parallel"``).

The generic figures plot errors against one numeric axis; a motion study mixes motion types
(x/y/z translations, rx/ry/rz rotations, stack shapes), so this figure groups by
``p.motion.shape``: (a) the 3-module platform positions, target vs Exudyn FK vs the fitted CC
arc; (b) CC-fit position error vs amplitude per stack shape; (c) single-module IK->FK round-trip
error vs amplitude per axis, failed (unreached) poses marked with crosses.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from .figures import ReportFigure

__all__ = ["motion_figures", "motion_overview_figure"]


def motion_overview_figure(df: pd.DataFrame) -> Figure:
    """The three-panel overview of a motion-study result table (all rows, failed included)."""
    fig = Figure(figsize=(12, 4.3), layout="constrained")
    axs = fig.subplots(1, 3, gridspec_kw={"width_ratios": [0.8, 1, 1.1]})
    # (a) stack shapes
    ax = axs[0]
    st = df[df["p.motion.kind"] == "stack"]
    colors = {"translation": "C0", "s_shape": "C1", "bending": "C2"}
    for (shape, value), g in st.groupby(["p.motion.shape", "p.motion.value"], sort=True):
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
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title("(a) 3 modules: target o, FK -, CC arc x", fontsize=10)
    for s, c in colors.items():
        ax.plot([], [], color=c, label=s)
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(alpha=0.3)
    # (b) CC fit error vs amplitude (stack)
    ax = axs[1]
    cc = st[(st["model"] == "cc_fit") & (st["status"] == "ok")]
    for shape, g in cc.groupby("p.motion.shape"):
        g = g.sort_values("p.motion.value")
        ax.plot(g["p.motion.value"], 1e3 * g["x.cc_max_error"], "o-", color=colors.get(shape, "k"), label=shape)
    ax.set_xlabel("amplitude (translation [m], S / bend [rad])")
    ax.set_ylabel("max platform distance from CC arc [mm]")
    ax.set_title("(b) CC arc fit through FK platforms", fontsize=10)
    if len(cc):
        ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    # (c) single-module round trip and reach
    ax = axs[2]
    md = df[(df["p.motion.kind"] == "module") & (df["model"] == "series_parallel")].copy()
    # rx / ry about another centre than the platform (p.motion.pivot) are separate curves
    md["_curve"] = md["p.motion.shape"]
    if "p.motion.pivot" in md.columns:
        piv = md["p.motion.pivot"].notna()
        md.loc[piv, "_curve"] = [f"{a} @ {p:g} h" for a, p in zip(md.loc[piv, "p.motion.shape"], md.loc[piv, "p.motion.pivot"])]
    for k, (axis, g) in enumerate(md.groupby("_curve", sort=False)):
        g = g.sort_values("p.motion.value")
        ok = g[g["status"] == "ok"]
        amp = float(np.max(np.abs(g["p.motion.value"]))) or 1.0
        unit = f"{np.degrees(amp):.0f} deg" if axis.startswith("r") else f"{1e3 * amp:.0f} mm"
        c = f"C{k}"
        ax.semilogy(ok["p.motion.value"] / amp, np.maximum(ok["x.fk_position_error"], 1e-16), "o-", color=c,
                    label=f"{axis} (1 = {unit})")
        bad = g[g["status"] != "ok"]
        if len(bad):
            ax.semilogy(bad["p.motion.value"] / amp, np.full(len(bad), 1e-17), "x", color=c, ms=10, mew=2)
    ax.set_xlabel("motion / Fig 6 amplitude")
    ax.set_ylabel("|FK(IK(T)) - T| [m]")
    ax.set_title("(c) one module: IK->FK round trip\n(x at 1e-17: IK failed)", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    return fig


def motion_figures(results: pd.DataFrame) -> list[ReportFigure]:
    """``[ReportFigure]`` for a motion-study table, ``[]`` for any other study."""
    if "p.motion.kind" not in results.columns:
        return []
    fig = motion_overview_figure(results)
    summary = ("Series-parallel trunk (Huang et al.): (a) platform origins of the 3-module motions, target, "
               "Exudyn FK after IK and the constant-curvature arc fitted through them; (b) how far the platforms "
               "sit from that arc per motion amplitude; (c) single-module IK->FK round-trip error along each "
               "Fig 6 motion (crosses: poses the IK did not reach; 'rx @ 0.5 h': rotation about the point at "
               "half the module height instead of the platform centre).")
    return [ReportFigure("motion_overview", "Series-parallel motions and the CC arc fit", fig, summary)]
