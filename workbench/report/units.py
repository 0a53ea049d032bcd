"""The unit table: a readable label with its unit for every parameter and result key the report shows.

A study's ``[report] labels`` win; otherwise :func:`label_of` looks the key up here (``p.`` prefix
optional): ``robot.*``, ``load.*``, ``scenario.*``, ``motion.*``, ``solver.*``, ``geometry.*``
parameters, result columns (``tip_twist``, ``length_change``, ...), ``series.*`` names and
``x.*`` extras.  A key the table does not know keeps its name, with the unit left open (never
a guessed unit).  Keys whose unit depends on another column (``motion.value``: metres for a
translation, radians for a rotation) are in :data:`UNIT_DEPENDS_ON`; figures never put two units
on one axis (:func:`unit_groups`).  Checked by ``tests/report/test_units.py``.
"""

from __future__ import annotations

from typing import Mapping

import pandas as pd

__all__ = ["UNITS", "UNIT_DEPENDS_ON", "label_of", "unit_of", "unit_groups"]

#: key (without ``p.``) -> (readable name, unit; "" = dimensionless, None = category / no unit)
UNITS: dict[str, tuple[str, str | None]] = {
    # robot
    "robot.length": ("robot length L", "m"), "robot.total_length": ("robot length L", "m"),
    "robot.section_length": ("section length", "m"), "robot.n_sections": ("sections", ""),
    "robot.diameter": ("backbone diameter", "m"), "robot.rod_diameter": ("backbone diameter", "m"),
    "robot.outer_diameter": ("outer diameter", "m"), "robot.youngs_modulus": ("Young's modulus E", "Pa"),
    "robot.density": ("density", "kg/m³"), "robot.poisson_ratio": ("Poisson ratio", ""),
    "robot.gravity": ("gravity g", "m/s²"), "robot.base_orientation": ("base orientation", None),
    "robot.tendon_offset": ("tendon offset d", "m"), "robot.tendon_count": ("tendons per section", ""),
    "robot.tendon_stiffness": ("tendon stiffness EA_t", "N"), "robot.disks_per_section": ("disks per section", ""),
    "robot.payload_mass": ("payload mass", "kg"), "robot.disk_mass": ("disk mass", "kg"),
    "robot.total_mass": ("robot mass", "kg"), "robot.n_plates": ("plates", ""),
    "robot.bending_stiffness": ("bending stiffness EI", "N m²"), "robot.axial_stiffness": ("axial stiffness EA", "N"),
    "robot.torsional_stiffness": ("torsional stiffness GJ", "N m²"), "robot.joint_stiffness": ("joint stiffness", "N m/rad"),
    "robot.wire_diameter": ("wire diameter", "m"), "robot.preset": ("robot preset", None),
    "robot.planar": ("planar", None),
    # load
    "load.bend_angle": ("bending angle θ", "rad"), "load.bend_plane": ("bending plane φ", "rad"),
    "load.pretension": ("pretension", "N"), "load.duration": ("duration", "s"), "load.ramp_time": ("ramp time", "s"),
    "load.mode": ("tendon command mode", None), "load.analysis": ("analysis", None),
    "load.tip_force": ("tip force (base frame)", "N"), "load.tip_torque": ("tip torque (base frame)", "N m"),
    "derived.gravity_parameter": ("gravity parameter γ = qL³/EI", ""),
    # scenarios
    "scenario.delay": ("wire delay", "s"), "scenario.move_time": ("wire move time", "s"),
    "scenario.settle_time": ("settling time", "s"), "scenario.theta": ("bending angle θ", "rad"),
    "scenario.alpha": ("bending direction α", "rad"), "scenario.shape": ("trajectory", None),
    "scenario.sample": ("snapshot", ""), "scenario.n_samples": ("snapshots", ""),
    "scenario.delayed_wire": ("delayed wire", ""), "scenario.name": ("scenario", None),
    # series-parallel motions
    "motion.kind": ("motion kind", None), "motion.shape": ("motion", None), "motion.value": ("motion amplitude", None),
    "motion.pivot": ("pivot height / module height", ""), "motion.n_modules": ("modules", ""),
    "motion.plane": ("motion plane", "rad"),
    # solver
    "solver.tendon_model": ("tendon model", None), "solver.n_elements": ("elements", ""),
    "solver.time_step": ("time step", "s"), "solver.damping": ("damping", ""),
    # derived report axes
    "kappaL": ("bending angle κL", "rad"), "gamma": ("gravity parameter γ = qL³/EI", ""), "d_over_L": ("tendon offset d/L", ""),
    # result columns and series
    "tip_twist": ("tip twist", "rad"), "length_change": ("backbone length change", "m"),
    "tendon_stretch": ("tendon stretch", "m"), "tendon_tensions": ("tendon tension", "N"),
    "tendon_lengths": ("tendon length change", "m"), "tip_position": ("tip position (base frame)", "m"),
    "commands": ("tendon command", None), "wall_time": ("wall time", "s"),
    "tip_error_pct": ("tip position error", "% L"), "tip_error": ("tip position error", "m"),
    "orientation_error_deg": ("tip orientation error", "deg"), "shape_error_rms_pct": ("RMS shape error", "% L"),
    # extras
    "x.max_leg_compression": ("largest leg compression", "N"), "x.buckling_ratio": ("compression / Euler load", ""),
    "x.min_leg_gap": ("smallest gap between legs", "m"), "x.fk_position_error": ("FK position error", "m"),
    "x.fk_rotation_error": ("FK rotation error", "rad"), "x.cc_rms_error": ("CC fit RMS error", "m"),
    "x.cc_max_error": ("CC fit max error", "m"), "x.cc_curvature": ("CC fit curvature", "1/m"),
}

#: keys whose unit is set by another column's value: key -> (column, {value: unit})
UNIT_DEPENDS_ON: dict[str, tuple[str, dict[str, str]]] = {
    "motion.value": ("motion.shape", {"x": "m", "y": "m", "z": "m", "rx": "rad", "ry": "rad", "rz": "rad",
                                      "translation": "m", "s_shape": "rad", "bending": "rad"}),
}


def _key(col: str) -> str:
    return col[2:] if col.startswith("p.") else col


def unit_of(col: str) -> str | None:
    """The unit of ``col`` ("" dimensionless, ``None`` unknown or categorical)."""
    entry = UNITS.get(_key(col))
    return entry[1] if entry else None


def label_of(col: str, labels: Mapping[str, str] | None = None, unit: str | None = None) -> str:
    """Axis label of ``col``: the study's label, else ``"name [unit]"`` from :data:`UNITS`, else the key.

    ``unit`` overrides the table's unit (for :data:`UNIT_DEPENDS_ON` keys, per group).
    """
    if labels and col in labels:
        return labels[col]
    k = _key(col)
    name, u = UNITS.get(k, (k, None))
    u = unit if unit is not None else u
    return f"{name} [{u}]" if u else name


def unit_groups(df: pd.DataFrame, col: str) -> dict[str | None, pd.Index]:
    """Row index of ``df`` per unit of ``col``: one group unless the unit depends on another column.

    Rows whose unit the table does not know form the group ``None``.
    """
    dep = UNIT_DEPENDS_ON.get(_key(col))
    if dep is None:
        return {unit_of(col): df.index}
    other, units = dep
    oc = other if other in df.columns else f"p.{other}"
    if oc not in df.columns:
        return {None: df.index}
    u = df[oc].astype(str).map(units)
    return {k: df.index[(u == k) if k is not None else u.isna()] for k in dict.fromkeys(u.where(u.notna(), None))}
