"""Pseudo-rigid-body chain (Hencky bar-chain) model of a planar tendon-driven rod: ``run(robot, load, options)``.

The backbone (reference length L, inextensible, unshearable) is cut into ``n`` rigid links joined by
rotational springs -- the Hencky bar-chain (H. Hencky, "Über die angenäherte Lösung von
Stabilitätsproblemen im Raum mittels der elastischen Gelenkkette", Der Eisenbau 11, 1920, 437-452), a
pseudo-rigid-body model in the sense of L. L. Howell, *Compliant Mechanisms* (Wiley, 2001).  The links
are the chords between the joints at ``s_0 = 0 < s_1 < ... < s_n = L``; ``options.n_elements`` links are
shared among the sections in proportion to their lengths (at least one each), so every section end is a
joint.  A joint's spring has the compliance of the two half-links next to it,
``c_i = sum (h / 2) / EI`` (``EI`` at the half-link's middle): ``EI / h`` at an inner joint of equal links
and ``2 EI / h`` at the clamp, as in C. M. Wang et al., "Hencky bar-chain model for buckling and
vibration of beams with elastic end restraints", Int. J. Struct. Stab. Dyn. 15 (2015) 1540007.  The tip
joint ``s_n`` has no link after it: its rotation only turns the tip frame.

Static equilibrium of every joint (the moment the spring carries equals the moment about the joint of
everything distal of it, in the base x-z plane, rotation about base +y)::

    theta_i = sum over the half-links h next to joint i of  c_h (M_ext(i) + M_tendon(h))

``M_tendon(h) = sum T d cos(sigma)`` of the tendons routed through the half-link: a frictionless
continuously routed tendon of constant offset ``d`` loads an inextensible rod by the uniform moment
``T d`` alone (Rucker & Webster, IEEE T-RO 27, 2011; its compression ``T`` is carried by the backbone
without bending it).  ``M_ext(i)`` collects the weights of the distal links (at their chord midpoints),
of the disks (at their stations on the chords), of the payload and the tip force (at the tip), and the
tip torque about base y.  The ``n`` equations are solved with :func:`scipy.optimize.root` (``hybr``)
from the tendon-only shape (explicit) with the external loads ramped in up to ``options.max_load_steps``
steps when the full load does not converge at once.

Properties checked by ``examples/plugin/tests/test_prb_chain.py``: under tendon moments alone every
joint turns by exactly the arc's angle over its two half-links, so the tip frame's orientation equals the
constant-curvature (CC) model's for any ``n`` and the tip converges to CC's at order 2 in ``1 / n`` (the
links are as long as the arc they replace, not as its chord); under a tip force (with or without a tip
torque) or self-weight the tip converges at order 2 to the elastica
(:func:`workbench.reference.elastica.clamped_elastica`).

What it does not do (declared in ``trunk_workbench_prb.rows.MODEL``, refused here too): spatial cases
(tendons off the x-z plane, forces along y, torques not about y, gravity with a y component), length
control, eyelet tendons, tapered tendon offsets, payload offsets, dynamics, torsion, axial or shear
strain.
"""

from __future__ import annotations

import time

import numpy as np

from workbench.models import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from workbench.models.inputs import check_model_inputs
from workbench.robot import LoadCase, Robot

__all__ = ["run", "link_stations"]

_TOL = 1e-9


def link_stations(robot: Robot, n_links: int) -> np.ndarray:
    """Joint stations ``s_0 = 0 .. s_n = L`` [m]: ``n_links`` links shared by the sections in proportion
    to their lengths (at least one each), equal within a section."""
    ends = np.concatenate([[0.0], robot.section_ends])
    per = np.maximum(1, np.round(n_links * robot.section_lengths / robot.length).astype(int))
    return np.concatenate([[0.0], *[np.linspace(a, b, k + 1)[1:] for a, b, k in zip(ends[:-1], ends[1:], per)]])


def _refuse(robot: Robot, load: LoadCase, options: SolverOptions) -> None:
    """ValueError (one line) for a case this planar static model does not represent."""
    why = []
    if load.analysis != "static":
        why.append("dynamic analysis (static only)")
    act = load.actuation
    if act is not None and act.mode != "tension":
        why.append(f"tendon mode {act.mode!r} (tension only)")
    if act is not None and any(act.values) and options.tendon_model != "continuum":
        why.append(f"tendon_model {options.tendon_model!r} (continuum only)")
    for j, sigma, group in robot.tendon_table():
        if abs(np.sin(sigma)) > _TOL:
            why.append(f"the tendon of section {j} at sigma = {sigma:.4g} rad is off the base x-z plane")
            break
        if group.offset_tip is not None:
            why.append(f"the tendons of section {j} are tapered (constant offsets only)")
            break
    F, M, g = np.asarray(load.tip_force), np.asarray(load.tip_torque), robot.gravity_in_base()
    if abs(F[1]) > _TOL * max(1.0, np.abs(F).max()) or max(abs(M[0]), abs(M[2])) > _TOL * max(1.0, np.abs(M).max()):
        why.append("a tip load off the base x-z plane")
    if abs(g[1]) > _TOL * max(1.0, np.abs(g).max()):
        why.append("gravity with a component along base y")
    if robot.payload.mass > 0 and any(robot.payload.offset):
        why.append("a payload offset")
    if why:
        raise ValueError("prb_chain: planar static chain, cannot represent " + "; ".join(why))


def _tendon_moments(robot: Robot, load: LoadCase, mids: np.ndarray) -> np.ndarray:
    """``sum T d cos(sigma)`` [N m] of the tendons routed through the points ``mids`` (arc length)."""
    act = load.actuation
    if act is None:
        return np.zeros(mids.size)
    ends = robot.section_ends
    sec_of = np.searchsorted(ends, mids)  # section of each point (mids are strictly inside sections)
    out = np.zeros(mids.size)
    for T, (j, sigma, group) in zip(act.values, robot.tendon_table()):
        out += np.where(sec_of <= j, T * group.offset * np.cos(sigma), 0.0)
    return out


def _point_loads(robot: Robot, load: LoadCase, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Stations [m] and (x, z) forces [N] of the weights and the tip force (link weights at chord midpoints)."""
    g = robot.gravity_in_base()[[0, 2]]
    mid = 0.5 * (s[:-1] + s[1:])
    mu = np.array([_cross_section(robot, m).mass_per_length for m in mid])
    stations = [mid, np.concatenate([s0 + sec.disk_positions() for s0, sec in
                                     zip(np.r_[0.0, robot.section_ends[:-1]], robot.sections)]), [robot.length]]
    masses = [mu * np.diff(s), np.concatenate([np.full(sec.n_disks, sec.disk_mass) for sec in robot.sections]),
              [robot.payload.mass]]
    st, m = np.concatenate(stations), np.concatenate(masses)
    forces = m[:, None] * g[None, :]
    forces[-1] += np.asarray(load.tip_force)[[0, 2]]
    keep = np.any(forces != 0, axis=1)
    return st[keep], forces[keep]


def _cross_section(robot: Robot, s: float):
    """The backbone cross-section at arc length ``s`` strictly inside a section (tapered ones interpolated)."""
    ends = robot.section_ends
    j = int(np.searchsorted(ends, s))
    start = ends[j - 1] if j else 0.0
    return robot.sections[j].cross_section_at((s - start) / robot.section_lengths[j])


def _shape(theta: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Link angles ``psi`` (from base z towards base x) and joint points ``(n + 1, 2)`` as (x, z)."""
    psi = np.cumsum(theta)
    h = np.diff(s)
    p = np.vstack([[0.0, 0.0], np.cumsum(np.column_stack([h * np.sin(psi), h * np.cos(psi)]), axis=0)])
    return psi, p


def _on_chain(psi: np.ndarray, p: np.ndarray, s: np.ndarray, where: np.ndarray) -> np.ndarray:
    """(x, z) of arc-length points ``where`` on the chord polygon."""
    k = np.clip(np.searchsorted(s, where, side="right") - 1, 0, psi.size - 1)
    return p[k] + (where - s[k])[:, None] * np.column_stack([np.sin(psi[k]), np.cos(psi[k])])


def _residual_factory(robot: Robot, load: LoadCase, s: np.ndarray):
    """``residual(theta, lam)`` of the joint equilibria (module docstring) with external loads scaled by ``lam``."""
    h = np.diff(s)
    mids = 0.5 * (s[:-1] + s[1:])
    ei = np.array([_cross_section(robot, m).EI for m in mids])
    c_half = 0.5 * h / ei                             # compliance of each half-link
    mt = _tendon_moments(robot, load, mids)
    c_left = np.r_[0.0, c_half]                       # half-link proximal of joint i (none at the clamp)
    c_right = np.r_[c_half, 0.0]                      # distal (none at the tip)
    tendon = c_left * np.r_[0.0, mt] + c_right * np.r_[mt, 0.0]
    c = c_left + c_right
    ls, lf = _point_loads(robot, load, s)
    torque = float(load.tip_torque[1])
    distal = ls[None, :] > s[:, None] + 1e-12 * robot.length  # (joint, load)

    def residual(theta_links: np.ndarray, lam: float) -> np.ndarray:
        psi, p = _shape(theta_links, s)
        r = _on_chain(psi, p, s, ls)                                     # load points (x, z)
        arm = r[None, :, :] - p[:, None, :]                              # (joint, load, 2)
        m = np.sum(np.where(distal, arm[..., 1] * lf[None, :, 0] - arm[..., 0] * lf[None, :, 1], 0.0), axis=1)
        theta = tendon + c * lam * (m + torque)
        return theta_links - theta[:-1]

    def tip_rotation(theta_links: np.ndarray, lam: float) -> float:
        return float(tendon[-1] + c[-1] * lam * torque)

    return residual, tip_rotation, tendon[:-1]


def _solve(residual, theta0: np.ndarray, options: SolverOptions) -> tuple[np.ndarray, int, int]:
    """Equilibrium at full load from ``theta0`` (load factor 0): direct, else ramped; (theta, evaluations, steps)."""
    from scipy.optimize import root

    scale = max(1.0, float(np.abs(theta0).max()))
    steps, nfev = 1, 0
    while steps <= options.max_load_steps:
        theta, ok = theta0.copy(), True
        for lam in np.linspace(0.0, 1.0, steps + 1)[1:]:
            sol = root(residual, theta, args=(lam,), method="hybr", tol=options.newton_tolerance)
            nfev += sol.nfev
            ok = sol.success and np.abs(residual(sol.x, lam)).max() <= 1e3 * options.newton_tolerance * scale
            if not ok:
                break
            theta = sol.x
        if ok:
            return theta, nfev, steps
        steps *= 4
    raise ModelFailure(f"prb_chain: no equilibrium found within {options.max_load_steps} load steps")


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """The pseudo-rigid-body chain's static equilibrium (model ``"prb_chain"``, module docstring).

    Returns
    -------
    PhysicsResult
        Backbone points at ``options.n_stations`` stations on the chord polygon; tip frame with its
        z axis along the tip tangent (last link turned by the tip joint); ``length_change`` 0
        (inextensible); ``tendon_tensions`` the commanded tensions; ``joint_angles`` ``(n + 1, 1)``
        (clamp to tip joint); extras ``n_links``.

    Raises
    ------
    ValueError
        A case outside the model (one line naming what).
    ModelFailure
        No equilibrium within ``options.max_load_steps`` load steps.
    """
    check_model_inputs(robot, load, options)
    _refuse(robot, load, options)
    t0 = time.perf_counter()
    s = link_stations(robot, options.n_elements)
    residual, tip_rotation, theta0 = _residual_factory(robot, load, s)
    theta, nfev, steps = _solve(residual, theta0, options)
    psi, p = _shape(theta, s)
    stations = np.linspace(0.0, robot.length, options.n_stations)
    xz = _on_chain(psi, p, s, stations)
    positions = np.column_stack([xz[:, 0], np.zeros(stations.size), xz[:, 1]])
    tip_angle = psi[-1] + tip_rotation(theta, 1.0)
    frame = np.eye(4)
    frame[:3, :3] = [[np.cos(tip_angle), 0.0, np.sin(tip_angle)], [0.0, 1.0, 0.0],
                     [-np.sin(tip_angle), 0.0, np.cos(tip_angle)]]
    frame[:3, 3] = positions[-1]
    act = load.actuation
    return PhysicsResult(
        model="prb_chain", stations=stations, positions=positions, tip_frame=frame, length_change=0.0,
        tendon_tensions=np.asarray(act.values) if act is not None else np.zeros(robot.n_tendons), tip_twist=0.0,
        solver=SolverInfo(converged=True, iterations=nfev, wall_time=time.perf_counter() - t0, path_steps=steps),
        joint_angles=np.r_[theta, tip_rotation(theta, 1.0)][:, None], extras={"n_links": float(s.size - 1)})
