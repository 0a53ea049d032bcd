"""Constant-curvature (CC) kinematics as a model: the prediction the physics models are judged against.

The CC model knows only geometry: every section bends into a circular arc, determined by the
tendon commands alone.  Gravity, payload and tip loads are ignored, tendons and backbone are
rigid (tension mode) or the backbone length follows the mean tendon length (length mode) -- that
is exactly what the workbench measures against the physics.

Tendon routing convention (shared with the physics models)
----------------------------------------------------------
A tendon of section ``k`` is anchored on the base plate at its group's offset ``d`` and
angle ``sigma``, runs along the backbone through the disks of sections ``0..k`` and
terminates on the last disk of section ``k``.  A tapered (tronconic) group's offset varies
linearly along the tendon's whole routed length, from ``offset`` at the base plate to
``offset_tip`` at the terminating disk; for CC purposes a tendon's offset in a section is
its mean over that section (exact for the tendon length, which is linear in the offset).

Maps
----
Tension mode (moment balance of a frictionless tendon, e.g. Webster & Jones 2010, Sec. 3;
Rucker & Webster 2011): the tendons passing through section ``j`` exert the uniform moment
``m_j = sum_i T_i d_i (cos sigma_i, sin sigma_i)`` and the section bends with curvature
vector ``m_j / EI_j`` (direction ``phi_j = atan2(m_y, m_x)``), ``EI_j`` taken at mid-section.

Length mode (arc geometry): in a section of arc ``(kappa, phi, ell)`` a tendon at
``(sigma, d)`` has length ``ell (1 - kappa d cos(sigma - phi))``; a tendon's commanded
change is the sum of its per-section changes relative to the straight robot.  The inverse
peels the sections from the base outwards.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..kinematics import (
    arc_from_tendon_lengths,
    forward_kinematics,
    tendon_lengths_from_arc,
)
from ..robot import LoadCase, Robot, TendonActuation
from .inputs import check_model_inputs
from .result import PhysicsResult, SolverInfo, SolverOptions, series_times

__all__ = ["ArcStresses", "actuation_from_arc", "arc_from_actuation", "arc_stresses", "run"]


def _section_offset(robot: Robot, tendon_section: int, section: int) -> float:
    """Mean offset [m] of a tendon of ``tendon_section`` over ``section`` (<= tendon_section)."""
    group = robot.sections[tendon_section].tendons
    ends = robot.section_ends
    start = ends[section - 1] if section > 0 else 0.0
    return group.offset_at(0.5 * (start + ends[section]) / ends[tendon_section])


def _section_ei(robot: Robot, j: int) -> float:
    return robot.sections[j].cross_section_at(0.5).EI


def _check_arc(robot: Robot, kappa, phi) -> tuple[np.ndarray, np.ndarray]:
    n = robot.n_sections
    k = np.asarray(kappa, dtype=float).reshape(-1)
    p = np.asarray(phi, dtype=float).reshape(-1)
    if p.size == 1 and n > 1:
        p = np.full(n, p[0])
    if k.shape != (n,) or p.shape != (n,):
        raise ValueError(
            f"kappa and phi must have shape ({n},) (one per section), got {k.shape} and {p.shape}"
        )
    if not (np.all(np.isfinite(k)) and np.all(np.isfinite(p))):
        raise ValueError("kappa and phi must be finite")
    return k, p


def actuation_from_arc(
    robot: Robot,
    kappa,
    phi,
    mode: str,
    pretension: float = 0.0,
) -> TendonActuation:
    """Tendon commands that make the CC model bend every section into the given arc.

    Parameters
    ----------
    robot : Robot
        The robot (sections with tendon groups).
    kappa, phi : array_like, shape (n_sections,)
        Curvature [1/m] and bending-plane angle [rad] per section (a scalar ``phi`` is
        broadcast).
    mode : {"tension", "length"}
        ``"tension"``: the smallest non-negative tendon tensions (plus ``pretension`` in
        every tendon) whose moments give ``EI_j kappa_j`` in every section.
        ``"length"``: the tendon length changes of the CC arc geometry.
    pretension : float
        Tension [N] added to every tendon (tension mode) or passed on as the length-mode
        preload.

    Returns
    -------
    TendonActuation

    Raises
    ------
    ValueError
        If a tendon group cannot produce the requested moment (e.g. two antagonistic
        tendons asked to bend out of their plane), or shapes are wrong.
    """
    k, p = _check_arc(robot, kappa, phi)
    table = robot.tendon_table()
    if not table:
        raise ValueError("the robot has no tendons to actuate")
    ell = robot.section_lengths
    if mode == "length":
        values = np.zeros(len(table))
        for i, (sec, sigma, _group) in enumerate(table):
            for j in range(sec + 1):
                d = _section_offset(robot, sec, j)
                lj = tendon_lengths_from_arc(k[j], p[j], ell[j], np.array([sigma]), d)
                values[i] += float(np.asarray(lj).reshape(-1)[0]) - ell[j]
        return TendonActuation("length", tuple(values), pretension=pretension)
    if mode != "tension":
        raise ValueError(f"mode must be 'tension' or 'length', got {mode!r}")
    # required section moments, then each group supplies the difference to the next section
    M = np.array([_section_ei(robot, j) * k[j] * np.array([np.cos(p[j]), np.sin(p[j])])
                  for j in range(robot.n_sections)])
    tensions = np.zeros(len(table))
    for j in reversed(range(robot.n_sections)):
        # moment of the (already solved) tendons of later sections passing through section j
        later = np.zeros(2)
        for i, (sec, sigma, _g) in enumerate(table):
            if sec > j:
                later += tensions[i] * _section_offset(robot, sec, j) * np.array([np.cos(sigma), np.sin(sigma)])
        need = M[j] - later
        idx = [i for i, (sec, _, _) in enumerate(table) if sec == j]
        if not idx:
            if np.linalg.norm(need) > 1e-9 * max(1e-12, np.linalg.norm(M[j])) and np.linalg.norm(need) > 1e-12:
                raise ValueError(f"section {j} has no tendons of its own and cannot take a different moment "
                                 f"than the tendons passing through it give")
            continue
        d = _section_offset(robot, j, j)
        sig = np.array([table[i][1] for i in idx])
        A = d * np.vstack([np.cos(sig), np.sin(sig)])
        from scipy.optimize import nnls  # lazily: validate imports this module (2 s of scipy on a busy machine)

        T, resid = nnls(A, need)
        if resid > 1e-9 * max(1e-12, np.linalg.norm(need)) and resid > 1e-12:
            raise ValueError(
                f"the tendons of section {j} (angles {np.round(sig, 4).tolist()} rad) cannot produce the bending "
                f"moment needed in the plane phi = {p[j]:.4f} rad"
            )
        tensions[idx] = T
    # nnls gives non-negative tensions; balanced groups may carry a common preload
    tensions = tensions + float(pretension)
    return TendonActuation("tension", tuple(tensions), pretension=0.0)


def arc_from_actuation(robot: Robot, actuation: TendonActuation | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The CC arc of every section for the final tendon commands.

    Returns
    -------
    kappa, phi, ell : ndarray, shape (n_sections,)
        Curvature [1/m], bending-plane angle [rad], arc length [m].  In tension mode
        ``ell`` is the undeformed section length; in length mode it follows the tendon
        lengths (the "virtual" length of Cojocaru's Eq 12).
    """
    n = robot.n_sections
    ell0 = robot.section_lengths.copy()
    if actuation is None:
        return np.zeros(n), np.zeros(n), ell0
    actuation.check_against(robot)
    table = robot.tendon_table()
    vals = np.asarray(actuation.values)
    kappa, phi, ell = np.zeros(n), np.zeros(n), ell0.copy()
    if actuation.mode == "tension":
        for j in range(n):
            m = np.zeros(2)
            for i, (sec, sigma, _g) in enumerate(table):
                if sec >= j:
                    m += vals[i] * _section_offset(robot, sec, j) * np.array([np.cos(sigma), np.sin(sigma)])
            kappa[j] = np.hypot(*m) / _section_ei(robot, j)
            phi[j] = np.arctan2(m[1], m[0]) if kappa[j] > 0 else 0.0
        return kappa, phi, ell
    # length mode: peel sections from the base outwards
    consumed = np.zeros(len(table))
    for j in range(n):
        idx = [i for i, (sec, _, _) in enumerate(table) if sec == j]
        if not idx:
            raise ValueError(f"length mode needs tendons terminating in every section; section {j} has none")
        sig = np.array([table[i][1] for i in idx])
        d = _section_offset(robot, j, j)
        lengths = ell0[j] + vals[idx] - consumed[idx]
        if len(idx) == 2 and np.isclose(abs(np.angle(np.exp(1j * (sig[1] - sig[0])))), np.pi):
            # antagonistic pair: planar closed form (the out-of-plane component is unobservable)
            ell[j] = lengths.mean()
            kc = (lengths[1] - lengths[0]) / (2.0 * d * ell[j])  # kappa cos(phi - sigma_0)
            kappa[j] = abs(kc)
            phi[j] = sig[0] if kc >= 0 else sig[0] + np.pi
        else:
            kj, pj, lj = arc_from_tendon_lengths(lengths, sig, d)
            kappa[j], phi[j], ell[j] = float(kj), float(pj), float(lj)
        # what the outer tendons spend in this section
        for i, (sec, sigma, _g) in enumerate(table):
            if sec > j:
                li = tendon_lengths_from_arc(kappa[j], phi[j], ell[j], np.array([sigma]), _section_offset(robot, sec, j))
                consumed[i] += float(np.asarray(li).reshape(-1)[0]) - ell0[j]
    phi = np.where(kappa > 0, np.angle(np.exp(1j * phi)), 0.0)
    return kappa, phi, ell


def _cc_backbone_frames(robot: Robot, act: TendonActuation, times: np.ndarray, cmds: np.ndarray,
                        stations: np.ndarray) -> dict[str, np.ndarray]:
    """Decimated CC backbones over time (``series.backbone``, :mod:`workbench.models.backbone_frames`)."""
    from .backbone_frames import backbone_series, frame_stride

    keep = np.unique(np.r_[np.arange(0, times.size - 1, frame_stride(times.size - 1)), times.size - 1])
    ends0 = np.concatenate([[0.0], robot.section_ends])
    frames = []
    for q in keep:
        kq, pq, lq = arc_from_actuation(robot, TendonActuation(act.mode, tuple(cmds[q]), pretension=act.pretension))
        s_q = np.interp(stations, ends0, np.concatenate([[0.0], np.cumsum(lq)]))
        frames.append(forward_kinematics(kq, pq, lq, s=s_q)[:, :3, 3])
    return backbone_series(times[keep], frames)


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """The CC prediction for a load case (model ``"cc"``).

    Gravity, payload and tip loads are ignored by construction.  For a dynamic load case
    the final commands are used and, in addition, the CC tip and virtual length are
    reported as time series on the grid every dynamic model stores (:func:`series_times`).

    Returns
    -------
    PhysicsResult
        ``tendon_tensions`` are the commanded tensions (tension mode) or NaN (length mode:
        CC kinematics predicts no forces); ``length_change`` is the virtual length change
        ``sum(ell) - L``; ``tip_twist`` is 0; extras ``kappa_j``, ``phi_j`` and the stresses
        CC implies (:func:`_stress`).
    """
    check_model_inputs(robot, load, options)
    t0 = time.perf_counter()
    act = load.actuation
    kappa, phi, ell = arc_from_actuation(robot, act)
    stations = np.linspace(0.0, robot.length, options.n_stations)
    # stations are reference arc lengths: map them section-wise onto the (possibly
    # stretched) CC arcs
    ends0 = np.concatenate([[0.0], robot.section_ends])
    ends = np.concatenate([[0.0], np.cumsum(ell)])
    s_cc = np.interp(stations, ends0, ends)
    frames = forward_kinematics(kappa, phi, ell, s=s_cc)
    tip = forward_kinematics(kappa, phi, ell)
    tensions = (np.asarray(act.values) if act is not None and act.mode == "tension"
                else np.full(robot.n_tendons, np.nan))
    series: dict[str, np.ndarray] = {}
    time_axis = None
    if load.analysis == "dynamic" and act is not None:
        time_axis = series_times(load.duration, options.time_step)  # the physics models' output grid
        cmds = act.command_at(time_axis, load.ramp_time)
        tips = np.empty((time_axis.size, 3))
        dl = np.empty(time_axis.size)
        for q, c in enumerate(cmds):
            kq, pq, lq = arc_from_actuation(robot, TendonActuation(act.mode, tuple(c), pretension=act.pretension))
            tips[q] = forward_kinematics(kq, pq, lq)[:3, 3]
            dl[q] = lq.sum() - robot.length
        series = {"tip_position": tips, "length_change": dl, "commands": cmds,
                  **_cc_backbone_frames(robot, act, time_axis, cmds, stations)}
    return PhysicsResult(
        model="cc",
        stations=stations,
        positions=frames[:, :3, 3],
        tip_frame=tip,
        length_change=float(ell.sum() - robot.length),
        tendon_tensions=tensions,
        tip_twist=0.0,
        solver=SolverInfo(converged=True, iterations=0, wall_time=time.perf_counter() - t0),
        time=time_axis,
        series=series,
        extras={**{f"kappa_{j}": float(kappa[j]) for j in range(robot.n_sections)},
                **{f"phi_{j}": float(phi[j]) for j in range(robot.n_sections)},
                **_stress(robot, kappa, tensions)},
    )


@dataclass(frozen=True)
class ArcStresses:
    """The stresses the CC arc of a command implies (:func:`arc_stresses`), per section and per tendon.

    Attributes
    ----------
    axial, bending : ndarray, shape (n_sections,) or None
        ``sum T / A`` of the tendons passing each section (0 in length mode: CC predicts no
        forces) and ``EI |kappa| / W`` at mid-section [Pa]; ``None`` when a section has no
        stress geometry (``area`` / ``section_modulus``).
    yield_strength : ndarray, shape (n_sections,) or None
        Backbone yield strength at mid-section [Pa] (NaN: unknown).
    tendon, tendon_strength : ndarray, shape (n_tendons,) or None
        Tendon stress ``T / A_t`` and tensile strength [Pa] (NaN: unknown), ``robot.tendon_table()``
        order; ``None`` in length mode or when a tendon has no area.
    """

    axial: np.ndarray | None
    bending: np.ndarray | None
    yield_strength: np.ndarray | None
    tendon: np.ndarray | None
    tendon_strength: np.ndarray | None

    @property
    def backbone(self) -> np.ndarray | None:
        """Combined outer-fibre stress ``axial + bending`` per section [Pa] (:func:`~.stress.combined_stress`)."""
        return None if self.axial is None else self.axial + self.bending


def arc_stresses(robot: Robot, kappa: np.ndarray, tensions: np.ndarray) -> ArcStresses:
    """The stresses of the CC arc ``kappa`` (shape (n_sections,)) under ``tensions`` [N] (NaN: length mode).

    Backbone: the bending stress ``EI kappa / W`` of every section's arc plus, in tension mode,
    the axial ``sum T / A`` of the tendons passing the section, combined as
    :func:`workbench.models.stress.combined_stress` does; tendons: ``T / A_t``.  Pure numpy; the
    CC model's stress extras and the study's plausibility warnings both use it.
    """
    from .stress import combined_stress, section_arrays, tendon_arrays

    cs = [robot.sections[j].cross_section_at(0.5) for j in range(robot.n_sections)]
    arrs = section_arrays(cs)
    T_raw = np.asarray(tensions, dtype=float)
    axial = bending = strength = None
    if arrs is not None:
        T = np.nan_to_num(T_raw)
        N = np.array([sum(T[i] for i, (sec, _, _) in enumerate(robot.tendon_table()) if sec >= j)
                      for j in range(robot.n_sections)], dtype=float)
        M = np.array([c.EI for c in cs]) * np.abs(np.asarray(kappa, dtype=float))
        axial = combined_stress(N, 0.0, arrs[0], arrs[1])
        bending = combined_stress(0.0, M, arrs[0], arrs[1])
        strength = arrs[2]
    tab = tendon_arrays(robot)
    tendon = tendon_strength = None
    if tab is not None and T_raw.size == tab[0].size and np.all(np.isfinite(T_raw)):
        tendon, tendon_strength = np.abs(T_raw) / tab[0], tab[1]
    return ArcStresses(axial, bending, strength, tendon, tendon_strength)


def _stress(robot: Robot, kappa: np.ndarray, tensions: np.ndarray) -> dict[str, float]:
    """What CC can say about stresses (:mod:`workbench.models.stress`, :func:`arc_stresses`): the
    backbone stress of every section's arc and the tendon stresses; length mode predicts no
    forces, so the backbone stress is the bending part alone and there is no tendon stress."""
    from .stress import stress_extras

    parts = arc_stresses(robot, kappa, tensions)
    return stress_extras(parts.backbone, parts.yield_strength, robot, tensions)
