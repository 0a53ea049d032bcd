"""A uniform steel rod with evenly spaced tendons: the reference robot of the validation tests."""

from __future__ import annotations


from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for

__all__ = ["steel_rod"]


def steel_rod(
    *,
    length: float = 0.8,
    diameter: float = 6e-3,
    youngs_modulus: float = 210e9,
    density: float = 7850.0,
    poisson_ratio: float = 0.3,
    n_sections: int = 1,
    tendon_count: int = 2,
    tendon_offset: float = 0.02,
    tendon_stiffness: float = 4.0e4,
    first_tendon_angle: float = 0.0,
    disks_per_section: int = 8,
    disk_mass: float = 0.0,
    gravity: float = 0.0,
    base_orientation: str = "vertical",
    payload_mass: float = 0.0,
) -> Robot:
    """Uniform circular steel rod split into equal sections.

    Parameters
    ----------
    length : float
        Total backbone length L [m] (default 0.8).
    diameter : float
        Rod diameter [m] (default 6 mm: EI = 13.36 N m^2 for steel).
    youngs_modulus, density, poisson_ratio : float
        Material [Pa], [kg/m^3], [-] (default structural steel).
    n_sections : int
        Number of equal-length sections, each with its own tendon group.
    tendon_count : int
        Tendons per section, evenly spaced in angle starting at ``first_tendon_angle``.
        2 tendons at 0 and pi give planar antagonistic bending.
    tendon_offset : float
        Tendon offset d from the centreline [m].
    tendon_stiffness : float
        Tendon axial stiffness EA_t [N].
    disks_per_section : int
        Spacer disks (eyelets) per section.
    disk_mass : float
        Mass of each disk [kg].
    gravity : float
        Magnitude of gravity [m/s^2] (acts along world -z).  Default 0.
    base_orientation : {"vertical", "horizontal", "upside_down"}
        Direction the robot points at its base (see :func:`base_rotation_for`).
    payload_mass : float
        Point mass at the tip [kg].
    """
    if int(n_sections) != n_sections or n_sections < 1:
        raise ValueError(f"n_sections must be a positive integer, got {n_sections!r}")
    rod = CrossSection.circular(diameter, youngs_modulus, density, poisson_ratio)
    sections = tuple(
        Section(
            length=length / n_sections,
            cross_section=rod,
            tendons=TendonGroup.evenly_spaced(tendon_count, tendon_offset, tendon_stiffness, first_tendon_angle),
            n_disks=disks_per_section,
            disk_mass=disk_mass,
        )
        for _ in range(int(n_sections))
    )
    return Robot(
        sections=sections,
        gravity=(0.0, 0.0, -float(gravity)),
        payload=Payload(mass=payload_mass),
        base_rotation=base_rotation_for(base_orientation),
        name="steel_rod",
    )
