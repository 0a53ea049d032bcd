"""Plausibility warnings: values far outside the range where the models mean anything (not errors).

``validate`` (and ``run``) print them as ``warning:`` lines and go on: a study may explore an
odd corner on purpose.  Each threshold is an assumption, stated here and in the message:

- :data:`MIN_SLENDERNESS` -- every model of the workbench is a rod theory (CC arc, beams,
  link chains): length / diameter below 5 is no slender rod (a 6 m diameter "rod" of 0.8 m).
- :data:`MAX_BENDING_STRAIN` -- the CC arc of the tendon commands bends section ``j`` to
  curvature ``kappa_j``; its surface strain ``kappa_j d_j / 2`` above 1 % (5 x the yield strain
  of steel) is beyond the elastic range of metals, while every model here is linear elastic
  (3 340 N on a 6 mm steel rod: 1.5 %, 3 150 MPa).  Only for solid rods of a stated material
  (:func:`solid_rod`); superelastic NiTi reaches several percent: the message says so.
- :data:`MAX_TURNS` -- a CC bend of more than one full turn per robot (``sum kappa_j L_j > 2 pi``)
  makes the robot pass through itself.

The CC arc comes from :func:`workbench.models.cc.arc_from_actuation` (pure numpy).  Checked by
``tests/study/test_capabilities.py``.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

__all__ = ["MAX_BENDING_STRAIN", "MAX_TURNS", "MIN_SLENDERNESS", "plausibility_warnings", "solid_rod"]

MIN_SLENDERNESS = 5.0
MAX_BENDING_STRAIN = 0.01
MAX_TURNS = 1.0


def _diameter(cs: Any) -> float:
    """Outer diameter [m]: the declared one, else that of the solid circle of the same area."""
    return float(cs.diameter) if getattr(cs, "diameter", None) else math.sqrt(4.0 * float(cs.A) / math.pi)


def solid_rod(robot_params: Mapping[str, Any]) -> bool:
    """The preset is a solid rod of a stated material (``diameter`` and ``youngs_modulus`` parameters).

    Presets of real robots describe an equivalent section (springs, disks, links): a surface
    strain of that section means nothing, so the strain warning is for solid rods only.
    """
    return "diameter" in robot_params and "youngs_modulus" in robot_params


def plausibility_warnings(robot: Any, load_case: Any, params: Mapping[str, Any]) -> list[str]:
    """The warnings of one built case (``"<key>: <what is implausible> ..."``, one line each)."""
    rp, lp = params.get("robot", {}), params.get("load", {})
    out = []
    d = max(_diameter(s.cross_section) for s in robot.sections)
    slender = robot.length / d
    if slender < MIN_SLENDERNESS:
        key = "robot.diameter" if "diameter" in rp else "robot.length"
        out.append(f"{key}: length / diameter = {slender:.3g} (length {robot.length:g} m, diameter {d:g} m) is no "
                   f"slender rod; every model here is a rod theory (warned below L/d = {MIN_SLENDERNESS:g})")
    act = load_case.actuation
    if act is None or not robot.n_tendons:
        return out
    try:
        from ..models.cc import arc_from_actuation

        kappa, _, ell = arc_from_actuation(robot, act)
    except Exception:  # noqa: BLE001 - an infeasible command is reported by the checks, not here
        return out
    key = next((f"load.{k}" for k in ("tensions", "length_changes", "bend_angle") if lp.get(k) is not None), "load")
    strains = [abs(float(k)) * _diameter(s.cross_section) / 2.0 for k, s in zip(kappa, robot.sections)]
    j = int(np.argmax(strains))
    if solid_rod(rp) and strains[j] > MAX_BENDING_STRAIN:
        stress = float(rp["youngs_modulus"]) * strains[j]
        out.append(f"{key}: the CC arc of these commands bends section {j} to kappa = {abs(kappa[j]):.3g} 1/m: "
                   f"surface strain kappa d / 2 = {100 * strains[j]:.2g} %, stress E kappa d / 2 = {stress / 1e6:.3g} "
                   f"MPa, beyond the elastic range of metals (warned above {100 * MAX_BENDING_STRAIN:g} %; "
                   f"superelastic NiTi reaches ~6 %); the models are linear elastic")
    turns = float(np.sum(np.abs(kappa) * ell)) / (2.0 * math.pi)
    if turns > MAX_TURNS * (1.0 + 1e-4):
        out.append(f"{key}: the CC arc of these commands bends the robot by {turns:.3g} full turns "
                   f"(sum kappa L = {2 * math.pi * turns:.3g} rad > 2 pi): it would pass through itself")
    return out
