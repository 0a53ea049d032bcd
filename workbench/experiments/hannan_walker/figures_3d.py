"""Report figures of the 32-DOF Hannan & Walker study: spatial shapes and the tracking error.

Registered as ``registry.FIGURES["hannan_walker_3d"]``: :func:`matches` picks studies whose cases
ran the ``hannan_walker_spatial`` scenario; :func:`figures` draws the backbones of every path
sample in 3-D (one panel per plan shape and gravity case, base frame) and the tip-to-line error
of every model along the line.  The first figure's caption states the study's question, findings
and assumptions (:data:`ABOUT`).  Checked by ``tests/experiments/test_hannan_walker_3d.py`` and the
report tier of ``tests/regression`` (the ``hannan_walker_3d`` study's ``report.html``).
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...assumptions import Assumption
from ...compare.table import row_positions
from ...report.style import ReportFigure, fmt, model_color, model_label
from ...robot.orientation import base_rotation_for
from ..about import StudyAbout, about_summary

__all__ = ["ABOUT", "matches", "figures", "gravity_label"]

ABOUT = StudyAbout(
    question=("does the constant-curvature plan of a spatial tip line survive the robot Hannan & Walker built -- "
              "16 two-DOF joints, 16 cables, the paper's planar cable geometry (Eq 1) applied per cable plane -- "
              "under gravity in any direction?"),
    assumptions=(
        Assumption("robot.joint_stiffness", what="joint spring stiffness per section [N m/rad]",
                   source="assumed, preset hannan_walker: the paper gives none"),
        Assumption("robot.section_masses", what="section masses [kg]", source="assumed, preset hannan_walker"),
        Assumption("robot.tendon_stiffness", what="cable stiffness EA_t [N]", source="assumed: ~1 mm steel wire"),
        Assumption("load.pretension", what="cable pretension [N]", source="assumed: keeps antagonists taut"),
        Assumption("", what="two-DOF joints as Cardan joints Rx(a) Ry(b), torsion locked, equal springs on both axes",
                   source="modelling choice: the paper says 'two-DOF joints' without their kinematics"),
        Assumption("", what="Eq 1 per cable plane, equal joint angles per section and plane (Eq 2-3)",
                   source="the paper's planar cable map extended plane by plane"),
    ),
    paper_rows=("Hannan & Walker Sec. 3: the 32-DOF, 16-cable robot (16 two-DOF joints, two antagonistic cable "
                "pairs per section, 90 deg apart)", "Eq 1-3 applied per plane", "Eq 10-11 spatial resolved-rate plan"),
)


def matches(results) -> bool:
    """True for a study whose (first ok) cases ran the ``hannan_walker_spatial`` scenario."""
    ok = results.ok
    return (not ok.empty and "p.scenario.name" in ok
            and ok["p.scenario.name"].iloc[0] == "hannan_walker_spatial")


def gravity_label(row) -> str:
    """Gravity of a row in the base frame, e.g. ``"g along base (-1, 0, 0)"`` (``"no gravity"`` at 0)."""
    g = float(row.get("p.robot.gravity", 0.0))
    if not g > 0:
        return "no gravity"
    d = row.get("p.robot.gravity_direction", "[0, 0, -1]")
    d = np.asarray(json.loads(d) if isinstance(d, str) else d, dtype=float)
    R = np.asarray(base_rotation_for(str(row.get("p.robot.base_orientation", "vertical"))))
    b = R.T @ (d / np.linalg.norm(d))
    return "g along base (" + ", ".join(f"{v:.2g}" if abs(v) > 1e-12 else "0" for v in b) + ")"


def _with_labels(ok: pd.DataFrame) -> pd.DataFrame:
    ok = ok.copy()
    ok["_gravity"] = [gravity_label(r) for _, r in ok.iterrows()]
    return ok


def _target(r) -> np.ndarray:
    a = np.array([float(r[f"p.scenario.start_{c}"]) for c in "xyz"])
    b = np.array([float(r[f"p.scenario.end_{c}"]) for c in "xyz"])
    n = int(r["p.scenario.n_samples"])
    return a + (b - a) * int(r["p.scenario.sample"]) / (n - 1)


def _shape_panel(ax, sub: pd.DataFrame, models) -> None:
    r0 = sub.iloc[0]
    a = np.array([float(r0[f"p.scenario.start_{c}"]) for c in "xyz"])
    b = np.array([float(r0[f"p.scenario.end_{c}"]) for c in "xyz"])
    ax.plot(*np.stack([a, b]).T, color="#ff7f0e", lw=2.5, alpha=0.6, label="commanded line")
    for m in models:
        for j, (_, r) in enumerate(sub[sub["model"] == m].iterrows()):
            bp = row_positions(r.to_dict())
            if bp is not None:
                P = bp[1]
                ax.plot(P[:, 0], P[:, 1], P[:, 2], color=model_color(m, models), lw=1.0 if m != "cc" else 1.6,
                        ls="--" if m == "cc" else "-", alpha=0.85, label=model_label(m) if j == 0 else None)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")


def _errors(ok: pd.DataFrame) -> pd.DataFrame:
    """Tip-to-line error [m] and |tip twist| per ok row."""
    rows = []
    for _, r in ok.iterrows():
        tip = np.array([float(r["tip_x"]), float(r["tip_y"]), float(r["tip_z"])])
        rows.append({"model": r["model"], "shape": r["p.scenario.shape"], "gravity": r["_gravity"],
                     "sample": int(r["p.scenario.sample"]), "error": float(np.linalg.norm(tip - _target(r))),
                     "twist": abs(float(r.get("tip_twist", np.nan)))})
    return pd.DataFrame(rows)


def _findings(err: pd.DataFrame) -> list[str]:
    out = []
    for (shape, grav, m), g in err.groupby(["shape", "gravity", "model"], sort=False):
        txt = f"{shape}, {grav}, {model_label(m)}: tip-to-line error {fmt(1e3 * g['error'].min())}-{fmt(1e3 * g['error'].max())} mm"
        if m != "cc" and np.isfinite(g["twist"]).any():
            txt += f", tip twist up to {fmt(g['twist'].max())} rad"
        out.append(txt)
    return out


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """3-D backbones per plan shape and gravity case, and the tracking error along the line."""
    ok = _with_labels(results.ok)
    models = list(results.models)
    shapes = list(dict.fromkeys(ok["p.scenario.shape"]))
    gravs = list(dict.fromkeys(ok["_gravity"]))
    fig = Figure(figsize=(4.2 * len(gravs), 4.0 * len(shapes)), layout="constrained")
    for i, shape in enumerate(shapes):
        for j, grav in enumerate(gravs):
            ax = fig.add_subplot(len(shapes), len(gravs), i * len(gravs) + j + 1, projection="3d")
            sub = ok[(ok["p.scenario.shape"] == shape) & (ok["_gravity"] == grav)].sort_values("p.scenario.sample")
            if not sub.empty:
                _shape_panel(ax, sub, models)
            ax.set_title(f"{shape}, {grav}", fontsize=9)
            if i == 0 and j == 0:
                ax.legend(frameon=False, fontsize=7, loc="upper left")
    fig.suptitle("32-DOF Hannan & Walker trunk: spatial CC plan and the two-DOF-joint chain (base frame)")
    err = _errors(ok)
    summary = about_summary(ABOUT, ok, _findings(err))
    out = [ReportFigure("hannan_walker_3d_shapes", "32-DOF trunk: backbones along the spatial line", fig, summary)]
    fig2 = Figure(figsize=(5.0 * len(shapes), 4.2), layout="constrained")
    axs = np.atleast_1d(fig2.subplots(1, len(shapes)))
    styles = ["-", "--", ":", "-."]
    for ax, shape in zip(axs, shapes):
        for (m, grav), g in err[err["shape"] == shape].groupby(["model", "gravity"], sort=False):
            g = g.sort_values("sample")
            ax.plot(g["sample"], 1e3 * g["error"], marker="o", color=model_color(m, models),
                    ls=styles[gravs.index(grav) % len(styles)], label=f"{model_label(m)}, {grav}")
        ax.set_xlabel("sample along the line")
        ax.set_ylabel("|tip - line target| [mm]")
        ax.set_title(shape)
        ax.legend(frameon=False, fontsize=6.5)
    text = ("Distance of each model's tip from the commanded line point (base frame).  The CC row reads the cable "
            "commands back through the CC tendon map, so its error is the mismatch between Eq 1 per plane and CC "
            "tendon geometry; the two-DOF-joint chain adds the joint springs, finite cable stiffness, gravity and the "
            "Cardan coupling of oblique bends that Eq 1 per plane ignores.")
    out.append(ReportFigure("hannan_walker_3d_error", "32-DOF trunk: tracking error along the line", fig2, text))
    return out
