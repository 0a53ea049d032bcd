"""A uniform steel rod with evenly spaced tendons: the formula of the parametric preset ``steel_rod.toml``.

No paper describes the rod: the studies that use it (quickstart, bending, sag_validity) choose its
dimensions.  Its parameters (defaults, units, and where each value comes from) are data in
``steel_rod.toml`` (``docs/robot-format.md``, "Presets"); this module holds the formula
:func:`derive` that maps them to the :class:`Robot`, and ``build_preset("steel_rod")``, the preset itself.
Checked by ``tests/robot/test_data_presets.py``.
"""

from __future__ import annotations

from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for
from .per_section import per_section

__all__ = ["derive"]


def derive(
    *,
    length: float,
    diameter: float | list[float],
    youngs_modulus: float | list[float],
    density: float | list[float],
    poisson_ratio: float | list[float],
    n_sections: int,
    tendon_count: int | list[int],
    tendon_offset: float | list[float],
    tendon_stiffness: float | list[float],
    tendon_youngs_modulus: float | list[float],
    tendon_strength: float | list[float],
    yield_strength: float | list[float],
    first_tendon_angle: float | list[float],
    disks_per_section: int | list[int],
    disk_mass: float | list[float],
    gravity: float,
    base_orientation: str,
    payload_mass: float,
) -> Robot:
    """Uniform circular steel rod split into equal sections (the formula of ``steel_rod.toml``).

    The parameters, their defaults, units and sources are data in ``steel_rod.toml``;
    ``build_preset("steel_rod", **params)`` (:mod:`workbench.robot.presets`) is that preset.

    Parameters
    ----------
    length : float
        Total backbone length L [m].
    diameter : float
        Rod diameter [m].
    youngs_modulus, density, poisson_ratio : float
        Material [Pa], [kg/m^3], [-].
    n_sections : int
        Number of equal-length sections, each with its own tendon group.
    tendon_count : int
        Tendons per section, evenly spaced in angle starting at ``first_tendon_angle``.
        2 tendons at 0 and pi give planar antagonistic bending.
    tendon_offset : float
        Tendon offset d from the centreline [m].
    tendon_stiffness : float
        Tendon axial stiffness EA_t [N].
    tendon_youngs_modulus : float
        Tendon material modulus [Pa]: the tendon area is ``tendon_stiffness / tendon_youngs_modulus``.
    tendon_strength : float
        Tendon tensile strength [Pa].
    yield_strength : float
        Backbone 0.2 % proof stress [Pa].
    disks_per_section : int
        Spacer disks (eyelets) per section.
    disk_mass : float
        Mass of each disk [kg].
    gravity : float
        Magnitude of gravity [m/s^2] (acts along world -z).
    base_orientation : {"vertical", "horizontal", "upside_down"}
        Direction the robot points at its base (see :func:`base_rotation_for`).
    payload_mass : float
        Point mass at the tip [kg].

    Every parameter in :data:`PER_SECTION` may also be a list of ``n_sections`` values, one per
    section (e.g. ``diameter=[1.4e-3, 1.0e-3]``); a scalar applies to every section.  Checked by
    ``tests/robot/test_per_section.py``.
    """
    if int(n_sections) != n_sections or n_sections < 1:
        raise ValueError(f"n_sections must be a positive integer, got {n_sections!r}")
    n = int(n_sections)
    v = {k: per_section(k, val, n) for k, val in (
        ("diameter", diameter), ("youngs_modulus", youngs_modulus), ("density", density),
        ("poisson_ratio", poisson_ratio), ("yield_strength", yield_strength), ("tendon_count", tendon_count),
        ("tendon_offset", tendon_offset), ("tendon_stiffness", tendon_stiffness),
        ("tendon_youngs_modulus", tendon_youngs_modulus), ("tendon_strength", tendon_strength),
        ("first_tendon_angle", first_tendon_angle), ("disks_per_section", disks_per_section),
        ("disk_mass", disk_mass))}
    sections = tuple(
        Section(
            length=length / n_sections,
            cross_section=CrossSection.circular(v["diameter"][k], v["youngs_modulus"][k], v["density"][k],
                                                v["poisson_ratio"][k], yield_strength=v["yield_strength"][k]),
            tendons=TendonGroup.evenly_spaced(v["tendon_count"][k], v["tendon_offset"][k], v["tendon_stiffness"][k],
                                              v["first_tendon_angle"][k],
                                              area=v["tendon_stiffness"][k] / v["tendon_youngs_modulus"][k],
                                              strength=v["tendon_strength"][k]),
            n_disks=v["disks_per_section"][k],
            disk_mass=v["disk_mass"][k],
        )
        for k in range(n)
    )
    return Robot(
        sections=sections,
        gravity=(0.0, 0.0, -float(gravity)),
        payload=Payload(mass=payload_mass),
        base_rotation=base_rotation_for(base_orientation),
        name="steel_rod",
    )
