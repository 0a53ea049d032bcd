"""Report figures of Huang's n-module S-shape: how well 3, 5, 7 modules imitate the S-curve.

Registered as ``registry.FIGURES["series_parallel_s_shape"]``: :func:`matches` picks series-parallel
studies with ``s_shape`` stack motions at two or more module counts.  Figures: the distance of the
module centrelines (and of the platform chord polygon) from the commanded S-curve, divided by the
trunk length, against the number of modules (per amplitude, with the observed power law); and the
commanded curves with the solved platforms.  The first caption states question, findings and
assumptions (:data:`ABOUT`).  Checked by ``tests/experiments/test_series_parallel_backbone.py``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from ...assumptions import Assumption
from ...report.style import ReportFigure, fmt
from ..about import StudyAbout, about_summary
from .backbone import commanded_curve
from .worker import stack_targets

__all__ = ["ABOUT", "matches", "figures", "s_shape_table"]

ABOUT = StudyAbout(
    question=("does Huang's series-parallel trunk imitate the S-shape better with more modules, as the paper deduces "
              "from three? n = 3, 5, 7 identical modules are commanded onto the same S-curve (scaled with the trunk "
              "length: tangent angle at mid-length, top parallel to the base); inverse then forward kinematics in "
              "Exudyn, and the distance of the physical trunk from the curve"),
    assumptions=(
        Assumption("geometry.height", what="module height [m]",
                   source="assumed, ModuleGeometry default (the paper gives no sizes)"),
        Assumption("geometry.rod_diameter", what="rod diameter [m]", source="assumed, ModuleGeometry default"),
        Assumption("geometry.platform_radius", what="platform radius [m]", source="assumed, ModuleGeometry default"),
        Assumption("solver.n_elements", what="GE beam elements per leg", source="discretisation choice"),
        Assumption("", what="trunk centreline = mean of the six legs at equal fractions of their lengths",
                   source="measurement definition (the paper shows pictures only)"),
        Assumption("", what="more modules = more identical modules (the trunk grows with n); errors divided by the "
                             "length",
                   source="reading of 'if it has more sections' / 'more modules should be connected'"),
    ),
    paper_rows=("Huang et al. Sec. 4.2 / Fig 10d-e: 'the s-shaped orientation would be imitated better if it has "
                "more sections' (tested with n = 3, 5, 7)", "Sec. 5: 'to get better flexibility, more modules should "
                "be connected'"),
)


def matches(results) -> bool:
    """A series-parallel study with ``s_shape`` stacks at two or more module counts."""
    ok = results.ok
    if ok.empty or "p.pose.shape" not in ok or "p.pose.n_modules" not in ok:
        return False
    s = ok[ok["p.pose.shape"] == "s_shape"]
    return s["p.pose.n_modules"].nunique() >= 2


def s_shape_table(results_ok: pd.DataFrame) -> pd.DataFrame:
    """One row per ok ``series_parallel`` S-shape row: n, amplitude, trunk length and the errors over it."""
    s = results_ok[(results_ok["p.pose.shape"] == "s_shape") & (results_ok["model"] == "series_parallel")]
    t = pd.DataFrame({
        "n": s["p.pose.n_modules"].astype(int), "amplitude": s["p.pose.value"].astype(float),
        "L": s["robot_length"].astype(float), "backbone": s["x.backbone_max_error"].astype(float),
        "rms": s["x.backbone_rms_error"].astype(float), "polygon": s["x.polygon_max_error"].astype(float),
    })
    for c in ("backbone", "rms", "polygon"):
        t[c + "_rel"] = t[c] / t["L"]
    return t.sort_values(["amplitude", "n"]).reset_index(drop=True)


def _exponent(n: np.ndarray, e: np.ndarray) -> float:
    """Slope of ``log e`` against ``log n`` (least squares), NaN with fewer than two points."""
    ok = np.isfinite(e) & (e > 0)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(n[ok]), np.log(e[ok]), 1)[0])


def _findings(t: pd.DataFrame) -> list[str]:
    out = []
    for a, g in t.groupby("amplitude"):
        pts = ", ".join(f"n = {int(r.n)}: {fmt(100 * r.backbone_rel)} % L ({fmt(1e3 * r.backbone)} mm)" for r in g.itertuples())
        out.append(f"S-shape amplitude {fmt(a)} rad: largest centreline distance from the curve {pts}; "
                   f"power law n^{fmt(_exponent(g['n'].to_numpy(float), g['backbone_rel'].to_numpy()))} "
                   f"(chord polygon through the platforms: n^{fmt(_exponent(g['n'].to_numpy(float), g['polygon_rel'].to_numpy()))}, "
                   f"{fmt(100 * g['polygon_rel'].max())}-{fmt(100 * g['polygon_rel'].min())} % L)")
    return out


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """Error vs module count, and the commanded curves with the solved platforms."""
    ok = results.ok
    t = s_shape_table(ok)
    fig = Figure(figsize=(6.4, 4.6), layout="constrained")
    ax = fig.subplots()
    for i, (a, g) in enumerate(t.groupby("amplitude")):
        c = f"C{i}"
        ax.plot(g["n"], 100 * g["backbone_rel"], "o-", color=c, label=f"trunk centreline, {fmt(a)} rad")
        ax.plot(g["n"], 100 * g["polygon_rel"], "s:", color=c, mfc="none", label=f"platform chord polygon, {fmt(a)} rad")
    if not t.empty:
        n = np.array(sorted(t["n"].unique()), dtype=float)
        g0 = t[t["amplitude"] == t["amplitude"].max()].sort_values("n")
        ax.plot(n, 100 * g0["backbone_rel"].iloc[0] * (n / n[0]) ** -2, color="#999999", lw=0.8, ls="--", label="n^-2")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xticks(sorted(t["n"].unique()))
    ax.set_xticklabels([str(v) for v in sorted(t["n"].unique())])
    ax.set_xlabel("number of modules n")
    ax.set_ylabel("largest distance from the commanded S-curve [% of trunk length]")
    ax.legend(frameon=False, fontsize=7)
    ax.set_title("Huang's S-shape with more modules", fontsize=10)
    out = [ReportFigure("s_shape_vs_modules", "S-shape: distance from the commanded curve vs number of modules", fig,
                        about_summary(ABOUT, ok, _findings(t)))]
    out.append(_shapes_figure(ok, t))
    return out


def _shapes_figure(ok: pd.DataFrame, t: pd.DataFrame) -> ReportFigure:
    fig = Figure(figsize=(5.2, 5.6), layout="constrained")
    ax = fig.subplots()
    a = t["amplitude"].max() if not t.empty else 0.0
    sp = ok[(ok["model"] == "series_parallel") & (ok["p.pose.shape"] == "s_shape") & (ok["p.pose.value"] == a)]
    drawn = False
    for i, n in enumerate(sorted(t["n"].unique())):
        r = sp[sp["p.pose.n_modules"] == n]
        if r.empty:
            continue
        r = r.iloc[0]
        L = float(r["robot_length"])
        if not drawn:
            C = commanded_curve(stack_targets, "s_shape", a, n, L / n, float(r["p.pose.plane"]), n_points=400)
            ax.plot(C[:, 0] / L, C[:, 2] / L, color="#ff7f0e", lw=3, alpha=0.5, label="commanded S-curve")
            drawn = True
        P = np.asarray(r["positions"], dtype=float).reshape(-1, 3) / L
        ax.plot(P[:, 0], P[:, 2], ".-", color=f"C{i}", lw=0.9, label=f"n = {n}: platforms (FK) and chords")
    ax.set_aspect("equal")
    ax.set_xlabel("x / L (stack base frame)")
    ax.set_ylabel("z / L")
    ax.legend(frameon=False, fontsize=7, loc="lower right")
    text = (f"The commanded S-curve (amplitude {fmt(a)} rad; the same curve for every n once divided by the trunk "
            "length L) and the platforms the Exudyn forward kinematics puts on it.  The platforms sit on the curve by "
            "construction (inverse kinematics); the chords between them show how coarse a rigid chain through the "
            "same platforms would be; the flexible legs between the platforms are measured in the first figure.")
    return ReportFigure("s_shape_curves", "S-shape: commanded curve and solved platforms", fig, text)
