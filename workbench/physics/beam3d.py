"""Spatial tendon-driven backbone: Exudyn's geometrically exact beam with eyelet tendons.

Model ``"beam3d"``: ``run(robot, load, options) -> PhysicsResult``.

* Backbone: ``options.n_elements`` ``ObjectBeamGeometricallyExact`` elements on Euler-parameter
  nodes (``NodeRigidBodyEP``), distributed over the sections by :func:`element_layout` (the count
  is ``extras["n_elements"]``), each with the cross-section at its midpoint (tapers piecewise
  constant), stiffness ``diag(EA, GA, GA, GJ, EI, EI)`` (``GA = 100 EA`` if None).  Built in a model
  frame with the beam along model +x: model (x, y, z) = base (z, x, y) (``R_BASE_MODEL``); inputs
  are rotated in, results back.  Clamp: the six coordinates of node 0.
* Loads: gravity on every element, disk masses lumped onto the two nodes of their element, the
  payload as a tip mass point (an offset payload: a force at the offset point, static only); tip
  force and torque on the tip node (base-frame directions, not follower loads).
* Tendons (``options.tendon_model == "eyelets"``; ``"continuum"`` raises :class:`ModelFailure`
  for loaded tendons): anchored on the base plate at ``d(0)``, through rigid-marker eyelets at every
  disk at ``(d cos sigma, d sin sigma)``, offsets ``TendonGroup.offset_at(s / s_end)``
  (:func:`tendon_routes`).  Tension mode: zero-stiffness ``ObjectConnectorSpringDamper`` segments
  with constant force ``T``.  Length mode: one ``ObjectConnectorReevingSystemSprings`` per tendon,
  rest length ``L_path0 / (1 + T_pre/EA_t) + delta_l``, ``regularizationForce`` 1e-3 N, tensions
  ``max(0, EA_t stretch / rest length)``.  ``forODE2Connectors`` numerical differentiation is on.
* Static analysis: loads and commands scale with lambda 0 -> 1 through
  :func:`workbench.physics._stepping.ramp` (one ``SolveStatic`` per increment, doubling capped at
  the remaining load, halving on failure); more than ``options.max_load_steps`` attempts or an
  increment below 1e-6 raise :class:`ModelFailure`.
* Dynamic analysis: generalised-alpha from the static equilibrium at t = 0; commands
  ``TendonActuation.command_at(t, load.ramp_time)`` set in a ``preStepUserFunction`` (called with
  the *end* time of the coming step); sparse LU; ``options.damping = beta`` [s]: stiffness-proportional
  damping by inter-node connectors (``_System._add_section_dampers``; Exudyn ignores the section
  damping matrix); undamped tendons; series on the grid of
  :func:`workbench.models.result.series_times` (every ``max(time_step, duration / 1000)``).
* Outputs: ``positions`` by the element's own interpolation at ``options.n_stations`` stations;
  ``tip_frame`` = tip cross-section axes (z along the backbone); ``length_change`` = sum of
  ``L_e (|Gamma_e| - 1)``; ``tip_twist`` = sum of ``L_e kappa_1`` (relative to the base frame
  parallel-transported along d1); ``tendon_tensions``; dynamics ``series`` ``tip_position`` (k, 3),
  ``tendon_tensions`` (k, n), ``tendon_stretch`` (k, n), ``length_change`` (k,), ``tip_twist`` (k,);
  ``extras`` ``n_elements``, ``load_steps``, ``n_steps``.

Checked by ``tests/physics/test_beam3d.py`` (exact arcs in any plane, torsion, compression,
convergence, sag, CC arcs, frequency, damping, rejections, dynamics) and ``test_beam3d_preset.py``;
measured behaviour in ``docs/models.md`` ("Geometrically exact beam").
"""

from __future__ import annotations

import time as _time

import numpy as np

from ..models.inputs import check_model_inputs
from ..models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ..robot import LoadCase, Robot
from ._beam3d_layout import R_BASE_MODEL, element_layout, tendon_routes
from ._stepping import RampExhausted, RampPolicy, RampStalled, ramp

__all__ = ["run", "element_layout", "tendon_routes", "R_BASE_MODEL"]

_MIN_INCREMENT = 1e-6
_STATIC_MAX_ITERATIONS = 50
#: doubling capped at the load still to go, halving on failure (the step sequence of this model)
_RAMP_POLICY = RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="remaining",
                          min_increment=_MIN_INCREMENT, end_tolerance=1e-14)


def _check(robot: Robot, load: LoadCase, options: SolverOptions) -> None:
    check_model_inputs(robot, load, options)
    if load.analysis == "dynamic" and robot.payload.mass > 0 and any(robot.payload.offset):
        raise ModelFailure("beam3d: a payload with non-zero offset is supported in static analysis only")


def _tendons_active(robot: Robot, load: LoadCase) -> str:
    """'none', 'tension' or 'length': which tendon objects the case needs."""
    act = load.actuation
    if act is None or robot.n_tendons == 0:
        return "none"
    if act.mode == "tension" and not any(v > 0 for v in act.values):
        return "none"
    return act.mode



def _static_settings(options: SolverOptions):
    from ._exudyn import static_settings

    s = static_settings(options, 1)
    st = s.staticSolver
    st.adaptiveStep = False
    st.newton.numericalDifferentiation.forODE2Connectors = True
    st.newton.maxIterations = _STATIC_MAX_ITERATIONS
    return s


def _ramp_static(system, options: SolverOptions, values_at, lam_pre_at, loads_at) -> tuple[int, int]:
    """Load ramp lambda: 0 -> 1 (``_RAMP_POLICY``); one ``SolveStatic`` per attempt.

    ``values_at(lam)`` tendon commands, ``lam_pre_at(lam)`` pretension factor,
    ``loads_at(lam)`` load factor.  A failed attempt (solver error or non-finite state)
    restores the ODE2 and algebraic coordinates.  Returns (accepted increments, attempts).
    """
    import exudyn as exu

    from ._exudyn import ode2_saver

    mbs = system.mbs
    settings = _static_settings(options)

    def attempt(lam: float) -> bool:
        system.set_tendons(values_at(lam), lam_pre_at(lam))
        system.set_loads(loads_at(lam))
        try:
            exu.SolveStatic(mbs, settings, updateInitialValues=True)
        except exu.SolverError:
            return False
        return bool(np.all(np.isfinite(np.asarray(mbs.systemData.GetODE2Coordinates()))))

    save, restore = ode2_saver(mbs, with_ae=True)
    try:
        info = ramp(attempt, save, restore, max_attempts=options.max_load_steps, policy=_RAMP_POLICY)
    except RampExhausted as stop:
        raise ModelFailure(
            f"beam3d: static load ramp needs more than max_load_steps={options.max_load_steps} "
            f"increments (reached lambda={stop.lam:.4g})"
        ) from None
    except RampStalled as stop:
        raise ModelFailure(
            f"beam3d: static solve failed to converge (load increment below {_MIN_INCREMENT} at lambda={stop.lam:.4g})"
        ) from None
    return info.accepted, info.attempts


class _Recorder:
    """Time series of a dynamic run; a step retried at a smaller size overwrites its samples."""

    def __init__(self, system, n_tendons: int, stations=None, stride: int = 1):
        self.system = system
        self.n_t = n_tendons
        self.stations, self.stride = stations, stride  # backbone frames: every stride-th sample
        self.rec: dict[str, list] = {"t": [], "tip": [], "T": [], "dl": [], "tw": [], "st": [], "sb": [], "bb": []}
        self.strength = None  # backbone strength per element (stress_extras)

    def record(self, t: float, final: bool = False) -> None:
        T, st = self.system.tendon_state()
        if T.size != self.n_t:  # no tendon objects built (unloaded tendons)
            T, st = np.zeros(self.n_t), np.zeros(self.n_t)
        strains = self.system.element_strains()
        dl, tw = self.system.shape_scalars(strains)
        bs = self.system.backbone_stress(strains)
        if bs is not None:
            self.strength = bs[1]
        tip = self.system.tip_position()
        rec = self.rec
        # a step retried with a smaller step size calls pre_step again at the same t
        while rec["t"] and rec["t"][-1] >= t - 1e-12:
            for key in rec:
                rec[key].pop()
        rec["t"].append(t)
        rec["tip"].append(tip)
        rec["T"].append(T)
        rec["st"].append(st)
        rec["dl"].append(dl)
        rec["tw"].append(tw)
        rec["sb"].append(None if bs is None else bs[0])
        keep = self.stations is not None and (final or (len(rec["t"]) - 1) % self.stride == 0)
        rec["bb"].append(self.system.positions(self.stations) if keep else None)

    def stress(self, robot: Robot) -> dict[str, float]:
        """Stress extras (:func:`workbench.models.stress.stress_extras`) over every recorded state."""
        from ..models.stress import stress_extras

        sb = self.rec["sb"]
        sigma = None if not sb or any(x is None for x in sb) else np.concatenate(sb)
        T = np.asarray(self.rec["T"]).reshape(len(self.rec["t"]), self.n_t)
        return stress_extras(sigma, None if sigma is None else np.tile(self.strength, len(sb)), robot, T)

    def series(self) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        rec, n_t = self.rec, self.n_t
        times = np.asarray(rec["t"])
        return times, {
            "tip_position": np.asarray(rec["tip"]),
            "tendon_tensions": np.asarray(rec["T"]).reshape(len(times), n_t),
            "tendon_stretch": np.asarray(rec["st"]).reshape(len(times), n_t),
            "length_change": np.asarray(rec["dl"]),
            "tip_twist": np.asarray(rec["tw"]),
            **_kept_frames(times, rec["bb"]),
        }


def _kept_frames(times: np.ndarray, frames: list) -> dict[str, np.ndarray]:
    """``series.backbone`` / ``backbone_time`` of the recorded samples that kept a backbone."""
    from ..models.backbone_frames import backbone_series

    keep = [i for i, f in enumerate(frames) if f is not None]
    return backbone_series(times[keep], [frames[i] for i in keep]) if keep else {}


def _dynamic(system, load: LoadCase, options: SolverOptions, n_t: int, drive: bool, stations: np.ndarray):
    """Static equilibrium at t = 0, then generalised-alpha; returns (accepted, attempts, n_steps, times, series,
    stress extras over the recorded states).

    ``series`` includes decimated backbone frames at ``stations`` (:mod:`workbench.models.backbone_frames`)."""
    import exudyn as exu

    from ..models.backbone_frames import frame_stride
    from ._exudyn import dynamic_settings

    act = load.actuation
    cmd0 = act.command_at(0.0, load.ramp_time) if act is not None else np.zeros(n_t)
    acc, att = _ramp_static(system, options, lambda lam: lam * cmd0, lambda lam: lam, lambda lam: lam)
    sim = dynamic_settings(options, load.duration)
    ti = sim.timeIntegration
    ti.newton.numericalDifferentiation.forODE2Connectors = True
    ti.newton.useModifiedNewton = True
    # sparse LU: the banded beam system (~7 (n_el + 1) coordinates) factorises ~15x faster than dense
    # at 40 elements (benchmarks/README.md, "Wire delay"); same answer to solver precision
    sim.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    n_steps = ti.numberOfSteps
    h = load.duration / n_steps
    out_dt = max(1, int(round(max(h, load.duration / 1000.0) / h))) * h
    n_out = int(round(load.duration / out_dt)) + 1
    rec = _Recorder(system, n_t, stations, frame_stride(n_out))

    def pre_step(mbs, t):
        # Exudyn calls this with t = the END time of the step about to be solved;
        # the state is the converged state at t - h_cur (last accepted step).
        solver = mbs.sys.get("dynamicSolver")
        h_cur = solver.it.currentStepSize if solver is not None else h
        t_state = t - h_cur
        if drive:  # record the state with the commands it was solved for
            system.set_tendons(act.command_at(t_state, load.ramp_time), 1.0)
        k = round(t_state / out_dt)
        if abs(t_state - k * out_dt) < 0.5 * h:
            rec.record(float(t_state))
        if drive:  # commands at the end of this step (exact also for reduced steps)
            system.set_tendons(act.command_at(t, load.ramp_time), 1.0)
        return True

    system.mbs.SetPreStepUserFunction(pre_step)
    try:
        exu.SolveDynamic(system.mbs, sim, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    except exu.SolverError as err:
        raise ModelFailure(f"beam3d: dynamic solve failed: {err}") from None
    if drive:
        system.set_tendons(act.command_at(load.duration, load.ramp_time), 1.0)
    rec.record(float(load.duration), final=True)
    times, series = rec.series()
    return acc, att, n_steps, times, series, rec.stress(system.robot)


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Solve the geometrically exact spatial backbone (model ``"beam3d"``).

    Parameters
    ----------
    robot : Robot
        Robot description (any number of sections, tapered sections allowed).
    load : LoadCase
        Tendon actuation, tip loads, static or dynamic analysis.
    options : SolverOptions
        ``n_elements``, ``tendon_model`` (only ``"eyelets"`` for loaded tendons),
        ``n_stations``, Newton tolerance, ``max_load_steps``, ``time_step``, ``damping``
        (stiffness-proportional beta [s], dynamics only), ``spectral_radius``.

    Returns
    -------
    PhysicsResult
        Base-frame results, see the module docstring.

    Raises
    ------
    ModelFailure
        Continuum tendons requested with loaded tendons, static ramp exhausted, NaN state,
        payload offset in dynamics.
    """
    from ._beam3d_system import _System
    from ._exudyn import quiet_exudyn

    _check(robot, load, options)
    mode = _tendons_active(robot, load)
    if mode != "none" and options.tendon_model != "eyelets":
        raise ModelFailure(
            "beam3d supports only tendon_model='eyelets' for loaded tendons "
            f"(got tendon_model={options.tendon_model!r}); continuum tendon loads are not implemented"
        )
    t_wall = _time.perf_counter()
    stations = np.linspace(0.0, robot.length, options.n_stations)
    act = load.actuation
    n_t = robot.n_tendons
    with quiet_exudyn():
        system = _System(robot, load, options, mode)
        extras = {"n_elements": float(len(system.elements))}
        if load.analysis == "static":
            final = np.asarray(act.values) if act is not None else np.zeros(n_t)
            acc, att = _ramp_static(system, options, lambda lam: lam * final, lambda lam: lam, lambda lam: lam)
            extras["load_steps"] = float(acc)
            times, series = None, {}
        else:
            acc, att, n_steps, times, series, stress = _dynamic(system, load, options, n_t,
                                                                act is not None and mode != "none", stations)
            extras.update(load_steps=float(acc), n_steps=float(n_steps))
        positions = system.positions(stations)
        tip = system.tip_frame()
        T, _ = system.tendon_state()
        strains = system.element_strains()
        dl, tw = system.shape_scalars(strains)
        if load.analysis == "static":
            from ..models.stress import stress_extras

            bs = system.backbone_stress(strains)
            Tn = T if T.size == n_t else np.zeros(n_t)
            stress = stress_extras(None if bs is None else bs[0], None if bs is None else bs[1], robot, Tn)
        extras.update(stress)
    if not (np.all(np.isfinite(positions)) and np.all(np.isfinite(tip))):
        raise ModelFailure("beam3d: non-finite state after the solve")
    if n_t and T.size != n_t:
        T = np.zeros(n_t)
    return PhysicsResult(
        model="beam3d",
        stations=stations,
        positions=positions,
        tip_frame=tip,
        length_change=dl,
        tendon_tensions=T if n_t else np.zeros(0),
        tip_twist=tw,
        solver=SolverInfo(converged=True, iterations=int(att), wall_time=_time.perf_counter() - t_wall, message="ok"),
        time=times,
        series=series,
        extras=extras,
    )
