"""Robot description -> the planar contact system, and the registry model ``"contact"`` (no object).

:func:`planar_setup` maps a robot onto the planar mesh (``_ancf_problem``) and the per-element half
diameters; :func:`tendon_strains` turns continuum-tendon tensions into the exact prescribed strains
(moment ``T y cos(alpha)`` and compression ``T cos(alpha)`` per element, as
:mod:`workbench.physics.ancf` does it); :func:`chamber_strains` does the same for fluidic chamber
pressures (:mod:`workbench.robot.fluidic`).  :func:`run` is ``run(robot, load, options)`` of the
registered model ``"contact"``: the contact system without an object, tension-mode continuum
tendons, statics -- it equals ``ancf`` with continuum tendons to solver precision
(``tests/physics/test_contact.py``), which is what makes the contact rows comparable with the
other models.  Grasp tasks with an object: :mod:`.procedures` and ``workbench/experiments``.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from ...models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot
from .._ancf_problem import PlanarModelError, build_problem

__all__ = ["planar_setup", "tendon_strains", "section_tendon_strains", "chamber_strains", "without_tendons",
           "section_of_elements", "run"]


def without_tendons(robot: Robot) -> Robot:
    """The robot with every tendon group removed (a fluidic section's chambers replace them)."""
    return replace(robot, sections=tuple(replace(s, tendons=None) for s in robot.sections))


def planar_setup(robot: Robot, options: SolverOptions, load: LoadCase | None = None):
    """``(pb, half_width)``: the planar problem (mesh, stiffness, gravity in Exudyn's plane) and the
    half diameter [m] of every element (0 where the description gives no diameter)."""
    pb = build_problem(robot, load if load is not None else LoadCase(), options)
    sec, frac = section_of_elements(robot, pb.s_nodes)
    hw = np.array([0.5 * (robot.sections[j].cross_section_at(f).diameter or 0.0) for j, f in zip(sec, frac)])
    return pb, hw


def section_of_elements(robot: Robot, s_nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Section index and fraction within the section of every element midpoint, ``(n_el,)`` each."""
    mid = 0.5 * (s_nodes[1:] + s_nodes[:-1])
    ends = robot.section_ends
    sec = np.minimum(np.searchsorted(ends, mid), robot.n_sections - 1)
    start = np.concatenate([[0.0], ends[:-1]])[sec]
    return sec, (mid - start) / robot.section_lengths[sec]


def tendon_strains(pb, tensions) -> tuple[np.ndarray, np.ndarray]:
    """Prescribed strains ``(kappa0, eps0)`` per element of continuum tendons with tensions [N] (global order).

    ``kappa0 = sum T y cos(alpha) / EI`` (per reference length, > 0 towards base +x),
    ``eps0 = -sum T cos(alpha) / EA`` with ``y`` the tendon offset and ``tan(alpha) = y'``.
    """
    T = np.asarray(tensions, dtype=float).reshape(-1)
    if T.size != len(pb.tendons):
        raise ValueError(f"need {len(pb.tendons)} tensions, got {T.size}")
    sn = pb.s_nodes
    smid = 0.5 * (sn[1:] + sn[:-1])
    kap = np.zeros(smid.size)
    eps = np.zeros(smid.size)
    for Ti, td in zip(T, pb.tendons):
        on = smid < td.end
        cosa = 1.0 / np.sqrt(1.0 + td.dy(smid) ** 2)
        kap += np.where(on, Ti * td.y(smid) * cosa / pb.EI, 0.0)
        eps += np.where(on, -Ti * cosa / pb.EA, 0.0)
    return kap, eps


def chamber_strains(robot: Robot, pb, layouts, pressures, *, plane_tolerance: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """Prescribed strains per element of fluidic chambers (one :class:`~workbench.robot.fluidic.ChamberLayout`
    and one pressure vector [Pa] per section).

    Raises
    ------
    PlanarModelError
        The chambers bend a section out of the base x-z plane (moment component along base y).
    """
    from ...robot.fluidic import section_loads

    sec, _ = section_of_elements(robot, pb.s_nodes)
    N = np.zeros(robot.n_sections)
    M = np.zeros(robot.n_sections)
    for j, (lay, p) in enumerate(zip(layouts, pressures)):
        if lay is None:
            continue
        n_j, m_j = section_loads(lay, p)
        if abs(m_j[1]) > plane_tolerance * max(1.0, float(np.hypot(*m_j))):
            raise PlanarModelError(f"the chambers of section {j} bend it out of the base x-z plane "
                                   f"(moment {m_j.tolist()} N m); the planar contact model needs phi = 0 or pi")
        N[j], M[j] = n_j, m_j[0]
    return M[sec] / pb.EI, N[sec] / pb.EA


def section_tendon_strains(robot: Robot, pb, tensions, *, plane_tolerance: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """Prescribed strains per element of continuum tendons at *any* angles whose moments stay in the x-z plane.

    Per section the tendons passing through it give the moment ``sum T d (cos sigma, sin sigma)``
    (d: the group's offset; constant offsets only) and the compression ``sum T``; the out-of-plane
    component must cancel (e.g. two equal tendons at +-120 deg).  For tendons at ``sigma = 0, pi``
    this equals :func:`tendon_strains`.

    Raises
    ------
    PlanarModelError
        A tapered tendon group, or a net moment out of the base x-z plane in some section.
    """
    T = np.asarray(tensions, dtype=float).reshape(-1)
    table = robot.tendon_table()
    if T.size != len(table):
        raise ValueError(f"need {len(table)} tensions, got {T.size}")
    sec, _ = section_of_elements(robot, pb.s_nodes)
    N = np.zeros(robot.n_sections)
    M = np.zeros(robot.n_sections)
    for j in range(robot.n_sections):
        m = np.zeros(2)
        for Ti, (k, sigma, grp) in zip(T, table):
            if grp.offset_tip is not None:
                raise PlanarModelError("the planar contact model takes tendons of constant offset only")
            if k >= j:
                m += Ti * grp.offset * np.array([np.cos(sigma), np.sin(sigma)])
                N[j] -= Ti
        if abs(m[1]) > plane_tolerance * max(1.0, float(np.hypot(*m))):
            raise PlanarModelError(f"the tendons bend section {j} out of the base x-z plane (moment {m.tolist()} N m)")
        M[j] = m[0]
    return M[sec] / pb.EI, N[sec] / pb.EA


def _check_load(load: LoadCase) -> np.ndarray:
    if load.analysis != "static":
        raise ModelFailure("the contact model is static only (analysis = 'static')")
    if np.any(np.asarray(load.tip_force) != 0) or np.any(np.asarray(load.tip_torque) != 0):
        raise PlanarModelError("the contact model takes no tip force or torque (give the load to ancf instead)")
    act = load.actuation
    if act is None:
        return np.zeros(0)
    if act.mode != "tension":
        raise PlanarModelError("the contact model drives continuum tendons in tension mode only (mode = 'tension')")
    return np.asarray(act.values, dtype=float)


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Planar contact model without an object (model ``"contact"``; module docstring).

    Tendon strains and gravity are ramped together (adaptive halving, at most
    ``options.max_load_steps`` attempts).  ``options.tendon_model`` must be ``"continuum"``.
    """
    from .._exudyn import quiet_exudyn
    from .system import PlanarContactSystem

    t0 = time.perf_counter()
    if options.tendon_model != "continuum":
        raise PlanarModelError("the contact model uses continuum tendons (solver.tendon_model = 'continuum')")
    T = _check_load(load)
    pb, hw = planar_setup(robot, options, load)
    if T.size == 0:
        T = np.zeros(len(pb.tendons))
    kap, eps = tendon_strains(pb, T)
    stations = np.linspace(0.0, pb.L, options.n_stations)
    with quiet_exudyn():
        sysm = PlanarContactSystem(pb, hw, tolerance=options.newton_tolerance)

        def apply(lam: float) -> None:
            sysm.set_strains(lam * kap, lam * eps)
            sysm.set_gravity(lam)

        steps = sysm.load_ramp(apply, options.max_load_steps)
        pos, tan = sysm.positions(stations)
        length_change = sysm.arc_length() - pb.L
    th = math.atan2(tan[-1, 0], tan[-1, 2])
    H = np.eye(4)
    H[:3, :3] = [[math.cos(th), 0.0, math.sin(th)], [0.0, 1.0, 0.0], [-math.sin(th), 0.0, math.cos(th)]]
    H[:3, 3] = pos[-1]
    return PhysicsResult(
        model="contact", stations=stations, positions=pos, tip_frame=H, length_change=length_change,
        tendon_tensions=T, tip_twist=0.0,
        solver=SolverInfo(converged=True, iterations=sysm.newton, wall_time=time.perf_counter() - t0,
                          message=f"{steps} load steps"),
        extras={"static_steps": float(steps), "gravity_out_of_plane": pb.g_out},
    )
