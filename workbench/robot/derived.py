"""Derived quantities of a robot: stiffness and mass per section, total mass, tendon stiffness and
strength, first bending frequency.

Pure functions of a :class:`~workbench.robot.Robot` (numpy, scipy), SI units, no plotting.  What
needs the study or model layers -- the gravity parameter gamma (the definition of
``workbench.study.build.gravity_from_parameter``) and the stresses at a command (the CC model's
tension map and ``workbench.models.stress``) -- is in :mod:`workbench.study.robot_summary`, which
builds on this module; ``workbench robot show`` prints both.

Formulas
--------
* Stiffness and backbone mass per length are the :class:`~workbench.robot.CrossSection` fields
  (``EI = E pi d^4 / 64`` etc. for a solid rod, :meth:`CrossSection.circular`); a tapered section
  varies linearly from base to tip (:meth:`Section.cross_section_at`), so its backbone mass is
  ``L (m'_base + m'_tip) / 2``.
* Disks smeared: ``m'_smeared = m'_mean + n_disks m_disk / L`` (the disks' mass spread evenly over
  the section, as a distributed-load model sees it).
* Tendon: routed length ``L_t`` = arc length of the terminating disk (a tendon of section ``j``
  runs from the base plate to the end of section ``j``), axial spring stiffness ``k = EA_t / L_t``
  [N/m], force at strength ``F = sigma_t A_t`` [N].
* First bending frequency of the base-clamped, straight, unloaded robot (small vibration, gravity's
  geometric stiffness ignored): for a uniform robot without disk or payload mass the exact
  Euler-Bernoulli cantilever value ``omega_1 = (beta_1 L)^2 sqrt(EI / (m' L^4))``, ``beta_1 L =
  1.8751040687`` (the first root of ``1 + cos x cosh x = 0``; e.g. Rao, *Vibration of Continuous
  Systems*, 2007, Sec. 11.5); otherwise a finite-element eigenvalue: cubic Hermite Euler-Bernoulli
  elements (consistent mass, e.g. Przemieniecki, *Theory of Matrix Structural Analysis*, 1968,
  Ch. 11), ``EI`` and ``m'`` of each element at its midpoint, disks and payload as point masses
  (payload offset and rotary inertia ignored), a node at every disk.

Checked by ``tests/robot/test_derived.py`` (hand-calculated EI, EA, GJ, masses of steel_rod and the
Rao et al. 2021 robot; the finite elements against the analytic cantilever and the tip-mass
cantilever's frequency equation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .description import Robot, Section

__all__ = ["BETA1_L", "SectionProperties", "TendonProperties", "BendingFrequency", "section_properties",
           "tendon_properties", "total_mass", "is_uniform", "first_bending_frequency", "cantilever_frequency",
           "finite_element_frequency"]

#: First root of the clamped-free frequency equation ``1 + cos x cosh x = 0`` [-].
BETA1_L = 1.8751040687119611


@dataclass(frozen=True)
class SectionProperties:
    """Stiffness and mass of one section (:func:`section_properties`).

    Attributes
    ----------
    index : int
    length : float
        ``L_j`` [m].
    EI, EA, GJ : float
        Bending [N m^2], axial [N] and torsional [N m^2] stiffness at the section base.
    EI_tip : float or None
        ``EI`` at the section tip for a tapered section [N m^2] (``None``: uniform).
    mass_per_length : float
        Backbone mass per length at the base [kg/m].
    mass_per_length_tip : float or None
        Backbone mass per length at the tip of a tapered section [kg/m] (``None``: uniform).
    mass_per_length_smeared : float
        Mean backbone mass per length plus the disks smeared over the section [kg/m].
    backbone_mass, disk_mass : float
        Backbone mass ``L (m'_base + m'_tip) / 2`` and the section's disks ``n_disks m_disk`` [kg].
    diameter : float or None
        Outer diameter at the base [m] (``None``: not given, e.g. an equivalent rod).
    yield_strength : float or None
        Backbone strength [Pa] (``None``: unknown).
    """

    index: int
    length: float
    EI: float
    EA: float
    GJ: float
    EI_tip: float | None
    mass_per_length: float
    mass_per_length_tip: float | None
    mass_per_length_smeared: float
    backbone_mass: float
    disk_mass: float
    diameter: float | None
    yield_strength: float | None

    @property
    def mass(self) -> float:
        """Section mass, backbone and disks [kg]."""
        return self.backbone_mass + self.disk_mass


@dataclass(frozen=True)
class TendonProperties:
    """One tendon group (:func:`tendon_properties`): the tendons terminating at the end of a section.

    Attributes
    ----------
    section : int
        Index of the section whose end the group terminates at.
    count : int
    angles : tuple of float
        ``sigma_i`` [rad].
    offset, offset_tip : float
        Offset at the base plate and at the terminating disk [m] (equal without taper).
    routed_length : float
        ``L_t``: base plate to the terminating disk [m].
    axial_stiffness : float
        ``EA_t`` [N].
    spring_stiffness : float
        ``EA_t / L_t`` [N/m].
    area, strength : float or None
        Wire area [m^2] and tensile strength [Pa] (``None``: not given).
    """

    section: int
    count: int
    angles: tuple[float, ...]
    offset: float
    offset_tip: float
    routed_length: float
    axial_stiffness: float
    spring_stiffness: float
    area: float | None
    strength: float | None

    @property
    def force_at_strength(self) -> float | None:
        """Tension at which one wire reaches its strength, ``sigma_t A_t`` [N] (``None``: unknown)."""
        return None if self.area is None or self.strength is None else self.strength * self.area


@dataclass(frozen=True)
class BendingFrequency:
    """First bending frequency of the clamped robot (:func:`first_bending_frequency`).

    Attributes
    ----------
    hertz : float
        ``f_1 = omega_1 / (2 pi)`` [Hz].
    method : str
        ``"analytic"`` (uniform Euler-Bernoulli cantilever) or ``"finite elements"``.
    note : str
        One line saying what the value includes.
    """

    hertz: float
    method: str
    note: str


def _section_props(j: int, s: Section) -> SectionProperties:
    a = s.cross_section
    b = s.cross_section_tip
    m_tip = None if b is None else b.mass_per_length
    m_mean = a.mass_per_length if b is None else 0.5 * (a.mass_per_length + b.mass_per_length)
    disks = s.n_disks * s.disk_mass
    return SectionProperties(
        index=j, length=s.length, EI=a.EI, EA=a.EA, GJ=a.GJ, EI_tip=None if b is None else b.EI,
        mass_per_length=a.mass_per_length, mass_per_length_tip=m_tip,
        mass_per_length_smeared=m_mean + disks / s.length, backbone_mass=m_mean * s.length, disk_mass=disks,
        diameter=a.diameter, yield_strength=a.yield_strength)


def section_properties(robot: Robot) -> tuple[SectionProperties, ...]:
    """Stiffness and mass of every section, base to tip (formulas: module docstring)."""
    return tuple(_section_props(j, s) for j, s in enumerate(robot.sections))


def total_mass(robot: Robot) -> float:
    """Backbone, disks and payload [kg]."""
    return float(sum(p.mass for p in section_properties(robot)) + robot.payload.mass)


def tendon_properties(robot: Robot) -> tuple[TendonProperties, ...]:
    """Every tendon group, base to tip (formulas: module docstring)."""
    ends = robot.section_ends
    out = []
    for j, s in enumerate(robot.sections):
        g = s.tendons
        if g is None:
            continue
        lt = float(ends[j])
        out.append(TendonProperties(
            section=j, count=g.count, angles=g.angles, offset=g.offset,
            offset_tip=g.offset if g.offset_tip is None else g.offset_tip, routed_length=lt,
            axial_stiffness=g.axial_stiffness, spring_stiffness=g.axial_stiffness / lt, area=g.area,
            strength=g.strength))
    return tuple(out)


def is_uniform(robot: Robot) -> bool:
    """Every section has the same cross-section and none is tapered (the rule of ``derived.gravity_parameter``)."""
    cs = robot.sections[0].cross_section
    return all(s.cross_section == cs and s.cross_section_tip is None for s in robot.sections)


def cantilever_frequency(EI: float, mass_per_length: float, length: float) -> float:
    """Exact first bending frequency [Hz] of a uniform Euler-Bernoulli cantilever.

    ``f_1 = (beta_1 L)^2 sqrt(EI / (m' L^4)) / (2 pi)`` with :data:`BETA1_L`.
    """
    return BETA1_L**2 * math.sqrt(EI / (mass_per_length * length**4)) / (2.0 * math.pi)


def _hermite_matrices(EI: float, m: float, h: float) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and consistent mass of one Euler-Bernoulli element, DOFs ``(w1, t1, w2, t2)``."""
    k = EI / h**3 * np.array([[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                              [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    mm = m * h / 420.0 * np.array([[156, 22 * h, 54, -13 * h], [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                   [54, 13 * h, 156, -22 * h], [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    return k, mm


def finite_element_frequency(robot: Robot, min_elements: int = 24) -> float:
    """First eigenfrequency [Hz] of the clamped robot by Hermite beam elements (module docstring).

    ``min_elements`` elements per section at least, rounded up to a multiple of its disk count so
    that every disk sits on a node; the robot must have mass (:func:`first_bending_frequency` checks).
    """
    from scipy.linalg import eigh

    EIs, ms, hs, point = [], [], [], []
    for s in robot.sections:
        per_disk = max(1, math.ceil(min_elements / s.n_disks))
        n = s.n_disks * per_disk  # a node at every disk
        h = s.length / n
        for e in range(n):
            cs = s.cross_section_at((e + 0.5) / n)
            EIs.append(cs.EI)
            ms.append(cs.mass_per_length)
            hs.append(h)
            point.append(s.disk_mass if (e + 1) % per_disk == 0 else 0.0)
    point[-1] += robot.payload.mass
    ne = len(hs)
    K = np.zeros((2 * ne + 2, 2 * ne + 2))
    M = np.zeros_like(K)
    for e in range(ne):
        k, mm = _hermite_matrices(EIs[e], ms[e], hs[e])
        sl = slice(2 * e, 2 * e + 4)
        K[sl, sl] += k
        M[sl, sl] += mm
        M[2 * e + 2, 2 * e + 2] += point[e]  # point mass at the element's end node
    K, M = K[2:, 2:], M[2:, 2:]  # clamped base: w = w' = 0
    # K is positive definite, M only semi-definite (a massless backbone with disks): solve M v = mu K v,
    # the largest mu = 1 / omega_1^2
    n = K.shape[0]
    mu = eigh(M, K, eigvals_only=True, subset_by_index=[n - 1, n - 1])[0]
    return 1.0 / (2.0 * math.pi * math.sqrt(mu))


def first_bending_frequency(robot: Robot, min_elements: int = 24) -> BendingFrequency | None:
    """First bending frequency of the base-clamped robot (formulas: module docstring).

    Parameters
    ----------
    robot : Robot
    min_elements : int
        Finite elements per section at least (rounded up to a multiple of its disk count).

    Returns
    -------
    BendingFrequency or None
        ``None`` for a massless robot (no vibration to speak of).
    """
    if total_mass(robot) <= 0.0:
        return None
    cs = robot.sections[0].cross_section
    no_points = robot.payload.mass == 0.0 and all(s.disk_mass == 0.0 for s in robot.sections)
    if is_uniform(robot) and no_points:
        return BendingFrequency(cantilever_frequency(cs.EI, cs.mass_per_length, robot.length), "analytic",
                                "uniform Euler-Bernoulli cantilever, (1.8751)^2 sqrt(EI / (m' L^4)) / 2 pi")
    f = finite_element_frequency(robot, min_elements)
    return BendingFrequency(f, "finite elements",
                            "Hermite beam elements, disks and payload as point masses, straight unloaded robot")
