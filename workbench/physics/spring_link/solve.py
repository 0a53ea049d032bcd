"""Static load ramp, backend and dimension choice, and the solve entry points."""

from __future__ import annotations

import time
from typing import Callable

import numpy as np

from ...models.inputs import check_model_inputs
from ...models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ...robot import LoadCase, Robot
from .chain import _Chain
from .planar import _Planar
from .spatial import _Spatial
from .tree import _Tree
from .geometry import chain_geometry_from_robot
from .params import SpringLinkParams, is_planar
from .._stepping import RampExhausted, RampPolicy, RampStalled, ramp

__all__ = ["solve", "run"]

_SPARSE_FROM = 16

#: The static ramp's step rule: first try the full load, halve on failure, double (capped at 1)
#: after every success, give up below an increment of 1e-6.
_STATIC_RAMP = RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="one", min_increment=1e-6)


def _use_sparse(settings, model) -> None:  # noqa: ANN001
    """Sparse LU for larger chains (dense LU dominated the 3-D solve time from N ~ 32)."""
    import exudyn as exu

    if model.geo.n_links >= _SPARSE_FROM:
        settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse


def _static_ramp(model: _Chain, options: SolverOptions, params: SpringLinkParams,
                 apply: Callable[[float], None]) -> tuple[int, int]:
    """Ramp ``apply(lam)`` from 0 to 1 with repeated static solves; returns (steps, newton its).

    One attempt applies the load factor and solves, re-solving while the slack/taut active set
    of length-controlled tendons changes (at most ``params.max_active_set_iterations`` passes).
    A failed attempt (Exudyn ``SolverError``, non-finite state, an unsettled active set) restores
    the state and the active set and halves the increment (:data:`_STATIC_RAMP`); a non-positive
    rope rest length is not a solver failure and propagates.  Newton iterations of every attempt
    are counted.  Checked by ``test_max_load_steps_is_a_failure``,
    ``test_rigid_body_ramp_failure_names_the_numerical_cause`` and ``test_spring_link_layout.py``.

    Raises
    ------
    ModelFailure
        More than ``options.max_load_steps`` attempts, or an increment below 1e-6.
    """
    from .._exudyn import static_settings

    exu = model.exu
    mbs = model.mbs
    settings = static_settings(options, 1)
    _use_sparse(settings, model)
    settings.staticSolver.adaptiveStep = False
    # eyelet ropes loading the joint constraints make Newton converge only linearly (measured
    # ~100-125 iterations at N = 16 vs 3-6 for continuum tendons, docs/models.md): allow more.
    eyelet_ropes = model.model == "eyelets" and model.mode is not None
    settings.staticSolver.newton.maxIterations = 250 if eyelet_ropes else 40
    newton_its = 0

    def attempt(lam: float) -> bool:
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
                    return True
                apply(lam)
            raise ModelFailure("spring_link: tendon slack/taut switching did not settle")
        except (exu.SolverError, RuntimeError) as err:  # ModelFailure is a RuntimeError too
            if isinstance(err, ModelFailure) and "rest length" in str(err):
                raise
            return False

    def save() -> tuple:
        return mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.Initial), list(model.tendon_active)

    def restore(state: tuple) -> None:
        q_save, active = state
        mbs.systemData.SetODE2Coordinates(q_save, configuration=exu.ConfigurationType.Initial)
        mbs.systemData.SetODE2Coordinates(q_save, configuration=exu.ConfigurationType.Current)
        model.tendon_active = active

    try:
        info = ramp(attempt, save, restore, max_attempts=options.max_load_steps, policy=_STATIC_RAMP)
    except RampExhausted as err:
        hint = ""
        if model.model == "eyelets" and model.mode is not None and model.rigid_bodies:
            hint = ("; eyelet ropes on the rigid-body chain converge only linearly in Newton (numerical, "
                    "not a physical instability): use SpringLinkParams(backend='tree') where possible")
        raise ModelFailure(
            f"spring_link: static load ramp exceeded options.max_load_steps={options.max_load_steps} "
            f"(reached load factor {err.lam:.4g}){hint}"
        ) from None
    except RampStalled as err:
        raise ModelFailure(f"spring_link: static solve failed near load factor {err.lam:.4g}") from None
    return info.attempts, newton_its


def solve(robot: Robot, load: LoadCase, options: SolverOptions,
          params: SpringLinkParams = SpringLinkParams()) -> PhysicsResult:
    """Static or dynamic solve of the spring-link chain (see the module docstring).

    Parameters
    ----------
    robot : Robot
    load : LoadCase
    options : SolverOptions
        ``n_elements`` is the number of links ``N`` (multiple of the number of sections).
    params : SpringLinkParams
        Model-specific settings.

    Returns
    -------
    PhysicsResult
        ``joint_angles`` shape ``(N, 1)``; for dynamics ``time`` (k,) and series
        ``tip_position`` (k, 3), ``tendon_tensions`` (k, n_tendons).

    Raises
    ------
    ModelFailure
        Non-planar case, failed load ramp, non-positive tendon rest length.
    ValueError
        ``n_elements`` not a multiple of the number of sections.
    """
    from .._exudyn import dynamic_settings, quiet_exudyn

    check_model_inputs(robot, load, options)
    planar, why = is_planar(robot, load)
    if params.dimension == "2d" and not planar:
        raise ModelFailure(f"spring_link: dimension='2d' requested but the case is not planar: {why}")
    use_2d = params.dimension == "2d" or (params.dimension == "auto" and planar)
    act_mode = None if load.actuation is None else load.actuation.mode
    geo = chain_geometry_from_robot(robot, options.n_elements)
    t0 = time.perf_counter()
    with quiet_exudyn():
        tree_ok = not params.axial and (use_2d or params.torsion == "locked")
        if params.backend == "tree" and not tree_ok:
            raise ModelFailure("spring_link: backend='tree' supports inextensible chains that are planar or have "
                               "torsion='locked' (Cardan joints) only")
        # eyelet ropes (reeving or constant-force segments) on the rigid-body chain stall the static
        # ramp (see Limitations); the constraint-free tree solves them in a few Newton iterations
        ropes = options.tendon_model == "eyelets" and act_mode is not None
        auto_tree = params.backend == "auto" and ropes
        if tree_ok and (params.backend == "tree" or auto_tree):
            model = _Tree(robot, load, options, geo, spatial=not use_2d)
        elif use_2d:
            model = _Planar(robot, load, options, geo, params.axial)
        else:
            model = _Spatial(robot, load, options, geo, params.torsion, params.axial)
        act = load.actuation
        n_t = len(model.tendons)
        final = np.zeros(n_t) if act is None else np.asarray(act.values)
        if load.analysis == "static":

            def apply(lam: float) -> None:
                model.set_external(lam)
                model.set_tendons(lam * final, lam)

            steps, its = _static_ramp(model, options, params, apply)
            info = SolverInfo(converged=True, iterations=its, wall_time=time.perf_counter() - t0,
                              message=f"{steps} load steps")
            return model.result(info)

        # dynamic: equilibrium under external loads with commands at t = 0, then integrate
        start = np.zeros(n_t) if act is None else act.command_at(0.0, load.ramp_time)

        def apply0(lam: float) -> None:
            model.set_external(lam)
            model.set_tendons(lam * start, lam)

        steps, its = _static_ramp(model, options, params, apply0)
        exu = model.exu
        rec_t, rec_tip, rec_T = [], [], []

        def pre_step(mbs, t):  # noqa: ANN001 - Exudyn callback signature
            cmd = start if act is None else act.command_at(t, load.ramp_time)
            if model.mode == "length":
                model._L0 = model.rest_lengths(np.asarray(cmd), 1.0)
                model.update_active_set()
            model.set_tendons(np.asarray(cmd), 1.0)
            r = model.result(SolverInfo(True))
            rec_t.append(t)
            rec_tip.append(r.tip_position.copy())
            rec_T.append(r.tendon_tensions.copy())
            return True

        model.mbs.SetPreStepUserFunction(pre_step)
        settings = dynamic_settings(options, load.duration)
        _use_sparse(settings, model)
        solver = exu.MainSolverImplicitSecondOrder()
        try:
            solver.SolveSystem(model.mbs, settings)
        except exu.SolverError as err:
            raise ModelFailure(f"spring_link: dynamic solve failed: {err}") from err
        res = model.result(SolverInfo(True))
        rec_t.append(load.duration)
        rec_tip.append(res.tip_position.copy())
        rec_T.append(res.tendon_tensions.copy())
        info = SolverInfo(converged=True, iterations=int(solver.it.newtonStepsCount),
                          wall_time=time.perf_counter() - t0, message=f"{len(rec_t) - 1} time steps")
        return model.result(
            info, time_=np.asarray(rec_t),
            series={"tip_position": np.asarray(rec_tip), "tendon_tensions": np.asarray(rec_T)},
        )


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Registered model ``"spring_link"``: :func:`solve` with default :class:`SpringLinkParams`."""
    return solve(robot, load, options, SpringLinkParams())
