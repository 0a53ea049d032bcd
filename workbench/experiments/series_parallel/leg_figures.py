"""Counterparts of Huang et al.'s leg-shape figures: the flexible legs, not just the platform origins.

:func:`module_legs_figure` (paper Fig 6): one 3-D panel per single-module motion at its largest
negative and positive amplitude, the six leg centrelines of the Exudyn FK state, base and moving
platform.  :func:`stack_legs_figure` (paper Fig 10): one panel per stack shape and amplitude,
every module's legs and platforms.  Both read the ``legs`` column of the ``series_parallel``
rows (FK leg centrelines (n, 6, N+1, 3) [m], stack base frame = world frame, z up); a run
stored before that column existed gets no leg figure.  Checked by
``tests/experiments/test_series_parallel_figures.py``.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from ...compare.table import array_cell
from ...report.style import ReportFigure, fmt

__all__ = ["leg_shape_figures", "module_legs_figure", "stack_legs_figure", "row_legs"]

_ORDER = {"x": 0, "y": 1, "z": 2, "rx": 3, "ry": 4, "rz": 5}
_UNIT = {"x": "mm", "y": "mm", "z": "mm", "rx": "deg", "ry": "deg", "rz": "deg"}


def row_legs(row: Mapping[str, Any]) -> np.ndarray | None:
    """``(n_modules, 6, n_nodes, 3)`` leg centrelines of a ``series_parallel`` row [m], or ``None``."""
    legs = array_cell(row.get("legs"))
    st = array_cell(row.get("stations"))
    if legs is None or st is None or legs.size == 0:
        return None
    n_mod = st.size - 1
    if n_mod < 1 or legs.size % (n_mod * 18):
        return None
    return legs.reshape(n_mod, 6, -1, 3)


def _draw_legs(ax, legs: np.ndarray, color: str) -> None:
    for k in range(legs.shape[0]):
        for i in range(6):
            p = legs[k, i]
            ax.plot(p[:, 0], p[:, 1], p[:, 2], color=color, lw=1.3)
        for end in (0, -1):  # platforms: polygons through the rod ends
            ring = legs[k, :, end, :]
            ring = np.vstack([ring, ring[:1]])
            ax.plot(ring[:, 0], ring[:, 1], ring[:, 2], color="0.35", lw=0.9)


def _box(ax, pts: np.ndarray) -> None:
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c, r = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo)) * 1.05
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("world x [m]", fontsize=7, labelpad=-8)
    ax.set_ylabel("world y [m]", fontsize=7, labelpad=-8)
    ax.set_zlabel("world z [m]", fontsize=7, labelpad=-8)
    ax.tick_params(labelsize=6, pad=-3)
    ax.view_init(elev=18, azim=-60)


def _pose_name(row: Mapping[str, Any]) -> str:
    shape = str(row["p.pose.shape"])
    piv = row.get("p.pose.pivot")
    return shape + (f" @ {fmt(float(piv))} h" if shape in ("rx", "ry") and piv is not None and np.isfinite(piv)
                    and float(piv) != 1.0 else "")


def _amplitude(row: Mapping[str, Any]) -> str:
    shape, v = str(row["p.pose.shape"]), float(row["p.pose.value"])
    unit = _UNIT.get(shape)
    if unit == "mm":
        return f"{fmt(1e3 * v)} mm"
    if unit == "deg":
        return f"{fmt(np.degrees(v))}°"
    return fmt(v)


def _extremes(rows: pd.DataFrame) -> list[dict]:
    """The ok rows of one motion at its most negative and most positive amplitude (one if they coincide)."""
    ok = rows[rows["status"] == "ok"].sort_values("p.pose.value", kind="mergesort")
    if ok.empty:
        return []
    picks = [ok.iloc[0].to_dict(), ok.iloc[-1].to_dict()]
    return picks[:1] if picks[0]["case_id"] == picks[1]["case_id"] else picks


def module_legs_figure(df: pd.DataFrame) -> tuple[Figure, list[str]] | None:
    """Fig 6 counterpart: every single-module motion at its extreme amplitudes; ``None`` without legs."""
    sp = df[(df["model"] == "series_parallel") & (df["p.pose.kind"] == "module")]
    groups = []
    if sp.empty:
        return None
    for name, g in sp.groupby(sp.apply(_pose_name, axis=1), sort=False):
        picks = [r for r in _extremes(g) if row_legs(r) is not None]
        if picks:
            groups.append((name, picks))
    if not groups:
        return None
    groups.sort(key=lambda ng: (_ORDER.get(ng[0].split(" ")[0], 9), ng[0]))  # the paper's order: x y z rx ry rz
    ncol = len(groups)
    fig = Figure(figsize=(2.3 * ncol + 0.4, 5.2))
    fig.subplots_adjust(left=0.02, right=0.97, top=0.9, bottom=0.06, wspace=0.3, hspace=0.35)
    cases = []
    for j, (name, picks) in enumerate(groups):
        for i, r in enumerate(picks):
            ax = fig.add_subplot(2, ncol, i * ncol + j + 1, projection="3d")
            legs = row_legs(r)
            _draw_legs(ax, legs, "C0" if i == 0 else "C3")
            _box(ax, legs.reshape(-1, 3))
            ax.set_title(f"{name} = {_amplitude(r)}", fontsize=8.5)
            cases.append(str(r["case_id"]))
    return fig, cases


def stack_legs_figure(df: pd.DataFrame) -> tuple[Figure, list[str]] | None:
    """Fig 10 counterpart: every stack shape and amplitude, all modules' legs (x-z and y-z side views)."""
    sp = df[(df["model"] == "series_parallel") & (df["p.pose.kind"] == "stack") & (df["status"] == "ok")]
    rows = [r for r in sp.sort_values(["p.pose.shape", "p.pose.value"], kind="mergesort").to_dict("records")
            if row_legs(r) is not None]
    if not rows:
        return None
    allp = np.vstack([row_legs(r).reshape(-1, 3) for r in rows])
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = 0.05 * float(np.max(hi - lo))
    fig = Figure(figsize=(1.9 * len(rows) * 2 + 0.6, 4.6), layout="constrained")
    axs = fig.subplots(1, 2 * len(rows), sharey=True)
    for j, r in enumerate(rows):
        legs = row_legs(r)
        unit = "m" if r["p.pose.shape"] == "translation" else "rad"
        for v, (a, name) in enumerate(((0, "x"), (1, "y"))):
            ax = axs[2 * j + v]
            for k in range(legs.shape[0]):
                for i in range(6):
                    ax.plot(legs[k, i, :, a], legs[k, i, :, 2], color="C0", lw=1.0)
                for end in (0, -1):
                    ring = legs[k, :, end, :]
                    ax.plot(ring[:, a], ring[:, 2], color="0.35", lw=2.0)
            ax.set_xlim(lo[a] - pad, hi[a] + pad)
            ax.set_ylim(lo[2] - pad, hi[2] + pad)
            ax.set_aspect("equal", adjustable="box")
            ax.set_xlabel(f"world {name} [m]")
            if v == 0:
                ax.set_title(f"{r['p.pose.shape']} = {fmt(float(r['p.pose.value']))} {unit}", fontsize=9, loc="left")
    axs[0].set_ylabel("world z [m]")
    return fig, [str(r["case_id"]) for r in rows]


def leg_shape_figures(df: pd.DataFrame) -> list[ReportFigure]:
    """The ``module_legs`` (Fig 6) and ``stack_legs`` (Fig 10) figures that the table's data allows."""
    out = []
    got = module_legs_figure(df)
    if got is not None:
        fig, cases = got
        out.append(ReportFigure(
            "module_legs", "One module along Huang's Fig 6 motions: the legs", fig,
            "Counterpart of Huang et al. Fig 6: the six flexible legs (centrelines of the Exudyn FK state after IK) and "
            "the base and moving platforms (grey), in the world frame (z up), for each single-module motion at its "
            "most negative (top row) and most positive (bottom row) amplitude the IK reached; 'rx @ 0.5 h': rotation "
            "about the point at half the module height.  Equal axis scaling per panel.", cases=tuple(cases)))
    got = stack_legs_figure(df)
    if got is not None:
        fig, cases = got
        out.append(ReportFigure(
            "stack_legs", "The stack along Huang's Fig 10 shapes: the legs", fig,
            "Counterpart of Huang et al. Fig 10: every module's legs and platforms of the stack for each stack shape "
            "(translation: tip offset [m]; s_shape: tangent angle at mid-length [rad]; bending: total bend angle "
            "[rad]) and amplitude, seen along world y (x-z view) and along world x (y-z view), z up, equal axis "
            "scaling; platforms grey.", cases=tuple(cases)))
    return out
