"""Hannan & Walker's segmented 'elephant trunk' (papers/000_, Sec. 3).

From the paper: total length 83.82 cm; 16 two-DOF joints (32 DOF) in 4 sections of 4 joints;
section diameters 10.16 / 8.89 / 7.62 / 6.35 cm; springs between adjacent segments supply the
bending stiffness; per section two antagonistic cable pairs, 90 degrees apart, terminate on the
section's last (every fourth) segment.

Not given in the paper and chosen as documented, plausible defaults (their values and sources are
data in ``hannan_walker.toml``, ``docs/robot-format.md`` "Presets"; this module holds the formula
:func:`derive` and ``build_preset("hannan_walker")``, the preset itself):

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

from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for

__all__ = ["derive", "HW_JOINTS_PER_SECTION"]

#: Joints per section (paper, Sec. 3: 16 joints, 4 sections): the formula's n.
HW_JOINTS_PER_SECTION = 4


def _four(name: str, values: Sequence[float]) -> tuple[float, ...]:
    v = tuple(float(x) for x in values)
    if len(v) != 4:
        raise ValueError(f"{name} must hold 4 values (one per section), got {len(v)}")
    if any(not math.isfinite(x) or x <= 0 for x in v):
        raise ValueError(f"{name} must be finite and > 0, got {list(v)}")
    return v


def derive(
    *,
    total_length: float,
    diameters: Sequence[float],
    joint_stiffness: Sequence[float],
    section_masses: Sequence[float],
    tendon_stiffness: float,
    tendon_area: float,
    tendon_strength: float,
    planar: bool,
    gravity: float,
    base_orientation: str,
    payload_mass: float,
    axial_stiffness: float,
) -> Robot:
    """The Hannan & Walker trunk as a 4-section robot (the formula of ``hannan_walker.toml``).

    The parameters, their defaults, units and sources are data in ``hannan_walker.toml``;
    ``build_preset("hannan_walker", **params)`` (:mod:`workbench.robot.presets`) is that preset.

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
        Cable cross-section [m^2] and tensile strength [Pa] for the tendon stress;
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
