"""Findings sentences of the series-parallel study (``registry.FIGURES["series_parallel"].findings``).

FK(IK) meets the target to solver precision at any mesh, so the IK round trip says nothing about
the physics' accuracy: that is in the insertion lengths.  These sentences give the largest
discretisation error of the lengths (``x.disc_length_error``) and the platform error it causes
(``x.disc_tip_error``), next to the round-trip residual, and the largest leg force.  Checked by the
report tier of ``tests/regression`` (four headings).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ...report.headline import baseline_cases
from ...report.load import numeric
from ...report.style import fmt

__all__ = ["findings"]


def _pose_text(row) -> str:
    pivot = row.get("p.pose.pivot")
    about = "" if pivot is None or (isinstance(pivot, float) and np.isnan(pivot)) else f" about {fmt(pivot)} h"
    return f"{row['p.pose.kind']} {row['p.pose.shape']} {fmt(float(row['p.pose.value']))}{about}"


def findings(results, cmp: pd.DataFrame) -> list[str]:
    ok = baseline_cases(results, results.ok)
    sp = ok[ok["model"] == "series_parallel"]
    if sp.empty:
        return []
    out = []
    if "x.disc_length_error" in sp and np.isfinite(numeric(sp["x.disc_length_error"])).any():
        dl, dt = numeric(sp["x.disc_length_error"]), numeric(sp["x.disc_tip_error"])
        i, j = int(np.nanargmax(dl)), int(np.nanargmax(dt))
        rt = numeric(sp["x.fk_position_error"]) if "x.fk_position_error" in sp else np.array([np.nan])
        out.append(f"IK insertion lengths: discretisation error up to {fmt(1e3 * dl[i])} mm ({_pose_text(sp.iloc[i])}); "
                   f"applied to the converged module these lengths would move the platform by up to "
                   f"{fmt(1e3 * dt[j])} mm ({_pose_text(sp.iloc[j])}), while FK(IK) meets the target to "
                   f"{fmt(np.nanmax(rt))} m (solver precision, not the physics' accuracy).")
        missing = int(np.sum(~np.isfinite(dl)))
        if missing:
            out.append(f"{missing} cases have no length estimate (a coarse IK failed: see disc_status in results.csv).")
    if "x.max_leg_compression" in sp:
        c = numeric(sp["x.max_leg_compression"])
        k = int(np.nanargmax(c))
        out.append(f"Largest leg compression {fmt(c[k])} N ({_pose_text(sp.iloc[k])}), "
                   f"{fmt(float(sp['x.buckling_ratio'].iloc[k]))} x the clamped-clamped Euler load of that leg.")
    return out
