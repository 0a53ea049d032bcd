"""Robot descriptions shared by every model (CC kinematics and all physics models).

All quantities are SI (m, kg, s, N, Pa, rad).  Every dataclass is frozen and validated on
construction, so a model never receives a negative length or a NaN stiffness.

Conventions
-----------
The robot is described in its **base frame**: the undeformed backbone runs along the base
+z axis from s = 0 (clamped base) to s = L (tip).  A bending plane at angle ``phi`` is
measured from the base x axis (the constant-curvature convention of
:mod:`workbench.kinematics`).  Planar models bend in the base x-z plane (phi = 0 or pi).
Tendon angles ``sigma`` are measured from the base x axis as well; a tendon at
``sigma = 0`` sits at (+d, 0) in the cross-section and, when pulled, bends the robot
towards +x (phi = 0).

The base pose (``Robot.base_rotation``, ``Robot.base_position``) maps base-frame vectors
to world-frame vectors; ``Robot.gravity`` is given in the world frame and
:meth:`Robot.gravity_in_base` converts it.  Results of every model are reported in the
base frame; :mod:`workbench.robot.frames` converts them to the world frame (the result tables'
``tip_world_*`` columns, the report's figures).

Example
-------
>>> from workbench.robot import CrossSection, Section, TendonGroup, Robot
>>> rod = CrossSection.circular(diameter=6e-3, youngs_modulus=210e9, density=7850.0)
>>> tendons = TendonGroup(angles=(0.0, 3.14159265358979),  offset=0.02, axial_stiffness=2e4)
>>> robot = Robot(sections=(Section(length=0.8, cross_section=rod, tendons=tendons),))
>>> round(robot.length, 3)
0.8
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Mapping, Sequence

import numpy as np

__all__ = [
    "CrossSection",
    "TendonGroup",
    "Section",
    "Payload",
    "Robot",
    "RobotDescriptionError",
    "circular_section",
]


class RobotDescriptionError(ValueError):
    """A robot description is physically or structurally invalid."""


def checked_positive(name: str, value: float, *, allow_zero: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise RobotDescriptionError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise RobotDescriptionError(f"{name} must be finite, got {v}")
    if v < 0 or (v == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise RobotDescriptionError(f"{name} must be {bound}, got {v}")
    return v


def checked_vector(name: str, value: Sequence[float], n: int = 3) -> tuple[float, ...]:
    arr = np.asarray(value, dtype=float)
    if arr.shape != (n,):
        raise RobotDescriptionError(f"{name} must have shape ({n},), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise RobotDescriptionError(f"{name} must be finite, got {arr.tolist()}")
    return tuple(float(x) for x in arr)


def circular_section(diameter: float) -> tuple[float, float, float]:
    """Area and area moments of a solid circular section of diameter ``d`` [m].

    The one formula behind :meth:`CrossSection.circular`,
    ``workbench.reference.cosserat.RodStiffness.circular`` and
    ``workbench.physics.series_parallel.ModuleGeometry.rod_params`` (each keeps its own type);
    ``tests/reference/test_circular_section.py`` checks the three agree bit for bit.  The
    diameter is not validated here (each caller does).

    Returns
    -------
    area : float
        ``A = pi d^2 / 4`` [m^2].
    second_moment : float
        ``I = pi d^4 / 64`` [m^4], about any diameter.
    polar_moment : float
        ``J = 2 I = pi d^4 / 32`` [m^4].
    """
    area = math.pi * diameter**2 / 4.0
    second_moment = math.pi * diameter**4 / 64.0
    return area, second_moment, 2.0 * second_moment


@dataclass(frozen=True)
class CrossSection:
    """Elastic and inertial properties of the backbone cross-section.

    Parameters
    ----------
    EI : float
        Bending stiffness [N m^2] (isotropic section: same about both axes).
    EA : float
        Axial stiffness [N].
    GJ : float
        Torsional stiffness [N m^2].
    mass_per_length : float
        Mass per unit length [kg/m].
    GA : float, optional
        Shear stiffness [N] for shear-deformable (geometrically exact) beams; default
        ``EA / (2 (1 + 0.3)) * 0.9`` is used by :meth:`circular`; ``None`` means "use a
        large value" (shear-rigid, Euler-Bernoulli limit) and is left to the model.
    diameter : float, optional
        Outer diameter [m], informational (used for drawing and for link inertia).
    area : float, optional
        Cross-section area [m^2] for stresses (``N / A``); ``None``: no stress geometry (e.g. an
        equivalent rod of springs), the models then report no backbone stress.
    section_modulus : float, optional
        Elastic section modulus ``W = I / c`` [m^3] for bending stresses (``M / W``, ``c`` the
        outer-fibre distance); ``None`` as for ``area``.
    yield_strength : float, optional
        Allowable normal stress of the backbone material [Pa] (its 0.2 % proof stress for the
        presets' steels); ``None``: unknown, stresses are reported but not judged.
    """

    EI: float
    EA: float
    GJ: float
    mass_per_length: float
    GA: float | None = None
    diameter: float | None = None
    area: float | None = None
    section_modulus: float | None = None
    yield_strength: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "EI", checked_positive("CrossSection.EI", self.EI))
        object.__setattr__(self, "EA", checked_positive("CrossSection.EA", self.EA))
        object.__setattr__(self, "GJ", checked_positive("CrossSection.GJ", self.GJ))
        object.__setattr__(
            self,
            "mass_per_length",
            checked_positive("CrossSection.mass_per_length", self.mass_per_length, allow_zero=True),
        )
        if self.GA is not None:
            object.__setattr__(self, "GA", checked_positive("CrossSection.GA", self.GA))
        for name in ("diameter", "area", "section_modulus", "yield_strength"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, checked_positive(f"CrossSection.{name}", getattr(self, name)))

    @classmethod
    def circular(
        cls,
        diameter: float,
        youngs_modulus: float = 210e9,
        density: float = 7850.0,
        poisson_ratio: float = 0.3,
        yield_strength: float | None = None,
    ) -> "CrossSection":
        """Solid circular rod (defaults: steel; strength unknown unless given).

        ``EI = E pi d^4 / 64``, ``EA = E pi d^2 / 4``, ``GJ = G pi d^4 / 32`` with
        ``G = E / (2 (1 + nu))``, shear stiffness ``GA = kappa_s G A`` with the circular
        shear coefficient ``kappa_s = 6 (1 + nu) / (7 + 6 nu)``; stress geometry ``A = pi d^2 / 4``,
        ``W = pi d^3 / 32``.
        """
        d = checked_positive("diameter", diameter)
        E = checked_positive("youngs_modulus", youngs_modulus)
        rho = checked_positive("density", density, allow_zero=True)
        nu = float(poisson_ratio)
        if not (-1.0 < nu < 0.5):
            raise RobotDescriptionError(f"poisson_ratio must be in (-1, 0.5), got {nu}")
        area, inertia, polar = circular_section(d)
        G = E / (2.0 * (1.0 + nu))
        kappa_s = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)
        return cls(
            EI=E * inertia,
            EA=E * area,
            GJ=G * polar,
            mass_per_length=rho * area,
            GA=kappa_s * G * area,
            diameter=d,
            area=area,
            section_modulus=inertia / (0.5 * d),
            yield_strength=yield_strength,
        )

    @classmethod
    def tube(
        cls,
        outer_diameter: float,
        inner_diameter: float,
        youngs_modulus: float,
        density: float,
        poisson_ratio: float = 0.3,
        yield_strength: float | None = None,
    ) -> "CrossSection":
        """Circular tube (hollow rod) of outer and inner diameter ``D > d >= 0`` [m].

        ``A = pi (D^2 - d^2) / 4``, ``I = pi (D^4 - d^4) / 64``, ``J = 2 I``, ``W = I / (D / 2)``;
        shear coefficient of the hollow circle (Cowper 1966, "The shear coefficient in Timoshenko's
        beam theory", J. Appl. Mech. 33:335, Table 1) ``kappa_s = 6 (1 + nu)(1 + m^2)^2 /
        ((7 + 6 nu)(1 + m^2)^2 + (20 + 12 nu) m^2)`` with ``m = d / D`` (the solid value of
        :meth:`circular` at ``m = 0``).  ``d = 0`` returns :meth:`circular` itself (bit for bit).
        Checked by ``tests/robot/test_robot_spec.py``.
        """
        D = checked_positive("outer_diameter", outer_diameter)
        d = checked_positive("inner_diameter", inner_diameter, allow_zero=True)
        if d == 0.0:
            return cls.circular(D, youngs_modulus, density, poisson_ratio, yield_strength)
        if d >= D:
            raise RobotDescriptionError(f"inner_diameter must be < outer_diameter ({D}), got {d}")
        E = checked_positive("youngs_modulus", youngs_modulus)
        rho = checked_positive("density", density, allow_zero=True)
        nu = float(poisson_ratio)
        if not (-1.0 < nu < 0.5):
            raise RobotDescriptionError(f"poisson_ratio must be in (-1, 0.5), got {nu}")
        area = math.pi * (D**2 - d**2) / 4.0
        inertia = math.pi * (D**4 - d**4) / 64.0
        G = E / (2.0 * (1.0 + nu))
        m2 = (d / D) ** 2
        kappa_s = 6.0 * (1.0 + nu) * (1.0 + m2) ** 2 / ((7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2)
        return cls(
            EI=E * inertia, EA=E * area, GJ=G * 2.0 * inertia, mass_per_length=rho * area,
            GA=kappa_s * G * area, diameter=D, area=area, section_modulus=inertia / (0.5 * D),
            yield_strength=yield_strength,
        )

    def scaled(self, factor: float) -> "CrossSection":
        """Return a copy with every stiffness multiplied by ``factor`` (mass unchanged)."""
        f = checked_positive("factor", factor)
        return replace(
            self,
            EI=self.EI * f,
            EA=self.EA * f,
            GJ=self.GJ * f,
            GA=None if self.GA is None else self.GA * f,
        )


@dataclass(frozen=True)
class TendonGroup:
    """The tendons that terminate at the end of one section.

    Tendons of section ``j`` are routed (frictionless) through the disks of sections
    ``0..j`` and terminate on the last disk of section ``j``.

    Parameters
    ----------
    angles : tuple of float
        Angular positions ``sigma_i`` of the tendons in the cross-section [rad], measured
        from the base x axis (e.g. ``(0, 2pi/3, 4pi/3)``).
    offset : float
        Radial offset ``d`` of the tendons from the backbone centreline [m] at the robot's
        base plate (where every tendon is anchored).
    offset_tip : float, optional
        Offset at the terminating disk [m] for tronconic (tapered) robots; ``None`` means
        constant offset.  The offset varies linearly with arc length along the tendon's
        whole routed length, from the base plate (s = 0) to the end of its section.
    axial_stiffness : float
        Tendon axial stiffness ``EA_t`` [N] (e.g. steel wire of 0.5 mm: ~4e4 N).
    area : float, optional
        Load-bearing cross-section area of one tendon [m^2] (tendon stress ``T / area``);
        ``None``: no tendon stress (e.g. equivalent tendons standing in for other actuators).
    strength : float, optional
        Allowable tensile stress of the tendon [Pa] (the presets' steel wires: the minimum
        tensile strength, so a ratio above 1 means the wire breaks); ``None``: unknown.
    """

    angles: tuple[float, ...]
    offset: float
    axial_stiffness: float = 4.0e4
    offset_tip: float | None = None
    area: float | None = None
    strength: float | None = None

    def __post_init__(self) -> None:
        ang = np.asarray(self.angles, dtype=float).reshape(-1)
        if ang.size == 0:
            raise RobotDescriptionError("TendonGroup.angles must hold at least one angle")
        if not np.all(np.isfinite(ang)):
            raise RobotDescriptionError("TendonGroup.angles must be finite")
        object.__setattr__(self, "angles", tuple(float(a) for a in ang))
        object.__setattr__(self, "offset", checked_positive("TendonGroup.offset", self.offset))
        object.__setattr__(
            self, "axial_stiffness", checked_positive("TendonGroup.axial_stiffness", self.axial_stiffness)
        )
        for name in ("offset_tip", "area", "strength"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, checked_positive(f"TendonGroup.{name}", getattr(self, name)))

    @property
    def count(self) -> int:
        """Number of tendons in the group."""
        return len(self.angles)

    @classmethod
    def evenly_spaced(
        cls, count: int, offset: float, axial_stiffness: float = 4.0e4, first_angle: float = 0.0,
        offset_tip: float | None = None, area: float | None = None, strength: float | None = None,
    ) -> "TendonGroup":
        """``count`` tendons at ``first_angle + 2 pi k / count``."""
        if int(count) != count or count < 1:
            raise RobotDescriptionError(f"tendon count must be a positive integer, got {count!r}")
        angles = tuple(first_angle + 2.0 * math.pi * k / count for k in range(int(count)))
        return cls(angles=angles, offset=offset, axial_stiffness=axial_stiffness, offset_tip=offset_tip,
                   area=area, strength=strength)

    def offset_at(self, fraction: float) -> float:
        """Tendon offset [m] at ``fraction`` in [0, 1] of the tendon's routed length.

        ``fraction = s / s_end`` with ``s_end`` the arc length of the terminating disk.
        """
        if self.offset_tip is None:
            return self.offset
        return self.offset + (self.offset_tip - self.offset) * float(fraction)


@dataclass(frozen=True)
class Section:
    """One constant-curvature section of the robot.

    Parameters
    ----------
    length : float
        Section arc length [m].
    cross_section : CrossSection
        Backbone properties at the section base.
    cross_section_tip : CrossSection, optional
        Backbone properties at the section tip (linear taper between base and tip);
        ``None`` means uniform.
    n_disks : int
        Number of spacer disks (eyelets) in the section, equally spaced, the last one at
        the section end.  Tendons of this and later sections pass through them.
    disk_mass : float
        Mass of each disk [kg] (lumped on the backbone).
    tendons : TendonGroup, optional
        Tendons terminating at the end of this section (``None``: no tendons).
    """

    length: float
    cross_section: CrossSection
    tendons: TendonGroup | None = None
    n_disks: int = 8
    disk_mass: float = 0.0
    cross_section_tip: CrossSection | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", checked_positive("Section.length", self.length))
        object.__setattr__(self, "disk_mass", checked_positive("Section.disk_mass", self.disk_mass, allow_zero=True))
        if int(self.n_disks) != self.n_disks or self.n_disks < 1:
            raise RobotDescriptionError(f"Section.n_disks must be a positive integer, got {self.n_disks!r}")
        object.__setattr__(self, "n_disks", int(self.n_disks))
        if not isinstance(self.cross_section, CrossSection):
            raise RobotDescriptionError("Section.cross_section must be a CrossSection")
        if self.cross_section_tip is not None and not isinstance(self.cross_section_tip, CrossSection):
            raise RobotDescriptionError("Section.cross_section_tip must be a CrossSection or None")
        if self.tendons is not None and not isinstance(self.tendons, TendonGroup):
            raise RobotDescriptionError("Section.tendons must be a TendonGroup or None")

    def disk_positions(self) -> np.ndarray:
        """Arc-length positions of the disks within the section, ``(n_disks,)`` [m]."""
        return self.length * np.arange(1, self.n_disks + 1) / self.n_disks

    def cross_section_at(self, fraction: float) -> CrossSection:
        """Backbone properties at ``fraction`` in [0, 1] of the section (linear taper)."""
        if self.cross_section_tip is None:
            return self.cross_section
        a, b, f = self.cross_section, self.cross_section_tip, float(fraction)

        def lerp(x: float | None, y: float | None) -> float | None:
            if x is None or y is None:
                return None
            return x + (y - x) * f

        return CrossSection(
            EI=lerp(a.EI, b.EI), EA=lerp(a.EA, b.EA), GJ=lerp(a.GJ, b.GJ),
            mass_per_length=lerp(a.mass_per_length, b.mass_per_length),
            GA=lerp(a.GA, b.GA), diameter=lerp(a.diameter, b.diameter),
            area=lerp(a.area, b.area), section_modulus=lerp(a.section_modulus, b.section_modulus),
            yield_strength=lerp(a.yield_strength, b.yield_strength),
        )


@dataclass(frozen=True)
class Payload:
    """A point mass rigidly attached to the tip.

    Parameters
    ----------
    mass : float
        Payload mass [kg].
    offset : tuple of 3 float
        Position of the payload's centre of mass in the tip frame [m].
    """

    mass: float = 0.0
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", checked_positive("Payload.mass", self.mass, allow_zero=True))
        object.__setattr__(self, "offset", checked_vector("Payload.offset", self.offset))


_IDENTITY = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


@dataclass(frozen=True)
class Robot:
    """A multi-section tendon-driven continuum robot.

    Parameters
    ----------
    sections : tuple of Section
        Sections from base to tip.
    gravity : tuple of 3 float
        Gravitational acceleration in the **world** frame [m/s^2]; default zero.
    payload : Payload
        Tip payload.
    base_rotation : 3x3 nested tuple
        Rotation matrix world <- base (columns: base axes in world coordinates).
        Default identity: the robot points up (+z) when gravity is (0, 0, -9.81).
    base_position : tuple of 3 float
        Base origin in the world frame [m].
    name : str
        Free-form name (presets set it).
    """

    sections: tuple[Section, ...]
    gravity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    payload: Payload = field(default_factory=Payload)
    base_rotation: tuple[tuple[float, float, float], ...] = _IDENTITY
    base_position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    name: str = "robot"

    def __post_init__(self) -> None:
        secs = tuple(self.sections)
        if not secs:
            raise RobotDescriptionError("Robot.sections must hold at least one Section")
        for i, s in enumerate(secs):
            if not isinstance(s, Section):
                raise RobotDescriptionError(f"Robot.sections[{i}] must be a Section, got {type(s).__name__}")
        object.__setattr__(self, "sections", secs)
        object.__setattr__(self, "gravity", checked_vector("Robot.gravity", self.gravity))
        object.__setattr__(self, "base_position", checked_vector("Robot.base_position", self.base_position))
        R = np.asarray(self.base_rotation, dtype=float)
        if R.shape != (3, 3):
            raise RobotDescriptionError(f"Robot.base_rotation must have shape (3, 3), got {R.shape}")
        if not np.allclose(R @ R.T, np.eye(3), atol=1e-9) or np.linalg.det(R) < 0:
            raise RobotDescriptionError("Robot.base_rotation must be a proper rotation matrix")
        object.__setattr__(self, "base_rotation", tuple(tuple(float(x) for x in row) for row in R))
        if not isinstance(self.payload, Payload):
            raise RobotDescriptionError("Robot.payload must be a Payload")

    # -- derived quantities -------------------------------------------------------------
    @property
    def n_sections(self) -> int:
        return len(self.sections)

    @property
    def length(self) -> float:
        """Total backbone length L [m]."""
        return float(sum(s.length for s in self.sections))

    @property
    def section_lengths(self) -> np.ndarray:
        """``(n_sections,)`` section lengths [m]."""
        return np.array([s.length for s in self.sections])

    @property
    def section_ends(self) -> np.ndarray:
        """``(n_sections,)`` arc length at the end of each section [m]."""
        return np.cumsum(self.section_lengths)

    @property
    def n_tendons(self) -> int:
        """Total number of tendons, counted in section order."""
        return sum(s.tendons.count for s in self.sections if s.tendons is not None)

    def tendon_table(self) -> list[tuple[int, float, TendonGroup]]:
        """One ``(section_index, sigma, group)`` entry per tendon, in the global tendon order.

        Every per-tendon array in the workbench (commands, tensions) uses this order.
        """
        out = []
        for j, s in enumerate(self.sections):
            if s.tendons is not None:
                out.extend((j, a, s.tendons) for a in s.tendons.angles)
        return out

    def gravity_in_base(self) -> np.ndarray:
        """Gravity expressed in the base frame, ``(3,)`` [m/s^2]."""
        R = np.asarray(self.base_rotation)
        return R.T @ np.asarray(self.gravity)

    def disk_stations(self) -> np.ndarray:
        """Arc lengths of all disks along the whole robot, ``(n_disks_total,)`` [m]."""
        starts = np.concatenate([[0.0], self.section_ends[:-1]])
        return np.concatenate([s0 + s.disk_positions() for s0, s in zip(starts, self.sections)])

    # -- (de)serialisation at file/CLI boundaries -----------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Plain-data representation (JSON/TOML friendly); inverse of :meth:`from_dict`."""
        from dataclasses import asdict

        d = asdict(self)
        return d

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> "Robot":
        """Build a robot from plain data (as produced by :meth:`to_dict`)."""
        data = dict(data)
        sections = []
        for i, sd in enumerate(data.pop("sections")):
            sd = dict(sd)
            cs = CrossSection(**sd.pop("cross_section"))
            cst = sd.pop("cross_section_tip", None)
            td = sd.pop("tendons", None)
            sections.append(
                Section(
                    cross_section=cs,
                    cross_section_tip=None if cst is None else CrossSection(**cst),
                    tendons=None if td is None else TendonGroup(**{**td, "angles": tuple(td["angles"])}),
                    **sd,
                )
            )
        payload = data.pop("payload", None)
        return cls(
            sections=tuple(sections),
            payload=Payload(**payload) if payload is not None else Payload(),
            **{k: (tuple(tuple(r) for r in v) if k == "base_rotation" else v) for k, v in data.items()},
        )
