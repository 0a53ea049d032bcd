"""Report figure of the wire-delay study: where the kinematic virtual compression goes.

Registered as ``registry.FIGURES["wire_delay"]``: :func:`matches` picks studies whose cases ran
the ``wire_delay`` scenario, :func:`figures` draws one figure from the first physics model's
rows.  The commanded wire lengths and their CC reading are recomputed from the stored case
parameters with the functions the run used (:mod:`.analysis`).  Checked by the report tier of
``tests/regression`` (the ``wire_delay`` study's ``report.html``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...compare.metrics import compression_split
from ...compare.table import array_cell
from ...report.style import ReportFigure, fmt, model_label
from ...study.params import section_params
from .analysis import cc_reading, commanded_wire_lengths, wire_geometry

__all__ = ["matches", "figures"]

_COLORS = ["#1b9e77", "#7570b3", "#d95f02", "#e7298a", "#66a61e", "#e6ab02"]


def matches(results) -> bool:
    """True for a study whose (first ok) cases ran the ``wire_delay`` scenario."""
    ok = results.ok
    return not ok.empty and "p.scenario.name" in ok and ok["p.scenario.name"].iloc[0] == "wire_delay"


def robot_and_load(row: Mapping[str, Any]):
    """The robot, the load case and the scenario parameters a stored row ran with."""
    from ...study.build import build_load, build_robot
    from ...study.scenarios import load_with_scenario

    robot = build_robot(section_params(row, "robot"), section_params(row, "derived"))
    scen = section_params(row, "scenario")
    load = load_with_scenario(robot, section_params(row, "load"), scen or None)
    return robot, build_load(robot, load), scen


@dataclass(frozen=True, eq=False)
class _Run:
    """The time series of one stored wire-delay case, as plotted (SI units)."""

    delay: float
    H: float
    t: np.ndarray
    e: np.ndarray
    dl: np.ndarray
    stretch: np.ndarray
    tensions: np.ndarray
    tip_error: np.ndarray
    twist: np.ndarray | None
    t_star: float


def _run_of_row(r: Mapping[str, Any]) -> _Run:
    robot, load, scen = robot_and_load(r)
    t = array_cell(r["time"])
    n_t = robot.n_tendons
    cc = cc_reading(commanded_wire_lengths(robot, load.actuation, t, load.ramp_time), wire_geometry(robot))
    tip = array_cell(r["series.tip_position"]).reshape(t.size, 3)
    delay = float(r["p.scenario.delay"])
    # the instant the late wire starts (e is extreme from then until the others stop);
    # without delay the end of the move
    t_star = min(delay, float(scen.get("move_time", load.ramp_time))) if delay > 0 else float(load.ramp_time)
    return _Run(
        delay=delay, H=robot.sections[0].length, t=t, e=cc.virtual_compression,
        dl=array_cell(r["series.length_change"]),
        stretch=array_cell(r["series.tendon_stretch"]).reshape(t.size, n_t),
        tensions=array_cell(r["series.tendon_tensions"]).reshape(t.size, n_t),
        tip_error=np.linalg.norm(tip - cc.tip, axis=1), twist=array_cell(r.get("series.tip_twist")), t_star=t_star,
    )


def _plot_run(axs, run: _Run, color: str) -> None:
    t, H = run.t, run.H
    lab = f"delay {fmt(run.delay)} s"
    axs[0].plot(t, 100 * run.e / H, color=color, label=lab)
    axs[1].plot(t, 100 * run.dl / H, color=color, label=lab)
    axs[2].plot(t, 1e3 * run.stretch.mean(axis=1), color=color, label=lab)
    axs[3].plot(t, 1e3 * run.tip_error, color=color, label=lab)
    if run.twist is not None and run.twist.size == t.size:
        axs[4].plot(t, np.degrees(run.twist), color=color, label=lab)


def _split_at_start(run: _Run):
    """``(delay, t_k, split, sentence)`` at the sample nearest the late wire's start."""
    t, e, dl, st, err, H = run.t, run.e, run.dl, run.stretch, run.tip_error, run.H
    k = int(np.argmin(np.abs(t - run.t_star)))
    sp = compression_split(e[k], dl[k], st[k].mean())
    text = (
        f"delay {fmt(run.delay)} s: virtual compression {fmt(1e3 * e[k])} mm ({fmt(100 * e[k] / H)} % of H) "
        f"at t = {fmt(t[k])} s (min over time {fmt(100 * e.min() / H)} %); there the beam's backbone changes by {fmt(1e3 * dl[k])} mm "
        f"({fmt(100 * dl[k] / H)} % of H), the wires stretch by {fmt(1e3 * st[k].mean())} mm on average "
        f"(max tension {fmt(run.tensions[k].max())} N), and the shape leaves the CC family by "
        f"{fmt(1e3 * sp.shape)} mm (tip {fmt(1e3 * err[k])} mm off the CC tip; peak tip error "
        f"{fmt(1e3 * err.max())} mm at t = {fmt(t[int(np.argmax(err))])} s, final {fmt(1e3 * err[-1])} mm)."
    )
    return run.delay, t[k], sp, text


def _label_time_axes(axs, m: str) -> None:
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


def _split_panel(ax, split_rows) -> None:
    """Stacked bars: backbone + tendon stretch + shape = e, one bar per delay."""
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


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """Cojocaru Fig 7 (:mod:`.fig7`), then the wire-delay figure of the first physics model with time series."""
    from .fig7 import wire_lengths_figure

    ok = results.ok
    fig7 = [wire_lengths_figure(ok.iloc[0].to_dict())] if not ok.empty else []
    phys = [m for m in results.models if m != "cc"]
    if not phys:
        return fig7
    m = phys[0]
    rows = ok[(ok["model"] == m) & ok["time"].map(lambda v: array_cell(v) is not None)]
    if rows.empty:
        return fig7
    rows = rows.sort_values("p.scenario.delay")
    fig = Figure(figsize=(12.5, 7.2), layout="constrained")
    axs = fig.subplots(2, 3).ravel()
    texts, split_rows = [], []
    for i, (_, r) in enumerate(rows.iterrows()):
        run = _run_of_row(r.to_dict())
        _plot_run(axs, run, _COLORS[i % len(_COLORS)])
        delay, tk, sp, text = _split_at_start(run)
        split_rows.append((delay, tk, sp))
        texts.append(text)
    _label_time_axes(axs, m)
    _split_panel(axs[5], split_rows)
    fig.suptitle("Cojocaru wire delay: where the kinematic virtual compression goes")
    summary = ("Wire 1 starts late; e is the common offset of the commanded wire lengths from the nearest CC "
               "configuration (e < 0: the wires would have to compress the bone). " + " ".join(texts))
    return fig7 + [ReportFigure("wire_delay_split", "Wire delay: virtual compression vs the physics", fig, summary,
                                cases=tuple(map(str, rows["case_id"])))]
