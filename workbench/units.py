"""The one unit table: the readable name and unit of every parameter and result key.

:data:`UNITS` maps a key (``robot.length``, ``load.tensions``, ``solver.time_step``, a result
column such as ``tip_x``; parameters without their ``p.`` prefix) to ``(name, unit)``:

- ``unit``: ``""`` dimensionless, ``None`` a category or text, a string such as ``"m/s²"``
  (one spelling, the one the reports print), or :class:`UnitBy` when another column's value
  sets it (a pose amplitude: metres for a translation, radians for a rotation);
- ``name``: the readable name the report shows as ``"name [unit]"``; ``None`` when the key has
  none yet -- the report then shows the bare key without a unit, as for any key it does not
  know, while the stored field metadata and the study messages still carry the unit.

The table holds generic keys only.  A study kind or a figure set adds its own keys (its
scenario parameters, its extra result columns) through the ``units`` field of its registry row
(:class:`workbench.registry.KindInfo`, :class:`workbench.registry.FigureSet`): a
``"module:attribute"`` of a mapping of the same form, merged in on the first lookup of a key
the generic table does not hold.  :func:`quantity` is the one lookup; it serves the Parquet
field metadata (:mod:`workbench.study.columns`), the study messages
(:mod:`workbench.study.messages`), :func:`workbench.results.load` and the report
(:mod:`workbench.report.units`).  Imports only the registry (data), so validation stays free
of execution code.

A data file read by the workbench (a calibration study's measured columns) may give a length in
``mm`` or a force in ``mN``: :data:`CONVERSIONS` and :func:`si_factor` convert the spellings it
accepts to the SI unit of the table above.

Checked by ``tests/test_unit_table.py``, ``tests/report/test_units.py``,
``tests/study/test_messages.py`` and ``tests/measure/test_measure_data_units.py``.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Mapping, NamedTuple

__all__ = ["CONVERSIONS", "Quantity", "UNITS", "UnitBy", "quantity", "si_factor", "unit_of"]


class UnitBy(NamedTuple):
    """A unit set by another column: ``units[str(value of column)]`` (``column`` without ``p.``)."""

    column: str
    units: Mapping[str, str]


class Quantity(NamedTuple):
    """What :func:`quantity` returns: the readable name (or ``None``) and the unit."""

    name: str | None
    unit: str | UnitBy | None


#: key (without ``p.``) -> (readable name or None, unit); see the module docstring
UNITS: dict[str, tuple[str | None, str | UnitBy | None]] = {
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
    "robot.inner_diameter": ("inner diameter", "m"), "robot.shear_modulus": ("shear modulus G", "Pa"),
    "robot.shear_stiffness": ("shear stiffness GA", "N"), "robot.mass_per_length": ("mass per length", "kg/m"),
    "robot.yield_strength": ("yield strength", "Pa"),
    # load
    "load.bend_angle": ("bending angle θ", "rad"), "load.bend_plane": ("bending plane φ", "rad"),
    "load.pretension": ("pretension", "N"), "load.duration": ("duration", "s"), "load.ramp_time": ("ramp time", "s"),
    "load.mode": ("tendon command mode", None), "load.analysis": ("analysis", None),
    "load.tip_force": ("tip force (base frame)", "N"), "load.tip_torque": ("tip torque (base frame)", "N m"),
    "load.tensions": (None, "N"), "load.length_changes": (None, "m"),
    "load.start_delays": (None, "s"), "load.ramp_durations": (None, "s"),
    "derived.gravity_parameter": ("gravity parameter γ = qL³/EI", ""),
    # scenarios (the parameters of one scenario come with its figure set's row)
    "scenario.name": ("scenario", None),
    # solver
    "solver.tendon_model": ("tendon model", None), "solver.n_elements": ("elements", ""),
    "solver.time_step": ("time step", "s"), "solver.damping": ("damping", ""),
    "solver.max_case_seconds": (None, "s"), "solver.max_case_memory": (None, "bytes"),
    # derived report axes
    "kappaL": ("bending angle κL", "rad"), "gamma": ("gravity parameter γ = qL³/EI", ""), "d_over_L": ("tendon offset d/L", ""),
    # result columns (docs/architecture.md, "Result tables") and the report's error columns
    "tip_twist": ("tip twist", "rad"), "length_change": ("backbone length change", "m"),
    "tendon_stretch": ("tendon stretch", "m"), "tendon_tensions": ("tendon tension", "N"),
    "tendon_lengths": ("tendon length change", "m"), "tip_position": ("tip position (base frame)", "m"),
    "commands": ("tendon command", None), "wall_time": ("wall time", "s"),
    "tip_error_pct": ("tip position error", "% L"), "tip_error": ("tip position error", "m"),
    "orientation_error_deg": ("tip orientation error", "deg"), "shape_error_rms_pct": ("RMS shape error", "% L"),
    "robot_length": (None, "m"), "robot_gravity": (None, "m/s²"),
    "tip_x": (None, "m"), "tip_y": (None, "m"), "tip_z": (None, "m"),
    "tip_world_x": (None, "m"), "tip_world_y": (None, "m"), "tip_world_z": (None, "m"),
    "tip_frame": (None, "m"),  # homogeneous base <- tip transform: rotation dimensionless, translation [m]
    "iterations": (None, ""), "path_steps": ("load path steps", ""), "path_event": ("load path event", None),
    "path_event_fraction": ("load fraction of the path event", ""), "stations": (None, "m"), "positions": (None, "m"), "joint_angles": (None, "rad"),
    "time": (None, "s"), "backbone": (None, "m"), "backbone_time": (None, "s"),
}


@lru_cache(maxsize=1)
def _registered() -> dict[str, tuple[str | None, str | UnitBy | None]]:
    """The keys the registry rows add (``units`` of ``workbench.registry.table("kinds")`` and ``FIGURES``)."""
    from . import registry

    out: dict[str, tuple[str | None, str | UnitBy | None]] = {}
    rows = [*registry.table("kinds").values(), *registry.table("figures").values()]
    for target in dict.fromkeys(r.units for r in rows if r.units):
        for key, entry in registry.resolve(target).items():
            if key in UNITS or out.get(key, entry) != entry:
                raise ValueError(f"unit key {key!r} of {target} is already in the unit table with another entry")
            out[key] = tuple(entry)
    return out


def quantity(key: str) -> Quantity | None:
    """Name and unit of ``key`` (``p.`` prefix optional): the generic table, then the registered keys.

    ``None`` when no table knows the key (its unit is then left open, never guessed).
    """
    k = key[2:] if key.startswith("p.") else key
    entry = UNITS.get(k) or _registered().get(k)
    return Quantity(*entry) if entry is not None else None


def unit_of(key: str) -> str | None:
    """The fixed unit of ``key``: ``""`` dimensionless; ``None`` unknown, a category or set by another column."""
    q = quantity(key)
    return q.unit if q is not None and isinstance(q.unit, str) else None


#: unit spelling a data file may use -> (the SI unit of its kind, factor: value in SI = factor * value)
CONVERSIONS: dict[str, tuple[str, float]] = {
    "m": ("m", 1.0), "cm": ("m", 1e-2), "mm": ("m", 1e-3), "um": ("m", 1e-6), "µm": ("m", 1e-6),
    "in": ("m", 0.0254),
    "N": ("N", 1.0), "mN": ("N", 1e-3), "kN": ("N", 1e3),
    "rad": ("rad", 1.0), "deg": ("rad", 0.017453292519943295),
}


def si_factor(unit: str, si_unit: str) -> float:
    """The factor that turns a value in ``unit`` into ``si_unit`` (one of the SI units of :data:`CONVERSIONS`).

    Raises
    ------
    ValueError
        ``unit`` is unknown (the message lists the units of that kind) or of another kind
        (``"N"`` for a length); one line, for the caller to prefix with its key path.
    """
    known = [u for u, (si, _) in CONVERSIONS.items() if si == si_unit]
    if unit not in CONVERSIONS:
        raise ValueError(f"unknown unit {unit!r}; {si_unit} units: {', '.join(known)}")
    si, factor = CONVERSIONS[unit]
    if si != si_unit:
        raise ValueError(f"{unit!r} is a unit of {si}, not of {si_unit}; {si_unit} units: {', '.join(known)}")
    return factor
