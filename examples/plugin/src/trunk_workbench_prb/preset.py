"""A two-section NiTi rod of the sizes of Rao et al. (2021), with one antagonistic tendon pair per section.

P. Rao, Q. Peyron, S. Lilge, J. Burgner-Kahrs, "How to Model Tendon-Driven Continuum Robots and
Benchmark Modelling Performance", Frontiers in Robotics and AI 7 (2021) 630245: two sections of
0.2 m, a NiTi backbone of 1.4 mm diameter with E = 54 GPa, ten disks per section and tendons at a
pitch radius of 10 mm.  Their robot has three tendons per section (at 90, -30 and 210 deg); this
preset puts a planar antagonistic pair (0 and 180 deg) in every section instead, so that planar
models (such as this plug-in's ``prb_chain``) apply -- a study choice, declared in :data:`SETTINGS`.
Sources of each parameter: :data:`GIVEN`, :data:`ASSUMED`, :data:`SETTINGS` (the convention of
:mod:`workbench.robot.presets`, read by the report's Assumptions table).
"""

from __future__ import annotations

from workbench.assumptions import Assumption
from workbench.robot import CrossSection, Payload, Robot, Section, TendonGroup, base_rotation_for

__all__ = ["ASSUMED", "GIVEN", "SETTINGS", "prb_niti_pair"]

_RAO = "Rao et al. 2021 (Front. Robot. AI 7:630245)"

#: Parameters the source paper gives.
GIVEN: dict[str, str] = {
    "section_length": f"{_RAO}: 0.2 m per section",
    "n_sections": f"{_RAO}: two sections",
    "diameter": f"{_RAO}: NiTi backbone, 1.4 mm",
    "youngs_modulus": f"{_RAO}: 54 GPa",
    "tendon_offset": f"{_RAO}: tendon pitch radius 10 mm",
    "disks_per_section": f"{_RAO}: ten disks per section",
}
#: Parameters assumed, with where the value comes from.
ASSUMED: tuple[Assumption, ...] = (
    Assumption("density", "NiTi, 6450 kg/m^3 (typical data-sheet value of binary nitinol)"),
    Assumption("poisson_ratio", "NiTi, 0.33 (typical data-sheet value of binary nitinol)"),
    Assumption("tendon_stiffness", "steel wire of 0.3 mm: E A = 210 GPa x 0.0707 mm^2 = 1.48e4 N"),
    Assumption("disk_mass", "0: disk masses are not part of this preset"),
)
#: Parameters each study chooses.
SETTINGS: dict[str, str] = {k: "study choice" for k in ("gravity", "base_orientation", "payload_mass")}


def prb_niti_pair(
    *,
    section_length: float = 0.2,
    n_sections: int = 2,
    diameter: float = 1.4e-3,
    youngs_modulus: float = 54e9,
    density: float = 6450.0,
    poisson_ratio: float = 0.33,
    tendon_offset: float = 0.01,
    tendon_stiffness: float = 1.48e4,
    disks_per_section: int = 10,
    disk_mass: float = 0.0,
    gravity: float = 0.0,
    base_orientation: str = "vertical",
    payload_mass: float = 0.0,
) -> Robot:
    """Equal NiTi sections, each with a tendon pair at 0 and pi terminating at its end.

    Parameters
    ----------
    section_length : float
        Length of each section [m].
    n_sections : int
        Number of sections.
    diameter, youngs_modulus, density, poisson_ratio : float
        Backbone rod [m], [Pa], [kg/m^3], [-].
    tendon_offset : float
        Tendon offset from the centreline [m].
    tendon_stiffness : float
        Tendon axial stiffness EA_t [N].
    disks_per_section : int
        Spacer disks per section.
    disk_mass : float
        Mass of each disk [kg].
    gravity : float
        Magnitude of gravity [m/s^2] along world -z.
    base_orientation : {"vertical", "horizontal", "upside_down"}
        Direction the robot points at its base.
    payload_mass : float
        Point mass at the tip [kg].
    """
    if int(n_sections) != n_sections or n_sections < 1:
        raise ValueError(f"n_sections must be a positive integer, got {n_sections!r}")
    rod = CrossSection.circular(diameter, youngs_modulus, density, poisson_ratio)
    pair = TendonGroup.evenly_spaced(2, tendon_offset, tendon_stiffness)
    sections = tuple(Section(length=section_length, cross_section=rod, tendons=pair, n_disks=disks_per_section,
                             disk_mass=disk_mass) for _ in range(int(n_sections)))
    return Robot(sections=sections, gravity=(0.0, 0.0, -float(gravity)), payload=Payload(mass=payload_mass),
                 base_rotation=base_rotation_for(base_orientation))
