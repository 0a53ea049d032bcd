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

Discretisation: ``options.n_elements`` cable elements distributed over the sections like
:func:`workbench.physics.beam3d.element_layout`, each with the cross-section at its
midpoint (EI, EA, mass per length; GJ and GA do not exist in this element).
``useReducedOrderIntegration=2`` (Lobatto axial integration; removes most coarse-mesh
axial locking under large sag, facts note).  Clamp: node-0 position and the two
transverse slope components are fixed; the axial slope component is left free (fixing it
forbids axial strain at the clamp).  The cable runs along the base z axis directly (no
internal frame).

Static analysis: own load ramp (all loads scale with lambda 0 -> 1, one ``SolveStatic`` per
increment with ``updateInitialValues=True``, halving on failure, at most
``options.max_load_steps`` attempts).  Dynamic analysis: generalised-alpha from the static
equilibrium; loads are constant, so a dynamic run stays at rest (there is nothing in this
model to drive it); damping ``options.damping`` = beta [s] multiplies the bending and
axial stiffness (``bendingDamping = beta EI``, ``axialDamping = beta EA``).

Outputs: positions from the element's own (cubic Hermite) interpolation at the stations;
``tip_frame`` z axis = the unit tip tangent, x/y axes = the base x/y axes parallel-
transported along the node tangents (successive minimal rotations; the cable has no
material frame); ``tip_twist`` = 0; ``length_change`` = integral of ``|r'| - 1`` by
3-point Gauss quadrature per element; ``tendon_tensions`` = zeros.
"""

from __future__ import annotations

import time as _time

import numpy as np

from ..models.inputs import check_model_inputs
from ..models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ..robot import LoadCase, Robot
from .beam3d import element_layout

__all__ = ["run"]

_MIN_INCREMENT = 1e-6


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
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint,
        LoadForceVector,
        LoadMassProportional,
        MarkerBodyMass,
        MarkerNodeCoordinate,
        MarkerNodePosition,
        NodePointGround,
        NodePointSlope1,
        ObjectANCFCable,
        ObjectMassPoint,
    )

    from ._exudyn import dynamic_settings, quiet_exudyn, static_settings

    _check(robot, load, options)
    t_wall = _time.perf_counter()
    node_s, elem_sec = element_layout(robot, options.n_elements)
    elem_len = np.diff(node_s)
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    g = robot.gravity_in_base()
    with quiet_exudyn():
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        nodes = [mbs.AddNode(NodePointSlope1(referenceCoordinates=[0, 0, float(s), 0, 0, 1])) for s in node_s]
        elements = []
        for e, j in enumerate(elem_sec):
            sec = robot.sections[int(j)]
            cs = sec.cross_section_at((0.5 * (node_s[e] + node_s[e + 1]) - starts[j]) / sec.length)
            elements.append(
                mbs.AddObject(
                    ObjectANCFCable(
                        nodeNumbers=[nodes[e], nodes[e + 1]], length=float(elem_len[e]),
                        massPerLength=cs.mass_per_length, bendingStiffness=cs.EI, axialStiffness=cs.EA,
                        bendingDamping=options.damping * cs.EI, axialDamping=options.damping * cs.EA,
                        useReducedOrderIntegration=2,
                    )
                )
            )
        ng = mbs.AddNode(NodePointGround())
        mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ng, coordinate=0))
        for k in (0, 1, 2, 3, 4):  # position and the transverse slope components x', y'
            mk = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=k))
            mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mk]))
        loads = []
        has_g = bool(np.any(g != 0))
        if has_g:
            for el in elements:
                mm = mbs.AddMarker(MarkerBodyMass(bodyNumber=el))
                loads.append((mbs.AddLoad(LoadMassProportional(markerNumber=mm, loadVector=[0, 0, 0])), g))
        lumped = np.zeros(len(nodes))
        for j, sec in enumerate(robot.sections):
            if sec.disk_mass > 0:
                for sd in starts[j] + sec.disk_positions():
                    e = min(max(int(np.searchsorted(node_s, sd, side="left")) - 1, 0), len(elements) - 1)
                    w1 = (sd - node_s[e]) / elem_len[e]
                    lumped[e] += sec.disk_mass * (1.0 - w1)
                    lumped[e + 1] += sec.disk_mass * w1
        lumped[-1] += robot.payload.mass
        for i, m in enumerate(lumped):
            if m > 0 and i > 0:
                mp = mbs.AddObject(ObjectMassPoint(nodeNumber=nodes[i], mass=float(m)))
                if has_g:
                    mm = mbs.AddMarker(MarkerBodyMass(bodyNumber=mp))
                    loads.append((mbs.AddLoad(LoadMassProportional(markerNumber=mm, loadVector=[0, 0, 0])), g))
        F = np.asarray(load.tip_force)
        if np.any(F != 0):
            mt = mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[-1]))
            loads.append((mbs.AddLoad(LoadForceVector(markerNumber=mt, loadVector=[0, 0, 0])), F))
        mbs.Assemble()

        settings = static_settings(options, 1)
        settings.staticSolver.adaptiveStep = False
        lam, dlam, accepted, attempts = 0.0, 1.0, 0, 0
        while lam < 1.0 - 1e-14:
            if attempts >= options.max_load_steps:
                raise ModelFailure(
                    f"ancf3d: static load ramp needs more than max_load_steps={options.max_load_steps} "
                    f"increments (reached lambda={lam:.4g})"
                )
            attempts += 1
            target = min(1.0, lam + dlam)
            q0 = np.asarray(mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.Initial))
            for ld, v in loads:
                mbs.SetLoadParameter(ld, "loadVector", [float(x) for x in target * np.asarray(v)])
            ok = True
            try:
                exu.SolveStatic(mbs, settings, updateInitialValues=True)
                ok = bool(np.all(np.isfinite(mbs.systemData.GetODE2Coordinates())))
            except exu.SolverError:
                ok = False
            if ok:
                lam = target
                accepted += 1
                dlam = min(2.0 * dlam, max(1.0 - lam, 1e-14))
            else:
                mbs.systemData.SetODE2Coordinates(q0, configuration=exu.ConfigurationType.Initial)
                mbs.systemData.SetODE2Coordinates(q0, configuration=exu.ConfigurationType.Current)
                dlam *= 0.5
                if dlam < _MIN_INCREMENT:
                    raise ModelFailure(f"ancf3d: static solve failed (increment below {_MIN_INCREMENT} at lambda={lam:.4g})")
        times = None
        series: dict[str, np.ndarray] = {}
        extras = {"n_elements": float(len(elements)), "load_steps": float(accepted)}
        if load.analysis == "dynamic":
            sim = dynamic_settings(options, load.duration)
            rec_t, rec_p = [], []
            n_steps = sim.timeIntegration.numberOfSteps
            h = load.duration / n_steps
            every = max(1, int(round(max(h, load.duration / 1000.0) / h)))
            counter = {"k": 0}

            def pre_step(mbs_, t):
                # Exudyn passes the end time of the coming step; the state is at t - h
                if counter["k"] % every == 0:
                    rec_t.append(float(t) - h)
                    rec_p.append(np.asarray(mbs_.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)))
                counter["k"] += 1
                return True

            mbs.SetPreStepUserFunction(pre_step)
            try:
                exu.SolveDynamic(mbs, sim, solverType=exu.DynamicSolverType.GeneralizedAlpha)
            except exu.SolverError as err:
                raise ModelFailure(f"ancf3d: dynamic solve failed: {err}") from None
            rec_t.append(float(load.duration))
            rec_p.append(np.asarray(mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)))
            times = np.asarray(rec_t)
            series = {"tip_position": np.asarray(rec_p)}
            extras["n_steps"] = float(n_steps)

        stations = np.linspace(0.0, robot.length, options.n_stations)
        positions = np.empty((stations.size, 3))
        for i, s in enumerate(stations):
            e = min(max(int(np.searchsorted(node_s, s, side="left")) - 1, 0), len(elements) - 1)
            positions[i] = mbs.GetObjectOutputBody(
                elements[e], exu.OutputVariableType.Position, localPosition=[float(s - node_s[e]), 0, 0]
            )
        tangents = np.array(
            [mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates)[3:6] + np.array([0, 0, 1.0]) for n in nodes]
        )
        gp = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
        gw = np.array([5.0, 8.0, 5.0]) / 9.0
        dl = 0.0
        for el, Le in zip(elements, elem_len):
            for x, w in zip(gp, gw):
                d1 = mbs.GetObjectOutputBody(el, exu.OutputVariableType.Director1, localPosition=[0.5 * Le * (1 + x), 0, 0])
                dl += 0.5 * Le * w * (np.linalg.norm(d1) - 1.0)
        tip = np.eye(4)
        tip[:3, :3] = _bishop_tip_frame(tangents)
        tip[:3, 3] = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)
    if not (np.all(np.isfinite(positions)) and np.all(np.isfinite(tip))):
        raise ModelFailure("ancf3d: non-finite state after the solve")
    return PhysicsResult(
        model="ancf3d",
        stations=stations,
        positions=positions,
        tip_frame=tip,
        length_change=float(dl),
        tendon_tensions=np.zeros(robot.n_tendons),
        tip_twist=0.0,
        solver=SolverInfo(converged=True, iterations=attempts, wall_time=_time.perf_counter() - t_wall, message="ok"),
        time=times,
        series=series,
        extras=extras,
    )
