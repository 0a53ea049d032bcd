"""Report figures of grasp studies: CC wrap vs physical wrap, contact, holding force, pull-out, carry.

Registered as ``registry.FIGURES["whole_arm_grasp"]``: :func:`matches` picks results of the
``whole_arm_wrap`` scenario; :func:`figures` draws

1. the wraps: CC backbone (where it penetrates the object, red) vs the physical backbone holding
   the released object, the object where CC planned it and where it settled;
2. contact along the arm: the physics' contact line load and CC's surface gap (< 0: penetration);
3. the sweep: holding force against object size x squeeze x friction (error bars: the
   ``x.disc_holding_force`` mesh estimate plus the pull-step resolution) and the settling offset;
4. the pull-out curves; 5. carrying: planned vs actual path of the object.

The summaries quote the study's question, findings and assumptions (:mod:`.notes`).  Frames: base
frame (x, z) = world frame for the vertical trunk.  Checked by ``tests/experiments/test_whole_arm_grasp.py``
(the report of a small study builds with these figures).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...compare.table import array_cell, row_positions
from ...report.style import ReportFigure, fmt
from ...report.headline import baseline_cases
from ..about import assumption_values
from .findings import findings
from .notes import ABOUT

__all__ = ["matches", "figures", "SCENARIO"]

SCENARIO = "whole_arm_wrap"
_COLORS = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02"]
_STYLES = ["-", "--", ":", "-."]


def matches(results) -> bool:
    """True for results of the ``whole_arm_wrap`` scenario."""
    ok = results.ok
    return not ok.empty and "p.scenario.name" in ok and ok["p.scenario.name"].iloc[0] == SCENARIO


def _val(row, key, default=np.nan) -> float:
    v = row.get(key, default)
    try:
        return float(v)
    except (TypeError, ValueError):
        return default


def _pairs(ok: pd.DataFrame) -> list[tuple[pd.Series, pd.Series]]:
    """``(cc row, contact row)`` per case that has both."""
    out = []
    for _, g in ok.groupby("case_id", sort=False):
        cc, ph = g[g["model"] == "cc"], g[g["model"] == "contact"]
        if len(cc) and len(ph):
            out.append((cc.iloc[0], ph.iloc[0]))
    return out


def _middle(values) -> float:
    v = sorted(set(float(x) for x in values))
    return v[len(v) // 2]


def _circle(ax, c, r, **kw) -> None:
    t = np.linspace(0, 2 * np.pi, 121)
    ax.plot(1e3 * (c[0] + r * np.cos(t)), 1e3 * (c[1] + r * np.sin(t)), **kw)


def _wrap_panel(ax, cc: pd.Series, ph: pd.Series) -> str:
    r = _val(cc, "p.scenario.object_radius")
    c0 = np.array([_val(cc, "x.object_x"), _val(cc, "x.object_z")])
    _, pc = row_positions(cc.to_dict())
    _, pp = row_positions(ph.to_dict())
    ax.plot(1e3 * pc[:, 0], 1e3 * pc[:, 2], "k--", lw=1.6, label="CC plan (centreline)")
    ax.plot(1e3 * pp[:, 0], 1e3 * pp[:, 2], color="#ff7f0e", lw=2.0, label="physics, object released")
    hw = array_cell(cc.get("series.half_width"))
    if hw is not None and hw.size == len(pp):
        for P, col, ls in ((pp, "#ff7f0e", "-"), (pc, "k", "--")):
            t = np.gradient(P[:, [0, 2]], axis=0)
            n = np.column_stack([-t[:, 1], t[:, 0]]) / np.linalg.norm(t, axis=1, keepdims=True)
            for sgn in (1.0, -1.0):
                ax.plot(1e3 * (P[:, 0] + sgn * hw * n[:, 0]), 1e3 * (P[:, 2] + sgn * hw * n[:, 1]), color=col,
                        ls=ls, lw=0.5, alpha=0.6)
    _circle(ax, c0, r, color="0.5", ls="--", lw=1.0, label="object where CC holds it")
    held = _val(ph, "x.held", 0.0) > 0
    if held:
        c1 = c0 + np.array([_val(ph, "x.settle_dx"), _val(ph, "x.settle_dz")])
        _circle(ax, c1, r, color="#d62728", lw=1.4, label="object where it settled")
    s, fn = array_cell(ph.get("series.contact_s")), array_cell(ph.get("series.contact_fn"))
    st = array_cell(ph.get("stations"))
    if s is not None and fn is not None and st is not None and np.any(fn > 0):
        on = fn > 0
        x, z = np.interp(s[on], st, pp[:, 0]), np.interp(s[on], st, pp[:, 2])
        ax.scatter(1e3 * x, 1e3 * z, s=8 + 60 * fn[on] / fn.max(), color="#ff7f0e", edgecolor="k", lw=0.4,
                   zorder=5, label="contact (size ~ force)")
    ax.plot(0, 0, "ks", ms=5)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm] (base = world frame)")
    ax.set_ylabel("z [mm]")
    ax.set_title(f"r = {fmt(1e3 * r)} mm, squeeze {fmt(_val(cc, 'p.scenario.squeeze'))}, "
                 f"friction {fmt(_val(cc, 'p.scenario.friction'))}", fontsize=9)
    d = np.hypot(_val(ph, "x.settle_dx"), _val(ph, "x.settle_dz"))
    return (f"r = {fmt(1e3 * r)} mm: CC's arc penetrates the object by up to {fmt(1e3 * _val(cc, 'x.cc_max_penetration'))} mm "
            f"over {fmt(1e3 * _val(cc, 'x.cc_penetration_arc'))} mm of arm; the physics "
            + (f"holds it {fmt(1e3 * d)} mm from where CC holds it (contact over {fmt(1e3 * _val(ph, 'x.arc'))} mm, "
               f"{fmt(_val(ph, 'x.normal_force'))} N normal force)" if held else "does not hold it (it slips out)"))


def _selected(pairs, key: str):
    """One pair per value of ``key`` at the middle values of the other swept scenario keys."""
    keys = [k for k in ("p.scenario.object_radius", "p.scenario.squeeze", "p.scenario.friction") if k != key]
    mid = {k: _middle(p[0][k] for p in pairs) for k in keys}
    sel = [p for p in pairs if all(abs(float(p[0][k]) - mid[k]) < 1e-12 for k in keys)]
    return sorted(sel, key=lambda p: float(p[0][key]))


def _wraps_figure(pairs) -> ReportFigure:
    all_pairs = pairs
    sel = _selected(pairs, "p.scenario.object_radius") or pairs[:1]
    fig = Figure(figsize=(max(7.5, 4.6 * len(sel)), 4.9), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(sel)))
    texts = [_wrap_panel(ax, cc, ph) for ax, (cc, ph) in zip(axes, sel)]
    fig.legend(*axes[0].get_legend_handles_labels(), frameon=False, fontsize=7, loc="outside lower center", ncol=5)
    fig.suptitle("CC wrap plan vs the physical wrap (thin lines: the arm's surface; gravity along -z)")
    return ReportFigure("grasp_wraps", "Whole-arm wrap: CC plan vs physics", fig, _summary(texts, findings(all_pairs)))


def _summary(texts, found) -> str:
    """Question, findings (computed), the seed-paper rows answered, the panels, and the assumptions."""
    return (f"Question: {ABOUT.question} Findings: " + "; ".join(found) + ". Answers: "
            + "; ".join(ABOUT.paper_rows) + ". " + "; ".join(texts) + ". Assumptions: "
            + "; ".join(assumption_values(ABOUT, pd.DataFrame())) + ".")


def _surface_gap(row: pd.Series, centre, r: float, hw):
    """``(stations, gap)``: the arm's surface distance [m] to the object along the backbone (< 0: inside it);
    ``hw`` the half diameter at the stations (the CC row's ``series.half_width``)."""
    _, P = row_positions(row.to_dict())
    st = array_cell(row.get("stations"))
    if P is None or st is None or hw is None or hw.size != len(P):
        return None, None
    return st, np.hypot(P[:, 0] - centre[0], P[:, 2] - centre[1]) - r - hw


def _contact_figure(pairs) -> ReportFigure:
    sel = _selected(pairs, "p.scenario.squeeze") or pairs[:1]
    fig = Figure(figsize=(10.5, 4.2), layout="constrained")
    ax, axg = fig.subplots(1, 2)
    texts = []
    for i, (cc, ph) in enumerate(sel):
        col = _COLORS[i % len(_COLORS)]
        sq = _val(cc, "p.scenario.squeeze")
        s, fn = array_cell(ph.get("series.contact_s")), array_cell(ph.get("series.contact_fn"))
        if s is not None and fn is not None:
            ds = np.gradient(s) if s.size > 1 else np.ones_like(s)
            ax.plot(1e3 * s, fn / ds, color=col, label=f"squeeze {fmt(sq)}")
            on = fn > 0
            if on.any():
                texts.append(f"squeeze {fmt(sq)}: the physical arm touches at s = {fmt(1e3 * s[on].min())}-"
                             f"{fmt(1e3 * s[on].max())} mm, peak {fmt((fn / ds).max())} N/m")
        r = _val(cc, "p.scenario.object_radius")
        c0 = np.array([_val(cc, "x.object_x"), _val(cc, "x.object_z")])
        hw = array_cell(cc.get("series.half_width"))
        st, g = _surface_gap(cc, c0, r, hw)
        if st is not None:
            axg.plot(1e3 * st, 1e3 * g, color=col, ls="--", label=f"CC plan, squeeze {fmt(sq)}")
            inside = g < 0
            texts.append(f"CC's arm surface is inside the object over {fmt(1e3 * np.ptp(st[inside]) if inside.any() else 0)} "
                         f"mm of arc (deepest {fmt(-1e3 * g.min())} mm)")
        if _val(ph, "x.held", 0.0) > 0:
            c1 = c0 + np.array([_val(ph, "x.settle_dx"), _val(ph, "x.settle_dz")])
            st, g = _surface_gap(ph, c1, r, hw)
            if st is not None:
                axg.plot(1e3 * st, 1e3 * g, color=col, label=f"physics, squeeze {fmt(sq)}")
    ax.set_xlabel("arc length s [mm] (reference)")
    ax.set_ylabel("contact line load [N/m] (physics, released object)")
    ax.set_title("where the physical arm touches the object")
    ax.legend(frameon=False)
    axg.axhline(0.0, color="k", lw=0.8)
    axg.set_xlabel("arc length s [mm] (reference)")
    axg.set_ylabel("surface gap to the object [mm] (< 0: inside it)")
    axg.set_title("CC ignores the object: where its arcs penetrate or miss it")
    axg.set_ylim(-80, 120)
    axg.legend(frameon=False, fontsize=7)
    fig.suptitle(f"Contact along the arm (r = {fmt(1e3 * _val(sel[0][0], 'p.scenario.object_radius'))} mm, "
                 f"friction {fmt(_val(sel[0][0], 'p.scenario.friction'))})")
    return ReportFigure("grasp_contact", "Contact arc and forces; where CC penetrates or misses the object", fig,
                        "; ".join(texts) + ". Surface gap: distance of the arm's surface (centreline +- half the "
                        "diameter) from the object, CC against the object where CC holds it, physics against the "
                        "object where it settled; the gap of the physics is >= 0 up to the penalty's penetration.")


def _holding_error(ph: pd.Series) -> float:
    """Error bar of the holding force [N]: mesh (``x.disc_*``) + contact penalty (``x.pen_*``) + pull step."""
    return (_val(ph, "x.disc_holding_force", 0.0) + _val(ph, "x.pen_holding_force", 0.0)
            + _val(ph, "x.holding_force_step_err", 0.0))


def _sweep_figure(pairs) -> ReportFigure:
    radii = sorted({_val(c, "p.scenario.object_radius") for c, _ in pairs})
    frictions = sorted({_val(c, "p.scenario.friction") for c, _ in pairs})
    fig = Figure(figsize=(12.5, 4.4), layout="constrained")
    axf, axs = fig.subplots(1, 2)
    texts, lower, marked = [], 0, False
    for i, r in enumerate(radii):
        for j, mu in enumerate(frictions):
            sub = sorted(((c, p) for c, p in pairs if abs(_val(c, "p.scenario.object_radius") - r) < 1e-12
                          and abs(_val(c, "p.scenario.friction") - mu) < 1e-12 and "x.holding_force" in p),
                         key=lambda t: _val(t[0], "p.scenario.squeeze"))
            if not sub:
                continue
            sq = [_val(c, "p.scenario.squeeze") for c, _ in sub]
            F = [_val(p, "x.holding_force") for _, p in sub]
            lower += sum(_val(p, "x.pull_peak_resolved", 1.0) == 0 for _, p in sub)
            lab = f"r = {fmt(1e3 * r)} mm, friction {fmt(mu)}"
            axf.errorbar(sq, F, yerr=[_holding_error(p) for _, p in sub], color=_COLORS[i % len(_COLORS)],
                         ls=_STYLES[j % len(_STYLES)], marker="o", ms=4, capsize=3, label=lab)
            lb = [(x, f) for x, f, (_, p) in zip(sq, F, sub) if _val(p, "x.pull_peak_resolved", 1.0) == 0]
            if lb:
                axf.plot(*zip(*lb), "^", ms=9, mfc="none", color=_COLORS[i % len(_COLORS)],
                         label="lower bound (path ended at a fold)" if not marked else None)
                marked = True
            bars = [1e3 * sum(_val(p, f"x.{e}_settle_{c}", 0.0) for e in ("disc", "pen") for c in ("dx", "dz"))
                    for _, p in sub]
            axs.errorbar(sq, [1e3 * np.hypot(_val(p, "x.settle_dx"), _val(p, "x.settle_dz")) for _, p in sub],
                         yerr=bars, color=_COLORS[i % len(_COLORS)], ls=_STYLES[j % len(_STYLES)], marker="o", ms=4,
                         capsize=3)
            texts.append(f"{lab}: holding force {fmt(min(F))}-{fmt(max(F))} N")
    axf.set_xlabel("squeeze (commanded / touching curvature of the wrap)")
    axf.set_ylabel("holding force [N] (largest pull on the static path)")
    axf.set_title("holding force against a pull straight down")
    axf.legend(frameon=False, fontsize=6.5, ncol=2)
    axs.set_xlabel("squeeze")
    axs.set_ylabel("|settled centre - CC centre| [mm]")
    axs.set_title("where the object settles vs where CC holds it")
    fig.suptitle("Object size x tendon tension x friction")
    note = (f" {lower} case(s) ended the pull at a fold or the distance limit while the force still rose: "
            f"their value is a lower bound." if lower else "")
    return ReportFigure("grasp_sweep", "Holding force: object size x squeeze x friction", fig,
                        "; ".join(texts) + ". Error bars: |F(n) - F(n/2)| (mesh, x.disc_holding_force) plus "
                        "|F(k) - F(k/10)| (contact penalty, x.pen_holding_force) plus the pull-step resolution."
                        + note)


def _pull_figure(pairs) -> ReportFigure:
    r_mid = _middle(_val(c, "p.scenario.object_radius") for c, _ in pairs)
    fig = Figure(figsize=(7.5, 4.4), layout="constrained")
    ax = fig.subplots()
    squeezes = sorted({_val(c, "p.scenario.squeeze") for c, _ in pairs})
    frictions = sorted({_val(c, "p.scenario.friction") for c, _ in pairs})
    ends = {0: "distance limit", 1: "contact lost", 2: "no equilibrium (fold)", 3: "snap"}
    texts = []
    for cc, ph in pairs:
        u, F = array_cell(ph.get("series.pull_u")), array_cell(ph.get("series.pull_force"))
        if u is None or F is None or abs(_val(cc, "p.scenario.object_radius") - r_mid) > 1e-12:
            continue
        i, j = squeezes.index(_val(cc, "p.scenario.squeeze")), frictions.index(_val(cc, "p.scenario.friction"))
        ax.plot(1e3 * u, F, color=_COLORS[i % len(_COLORS)], ls=_STYLES[j % len(_STYLES)],
                label=f"squeeze {fmt(squeezes[i])}, friction {fmt(frictions[j])}")
        ax.plot(1e3 * u[-1], F[-1], "x", color=_COLORS[i % len(_COLORS)])
        texts.append(f"squeeze {fmt(squeezes[i])}, friction {fmt(frictions[j])}: peak {fmt(F.max())} N, path ends at "
                     f"{fmt(1e3 * u[-1])} mm ({ends.get(int(_val(ph, 'x.pull_end', 0)), '?')})")
    ax.set_xlabel("pull displacement [mm] (straight down, from the held position)")
    ax.set_ylabel("pull force [N]")
    ax.set_title(f"pull-out curves, object radius {fmt(1e3 * r_mid)} mm (x: end of the static path)")
    ax.legend(frameon=False, fontsize=7)
    return ReportFigure("grasp_pull", "Pull-out: force against displacement", fig, "; ".join(texts) + ".")


def _carry_figure(pairs) -> ReportFigure | None:
    sel = [p for p in _selected(pairs, "p.scenario.object_radius") if p[1].get("series.carry_actual") is not None]
    if not sel:
        return None
    fig = Figure(figsize=(6.5, 5.0), layout="constrained")
    ax = fig.subplots()
    texts = []
    for i, (cc, ph) in enumerate(sel):
        P = array_cell(ph.get("series.carry_planned")).reshape(-1, 2)
        A = array_cell(ph.get("series.carry_actual")).reshape(-1, 2)
        col = _COLORS[i % len(_COLORS)]
        r = _val(cc, "p.scenario.object_radius")
        ax.plot(1e3 * P[:, 0], 1e3 * P[:, 1], "o--", color=col, mfc="none", label=f"CC plan, r = {fmt(1e3 * r)} mm")
        ax.plot(1e3 * A[:, 0], 1e3 * A[:, 1], "o-", color=col, label=f"physics, r = {fmt(1e3 * r)} mm")
        texts.append(f"r = {fmt(1e3 * r)} mm: object {fmt(1e3 * _val(ph, 'x.carry_max_error'))} mm off the planned path "
                     f"at worst ({fmt(1e3 * _val(ph, 'x.carry_move_error'))} +- "
                     f"{fmt(1e3 * (_val(ph, 'x.disc_carry_move_error', 0.0) + _val(ph, 'x.pen_carry_move_error', 0.0)))}"
                     f" mm of it tracking error of the move, the "
                     f"rest the settling offset), planned move {fmt(1e3 * np.linalg.norm(P[-1] - P[0]))} mm, actual "
                     f"{fmt(1e3 * np.linalg.norm(A[-1] - A[0]))} mm")
    ax.set_aspect("equal")
    ax.set_xlabel("object centre x [mm] (base = world)")
    ax.set_ylabel("object centre z [mm]")
    ax.set_title("carrying the object: planned vs actual centre")
    ax.legend(frameon=False, fontsize=7)
    return ReportFigure("grasp_carry", "Moving the object along a path", fig, "; ".join(texts) + ".")


def figures(results, cmp: pd.DataFrame) -> list[ReportFigure]:
    """The grasp figures (module docstring); cases without both rows are left out."""
    pairs = _pairs(baseline_cases(results, results.ok))  # sensitivity cases: the Sensitivity section
    if not pairs:
        return []
    figs = [_wraps_figure(pairs), _contact_figure(pairs)]
    if any("x.holding_force" in p for _, p in pairs):
        figs += [_sweep_figure(pairs), _pull_figure(pairs)]
    carry = _carry_figure(pairs)
    return figs + ([carry] if carry is not None else [])
