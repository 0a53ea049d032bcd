"""Fluidic (pneumatic) chamber actuation of one section: pressures <-> section loads <-> CC arc.

A section driven by pressurised chambers (Shao et al.'s flexible pneumatic actuators, FPAs;
papers/002_, Sec. 2.2: "When the FPA was pressurized, it elongated in the axial direction")
is modelled as the section's equivalent elastic rod plus one straight chamber line per
angular position ``sigma_i`` at offset ``d`` from the centreline.  A chamber at pressure ``p_i``
with effective piston area ``A`` pushes the plates apart with ``F_i = A p_i`` (chambers in series
between plates carry the same force).  On the rod this is a tendon with a *negative* tension:

* axial force ``N = sum_i F_i`` (tension of the rod: the section **lengthens**, where tendons
  shorten it);
* bending moment ``m = sum_i F_i d (-cos sigma_i, -sin sigma_i)`` as a curvature-direction
  vector in the base x-y plane: a pressurised chamber bends the section *away* from itself.

With the extensible rod's constitutive law (Reissner: ``N = EA eps``, ``M = EI dtheta/dS`` with
``S`` the reference arc length; the law of the 2-D ANCF cable that the physics uses, checked by
``tests/physics/test_contact.py``) a section of reference length ``L`` becomes the arc

``s = L (1 + N / EA)``, ``theta = |m| L / EI``, ``kappa = theta / s``, ``phi = atan2(m_y, m_x)``,

i.e. Shao's joint variables ``q = [s, k, phi]`` (Eq 1-5) follow from the pressures.  What the
paper does not give and is therefore an **assumption of every study that uses this**: the
linear force law ``F = A p`` (no FPA hysteresis, no pressure-dependent stiffness; the paper only
says pressures are computed "according to the FPAs' characteristics and geometry", Sec. 4,
citing an unavailable thesis), the effective area ``A``, and that the chambers' own elasticity
is part of the rod's ``EI`` and ``EA``.  The paper gives the maximum pressure, 0.6 MPa.

Pure numpy.  Checked by ``tests/robot/test_fluidic.py`` (round trips, limits, signs against a
tendon) and, through the planar contact model, by ``tests/physics/test_contact.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .description import RobotDescriptionError, checked_positive

__all__ = ["ChamberLayout", "chamber_forces", "section_loads", "arc_from_pressures", "pressures_from_arc",
           "pressures_for_bend"]


@dataclass(frozen=True)
class ChamberLayout:
    """The chamber lines of one section.

    Parameters
    ----------
    angles : tuple of float
        Angular positions ``sigma_i`` [rad] from the base x axis (at least 3, not all on one
        line, for bending in any plane).
    offset : float
        Radial offset ``d`` [m] of the chamber axes from the centreline.
    area : float
        Effective piston area ``A`` [m^2] (force per unit pressure).
    max_pressure : float
        Largest admissible gauge pressure [Pa] (``inf``: no limit).
    """

    angles: tuple[float, ...]
    offset: float
    area: float
    max_pressure: float = math.inf

    def __post_init__(self) -> None:
        ang = np.asarray(self.angles, dtype=float).reshape(-1)
        if ang.size < 1 or not np.all(np.isfinite(ang)):
            raise RobotDescriptionError("ChamberLayout.angles must hold at least one finite angle")
        object.__setattr__(self, "angles", tuple(float(a) for a in ang))
        object.__setattr__(self, "offset", checked_positive("ChamberLayout.offset", self.offset))
        object.__setattr__(self, "area", checked_positive("ChamberLayout.area", self.area))
        mp = float(self.max_pressure)
        if not mp > 0 or math.isnan(mp):
            raise RobotDescriptionError(f"ChamberLayout.max_pressure must be > 0, got {mp}")
        object.__setattr__(self, "max_pressure", mp)

    @property
    def count(self) -> int:
        """Number of chamber lines."""
        return len(self.angles)


def _pressures(layout: ChamberLayout, pressures) -> np.ndarray:
    p = np.asarray(pressures, dtype=float).reshape(-1)
    if p.shape != (layout.count,):
        raise ValueError(f"need one pressure per chamber ({layout.count}), got {p.size}")
    if not np.all(np.isfinite(p)) or np.any(p < 0):
        raise ValueError(f"chamber pressures must be finite and >= 0 (gauge, a chamber cannot pull), got {p.tolist()}")
    return p


def chamber_forces(layout: ChamberLayout, pressures) -> np.ndarray:
    """Push force ``F_i = A p_i`` [N] of every chamber line, ``(n,)``; pressures [Pa]."""
    return layout.area * _pressures(layout, pressures)


def section_loads(layout: ChamberLayout, pressures) -> tuple[float, np.ndarray]:
    """Axial force ``N`` [N] (> 0 lengthens) and bending moment vector ``m`` (2,) [N m] of the chambers.

    ``m`` points in the direction the section bends towards (base x-y plane):
    ``m = sum_i F_i d (-cos sigma_i, -sin sigma_i)``.
    """
    F = chamber_forces(layout, pressures)
    sig = np.asarray(layout.angles)
    m = -layout.offset * np.array([np.sum(F * np.cos(sig)), np.sum(F * np.sin(sig))])
    return float(F.sum()), m


def arc_from_pressures(layout: ChamberLayout, pressures, EI: float, EA: float, length: float
                       ) -> tuple[float, float, float]:
    """Constant-curvature arc ``(s, kappa, phi)`` of a section under chamber pressures (module docstring).

    Returns
    -------
    s : float
        Arc length [m] (``L (1 + N / EA)``).
    kappa : float
        Curvature [1/m] of the arc (``theta / s`` with ``theta = |m| L / EI``).
    phi : float
        Bending direction [rad] (0 when straight).
    """
    N, m = section_loads(layout, pressures)
    s = float(length) * (1.0 + N / float(EA))
    theta = float(np.hypot(*m)) * float(length) / float(EI)
    phi = float(np.arctan2(m[1], m[0])) if theta > 0 else 0.0
    return s, theta / s, phi


def pressures_from_arc(layout: ChamberLayout, kappa: float, phi: float, EI: float, EA: float, length: float,
                       s: float | None = None) -> np.ndarray:
    """Chamber pressures [Pa] that give the arc ``(s, kappa, phi)`` (inverse of :func:`arc_from_pressures`).

    Parameters
    ----------
    kappa, phi : float
        Curvature [1/m] (>= 0) and bending direction [rad].
    EI, EA, length : float
        The section's equivalent rod and reference length [m].
    s : float, optional
        Arc length [m].  ``None``: the shortest arc, i.e. the least total chamber force that
        bends the section (at least one chamber unpressurised).

    Raises
    ------
    ValueError
        No non-negative pressures give the arc (``s`` too short for that bend: chambers can only
        lengthen), or a pressure exceeds ``layout.max_pressure``.
    """
    from scipy.optimize import linprog

    if not (math.isfinite(kappa) and kappa >= 0):
        raise ValueError(f"kappa must be finite and >= 0, got {kappa}")
    sig = np.asarray(layout.angles)
    d, L = layout.offset, float(length)
    # unknowns F_i >= 0:  N = sum F (from s);  -d sum F (cos, sin) = EI theta / L (cos phi, sin phi)
    A_bend = -d * np.vstack([np.cos(sig), np.sin(sig)])
    if s is None:
        # least total force for the bend; theta depends on s = L (1 + sum F / EA): kappa s = theta
        # with sum F = N  ->  A_bend F = EI kappa (1 + N/EA) e  (linear in F)
        e = np.array([math.cos(phi), math.sin(phi)])
        A_eq = A_bend - (EI * kappa / EA) * np.outer(e, np.ones(sig.size))
        b_eq = EI * kappa * e
        res = linprog(np.ones(sig.size), A_eq=A_eq, b_eq=b_eq, bounds=[(0, None)] * sig.size, method="highs")
        if not res.success:
            raise ValueError(f"no chamber pressures bend the section to kappa = {kappa:.4g} 1/m in the plane "
                             f"phi = {phi:.4g} rad ({res.message})")
        F = res.x
    else:
        if not s >= L * (1.0 - 1e-12):
            raise ValueError(f"chambers only lengthen the section: s = {s:.6g} m < L = {L:.6g} m")
        theta = kappa * s
        A = np.vstack([A_bend, np.ones(sig.size)])
        b = np.concatenate([EI * theta / L * np.array([math.cos(phi), math.sin(phi)]), [EA * (s / L - 1.0)]])
        res = linprog(np.zeros(sig.size), A_eq=A, b_eq=b, bounds=[(0, None)] * sig.size, method="highs")
        if not res.success:
            raise ValueError(f"no non-negative chamber pressures give s = {s:.6g} m, kappa = {kappa:.4g} 1/m, "
                             f"phi = {phi:.4g} rad: the bend needs more extension than that")
        F = res.x
    p = np.maximum(F, 0.0) / layout.area
    if np.any(p > layout.max_pressure * (1 + 1e-9)):
        raise ValueError(f"the arc needs a chamber pressure of {p.max() / 1e6:.4g} MPa, above the limit of "
                         f"{layout.max_pressure / 1e6:.4g} MPa")
    return p


def pressures_for_bend(layout: ChamberLayout, theta: float, phi: float, EI: float, length: float) -> np.ndarray:
    """The least chamber pressures [Pa] that bend a section by ``theta`` [rad] towards ``phi`` [rad].

    ``theta = |m| L / EI`` does not depend on the extension, so this is a linear programme in the
    chamber forces (least total force).  The arc length follows from :func:`arc_from_pressures`.

    Raises
    ------
    ValueError
        The chambers cannot bend the section towards ``phi``, or a pressure exceeds the limit.
    """
    from scipy.optimize import linprog

    if not (math.isfinite(theta) and theta >= 0):
        raise ValueError(f"bend angle must be finite and >= 0, got {theta}")
    sig = np.asarray(layout.angles)
    A = -layout.offset * np.vstack([np.cos(sig), np.sin(sig)])
    b = float(EI) * theta / float(length) * np.array([math.cos(phi), math.sin(phi)])
    res = linprog(np.ones(sig.size), A_eq=A, b_eq=b, bounds=[(0, None)] * sig.size, method="highs")
    if not res.success:
        raise ValueError(f"the chambers cannot bend the section by {theta:.4g} rad towards phi = {phi:.4g} rad")
    p = np.maximum(res.x, 0.0) / layout.area
    if np.any(p > layout.max_pressure * (1 + 1e-9)):
        raise ValueError(f"a bend of {theta:.4g} rad needs a chamber pressure of {p.max() / 1e6:.4g} MPa, above the "
                         f"limit of {layout.max_pressure / 1e6:.4g} MPa")
    return p
