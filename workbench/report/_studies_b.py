"""Study-specific report figures: wire delay (Cojocaru), Hannan & Walker replay, fruit harvester.

:func:`study_figures` recognises the study from its result table (the ``[scenario]`` name or
the robot preset) and returns the key figures of that study; other studies get none.  The
figures recompute command-side quantities (commanded wire lengths, line targets, CC
centres of arc) with the same pure functions the runner used, from the case parameters.

Fruit-harvester grasp envelope: Shao et al. (papers/002_, Sec. 4) state that the arc length
``s`` and curvature ``kappa`` limits bound the object sizes that can be scooped (up to
100 mm, 200 g) but give no numbers.  **Assumed** here (documented, plotted as such): the
skin of a section of outer diameter ``D`` wraps an object of diameter
``d = 2 / kappa - D``; holding it needs a wrap angle ``kappa s >= 3 pi / 2``; the section can
contract to ``s_min = 0.34 m`` (15 %) and not elongate beyond ``0.40 m``; the curvature is
limited by the actuators to ``kappa <= 25 1/m``.  Then
``d in [2 / kappa_max - D, 2 s / (3 pi / 2) - D]``, i.e. 20 ... 110 mm at s = 0.40 m.
"""

from __future__ import annotations

import json
import math
from typing import Any, Mapping

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ..compare.table import array_cell, row_positions
from .figures import ReportFigure, fmt, model_color, model_label
from .load import Study

__all__ = ["study_figures", "circle_fit", "HARVESTER_LIMITS"]

#: Assumed limits of the harvester grasp envelope (see the module docstring).
HARVESTER_LIMITS = {"s_min": 0.34, "s_max": 0.40, "kappa_max": 25.0, "wrap_angle": 1.5 * math.pi}


def _value(v: Any) -> Any:
    if isinstance(v, str) and v[:1] in "[{":
        return json.loads(v)
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating,)):
        return float(v)
    return v


def _section(row: Mapping[str, Any], section: str) -> dict[str, Any]:
    pre = f"p.{section}."
    return {k[len(pre):]: _value(v) for k, v in row.items() if str(k).startswith(pre) and not _isnan(v)}


def _isnan(v: Any) -> bool:
    return isinstance(v, float) and math.isnan(v)


def _robot_and_load(row: Mapping[str, Any]):
    from ..study.evaluate import build_load, build_robot
    from ..study.scenarios import load_with_scenario

    robot = build_robot(_section(row, "robot"), _section(row, "derived"))
    load = _section(row, "load")
    scen = _section(row, "scenario")
    load = load_with_scenario(robot, load, scen or None)
    return robot, build_load(robot, load), scen


def circle_fit(points: np.ndarray) -> tuple[np.ndarray, float]:
    """Least-squares circle (Kasa) through planar points ``(m, 2)``: ``(centre (2,), radius)``."""
    p = np.asarray(points, dtype=float)
    A = np.column_stack([2 * p[:, 0], 2 * p[:, 1], np.ones(len(p))])
    b = (p ** 2).sum(axis=1)
    sol, *_ = np.linalg.lstsq(A, b, rcond=None)
    c = sol[:2]
    return c, float(np.sqrt(sol[2] + c @ c))


def study_figures(study: Study, cmp: pd.DataFrame) -> list[ReportFigure]:
    """Key figures of the wire-delay, Hannan & Walker and fruit-harvester studies (else [])."""
    ok = study.ok
    if ok.empty:
        return []
    scen = ok["p.scenario.name"].iloc[0] if "p.scenario.name" in ok else None
    preset = ok["p.robot.preset"].iloc[0] if "p.robot.preset" in ok else None
    if scen == "wire_delay":
        return _wire_delay(study, ok)
    if scen == "hannan_walker_line":
        return _hannan_walker(study, ok)
    if preset == "shao_harvester":
        return _harvester(study, ok)
    return []


# --------------------------------------------------------------------------------------
# wire delay
# --------------------------------------------------------------------------------------
def _wire_delay(study: Study, ok: pd.DataFrame) -> list[ReportFigure]:
    from ..compare.metrics import compression_split
    from ..physics.wire_delay import _cc_tip, arc_from_wire_lengths_tronconic, wire_lengths_tronconic

    phys = [m for m in study.models if m != "cc"]
    if not phys:
        return []
    m = phys[0]
    rows = ok[(ok["model"] == m) & ok["time"].map(lambda v: array_cell(v) is not None)]
    if rows.empty:
        return []
    rows = rows.sort_values("p.scenario.delay")
    fig = Figure(figsize=(12.5, 7.2), layout="constrained")
    axs = fig.subplots(2, 3).ravel()
    cmap = ["#1b9e77", "#7570b3", "#d95f02", "#e7298a", "#66a61e", "#e6ab02"]
    texts, split_rows = [], []
    for i, (_, r) in enumerate(rows.iterrows()):
        r = r.to_dict()
        robot, load, scen = _robot_and_load(r)
        sec = robot.sections[0]
        g = sec.tendons
        H, d1 = sec.length, g.offset
        d2 = g.offset_tip if g.offset_tip is not None else g.offset
        sigma = np.asarray(g.angles, float)
        t = array_cell(r["time"])
        n_t = robot.n_tendons
        L0 = wire_lengths_tronconic(0.0, 0.0, H, d1, d2, sigma)
        Lcmd = L0 + load.actuation.command_at(t, load.ramp_time)
        th, ph, e = arc_from_wire_lengths_tronconic(Lcmd, H, d1, d2, sigma)
        tip_cc = _cc_tip(th, ph, H)
        dl = array_cell(r["series.length_change"])
        st = array_cell(r["series.tendon_stretch"]).reshape(t.size, n_t)
        tens = array_cell(r["series.tendon_tensions"]).reshape(t.size, n_t)
        tip = array_cell(r["series.tip_position"]).reshape(t.size, 3)
        tw = array_cell(r.get("series.tip_twist"))
        err = np.linalg.norm(tip - tip_cc, axis=1)
        delay = float(r["p.scenario.delay"])
        c = cmap[i % len(cmap)]
        lab = f"delay {fmt(delay)} s"
        axs[0].plot(t, 100 * e / H, color=c, label=lab)
        axs[1].plot(t, 100 * dl / H, color=c, label=lab)
        axs[2].plot(t, 1e3 * st.mean(axis=1), color=c, label=lab)
        axs[3].plot(t, 1e3 * err, color=c, label=lab)
        if tw is not None and tw.size == t.size:
            axs[4].plot(t, np.degrees(tw), color=c, label=lab)
        # the instant the late wire starts (e is extreme from then until the others stop);
        # without delay the end of the move
        t_star = min(delay, float(scen.get("move_time", load.ramp_time))) if delay > 0 else float(load.ramp_time)
        k = int(np.argmin(np.abs(t - t_star)))
        sp = compression_split(e[k], dl[k], st[k].mean())
        split_rows.append((delay, t[k], sp))
        texts.append(
            f"delay {fmt(delay)} s: virtual compression {fmt(1e3 * e[k])} mm ({fmt(100 * e[k] / H)} % of H) "
            f"at t = {fmt(t[k])} s (min over time {fmt(100 * e.min() / H)} %); there the beam's backbone changes by {fmt(1e3 * dl[k])} mm "
            f"({fmt(100 * dl[k] / H)} % of H), the wires stretch by {fmt(1e3 * st[k].mean())} mm on average "
            f"(max tension {fmt(tens[k].max())} N), and the shape leaves the CC family by "
            f"{fmt(1e3 * sp.shape)} mm (tip {fmt(1e3 * err[k])} mm off the CC tip; peak tip error "
            f"{fmt(1e3 * err.max())} mm at t = {fmt(t[int(np.argmax(err))])} s, final {fmt(1e3 * err[-1])} mm)."
        )
    titles = [
        ("kinematic virtual compression e (CC of the commands)", "e / H [%]"),
        (f"{model_label(m)} backbone length change", "dL / H [%]"),
        (f"{model_label(m)} mean wire stretch", "stretch [mm]"),
        (f"{model_label(m)} tip distance to the CC tip of the commands", "tip error [mm]"),
        (f"{model_label(m)} tip twist", "twist [deg]"),
    ]
    for ax, (ti, yl) in zip(axs, titles):
        ax.set_title(ti)
        ax.set_ylabel(yl)
        ax.set_xlabel("time [s]")
    axs[0].axhline(-2.0, color="0.4", ls=":", lw=1)
    axs[0].text(0.1, -2.0, "paper: ~2 %", va="bottom", fontsize=7.5, color="0.3")
    axs[0].legend(frameon=False, fontsize=7.5)
    ax = axs[5]
    x = np.arange(len(split_rows))
    names = [("backbone", "#4c72b0"), ("tendon_stretch", "#dd8452"), ("shape", "#55a868")]
    pos = np.zeros(len(x))
    neg = np.zeros(len(x))
    for attr, col in names:
        v = np.array([1e3 * getattr(sp, attr) for _, _, sp in split_rows])
        base = np.where(v >= 0, pos, neg)
        ax.bar(x, v, bottom=base, color=col, width=0.65, label=attr.replace("_", " "))
        pos += np.where(v >= 0, v, 0)
        neg += np.where(v < 0, v, 0)
    ax.plot(x, [1e3 * sp.virtual for _, _, sp in split_rows], "k_", ms=20, mew=2, label="virtual compression e")
    ax.set_xticks(x, [f"{fmt(d)} s\n(t={fmt(tk)} s)" for d, tk, _ in split_rows])
    ax.axhline(0, color="0.3", lw=0.7)
    ax.set_title("split of e at t = delay: e = dL - stretch + shape")
    ax.set_ylabel("[mm]")
    ax.set_xlabel("delay of wire 1 (instant; 0 s: end of move)")
    ax.legend(frameon=False, fontsize=7)
    fig.suptitle("Cojocaru wire delay: where the kinematic virtual compression goes")
    summary = ("Wire 1 starts late; e is the common offset of the commanded wire lengths from the nearest CC "
               "configuration (e < 0: the wires would have to compress the bone). " + " ".join(texts))
    return [ReportFigure("wire_delay_split", "Wire delay: virtual compression vs the physics", fig, summary)]


# --------------------------------------------------------------------------------------
# Hannan & Walker
# --------------------------------------------------------------------------------------
def _hannan_walker(study: Study, ok: pd.DataFrame) -> list[ReportFigure]:
    shapes = list(dict.fromkeys(ok["p.scenario.shape"]))
    models = list(study.models)
    fig = Figure(figsize=(5.0 * len(shapes) + 4.6, 5.6), layout="constrained")
    axs = fig.subplots(1, len(shapes) + 1)
    texts = []
    err_ax = axs[-1]
    for ax, shape in zip(axs, shapes):
        sub = ok[ok["p.scenario.shape"] == shape].sort_values("p.scenario.sample")
        r0 = sub.iloc[0]
        a = np.array([float(r0["p.scenario.start_x"]), float(r0["p.scenario.start_z"])])
        b = np.array([float(r0["p.scenario.end_x"]), float(r0["p.scenario.end_z"])])
        n = int(r0["p.scenario.n_samples"])
        ax.plot([a[0], b[0]], [a[1], b[1]], color="#ff7f0e", lw=2.5, alpha=0.6, label="commanded line")
        for mi, m in enumerate(models):
            sm = sub[sub["model"] == m]
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
            if ks:
                err_ax.plot(ks, 1e3 * np.array(errs), marker="o", color=model_color(m, models),
                            ls="-" if shape == shapes[0] else "--", label=f"{model_label(m)}, {shape}")
                texts.append(f"{shape}, {model_label(m)}: tip-to-line error {fmt(1e3 * min(errs))}-{fmt(1e3 * max(errs))} mm")
        ax.plot(0, 0, "ks", ms=6)
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("z [m]")
        ax.set_title(f"{shape}: snapshots 1-{n} (cf. paper Figs 7-12)" if shape == "line"
                     else f"{shape}: Eq 11 null-space towards q_d")
        ax.legend(frameon=False, fontsize=7.5, loc="lower left")
    err_ax.set_xlabel("sample along the line")
    err_ax.set_ylabel("|tip - line target| [mm]")
    err_ax.set_title("tracking error along the path")
    err_ax.legend(frameon=False, fontsize=7)
    fig.suptitle("Hannan & Walker trunk: CC plan replayed under gravity")
    summary = ("Backbone shapes of every path sample (the paper's six snapshots are photographs without "
               "numbers; these overlays are their model counterparts) and the tip's distance to the "
               "commanded line point.  The resolved-rate CC plan itself is on the line to the controller "
               "tolerance; the CC row is the CC tendon map read back from the jointed (Eq 1) cable commands, "
               "so its error is the CC-vs-jointed cable geometry mismatch, without gravity. " + "; ".join(texts) + ".")
    return [ReportFigure("hannan_walker_overlay", "Hannan & Walker: shapes along the line and tracking error", fig, summary)]


# --------------------------------------------------------------------------------------
# fruit harvester
# --------------------------------------------------------------------------------------
def _harvester(study: Study, ok: pd.DataFrame) -> list[ReportFigure]:
    lim = HARVESTER_LIMITS
    fig = Figure(figsize=(14.0, 4.8), layout="constrained")
    ax_env, ax_shape, ax_c = fig.subplots(1, 3)
    D = float(ok["p.robot.outer_diameter"].iloc[0]) if "p.robot.outer_diameter" in ok else 0.06
    s = np.linspace(lim["s_min"], lim["s_max"], 50)
    d_lo = np.full_like(s, 2.0 / lim["kappa_max"] - D)
    d_hi = 2.0 * s / lim["wrap_angle"] - D
    ax_env.fill_between(s * 1e3, 1e3 * d_lo, 1e3 * d_hi, color="#8da0cb", alpha=0.5, label="wrap grasp feasible")
    ax_env.axhline(100, color="k", ls=":", lw=1)
    ax_env.text(s[0] * 1e3, 101, "paper: objects up to 100 mm", fontsize=7.5, va="bottom")
    ax_env.set_xlabel("arc length s [mm]")
    ax_env.set_ylabel("object diameter d = 2/kappa - D [mm]")
    ax_env.set_title("centre-of-arc grasp envelope (assumed limits)")
    ax_env.legend(frameon=False, fontsize=7.5, loc="upper left")

    phys = [m for m in study.models if m != "cc"]
    bends = sorted(set(float(v) for v in ok["p.load.bend_angle"]))
    texts = []
    styles = ["-", "--", ":"]
    payloads = sorted(set(float(v) for v in ok["p.robot.payload_mass"]))
    cm = ["#fdae61", "#f46d43", "#d73027", "#a50026", "#67001f", "#313695"]
    bshow = bends[-1]
    for bi, bend in enumerate(bends):
        for m in phys:
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
                offs.append(np.linalg.norm(c_fit - c_cc))
                pls.append(pm)
                if bend == bshow:
                    col = cm[pi % len(cm)]
                    ax_shape.plot(bp[1][:, 0] * 1e3, bp[1][:, 2] * 1e3, color=col, label=f"{model_label(m)} {fmt(1e3 * pm)} g")
                    ax_shape.plot(c_fit[0] * 1e3, c_fit[1] * 1e3, "o", color=col, ms=5)
                    if pi == 0:
                        ax_shape.plot(bc[1][:, 0] * 1e3, bc[1][:, 2] * 1e3, "k--", lw=1.8, label="CC (any payload)")
                        ax_shape.plot(c_cc[0] * 1e3, c_cc[1] * 1e3, "kx", ms=9, mew=2, label="CC centre of arc")
            if pls:
                ax_c.plot(1e3 * np.array(pls), 1e3 * np.array(offs), marker="o", ls=styles[bi % 3],
                          color=model_color(m, study.models), label=f"{model_label(m)}, kappa s = {fmt(bend)} rad")
                texts.append(f"kappa s = {fmt(bend)} rad ({model_label(m)}): grasp centre {fmt(1e3 * offs[0])} mm off the "
                             f"CC centre without payload, {fmt(1e3 * offs[-1])} mm with {fmt(1e3 * pls[-1])} g")
    ax_shape.set_aspect("equal")
    ax_shape.set_xlabel("x [mm] (base frame)")
    ax_shape.set_ylabel("z [mm] (base frame; the base hangs, gravity along +z)")
    ax_shape.set_title(f"backbones and best-fit arc centres, kappa s = {fmt(bshow)} rad")
    ax_shape.legend(frameon=False, fontsize=6.5)
    ax_c.set_xlabel("payload [g]")
    ax_c.set_ylabel("|grasp centre - CC centre| [mm]")
    ax_c.set_title("grasp centre drift (best-fit arc of the backbone)")
    ax_c.legend(frameon=False, fontsize=7.5)
    fig.suptitle("Shao harvester: grasp envelope and payload sag")
    lo, hi = 1e3 * d_lo[-1], 1e3 * d_hi[-1]
    summary = (f"Envelope with the assumed limits s in [{fmt(1e3 * lim['s_min'])}, {fmt(1e3 * lim['s_max'])}] mm, "
               f"kappa <= {fmt(lim['kappa_max'])} 1/m, wrap angle >= {fmt(math.degrees(lim['wrap_angle']))} deg, "
               f"D = {fmt(1e3 * D)} mm: objects {fmt(lo)}-{fmt(hi)} mm at full length. Grasp centre = centre of the "
               f"least-squares circle through the backbone (x-z plane). " + "; ".join(texts) + ".")
    return [ReportFigure("harvester_grasp", "Fruit harvester: grasp envelope and grasp-centre drift under payload", fig, summary)]
