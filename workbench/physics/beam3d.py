"""Spatial tendon-driven backbone: Exudyn's geometrically exact beam with eyelet tendons.

Model ``"beam3d"``: ``run(robot, load, options) -> PhysicsResult``.

Structure
---------
* Backbone: ``options.n_elements`` ``ObjectBeamGeometricallyExact`` elements on
  ``NodeRigidBodyEP`` (Euler-parameter) nodes, distributed over the sections in proportion to their lengths (at least one
  per section; the actual count is ``extras["n_elements"]``).  Each element gets the
  cross-section at its midpoint (``Section.cross_section_at``: tapered sections are
  piecewise constant per element).  ``BeamSection`` stiffness
  ``diag(EA, GA, GA, GJ, EI, EI)`` with ``GA = CrossSection.GA`` or ``100 EA`` if None
  (shear-rigid limit); mass per length ``mu`` and rotary inertia per length
  ``mu EI/EA diag(2, 1, 1)`` (solid homogeneous section).
  Measured (exudyn 1.13.6, 8 elements, pure tip moment bending the rod to pi/2): with
  Lie-group nodes (``NodeRigidBodyRotVecLG``) static Newton converges only linearly and
  stalls at 64 % of the load when the bending plane is skew to the local y/z axes
  (phi = 0.7), with or without numerical differentiation; in-plane (phi = 0, pi/2) it is
  exact.  Euler-parameter nodes converge (7.9 Newton iterations per step) to the exact
  arc in every plane, so they are used here (this contradicts the facts note's "Lie-group
  nodes fine" for skew planes).
* Internal frame: Exudyn's beam axis is its local x.  The model is built in a "model
  frame" with the straight backbone along model +x and identity reference rotations
  (a non-zero reference rotation on the Lie-group nodes made ``SolveStatic`` fail in our
  measurements), model (x, y, z) = base (z, x, y).  Inputs are rotated in and results
  rotated back, so everything the caller sees is in the robot's base frame.
* Clamp: the six coordinates of node 0 are fixed.
* Loads: gravity ``robot.gravity_in_base()`` as mass-proportional loads on every element,
  the disk masses (lumped onto the two nodes of the element holding the disk, linear
  weights) and the payload (a mass point on the tip node; a payload with non-zero offset
  is a force at the offset point, static analysis only); tip force and tip torque on the
  tip node (base-frame directions, not follower loads).
* Tendons (``options.tendon_model == "eyelets"``): every tendon is anchored on the base
  plate at offset ``d(0)`` and routed through eyelets = rigid markers on the beam's
  cross-section frame at every disk of the sections it traverses, at
  ``(d cos sigma, d sin sigma)`` in the cross-section, and terminates on the last disk
  of its section.  Offsets: linear along the tendon's whole routed length,
  ``TendonGroup.offset_at(s / s_end)`` (tronconic taper; the TendonGroup convention).

  - tension mode: one ``ObjectConnectorSpringDamper`` per straight rope segment with zero
    stiffness and constant force ``T``: every segment carries exactly the same tension,
    which is what a frictionless rope does, with nothing to converge (a static solve of a
    single 50 N tendon on 16 elements took 0.09 s here).
  - length mode: one ``ObjectConnectorReevingSystemSprings`` per tendon (a single rope
    through all its eyelets, uniform tension by construction, axial stiffness EA_t over
    the whole current length).  A chain of independent springs would fix the length of
    every segment (a rope glued to every eyelet), which is wrong for a frictionless
    tendon whose total length is controlled, so the reeving system is used although its
    statics are slow: 3-10 s for one 3-tendon static solve (8 elements, 8-16 disks,
    EA_t = 1e8 N, bending to 1 rad), mostly because the step-size-converged Newton needs
    load increments of ~0.1 once a tendon goes slack.  In dynamics the two cost the
    same order (1 s simulated at 5 ms on the one-section Cojocaru robot, 8 elements:
    constant-force chain 5.0 s, reeving 3.1 s, measured on a loaded 2-core machine).
    Its rest length is ``L_path0 / (1 + T_pre/EA_t) + delta_l`` (reference
    path length through the eyelets, shortened so that the straight reference carries
    the pretension ``T_pre``, plus the command).  Exudyn's ``regularizationForce`` (set
    to 1e-3 N) limits the compression of a slack rope to 1e-3 N; reported tensions are
    ``max(0, EA_t stretch / rest length)``.
  - ``numericalDifferentiation.forODE2Connectors = True`` (the analytic Jacobian of
    offset connectors is wrong, facts note).

  ``options.tendon_model == "continuum"`` is **not implemented** for this model: a
  continuum tendon on a spatial beam needs distributed follower loads (Python user
  functions, ~50x slower).  A case that has tendons to load (non-zero tension, or length
  mode at all) raises :class:`ModelFailure` saying that only ``"eyelets"`` is supported;
  tendon-free cases (no actuation, or tension mode with all-zero tensions) run with
  either setting.
* Static analysis: own load ramping.  All loads, tension commands and length commands
  scale with a factor lambda from 0 to 1; each increment is one ``SolveStatic`` (Newton
  on the step size, residualMode 1, no internal adaptive stepping) with
  ``updateInitialValues=True``; a failed increment is retried at half the size.  More
  than ``options.max_load_steps`` attempted increments, or an increment below 1e-6,
  raise :class:`ModelFailure`.
* Dynamic analysis: implicit generalised-alpha (``options.time_step``,
  ``options.spectral_radius``), starting from the static equilibrium under gravity, the
  payload, the tip loads and the commands at t = 0.  Commands follow
  ``TendonActuation.command_at(t, load.ramp_time)`` and are set in a
  ``preStepUserFunction`` (Exudyn calls it with t = the *end* of the coming step, measured;
  the commands are set to their value at that time, constant within the step, and the
  state recorded there is labelled t - h_cur).  Damping: none in the material.  Exudyn
  1.13.6's ``ObjectBeamGeometricallyExact`` ignores ``BeamSection.dampingMatrix`` (measured:
  bit-identical trajectories for a section damping of 0 and of 1e-2 s times the stiffness, test
  ``test_exudyn_ge_beam_ignores_section_damping``), so ``options.damping > 0`` is rejected with
  :class:`ModelFailure` in dynamic analysis instead of being silently dropped; the only
  dissipation is the integrator's (``options.spectral_radius``).  Until the second session the
  wire-delay defaults set ``damping = 1e-3`` and it had no effect.
  The tendons are undamped: Exudyn's reeving damping acts on the rate of the rope's
  geometric length, not on its stretch rate, so with a moving rest length (a motor reeling
  in) it adds a spurious force ``beta EA_t v_wire / L`` (measured ~3 N, 5 % of the
  tension, at 6 mm/s with beta = 1e-3 s); the constant-force segments of tension mode
  carry exactly the commanded force.  Time series are recorded every
  ``output_interval = max(time_step, duration / 1000)``.

Outputs
-------
* ``positions`` at ``options.n_stations`` equally spaced reference stations, evaluated
  with the element's own interpolation (``GetObjectOutputBody(Position)`` at the
  station's local coordinate), i.e. not a polyline through the nodes.
* ``tip_frame``: base <- tip, columns (x, y, z) = the tip cross-section axes, z along the
  backbone; identity for the undeformed robot.
* ``length_change`` = sum over elements of ``L_e (|Gamma_e| - 1)`` with ``Gamma`` the
  element's strain vector (``e_x + StrainLocal[:3]``): the integrated centreline length
  (shear included) minus the reference length.
* ``tip_twist`` = sum over elements of ``L_e kappa_1`` with ``kappa_1`` the element's
  torsional curvature (``CurvatureLocal[0]``).  This is the angle between the tip
  cross-section and the base cross-section parallel-transported (torsion-free, Bishop
  frame) along the deformed director ``d1``: a Bishop frame has no angular velocity
  about the tangent, the material frame has ``kappa_1``, so their relative rotation is
  the integral of ``kappa_1`` (exact up to the beam's shear, which tilts ``d1`` against
  the centreline tangent by ``gamma = O(F/GA)``).
* ``tendon_tensions`` (global tendon order), ``solver`` info and, for dynamics, ``time``
  and ``series`` ``tip_position`` (k, 3), ``tendon_tensions`` (k, n), ``length_change``
  (k,), ``tip_twist`` (k,), ``tendon_stretch`` (k, n) (current path length minus rest
  length, length mode; zeros in tension mode).
* ``extras``: ``n_elements``, ``load_steps`` (static increments), ``n_steps`` (dynamic).
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field

import numpy as np

from ..models.inputs import check_model_inputs
from ..models.result import ModelFailure, PhysicsResult, SolverInfo, SolverOptions
from ..robot import LoadCase, Robot

__all__ = ["run", "element_layout", "tendon_routes", "R_BASE_MODEL"]

#: base <- model rotation: model x (beam axis) = base z, model y = base x, model z = base y.
R_BASE_MODEL = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])

_SHEAR_FACTOR_IF_NONE = 100.0
_REGULARIZATION_FORCE = 1e-3
_MIN_INCREMENT = 1e-6
_RAMP_GROWTH = 2.0
_STATIC_MAX_ITERATIONS = 50


@dataclass
class _Model:
    """Handles of one built Exudyn system (internal, mutable while solving)."""

    SC: object
    mbs: object
    nodes: list
    elements: list
    node_s: np.ndarray  # (n_nodes,) reference arc length of nodes
    elem_len: np.ndarray  # (n_el,)
    gravity_loads: list = field(default_factory=list)  # (load index, full vector)
    vector_loads: list = field(default_factory=list)  # (load index, full vector)
    tendon_mode: str = "none"  # "none" | "tension" | "length"
    tendon_objects: list = field(default_factory=list)  # per tendon: list of connector indices
    tendon_path0: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tendon_rest0: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tendon_values: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tendon_markers: list = field(default_factory=list)  # per tendon: list of marker indices


def _check(robot: Robot, load: LoadCase, options: SolverOptions) -> None:
    check_model_inputs(robot, load, options)
    if load.analysis == "dynamic" and robot.payload.mass > 0 and any(robot.payload.offset):
        raise ModelFailure("beam3d: a payload with non-zero offset is supported in static analysis only")
    if load.analysis == "dynamic" and options.damping > 0:
        raise ModelFailure(
            f"beam3d: options.damping = {options.damping:g} s is not supported: Exudyn's geometrically exact beam "
            f"ignores the section damping matrix, so it would have no effect; use damping = 0 (dissipation only "
            f"through options.spectral_radius)"
        )


def _tendons_active(robot: Robot, load: LoadCase) -> str:
    """'none', 'tension' or 'length': which tendon objects the case needs."""
    act = load.actuation
    if act is None or robot.n_tendons == 0:
        return "none"
    if act.mode == "tension" and not any(v > 0 for v in act.values):
        return "none"
    return act.mode


def element_layout(robot: Robot, n_elements: int) -> tuple[np.ndarray, np.ndarray]:
    """Node arc lengths and the section index of every element.

    Elements are distributed over sections in proportion to their lengths (at least one
    per section), uniform within a section.

    Returns
    -------
    node_s : ndarray, shape (n_el + 1,)
        Reference arc length of every node [m].
    elem_section : ndarray of int, shape (n_el,)
        Section index of every element.
    """
    Ls = robot.section_lengths
    counts = np.maximum(1, np.round(n_elements * Ls / Ls.sum()).astype(int))
    starts = np.concatenate([[0.0], np.cumsum(Ls)[:-1]])
    node_s = [0.0]
    sec = []
    for j, (s0, Lj, nj) in enumerate(zip(starts, Ls, counts)):
        node_s.extend(s0 + Lj * np.arange(1, nj + 1) / nj)
        sec.extend([j] * nj)
    node_s = np.asarray(node_s)
    node_s[-1] = robot.length
    return node_s, np.asarray(sec, dtype=int)


def _beam_section(cs, damping: float):
    import exudyn as exu

    GA = cs.GA if cs.GA is not None else _SHEAR_FACTOR_IF_NONE * cs.EA
    K = np.diag([cs.EA, GA, GA, cs.GJ, cs.EI, cs.EI])
    bs = exu.BeamSection()
    bs.stiffnessMatrix = K
    bs.dampingMatrix = damping * K  # ignored by Exudyn 1.13.6 (see the module docstring); 0 in dynamics
    bs.massPerLength = cs.mass_per_length
    bs.inertia = cs.mass_per_length * (cs.EI / cs.EA) * np.diag([2.0, 1.0, 1.0])
    return bs


def _locate(node_s: np.ndarray, s: float, prefer_left: bool = True) -> tuple[int, float]:
    """Element index and local coordinate (-L_e/2..L_e/2) of arc length ``s``."""
    n_el = node_s.size - 1
    if prefer_left:
        e = int(np.searchsorted(node_s, s, side="left")) - 1
    else:
        e = int(np.searchsorted(node_s, s, side="right")) - 1
    e = min(max(e, 0), n_el - 1)
    mid = 0.5 * (node_s[e] + node_s[e + 1])
    return e, float(s - mid)


def tendon_routes(robot: Robot) -> list[list[tuple[float, float]]]:
    """Eyelet route of every tendon: ``[(s, d), ...]`` from the base anchor to the termination.

    The first entry is the anchor on the base plate (s = 0), the last the terminating
    disk.  ``d`` is the tendon offset [m] at that station (see the module docstring).
    """
    routes = []
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    ends = robot.section_ends
    for j, sigma, group in robot.tendon_table():
        # offset linear along the whole routed length [0, ends[j]] (TendonGroup convention)
        route = [(0.0, group.offset_at(0.0))]
        for k in range(j + 1):
            sec = robot.sections[k]
            for sd in sec.disk_positions():
                s = float(starts[k] + sd)
                route.append((s, float(group.offset_at(s / ends[j]))))
        routes.append(route)
    return routes


def _build(robot: Robot, load: LoadCase, options: SolverOptions, tendon_mode: str, node_type: str = "EP") -> _Model:
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint,
        LoadForceVector,
        LoadMassProportional,
        LoadTorqueVector,
        MarkerBodyMass,
        MarkerBodyRigid,
        MarkerNodeCoordinate,
        MarkerNodeRigid,
        NodePointGround,
        NodeRigidBodyEP,
        NodeRigidBodyRotVecLG,
        ObjectBeamGeometricallyExact,
        ObjectConnectorReevingSystemSprings,
        ObjectConnectorSpringDamper,
        ObjectGround,
        ObjectMassPoint,
    )

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    node_s, elem_sec = element_layout(robot, options.n_elements)
    n_el = elem_sec.size
    elem_len = np.diff(node_s)
    if node_type == "EP":
        nodes = [mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=[float(s), 0, 0, 1, 0, 0, 0])) for s in node_s]
        clamped = (0, 1, 2, 4, 5, 6)  # position and Euler parameters e1..e3 (e0 follows from |e| = 1)
    else:
        nodes = [mbs.AddNode(NodeRigidBodyRotVecLG(referenceCoordinates=[float(s), 0, 0, 0, 0, 0])) for s in node_s]
        clamped = (0, 1, 2, 3, 4, 5)
    starts = np.concatenate([[0.0], robot.section_ends[:-1]])
    elements = []
    for e in range(n_el):
        j = int(elem_sec[e])
        sec = robot.sections[j]
        frac = (0.5 * (node_s[e] + node_s[e + 1]) - starts[j]) / sec.length
        bs = _beam_section(sec.cross_section_at(frac), options.damping)
        elements.append(
            mbs.AddObject(
                ObjectBeamGeometricallyExact(
                    nodeNumbers=[nodes[e], nodes[e + 1]], length=float(elem_len[e]), sectionData=bs,
                )
            )
        )
    model = _Model(SC=SC, mbs=mbs, nodes=nodes, elements=elements, node_s=node_s, elem_len=elem_len)

    # clamp
    ng = mbs.AddNode(NodePointGround())
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ng, coordinate=0))
    for k in clamped:
        mk = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=k))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mk]))

    g_m = R_BASE_MODEL.T @ robot.gravity_in_base()
    has_g = bool(np.any(g_m != 0.0))
    # gravity on the beam
    if has_g:
        for e in elements:
            mm = mbs.AddMarker(MarkerBodyMass(bodyNumber=e))
            model.gravity_loads.append((mbs.AddLoad(LoadMassProportional(markerNumber=mm, loadVector=[0, 0, 0])), g_m))
    # disk masses lumped on nodes
    lumped = np.zeros(len(nodes))
    for j, sec in enumerate(robot.sections):
        if sec.disk_mass > 0:
            for sd in starts[j] + sec.disk_positions():
                e, xl = _locate(node_s, sd)
                w1 = 0.5 + xl / elem_len[e]
                lumped[e] += sec.disk_mass * (1.0 - w1)
                lumped[e + 1] += sec.disk_mass * w1
    pay = robot.payload
    if pay.mass > 0 and not any(pay.offset):
        lumped[-1] += pay.mass
    for i, m in enumerate(lumped):
        if m > 0 and i > 0:
            mp = mbs.AddObject(ObjectMassPoint(nodeNumber=nodes[i], mass=float(m)))
            if has_g:
                mm = mbs.AddMarker(MarkerBodyMass(bodyNumber=mp))
                model.gravity_loads.append(
                    (mbs.AddLoad(LoadMassProportional(markerNumber=mm, loadVector=[0, 0, 0])), g_m)
                )
    if pay.mass > 0 and any(pay.offset) and has_g:
        off = np.asarray(pay.offset)  # tip frame (x, y, z) = local (y, z, x)
        loc = [0.5 * elem_len[-1] + off[2], off[0], off[1]]
        mk = mbs.AddMarker(MarkerBodyRigid(bodyNumber=elements[-1], localPosition=loc))
        model.vector_loads.append((mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=[0, 0, 0])), pay.mass * g_m))
    mtip = mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[-1]))
    F = R_BASE_MODEL.T @ np.asarray(load.tip_force)
    M = R_BASE_MODEL.T @ np.asarray(load.tip_torque)
    if np.any(F != 0):
        model.vector_loads.append((mbs.AddLoad(LoadForceVector(markerNumber=mtip, loadVector=[0, 0, 0])), F))
    if np.any(M != 0):
        model.vector_loads.append((mbs.AddLoad(LoadTorqueVector(markerNumber=mtip, loadVector=[0, 0, 0])), M))

    # tendons
    model.tendon_mode = tendon_mode
    if tendon_mode != "none":
        act = load.actuation
        ground = mbs.AddObject(ObjectGround())
        routes = tendon_routes(robot)
        table = robot.tendon_table()
        path0, rest0 = [], []
        for (j, sigma, group), route in zip(table, routes):
            c, s_ = math.cos(sigma), math.sin(sigma)
            markers = []
            pts = []
            for k, (s, d) in enumerate(route):
                if k == 0:
                    markers.append(mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0.0, d * c, d * s_])))
                else:
                    e, xl = _locate(node_s, s)
                    markers.append(
                        mbs.AddMarker(MarkerBodyRigid(bodyNumber=elements[e], localPosition=[xl, d * c, d * s_]))
                    )
                pts.append([s, d * c, d * s_])
            pts = np.asarray(pts)
            seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
            L0 = float(seg.sum())
            path0.append(L0)
            model.tendon_markers.append(markers)
            if tendon_mode == "tension":
                objs = [
                    mbs.AddObject(
                        ObjectConnectorSpringDamper(
                            markerNumbers=[markers[k], markers[k + 1]], referenceLength=float(seg[k]),
                            stiffness=0.0, damping=0.0, force=0.0
                        )
                    )
                    for k in range(len(markers) - 1)
                ]
                rest0.append(L0)
            else:
                EAt = group.axial_stiffness
                r0 = L0 / (1.0 + act.pretension / EAt)
                rest0.append(r0)
                objs = [
                    mbs.AddObject(
                        ObjectConnectorReevingSystemSprings(
                            markerNumbers=markers, stiffnessPerLength=EAt,
                            dampingPerLength=0.0, referenceLength=L0,
                            regularizationForce=_REGULARIZATION_FORCE,
                            sheavesAxes=exu.Vector3DList([[0.0, 0.0, 1.0]] * len(markers)),
                            sheavesRadii=[0.0] * len(markers)
                        )
                    )
                ]
            model.tendon_objects.append(objs)
        model.tendon_path0 = np.asarray(path0)
        model.tendon_rest0 = np.asarray(rest0)
        model.tendon_values = np.asarray(act.values)
    mbs.Assemble()
    return model


def _set_tendons(model: _Model, values: np.ndarray, lam_pre: float) -> None:
    """Apply tendon commands ``values`` (tension [N] or length change [m]).

    ``lam_pre`` scales the pretension shortening (static ramp); 1 in dynamics.
    """
    mbs = model.mbs
    if model.tendon_mode == "tension":
        for objs, T in zip(model.tendon_objects, values):
            for o in objs:
                mbs.SetObjectParameter(o, "force", float(T))
    elif model.tendon_mode == "length":
        for objs, L0, r0, dl in zip(model.tendon_objects, model.tendon_path0, model.tendon_rest0, values):
            rest = L0 + lam_pre * (r0 - L0) + float(dl)
            if rest <= 0:
                raise ModelFailure(f"beam3d: tendon rest length {rest:.4g} m <= 0 (command too large)")
            mbs.SetObjectParameter(objs[0], "referenceLength", float(rest))


def _set_loads(model: _Model, lam: float) -> None:
    mbs = model.mbs
    for ld, v in model.gravity_loads + model.vector_loads:
        mbs.SetLoadParameter(ld, "loadVector", [float(x) for x in lam * np.asarray(v)])


def _tendon_state(model: _Model) -> tuple[np.ndarray, np.ndarray]:
    """Current tensions [N] and stretches (path length - rest length) [m] of every tendon."""
    import exudyn as exu

    mbs = model.mbs
    n = len(model.tendon_objects)
    T = np.zeros(n)
    stretch = np.zeros(n)
    if model.tendon_mode == "tension":
        for i, objs in enumerate(model.tendon_objects):
            T[i] = float(mbs.GetObjectParameter(objs[0], "force"))
    elif model.tendon_mode == "length":
        for i, (objs, markers) in enumerate(zip(model.tendon_objects, model.tendon_markers)):
            pts = np.array([mbs.GetMarkerOutput(m, exu.OutputVariableType.Position) for m in markers])
            length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
            rest = float(mbs.GetObjectParameter(objs[0], "referenceLength"))
            EA = float(mbs.GetObjectParameter(objs[0], "stiffnessPerLength"))
            stretch[i] = length - rest
            T[i] = max(0.0, EA * stretch[i] / rest)
    return T, stretch


def _shape_scalars(model: _Model) -> tuple[float, float]:
    """(length change [m], tip twist [rad]) from element strains and torsional curvature."""
    import exudyn as exu

    mbs = model.mbs
    dl = 0.0
    tw = 0.0
    for e, Le in zip(model.elements, model.elem_len):
        g = np.asarray(mbs.GetObjectOutputBody(e, exu.OutputVariableType.StrainLocal, localPosition=[0, 0, 0]))
        k = np.asarray(mbs.GetObjectOutputBody(e, exu.OutputVariableType.CurvatureLocal, localPosition=[0, 0, 0]))
        Gam = np.array([1.0 + g[0], g[1], g[2]])
        dl += Le * (np.linalg.norm(Gam) - 1.0)
        tw += Le * k[0]
    return float(dl), float(tw)


def _tip_frame(model: _Model) -> np.ndarray:
    import exudyn as exu

    mbs = model.mbs
    p = np.asarray(mbs.GetNodeOutput(model.nodes[-1], exu.OutputVariableType.Position))
    A = np.asarray(mbs.GetNodeOutput(model.nodes[-1], exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
    T = np.eye(4)
    T[:3, :3] = R_BASE_MODEL @ A @ R_BASE_MODEL.T
    T[:3, 3] = R_BASE_MODEL @ p
    return T


def _positions(model: _Model, stations: np.ndarray) -> np.ndarray:
    import exudyn as exu

    mbs = model.mbs
    out = np.empty((stations.size, 3))
    for i, s in enumerate(stations):
        e, xl = _locate(model.node_s, float(s))
        p = mbs.GetObjectOutputBody(model.elements[e], exu.OutputVariableType.Position, localPosition=[xl, 0, 0])
        out[i] = R_BASE_MODEL @ np.asarray(p)
    return out


def _static_settings(options: SolverOptions):
    from ._exudyn import static_settings

    s = static_settings(options, 1)
    st = s.staticSolver
    st.adaptiveStep = False
    st.newton.numericalDifferentiation.forODE2Connectors = True
    st.newton.maxIterations = _STATIC_MAX_ITERATIONS
    return s


def _ramp_static(model: _Model, options: SolverOptions, values_at, lam_pre_at, loads_at) -> tuple[int, int]:
    """Own load ramp lambda: 0 -> 1 with halving on failure.

    ``values_at(lam)`` tendon commands, ``lam_pre_at(lam)`` pretension factor,
    ``loads_at(lam)`` load factor.  Returns (accepted increments, attempts).
    """
    import exudyn as exu

    mbs = model.mbs
    settings = _static_settings(options)
    lam = 0.0
    dlam = 1.0
    accepted = attempts = 0
    while lam < 1.0 - 1e-14:
        if attempts >= options.max_load_steps:
            raise ModelFailure(
                f"beam3d: static load ramp needs more than max_load_steps={options.max_load_steps} "
                f"increments (reached lambda={lam:.4g})"
            )
        target = min(1.0, lam + dlam)
        attempts += 1
        q0 = np.asarray(mbs.systemData.GetODE2Coordinates(configuration=exu.ConfigurationType.Initial))
        a0 = np.asarray(mbs.systemData.GetAECoordinates(configuration=exu.ConfigurationType.Initial))
        _set_tendons(model, values_at(target), lam_pre_at(target))
        _set_loads(model, loads_at(target))
        ok = True
        try:
            exu.SolveStatic(mbs, settings, updateInitialValues=True)
        except exu.SolverError:
            ok = False
        if ok:
            q = np.asarray(mbs.systemData.GetODE2Coordinates())
            ok = bool(np.all(np.isfinite(q)))
        if ok:
            lam = target
            accepted += 1
            dlam = min(1.0 - lam, _RAMP_GROWTH * dlam) if lam < 1.0 else dlam
        else:
            mbs.systemData.SetODE2Coordinates(q0, configuration=exu.ConfigurationType.Initial)
            mbs.systemData.SetODE2Coordinates(q0, configuration=exu.ConfigurationType.Current)
            mbs.systemData.SetAECoordinates(a0, configuration=exu.ConfigurationType.Initial)
            mbs.systemData.SetAECoordinates(a0, configuration=exu.ConfigurationType.Current)
            dlam *= 0.5
            if dlam < _MIN_INCREMENT:
                raise ModelFailure(
                    f"beam3d: static solve failed to converge (load increment below {_MIN_INCREMENT} at lambda={lam:.4g})"
                )
    return accepted, attempts


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
        (beta [s], stiffness-proportional), ``spectral_radius``.

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
    import exudyn as exu

    from ._exudyn import dynamic_settings, quiet_exudyn

    _check(robot, load, options)
    mode = _tendons_active(robot, load)
    if mode != "none" and options.tendon_model != "eyelets":
        raise ModelFailure(
            "beam3d supports only tendon_model='eyelets' for loaded tendons "
            f"(got tendon_model={options.tendon_model!r}); continuum tendon loads are not implemented"
        )
    t_wall = _time.perf_counter()
    stations = np.linspace(0.0, robot.length, options.n_stations)
    with quiet_exudyn():
        model = _build(robot, load, options, mode)
        act = load.actuation
        n_t = robot.n_tendons
        final = np.asarray(act.values) if act is not None else np.zeros(n_t)
        if load.analysis == "static":
            acc, att = _ramp_static(
                model, options, lambda lam: lam * final, lambda lam: lam, lambda lam: lam
            )
            extras = {"n_elements": float(len(model.elements)), "load_steps": float(acc)}
            times = None
            series = {}
            iters = att
        else:
            cmd0 = act.command_at(0.0, load.ramp_time) if act is not None else np.zeros(n_t)
            acc, att = _ramp_static(
                model, options, lambda lam: lam * cmd0, lambda lam: lam, lambda lam: lam
            )
            sim = dynamic_settings(options, load.duration)
            ti = sim.timeIntegration
            ti.newton.numericalDifferentiation.forODE2Connectors = True
            ti.newton.useModifiedNewton = True
            n_steps = ti.numberOfSteps
            h = load.duration / n_steps
            out_every = max(1, int(round(max(h, load.duration / 1000.0) / h)))
            rec = {"t": [], "tip": [], "T": [], "dl": [], "tw": [], "st": []}

            def record(t: float) -> None:
                T, st = _tendon_state(model)
                if T.size != n_t:  # no tendon objects built (unloaded tendons)
                    T, st = np.zeros(n_t), np.zeros(n_t)
                dl, tw = _shape_scalars(model)
                p = model.mbs.GetNodeOutput(model.nodes[-1], exu.OutputVariableType.Position)
                # a step retried with a smaller step size calls pre_step again at the same t
                while rec["t"] and rec["t"][-1] >= t - 1e-12:
                    for key in rec:
                        rec[key].pop()
                rec["t"].append(t)
                rec["tip"].append(R_BASE_MODEL @ np.asarray(p))
                rec["T"].append(T)
                rec["st"].append(st)
                rec["dl"].append(dl)
                rec["tw"].append(tw)

            drive = act is not None and mode != "none"
            out_dt = out_every * h

            def pre_step(mbs, t):
                # Exudyn calls this with t = the END time of the step about to be solved;
                # the state is the converged state at t - h_cur (last accepted step).
                solver = mbs.sys.get("dynamicSolver")
                h_cur = solver.it.currentStepSize if solver is not None else h
                t_state = t - h_cur
                if drive:  # record the state with the commands it was solved for
                    _set_tendons(model, act.command_at(t_state, load.ramp_time), 1.0)
                k = round(t_state / out_dt)
                if abs(t_state - k * out_dt) < 0.5 * h:
                    record(float(t_state))
                if drive:  # commands at the end of this step (exact also for reduced steps)
                    _set_tendons(model, act.command_at(t, load.ramp_time), 1.0)
                return True

            model.mbs.SetPreStepUserFunction(pre_step)
            try:
                exu.SolveDynamic(model.mbs, sim, solverType=exu.DynamicSolverType.GeneralizedAlpha)
            except exu.SolverError as err:
                raise ModelFailure(f"beam3d: dynamic solve failed: {err}") from None
            if drive:
                _set_tendons(model, act.command_at(load.duration, load.ramp_time), 1.0)
            record(float(load.duration))
            times = np.asarray(rec["t"])
            series = {
                "tip_position": np.asarray(rec["tip"]),
                "tendon_tensions": np.asarray(rec["T"]).reshape(len(times), n_t),
                "tendon_stretch": np.asarray(rec["st"]).reshape(len(times), n_t),
                "length_change": np.asarray(rec["dl"]),
                "tip_twist": np.asarray(rec["tw"]),
            }
            extras = {"n_elements": float(len(model.elements)), "load_steps": float(acc), "n_steps": float(n_steps)}
            iters = att
        positions = _positions(model, stations)
        tip = _tip_frame(model)
        T, _ = _tendon_state(model)
        dl, tw = _shape_scalars(model)
    if not (np.all(np.isfinite(positions)) and np.all(np.isfinite(tip))):
        raise ModelFailure("beam3d: non-finite state after the solve")
    if n_t and T.size != n_t:
        T = np.zeros(n_t)
    wall = _time.perf_counter() - t_wall
    return PhysicsResult(
        model="beam3d",
        stations=stations,
        positions=positions,
        tip_frame=tip,
        length_change=dl,
        tendon_tensions=T if n_t else np.zeros(0),
        tip_twist=tw,
        solver=SolverInfo(converged=True, iterations=int(iters), wall_time=wall, message="ok"),
        time=times,
        series=series,
        extras=extras,
    )
