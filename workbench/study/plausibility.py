"""Plausibility warnings: values far outside the range where the models mean anything (not errors).

``validate`` (and ``run``) print them as ``warning:`` lines and go on: a study may explore an
odd corner on purpose.  Each threshold is an assumption, stated here and in the message:

- :data:`MIN_SLENDERNESS` -- every model of the workbench is a rod theory (CC arc, beams,
  link chains): length / diameter below 5 is no slender rod (a 6 m diameter "rod" of 0.8 m).
- :data:`MAX_STRESS_RATIO` -- the stresses the CC arc of the commands implies
  (:func:`workbench.models.cc.arc_stresses`: backbone bending ``EI kappa / W`` plus axial
  ``sum T / A``, combined as :mod:`workbench.models.stress` does; tendon ``T / A_t``) above the
  strength the robot declares (``CrossSection.yield_strength``, ``TendonGroup.strength``, from the
  preset or the study): the rod yields or the wire breaks, while every model here is linear
  elastic.  The ratio 1 has no safety factor.  3 340 N on the 6 mm steel rod (tendon offset 20 mm,
  0.5 mm wire): backbone 3 268 MPa vs 1 200 MPa, wire 17 535 MPa vs 2 410 MPa.  The line names the
  strength's source (the preset parameter and its declared source, or the study's override).
  Where no strength is declared nothing is said.
- :data:`MAX_BENDING_STRAIN` -- for a section whose yield strength is unknown: the CC arc bends
  section ``j`` to curvature ``kappa_j``; its surface strain ``kappa_j d_j / 2`` above 1 % (5 x the
  yield strain of steel) is beyond the elastic range of metals.  Only for solid rods of a stated
  material (:func:`solid_rod`); superelastic NiTi reaches several percent: the message says so.
- :data:`MAX_TURNS` -- a CC bend of more than one full turn per robot (``sum kappa_j L_j > 2 pi``)
  makes the robot pass through itself.

The CC arc comes from :func:`workbench.models.cc.arc_from_actuation` (pure numpy).  Checked by
``tests/study/test_capabilities.py``.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

__all__ = ["MAX_BENDING_STRAIN", "MAX_STRESS_RATIO", "MAX_TURNS", "MIN_SLENDERNESS", "plausibility_warnings",
           "solid_rod", "strength_source"]

MIN_SLENDERNESS = 5.0
MAX_BENDING_STRAIN = 0.01
MAX_STRESS_RATIO = 1.0
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


def _mpa(x: float) -> str:
    return f"{x / 1e6:.0f} MPa" if abs(x) >= 1e9 else f"{x / 1e6:.3g} MPa"


def strength_source(robot_params: Mapping[str, Any], value: float, tendon: bool) -> str:
    """Where a declared strength comes from: the preset parameter that holds ``value`` and its source.

    ``"robot.yield_strength of preset 'steel_rod': <its declared source>"``, or
    ``"robot.<key> set in the study"`` when the study overrides the preset's default, or
    ``"preset '<name>'"`` when no parameter holds the value (a strength the preset fixes).
    """
    name = robot_params.get("preset", "?")
    keys = [k for k, v in robot_params.items() if "strength" in k and ("yield" in k) != tendon
            and isinstance(v, (int, float)) and not isinstance(v, bool)]
    key = next((k for k in keys if math.isclose(float(robot_params[k]), value, rel_tol=1e-9)), None)
    if key is None:
        return f"preset {name!r}"
    try:
        from ..robot.presets import preset_parameters, preset_sources

        default, sources = preset_parameters(name).get(key), preset_sources(name)
    except Exception:  # noqa: BLE001 - an unknown preset is reported by the checks
        return f"robot.{key}"
    if default is None or not math.isclose(float(default), value, rel_tol=1e-9):
        return f"robot.{key} set in the study"
    text = sources["given"].get(key) or sources["assumed"].get(key)
    return f"robot.{key} of preset {name!r}" + (f": {text.split(';')[0].strip()}" if text else "")


def _stress_warnings(robot: Any, rp: Mapping[str, Any], key: str, kappa, act) -> tuple[list[str], np.ndarray]:
    """The CC stress-vs-strength warnings, and per section whether its yield strength is known."""
    from ..models.cc import arc_stresses

    tensions = np.asarray(act.values, dtype=float) if act.mode == "tension" else np.full(robot.n_tendons, np.nan)
    st = arc_stresses(robot, kappa, tensions)
    out: list[str] = []
    known = np.zeros(robot.n_sections, dtype=bool)
    if st.axial is not None:
        known = np.isfinite(st.yield_strength)
        ratio = np.where(known, st.backbone / np.where(known, st.yield_strength, 1.0), 0.0)
        j = int(np.argmax(ratio))
        if ratio[j] > MAX_STRESS_RATIO:
            y = float(st.yield_strength[j])
            parts = (f"bending EI kappa / W {_mpa(st.bending[j])} + axial sum T / A {_mpa(st.axial[j])}"
                     if act.mode == "tension" else "bending EI kappa / W; CC predicts no tendon forces under length "
                                                   "control")
            out.append(f"{key}: the CC arc of these commands stresses the backbone of section {j} to "
                       f"{_mpa(st.backbone[j])} ({parts}), {ratio[j]:.3g} x its yield strength {_mpa(y)} "
                       f"({strength_source(rp, y, tendon=False)}); the rod would yield, the models are linear elastic")
    if st.tendon is not None:
        ok = np.isfinite(st.tendon_strength)
        ratio = np.where(ok, st.tendon / np.where(ok, st.tendon_strength, 1.0), 0.0)
        i = int(np.argmax(ratio)) if ratio.size else 0
        if ratio.size and ratio[i] > MAX_STRESS_RATIO:
            sec, _, group = robot.tendon_table()[i]
            s_ = float(st.tendon_strength[i])
            out.append(f"{key}: the CC tension {tensions[i]:.4g} N of tendon {i} (section {sec}) on its "
                       f"{group.area * 1e6:.3g} mm^2 wire is a stress T / A_t = {_mpa(st.tendon[i])}, "
                       f"{ratio[i]:.3g} x the tendon strength {_mpa(s_)} "
                       f"({strength_source(rp, s_, tendon=True)}); the wire would break")
    return out, known


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
    stress_lines, strength_known = _stress_warnings(robot, rp, key, kappa, act)
    out.extend(stress_lines)
    strains = [abs(float(k)) * _diameter(s.cross_section) / 2.0 for k, s in zip(kappa, robot.sections)]
    j = int(np.argmax(strains))
    if solid_rod(rp) and strains[j] > MAX_BENDING_STRAIN and not strength_known[j]:
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
