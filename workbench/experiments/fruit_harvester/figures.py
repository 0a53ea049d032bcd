"""Report figure of the fruit-harvester study: grasp envelope and grasp-centre drift under payload.

Registered as ``registry.FIGURES["fruit_harvester"]``: :func:`matches` picks bend-angle studies
(no ``[scenario]``) of the ``shao_harvester`` preset; :func:`figures` draws the assumed envelope
(:mod:`.envelope`), the backbones with their best-fit arc centres, and how far the grasp centre
drifts from the CC centre of arc with the payload.  Checked by the report tier of
``tests/regression`` (the ``fruit_harvester`` study's ``report.html``).  Backbones are drawn in the world frame
(the robot hangs: heavier payloads drop the tip); the centres are fitted in the bending plane.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...compare.table import row_positions
from ...report.style import ReportFigure, fmt, model_color, model_label
from ...report.scene import case_scene, to_frame
from .envelope import HARVESTER_LIMITS, circle_fit, grasp_envelope

__all__ = ["matches", "figures"]

_PAYLOAD_COLORS = ["#fdae61", "#f46d43", "#d73027", "#a50026", "#67001f", "#313695"]
_STYLES = ["-", "--", ":"]


def matches(results) -> bool:
    """True for a study of the ``shao_harvester`` preset that runs no scenario.

    A scenario study has its own figure set.
    """
    ok = results.ok
    if ok.empty or "p.robot.preset" not in ok or ok["p.robot.preset"].iloc[0] != "shao_harvester":
        return False
    scen = ok["p.scenario.name"].iloc[0] if "p.scenario.name" in ok else None
    return scen is None or (isinstance(scen, float) and math.isnan(scen))


def _envelope_panel(ax, D: float):
    lim = HARVESTER_LIMITS
    s = np.linspace(lim["s_min"], lim["s_max"], 50)
    d_lo, d_hi = grasp_envelope(s, D, lim)
    ax.fill_between(s * 1e3, 1e3 * d_lo, 1e3 * d_hi, color="#8da0cb", alpha=0.5, label="wrap grasp feasible")
    ax.axhline(100, color="k", ls=":", lw=1)
    ax.text(s[0] * 1e3, 101, "paper: objects up to 100 mm", fontsize=7.5, va="bottom")
    ax.set_xlabel("arc length s [mm]")
    ax.set_ylabel("object diameter d = 2/κ − D [mm]")
    ax.set_title("centre-of-arc grasp envelope (assumed limits)")
    ax.legend(frameon=False, fontsize=7.5, loc="upper left")
    return d_lo, d_hi


def _centre_offsets(ax_shape, ok: pd.DataFrame, m: str, bend: float, payloads, show: bool):
    """Grasp-centre offsets of model ``m`` per payload at one bend; draws the shapes when ``show``."""
    offs, pls = [], []
    for pi, pm in enumerate(payloads):
        sel = ok[(ok["p.load.bend_angle"] == bend) & (ok["p.robot.payload_mass"] == pm)]
        rm = sel[sel["model"] == m]
        rc = sel[sel["model"] == "cc"]
        if rm.empty or rc.empty:
            continue
        bp = row_positions(rm.iloc[0].to_dict())
        bc = row_positions(rc.iloc[0].to_dict())
        if bp is None or bc is None:
            continue
        c_fit, R = circle_fit(bp[1][:, [0, 2]])
        c_cc, _ = circle_fit(bc[1][:, [0, 2]])
        offs.append(np.linalg.norm(c_fit - c_cc))  # fitted in the base x-z plane (the bending plane)
        pls.append(pm)
        if show:  # drawn in the world frame: the base hangs, gravity points down the page
            scene = case_scene(rm.iloc[0].to_dict())

            def world(P):
                return 1e3 * to_frame(P, scene, "world")

            def centre(c):
                return world(np.array([c[0], 0.0, c[1]]))

            col = _PAYLOAD_COLORS[pi % len(_PAYLOAD_COLORS)]
            wp, wc = world(bp[1]), centre(c_fit)
            ax_shape.plot(wp[:, 0], wp[:, 2], color=col, label=f"{model_label(m)} {fmt(1e3 * pm)} g")
            ax_shape.plot(wc[0], wc[2], "o", color=col, ms=5)
            if pi == 0:
                wb, wcc = world(bc[1]), centre(c_cc)
                ax_shape.plot(wb[:, 0], wb[:, 2], "k--", lw=1.8, label="CC (any payload)")
                ax_shape.plot(wcc[0], wcc[2], "kx", ms=9, mew=2, label="CC centre of arc")
    return offs, pls


def _label_drift_axes(ax_shape, ax_c, bshow: float) -> None:
    ax_shape.set_aspect("equal")
    ax_shape.set_xlabel("world x [mm]")
    ax_shape.set_ylabel("world z [mm] (gravity along −z; the base hangs at 0)")
    ax_shape.set_title(f"backbones and best-fit arc centres, κs = {fmt(bshow)} rad")
    ax_shape.legend(frameon=False, fontsize=6.5, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    ax_c.set_xlabel("payload mass [g]")
    ax_c.set_ylabel("|grasp centre - CC centre| [mm]")
    ax_c.set_title("grasp centre drift (best-fit arc of the backbone)")
    ax_c.legend(frameon=False, fontsize=7.5)


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The envelope, the backbones at the largest bend, and the grasp-centre drift per model."""
    ok = results.ok
    lim = HARVESTER_LIMITS
    fig = Figure(figsize=(15.0, 4.8), layout="constrained")
    ax_env, ax_shape, ax_c = fig.subplots(1, 3, gridspec_kw={"width_ratios": [1, 1.35, 1]})
    D = float(ok["p.robot.outer_diameter"].iloc[0]) if "p.robot.outer_diameter" in ok else 0.06
    d_lo, d_hi = _envelope_panel(ax_env, D)
    phys = [m for m in results.models if m != "cc"]
    bends = sorted(set(float(v) for v in ok["p.load.bend_angle"]))
    payloads = sorted(set(float(v) for v in ok["p.robot.payload_mass"]))
    texts = []
    bshow = bends[-1]
    for bi, bend in enumerate(bends):
        for m in phys:
            offs, pls = _centre_offsets(ax_shape, ok, m, bend, payloads, bend == bshow)
            if pls:
                ax_c.plot(1e3 * np.array(pls), 1e3 * np.array(offs), marker="o", ls=_STYLES[bi % 3],
                          color=model_color(m, results.models), label=f"{model_label(m)}, κs = {fmt(bend)} rad")
                texts.append(f"kappa s = {fmt(bend)} rad ({model_label(m)}): grasp centre {fmt(1e3 * offs[0])} mm off the "
                             f"CC centre without payload, {fmt(1e3 * offs[-1])} mm with {fmt(1e3 * pls[-1])} g")
    _label_drift_axes(ax_shape, ax_c, bshow)
    fig.suptitle("Shao harvester: grasp envelope and payload sag")
    lo, hi = 1e3 * d_lo[-1], 1e3 * d_hi[-1]
    summary = (f"Envelope with the assumed limits s in [{fmt(1e3 * lim['s_min'])}, {fmt(1e3 * lim['s_max'])}] mm, "
               f"kappa <= {fmt(lim['kappa_max'])} 1/m, wrap angle >= {fmt(math.degrees(lim['wrap_angle']))} deg, "
               f"D = {fmt(1e3 * D)} mm: objects {fmt(lo)}-{fmt(hi)} mm at full length. Grasp centre = centre of the "
               f"least-squares circle through the backbone (x-z plane). " + "; ".join(texts) + ".")
    return [ReportFigure("harvester_grasp", "Fruit harvester: grasp envelope and grasp-centre drift under payload", fig, summary)]
