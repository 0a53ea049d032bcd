"""The fruit-harvesting continuum section of Shao et al. (paper 002_) as an equivalent rod."""

from __future__ import annotations

from ...assumptions import Assumption
from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for

__all__ = ["shao_harvester", "GIVEN", "ASSUMED", "SETTINGS"]

#: Parameters the paper gives (Sec. 4).
GIVEN: dict[str, str] = {
    "length": "paper Sec. 4: section II is 400 mm long",
    "total_mass": "paper Sec. 4: 230 g",
    "n_plates": "paper Sec. 4: actuator groups between five plates (4 intervals)",
}
#: Parameters the paper does not give, with where the value comes from.
ASSUMED: tuple[Assumption, ...] = (
    Assumption("bending_stiffness", "EI = 0.3 N m^2 (plausible for a silicone/FPA section: gamma = q L^3 / EI = "
                                    "1.2, visible sag as in the photos); the fruit_harvester study's sensitivity "
                                    "sweep varies it"),
    Assumption("axial_stiffness", "EA = 2 kN (not given)"),
    Assumption("torsional_stiffness", "GJ = 0.2 N m^2 (not given)"),
    Assumption("outer_diameter", "60 mm (drawing only; not given)"),
    Assumption("actuator_offset", "22 mm: the equivalent tendons stand in for the pneumatic actuator groups (not "
                                  "given)"),
    Assumption("actuator_stiffness", "2 kN equivalent tendon stiffness (not given)"),
)
#: Parameters each study chooses.
SETTINGS: dict[str, str] = {k: "study choice" for k in ("gravity", "base_orientation", "payload_mass")}


def shao_harvester(
    *,
    length: float = 0.4,
    total_mass: float = 0.23,
    bending_stiffness: float = 0.3,
    axial_stiffness: float = 2.0e3,
    torsional_stiffness: float = 0.2,
    outer_diameter: float = 0.06,
    actuator_offset: float = 0.022,
    actuator_stiffness: float = 2.0e3,
    n_plates: int = 4,
    gravity: float = 9.81,
    base_orientation: str = "upside_down",
    payload_mass: float = 0.0,
) -> Robot:
    """Section II of Shao et al.'s harvester: 400 mm, 230 g (paper 002_, Sec. 4).

    The prototype bends with twelve pneumatic actuators (FPAs) in three groups at 120 deg
    between five plates.  The workbench represents it as a uniform elastic rod driven by
    three equivalent tendons at 120 deg whose tension produces the same bending moment as
    the pressurised actuator groups; only the kinematic comparison (CC vs an elastic
    backbone under its own weight and a payload) is taken from the paper.

    Values the paper gives: ``length`` (400 mm) and ``total_mass`` (230 g, spread uniformly);
    objects up to 200 g and 100 mm.  **Assumed** (the paper does not state them; plausible
    for a silicone/FPA section of this size, exposed so studies can sweep them):
    ``bending_stiffness`` EI = 0.3 N m^2 (gives a gravity parameter
    gamma = q L^3 / EI = 1.2, i.e. visible sag, as the photos show),
    ``axial_stiffness`` 2 kN, ``torsional_stiffness`` 0.2 N m^2, ``outer_diameter`` 60 mm,
    actuator offset 22 mm, equivalent actuator stiffness 2 kN, 4 plate intervals.

    The default mounting is ``"upside_down"`` (the harvester hangs from its base and scoops
    fruit below it).  No stresses: the rod and its tendons are equivalents of pneumatic
    actuators (no stress geometry, no strengths; the admissible load is an actuator pressure the
    paper does not give).
    """
    m_per_l = float(total_mass) / float(length)
    cs = CrossSection(
        EI=bending_stiffness,
        EA=axial_stiffness,
        GJ=torsional_stiffness,
        mass_per_length=m_per_l,
        diameter=outer_diameter,
    )
    section = Section(
        length=length,
        cross_section=cs,
        tendons=TendonGroup.evenly_spaced(3, actuator_offset, actuator_stiffness),
        n_disks=n_plates,
    )
    return Robot(
        sections=(section,),
        gravity=(0.0, 0.0, -float(gravity)),
        payload=Payload(mass=payload_mass),
        base_rotation=base_rotation_for(base_orientation),
        name="shao_harvester",
    )
