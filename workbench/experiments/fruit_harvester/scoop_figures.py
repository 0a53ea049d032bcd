"""Report figures of the ``harvester_scoop`` studies: fluidic vs tendon section, fruit in the scoop vs tip mass.

Registered as ``registry.FIGURES["fruit_harvester_scoop"]``: :func:`matches` picks results of the
``harvester_scoop`` scenario; :func:`figures` draws

1. the scoops: CC arc (fluidic: lengthened by the chambers) and the physical section with the fruit
   released into it, per actuation, at the heaviest fruit;
2. the grasp centre (Shao's centre of arc, Eq 2) against the payload: how far the physical grasp
   centre (the fruit's centre, or the backbone's best-fit circle for a tip mass) lies from the CC
   centre, before and after the grasp-centre controller (x and z separately: the centre-of-arc
   Jacobian has no z row);
3. the section's length change: chambers lengthen, tendons shorten (CC and physics);
4. the controller's error history.

Frames: base frame (x, z); the harvester hangs, so base +z points down in the world.  Checked by
``tests/experiments/test_fruit_harvester_scoop.py`` (the report of a small study builds).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...compare.table import array_cell, row_positions
from ...report.style import ReportFigure, fmt
from ...report.headline import baseline_cases
from ..about import assumption_values
from .scoop_findings import findings
from .scoop_notes import ABOUT

__all__ = ["matches", "figures"]

_ACT = {"fluidic": "#1f77b4", "tendon": "#d62728"}
_PAY = {"object": "-", "tip": "--"}


def matches(results) -> bool:
    """True for results of the ``harvester_scoop`` scenario."""
    ok = results.ok
    return not ok.empty and "p.scenario.name" in ok and ok["p.scenario.name"].iloc[0] == "harvester_scoop"


def _f(row, key, default=np.nan) -> float:
    try:
        return float(row.get(key, default))
    except (TypeError, ValueError):
        return default


def _mass(row) -> float:
    return _f(row, "p.scenario.object_mass") if row.get("p.scenario.payload") == "object" else _f(row, "p.robot.payload_mass")


def _pairs(ok: pd.DataFrame):
    out = []
    for _, g in ok.groupby("case_id", sort=False):
        cc, ph = g[g["model"] == "cc"], g[g["model"] == "contact"]
        if len(cc) and len(ph):
            out.append((cc.iloc[0], ph.iloc[0]))
    return out


def _bar(row, key) -> float:
    """Error bar [same unit as ``key``]: mesh (``x.disc_*``) + contact penalty (``x.pen_*``); NaN when an
    estimate run failed (``x.disc_failed`` / ``x.pen_failed``) or none was made."""
    if _f(row, "x.disc_failed", 0.0) > 0 or _f(row, "x.pen_failed", 0.0) > 0:
        return np.nan
    d, p = _f(row, f"x.disc_{key}"), _f(row, f"x.pen_{key}", 0.0)
    return d + p if np.isfinite(d) else np.nan


def _circle(ax, c, r, **kw):
    t = np.linspace(0, 2 * np.pi, 121)
    ax.plot(1e3 * (c[0] + r * np.cos(t)), 1e3 * (c[1] + r * np.sin(t)), **kw)


def _shapes_figure(pairs) -> ReportFigure | None:
    obj = [p for p in pairs if p[0].get("p.scenario.payload") == "object"]
    if not obj:
        return None
    heaviest = max(_mass(c) for c, _ in obj)
    sel = sorted((p for p in obj if _mass(p[0]) == heaviest), key=lambda p: str(p[0]["p.scenario.actuation"]))
    fig = Figure(figsize=(max(9.0, 4.8 * len(sel)), 5.0), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(sel)))
    texts = []
    for ax, (cc, ph) in zip(axes, sel):
        act = str(cc["p.scenario.actuation"])
        _, pc = row_positions(cc.to_dict())
        _, pp = row_positions(ph.to_dict())
        r = 0.5 * _f(cc, "p.scenario.object_diameter")
        c0 = np.array([_f(cc, "x.object_x"), _f(cc, "x.object_z")])
        ax.plot(1e3 * pc[:, 0], 1e3 * pc[:, 2], "k--", label="CC arc")
        ax.plot(1e3 * pp[:, 0], 1e3 * pp[:, 2], color=_ACT.get(act, "C0"), lw=2, label="physics")
        ax.plot(1e3 * c0[0], 1e3 * c0[1], "kx", ms=9, mew=2, label="CC grasp centre")
        if _f(ph, "x.held", 0.0) > 0:
            c1 = c0 + np.array([_f(ph, "x.settle_dx"), _f(ph, "x.settle_dz")])
            _circle(ax, c1, r, color="#2ca02c", lw=1.4, label=f"fruit ({fmt(1e3 * heaviest)} g), settled")
            texts.append(f"{act}: the {fmt(1e3 * heaviest)} g fruit settles {fmt(1e3 * np.hypot(*(c1 - c0)))} mm "
                         f"from the CC grasp centre")
        ax.plot(0, 0, "ks", ms=5)
        ax.invert_yaxis()
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm] (base frame)")
        ax.set_ylabel("z [mm] (base frame; down in the world)")
        ax.set_title(f"{act} actuation, bend {fmt(np.degrees(_f(cc, 'x.wrap_angle')))} deg, "
                     f"CC arc length {fmt(1e3 * (_f(cc, 'robot_length') + _f(cc, 'length_change')))} mm", fontsize=9)
        ax.legend(frameon=False, fontsize=7)
    fig.suptitle("Shao harvester: the fruit in the scoop (CC arc vs physics, gravity)")
    summary = (f"Question: {ABOUT.question} Findings: " + "; ".join(findings(pairs)) + ". Answers: "
               + "; ".join(ABOUT.paper_rows) + ". " + "; ".join(texts) + ". Assumptions: "
               + "; ".join(assumption_values(ABOUT, pd.DataFrame())) + ".")
    return ReportFigure("scoop_shapes", "Harvester scoop: CC arc vs physics with the fruit", fig, summary)


def _centre_figure(pairs) -> ReportFigure:
    fig = Figure(figsize=(12.0, 4.4), layout="constrained")
    ax0, ax1 = fig.subplots(1, 2)
    texts = []
    for act in sorted({str(c["p.scenario.actuation"]) for c, _ in pairs}):
        for pay in ("object", "tip"):
            sub = sorted(((c, p) for c, p in pairs if c["p.scenario.actuation"] == act and c["p.scenario.payload"] == pay),
                         key=lambda t: _mass(t[0]))
            if not sub:
                continue
            m = 1e3 * np.array([_mass(c) for c, _ in sub])
            e0 = 1e3 * np.array([_f(p, "x.grasp_centre_error_initial") for _, p in sub])
            ex = 1e3 * np.abs([_f(p, "x.grasp_centre_error_x") for _, p in sub])
            ez = 1e3 * np.abs([_f(p, "x.grasp_centre_error_z") for _, p in sub])
            b0, bx, bz = (1e3 * np.array([_bar(p, k) for _, p in sub]) for k in
                          ("grasp_centre_error_initial", "grasp_centre_error_x", "grasp_centre_error_z"))
            col, ls = _ACT.get(act, "C0"), _PAY[pay]
            ax0.errorbar(m, e0, yerr=np.nan_to_num(b0), color=col, ls=ls, marker="o", capsize=3, label=f"{act}, {pay}")
            ax1.errorbar(m, ex, yerr=np.nan_to_num(bx), color=col, ls=ls, marker="s", ms=4, capsize=3,
                         label=f"{act}, {pay}: |x|")
            ax1.errorbar(m, ez, yerr=np.nan_to_num(bz), color=col, ls=ls, marker="^", ms=4, capsize=3, alpha=0.6,
                         label=f"{act}, {pay}: |z|")
            if np.all(np.isfinite(e0)):
                texts.append(f"{act}, {pay}: {fmt(e0.min())}-{fmt(e0.max())} mm off the CC centre (error bar up to "
                             f"{fmt(np.nanmax(b0) if np.isfinite(b0).any() else np.nan)} mm"
                             + (f", {int(np.isnan(b0).sum())} case(s) without a bar" if np.isnan(b0).any() else "")
                             + f"); after the controller |x| <= {fmt(np.nanmax(ex))} mm, |z| up to {fmt(np.nanmax(ez))} mm"
                             + (" (saturated at the pressure limit in "
                                f"{int(sum(_f(p, 'x.control_saturated', 0.0) > 0 for _, p in sub))} case(s))"
                                if any(_f(p, "x.control_saturated", 0.0) > 0 for _, p in sub) else ""))
    ax0.set_xlabel("payload [g]")
    ax0.set_ylabel("|grasp centre - CC centre| [mm]")
    ax0.set_title("open loop: the CC grasp centre under payload")
    ax0.legend(frameon=False, fontsize=7)
    ax1.set_xlabel("payload [g]")
    ax1.set_ylabel("remaining error [mm]")
    ax1.set_title("after the centre-of-arc controller (J_v has no z row)")
    ax1.legend(frameon=False, fontsize=6, ncol=2)
    fig.suptitle("Shao's grasp centre: CC prediction vs physics, and closing the loop with Eq 4-5")
    return ReportFigure("scoop_centre", "Grasp centre under payload, open and closed loop", fig,
                        "; ".join(texts) + ". Error bars: |v(n) - v(n/2)| (mesh, x.disc_*) + |v(k) - v(k/10)| "
                        "(contact penalty, x.pen_*); a case whose estimate run failed has none (x.disc_failed).")


def _length_figure(pairs) -> ReportFigure:
    fig = Figure(figsize=(7.0, 4.0), layout="constrained")
    ax = fig.subplots()
    labels, cc_dl, ph_dl = [], [], []
    for c, p in sorted(pairs, key=lambda t: (str(t[0]["p.scenario.actuation"]), str(t[0]["p.scenario.payload"]), _mass(t[0]))):
        labels.append(f"{c['p.scenario.actuation'][:3]} {c['p.scenario.payload'][:3]} {fmt(1e3 * _mass(c))}")
        cc_dl.append(100 * _f(c, "length_change") / _f(c, "robot_length"))
        ph_dl.append(100 * _f(p, "length_change") / _f(p, "robot_length"))
    x = np.arange(len(labels))
    ax.bar(x - 0.2, cc_dl, 0.4, color="0.6", label="CC")
    ax.bar(x + 0.2, ph_dl, 0.4, color="#ff7f0e", label="physics")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xticks(x, labels, rotation=60, fontsize=7)
    ax.set_ylabel("length change [% of L]")
    ax.set_title("chambers lengthen the section, tendons shorten it")
    ax.legend(frameon=False)
    acts = {str(c["p.scenario.actuation"]): 100 * _f(p, "length_change") / _f(p, "robot_length") for c, p in pairs}
    return ReportFigure("scoop_length", "Section length: fluidic vs tendon", fig,
                        "; ".join(f"{a}: {fmt(v)} % of L (physics)" for a, v in sorted(acts.items())) + ".")


def _control_figure(pairs) -> ReportFigure | None:
    rows = [(c, p) for c, p in pairs if p.get("series.control_error") is not None]
    if not rows:
        return None
    fig = Figure(figsize=(7.0, 4.0), layout="constrained")
    ax = fig.subplots()
    for c, p in rows:
        E = array_cell(p["series.control_error"]).reshape(-1, 2)
        act, pay = str(c["p.scenario.actuation"]), str(c["p.scenario.payload"])
        ax.semilogy(np.arange(len(E)), 1e3 * np.abs(E[:, 0]) + 1e-6, color=_ACT.get(act, "C0"), ls=_PAY[pay], marker="o",
                    ms=3, alpha=0.8)
    ax.set_xlabel("controller step")
    ax.set_ylabel("|x error| of the grasp centre [mm]")
    ax.set_title("resolved-rate steps with Shao's centre-of-arc Jacobian (colour: actuation; dashed: tip mass)")
    return ReportFigure("scoop_control", "Grasp-centre controller convergence", fig,
                        f"{len(rows)} cases; the x error falls by the factor shown per step, the z error stays (no z row in J_v).")


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The scoop figures (module docstring)."""
    pairs = _pairs(baseline_cases(results, results.ok))  # sensitivity cases: the Sensitivity section
    if not pairs:
        return []
    figs = [_shapes_figure(pairs), _centre_figure(pairs), _length_figure(pairs), _control_figure(pairs)]
    return [f for f in figs if f is not None]
