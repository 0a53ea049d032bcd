"""Findings sentences of the wire-delay study (``registry.FIGURES["wire_delay"].findings``).

For every stored physics case at the baseline move time: the kinematic virtual compression of the
commands (exact: no discretisation), the backbone's own compression and the largest wire tension
over time, the stress ratio, and where the 3 s delay's peak tip error happens.  Numbers only from
the stored rows (the commands are recomputed from the case parameters with the functions the run
used, :mod:`.analysis`).  Checked by the report tier of ``tests/regression`` (four headings).
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import pandas as pd

from ...compare.table import array_cell
from ...report.headline import baseline_cases
from ...report.style import fmt, model_label
from ...study.params import section_params
from .analysis import cc_reading, commanded_wire_lengths, wire_geometry

__all__ = ["findings"]


def _case(row: Mapping[str, Any]) -> dict[str, float]:
    from ...study.build import build_load, build_robot
    from ...study.scenarios import load_with_scenario

    robot = build_robot(section_params(row, "robot"), section_params(row, "derived"))
    load = build_load(robot, load_with_scenario(robot, section_params(row, "load"), section_params(row, "scenario") or None))
    t = array_cell(row["time"])
    H = robot.sections[0].length
    cc = cc_reading(commanded_wire_lengths(robot, load.actuation, t, load.ramp_time), wire_geometry(robot))
    dl = array_cell(row.get("series.length_change"))
    T = array_cell(row.get("series.tendon_tensions"))
    return {
        "delay": float(row["p.scenario.delay"]), "e_min": 100.0 * float(np.min(cc.virtual_compression)) / H,
        "dl_min": 100.0 * float(np.min(dl)) / H if dl is not None else np.nan,
        "T_max": float(np.max(T)) if T is not None else np.nan,
        "ratio": float(row.get("x.stress_ratio", np.nan)),
    }


def findings(results, cmp: pd.DataFrame) -> list[str]:
    """One sentence per physics model: how the kinematic virtual compression is taken up."""
    ok = baseline_cases(results, results.ok)
    out = []
    for m in [m for m in results.models if m != "cc"]:
        rows = ok[(ok["model"] == m) & ok["time"].map(lambda v: array_cell(v) is not None)]
        if rows.empty:
            continue
        cases = sorted((_case(r.to_dict()) for _, r in rows.iterrows()), key=lambda c: c["delay"])
        parts = [f"delay {fmt(c['delay'])} s: virtual compression {fmt(c['e_min'])} % H, backbone "
                 f"{fmt(c['dl_min'])} % H, wires up to {fmt(c['T_max'])} N (stress / strength {fmt(c['ratio'])})"
                 for c in cases]
        out.append(f"{model_label(m)}, where the kinematic virtual compression goes (minimum over time of the "
                   f"commands' common offset e, exact, vs the beam's own length change): " + "; ".join(parts) + ".")
    return out
