"""The picture of a robot that ``workbench robot show`` writes: straight and unloaded, in its base frame.

Three panels: the base-frame x-z and y-z views (backbone per section, disks, every tendon from the
base plate to its terminating disk with its offset varying along a tapered group, the payload, the
base frame axes and the gravity arrow) and the cross-section at the base plate (backbone, each
group's tendons at their base offset, filled, and at their tip offset, open).  A robot is long and
thin, so the two side views stretch the lateral (x, y) scale by a stated factor; the cross-section
is true to scale; a lower section's tendons are drawn wider, so groups that share a path stay visible.
Pure presentation of a :class:`~workbench.robot.Robot` (no derived physics):
matplotlib ``Figure`` (Agg, no pyplot) like every report figure.

Checked by ``tests/report/test_robot_picture.py`` (tendon end points and the lateral scale) and
``tests/study/test_robot_show.py`` (a non-empty PNG for every preset and committed study).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib import rc_context
from matplotlib.figure import Figure

from ..robot import Robot

__all__ = ["lateral_scale", "tendon_paths", "robot_figure", "save_robot_picture"]

_GROUP_COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf")


def _half_width(robot: Robot) -> float:
    """The largest lateral extent of the robot [m]: tendon offsets and backbone radii."""
    w = [0.0]
    for s in robot.sections:
        for cs in (s.cross_section, s.cross_section_tip):
            if cs is not None and cs.diameter is not None:
                w.append(0.5 * cs.diameter)
        if s.tendons is not None:
            w += [s.tendons.offset, s.tendons.offset_tip or 0.0]
    return max(w) or 0.01 * robot.length


def lateral_scale(robot: Robot) -> float:
    """Factor (a whole number >= 1) the side views stretch x and y by, so the robot is about 1/4 as wide as long."""
    return float(max(1, round(robot.length / (8.0 * _half_width(robot)))))


def tendon_paths(robot: Robot) -> list[tuple[int, float, np.ndarray]]:
    """``(section, sigma, points)`` per tendon: its straight-robot path in the base frame, ``(n, 3)`` [m].

    The path runs from the base plate (s = 0) to its terminating disk, with the offset linear in
    arc length (:meth:`TendonGroup.offset_at`), one point at every section end.
    """
    out = []
    ends = robot.section_ends
    for sec, sigma, group in robot.tendon_table():
        s = np.linspace(0.0, ends[sec], 16 * (sec + 1) + 1)
        d = np.array([group.offset_at(x / ends[sec]) for x in s])
        out.append((sec, sigma, np.column_stack([d * math.cos(sigma), d * math.sin(sigma), s])))
    return out


def _side_view(ax, robot: Robot, axis: int, k: float) -> None:
    """Backbone, disks, tendons, payload, base axes and gravity, projected on base (x or y, z) x ``k``."""
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    for j, (s, z0) in enumerate(zip(robot.sections, starts)):
        tip = s.cross_section_tip or s.cross_section
        r0 = 0.5 * (s.cross_section.diameter or 0.0) * k
        r1 = 0.5 * (tip.diameter or 0.0) * k
        ax.fill([-r0, r0, r1, -r1], [z0, z0, z0 + s.length, z0 + s.length], color="0.8" if j % 2 else "0.65",
                lw=0.8 if r0 == 0 else 0, edgecolor="0.35", zorder=2)
        ax.plot([0, 0], [z0, z0 + s.length], color="0.2", lw=0.6, zorder=2)
    paths = tendon_paths(robot)
    for z in robot.disk_stations():
        w = max([abs(np.interp(z, p[:, 2], p[:, axis], right=np.nan)) for _, _, p in paths if p[-1, 2] >= z - 1e-12]
                + [_half_width(robot) * 0.5])
        ax.plot([-1.15 * w * k, 1.15 * w * k], [z, z], color="0.45", lw=1.2, zorder=1)
    ax.plot([-1.3 * _half_width(robot) * k, 1.3 * _half_width(robot) * k], [0, 0], color="k", lw=3, zorder=3)
    last = max([sec for sec, _, _ in paths], default=0)
    for sec, _sigma, p in paths:  # a lower section's tendons wider: groups may share a path
        c = _GROUP_COLORS[sec % len(_GROUP_COLORS)]
        ax.plot(p[:, axis] * k, p[:, 2], color=c, lw=1.0 + 1.2 * (last - sec), zorder=4)
        ax.plot(p[-1, axis] * k, p[-1, 2], "o", color=c, ms=3.5, zorder=5)
    if robot.payload.mass > 0:
        ax.plot(0, robot.length, "s", color="k", ms=7, zorder=6)
        ax.annotate(f"payload {robot.payload.mass:g} kg", (0, robot.length), textcoords="offset points",
                    xytext=(6, 4), fontsize=8)


def _frame_and_gravity(ax, robot: Robot, axis: int) -> None:
    """Base frame axes at the origin (true lengths scaled to L/8) and the gravity direction in the base frame."""
    L = robot.length
    a = 0.12 * L
    name = "xy"[axis]
    ax.annotate("", (a, 0), (0, 0), arrowprops=dict(arrowstyle="->", color="tab:red", lw=1.6), zorder=7)
    ax.annotate("", (0, a), (0, 0), arrowprops=dict(arrowstyle="->", color="tab:blue", lw=1.6), zorder=7)
    ax.text(a, -0.03 * L, name, color="tab:red", fontsize=8)
    ax.text(0.01 * L, a, "z", color="tab:blue", fontsize=8)
    g = robot.gravity_in_base()
    gn = float(np.linalg.norm(g))
    if gn > 0:
        v = np.array([g[axis], g[2]]) / gn * 0.2 * L
        x0 = np.array([0.2 * L, 0.8 * L])
        if np.linalg.norm(v) > 1e-3 * L:
            ax.annotate("", x0 + v, x0, arrowprops=dict(arrowstyle="-|>", color="tab:purple", lw=1.6))
        ax.text(*(x0 + np.array([0.02 * L, 0.04 * L])), f"g {gn:.3g} m/s²" + ("" if np.linalg.norm(v) > 1e-3 * L
                                                                            else " (out of view)"),
                color="tab:purple", fontsize=8)


def _cross_section(ax, robot: Robot) -> None:
    """Base-plate cross-section, true to scale: backbone, tendons (filled: base offset, open: tip offset)."""
    cs = robot.sections[0].cross_section
    t = np.linspace(0, 2 * math.pi, 121)
    labels: dict[float, float] = {}  # tendon angle [deg] -> largest base offset, labelled once
    if cs.diameter is not None:
        ax.fill(0.5 * cs.diameter * np.cos(t), 0.5 * cs.diameter * np.sin(t), color="0.65")
    for j, s in enumerate(robot.sections):
        g = s.tendons
        if g is None:
            continue
        c = _GROUP_COLORS[j % len(_GROUP_COLORS)]
        ang = np.asarray(g.angles)
        ax.plot(g.offset * np.cos(ang), g.offset * np.sin(ang), "o", color=c, ms=5, label=f"section {j + 1}")
        if g.offset_tip is not None:
            ax.plot(g.offset_tip * np.cos(ang), g.offset_tip * np.sin(ang), "o", mfc="none", color=c, ms=5)
        for a, d in zip(ang, np.broadcast_to(g.offset, ang.shape)):
            labels[round(math.degrees(a) % 360, 1)] = max(d, labels.get(round(math.degrees(a) % 360, 1), 0.0))
    for deg, d in labels.items():
        a = math.radians(deg)
        ax.annotate(f"{deg:g}°", (d * math.cos(a), d * math.sin(a)), textcoords="offset points",
                    xytext=(12 * math.cos(a) - 6, 10 * math.sin(a) - 3), fontsize=7)
    w = _half_width(robot)
    ax.plot(1.15 * w * np.cos(t), 1.15 * w * np.sin(t), color="0.45", lw=1.0)
    ax.set_aspect("equal")
    ax.set_xlim(-1.5 * w, 1.5 * w)
    ax.set_ylim(-1.5 * w, 1.5 * w)
    ax.set_xlabel("base x [m]")
    ax.set_ylabel("base y [m]")
    ax.set_title("base plate (true scale)\nfilled: offset at base, open: at tip")
    if robot.n_tendons:
        ax.legend(loc="lower right", fontsize=7)


def robot_figure(robot: Robot, title: str | None = None) -> Figure:
    """The three-panel picture of ``robot`` (module docstring) as a matplotlib ``Figure``."""
    from .style import STYLE

    k = lateral_scale(robot)
    with rc_context({**STYLE, "axes.grid": False}):
        fig = Figure(figsize=(11.0, 5.6))
        axes = fig.subplots(1, 3, gridspec_kw={"width_ratios": [1, 1, 1.15]})
        for axis, ax in enumerate(axes[:2]):
            _side_view(ax, robot, axis, k)
            _frame_and_gravity(ax, robot, axis)
            half = 0.4 * robot.length
            ax.set_xlim(-half, half)
            ax.set_ylim(-0.08 * robot.length, 1.08 * robot.length)
            ax.set_aspect("equal")
            name = "xy"[axis]
            ax.set_xlabel(f"base {name} [m]" + (f" (lateral scale x{k:g})" if k > 1 else ""))
            ax.set_ylabel("base z [m]")
            ax.set_title(f"base {name}-z view")
        _cross_section(axes[2], robot)
        fig.suptitle(title or robot.name)
        fig.tight_layout()
    return fig


def save_robot_picture(robot: Robot, path: str | Path, title: str | None = None, dpi: int = 100) -> Path:
    """Write :func:`robot_figure` of ``robot`` as a PNG to ``path`` (folders created); returns the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    robot_figure(robot, title).savefig(p, dpi=dpi, format="png")
    return p
