"""The registered model ``"cosserat"``: ``run(robot, load, options) -> PhysicsResult``.

Statics only; tendons routed continuously or, with ``tendon_model = "eyelets"``, straight between the
disks (:mod:`.eyelets`, tension control only; its Newton starts from the continuous solution).  Tension control: the tensions are the commands.  Length control: the tensions
solve ``T = EA_t max(0, (l(T) - l0) / l0)`` (:func:`workbench.physics.tendon_loads.solve_length_controlled`,
rest lengths from :func:`~workbench.physics.tendon_loads.tendon_rest_lengths`, compliance of the
straight rod as the first quasi-Newton matrix), each ``l(T)`` a shooting solve warm-started from
the previous one; all those solves share one budget of ``options.max_load_steps`` load-ramp
attempts, so a length solve that creeps ends with :class:`ModelFailure` naming the budget
(``tests/physics/test_load_path.py``).  Outputs (base frame): positions at ``options.n_stations``
stations (dense output of the final integration), tip frame ``R(L)``, ``length_change`` = integral of
``|v| - 1``, ``tip_twist`` = integral of ``u_3``, tensions; the load path (``SolverInfo.path_steps`` /
``path_event`` / ``path_event_fraction``: :meth:`~workbench.physics.cosserat.shooting.Shooter.go_to`'s
ramps, the event of the first one that had one); ``extras``: ``newton_iterations``,
``load_steps``, ``shots`` (integrated trajectories) and ``tip_residual``.  Warm starts
(:mod:`.warm`): under tension control the ramp continues from ``options.warm_state`` when it is
this rod at a fraction of this load (the same load ray), else, or when the warm ramp fails or has
a load-path event, the model solves cold (``extras["warm_started"]`` 1 or 0, only when a state was
given); length control ignores it.  ``warm_state`` of the result: the final equilibrium of a
tension-controlled solve without a load-path event (else ``None``).  Checked by
``tests/physics/test_cosserat_model.py`` and ``tests/models/test_warm_cosserat.py``.
"""

from __future__ import annotations

import time

import numpy as np

from ...models.inputs import check_model_inputs
from ...models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot
from .._stepping import path_fields
from ..tendon_loads import solve_length_controlled, tendon_rest_lengths
from . import warm as warm_start
from .eyelets import eyelet_route, integrate_eyelets, rod_wrench_from_total
from .problem import RodProblem, rod_problem
from .rod import N_BASE, integrate_segments
from .shooting import Shooter, ShootingFailure

__all__ = ["run", "straight_compliance"]


def straight_compliance(pb: RodProblem) -> np.ndarray:
    """``(n_t, n_t)`` small-deflection ``dl_i/dT_j = -int_0^{min(e_i, e_j)} (r_i . r_j / EI + 1/EA) ds``
    of continuum tendons on the straight rod (the length solve's first quasi-Newton matrix)."""
    n = pb.n_tendons
    s = np.linspace(0.0, pb.length, 801)
    sec = np.array([pb.section_of(x) for x in s])
    f = (s - pb.section_starts[sec]) / pb.section_lengths[sec]
    K = pb.stiffness0[sec] + (pb.stiffness1[sec] - pb.stiffness0[sec]) * f[:, None]
    d = pb.tendon_offsets[:, :1] + (pb.tendon_offsets[:, 1:] - pb.tendon_offsets[:, :1]) * s / pb.tendon_ends[:, None]
    r = d[:, :, None] * pb.tendon_dirs[:, None, :]
    C = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            g = np.einsum("kc,kc->k", r[i], r[j]) / K[:, 3] + 1.0 / K[:, 2]
            G = np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.diff(s))])
            C[i, j] = -np.interp(min(pb.tendon_ends[i], pb.tendon_ends[j]), s, G)
    return C


def _eyelet_guess(pb: RodProblem, options: SolverOptions, shooter: Shooter, T: np.ndarray) -> np.ndarray | None:
    """The eyelet shooting's predictor: the continuous-tendon solution (its tip differs by the eyelet
    effect, ~1e-2 L on the peer benchmark) at a loose tolerance, as the rod's own clamp wrench
    (:func:`.eyelets.rod_wrench_from_total`); ``None`` for continuous tendons or where it fails."""
    if shooter.route is None or not np.any(T):
        return None
    continuous = Shooter(pb, max(options.newton_tolerance, 1e-4), compiled=shooter.compiled)
    try:
        continuous.go_to(T, options.max_load_steps)
        _, Y = integrate_segments(pb, continuous.x[None], T, 1.0, continuous.rtol, shooter.route.stations[1:2],
                                  compiled=shooter.compiled)
    except (ShootingFailure, RuntimeError):
        return None
    return rod_wrench_from_total(shooter.route, continuous.x, T, Y[0, 0, 0:3], Y[0, 0, 3:12].reshape(3, 3))


def _tensions(pb: RodProblem, load: LoadCase, options: SolverOptions, shooter: Shooter) -> tuple[np.ndarray, int]:
    """Tendon tensions of the equilibrium (the shooter ends at it); returns (tensions, ramp attempts)."""
    act = load.actuation
    if act is None or pb.n_tendons == 0:
        return np.zeros(pb.n_tendons), shooter.go_to(np.zeros(pb.n_tendons), options.max_load_steps)
    if act.mode == "tension":
        T = np.asarray(act.values, dtype=float)
        return T, shooter.go_to(T, options.max_load_steps, _eyelet_guess(pb, options, shooter, T))
    l0 = tendon_rest_lengths(pb.reference_tendon_lengths(), act.values, act.pretension, pb.tendon_stiffness)
    attempts = [0]
    # a shooting residual eps bends the rod by ~eps F_s L / EI, i.e. moves a tendon path by
    # ~d eps F_s L^2 / EI: stiff tendons (EA_t / l0 ~ 1e7 N/m) need it 1e3 x tighter than the
    # shape does, or the tension solve sees noise (measured: 0.2 N on EA_t = 1e7 N at eps = 1e-9)
    shooter.tol = max(1e-13, 1e-3 * shooter.tol)
    shooter.rtol = max(1e-13, 0.1 * shooter.tol)

    budget = options.max_load_steps
    solves = [0]

    def equilibrium(T: np.ndarray) -> np.ndarray:
        # one budget of load-ramp attempts (failed ones included) for the whole length solve: every
        # tension solve costs at least one, so it ends after at most max_load_steps shooting solves
        left = budget - shooter.attempts
        if left <= 0:
            raise ShootingFailure(f"length-controlled tendon solve used all max_load_steps={budget} load steps "
                                  f"in {solves[0]} tension solves without converging")
        solves[0] += 1
        attempts[0] += shooter.go_to(T, left)
        tip, _ = integrate_segments(pb, shooter.x[None], T, 1.0, shooter.rtol, compiled=shooter.compiled)
        return tip[0, N_BASE + 2:]

    info = solve_length_controlled(equilibrium, l0, pb.tendon_stiffness, straight_compliance(pb),
                                   initial_tensions=np.full(pb.n_tendons, act.pretension),
                                   tol=max(1e-10, options.newton_tolerance), length_tol=10.0 * options.newton_tolerance)
    equilibrium(info.tensions)
    return info.tensions, attempts[0]


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Solve the spatial Cosserat rod with continuously routed tendons (model ``"cosserat"``).

    Parameters
    ----------
    robot : Robot
        Any number of sections, tapered cross-sections and tendon offsets, disk masses, payload.
    load : LoadCase
        Static: tendon tensions or length changes, tip force and torque (dead loads, base frame).
    options : SolverOptions
        ``newton_tolerance`` (scaled tip residual; integration at a tenth of it),
        ``max_load_steps``, ``n_stations``; ``n_elements`` is not used (the integration is
        adaptive, 8th order).  ``tendon_model``: ``"continuum"`` (Rucker & Webster) or ``"eyelets"``
        (straight between the disks, :mod:`.eyelets`; tension control only).

    Raises
    ------
    ModelFailure
        Dynamic analysis, length-controlled eyelet tendons, or no converged equilibrium.
    """
    t0 = time.perf_counter()
    check_model_inputs(robot, load, options)
    if load.analysis != "static":
        raise ModelFailure("cosserat: static analysis only (no dynamics in the shooting model)")
    act = load.actuation
    eyelets = options.tendon_model == "eyelets"
    if eyelets and act is not None and act.mode == "length":
        raise ModelFailure("cosserat: length-controlled tendons need tendon_model='continuum' (eyelet routing "
                           "is tension-controlled only; beam3d, ancf or spring_link carry eyelets in length mode)")
    pb = rod_problem(robot, load)
    route = eyelet_route(robot, pb) if eyelets else None
    # warm starts: continuous routing only (the eyelet chords are solved afresh in every shot)
    shooter, T, attempts, warm = (None, None, 0, False) if eyelets else _warm_solve(pb, load, options)
    try:
        if shooter is None:
            shooter = Shooter(pb, options.newton_tolerance, route=route)
            T, attempts = _tensions(pb, load, options, shooter)
        stations = np.linspace(0.0, robot.length, options.n_stations)
        if route is None:
            tip, Y = integrate_segments(pb, shooter.x[None], T, 1.0, shooter.rtol, stations,
                                        compiled=shooter.compiled)
        else:
            tip, Y, _ = integrate_eyelets(pb, route, shooter.x[None], T, 1.0, shooter.rtol, stations,
                                          compiled=shooter.compiled)
    except (ShootingFailure, RuntimeError) as err:
        raise ModelFailure(f"cosserat: {err}") from None
    res = float(np.max(np.abs(shooter.tip_residual(tip, 1.0, T))))
    frame = np.eye(4)
    frame[:3, :3] = tip[0, 3:12].reshape(3, 3)
    frame[:3, 3] = tip[0, 0:3]
    U, _, Vt = np.linalg.svd(frame[:3, :3])
    frame[:3, :3] = U @ Vt
    # a state to start from: the end of the straight load path (tension control), without an event
    offer = route is None and (act is None or act.mode == "tension") \
        and not path_fields(*shooter.ramps)["path_event"] and shooter.sign == 1
    extras = {"newton_iterations": float(shooter.newton_iterations), "load_steps": float(attempts),
              "shots": float(shooter.shots), "tip_residual": res}
    if options.warm_state is not None:
        extras["warm_started"] = float(warm)
    info = SolverInfo(converged=True, iterations=shooter.newton_iterations, wall_time=time.perf_counter() - t0,
                      message=f"{attempts} load steps", **path_fields(*shooter.ramps))
    return PhysicsResult(
        model="cosserat", stations=stations, positions=Y[:, 0, 0:3], tip_frame=frame,
        length_change=float(tip[0, N_BASE] - robot.length), tendon_tensions=T, tip_twist=float(tip[0, N_BASE + 1]),
        solver=info, extras=extras,
        warm_state=warm_start.encode(pb, T, shooter.x) if offer else None,
    )


def _warm_solve(pb: RodProblem, load: LoadCase, options: SolverOptions):  # noqa: ANN202
    """``(shooter, tensions, attempts, True)`` of a solve warm-started from ``options.warm_state``
    (tension control, a state on this load's ray: :mod:`.warm`), or ``(None, None, 0, False)``: no
    usable state, or the warm ramp failed or had a load-path event (the caller solves cold)."""
    act = load.actuation
    if options.warm_state is None or (act is not None and act.mode != "tension"):
        return None, None, 0, False
    T = np.zeros(pb.n_tendons) if act is None or pb.n_tendons == 0 else np.asarray(act.values, dtype=float)
    start = warm_start.decode(pb, options.warm_state, T)
    if start is None:
        return None, None, 0, False
    shooter = warm_start.RayShooter(pb, options.newton_tolerance, start[0])
    try:
        attempts = warm_start.go_from(shooter, start, T, options.max_load_steps)
    except (ShootingFailure, RuntimeError):
        return None, None, 0, False
    if path_fields(*shooter.ramps)["path_event"] or shooter.sign != 1:
        return None, None, 0, False
    return shooter, T, attempts, True
