"""Discretisation of a robot into a chain of rigid links (no Exudyn; pure numpy).

Layout ("half-link" or tangent-polygon discretisation) for ``N`` links:

* eyelet (disk) stations ``e_0 = 0 < e_1 < ... < e_N = L``; every section of the robot holds
  ``N / n_sections`` equally spaced intervals, so every section end is an eyelet station;
* joint ``k`` (``k = 1..N``) sits at the middle of ``[e_{k-1}, e_k]`` and stands for the rod
  piece ``[e_{k-1}, e_k]`` of length ``ds_k = e_k - e_{k-1}``: its rotational stiffness is
  ``EI(s_k) / ds_k`` (equivalent rod);
* link ``k`` runs from joint ``k`` to joint ``k + 1`` (the last link from joint ``N`` to the tip,
  half as long); it carries eyelet ``k`` at ``e_k - s_k = ds_k / 2`` past its joint.  The
  ground (base plate) carries eyelet 0 and the rod piece ``[0, s_1]``.

Under a pure end moment all joints turn by ``kappa ds``, so the tip orientation is exact and the
positions converge as ``O(1/N^2)``.  The link stations ``e_k`` carry continuum tendons; eyelet ropes
pass the robot's disks instead (see :mod:`.routing`).  With one disk per link
a straight rope segment spans exactly one joint at half-distance ``ds/2`` either side, which is
the joint geometry of Hannan & Walker's Eq (1) with ``h = ds/2``.  Checked by
``tests/physics/test_hannan_walker.py`` (joint springs and masses of the preset, Eq. 1 = measured rope
lengths) and ``test_spring_link_eyelets.py`` (disk placement).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...robot import Robot

__all__ = ["ChainGeometry", "chain_geometry_from_robot"]


@dataclass(frozen=True)
class ChainGeometry:
    """Reference geometry and lumped properties of an ``N``-link chain.

    Attributes
    ----------
    eyelets : ndarray, shape (N + 1,)
        Eyelet stations ``e_k`` [m] (``e_0 = 0``, ``e_N = L``).
    joints : ndarray, shape (N,)
        Joint stations ``s_k`` [m].
    link_lengths : ndarray, shape (N,)
        Length of link ``k`` (joint ``k`` to joint ``k+1`` or to the tip) [m].
    stiffness : ndarray, shape (N,)
        Bending stiffness of joint ``k`` [N m / rad], ``EI(s_k) / ds_k``.
    torsion_stiffness : ndarray, shape (N,)
        Torsional stiffness of joint ``k`` [N m / rad], ``GJ(s_k) / ds_k``.
    axial_stiffness : ndarray, shape (N,)
        Axial stiffness of joint ``k`` [N/m], ``EA(s_k) / ds_k``.
    shear_stiffness : ndarray, shape (N,)
        Shear stiffness of joint ``k`` [N/m], ``GA(s_k) / ds_k`` (``EA`` where ``GA`` is None).
    mass : ndarray, shape (N,)
        Link masses [kg] (rod material of the link span plus the disks on it, each a point mass
        at its own station).
    com : ndarray, shape (N,)
        Centre of mass of each link, distance from its joint along the link [m].
    inertia_bending : ndarray, shape (N,)
        Moment of inertia about a transverse axis through the centre of mass [kg m^2].
    inertia_axial : ndarray, shape (N,)
        Moment of inertia about the link axis [kg m^2].
    section_end_eyelet : ndarray of int, shape (n_sections,)
        Index ``k`` of the eyelet at the end of each section.
    """

    eyelets: np.ndarray
    joints: np.ndarray
    link_lengths: np.ndarray
    stiffness: np.ndarray
    torsion_stiffness: np.ndarray
    axial_stiffness: np.ndarray
    shear_stiffness: np.ndarray
    mass: np.ndarray
    com: np.ndarray
    inertia_bending: np.ndarray
    inertia_axial: np.ndarray
    section_end_eyelet: np.ndarray

    @property
    def n_links(self) -> int:
        return int(self.joints.size)


def section_of(robot: Robot, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Section index and fraction within the section for stations ``s``."""
    ends = robot.section_ends
    starts = np.concatenate([[0.0], ends[:-1]])
    idx = np.clip(np.searchsorted(ends, s, side="left"), 0, robot.n_sections - 1)
    frac = (s - starts[idx]) / robot.section_lengths[idx]
    return idx, np.clip(frac, 0.0, 1.0)


def _check_link_count(robot: Robot, n_links: int) -> None:
    n_sec = robot.n_sections
    if int(n_links) != n_links or n_links < 1 or n_links % n_sec:
        raise ValueError(
            f"spring_link: the number of links (options.n_elements) must be a positive multiple of the "
            f"number of sections ({n_sec}), got {n_links!r}"
        )


def _eyelet_stations(robot: Robot, per: int) -> np.ndarray:
    """Eyelet stations ``e_k`` (N + 1,): ``per`` equal intervals in every section, ``e_N = L``."""
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    e = [0.0]
    for s0, sec in zip(starts, robot.sections):
        e.extend(s0 + sec.length * np.arange(1, per + 1) / per)
    eyelets = np.asarray(e)
    eyelets[-1] = robot.length
    return eyelets


def _section_properties(robot: Robot, s: np.ndarray) -> dict[str, np.ndarray]:
    """EI, GJ, EA, GA (EA where None), mass per length ``mu`` and diameter ``d`` at stations ``s``."""
    idx, frac = section_of(robot, s)
    out: dict[str, list[float]] = {"EI": [], "GJ": [], "EA": [], "GA": [], "mu": [], "d": []}
    for i, f in zip(idx, frac):
        cs = robot.sections[i].cross_section_at(f)
        out["EI"].append(cs.EI)
        out["GJ"].append(cs.GJ)
        out["EA"].append(cs.EA)
        out["GA"].append(cs.EA if cs.GA is None else cs.GA)
        out["mu"].append(cs.mass_per_length)
        out["d"].append(0.0 if cs.diameter is None else cs.diameter)
    return {k: np.asarray(v) for k, v in out.items()}


def _rod_moments(robot: Robot, joints: np.ndarray, ends: np.ndarray, n_quad: int) -> tuple[np.ndarray, ...]:
    """Rod mass over each link span ``[joints[k], ends[k]]`` (Gauss-Legendre) and its first and
    second moments about the joint, plus ``sum w mu d^2`` for the solid-disk inertia terms."""
    xg, wg = np.polynomial.legendre.leggauss(n_quad)
    a, b = joints[:, None], ends[:, None]
    s = 0.5 * (a + b) + 0.5 * (b - a) * xg[None, :]   # (N, n_quad) Gauss points of every link
    w = 0.5 * (b - a) * wg[None, :]
    p = {k: v.reshape(s.shape) for k, v in _section_properties(robot, s.ravel()).items()}
    mass = np.sum(w * p["mu"], axis=1)
    first = np.sum(w * p["mu"] * (s - a), axis=1)
    second = np.sum(w * p["mu"] * (s - a) ** 2, axis=1)
    radial = np.sum(w * p["mu"] * p["d"] ** 2, axis=1)
    return mass, first, second, radial


def _disk_loads(robot: Robot, joints: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Disks as point masses at their own stations (``robot.disk_stations()``).

    A disk at station ``s`` sits on the link whose span ``[s_k, s_{k+1})`` contains it (the last
    link up to the tip), at ``s - s_k`` past that link's joint; a disk below the first joint sits
    on the base plate and loads nothing.  Returns per link the disk mass, its first and its second
    moment about the joint, so each disk's weight and inertia act at its own station (the
    point-load beam of ``tests/physics/test_spring_link_crossexam.py``).
    """
    n_links = joints.size
    mass, first, second = np.zeros(n_links), np.zeros(n_links), np.zeros(n_links)
    st = robot.disk_stations()
    m = np.concatenate([np.full(sec.n_disks, sec.disk_mass) for sec in robot.sections])
    k = np.searchsorted(joints, st, side="right") - 1
    on = (k >= 0) & (m > 0)
    z = st[on] - joints[k[on]]
    np.add.at(mass, k[on], m[on])
    np.add.at(first, k[on], m[on] * z)
    np.add.at(second, k[on], m[on] * z**2)
    return mass, first, second


def chain_geometry_from_robot(robot: Robot, n_links: int, n_quad: int = 8) -> ChainGeometry:
    """Discretise ``robot`` into ``n_links`` rigid links (see the module docstring).

    Parameters
    ----------
    robot : Robot
        The robot; its cross-sections give EI, GJ, EA, mass per length and diameter.
    n_links : int
        Number of links ``N``; must be a multiple of the number of sections.
    n_quad : int
        Gauss points per link for mass and centre-of-mass integration of tapered sections.

    Returns
    -------
    ChainGeometry

    Raises
    ------
    ValueError
        ``n_links`` is not a positive multiple of the number of sections.
    """
    _check_link_count(robot, n_links)
    n_links = int(n_links)
    per = n_links // robot.n_sections
    eyelets = _eyelet_stations(robot, per)
    ds = np.diff(eyelets)
    joints = 0.5 * (eyelets[:-1] + eyelets[1:])
    ends = np.append(joints[1:], robot.length)
    link_lengths = ends - joints
    pj = _section_properties(robot, joints)
    mass, first, second, radial = _rod_moments(robot, joints, ends, n_quad)
    disk, disk_first, disk_second = _disk_loads(robot, joints)
    m_tot = mass + disk
    if np.any(m_tot <= 0):
        # massless chain: keep a tiny mass so that the rigid bodies are well defined in dynamics;
        # statics does not depend on it.
        m_tot = np.where(m_tot > 0, m_tot, 1e-9)
    com = (first + disk_first) / np.where(mass + disk > 0, mass + disk, 1.0)
    com = np.where(mass + disk > 0, com, 0.5 * link_lengths)
    I_about_joint = second + disk_second + radial / 16.0
    return ChainGeometry(
        eyelets=eyelets,
        joints=joints,
        link_lengths=link_lengths,
        stiffness=pj["EI"] / ds,
        torsion_stiffness=pj["GJ"] / ds,
        axial_stiffness=pj["EA"] / ds,
        shear_stiffness=pj["GA"] / ds,
        mass=m_tot,
        com=com,
        inertia_bending=np.maximum(I_about_joint - m_tot * com**2, 1e-12),
        inertia_axial=np.maximum(radial / 8.0, 1e-12),
        section_end_eyelet=(np.arange(1, robot.n_sections + 1) * per).astype(int),
    )
