"""The rod problem the Cosserat model solves, built from a robot and a load case (pure numpy).

Everything is in the robot's base frame and SI units.  The rod's reference state is straight
along base +z with its cross-section frame equal to the base frame (material axis 3 = tangent,
axis 1 = base x), so a tendon at angle ``sigma`` and offset ``d`` sits at
``r(s) = d(s) (cos sigma, sin sigma, 0)`` in the material frame.  Integration segments end at
every section end (the set of tendons changes there) and at every disk that carries mass (its
weight is a point force on the centreline).  Checked by ``tests/physics/test_cosserat_model.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...robot import LoadCase, Robot

__all__ = ["RodProblem", "rod_problem", "GA_FACTOR_IF_NONE"]

#: Shear stiffness ``GA = 100 EA`` where ``CrossSection.GA`` is None (the shear-rigid limit; as
#: ``beam3d``).
GA_FACTOR_IF_NONE = 100.0


@dataclass(frozen=True)
class RodProblem:
    """A clamped Cosserat rod with continuously routed tendons.

    Attributes
    ----------
    length : float
        Reference length L [m].
    section_starts, section_lengths : ndarray, shape (n_sec,)
        Arc length where each section starts and its length [m].
    stiffness0, stiffness1 : ndarray, shape (n_sec, 6)
        ``(GA, GA, EA, EI, EI, GJ)`` at the start and end of each section (linear taper between).
    mass_per_length0, mass_per_length1 : ndarray, shape (n_sec,)
        Mass per length at the start and end of each section [kg/m].
    gravity : ndarray, shape (3,)
        Gravity in the base frame [m/s^2].
    tendon_dirs : ndarray, shape (n_t, 3)
        ``(cos sigma, sin sigma, 0)`` of every tendon (global tendon order).
    tendon_offsets : ndarray, shape (n_t, 2)
        Offset at the base plate and at the terminating section end [m].
    tendon_ends : ndarray, shape (n_t,)
        Arc length where each tendon terminates [m].
    tendon_stiffness : ndarray, shape (n_t,)
        ``EA_t`` [N].
    breakpoints : ndarray, shape (k,)
        Segment ends from 0 to L (section ends and loaded disks).
    point_forces : ndarray, shape (k, 3)
        Point force on the centreline at each breakpoint [N] (disk weights; 0 at 0 and L).
    tip_force, tip_torque : ndarray, shape (3,)
        Tip loads, base frame [N], [N m].
    payload_mass : float
        Tip payload [kg].
    payload_offset : ndarray, shape (3,)
        Payload centre of mass in the tip frame [m].
    """

    length: float
    section_starts: np.ndarray
    section_lengths: np.ndarray
    stiffness0: np.ndarray
    stiffness1: np.ndarray
    mass_per_length0: np.ndarray
    mass_per_length1: np.ndarray
    gravity: np.ndarray
    tendon_dirs: np.ndarray
    tendon_offsets: np.ndarray
    tendon_ends: np.ndarray
    tendon_stiffness: np.ndarray
    breakpoints: np.ndarray
    point_forces: np.ndarray
    tip_force: np.ndarray
    tip_torque: np.ndarray
    payload_mass: float
    payload_offset: np.ndarray

    @property
    def n_tendons(self) -> int:
        return int(self.tendon_ends.size)

    def section_of(self, s: float) -> int:
        """Index of the section containing ``s`` (a section end belongs to its own section)."""
        ends = self.section_starts + self.section_lengths
        return int(min(np.searchsorted(ends, s - 1e-12 * self.length, side="left"), ends.size - 1))

    def reference_tendon_lengths(self) -> np.ndarray:
        """``(n_t,)`` tendon path lengths of the straight unloaded rod [m] (a taper slants them)."""
        slope = (self.tendon_offsets[:, 1] - self.tendon_offsets[:, 0]) / self.tendon_ends
        return self.tendon_ends * np.sqrt(1.0 + slope**2)


def _stiffness(cs) -> np.ndarray:
    GA = cs.GA if cs.GA is not None else GA_FACTOR_IF_NONE * cs.EA
    return np.array([GA, GA, cs.EA, cs.EI, cs.EI, cs.GJ], dtype=float)


def rod_problem(robot: Robot, load: LoadCase) -> RodProblem:
    """The :class:`RodProblem` of ``robot`` under ``load`` (tendon tensions are passed separately).

    Disk masses act as point forces at the disk stations, the payload at its offset from the tip;
    the tip force and torque are dead loads in the base frame (as in every model).
    """
    n_sec = robot.n_sections
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    k0 = np.array([_stiffness(s.cross_section_at(0.0)) for s in robot.sections])
    k1 = np.array([_stiffness(s.cross_section_at(1.0)) for s in robot.sections])
    mu0 = np.array([s.cross_section_at(0.0).mass_per_length for s in robot.sections])
    mu1 = np.array([s.cross_section_at(1.0).mass_per_length for s in robot.sections])
    g = np.asarray(robot.gravity_in_base(), dtype=float)
    table = robot.tendon_table()
    ends = robot.section_ends
    dirs = np.array([[np.cos(sig), np.sin(sig), 0.0] for _, sig, _ in table]).reshape(-1, 3)
    offs = np.array([[grp.offset_at(0.0), grp.offset_at(1.0)] for _, _, grp in table]).reshape(-1, 2)
    t_end = np.array([ends[j] for j, _, _ in table], dtype=float)
    eat = np.array([grp.axial_stiffness for _, _, grp in table], dtype=float)
    L = robot.length
    pts = {0.0: np.zeros(3), L: np.zeros(3)}
    for e in ends:
        pts.setdefault(float(e), np.zeros(3))
    for j, sec in enumerate(robot.sections):
        if sec.disk_mass > 0:
            for sd in sec.disk_positions():
                s = min(float(starts[j] + sd), L)
                pts[s] = pts.get(s, np.zeros(3)) + sec.disk_mass * g
    keys = sorted(pts)
    # merge stations closer than round-off (a disk at a section end)
    bp, pf = [keys[0]], [pts[keys[0]]]
    for s in keys[1:]:
        if s - bp[-1] < 1e-12 * L:
            pf[-1] = pf[-1] + pts[s]
        else:
            bp.append(s)
            pf.append(pts[s])
    bp[-1] = L
    return RodProblem(
        length=L, section_starts=starts, section_lengths=robot.section_lengths.astype(float),
        stiffness0=k0, stiffness1=k1, mass_per_length0=mu0, mass_per_length1=mu1, gravity=g,
        tendon_dirs=dirs, tendon_offsets=offs, tendon_ends=t_end, tendon_stiffness=eat,
        breakpoints=np.asarray(bp), point_forces=np.asarray(pf),
        tip_force=np.asarray(load.tip_force, dtype=float), tip_torque=np.asarray(load.tip_torque, dtype=float),
        payload_mass=float(robot.payload.mass), payload_offset=np.asarray(robot.payload.offset, dtype=float),
    )
