"""Report figures of the closed-loop study: open vs closed loop along the path and over the sweeps.

Registered as ``registry.FIGURES["closed_loop"]``: :func:`matches` picks studies whose cases ran
the ``closed_loop`` scenario.  Figures: the largest tracking error of every loop against the cable
stiffness (per plan shape and mounting, payload as line style); the error along the path and per
control step for the assumed robot; the backbones at the last sample of the worst open-loop case.
The first caption states question, findings and assumptions (:data:`ABOUT`).  Checked by
``tests/experiments/test_closed_loop.py`` and the regression tier's ``closed_loop`` study.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...assumptions import Assumption
from ...compare.table import array_cell, row_positions
from ...report.style import ReportFigure, fmt, model_color, model_label
from ..about import StudyAbout, about_summary, from_preset
from .worker import CLOSED_SUFFIX, PLAN

__all__ = ["ABOUT", "matches", "figures", "loop_table"]

ABOUT = StudyAbout(
    question=("is constant curvature (CC) good enough as a *controller* model where it is poor as a predictor? "
              "Hannan & Walker's resolved-rate / null-space controller (Eq 10-11, CC Jacobian) reads the physics "
              "tip at every control step and commands the cables; compared with the open-loop replay of its CC plan"),
    assumptions=(
        from_preset("hannan_walker", "joint_stiffness", "joint spring stiffness per section [N m/rad]"),
        from_preset("hannan_walker", "section_masses", "section masses [kg]"),
        from_preset("hannan_walker", "tendon_stiffness", "cable stiffness EA_t [N]", note="swept"),
        Assumption("robot.payload_mass", what="tip payload [kg]", source="swept"),
        Assumption("load.pretension", what="cable pretension [N]", source="assumed"),
        Assumption("scenario.gain", what="controller gain H1 of Eq 11", source="assumed (1 = full resolved-rate step)"),
        Assumption("scenario.steps_per_sample", what="control steps per path sample", source="assumed"),
        Assumption("scenario.noise", what="tip measurement noise, std per coordinate [m]", source="assumed, swept"),
        Assumption("", what="quasi-static plant: each control step is a static equilibrium (warm-started re-solve)",
                   source="modelling choice: the paper's controller is kinematic"),
    ),
    paper_rows=("Hannan & Walker Eq 10-11 (resolved-rate control with null-space task) run in the loop on the "
                "physics instead of open loop", "Sec. 5 line-tracking and grasp-approach experiments (Figs 7-12)"),
)


def matches(results) -> bool:
    """True for a study whose (first ok) cases ran the ``closed_loop`` scenario."""
    ok = results.ok
    return not ok.empty and "p.scenario.name" in ok and ok["p.scenario.name"].iloc[0] == "closed_loop"


def _loop_of(model: str) -> tuple[str, str]:
    if model == PLAN:
        return "plan", PLAN
    if model.endswith(CLOSED_SUFFIX):
        return "closed", model[: -len(CLOSED_SUFFIX)]
    return "open", model


def loop_table(ok: pd.DataFrame) -> pd.DataFrame:
    """One row per result row: loop (plan/open/closed), plant, the swept settings and its errors [m]."""
    rows = []
    for _, r in ok.iterrows():
        loop, plant = _loop_of(str(r["model"]))
        err = array_cell(r.get("series.tip_error"))
        rows.append({"model": r["model"], "loop": loop, "plant": plant, "shape": r["p.scenario.shape"],
                     "mount": r["p.robot.base_orientation"], "EA_t": float(r["p.robot.tendon_stiffness"]),
                     "payload": float(r["p.robot.payload_mass"]), "noise": float(r["p.scenario.noise"]),
                     "steps": int(r["p.scenario.steps_per_sample"]), "max_error": float(r["x.max_tracking_error"]),
                     "error": err, "step_error": array_cell(r.get("series.step_error")), "row": r})
    return pd.DataFrame(rows)


def _nominal(t: pd.DataFrame) -> pd.DataFrame:
    """Noise-free rows at the most control steps (the sweep's reference controller)."""
    return t[(t["noise"] == t["noise"].min()) & (t["steps"] == t["steps"].max())]


def _sweep_figure(t: pd.DataFrame, plants: list[str], models) -> Figure:
    nom = _nominal(t)
    panels = list(dict.fromkeys(zip(nom["shape"], nom["mount"])))
    fig = Figure(figsize=(4.4 * len(panels), 4.4), layout="constrained")
    axs = np.atleast_1d(fig.subplots(1, len(panels), sharey=True))
    styles = ["-", "--", ":", "-."]
    payloads = sorted(nom["payload"].unique())
    for ax, (shape, mount) in zip(axs, panels):
        sub = nom[(nom["shape"] == shape) & (nom["mount"] == mount) & (nom["loop"] != "plan")]
        for (model, pay), g in sub.groupby(["model", "payload"], sort=False):
            g = g.sort_values("EA_t")
            ax.plot(g["EA_t"], 1e3 * g["max_error"], marker="o" if model.endswith(CLOSED_SUFFIX) else "s",
                    color=model_color(model, models), ls=styles[payloads.index(pay) % len(styles)],
                    label=f"{model_label(model)}, payload {fmt(pay)} kg")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("cable stiffness EA_t [N]")
        ax.set_title(f"{shape}, {mount} mount", fontsize=9)
    axs[0].set_ylabel("largest |tip - target| along the path [mm]")
    axs[0].legend(frameon=False, fontsize=6.5)
    fig.suptitle("Open loop (CC plan replayed) vs closed loop (controller reads the physics tip)")
    return fig


def _path_figure(t: pd.DataFrame, models) -> tuple[Figure, str]:
    """Error along the path (every loop setting) and per control step, at the worst open-loop physics setting."""
    phys = t[(t["loop"] == "open") & (t["plant"] != "cc")]
    worst = phys.loc[phys["max_error"].idxmax()] if not phys.empty else t.iloc[0]
    keys = ["shape", "mount", "EA_t", "payload"]
    same = t[np.logical_and.reduce([t[k] == worst[k] for k in keys])]
    fig = Figure(figsize=(10.5, 4.2), layout="constrained")
    ax, ax2 = fig.subplots(1, 2)
    nominal = (same["noise"] == same["noise"].min()) & (same["steps"] == same["steps"].max())
    for _, r in same[(same["loop"] == "closed") | ((same["loop"] == "open") & nominal)].iterrows():
        if r["error"] is None:
            continue
        lab = f"{model_label(r['model'])}" + (f", noise {fmt(1e3 * r['noise'])} mm, {r['steps']} steps/sample"
                                            if r["loop"] == "closed" else "")
        ax.plot(np.arange(r["error"].size), np.maximum(1e3 * r["error"], 1e-6), marker="o",
                color=model_color(r["model"], models), ls="-" if r["loop"] == "closed" else "--",
                alpha=0.5 + 0.5 * (r["noise"] == 0), label=lab)
        if r["loop"] == "closed" and r["step_error"] is not None:
            ax2.plot(np.arange(1, r["step_error"].size + 1), np.maximum(1e3 * r["step_error"], 1e-9),
                     color=model_color(r["model"], models), alpha=0.5 + 0.5 * (r["noise"] == 0), label=lab)
    ax.set_yscale("log")
    ax.set_xlabel("path sample")
    ax.set_ylabel("|tip - target| at the sample's last step [mm]")
    ax.legend(frameon=False, fontsize=6.5)
    ax2.set_yscale("log")
    ax2.set_xlabel("control step (one plant solve each)")
    ax2.set_ylabel("|tip - current target| [mm]")
    what = (f"{worst['shape']}, {worst['mount']} mount, EA_t {fmt(worst['EA_t'])} N, payload {fmt(worst['payload'])} kg")
    fig.suptitle(f"Along the path and per control step: {what} (the worst open-loop case)")
    return fig, what


def _shape_figure(t: pd.DataFrame, what_keys: pd.Series, models) -> Figure:
    same = t[np.logical_and.reduce([t[k] == what_keys[k] for k in ["shape", "mount", "EA_t", "payload"]])]
    same = same[(same["noise"] == same["noise"].min()) & (same["steps"] == same["steps"].max())]
    fig = Figure(figsize=(5.2, 5.4), layout="constrained")
    ax = fig.subplots()
    for _, r in same.iterrows():
        bp = row_positions(r["row"].to_dict())
        if bp is not None:
            P = bp[1]
            ax.plot(P[:, 0], P[:, 2], color=model_color(r["model"], models), ls="--" if r["loop"] == "plan" else "-",
                    label=model_label(r["model"]))
    tgt = array_cell(same.iloc[0]["row"].get("series.target")).reshape(-1, 3)
    ax.plot(tgt[:, 0], tgt[:, 2], color="#ff7f0e", lw=2.5, alpha=0.6, label="commanded line")
    ax.plot(0, 0, "ks", ms=6)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m] (base frame)")
    ax.set_ylabel("z [m]")
    ax.legend(frameon=False, fontsize=7)
    return fig


def _findings(t: pd.DataFrame) -> list[str]:
    out = []
    nom = _nominal(t)
    for plant in [p for p in dict.fromkeys(nom["plant"]) if p != PLAN]:
        o, c = nom[(nom["plant"] == plant) & (nom["loop"] == "open")], nom[(nom["plant"] == plant) & (nom["loop"] == "closed")]
        if not o.empty and not c.empty:
            out.append(f"{model_label(plant)}: largest tracking error open loop {fmt(1e3 * o['max_error'].min())}-"
                       f"{fmt(1e3 * o['max_error'].max())} mm, closed loop {fmt(1e3 * c['max_error'].min())}-"
                       f"{fmt(1e3 * c['max_error'].max())} mm over the cable-stiffness, payload and mounting sweep "
                       f"({int(c['steps'].iloc[0])} control steps per sample, no noise)")
    cl = t[(t["loop"] == "closed") & (t["plant"] != "cc")]
    for (noise, steps), g in cl.groupby(["noise", "steps"]):
        out.append(f"closed loop with noise {fmt(1e3 * noise)} mm and {steps} step(s) per sample: largest error "
                   f"{fmt(1e3 * g['max_error'].min())}-{fmt(1e3 * g['max_error'].max())} mm")
    return out


def _contraction(step_error: np.ndarray | None, steps: int) -> float:
    """Median ratio of successive step errors within a sample (the loop's convergence factor per step)."""
    if step_error is None or steps < 2:
        return float("nan")
    e = step_error.reshape(-1, steps)
    r = e[:, 1:] / np.where(e[:, :-1] > 0, e[:, :-1], np.nan)
    r = r[np.isfinite(r) & (e[:, 1:] > 1e-12)]
    return float(np.median(r)) if r.size else float("nan")


def _path_text(t: pd.DataFrame, worst: pd.Series, what: str) -> str:
    same = t[np.logical_and.reduce([t[k] == worst[k] for k in ["shape", "mount", "EA_t", "payload"]])]
    parts = [f"{what}: open loop (dashed) {fmt(1e3 * worst['max_error'])} mm at worst along the path"]
    for _, r in same[(same["loop"] == "closed") & (same["plant"] == worst["plant"])].iterrows():
        txt = (f"closed loop, noise {fmt(1e3 * r['noise'])} mm, {r['steps']} step(s)/sample: largest "
               f"{fmt(1e3 * r['max_error'])} mm, last sample {fmt(1e3 * r['error'][-1])} mm")
        c = _contraction(r["step_error"], r["steps"])
        if np.isfinite(c) and r["noise"] == 0:
            txt += f", error shrinks by a median factor {fmt(c)} per control step"
        parts.append(txt)
    return "; ".join(parts) + "."


def _shape_text(t: pd.DataFrame, worst: pd.Series, what: str) -> str:
    same = t[np.logical_and.reduce([t[k] == worst[k] for k in ["shape", "mount", "EA_t", "payload"]])]
    same = same[(same["noise"] == same["noise"].min()) & (same["steps"] == same["steps"].max())]
    parts = []
    for _, r in same.iterrows():
        k = array_cell(r["row"].get("series.kappa"))
        ell = np.full(4, float(r["row"]["robot_length"]) / 4)
        if k is not None and k.size % 4 == 0:
            parts.append(f"{model_label(r['model'])} commands bend angles "
                         f"{', '.join(fmt(v) for v in k.reshape(-1, 4)[-1] * ell)} rad")
    return (f"{what}: the CC plan (dashed), the open-loop replay and the closed loop at the path's end (base frame "
            "x-z); the closed loop reaches the target by commanding other section bends than the plan: "
            + "; ".join(parts) + ".")


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The sweep summary, the path/step errors of the worst case and its backbones (see module docstring)."""
    ok = results.ok
    models = list(results.models)
    t = loop_table(ok)
    plants = [p for p in dict.fromkeys(t["plant"]) if p != PLAN]
    out = [ReportFigure("closed_loop_sweep", "Closed loop vs open loop: tracking error over the sweeps",
                        _sweep_figure(t, plants, models), about_summary(ABOUT, ok, _findings(t)))]
    worst = t[(t["loop"] == "open") & (t["plant"] != "cc")]
    worst = worst.loc[worst["max_error"].idxmax()] if not worst.empty else t.iloc[0]
    fig, what = _path_figure(t, models)
    out.append(ReportFigure("closed_loop_path", "Tracking error along the path and per control step", fig,
                            _path_text(t, worst, what)))
    out.append(ReportFigure("closed_loop_shapes", "Backbones at the last sample of the worst open-loop case",
                            _shape_figure(t, worst, models), _shape_text(t, worst, what)))
    return out
