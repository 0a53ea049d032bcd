"""The planar ANCF problem: robot and load mapped into Exudyn's plane (pure numpy; private).

Description half of :mod:`workbench.physics.ancf` (which builds its system from :func:`build_problem`).  The robot
bends in its base x-z plane; Exudyn's plane ``(X, Y)`` is (base z, base x), so the backbone starts
along Exudyn +X and a rotation about Exudyn +Z is a rotation about base +y.  Only tendons at
``sigma = 0`` (offset ``+d`` along base x, Exudyn +Y) or ``sigma = pi`` (``-d``), within 1e-9 rad,
fit; tip forces must lie in the x-z plane and tip torques along base y; payload offsets are not
supported -- anything else raises :class:`PlanarModelError`.  Gravity: the in-plane components
``(g_z, g_x)``; a component along base y raises :class:`ModelFailure` (``g_out`` stays 0).  Mesh: elements per section in
proportion to its length (at least one each), so every section end is a node; per element EI,
EA and the backbone's own mass per length ``mu_rod`` at the element midpoint; the disks as stations and masses
(``disk_s``, ``disk_m``: ``ancf`` and ``contact`` put each disk's weight at its station).  A
tendon's offset varies linearly along its routed length ``[0, end]`` from ``TendonGroup.offset``
(base plate) to ``TendonGroup.offset_tip`` (terminating disk): for a single section this is
``TendonGroup.offset_at``; for tendons of later sections it is this model's reading of the
description (which defines the offset over the group's own section only).  Checked by
``tests/physics/test_ancf.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..models.inputs import check_model_inputs
from ..models.result import ModelFailure, SolverOptions
from ..robot import LoadCase, Robot

__all__ = ["PlanarModelError"]

_SIGMA_TOL = 1e-9
#: relative size of a base-y gravity component that is refused (rounding of a rotation matrix is far below)
_GRAVITY_TOL = 1e-9


class PlanarModelError(ValueError):
    """The robot or load does not fit the planar (base x-z) model."""


@dataclass(frozen=True)
class _Tendon:
    sign: float  # +1: sigma = 0 (base +x, Exudyn +Y); -1: sigma = pi
    end: float  # arc length of the terminating disk [m]
    d0: float  # offset at s = 0 [m]
    d1: float  # offset at s = end [m]
    EAt: float
    eyelets: tuple[float, ...]  # disk stations along the path [m], last = end

    def y(self, s):
        s = np.asarray(s, dtype=float)
        return self.sign * (self.d0 + (self.d1 - self.d0) * s / self.end)

    def dy(self, s):
        return np.full_like(np.asarray(s, dtype=float), self.sign * (self.d1 - self.d0) / self.end)


@dataclass(frozen=True)
class AncfProblem:
    L: float
    s_nodes: np.ndarray  # (n+1,)
    EI: np.ndarray  # (n,)
    EA: np.ndarray
    gravity: np.ndarray  # (2,) Exudyn plane
    tip_force: np.ndarray  # (2,)
    tip_torque: float
    payload: float
    tendons: tuple[_Tendon, ...]
    g_out: float
    cross_sections: tuple = ()  # (n,) CrossSection of every element (its midpoint), for stresses
    mu_rod: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (n,) backbone alone [kg/m]
    disk_s: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (m,) disk stations [m] (mass > 0)
    disk_m: np.ndarray = field(default_factory=lambda: np.zeros(0))  # (m,) disk masses [kg]


def _tendon_sign(sigma: float, index: int) -> float:
    w = math.remainder(sigma, 2.0 * math.pi)
    if abs(w) <= _SIGMA_TOL:
        return 1.0
    if abs(abs(w) - math.pi) <= _SIGMA_TOL:
        return -1.0
    raise PlanarModelError(
        f"tendon {index} sits at sigma = {sigma!r} rad; the planar ANCF model only accepts tendons at "
        f"sigma = 0 or pi (within {_SIGMA_TOL} rad): use a spatial model (beam3d) instead"
    )


def build_problem(robot: Robot, load: LoadCase, options: SolverOptions) -> AncfProblem:
    check_model_inputs(robot, load, options)
    L = robot.length
    F = np.asarray(load.tip_force)
    M = np.asarray(load.tip_torque)
    scale_f = max(1.0, float(np.linalg.norm(F)))
    if abs(F[1]) > 1e-12 * scale_f:
        raise PlanarModelError(f"tip_force must lie in the base x-z plane (y component 0), got {F.tolist()}")
    scale_m = max(1.0, float(np.linalg.norm(M)))
    if abs(M[0]) > 1e-12 * scale_m or abs(M[2]) > 1e-12 * scale_m:
        raise PlanarModelError(f"tip_torque must be along base y (x, z components 0), got {M.tolist()}")
    if np.any(np.asarray(robot.payload.offset) != 0.0):
        raise PlanarModelError(f"payload offset {robot.payload.offset} is not supported by the planar ANCF model")
    # mesh: elements per section proportional to length, at least one each
    lengths = robot.section_lengths
    n_sec = len(lengths)
    if options.n_elements < n_sec:
        raise ValueError(f"n_elements={options.n_elements} must be >= the number of sections ({n_sec})")
    raw = options.n_elements * lengths / L
    counts = np.maximum(1, np.floor(raw).astype(int))
    while counts.sum() < options.n_elements:
        counts[np.argmax(raw - counts)] += 1
    while counts.sum() > options.n_elements:
        k = np.argmax(np.where(counts > 1, counts - raw, -np.inf))
        counts[k] -= 1
    s_nodes = [0.0]
    EI, EA, mu_rod, sections = [], [], [], []
    s0 = 0.0
    for sec, n in zip(robot.sections, counts):
        for k in range(n):
            frac = (k + 0.5) / n
            cs = sec.cross_section_at(frac)
            sections.append(cs)
            EI.append(cs.EI)
            EA.append(cs.EA)
            mu_rod.append(cs.mass_per_length)
            s_nodes.append(s0 + sec.length * (k + 1) / n)
        s0 += sec.length
    s_nodes = np.array(s_nodes)
    s_nodes[-1] = L
    g = robot.gravity_in_base()
    if abs(g[1]) > _GRAVITY_TOL * float(np.linalg.norm(g)):
        raise ModelFailure(
            f"gravity {np.round(g, 12).tolist()} m/s^2 (base frame) has a component {g[1]:.4g} m/s^2 along base y, "
            "out of the plane of the planar ANCF models (robot.base_orientation / robot.gravity_direction): "
            "refused instead of dropped; use a spatial model (beam3d, cosserat)")
    ends = robot.section_ends
    disks = robot.disk_stations()
    disk_m = np.concatenate([np.full(sec.n_disks, sec.disk_mass) for sec in robot.sections])
    tendons = []
    for i, (j, sigma, grp) in enumerate(robot.tendon_table()):
        sign = _tendon_sign(sigma, i)
        end = float(s_nodes[np.argmin(np.abs(s_nodes - ends[j]))])
        d1 = grp.offset if grp.offset_tip is None else grp.offset_tip
        eyes = tuple(float(x) for x in disks[disks <= ends[j] * (1 + 1e-12)])
        tendons.append(_Tendon(sign, end, grp.offset, d1, grp.axial_stiffness, eyes))
    return AncfProblem(
        L=L, s_nodes=s_nodes, EI=np.array(EI), EA=np.array(EA),
        gravity=np.array([g[2], g[0]]), tip_force=np.array([F[2], F[0]]), tip_torque=float(M[1]),
        payload=robot.payload.mass, tendons=tuple(tendons), g_out=float(g[1]), cross_sections=tuple(sections),
        mu_rod=np.array(mu_rod), disk_s=disks[disk_m > 0], disk_m=disk_m[disk_m > 0],
    )
