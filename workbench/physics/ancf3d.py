"""Spatial ANCF cable backbone (Exudyn ``ObjectANCFCable``) for tendon-free load cases.

Model ``"ancf3d"``: ``run(robot, load, options) -> PhysicsResult``.

The 3-D ANCF cable (Euler-Bernoulli, position + slope nodes ``NodePointSlope1``) has no
cross-section frame and no torsion: rigid markers and torques are rejected by Exudyn and
y/z offsets of markers are silently ignored (facts note).  So this model covers gravity
sag, the payload (at zero offset) and tip forces only, and is the independent cross-check
of :mod:`workbench.physics.beam3d` for those cases.  It raises :class:`ModelFailure` for

* any tendon that would be loaded (tension mode with a non-zero tension, length mode with a
  non-zero command or pretension).  Unloaded tendons (no actuation, all-zero commands, no
  pretension) are treated as absent (slack), also in length mode;
* a non-zero tip torque (no rotational degrees of freedom);
* a payload with a non-zero offset (no tip frame to carry it).

Disks: weights at their stations, masses lumped onto the element's nodes (:meth:`_System._disk_weights`).

Discretisation: ``options.n_elements`` cable elements distributed over the sections like
:func:`workbench.physics._beam3d_layout.element_layout`, each with the cross-section at its
midpoint (EI, EA, mass per length; GJ and GA do not exist in this element).
``useReducedOrderIntegration=2`` (Lobatto axial integration; removes most coarse-mesh
axial locking under large sag, facts note).  Clamp: node-0 position and the two
transverse slope components are fixed; the axial slope component is left free (fixing it
forbids axial strain at the clamp).  The cable runs along the base z axis directly (no
internal frame).

Static analysis: all loads scale with lambda 0 -> 1 through :func:`workbench.physics._stepping.load_ramp`
(one ``SolveStatic`` per increment, doubling capped at the remaining load, halving on failure, at
most ``options.max_load_steps`` attempts).  Dynamic analysis: generalised-alpha from the static
equilibrium; loads are constant, so a dynamic run stays at rest (nothing in this model drives it);
damping ``options.damping`` = beta [s]: ``bendingDamping = beta EI``, ``axialDamping = beta EA``.

Outputs: positions from the element's own (cubic Hermite) interpolation at the stations;
``tip_frame`` z axis = the unit tip tangent, x/y axes = the base x/y axes parallel-transported
along the node tangents (the cable has no material frame); ``tip_twist`` = 0; ``length_change`` =
integral of ``|r'| - 1`` (3-point Gauss per element); ``tendon_tensions`` = zeros; extras
``max_stress_backbone`` / ``stress_ratio`` of the final state (:meth:`_System.backbone_stress`).
Checked by ``tests/physics/test_ancf3d.py`` and the ``ancf3d`` comparisons in ``test_beam3d.py``.
"""

from __future__ import annotations

import math

import time as _time

import numpy as np

from ..models.inputs import check_model_inputs
from ..models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ..robot import LoadCase, Robot
from ._stepping import LoadRampInfo, PathPoint, RampExhausted, RampPolicy, RampStalled, load_ramp, path_fields
from ._beam3d_layout import element_layout

__all__ = ["run"]

_MIN_INCREMENT = 1e-6
#: doubling capped at the load still to go, halving on failure (the step sequence of this model)
_RAMP_POLICY = RampPolicy(first_increment=1.0, growth=2.0, grow_after=1, cap="remaining",
                          min_increment=_MIN_INCREMENT, end_tolerance=1e-14)


def _check(robot: Robot, load: LoadCase, options: SolverOptions) -> None:
    check_model_inputs(robot, load, options)
    act = load.actuation
    if act is not None:
        if any(v != 0 for v in act.values) or act.pretension > 0:
            raise ModelFailure(
                "ancf3d has no cross-section frame and cannot carry offset tendons: tendon commands "
                f"must be all zero with no pretension (got mode={act.mode!r}, values={list(act.values)}, "
                f"pretension={act.pretension}); use model 'beam3d' for tendon actuation"
            )
    if any(load.tip_torque):
        raise ModelFailure(f"ancf3d has no rotational coordinates: tip_torque must be zero, got {load.tip_torque}")
    if robot.payload.mass > 0 and any(robot.payload.offset):
        raise ModelFailure("ancf3d has no tip frame: the payload offset must be (0, 0, 0)")


def _bishop_tip_frame(tangents: np.ndarray) -> np.ndarray:
    """Parallel-transport the base x/y axes along unit tangents ``(n, 3)``; returns ``(3, 3)``."""
    R = np.eye(3)
    t_prev = np.array([0.0, 0.0, 1.0])
    for t in tangents:
        t = t / np.linalg.norm(t)
        v = np.cross(t_prev, t)
        c = float(np.dot(t_prev, t))
        s = np.linalg.norm(v)
        if s > 1e-15:
            k = v / s
            K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
            Q = np.eye(3) + s * K + (1.0 - c) * K @ K
            R = Q @ R
        t_prev = t
    return R


class _System:
    """The assembled Exudyn system of one ancf3d solve: cable, clamp, masses and the ramped loads.

    ``loads`` lists ``(load index, full vector)`` in the order added: gravity on the elements and
    on the payload (a tip mass point), the disks' weights at their stations (:meth:`_disk_weights`),
    then the tip force.  Disk masses (inertia) are lumped linearly onto their element's two nodes.
    """

    def __init__(self, robot: Robot, load: LoadCase, options: SolverOptions):
        import exudyn as exu
        from exudyn.itemInterface import LoadForceVector, MarkerNodePosition, NodePointSlope1, ObjectANCFCable

        from ._exudyn import add_gravity_loads, add_point_masses, clamp_coordinates, lumped_disk_masses

        self.exu = exu
        self.SC = exu.SystemContainer()
        mbs = self.mbs = self.SC.AddSystem()
        node_s, elem_sec = element_layout(robot, options.n_elements)
        self.node_s, self.elem_len = node_s, np.diff(node_s)
        starts = np.concatenate([[0.0], robot.section_ends[:-1]])
        self.nodes = [mbs.AddNode(NodePointSlope1(referenceCoordinates=[0, 0, float(s), 0, 0, 1])) for s in node_s]
        self.elements = []
        self.elem_cs = []  # CrossSection of every element (its midpoint), for stresses
        for e, j in enumerate(elem_sec):
            sec = robot.sections[int(j)]
            cs = sec.cross_section_at((0.5 * (node_s[e] + node_s[e + 1]) - starts[j]) / sec.length)
            self.elem_cs.append(cs)
            self.elements.append(mbs.AddObject(ObjectANCFCable(
                nodeNumbers=[self.nodes[e], self.nodes[e + 1]], length=float(self.elem_len[e]),
                massPerLength=cs.mass_per_length, bendingStiffness=cs.EI, axialStiffness=cs.EA,
                bendingDamping=options.damping * cs.EI, axialDamping=options.damping * cs.EA,
                useReducedOrderIntegration=2,
            )))
        clamp_coordinates(mbs, self.nodes[0], (0, 1, 2, 3, 4))  # position and the transverse slopes x', y'
        add_point_masses(mbs, self.nodes, lumped_disk_masses(robot, node_s))  # disk inertia (weights below)
        payload = np.zeros(len(node_s))
        payload[-1] = robot.payload.mass
        points = add_point_masses(mbs, self.nodes, payload)
        g = robot.gravity_in_base()
        self.loads = [(ld, g) for ld in add_gravity_loads(mbs, self.elements + points)] if np.any(g != 0) else []
        if np.any(g != 0):
            self.loads += self._disk_weights(robot, g)
        F = np.asarray(load.tip_force)
        if np.any(F != 0):
            mt = mbs.AddMarker(MarkerNodePosition(nodeNumber=self.nodes[-1]))
            self.loads.append((mbs.AddLoad(LoadForceVector(markerNumber=mt, loadVector=[0, 0, 0])), F))
        mbs.Assemble()

    def _disk_weights(self, robot: Robot, g: np.ndarray) -> list:
        """Each disk's weight as a force at its station (position marker on the element that holds it,
        Exudyn's consistent Hermite load: exact nodal values of the linear beam on any mesh); ``(load index,
        full vector)`` per disk of mass > 0.  The disk masses (inertia) are lumped linearly onto the element's
        two nodes (exact when disks sit on nodes).  Checked by ``tests/physics/test_ancf_disks.py``."""
        from exudyn.itemInterface import LoadForceVector, MarkerBodyPosition

        mbs, node_s = self.mbs, self.node_s
        starts = np.concatenate([[0.0], robot.section_ends[:-1]])
        out = []
        for j, sec in enumerate(robot.sections):
            if sec.disk_mass <= 0:
                continue
            for sd in starts[j] + sec.disk_positions():
                e = min(max(int(np.searchsorted(node_s, sd, side="left")) - 1, 0), len(self.elements) - 1)
                mk = mbs.AddMarker(MarkerBodyPosition(bodyNumber=self.elements[e],
                                                      localPosition=[float(sd - node_s[e]), 0.0, 0.0]))
                out.append((mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=[0, 0, 0])), sec.disk_mass * g))
        return out

    def tip_position(self) -> np.ndarray:
        """Tip node position ``(3,)`` [m] (base frame)."""
        return np.asarray(self.mbs.GetNodeOutput(self.nodes[-1], self.exu.OutputVariableType.Position))

    def positions(self, stations: np.ndarray) -> np.ndarray:
        """Centreline points at reference stations by the element's own interpolation, ``(m, 3)`` [m]."""
        out = np.empty((stations.size, 3))
        for i, s in enumerate(stations):
            e = min(max(int(np.searchsorted(self.node_s, s, side="left")) - 1, 0), len(self.elements) - 1)
            out[i] = self.mbs.GetObjectOutputBody(
                self.elements[e], self.exu.OutputVariableType.Position, localPosition=[float(s - self.node_s[e]), 0, 0]
            )
        return out

    def length_change(self) -> float:
        """Integral of ``|r'| - 1`` over the cable (3-point Gauss per element) [m]."""
        gp = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
        gw = np.array([5.0, 8.0, 5.0]) / 9.0
        dl = 0.0
        for el, Le in zip(self.elements, self.elem_len):
            for x, w in zip(gp, gw):
                d1 = self.mbs.GetObjectOutputBody(el, self.exu.OutputVariableType.Director1,
                                                  localPosition=[0.5 * Le * (1 + x), 0, 0])
                dl += 0.5 * Le * w * (np.linalg.norm(d1) - 1.0)
        return float(dl)

    def backbone_stress(self):
        """Largest normal stress at five points per element (:mod:`workbench.models.stress`) and the strength there.

        Cubic Hermite centreline from the node positions and slopes: axial strain ``|r'| - 1``,
        bending ``|r' x r''| / |r'|^2``.  ``(sigma (5 n,), strength (5 n,))`` or ``None``.
        """
        from ..models.stress import combined_stress, section_arrays

        arrs = section_arrays(self.elem_cs)
        if arrs is None:
            return None
        coords = self.exu.OutputVariableType.Coordinates
        q = np.array([self.mbs.GetNodeOutput(n, coords) for n in self.nodes], dtype=float)
        q = q + np.column_stack([np.zeros((len(self.nodes), 2)), self.node_s, np.zeros((len(self.nodes), 2)),
                                 np.ones(len(self.nodes))])
        xi = np.linspace(0.0, 1.0, 5)
        sig, strength = [], []
        for e, Le in enumerate(self.elem_len):
            r0, t0, r1, t1 = q[e, :3], q[e, 3:], q[e + 1, :3], q[e + 1, 3:]
            dr = (np.outer((-6 * xi + 6 * xi**2) / Le, r0) + np.outer(1 - 4 * xi + 3 * xi**2, t0)
                  + np.outer((6 * xi - 6 * xi**2) / Le, r1) + np.outer(-2 * xi + 3 * xi**2, t1))
            ddr = (np.outer((-6 + 12 * xi) / Le**2, r0) + np.outer((-4 + 6 * xi) / Le, t0)
                   + np.outer((6 - 12 * xi) / Le**2, r1) + np.outer((-2 + 6 * xi) / Le, t1))
            n2 = np.sum(dr * dr, axis=1)
            cs = self.elem_cs[e]
            sig.append(combined_stress(cs.EA * (np.sqrt(n2) - 1.0),
                                       cs.EI * np.linalg.norm(np.cross(dr, ddr), axis=1) / n2, arrs[0][e], arrs[1][e]))
            strength.append(np.full(xi.size, arrs[2][e]))
        return np.concatenate(sig), np.concatenate(strength)

    def tip_frame(self) -> np.ndarray:
        """Base <- tip ``(4, 4)``: z = unit tip tangent, x/y parallel-transported along the node tangents."""
        coords = self.exu.OutputVariableType.Coordinates
        tangents = np.array([self.mbs.GetNodeOutput(n, coords)[3:6] + np.array([0, 0, 1.0]) for n in self.nodes])
        tip = np.eye(4)
        tip[:3, :3] = _bishop_tip_frame(tangents)
        tip[:3, 3] = self.tip_position()
        return tip


def _path_point(system: _System, length: float) -> PathPoint:
    """The load-path measure of the current state: tip position / L and tip tangent (base frame)."""
    T = system.tip_frame()
    return PathPoint(tuple(np.concatenate([T[:3, 3] / length, T[:3, 2]])))


def _ramp_static(system: _System, options: SolverOptions, length: float) -> LoadRampInfo:
    """Load ramp lambda: 0 -> 1 (``_RAMP_POLICY``, the path checked on the tip measure of
    :func:`_path_point`); returns the ramp's outcome."""
    from ._exudyn import ode2_saver, set_load_factor, static_settings

    exu, mbs = system.exu, system.mbs
    settings = static_settings(options, 1)
    settings.staticSolver.adaptiveStep = False

    def attempt(lam: float) -> bool | PathPoint:
        set_load_factor(mbs, system.loads, lam)
        try:
            exu.SolveStatic(mbs, settings, updateInitialValues=True)
        except exu.SolverError:
            return False
        return bool(np.all(np.isfinite(mbs.systemData.GetODE2Coordinates()))) and _path_point(system, length)

    save, restore = ode2_saver(mbs, with_ae=False)
    try:
        info = load_ramp(attempt, save, restore, max_attempts=options.max_load_steps, policy=_RAMP_POLICY,
                         start=_path_point(system, length))
    except RampExhausted as stop:
        raise ModelFailure(
            f"ancf3d: static load ramp needs more than max_load_steps={options.max_load_steps} "
            f"increments (reached lambda={stop.lam:.4g})"
        ) from None
    except RampStalled as stop:
        raise ModelFailure(f"ancf3d: static solve failed (increment below {_MIN_INCREMENT} at lambda={stop.lam:.4g})") from None
    return info


def _dynamic(system: _System, load: LoadCase, options: SolverOptions, stations: np.ndarray
             ) -> tuple[np.ndarray, dict, int]:
    """Generalised-alpha from the current state; returns (times, series, n_steps).

    ``series`` includes decimated backbone frames at ``stations`` (:mod:`workbench.models.backbone_frames`)."""
    from ..models.backbone_frames import backbone_series, frame_stride
    from ._exudyn import dynamic_settings

    exu = system.exu
    sim = dynamic_settings(options, load.duration)
    rec_t, rec_p, bb_t, bb_p = [], [], [], []
    n_steps = sim.timeIntegration.numberOfSteps
    h = load.duration / n_steps
    every = max(1, int(round(max(h, load.duration / 1000.0) / h)))
    stride = frame_stride(math.ceil(n_steps / every))
    counter = {"k": 0}

    def pre_step(mbs_, t):
        # Exudyn passes the end time of the coming step; the state is at t - h
        if counter["k"] % every == 0:
            rec_t.append(float(t) - h)
            rec_p.append(np.asarray(mbs_.GetNodeOutput(system.nodes[-1], exu.OutputVariableType.Position)))
            if (len(rec_t) - 1) % stride == 0:
                bb_t.append(rec_t[-1])
                bb_p.append(system.positions(stations))
        counter["k"] += 1
        return True

    system.mbs.SetPreStepUserFunction(pre_step)
    try:
        exu.SolveDynamic(system.mbs, sim, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    except exu.SolverError as err:
        raise ModelFailure(f"ancf3d: dynamic solve failed: {err}") from None
    rec_t.append(float(load.duration))
    rec_p.append(system.tip_position())
    bb_t.append(rec_t[-1])
    bb_p.append(system.positions(stations))
    return np.asarray(rec_t), {"tip_position": np.asarray(rec_p), **backbone_series(bb_t, bb_p)}, n_steps


def run(robot: Robot, load: LoadCase, options: SolverOptions) -> PhysicsResult:
    """Solve the spatial ANCF cable backbone (model ``"ancf3d"``).

    Parameters
    ----------
    robot : Robot
        Robot description (tendons, if any, must be unloaded).
    load : LoadCase
        Tip force, static or dynamic analysis (no tip torque, no tendon commands).
    options : SolverOptions
        ``n_elements``, ``n_stations``, Newton tolerance, ``max_load_steps``,
        ``time_step``, ``damping``, ``spectral_radius``.

    Returns
    -------
    PhysicsResult
        Base-frame results (see the module docstring).

    Raises
    ------
    ModelFailure
        Unsupported load (tendons, torque, payload offset) or a failed static ramp.
    """
    from ._exudyn import quiet_exudyn

    _check(robot, load, options)
    t_wall = _time.perf_counter()
    with quiet_exudyn():
        system = _System(robot, load, options)
        ramp = _ramp_static(system, options, robot.length)
        times, series = None, {}
        extras = {"n_elements": float(len(system.elements)), "load_steps": float(ramp.accepted)}
        stations = np.linspace(0.0, robot.length, options.n_stations)
        if load.analysis == "dynamic":
            times, series, n_steps = _dynamic(system, load, options, stations)
            extras["n_steps"] = float(n_steps)
        positions = system.positions(stations)
        dl = system.length_change()
        tip = system.tip_frame()
        from ..models.stress import stress_extras

        bs = system.backbone_stress()  # final state (also in dynamics)
        extras.update(stress_extras(None if bs is None else bs[0], None if bs is None else bs[1]))
    if not (np.all(np.isfinite(positions)) and np.all(np.isfinite(tip))):
        raise ModelFailure("ancf3d: non-finite state after the solve")
    return PhysicsResult(
        model="ancf3d",
        stations=stations,
        positions=positions,
        tip_frame=tip,
        length_change=dl,
        tendon_tensions=np.zeros(robot.n_tendons),
        tip_twist=0.0,
        solver=SolverInfo(converged=True, iterations=ramp.attempts, wall_time=_time.perf_counter() - t_wall,
                          message="ok", **path_fields(ramp)),
        time=times,
        series=series,
        extras=extras,
    )
