"""Counterpart of Cojocaru et al. Fig 7: the three wire lengths as the bending direction goes round.

:func:`wire_lengths_figure` evaluates the paper's tronconic wire-length model (Eq 4-11,
:func:`workbench.kinematics.wire_lengths_tronconic_paper`, paper convention: direction ``alpha``, wires
at 0/120/240 deg, disk diameters ``D1, D2``) at ``theta = 45 deg`` for ``alpha`` from 0 to 360 deg,
for the section geometry of the study's robot (the preset's documented dimensions, an assumption
where the paper gives none: stated in the caption).  Pure kinematics, no physics model.  Checked
by ``tests/experiments/test_wire_delay_fig7.py``.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
from matplotlib.figure import Figure

from ...kinematics import wire_lengths_tronconic_paper
from ...report.style import ReportFigure, fmt
from ...study.build import build_robot
from ...study.params import section_params
from .analysis import wire_geometry

__all__ = ["fig7_curves", "wire_lengths_figure"]


def fig7_curves(H: float, d_base: float, d_tip: float, theta: float = np.pi / 4, n: int = 361):
    """``(alpha [rad] (n,), wire lengths [m] (n, 3))`` at bending angle ``theta`` (paper convention)."""
    alpha = np.linspace(0.0, 2 * np.pi, n)
    return alpha, wire_lengths_tronconic_paper(np.full(n, theta), alpha, H, 2.0 * d_base, 2.0 * d_tip)


def wire_lengths_figure(row: Mapping[str, Any]) -> ReportFigure:
    """The ``cojocaru_fig7`` figure for the robot of a stored wire-delay row."""
    geo = wire_geometry(build_robot(section_params(row, "robot"), section_params(row, "derived")))
    alpha, Lw = fig7_curves(geo.length, geo.offset_base, geo.offset_tip)
    fig = Figure(figsize=(6.4, 3.6), layout="constrained")
    ax = fig.subplots()
    for k, c in enumerate(("#1b9e77", "#7570b3", "#d95f02")):
        ax.plot(np.degrees(alpha), 1e3 * Lw[:, k], color=c, label=f"wire {k + 1}")
    ax.axhline(1e3 * geo.length, color="0.5", lw=0.8, ls=":", label="straight (H)")
    ax.set_xlabel("bending direction α [deg] (paper convention)")
    ax.set_ylabel("wire length [mm]")
    ax.set_xticks(range(0, 361, 60))
    ax.set_xlim(0, 360)
    ax.legend(frameon=False, fontsize=8, ncol=4, loc="upper center", bbox_to_anchor=(0.5, -0.2))
    i_min = np.argmin(Lw, axis=0)
    summary = (f"Counterpart of Cojocaru et al. Fig 7: lengths of the three control wires at θ = 45° as the bending "
               f"direction α goes from 0° to 360° (Eq 4-11), for the study's section: H = {fmt(1e3 * geo.length)} mm, "
               f"hole-circle diameters D1 = {fmt(2e3 * geo.offset_base)} mm (base), D2 = {fmt(2e3 * geo.offset_tip)} mm "
               "(top) — the preset's assumed dimensions (the paper gives the shape of the curves, not these sizes). "
               f"Each wire is shortest where the section bends towards it (α = {', '.join(fmt(np.degrees(alpha[i])) for i in i_min)}°) "
               f"and ranges {fmt(1e3 * Lw.min())} … {fmt(1e3 * Lw.max())} mm; the curves are 120° apart.")
    return ReportFigure("cojocaru_fig7", "Wire lengths vs bending direction (Cojocaru Fig 7)", fig, summary)
