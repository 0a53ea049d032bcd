"""Hannan & Walker's segmented 'elephant trunk' (papers/000_, Sec. 3).

From the paper: total length 83.82 cm; 16 two-DOF joints (32 DOF) in 4 sections of 4 joints;
section diameters 10.16 / 8.89 / 7.62 / 6.35 cm; springs between adjacent segments supply the
bending stiffness; per section two antagonistic cable pairs, 90 degrees apart, terminate on the
section's last (every fourth) segment.

Not given in the paper and chosen here as documented, plausible defaults (all parameters):

* equal section lengths (83.82 / 4 cm), joints equally spaced (5.24 cm);
* per-joint rotational spring stiffness per section ``joint_stiffness`` (120 / 80 / 50 /
  25 N m/rad: under self-weight the horizontal trunk's joints turn by 0-3.1 degrees and the tip
  drops by 0.21 m, computed with :mod:`workbench.physics.spring_link`, N = 16);
* section masses ``section_masses`` (0.8 / 0.6 / 0.45 / 0.3 kg: hollow conduit segments, springs
  and plates), spread uniformly along each section;
* cables at the segment radius ``w`` of their own section (Eq. 1's ``w``) throughout their
  routing (the robot description has one offset per tendon), steel wire ``EA_t = 1.6e5 N``
  (about 1 mm diameter).

Spring-link equivalence: the description is the generic :class:`~workbench.robot.Robot`; a joint
spring ``k`` in a section of length ``l`` with ``n = 4`` joints is written as the equivalent rod
stiffness ``EI = k * l / n`` (so :mod:`workbench.physics.spring_link` with
``options.n_elements = 16`` reproduces the joint springs exactly, because it uses
``k = EI / ds`` with ``ds = l / 4``).  Axial stiffness ``EA`` is set high (the segments do not
compress) and the torsional stiffness ``GJ`` equal to ``EI`` (torsion is not modelled by the
planar chain).
"""

from __future__ import annotations

import math
from typing import Sequence

from ...assumptions import Assumption
from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for

__all__ = ["hannan_walker", "HW_TOTAL_LENGTH", "HW_DIAMETERS", "HW_JOINTS_PER_SECTION", "GIVEN", "ASSUMED",
           "SETTINGS"]

#: Total backbone length [m] (paper, Sec. 3).
HW_TOTAL_LENGTH = 0.8382
#: Section diameters base to tip [m] (paper, Sec. 3).
HW_DIAMETERS = (0.1016, 0.0889, 0.0762, 0.0635)
#: Joints per section (paper, Sec. 3: 16 joints, 4 sections).
HW_JOINTS_PER_SECTION = 4

#: Parameters the paper gives (Sec. 3).
GIVEN: dict[str, str] = {
    "total_length": "paper Sec. 3: 83.82 cm",
    "diameters": "paper Sec. 3: 10.16 / 8.89 / 7.62 / 6.35 cm",
    "planar": "paper Sec. 5: the planar experiments use one antagonistic cable pair per section",
}
#: Parameters the paper does not give, with where the value comes from.
ASSUMED: tuple[Assumption, ...] = (
    Assumption("joint_stiffness", "120 / 80 / 50 / 25 N m/rad per joint (plausible: under self-weight the "
                                  "horizontal trunk's joints turn by 0-3.1 deg); the paper: springs between "
                                  "segments, no values"),
    Assumption("section_masses", "0.8 / 0.6 / 0.45 / 0.3 kg (hollow conduit segments, springs, plates; not given)"),
    Assumption("tendon_stiffness", "cable E A_t = 1.6e5 N, a 1 mm steel wire (not given): CC's accuracy under "
                                   "gravity depends on it (see the hannan_walker study's sensitivity sweep)"),
    Assumption("tendon_area", "1 mm cable, 0.785 mm^2 (not given)"),
    Assumption("tendon_strength", "music wire ASTM A228, 1.0 mm: minimum tensile strength 2172 MPa (315 ksi)"),
    Assumption("axial_stiffness", "1e7 N: the segments do not compress (not given)"),
)
#: Parameters each study chooses.
SETTINGS: dict[str, str] = {k: "study choice" for k in ("gravity", "base_orientation", "payload_mass")}


def _four(name: str, values: Sequence[float]) -> tuple[float, ...]:
    v = tuple(float(x) for x in values)
    if len(v) != 4:
        raise ValueError(f"{name} must hold 4 values (one per section), got {len(v)}")
    if any(not math.isfinite(x) or x <= 0 for x in v):
        raise ValueError(f"{name} must be finite and > 0, got {list(v)}")
    return v


def hannan_walker(
    *,
    total_length: float = HW_TOTAL_LENGTH,
    diameters: Sequence[float] = HW_DIAMETERS,
    joint_stiffness: Sequence[float] = (120.0, 80.0, 50.0, 25.0),
    section_masses: Sequence[float] = (0.8, 0.6, 0.45, 0.3),
    tendon_stiffness: float = 1.6e5,
    tendon_area: float = 7.85e-7,
    tendon_strength: float = 2.17e9,  # music wire ASTM A228, 1.0 mm (ASSUMED above)
    planar: bool = True,
    gravity: float = 9.81,
    base_orientation: str = "vertical",
    payload_mass: float = 0.0,
    axial_stiffness: float = 1.0e7,
) -> Robot:
    """The Hannan & Walker trunk as a 4-section robot description.

    Parameters
    ----------
    total_length : float
        Backbone length [m] (paper: 0.8382).
    diameters : sequence of 4 float
        Section (segment) diameters [m], base to tip (paper: 0.1016, 0.0889, 0.0762, 0.0635).
    joint_stiffness : sequence of 4 float
        Rotational spring stiffness of each joint of a section [N m/rad] (assumed).
    section_masses : sequence of 4 float
        Mass of each section [kg] (assumed), uniform along the section.
    tendon_stiffness : float
        Cable axial stiffness ``EA_t`` [N].
    tendon_area, tendon_strength : float
        Cable cross-section [m^2] and tensile strength [Pa] for the tendon stress (see :data:`ASSUMED`);
        the backbone (springs between segments) has no stress geometry: no backbone stress.
    planar : bool
        ``True``: only the antagonistic pair in the base x-z plane (sigma = 0, pi) per section
        (the paper's planar experiments; 8 cables).  ``False``: both pairs (sigma = 0, pi/2, pi,
        3pi/2; 16 cables).
    gravity : float
        Magnitude of gravity [m/s^2] along world -z.
    base_orientation : {"vertical", "horizontal", "upside_down"}
        Mounting (see :func:`~workbench.robot.orientation.base_rotation_for`).
    payload_mass : float
        Tip payload [kg].
    axial_stiffness : float
        ``EA`` [N] of the equivalent rod (segments are practically incompressible).

    Returns
    -------
    Robot
        Four sections, each with ``n_disks = 4`` (one per segment), the equivalent-rod
        ``EI = k l / 4`` and the cables at offset ``w = diameter / 2``.
    """
    diam = _four("diameters", diameters)
    k = _four("joint_stiffness", joint_stiffness)
    m = _four("section_masses", section_masses)
    if not (math.isfinite(total_length) and total_length > 0):
        raise ValueError(f"total_length must be finite and > 0, got {total_length}")
    l = total_length / 4.0
    ds = l / HW_JOINTS_PER_SECTION
    angles = (0.0, math.pi) if planar else (0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi)
    sections = []
    for j in range(4):
        EI = k[j] * ds
        cs = CrossSection(EI=EI, EA=axial_stiffness, GJ=EI, mass_per_length=m[j] / l, diameter=diam[j])
        sections.append(
            Section(
                length=l,
                cross_section=cs,
                tendons=TendonGroup(angles=angles, offset=diam[j] / 2.0, axial_stiffness=tendon_stiffness,
                                    area=tendon_area, strength=tendon_strength),
                n_disks=HW_JOINTS_PER_SECTION,
            )
        )
    return Robot(
        sections=tuple(sections),
        gravity=(0.0, 0.0, -float(gravity)),
        payload=Payload(mass=payload_mass),
        base_rotation=base_rotation_for(base_orientation),
        name="hannan_walker",
    )
