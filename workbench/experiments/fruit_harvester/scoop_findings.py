"""The fluidic harvester study's findings, computed from its rows (never typed in): one sentence each.

:func:`findings` takes the ``(cc row, contact row)`` pairs and states the length change of each
actuation (CC and physics), where the fruit settles against Shao's grasp centre, and what the
centre-of-arc controller achieves.  Kept apart from the figures (as data for a report's "Findings"
section); the scoop figure quotes them.  Checked by ``tests/experiments/test_fruit_harvester_scoop.py``.
"""

from __future__ import annotations

import numpy as np

from ...report.style import fmt
from ..whole_arm_grasp.findings import column, span

__all__ = ["findings"]


def findings(pairs) -> tuple[str, ...]:
    """Sentences (no trailing period) stating the study's results; empty without pairs."""
    out = []
    for act in sorted({str(c["p.scenario.actuation"]) for c, _ in pairs}):
        sub = [(c, p) for c, p in pairs if str(c["p.scenario.actuation"]) == act]
        cc, ph = [c for c, _ in sub], [p for _, p in sub]
        L = column(cc, "robot_length")
        out.append(f"{act}: the section's length changes by {span(100 * column(ph, 'length_change') / L)} % of L in the "
                   f"physics, by {span(100 * column(cc, 'length_change') / L)} % in CC")
        obj = [p for c, p in sub if c.get("p.scenario.payload") == "object"]
        held = [p for p in obj if float(p.get("x.held", 0.0)) > 0]
        if obj:
            out.append(f"{act}: {len(held)} of {len(obj)} fruits held; they settle {span(column(held, 'x.settle_dz'), 1e3)} mm "
                       f"below and {span(np.abs(column(held, 'x.settle_dx')), 1e3)} mm beside the CC grasp centre")
        ex = np.abs(column(ph, "x.grasp_centre_error_x"))
        if np.isfinite(ex).any():
            sat = int(np.nansum(column(ph, "x.control_saturated") > 0))
            out.append(f"{act}: the centre-of-arc controller leaves |x| errors of {span(ex, 1e3)} mm and vertical errors "
                       f"of {span(np.abs(column(ph, 'x.grasp_centre_error_z')), 1e3)} mm (its Jacobian has no z row)"
                       + (f"; it saturated at the pressure limit in {sat} case(s)" if sat else ""))
    return tuple(out)
