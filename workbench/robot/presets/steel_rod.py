"""A uniform steel rod with evenly spaced tendons: the reference robot of the validation tests.

No paper describes it: the studies that use it (quickstart, bending, sag_validity) choose its
dimensions; its material data are declared in :data:`ASSUMED` (with their sources), the study's
choices in :data:`SETTINGS` (the report's "Assumptions" section reads both,
:mod:`workbench.robot.presets` documents the convention).
"""

from __future__ import annotations


from ...assumptions import Assumption
from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for
from .per_section import per_section

__all__ = ["steel_rod", "GIVEN", "ASSUMED", "SETTINGS", "PER_SECTION", "SPRING_STEEL_YIELD", "WIRE_STRENGTH_05MM"]

#: 0.2 % proof stress of hardened and tempered spring steel 52CrMoV4 (1.7701, DIN 17221 / EN 10089),
#: Rp0.2 >= 1200 MPa (Saarstahl material data sheet 52CrMoV4) [Pa].
SPRING_STEEL_YIELD = 1.2e9
#: Minimum tensile strength of 0.5 mm (0.020 in) music wire, ASTM A228 Table 1: 350 ksi = 2413 MPa [Pa].
WIRE_STRENGTH_05MM = 2.41e9

#: Parameters a source paper gives (none: no paper describes this rod).
GIVEN: dict[str, str] = {}
#: Parameters assumed, with where the value comes from.
ASSUMED: tuple[Assumption, ...] = (
    Assumption("youngs_modulus", "steel, 210 GPa"),
    Assumption("density", "steel, 7850 kg/m^3"),
    Assumption("poisson_ratio", "steel, 0.3"),
    Assumption("yield_strength", "hardened and tempered spring steel 52CrMoV4 (EN 10089): Rp0.2 >= 1200 MPa "
                                 "(Saarstahl data sheet); a backbone stress ratio above 1 means the rod yields"),
    Assumption("tendon_stiffness", "steel wire of 0.5 mm (E A = 210 GPa x 0.196 mm^2 = 4.1e4 N)"),
    Assumption("tendon_youngs_modulus", "steel, 210 GPa (tendon area = tendon_stiffness / tendon_youngs_modulus)"),
    Assumption("tendon_strength", "music wire ASTM A228, 0.5 mm: minimum tensile strength 2413 MPa (350 ksi); a "
                                  "tendon stress ratio above 1 means the wire breaks (no safety factor)"),
)
#: Parameters each study chooses (its configuration, shown with the study).
SETTINGS: dict[str, str] = {k: "study choice" for k in (
    "length", "diameter", "n_sections", "tendon_count", "tendon_offset", "first_tendon_angle",
    "disks_per_section", "disk_mass", "gravity", "base_orientation", "payload_mass")}

#: Parameters that take one value per section as a list of ``n_sections`` entries (a scalar: every section).
PER_SECTION: tuple[str, ...] = (
    "diameter", "youngs_modulus", "density", "poisson_ratio", "yield_strength", "tendon_count", "tendon_offset",
    "tendon_stiffness", "tendon_youngs_modulus", "tendon_strength", "first_tendon_angle", "disks_per_section",
    "disk_mass")


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
    tendon_youngs_modulus: float = 210e9,
    tendon_strength: float = WIRE_STRENGTH_05MM,
    yield_strength: float = SPRING_STEEL_YIELD,
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
    tendon_youngs_modulus : float
        Tendon material modulus [Pa]: the tendon area is ``tendon_stiffness / tendon_youngs_modulus``.
    tendon_strength : float
        Tendon tensile strength [Pa] (default :data:`WIRE_STRENGTH_05MM`).
    yield_strength : float
        Backbone 0.2 % proof stress [Pa] (default :data:`SPRING_STEEL_YIELD`).
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
