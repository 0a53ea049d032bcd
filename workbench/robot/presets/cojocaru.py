"""Cojocaru et al.'s tronconic tentacle arm: a steel-rod backbone, 3 sections, 3 wires each.

Source: Cojocaru, Boccolato, Dinulescu, Predescu, Manta, Dumitru, "3D Kinematics Control for
a Hyper Redundant Robot" (``/work/shared/papers/001_*``).  The paper gives the structure
(elastic steel-rod backbone, three truncated-cone segments, total length > 1 m, three
wires per segment at 120 degrees, end-disk diameters D1 > D2 per segment) but not the
dimensions; every number below is a plausible default, documented as such (as data in
:data:`ASSUMED`, the paper's facts in :data:`GIVEN`).
"""

from __future__ import annotations

import math

from ...assumptions import Assumption
from ..description import CrossSection, Payload, Robot, Section, TendonGroup
from ..orientation import base_rotation_for
from .per_section import per_section

__all__ = ["cojocaru_tronconic", "GIVEN", "ASSUMED", "SETTINGS", "PER_SECTION", "WIRE_STRENGTH_1MM"]

#: Minimum tensile strength of 1.0 mm (0.040 in) music wire, ASTM A228 Table 1: 315 ksi = 2172 MPa [Pa].
WIRE_STRENGTH_1MM = 2.17e9

GIVEN: dict[str, str] = {
    "n_sections": "paper Sec. 2: three segments",
    "first_wire_angle": "paper Eq 10: three wires at 120 deg (wire 1 at 0)",
}
ASSUMED: tuple[Assumption, ...] = (
    Assumption("section_length", "0.35 m: the paper says only 'more than one meter' for three segments"),
    Assumption("rod_diameter", "4 mm steel rod (the paper: an elastic steel rod, no size): EI = 2.64 N m^2"),
    Assumption("youngs_modulus", "steel, 210 GPa"),
    Assumption("density", "steel, 7850 kg/m^3"),
    Assumption("poisson_ratio", "steel, 0.3"),
    Assumption("yield_strength", "hardened and tempered spring steel 52CrMoV4 (EN 10089): Rp0.2 >= 1200 MPa "
                                 "(Saarstahl data sheet)"),
    Assumption("base_disk_diameter", "100 mm (the paper: D1 > D2, no values)"),
    Assumption("disk_diameter_step", "20 mm per section (disks 100 -> 80 -> 60 -> 40 mm)"),
    Assumption("wire_diameter", "1 mm steel wire (the paper: control wires, no size): EA_t = 1.65e5 N"),
    Assumption("wire_youngs_modulus", "steel, 210 GPa"),
    Assumption("wire_strength", "music wire ASTM A228, 1.0 mm: minimum tensile strength 2172 MPa (315 ksi); a ratio "
                                "above 1 means the wire breaks (no safety factor)"),
    Assumption("disks_per_section", "5 spacer disks per section (not given)"),
    Assumption("disk_mass", "0 (disks massless; gravity is off in the paper's kinematic experiment)"),
)
SETTINGS: dict[str, str] = {k: "study choice" for k in ("gravity", "base_orientation", "payload_mass")}
#: Parameters that take one value per section as a list of ``n_sections`` entries (a scalar: every section).
PER_SECTION: tuple[str, ...] = ("rod_diameter", "youngs_modulus", "density", "poisson_ratio", "yield_strength",
                                "wire_diameter", "wire_youngs_modulus", "wire_strength", "first_wire_angle",
                                "disks_per_section", "disk_mass")


def cojocaru_tronconic(
    *,
    section_length: float = 0.35,
    n_sections: int = 3,
    rod_diameter: float = 4e-3,
    youngs_modulus: float = 210e9,
    density: float = 7850.0,
    poisson_ratio: float = 0.3,
    base_disk_diameter: float = 0.10,
    disk_diameter_step: float = 0.02,
    wire_diameter: float = 1.0e-3,
    wire_youngs_modulus: float = 210e9,
    wire_strength: float = WIRE_STRENGTH_1MM,
    yield_strength: float = 1.2e9,  # spring steel 52CrMoV4, Rp0.2 (ASSUMED below)
    first_wire_angle: float = 0.0,
    disks_per_section: int = 5,
    disk_mass: float = 0.0,
    gravity: float = 0.0,
    base_orientation: str = "vertical",
    payload_mass: float = 0.0,
) -> Robot:
    """Tronconic tentacle arm after Cojocaru et al. (steel rod, 3 sections, 3 wires each).

    Section ``k`` (0-based) is a truncated cone whose end disks have diameters
    ``D1_k = base_disk_diameter - k * disk_diameter_step`` (section base) and
    ``D2_k = D1_k - disk_diameter_step`` (section tip); its three wires run at the disk
    rim, so the tendon offset tapers linearly from ``D1_k / 2`` to ``D2_k / 2``
    (``TendonGroup.offset`` / ``offset_tip``), exactly the geometry of the paper's Eq 5-11.

    Parameters
    ----------
    section_length : float
        Length H of each section [m].  Default 0.35 (3 x 0.35 = 1.05 m; the paper only
        says "more than one meter").
    n_sections : int
        Number of sections (paper: 3).
    rod_diameter : float
        Diameter of the steel backbone rod [m].  Default 4 mm (plausible; not given):
        EI = 2.64 N m^2, so bending one section to 45 degrees needs ~150 N of wire tension.
    youngs_modulus, density, poisson_ratio : float
        Backbone material [Pa], [kg/m^3], [-] (default structural steel).
    base_disk_diameter : float
        D1 of the first section [m].  Default 0.10 (plausible; not given).
    disk_diameter_step : float
        Diameter reduction per section [m] (D2_k = D1_k - step and D1_{k+1} = D2_k).
        Default 0.02: disks 100 -> 80 -> 60 -> 40 mm.  Must leave D2 > 0.
    wire_diameter, wire_youngs_modulus : float
        Steel control wire [m], [Pa]: ``EA_t = E pi d_w^2 / 4`` (default 1 mm steel wire,
        EA_t = 1.65e5 N; plausible, not given).
    wire_strength, yield_strength : float
        Wire tensile strength and backbone 0.2 % proof stress [Pa] (see :data:`ASSUMED`).
    first_wire_angle : float
        Angle sigma of wire 1 [rad]; the others follow at +120 and +240 degrees (paper Eq 10).
    disks_per_section : int
        Spacer disks (eyelets) per section, the last one at the section end (default 5).
    disk_mass : float
        Mass of each disk [kg] (default 0).
    gravity : float
        Magnitude of gravity [m/s^2] along world -z (default 0).
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

    Every parameter in :data:`PER_SECTION` may also be a list of ``n_sections`` values, one per
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
