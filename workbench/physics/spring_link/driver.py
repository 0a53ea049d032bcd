"""Driving a spring-link chain: chain choice, the static load ramp, statics and dynamics.

:func:`solve` picks the chain (:func:`build_chain`: dimension from :func:`.params.is_planar` and
``SpringLinkParams.dimension``; the kinematic tree for eyelet ropes where it applies, rigid bodies
otherwise), ramps the loads (:func:`static_ramp` on :func:`workbench.physics._stepping.load_ramp`) and
for dynamics integrates with implicit generalised-alpha, updating the tendon commands of
:meth:`TendonActuation.command_at` every step.  :func:`run` is the registered model
``"spring_link"`` (default :class:`SpringLinkParams`).  Warm starts (:mod:`workbench.models.warm`): a
tension-controlled static solve continues its ramp from ``options.warm_state`` when that is this chain
at a fraction of this load (:func:`_warm_ramp`), else solves cold; ``PhysicsResult.warm_state`` is
its equilibrium (coordinates and active set) when the load path had no event.  Checked by
``tests/physics/test_spring_link*.py`` and ``tests/models/test_warm_spring_link.py``.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Callable

import numpy as np

from ...models.inputs import check_model_inputs
from ...models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot
from ...models.backbone_frames import backbone_series, frame_stride
from .._stepping import path_fields, PathPoint, RampExhausted, RampPolicy, RampStalled, load_ramp
from .chain import Chain
from .geometry import ChainGeometry, chain_geometry_from_robot
from .lengthmode import settle_lagged
from .params import SpringLinkParams, is_planar, resolve_axial
from .planar import PlanarChain
from .richardson import check_richardson, richardson_result
from .spatial import SpatialChain
from .tree import TreeChain

__all__ = ["solve", "run"]

_SPARSE_FROM = 16

#: The static ramp's step rule: first try the full load, halve on failure, double (capped at 1)
#: after every success, give up below an increment of 1e-6.
#: a first step that moves the last link's measure by more than 2 (tip position / L and axis together) is
#: halved: the whole load in one step curled the chain in issue 28's branch-jump case
_STATIC_RAMP = RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="one", min_increment=1e-6,
                          max_motion=2.0)

_BODIES_HINT = ("; the rigid-body chain's static Newton converges only linearly under large joint reactions "
                "(Exudyn's iteration matrix lacks their geometric stiffness; numerical, not a physical "
                "instability): use backend='tree' (solver.spring_link_backend = \"tree\" or \"auto\")")


def _use_sparse(settings, model) -> None:  # noqa: ANN001
    """Sparse LU for larger chains (dense LU dominated the 3-D solve time from N ~ 32)."""
    import exudyn as exu

    if model.geo.n_links >= _SPARSE_FROM:
        settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse


def _path_point(model: Chain) -> PathPoint:
    """The load-path measure of the chain's state: last joint position / L and last link axis."""
    if model.planar:
        P, beta = model.link_states()
        axis = np.array([math.sin(beta[-1]), 0.0, math.cos(beta[-1])])
    else:
        P, R = model.link_frames()
        axis = R[-1][:, 2]
    return PathPoint(tuple(np.concatenate([P[-1] / model.robot.length, axis])))


def static_ramp(model: Chain, options: SolverOptions, params: SpringLinkParams,
                 apply: Callable[[float], None],
                 check: Callable[[float, PathPoint], bool] | None = None) -> tuple[int, int]:
    """Ramp ``apply(lam)`` from 0 to 1 with repeated static solves; returns (steps, newton its).

    One attempt applies the load factor and solves, re-solving while the slack/taut active set
    of length-controlled tendons changes (at most ``params.max_active_set_iterations`` passes);
    the ramp checks the load path on :func:`_path_point` (:func:`~workbench.physics._stepping.load_ramp`:
    a jump of the last link is refined).  A failed attempt (Exudyn ``SolverError``, non-finite state,
    an unsettled active set) restores the chain's state (:meth:`Chain.save_state`) and halves the
    increment (:data:`_STATIC_RAMP`); the ramp's :class:`~workbench.physics._stepping.LoadRampInfo` is
    appended to ``model.ramps`` (the result's path fields, :func:`~workbench.physics._stepping.path_fields`);
    a non-positive rope rest length is not a solver failure and propagates.  ``check(lam, point)``
    (a warm start's first-step check, :func:`_warm_ramp`) may reject a solved attempt.  Newton iterations
    of every attempt are counted.  Checked by ``test_max_load_steps_is_a_failure``,
    ``test_rigid_body_ramp_failure_names_the_numerical_cause`` and ``test_spring_link_layout.py``.

    Raises
    ------
    ModelFailure
        More than ``options.max_load_steps`` attempts, or an increment below 1e-6.
    """
    from .._exudyn import static_settings

    exu, mbs = model.exu, model.mbs
    settings = static_settings(options, 1)
    _use_sparse(settings, model)
    settings.staticSolver.adaptiveStep = False
    # eyelet ropes loading the joint constraints of the rigid bodies make Newton converge only
    # linearly (~100-125 iterations at N = 16 vs 3-6 for continuum tendons, docs/models.md): allow
    # more there.  The tree's Newton is quadratic (4-16 iterations per step up to alpha = 10);
    # a failing step is cut off early, a 3-D tree Jacobian with ropes costs ~0.5-2 s.
    eyelet_ropes = model.ropes and model.mode is not None
    settings.staticSolver.newton.maxIterations = (250 if eyelet_ropes else 40) if model.rigid_bodies else 25
    if model.link_ropes:  # modified Newton: a rope Jacobian costs ~ a dozen residuals, keep it while it contracts
        settings.staticSolver.newton.useModifiedNewton = True
    # Exudyn differentiates the tip loads numerically even when they are zero (on the 3-D tree most of
    # the Jacobian's time); a zero load has a zero Jacobian, so skipping it changes nothing
    settings.staticSolver.computeLoadsJacobian = bool(np.any(model.tip_force_full) or np.any(model.tip_torque_full))
    newton_its = 0

    def attempt(lam: float) -> bool | PathPoint:
        nonlocal newton_its
        try:
            apply(lam)
            for _ in range(params.max_active_set_iterations):
                solver = exu.MainSolverStatic()
                if not solver.SolveSystem(mbs, settings):
                    raise exu.SolverError("static Newton did not converge")
                newton_its += int(solver.it.newtonStepsCount)
                q = mbs.systemData.GetODE2Coordinates()
                if not np.all(np.isfinite(q)):
                    raise exu.SolverError("non-finite state")
                mbs.systemData.SetODE2Coordinates(q, configuration=exu.ConfigurationType.Initial)
                if not model.update_active_set():
                    point = _path_point(model)
                    return point if check is None or check(lam, point) else False
                apply(lam)
            raise ModelFailure("spring_link: tendon slack/taut switching did not settle")
        except (exu.SolverError, RuntimeError) as err:  # ModelFailure is a RuntimeError too
            if isinstance(err, ModelFailure) and "rest length" in str(err):
                raise
            return False

    try:
        info = load_ramp(attempt, model.save_state, model.restore_state, max_attempts=options.max_load_steps,
                         policy=_STATIC_RAMP, start=_path_point(model))
    except RampExhausted as err:
        hint = _BODIES_HINT if model.rigid_bodies and not model.axial else ""
        raise ModelFailure(
            f"spring_link: static load ramp exceeded options.max_load_steps={options.max_load_steps} "
            f"(reached load factor {err.lam:.4g}){hint}"
        ) from None
    except RampStalled as err:
        raise ModelFailure(f"spring_link: static solve failed near load factor {err.lam:.4g}") from None
    model.ramps.append(info)
    return info.attempts, newton_its


def ramp_to(model: Chain, params: SpringLinkParams, commands: np.ndarray) -> tuple[int, int]:
    """Static equilibrium under gravity, tip loads and tendon ``commands``, all ramped together."""

    def apply(lam: float) -> None:
        model.set_external(lam)
        model.set_tendons(lam * commands, lam)

    return static_ramp(model, model.options, params, apply)


def build_chain(robot: Robot, load: LoadCase, options: SolverOptions, geo: ChainGeometry,
                 params: SpringLinkParams, use_2d: bool) -> Chain:
    """The chain variant for this case: the kinematic tree for every inextensible chain
    (``backend`` ``"auto"`` or ``"tree"``), rigid bodies for ``backend="bodies"`` or ``axial=True``."""
    if params.backend == "tree" and params.axial:
        raise ModelFailure("spring_link: backend='tree' supports inextensible chains only (axial=False); "
                           "axial springs need backend='bodies' or 'auto'")
    # rigid bodies + joints: Exudyn's static Newton matrix lacks the geometric stiffness of the
    # joint reactions (docs/models.md), so their ramp stalls under large dead loads and rope forces
    if params.backend != "bodies" and not params.axial:
        return TreeChain(robot, load, options, geo, spatial=not use_2d, torsion=params.torsion)
    if use_2d:
        return PlanarChain(robot, load, options, geo, params.axial)
    return SpatialChain(robot, load, options, geo, params.torsion, params.axial)


class _WarmAbandoned(Exception):
    """A warm start's first step kept leaving the cold path (not a solver failure: the ramp stops)."""


def _warm_load(model: Chain) -> np.ndarray:
    """The ramped load (gravity, tip force, tip torque, tensions): the ray a warm start must lie on."""
    act, ld = model.load.actuation, model.load
    T = np.zeros(len(model.tendons)) if act is None else np.asarray(act.values, dtype=float)
    return np.concatenate([model.robot.gravity_in_base(), ld.tip_force, ld.tip_torque, T])


def _warm_head(model: Chain, size: int) -> np.ndarray:
    n_q = len(model.mbs.systemData.GetODE2Coordinates())
    return np.array([size, 1.0, model.robot.length, model.options.n_elements, n_q, 9 + len(model.tendons),
                     float(model.planar), float(model.rigid_bodies)])


def _warm_encode(model: Chain) -> np.ndarray:
    """The warm state of the chain's equilibrium: header, ramped load, coordinates, active set."""
    q, active = model.save_state()
    body = np.concatenate([_warm_load(model), np.asarray(q, dtype=float), np.asarray(active, dtype=float)])
    return np.concatenate([_warm_head(model, 8 + body.size), body])


def _warm_decode(model: Chain, state) -> tuple[float, np.ndarray, list[bool]] | None:
    """``(c, coordinates, active set)`` of the part of ``state`` (parts of several resolutions concatenated:
    a Richardson solve's) that is this chain at ``0 < c <= 1`` x its load, else ``None``."""
    from ...models.warm import ray_fraction

    s = np.asarray(state, dtype=float).reshape(-1)
    i = 0
    if not np.all(np.isfinite(s)):
        return None
    while 8 <= s.size - i and 8 <= int(s[i]) <= s.size - i:
        part, i = s[i:i + int(s[i])], i + int(s[i])
        head = _warm_head(model, part.size)
        if part.size != 8 + head[5] + head[4] + len(model.tendons) or not np.array_equal(part[:8], head):
            continue
        n_v, n_q = int(head[5]), int(head[4])
        c = ray_fraction(part[8:8 + n_v], _warm_load(model))
        return None if c is None else (c, part[8 + n_v:8 + n_v + n_q], [bool(a) for a in part[8 + n_v + n_q:]])
    return None


def _warm_ramp(model: Chain, params: SpringLinkParams, final: np.ndarray, start) -> tuple[int, int] | None:
    """The static ramp continued from a neighbour's equilibrium ``start`` at ``c`` x this load
    (:func:`_warm_decode`), its first step checked against the cold path's secant
    (:func:`workbench.models.warm.leaves_secant`, three tries); ``None`` (the chain back in its
    reference state) when it fails or has a path event."""
    from ...models.warm import leaves_secant

    c, q, active = start
    reference, unloaded, ramps = model.save_state(), _path_point(model).measure, len(model.ramps)
    model.restore_state((q, active))
    at_c = _path_point(model).measure
    state = {"first": True, "rejected": 0}

    def check(lam: float, point: PathPoint) -> bool:
        if state["first"] and leaves_secant(unloaded, at_c, c, lam, point.measure, _STATIC_RAMP.jump_ratio,
                                            _STATIC_RAMP.jump_floor):
            state["rejected"] += 1
            if state["rejected"] >= 3:
                raise _WarmAbandoned
            return False
        state["first"] = False
        return True

    def apply(t: float) -> None:
        lam = c + t * (1.0 - c)
        model.set_external(lam)
        model.set_tendons(lam * final, lam)

    try:
        out = static_ramp(model, model.options, params, apply, check)
    except (ModelFailure, _WarmAbandoned):
        out = None
    if out is None or model.ramps[-1].path_event:
        del model.ramps[ramps:]
        model.restore_state(reference)
        return None
    return out


def _solve_static(model: Chain, params: SpringLinkParams, t0: float) -> PhysicsResult:
    act = model.load.actuation
    final = np.zeros(len(model.tendons)) if act is None else np.asarray(act.values)
    # warm starts (workbench.models.warm): tension control only, from a state at a fraction of this load
    tension = (act is None or act.mode == "tension") and not model.lagged_length
    state = model.options.warm_state
    start = _warm_decode(model, state) if tension and state is not None else None
    warm = None if start is None else _warm_ramp(model, params, final, start)
    steps, its = warm or ramp_to(model, params, final)
    repeats = 0
    if model.lagged_length:  # planar continuum length mode with axial springs: lagged couplings

        def resolve(old: tuple, new: tuple) -> None:
            def apply(lam: float) -> None:
                model.lag_gaps = old[0] + lam * (new[0] - old[0])
                model.lag_tensions = old[1] + lam * (new[1] - old[1])
                model.set_tendons(final, 1.0)

            nonlocal steps, its
            s, i = static_ramp(model, model.options, params, apply)
            steps, its = steps + s, its + i

        repeats = settle_lagged(model, resolve)
    info = SolverInfo(converged=True, iterations=its, wall_time=time.perf_counter() - t0,
                      message=f"{steps} load steps" + (f" ({repeats} lagged-coupling equilibria)" if repeats else ""),
                      **path_fields(*model.ramps))
    res = model.result(info)
    extras = {**res.extras, **({} if state is None else {"warm_started": float(warm is not None)})}
    return replace(res, extras=extras, warm_state=_warm_encode(model) if tension and not info.path_event else None)


def _solve_dynamic(model: Chain, params: SpringLinkParams, t0: float) -> PhysicsResult:
    """Equilibrium under the external loads with the commands at t = 0, then integrate."""
    from .._exudyn import dynamic_settings

    load, exu = model.load, model.exu
    act = load.actuation
    start = np.zeros(len(model.tendons)) if act is None else act.command_at(0.0, load.ramp_time)
    ramp_to(model, params, start)
    rec_t, rec_tip, rec_T, bb_t, bb_p = [], [], [], [], []
    peak: dict[str, float] = {}  # largest stress extras over the recorded states
    h = model.options.time_step if model.options.time_step > 0 else load.duration
    stride = frame_stride(math.ceil(load.duration / h))

    def record(t: float, r: PhysicsResult, final: bool = False) -> None:
        while rec_t and rec_t[-1] >= t - 1e-12:  # a step retried at a smaller size: drop its samples
            for lst in (rec_t, rec_tip, rec_T):
                lst.pop()
            while bb_t and bb_t[-1] >= t - 1e-12:
                bb_t.pop()
                bb_p.pop()
        if final or len(rec_t) % stride == 0:  # decimated backbone frames for the report's viewer
            bb_t.append(t)
            bb_p.append(np.asarray(r.positions, dtype=float).copy())
        rec_t.append(t)
        rec_tip.append(r.tip_position.copy())
        rec_T.append(r.tendon_tensions.copy())
        for k in ("max_stress_backbone", "max_stress_tendon", "stress_ratio"):
            if k in r.extras:
                peak[k] = max(peak.get(k, 0.0), float(r.extras[k]))

    def command(t: float) -> None:
        cmd = start if act is None else act.command_at(t, load.ramp_time)
        if model.mode == "length":
            model._L0 = model.rest_lengths(np.asarray(cmd), 1.0)
            model.update_active_set()
        model.set_tendons(np.asarray(cmd), 1.0)

    def pre_step(mbs, t):  # noqa: ANN001 - Exudyn callback signature
        # Exudyn passes the END time of the coming step; the state is the one at its start
        t_state = float(t) - float(solver.it.currentStepSize)  # record() drops a retried step's samples
        command(t_state)  # the state is recorded with the commands it was solved for
        record(t_state, model.result(SolverInfo(True)))
        command(float(t))  # the commands of the coming step, at its end time
        return True

    solver = exu.MainSolverImplicitSecondOrder()
    model.mbs.SetPreStepUserFunction(pre_step)
    settings = dynamic_settings(model.options, load.duration)
    _use_sparse(settings, model)
    try:
        solver.SolveSystem(model.mbs, settings)
    except exu.SolverError as err:
        raise ModelFailure(f"spring_link: dynamic solve failed: {err}") from err
    record(load.duration, model.result(SolverInfo(True)), final=True)
    info = SolverInfo(converged=True, iterations=int(solver.it.newtonStepsCount),
                      wall_time=time.perf_counter() - t0, message=f"{len(rec_t) - 1} time steps")
    res = model.result(
        info, time_=np.asarray(rec_t),
        series={"tip_position": np.asarray(rec_tip), "tendon_tensions": np.asarray(rec_T),
                **backbone_series(bb_t, bb_p)},
    )
    return replace(res, extras={**res.extras, **peak})


def solve(robot: Robot, load: LoadCase, options: SolverOptions,
          params: SpringLinkParams = SpringLinkParams()) -> PhysicsResult:
    """Static or dynamic solve of the spring-link chain (see :mod:`workbench.physics.spring_link`).

    Parameters
    ----------
    robot : Robot
    load : LoadCase
    options : SolverOptions
        ``n_elements`` is the number of links ``N`` (multiple of the number of sections).
    params : SpringLinkParams
        Model-specific settings (``richardson=True``: two static solves extrapolated, :mod:`.richardson`).

    Returns
    -------
    PhysicsResult
        ``joint_angles`` shape ``(N, 1)`` (planar), ``(N, 3)`` or ``(N, 2)`` (3-D, sprung or
        locked torsion); for dynamics ``time`` (k,) and series ``tip_position`` (k, 3),
        ``tendon_tensions`` (k, n_tendons).

    Raises
    ------
    ModelFailure
        Non-planar case with ``dimension="2d"``, unsupported combination, failed load ramp,
        non-positive tendon rest length.
    ValueError
        ``n_elements`` not a multiple of the number of sections.
    """
    from .._exudyn import quiet_exudyn

    check_model_inputs(robot, load, options)
    if params.richardson:
        check_richardson(options.n_elements, robot.n_sections, load.analysis)
        states = []  # both resolutions' warm states, concatenated (each picks its own: _warm_decode)

        def at(n: int) -> PhysicsResult:
            res = solve(robot, load, replace(options, n_elements=n), replace(params, richardson=False))
            states.append(res.warm_state)
            return res

        res = richardson_result(at, options.n_elements)
        return replace(res, warm_state=None if any(s is None for s in states) else np.concatenate(states))
    planar, why = is_planar(robot, load)
    if params.dimension == "2d" and not planar:
        raise ModelFailure(f"spring_link: dimension='2d' requested but the case is not planar: {why}")
    use_2d = params.dimension == "2d" or (params.dimension == "auto" and planar)
    params = replace(params, axial=resolve_axial(params, robot, load, options.tendon_model, use_2d))
    geo = chain_geometry_from_robot(robot, options.n_elements)
    t0 = time.perf_counter()
    with quiet_exudyn():
        model = build_chain(robot, load, options, geo, params, use_2d)
        if model.lagged_length and load.analysis != "static":
            raise ModelFailure("spring_link: planar continuum tendons in length mode with axial springs are static "
                               "only (lagged coupling, workbench/physics/spring_link/lengthmode.py); use axial=False "
                               "or tendon_model='eyelets'")
        if load.analysis == "static":
            return _solve_static(model, params, t0)
        return _solve_dynamic(model, params, t0)


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Registered model ``"spring_link"``: :func:`solve` with default :class:`SpringLinkParams` except
    the model's own settings in ``options`` (``options.settings("spring_link")``: ``backend``, ``axial`` and
    ``richardson``, the study keys ``solver.spring_link_backend``, ``solver.spring_link_axial`` and
    ``solver.spring_link_richardson``)."""
    return solve(robot, load, options, SpringLinkParams(**options.settings("spring_link")))
