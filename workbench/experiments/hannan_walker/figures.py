"""Report figure of the Hannan & Walker study: shapes along the line and the tracking error.

Registered as ``registry.FIGURES["hannan_walker"]``: :func:`matches` picks studies whose cases ran
the ``hannan_walker_line`` scenario; :func:`figures` draws one panel of backbone overlays per
plan shape (``line``, ``grasp``) and the tip-to-line error of every model.  Checked by the report
tier of ``tests/regression`` (the ``hannan_walker`` study's ``report.html``).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...compare.table import row_positions
from ...report.style import ReportFigure, fmt, model_color, model_label
from ...report.scene import case_scene

__all__ = ["matches", "figures"]


def matches(results) -> bool:
    """True for a study whose (first ok) cases ran the ``hannan_walker_line`` scenario."""
    ok = results.ok
    return (not ok.empty and "p.scenario.name" in ok
            and ok["p.scenario.name"].iloc[0] == "hannan_walker_line")


def _model_along_line(ax, sm: pd.DataFrame, m: str, models, a, b, n: int):
    """Plot model ``m``'s backbones of one shape; return ``(samples, tip-to-target errors)``."""
    errs, ks = [], []
    for j, (_, r) in enumerate(sm.iterrows()):
        k = int(r["p.scenario.sample"])
        target = a + (b - a) * k / (n - 1)
        bp = row_positions(r.to_dict())
        if bp is not None:
            P = bp[1]
            ax.plot(P[:, 0], P[:, 2], color=model_color(m, models), lw=1.2 if m != "cc" else 1.8,
                    ls="-" if m != "cc" else "--", alpha=0.85,
                    label=model_label(m) if j == 0 else None)
        errs.append(math.hypot(float(r["tip_x"]) - target[0], float(r["tip_z"]) - target[1]))
        ks.append(k)
    return ks, errs


def _shape_panel(ax, err_ax, sub: pd.DataFrame, shape: str, first_shape: str, models, texts: list) -> None:
    r0 = sub.iloc[0]
    a = np.array([float(r0["p.scenario.start_x"]), float(r0["p.scenario.start_z"])])
    b = np.array([float(r0["p.scenario.end_x"]), float(r0["p.scenario.end_z"])])
    n = int(r0["p.scenario.n_samples"])
    ax.plot([a[0], b[0]], [a[1], b[1]], color="#ff7f0e", lw=2.5, alpha=0.6, label="commanded line")
    for m in models:
        ks, errs = _model_along_line(ax, sub[sub["model"] == m], m, models, a, b, n)
        if ks:
            err_ax.plot(ks, 1e3 * np.array(errs), marker="o", ms=4, color=model_color(m, models),
                        ls="-" if shape == first_shape else "--", label=f"{model_label(m)}, {shape}")
            texts.append(f"{shape}, {model_label(m)}: tip-to-line error {fmt(1e3 * min(errs))}-{fmt(1e3 * max(errs))} mm")
    ax.plot(0, 0, "ks", ms=6)
    ax.set_aspect("equal")
    vertical = np.allclose(case_scene(r0.to_dict()).rotation, np.eye(3))
    ax.set_xlabel("world x [m] (= base x: vertical mount)" if vertical else "base x [m]")
    ax.set_ylabel("world z [m] (up; gravity along −z)" if vertical else "base z [m]")
    ax.set_title(f"{shape}: snapshots 1-{n} (cf. paper Figs 7-12)" if shape == "line"
                 else f"{shape}: Eq 11 null-space towards q_d")
    ax.legend(frameon=False, fontsize=7.5, loc="upper left", bbox_to_anchor=(0.0, -0.12), ncol=2)


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """Backbone overlays per plan shape and the tracking error along the path."""
    ok = results.ok
    shapes = list(dict.fromkeys(ok["p.scenario.shape"]))
    models = list(results.models)
    fig = Figure(figsize=(5.0 * len(shapes) + 5.6, 6.0), layout="constrained")
    axs = fig.subplots(1, len(shapes) + 1)
    texts: list[str] = []
    err_ax = axs[-1]
    for ax, shape in zip(axs, shapes):
        sub = ok[ok["p.scenario.shape"] == shape].sort_values("p.scenario.sample")
        _shape_panel(ax, err_ax, sub, shape, shapes[0], models, texts)
    err_ax.set_xlabel("sample along the line")
    err_ax.set_ylabel("|tip - line target| [mm]")
    err_ax.set_title("tracking error along the path")
    err_ax.legend(frameon=False, fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.suptitle("Hannan & Walker trunk: CC plan replayed under gravity")
    summary = ("Backbone shapes of every path sample (the paper's six snapshots are photographs without "
               "numbers; these overlays are their model counterparts) and the tip's distance to the "
               "commanded line point.  The resolved-rate CC plan itself is on the line to the controller "
               "tolerance; the CC row is the CC tendon map read back from the jointed (Eq 1) cable commands, "
               "so its error is the CC-vs-jointed cable geometry mismatch, without gravity. " + "; ".join(texts) + ".")
    return [ReportFigure("hannan_walker_overlay", "Hannan & Walker: shapes along the line and tracking error", fig, summary)]
