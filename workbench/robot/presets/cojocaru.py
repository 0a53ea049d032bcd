"""Cojocaru et al.'s tronconic tentacle arm: a steel-rod backbone, 3 sections, 3 wires each.

Source: Cojocaru, Boccolato, Dinulescu, Predescu, Manta, Dumitru, "3D Kinematics Control for
a Hyper Redundant Robot" (``/work/shared/papers/001_*``).  The paper gives the structure
(elastic steel-rod backbone, three truncated-cone segments, total length > 1 m, three
wires per segment at 120 degrees, end-disk diameters D1 > D2 per segment) but not the
dimensions; every number is a plausible default, assumed with its reason.  The parameters
(defaults, units, and where each value comes from) are data in ``cojocaru_tronconic.toml``
(``docs/robot-format.md``, "Presets"); this module holds the formula :func:`derive` that maps them
to the :class:`Robot`, and ``build_preset("cojocaru_tronconic")``, the preset itself.  Checked by
``tests/robot/test_data_presets.py``.
"""

from __future__ import annotations

import math

from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for
from .per_section import per_section

__all__ = ["derive"]


def derive(
    *,
    section_length: float,
    n_sections: int,
    rod_diameter: float,
    youngs_modulus: float,
    density: float,
    poisson_ratio: float,
    base_disk_diameter: float,
    disk_diameter_step: float,
    wire_diameter: float,
    wire_youngs_modulus: float,
    wire_strength: float,
    yield_strength: float,
    first_wire_angle: float,
    disks_per_section: int,
    disk_mass: float,
    gravity: float,
    base_orientation: str,
    payload_mass: float,
) -> Robot:
    """Tronconic tentacle arm after Cojocaru et al. (the formula of ``cojocaru_tronconic.toml``).

    The parameters, their defaults, units and sources are data in ``cojocaru_tronconic.toml``;
    ``build_preset("cojocaru_tronconic", **params)`` (:mod:`workbench.robot.presets`) is that preset.

    Section ``k`` (0-based) is a truncated cone whose end disks have diameters
    ``D1_k = base_disk_diameter - k * disk_diameter_step`` (section base) and
    ``D2_k = D1_k - disk_diameter_step`` (section tip); its three wires run at the disk
    rim, so the tendon offset tapers linearly from ``D1_k / 2`` to ``D2_k / 2``
    (``TendonGroup.offset`` / ``offset_tip``), exactly the geometry of the paper's Eq 5-11.

    Parameters
    ----------
    section_length : float
        Length H of each section [m].
    n_sections : int
        Number of sections (paper: 3).
    rod_diameter : float
        Diameter of the steel backbone rod [m].
    youngs_modulus, density, poisson_ratio : float
        Backbone material [Pa], [kg/m^3], [-].
    base_disk_diameter : float
        D1 of the first section [m].
    disk_diameter_step : float
        Diameter reduction per section [m] (D2_k = D1_k - step and D1_{k+1} = D2_k).
        Must leave D2 > 0.
    wire_diameter, wire_youngs_modulus : float
        Steel control wire [m], [Pa]: ``EA_t = E pi d_w^2 / 4``.
    wire_strength, yield_strength : float
        Wire tensile strength and backbone 0.2 % proof stress [Pa].
    first_wire_angle : float
        Angle sigma of wire 1 [rad]; the others follow at +120 and +240 degrees (paper Eq 10).
    disks_per_section : int
        Spacer disks (eyelets) per section, the last one at the section end.
    disk_mass : float
        Mass of each disk [kg].
    gravity : float
        Magnitude of gravity [m/s^2] along world -z.
    base_orientation : {"vertical", "horizontal", "upside_down"}
        Mounting orientation (see :func:`workbench.robot.base_rotation_for`).
    payload_mass : float
        Point mass at the tip [kg].

    Notes
    -----
    Sign convention: the paper measures the bending direction alpha so that wire 1 at
    ``alpha_1 = -alpha`` lies on the *outside* of the bend (its radius is ``R + D/2
    cos(alpha_1)``, Eq 9).  The workbench convention is that a tendon at ``sigma`` pulls
    the robot towards ``phi = sigma`` (tendon on the inside), so the paper's bending
    direction alpha corresponds to ``phi = alpha + pi`` here.

    Every parameter marked ``per_section`` in the file may also be a list of ``n_sections`` values, one per
    section; a scalar applies to every section (``tests/robot/test_per_section.py``).
    """
    if int(n_sections) != n_sections or n_sections < 1:
        raise ValueError(f"n_sections must be a positive integer, got {n_sections!r}")
    n = int(n_sections)
    d_tip_last = base_disk_diameter - n * disk_diameter_step
    if not (base_disk_diameter > 0 and d_tip_last > 0):
        raise ValueError(
            "disk diameters must stay > 0: base_disk_diameter - n_sections * disk_diameter_step = "
            f"{d_tip_last} m"
        )
    if disk_diameter_step < 0:
        raise ValueError(f"disk_diameter_step must be >= 0 (tronconic: D2 <= D1), got {disk_diameter_step}")
    v = {k: per_section(k, val, n) for k, val in (
        ("rod_diameter", rod_diameter), ("youngs_modulus", youngs_modulus), ("density", density),
        ("poisson_ratio", poisson_ratio), ("yield_strength", yield_strength), ("wire_diameter", wire_diameter),
        ("wire_youngs_modulus", wire_youngs_modulus), ("wire_strength", wire_strength),
        ("first_wire_angle", first_wire_angle), ("disks_per_section", disks_per_section), ("disk_mass", disk_mass))}
    sections = []
    for k in range(n):
        rod = CrossSection.circular(v["rod_diameter"][k], v["youngs_modulus"][k], v["density"][k],
                                    v["poisson_ratio"][k], yield_strength=v["yield_strength"][k])
        d_w = v["wire_diameter"][k]
        wire_area = math.pi * d_w**2 / 4.0
        ea_wire = v["wire_youngs_modulus"][k] * math.pi * d_w**2 / 4.0  # same rounding as before the stress fields
        # every wire runs on the cone's rim from the base plate to its terminating disk:
        # offset linear along its routed length (the TendonGroup convention)
        d_end = base_disk_diameter - (k + 1) * disk_diameter_step
        group = TendonGroup.evenly_spaced(
            3, base_disk_diameter / 2.0, ea_wire, v["first_wire_angle"][k],
            offset_tip=d_end / 2.0 if d_end != base_disk_diameter else None,
            area=wire_area, strength=v["wire_strength"][k],
        )
        sections.append(
            Section(
                length=section_length,
                cross_section=rod,
                tendons=group,
                n_disks=v["disks_per_section"][k],
                disk_mass=v["disk_mass"][k],
            )
        )
    return Robot(
        sections=tuple(sections),
        gravity=(0.0, 0.0, -float(gravity)),
        payload=Payload(mass=payload_mass),
        base_rotation=base_rotation_for(base_orientation),
        name="cojocaru_tronconic",
    )
