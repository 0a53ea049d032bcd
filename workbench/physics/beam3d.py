"""Spatial tendon-driven backbone: Exudyn's geometrically exact beam with eyelet tendons.

Model ``"beam3d"``: ``run(robot, load, options) -> PhysicsResult``.

* Backbone: ``options.n_elements`` ``ObjectBeamGeometricallyExact`` elements on Euler-parameter
  nodes (``NodeRigidBodyEP``), distributed over the sections by :func:`._beam3d_layout.element_layout` (the count
  is ``extras["n_elements"]``), each with the cross-section at its midpoint (tapers piecewise
  constant), stiffness ``diag(EA, GA, GA, GJ, EI, EI)`` (``GA = 100 EA`` if None).  Built in a model
  frame with the beam along model +x: model (x, y, z) = base (z, x, y) (``R_BASE_MODEL``); inputs
  are rotated in, results back.  Clamp: the six coordinates of node 0.
* Loads: gravity on every element, disk masses lumped onto the two nodes of their element, the
  payload as a tip mass point (an offset payload: a force at the offset point, static only); tip
  force and torque on the tip node (base-frame directions, not follower loads).
* Tendons (``options.tendon_model == "eyelets"``; ``"continuum"`` raises :class:`ModelFailure`
  for loaded tendons): anchored on the base plate at ``d(0)``, through marker eyelets at every
  disk at ``(d cos sigma, d sin sigma)``, offsets ``TendonGroup.offset_at(s / s_end)``
  (:func:`._beam3d_layout.tendon_routes`), on a massless node body at a disk on a node (but in undamped
  dynamics).  Tension mode: zero-stiffness ``ObjectConnectorSpringDamper`` segments with constant force
  ``T`` between ``MarkerBodyPosition`` eyelets.  Length mode: one ``ObjectConnectorReevingSystemSprings`` per tendon
  (rigid-marker eyelets), rest length ``L_path0 / (1 + T_pre/EA_t) + delta_l``, ``regularizationForce``
  1e-3 N, tensions ``max(0, EA_t stretch / rest length)``.  ``forODE2Connectors`` numerical differentiation.
* Static analysis (:func:`_ramp_static`): the load ramp (:func:`workbench.physics._stepping.load_ramp`)
  on the rod with EA, GA scaled down (:func:`auto_stiffness_stages`), then EA, GA raised at full
  load up to the real rod (``options.newton_tolerance``); the plain ramp if a stage fails.  Every
  ODE2 Jacobian term numerical (Exudyn's GE-beam one is wrong on EP nodes; ``docs/models.md``).
* Dynamic analysis: generalised-alpha from the static equilibrium at t = 0; commands ``TendonActuation.
  command_at(t, load.ramp_time)`` set in a ``preStepUserFunction`` (at the *end* time of the coming step);
  sparse LU; ``options.damping = beta`` [s]: Kelvin-Voigt damping by inter-node connectors (``Beam3DSystem.
  _add_section_dampers``), Newton stopped at ``DYNAMIC_ABSOLUTE_TOLERANCE_FACTOR x newton_tolerance`` if
  damped; series every ``max(time_step, duration / 1000)`` (:func:`workbench.models.result.series_times`).
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
from ._stepping import LoadRampInfo, PathPoint, RampExhausted, RampPolicy, RampStalled, load_ramp, path_fields

__all__ = ["run", "auto_stiffness_stages"]

_MIN_INCREMENT = 1e-6
_STATIC_MAX_ITERATIONS = 50
#: doubling capped at the load still to go, halving on failure (the step sequence of this model)
_RAMP_POLICY = RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="remaining",
                          min_increment=_MIN_INCREMENT, end_tolerance=1e-14)


def _check(robot: Robot, load: LoadCase, options: SolverOptions) -> None:
    check_model_inputs(robot, load, options)
    if load.analysis == "dynamic" and robot.payload.mass > 0 and any(robot.payload.offset):
        raise ModelFailure("beam3d: a payload with non-zero offset is supported in static analysis only")


def _built_tensions(system, mode: str, n_tendons: int) -> np.ndarray:
    """Tensions of all ``n_tendons`` tendons: zeros when none was built (``mode == "none"``: no tendon
    loads), else one per built tendon; a count that differs raises :class:`ModelFailure` with both lengths
    (it used to be replaced by zeros; ``tests/physics/test_beam3d_tensions.py``)."""
    if mode == "none":
        return np.zeros(n_tendons)
    T, _ = system.tendon_state()
    T = np.asarray(T, dtype=float)
    if T.size != n_tendons:
        raise ModelFailure(f"beam3d: {T.size} tendon tensions from the built system for the robot's {n_tendons} "
                           f"tendons (mode {mode!r}); the tendon objects do not match the robot")
    return T


def _tendons_active(robot: Robot, load: LoadCase) -> str:
    """'none', 'tension' or 'length': which tendon objects the case needs."""
    act = load.actuation
    if act is None or robot.n_tendons == 0:
        return "none"
    if act.mode == "tension" and not any(v > 0 for v in act.values):
        return "none"
    return act.mode



#: Predictor stages of a static solve ("auto": :func:`auto_stiffness_stages`); ``()``: load ramp only.
STIFFNESS_STAGES = "auto"
#: First stage: EA and GA scaled so that the stiffest element has ``EA L_e^2 / EI`` = this.
_SOFT_RATIO = 1.0
#: Factor between stages; the last one below 1 / 3 (then the robot's own stiffness).
_STAGE_GROWTH = 30.0
#: Newton tolerance of the predictor stages (their equilibria only start the next stage).
_STAGE_TOLERANCE = 1e-3
#: ``numericalDifferentiation.relativeEpsilon`` of the static Jacobian (Exudyn's default 1e-7 leaves
#: forward-difference errors in the stiff entries that are as large as the soft bending stiffness).
_FD_EPSILON = 1e-9
#: modified-Newton iterations per Jacobian in damped dynamics (Exudyn: 8; undamped runs keep 8); see ``_dynamic``
MODIFIED_NEWTON_ITERATIONS = 15
#: damped dynamics: Newton's absolute tolerance (RMS per coordinate of the increment, residualMode 1) is this
#: times ``options.newton_tolerance`` (1e-6 at the default 1e-9; Exudyn's relative test, a 1e-9 decrease of
#: the first increment, is rarely reached within a step, so the absolute one stops the iteration); see ``_dynamic``
DYNAMIC_ABSOLUTE_TOLERANCE_FACTOR = 1e3


def _static_settings(options: SolverOptions, jacobian: str = "numerical", tolerance: float | None = None):
    """Static settings; ``jacobian="numerical"``: every ODE2 term by numerical differentiation at
    ``_FD_EPSILON``; ``"exudyn_beam"``: Exudyn's beam Jacobian, numerical connectors only (the
    initial equilibrium of dynamics; that beam Jacobian is wrong on Euler-parameter nodes, ``docs/models.md``)."""
    from ._exudyn import static_settings

    s = static_settings(options, 1)
    st = s.staticSolver
    st.adaptiveStep = False
    nd = st.newton.numericalDifferentiation
    nd.forODE2Connectors = True
    if jacobian == "numerical":
        nd.forODE2 = True
        nd.relativeEpsilon = _FD_EPSILON
    elif jacobian != "exudyn_beam":
        raise ValueError(f"beam3d: jacobian must be 'numerical' or 'exudyn_beam', got {jacobian!r}")
    if tolerance is not None:
        st.newton.relativeTolerance = tolerance
    st.newton.maxIterations = _STATIC_MAX_ITERATIONS
    return s


def auto_stiffness_stages(EA, EI, element_lengths) -> tuple[float, ...]:
    """EA / GA factors of the predictor stages: ``s0 = _SOFT_RATIO / max(EA L_e^2 / EI)``, then
    ``s0 * _STAGE_GROWTH^k`` while below 1/3; ``()`` when the rod is that soft already.

    Parameters
    ----------
    EA, EI, element_lengths : (n_el,) array_like
        Axial stiffness [N], bending stiffness [N m^2] and length [m] of every element.
    """
    ratio = float(np.max(np.asarray(EA, float) * np.asarray(element_lengths, float) ** 2 / np.asarray(EI, float)))
    s = _SOFT_RATIO / ratio
    out = []
    while s < 1.0 / 3.0:
        out.append(s)
        s *= _STAGE_GROWTH
    return tuple(out)


def _check_stages(stages) -> tuple[float, ...] | str:
    if isinstance(stages, str):
        if stages != "auto":
            raise ValueError(f"beam3d: stiffness_stages must be 'auto' or a tuple of factors, got {stages!r}")
        return stages
    out = tuple(float(a) for a in stages)
    if any(not 0.0 < a < 1.0 for a in out) or list(out) != sorted(out):
        raise ValueError(f"beam3d: stiffness_stages must rise strictly inside (0, 1), got {stages!r}")
    return out


def _ramp_static(system, options: SolverOptions, values_at, lam_pre_at, loads_at, *,
                 stages=STIFFNESS_STAGES, jacobian: str = "numerical") -> tuple[int, int, LoadRampInfo]:
    """Static equilibrium at lambda = 1; returns (accepted increments, attempts), one ``SolveStatic`` each,
    and the outcome of the load ramp that was used (its path event: :func:`_path_point` measures the tip).

    ``values_at(lam)`` tendon commands, ``lam_pre_at(lam)`` pretension factor, ``loads_at(lam)``
    load factor.  With ``stages`` ("auto": :func:`auto_stiffness_stages`; axial-shear stiffness
    continuation): the load ramp (``_RAMP_POLICY``) with EA and GA scaled by ``stages[0]`` to
    ``_STAGE_TOLERANCE``, then one solve per further stage and one at the robot's own stiffness
    (``options.newton_tolerance``).
    The soft stages are predictors only: the result is the equilibrium of the real rod.  They
    exist because Newton's basin on the real rod is tiny: a bending step leaves axial-strain errors
    ~ EA dtheta^2 that act as compressive loads far above the rod's Euler load.  If any stage fails,
    the state is reset and the plain load ramp runs at full stiffness (``options.max_load_steps`` caps
    each of the two ramps).  A failed attempt (solver
    error or non-finite state) restores the ODE2 and algebraic coordinates.
    """
    import exudyn as exu

    from ._exudyn import ode2_saver

    mbs = system.mbs
    stages = _check_stages(stages)
    if stages == "auto":
        stages = auto_stiffness_stages([c.EA for c in system.elem_cs], [c.EI for c in system.elem_cs], system.elem_len)
    settings = _static_settings(options, jacobian)
    loose = _static_settings(options, jacobian, tolerance=max(_STAGE_TOLERANCE, options.newton_tolerance))

    def solve(s) -> bool:
        try:
            exu.SolveStatic(mbs, s, updateInitialValues=True)
        except exu.SolverError:
            return False
        return bool(np.all(np.isfinite(np.asarray(mbs.systemData.GetODE2Coordinates()))))

    def attempt_with(s):
        def attempt(lam: float) -> bool | PathPoint:
            system.set_tendons(values_at(lam), lam_pre_at(lam))
            system.set_loads(loads_at(lam))
            return solve(s) and _path_point(system)
        return attempt

    save, restore = ode2_saver(mbs, with_ae=True)
    accepted = attempts = 0
    begin = _path_point(system)
    if stages:
        start = save()
        system.set_axial_shear_scale(stages[0])
        try:
            info = load_ramp(attempt_with(loose), save, restore, max_attempts=options.max_load_steps,
                             policy=_RAMP_POLICY, start=begin)
            accepted, attempts = info.accepted, info.attempts
            ok = True
            for a in stages[1:] + (1.0,):
                system.set_axial_shear_scale(a)
                attempts += 1
                ok = solve(loose if a < 1.0 else settings)
                if not ok:
                    break
                accepted += 1
        except (RampExhausted, RampStalled):
            ok = False
        if ok:
            return accepted, attempts, info
        system.set_axial_shear_scale(1.0)  # fall back: the plain load ramp from the start
        restore(start)
    try:
        info = load_ramp(attempt_with(settings), save, restore, max_attempts=options.max_load_steps,
                         policy=_RAMP_POLICY, start=begin)
    except RampExhausted as stop:
        raise ModelFailure(
            f"beam3d: static load ramp needs more than max_load_steps={options.max_load_steps} "
            f"increments (reached lambda={stop.lam:.4g})"
        ) from None
    except RampStalled as stop:
        raise ModelFailure(
            f"beam3d: static solve failed to converge (load increment below {_MIN_INCREMENT} at lambda={stop.lam:.4g})"
        ) from None
    return accepted + info.accepted, attempts + info.attempts, info


def _path_point(system) -> PathPoint:
    """The load-path measure of the current state: tip position / L and tip tangent (base frame)."""
    T = system.tip_frame()
    return PathPoint(tuple(np.concatenate([T[:3, 3] / system.robot.length, T[:3, 2]])))


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
    # initial equilibrium: the plain ramp with Exudyn's beam Jacobian (no stiffness stages); the dynamic
    # answers are pinned with it (tests/regression golden wire_delay_arm)
    acc, att, _ = _ramp_static(system, options, lambda lam: lam * cmd0, lambda lam: lam, lambda lam: lam,
                               stages=(), jacobian="exudyn_beam")
    sim = dynamic_settings(options, load.duration)
    ti = sim.timeIntegration
    ti.newton.numericalDifferentiation.forODE2Connectors = True
    ti.newton.useModifiedNewton = True
    # damped: up to 15 (not Exudyn's 8) modified-Newton iterations before a new Jacobian: a Jacobian
    # costs about as much as 20 iterations (the eyelet ropes' numerical part), and fewer Jacobians give the
    # same answer (the Jacobian counts and times: benchmarks/README.md, "wire delay"; docs/models.md)
    # Undamped runs keep Exudyn's 8: their answer depends on the iteration path (the undamped arm's
    # compensated case moves by 3 mm at 12; tests/regression golden wire_delay_arm)
    ti.newton.maxModifiedNewtonIterations = MODIFIED_NEWTON_ITERATIONS if options.damping > 0 else 8
    # damped: stop Newton at an increment of 1e3 x newton_tolerance (RMS per coordinate) instead of 1e-12:
    # 2.4 instead of 6.5 iterations per step in the wire-delay case, whose headline moves by 2 um (1 % of
    # its 0.165 mm error bar; benchmarks/README.md, "wire delay"); a tighter options.newton_tolerance
    # tightens it.  Undamped runs keep 1e-12 (their answer depends on the iteration path, as above)
    if options.damping > 0:
        ti.newton.absoluteTolerance = DYNAMIC_ABSOLUTE_TOLERANCE_FACTOR * options.newton_tolerance
    # sparse LU: the banded beam system (~7 (n_el + 1) coordinates) factorises ~15x faster than dense
    # at 40 elements (benchmarks/README.md, "Wire delay"); same answer to solver precision
    sim.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    n_steps = ti.numberOfSteps
    h = load.duration / n_steps
    out_dt = max(1, int(round(max(h, load.duration / 1000.0) / h))) * h
    n_out = int(round(load.duration / out_dt)) + 1
    rec = _Recorder(system, n_t, stations, frame_stride(n_out))

    command = act.command_function(load.ramp_time) if drive else None

    def pre_step(mbs, t):
        # Exudyn calls this with t = the END time of the step about to be solved;
        # the state is the converged state at t - h_cur (last accepted step).
        solver = mbs.sys.get("dynamicSolver")
        h_cur = solver.it.currentStepSize if solver is not None else h
        t_state = t - h_cur
        k = round(t_state / out_dt)
        if abs(t_state - k * out_dt) < 0.5 * h:
            if drive:  # record the state with the commands it was solved for
                system.set_tendons(command(t_state), 1.0)
            rec.record(float(t_state))
        if drive:  # commands at the end of this step (exact also for reduced steps)
            system.set_tendons(command(t), 1.0)
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


def run(robot: Robot, load: LoadCase, options: SolverOptions, *, stiffness_stages=STIFFNESS_STAGES,
        jacobian: str = "numerical") -> PhysicsResult:
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
    stiffness_stages : "auto" or tuple of float
        Static analyses: EA and GA factors of the predictor stages (:func:`_ramp_static`,
        "auto": :func:`auto_stiffness_stages`); ``()`` runs the plain load ramp at full stiffness.
        The initial equilibrium of a dynamic analysis uses ``()`` and ``"exudyn_beam"``.
    jacobian : {"numerical", "exudyn_beam"}
        Static analyses: Jacobian of the static Newton (:func:`_static_settings`).

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
    from ._beam3d_system import Beam3DSystem
    from ._exudyn import quiet_exudyn

    _check(robot, load, options)
    _check_stages(stiffness_stages)
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
        system = Beam3DSystem(robot, load, options, mode)
        extras = {"n_elements": float(len(system.elements))}
        if load.analysis == "static":
            final = np.asarray(act.values) if act is not None else np.zeros(n_t)
            acc, att, path = _ramp_static(system, options, lambda lam: lam * final, lambda lam: lam, lambda lam: lam,
                                          stages=stiffness_stages, jacobian=jacobian)
            extras["load_steps"] = float(acc)
            times, series = None, {}
        else:
            path = None
            acc, att, n_steps, times, series, stress = _dynamic(system, load, options, n_t,
                                                                act is not None and mode != "none", stations)
            extras.update(load_steps=float(acc), n_steps=float(n_steps))
        positions = system.positions(stations)
        tip = system.tip_frame()
        T = _built_tensions(system, mode, n_t)
        strains = system.element_strains()
        dl, tw = system.shape_scalars(strains)
        if load.analysis == "static":
            from ..models.stress import stress_extras

            bs = system.backbone_stress(strains)
            stress = stress_extras(None if bs is None else bs[0], None if bs is None else bs[1], robot, T)
        extras.update(stress)
    if not (np.all(np.isfinite(positions)) and np.all(np.isfinite(tip))):
        raise ModelFailure("beam3d: non-finite state after the solve")
    return PhysicsResult(
        model="beam3d",
        stations=stations,
        positions=positions,
        tip_frame=tip,
        length_change=dl,
        tendon_tensions=T,
        tip_twist=tw,
        solver=SolverInfo(converged=True, iterations=int(att), wall_time=_time.perf_counter() - t_wall, message="ok",
                          **path_fields(path)),
        time=times,
        series=series,
        extras=extras,
    )
