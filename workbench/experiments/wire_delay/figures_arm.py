"""Report figures of Cojocaru's whole arm: section 1 moves, the upper sections are passive.

Registered as ``registry.FIGURES["wire_delay_arm"]``: :func:`matches` picks studies whose cases ran
the ``wire_delay_arm`` scenario.  Reference of every comparison: the *decoupled target* -- what the
paper's decoupled kinematics expects, section 1 on the CC arc its commanded wires give
(:func:`.analysis.cc_reading`) and the upper sections straight along its end tangent
(:func:`decoupled_target_tip`).  Figures: the final backbones per passive mode and delay; the tip's
distance from the decoupled target and the largest upper-wire tension over time.  The first caption
states question, findings and assumptions (:data:`ABOUT`).  Checked by
``tests/experiments/test_wire_delay_arm.py``.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...assumptions import Assumption
from ...compare.table import array_cell
from ...kinematics import forward_kinematics
from ...report.style import ReportFigure, fmt, model_label
from ..about import StudyAbout, about_summary
from .analysis import cc_reading, commanded_wire_lengths, wire_geometry
from .figures import robot_and_load

__all__ = ["ABOUT", "matches", "figures", "decoupled_target_tip", "upper_bend_angle"]

ABOUT = StudyAbout(
    question=("what does the paper's decoupled control do to Cojocaru's whole arm (three tronconic sections, > 1 m, "
              "all wires from the base) when section 1 makes the Sec. 5.1 wire move -- with and without the 3 s "
              "delay -- and the two upper sections are passive, i.e. their motors hold, compensate or release the "
              "wires that run through the bending section 1?"),
    assumptions=(
        Assumption("robot.section_length", what="section length H [m]",
                   source="assumed: 3 x 0.35 m (the paper: 'more than one meter')"),
        Assumption("robot.rod_diameter", what="steel backbone rod diameter [m]",
                   source="assumed, preset cojocaru_tronconic"),
        Assumption("robot.base_disk_diameter", what="disk diameter at the base [m]", source="assumed, preset"),
        Assumption("robot.disk_diameter_step", what="disk diameter step per section [m]", source="assumed, preset"),
        Assumption("robot.wire_diameter", what="steel wire diameter [m]", source="assumed, preset"),
        Assumption("robot.gravity", what="gravity [m/s^2]", source="as the paper's kinematic experiment"),
        Assumption("scenario.move_time", what="duration of every wire's move [s]",
                   source="assumed (the paper gives none)"),
        Assumption("load.pretension", what="wire pretension [N]", source="assumed"),
        Assumption("scenario.passive", what="what the upper motors do",
                   source="swept: the paper's decoupled command is 'held'"),
    ),
    paper_rows=("Cojocaru et al. Sec. 5.2: the three-segment arm of more than one meter",
                "Sec. 3: 'the three segments are controlled separately, without considering the interaction between "
                "them' and Sec. 5.4: 'we did not consider the errors introduced by the interaction between the segments'",
                "Sec. 5.1: the 3 s wire delay"),
)


def matches(results) -> bool:
    """True for a study whose (first ok) cases ran the ``wire_delay_arm`` scenario."""
    ok = results.ok
    return not ok.empty and "p.scenario.name" in ok and ok["p.scenario.name"].iloc[0] == "wire_delay_arm"


def decoupled_target_tip(robot, theta, phi) -> np.ndarray:
    """Tip ``(..., 3)`` [m] of section 1 on the arc ``(theta, phi)`` and the upper sections straight."""
    ell = np.asarray(robot.section_lengths, dtype=float)
    th = np.asarray(theta, dtype=float)
    k = np.zeros(th.shape + (ell.size,))
    k[..., 0] = th / ell[0]
    f = np.zeros_like(k)
    f[..., 0] = np.asarray(phi, dtype=float)
    return forward_kinematics(k, f, np.broadcast_to(ell, k.shape))[..., :3, 3]


def upper_bend_angle(row: Mapping[str, Any]) -> float:
    """Angle between the backbone tangent at the end of section 1 and the tip tangent [rad] (0: straight upper sections)."""
    P = np.asarray(row["positions"], dtype=float).reshape(-1, 3)
    s = np.asarray(row["stations"], dtype=float)
    H = float(row["p.robot.section_length"])
    i = int(np.argmin(np.abs(s - H)))
    t1 = P[min(i + 1, len(P) - 1)] - P[max(i - 1, 0)]
    t2 = np.asarray(row["tip_frame"], dtype=float).reshape(4, 4)[:3, 2]
    c = float(np.dot(t1, t2) / (np.linalg.norm(t1) * np.linalg.norm(t2)))
    return float(np.arccos(np.clip(c, -1.0, 1.0)))


def _case_series(r: Mapping[str, Any]) -> dict[str, np.ndarray]:
    """Time, tip distance from the decoupled target, largest upper-wire tension of one stored row."""
    robot, load, _ = robot_and_load(r)
    t = array_cell(r.get("time"))
    tips = array_cell(r.get("series.tip_position"))
    if t is None or tips is None:
        return {}
    geo = wire_geometry(robot)
    cc = cc_reading(commanded_wire_lengths(robot, _first_section(load.actuation), t, load.ramp_time), geo)
    target = decoupled_target_tip(robot, cc.theta, cc.phi)
    out = {"t": t, "tip_error": np.linalg.norm(tips.reshape(-1, 3) - target, axis=1)}
    T = array_cell(r.get("series.tendon_tensions"))
    if T is not None and np.isfinite(T).any():
        out["upper_tension"] = T.reshape(t.size, -1)[:, 3:].max(axis=1)
    return out


def _first_section(act):
    from dataclasses import replace

    n = 3
    return replace(act, values=act.values[:n], start_times=None if act.start_times is None else act.start_times[:n],
                   ramp_durations=None if act.ramp_durations is None else act.ramp_durations[:n])


def _cases(ok: pd.DataFrame) -> list[tuple[str, float]]:
    return list(dict.fromkeys(zip(ok["p.scenario.passive"], ok["p.scenario.delay"].astype(float))))


def _findings(ok: pd.DataFrame, series: dict) -> list[str]:
    out = []
    for (passive, delay) in _cases(ok):
        g = ok[(ok["p.scenario.passive"] == passive) & (ok["p.scenario.delay"].astype(float) == delay)]
        for _, r in g.iterrows():
            s = series.get((r["case_id"], r["model"]), {})
            txt = (f"{passive}, delay {fmt(delay)} s, {model_label(r['model'])}: upper sections bent by "
                   f"{fmt(np.degrees(upper_bend_angle(r)))} deg at the end")
            if "tip_error" in s:
                txt += (f", tip off the decoupled target by up to {fmt(1e3 * s['tip_error'].max())} mm "
                        f"({fmt(1e3 * s['tip_error'][-1])} mm at the end)")
            if "upper_tension" in s:
                txt += f", upper wires up to {fmt(s['upper_tension'].max())} N"
            if passive == "slack" and r["model"] == "cc":
                txt += " (CC has no slack wire: it reads the paid-out length as a bend, not a prediction)"
            out.append(txt)
    return out


def _shape_panels(ok: pd.DataFrame, cases, models, fig) -> None:
    axs = fig.subplots(1, len(cases), squeeze=False)[0]
    styles = {"cc": "--", "beam3d": "-"}
    for ax, (passive, delay) in zip(axs, cases):
        g = ok[(ok["p.scenario.passive"] == passive) & (ok["p.scenario.delay"].astype(float) == delay)]
        for _, r in g.iterrows():
            P = np.asarray(r["positions"], dtype=float).reshape(-1, 3)
            rad = np.hypot(P[:, 0], P[:, 1]) * np.sign(P[:, 0] + P[:, 1] + 1e-300)
            ax.plot(rad, P[:, 2], ls=styles.get(r["model"], "-"), label=model_label(r["model"]))
        if not g.empty:
            robot, load, sc = robot_and_load(g.iloc[0])
            tip = decoupled_target_tip(robot, float(sc["theta"]), float(sc["alpha"]) + np.pi)
            ax.plot(np.hypot(tip[0], tip[1]) * np.sign(tip[0] + tip[1]), tip[2], "k*", ms=10, label="decoupled target tip")
        ax.set_title(f"{passive}, delay {fmt(delay)} s", fontsize=9)
        ax.set_xlabel("distance from the base axis [m] (signed)")
        ax.set_aspect("equal")
    axs[0].set_ylabel("z [m]")
    axs[0].legend(frameon=False, fontsize=7)


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """Final backbones per case, and tip error / upper-wire tension over time (see the module docstring)."""
    ok = results.ok
    models = list(results.models)
    cases = _cases(ok)
    series = {(r["case_id"], r["model"]): _case_series(r) for _, r in ok.iterrows()}
    fig = Figure(figsize=(3.2 * len(cases) + 1.0, 4.8), layout="constrained")
    _shape_panels(ok, cases, models, fig)
    fig.suptitle("Cojocaru's arm at the end of the move: section 1 bent to (45 deg, 45 deg), upper sections passive")
    out = [ReportFigure("wire_delay_arm_shapes", "Whole arm: final backbones per passive mode and delay", fig,
                        about_summary(ABOUT, ok, _findings(ok, series)))]
    fig2 = Figure(figsize=(10.5, 4.2), layout="constrained")
    ax, ax2 = fig2.subplots(1, 2)
    for (cid, m), s in series.items():
        if not s:
            continue
        r = ok[(ok["case_id"] == cid) & (ok["model"] == m)].iloc[0]
        lab = f"{model_label(m)}, {r['p.scenario.passive']}, delay {fmt(float(r['p.scenario.delay']))} s"
        ax.plot(s["t"], 1e3 * s["tip_error"], ls="--" if m == "cc" else "-", label=lab)
        if "upper_tension" in s:
            ax2.plot(s["t"], s["upper_tension"], label=lab)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("|tip - decoupled target tip| [mm]")
    ax.legend(frameon=False, fontsize=6.5)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("largest upper-section wire tension [N]")
    ax2.legend(frameon=False, fontsize=6.5)
    text = ("Tip distance from the decoupled target (section 1 on the CC arc of its commanded wires, the upper "
            "sections straight) and the largest tension in the upper sections' wires, over the move.  The CC row "
            "reads all nine commanded wire lengths through the CC tendon map, i.e. what kinematics alone says the "
            "passive commands do to the upper sections.")
    out.append(ReportFigure("wire_delay_arm_time", "Whole arm: tip error and upper-wire tension over time", fig2, text))
    return out
