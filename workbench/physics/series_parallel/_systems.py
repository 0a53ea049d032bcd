"""Exudyn systems for the flexible parallel module (private to ``workbench.physics.series_parallel``).

Frames: the public API uses the Cosserat convention of Huang et al. (section axis 3 = rod tangent).
Exudyn's ``ObjectBeamGeometricallyExact`` runs along the node's local x axis, so an Exudyn node
frame is ``R_exu = R_cos @ C`` with the cyclic permutation ``C`` (``C e_x = e_z``).

Every system is built inside a function from plain arrays; nothing is kept between calls.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadForceVector,
    LoadTorqueVector,
    MarkerBodyRigid,
    MarkerNodeRigid,
    NodeRigidBodyEP,
    ObjectBeamGeometricallyExact,
    ObjectGround,
    ObjectJointGeneric,
    ObjectRigidBody,
)
from scipy.spatial.transform import Rotation

from .._exudyn import quiet_exudyn, settings

#: Cosserat section frame -> Exudyn beam node frame (beam axis = local x).
C_EXU = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])


@dataclass(frozen=True)
class RodParams:
    """Plain rod data: stiffnesses and weight per length."""

    EA: float
    GA: float
    EI: float
    GJ: float
    weight_per_length: float  # rho A [kg/m]


@dataclass(frozen=True)
class LegShape:
    """Initial guess of one leg: node positions and Cosserat frames, shape (N+1, 3), (N+1, 3, 3)."""

    positions: np.ndarray
    rotations: np.ndarray


@dataclass(frozen=True)
class StaticOutcome:
    converged: bool
    iterations: int
    residual: float
    reason: str
    wall_time: float


def _settings(tol: float, max_iter: int, n_load_steps: int):
    """Static settings of the leg and module solves (``tests/physics/test_exudyn_helpers.py`` pins the fields).

    Exudyn's own load stepping is adaptive only for more than one step: retrying a
    constraint-driven solve at a smaller "load" is pointless.
    """
    return settings(tol, max_iter, n_load_steps, absolute_tolerance=1e-14, adaptive=n_load_steps > 1,
                    minimum_step_size=1e-3, sensors_active=False)


def _section(rod: RodParams) -> "exu.BeamSection":
    sec = exu.BeamSection()
    sec.stiffnessMatrix = np.diag([rod.EA, rod.GA, rod.GA, rod.GJ, rod.EI, rod.EI])
    return sec


def _add_leg(mbs, rod: RodParams, base_pos, base_rot, length, shape: LegShape, gravity):
    """Leg as N GE beam elements; straight stress-free reference along the hole axis.

    Returns the node indices (first = hole, last = tip) and the beam object indices.
    """
    n_nodes = shape.positions.shape[0]
    s = np.linspace(0.0, length, n_nodes)
    t0 = base_rot[:, 2]
    q_ref = _ep(base_rot @ C_EXU)
    nodes = []
    for j in range(n_nodes):
        ref_p = base_pos + s[j] * t0
        q = _ep(shape.rotations[j] @ C_EXU)
        if np.dot(q, q_ref) < 0:
            q = -q
        nodes.append(
            mbs.AddNode(
                NodeRigidBodyEP(
                    referenceCoordinates=list(ref_p) + list(q_ref),
                    initialCoordinates=list(shape.positions[j] - ref_p) + list(q - q_ref),
                )
            )
        )
    sec = _section(rod)
    h = length / (n_nodes - 1)
    beams = []
    for j in range(n_nodes - 1):
        beams.append(mbs.AddObject(ObjectBeamGeometricallyExact(nodeNumbers=[nodes[j], nodes[j + 1]], length=h, sectionData=sec)))
    if gravity is not None:
        for j in range(n_nodes):
            w = h * (0.5 if j in (0, n_nodes - 1) else 1.0)
            mk = mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[j]))
            mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=list(w * rod.weight_per_length * np.asarray(gravity))))
    return nodes, beams


def _ep(R) -> np.ndarray:
    """Euler parameters (w, x, y, z) of a rotation matrix."""
    q = Rotation.from_matrix(R).as_quat()
    return np.array([q[3], q[0], q[1], q[2]])


def _hole_joint(mbs, body, local_pos, local_rot, node):
    """Hole (Eq 21): position and tangent fixed, rotation about the tangent free.

    Generic joint whose frame is the beam node frame (x = beam axis = hole axis); all axes
    constrained except the rotation about x.
    """
    m0 = mbs.AddMarker(
        MarkerBodyRigid(bodyNumber=body, localHT=exu.HT(rotation=np.asarray(local_rot) @ C_EXU, translation=list(local_pos)))
    )
    m1 = mbs.AddMarker(MarkerNodeRigid(nodeNumber=node))
    return mbs.AddObject(ObjectJointGeneric(markerNumbers=[m0, m1], constrainedAxes=[1, 1, 1, 0, 1, 1]))


def _clamp_joint(mbs, body, local_pos, local_rot, node):
    """Clamp: node frame = body frame @ local_rot @ C (Cosserat -> Exudyn), all six axes constrained."""
    m0 = mbs.AddMarker(
        MarkerBodyRigid(bodyNumber=body, localHT=exu.HT(rotation=np.asarray(local_rot) @ C_EXU, translation=list(local_pos)))
    )
    m1 = mbs.AddMarker(MarkerNodeRigid(nodeNumber=node))
    return mbs.AddObject(ObjectJointGeneric(markerNumbers=[m0, m1], constrainedAxes=[1, 1, 1, 1, 1, 1]))


#: ``TorqueLocal`` of a fully constrained generic joint, in the marker-0 joint frame, carries the
#: reaction moment on marker 1 with the joint-frame y and z components negated (measured: the
#: cantilever tip moment and the platform balance of the module are reproduced to round-off
#: only with this sign pattern).
_TORQUE_SIGNS = np.array([1.0, -1.0, -1.0])


def _tip_wrench_on_leg(mbs, joint, frame0, last_beam=None, beam_length=None, tip_node=None):
    """Force and moment the tip clamp exerts on the leg, ``n(L)`` and ``m(L)``, global frame.

    Both come from the clamp joint's reactions (``ForceLocal``, ``TorqueLocal``) in the joint
    frame ``frame0`` of marker 0, so they are exact for the discrete model (no extrapolation of
    element section forces).
    """
    F = frame0 @ np.asarray(mbs.GetObjectOutput(joint, exu.OutputVariableType.ForceLocal))
    M = frame0 @ (_TORQUE_SIGNS * np.asarray(mbs.GetObjectOutput(joint, exu.OutputVariableType.TorqueLocal)))
    return F, M


def _solve(mbs, tol, max_iter, n_load_steps):
    settings = _settings(tol, max_iter, n_load_steps)
    t0 = time.perf_counter()
    with quiet_exudyn():
        mbs.Assemble()
        try:
            ok = exu.SolveStatic(mbs, simulationSettings=settings, updateInitialValues=False, storeSolver=True)
            reason = "" if ok else "static solver did not converge"
        except exu.SolverError as err:  # non-convergence or singular system
            ok, reason = False, f"exudyn.SolverError: {str(err).strip().splitlines()[-1] if str(err).strip() else 'static solve failed'}"
    solver = mbs.sys.get("staticSolver")
    its = 0
    res = float("nan")
    if solver is not None:
        # the pinned Exudyn has both attributes; another version without them records 0 / NaN (named
        # AttributeError only: any other error is a bug and propagates)
        try:
            its = int(solver.it.newtonStepsCount)
        except AttributeError:  # pragma: no cover
            its = 0
        try:
            res = float(solver.newton.maxResidual) if hasattr(solver, "newton") else float("nan")
        except AttributeError:  # pragma: no cover
            res = float("nan")
    return StaticOutcome(bool(ok), its, res, reason, time.perf_counter() - t0)


def node_state(mbs, node):
    p = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Position))
    A = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
    return p, A


def solve_leg_tip_pose(rod, base_pos, base_rot, length, tip_pos, tip_rot, shape, gravity, tol, max_iter, free_twist=True):
    """One leg with prescribed tip pose (Eq 21, 25, 26).

    Returns (outcome, tip force on leg, tip moment on leg, node positions, node Cosserat frames).
    The tip force on the leg equals ``n(L)``, the tip moment ``m(L)`` (global frame).
    """
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    nodes, beams = _add_leg(mbs, rod, base_pos, base_rot, length, shape, gravity)
    if free_twist:
        _hole_joint(mbs, ground, base_pos, base_rot, nodes[0])
    else:
        _clamp_joint(mbs, ground, base_pos, base_rot, nodes[0])
    jt = _clamp_joint(mbs, ground, tip_pos, tip_rot, nodes[-1])
    out = _solve(mbs, tol, max_iter, 1)
    if not out.converged:
        return out, None, None, None, None
    F, M = _tip_wrench_on_leg(mbs, jt, np.asarray(tip_rot) @ C_EXU, beams[-1], length / (len(nodes) - 1), nodes[-1])
    P = np.empty((len(nodes), 3))
    R = np.empty((len(nodes), 3, 3))
    for j, n in enumerate(nodes):
        P[j], A = node_state(mbs, n)
        R[j] = A @ C_EXU.T
    return out, F, M, P, R


def solve_leg_tip_wrench(rod, base_pos, base_rot, length, tip_force, tip_moment, shape, gravity, tol, max_iter, n_load_steps):
    """Cantilever leg (clamped base) with dead tip force and moment; returns (outcome, P, R)."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    nodes, beams = _add_leg(mbs, rod, base_pos, base_rot, length, shape, gravity)
    _clamp_joint(mbs, ground, base_pos, base_rot, nodes[0])
    mk = mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[-1]))
    mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=list(map(float, tip_force))))
    mbs.AddLoad(LoadTorqueVector(markerNumber=mk, loadVector=list(map(float, tip_moment))))
    out = _solve(mbs, tol, max_iter, n_load_steps)
    if not out.converged:
        return out, None, None
    P = np.empty((len(nodes), 3))
    R = np.empty((len(nodes), 3, 3))
    for j, n in enumerate(nodes):
        P[j], A = node_state(mbs, n)
        R[j] = A @ C_EXU.T
    return out, P, R


@dataclass(frozen=True)
class ModuleSpec:
    """Plain data for one module inside a stack system (all in the module's base frame)."""

    hole_positions: np.ndarray  # (6, 3)
    hole_rotations: np.ndarray  # (6, 3, 3)
    attachments: np.ndarray  # (6, 3), platform frame
    lengths: np.ndarray  # (6,)
    rod: RodParams
    platform_mass: float
    platform_inertia: np.ndarray  # (3,) principal, platform frame
    mount: np.ndarray  # (4, 4): platform k frame <- base k+1 frame


def solve_stack(specs, base_pose, platform_guesses, leg_shapes, gravity, wrench, tol, max_iter, n_load_steps):
    """All modules in one system: module k's holes sit on platform k-1 (Eq 29-30).

    ``platform_guesses``: (n, 4, 4) global poses; ``leg_shapes``: per module list of 6 LegShape
    in global coordinates.  ``wrench``: (F, M) global at the last platform origin, or None.
    Returns (outcome, platform poses (n,4,4), tip forces on legs (n,6,3), tip moments (n,6,3),
    leg node positions (n,6,N+1,3)).
    """
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    base_body, base_T = ground, np.asarray(base_pose, dtype=float)
    bodies, pnodes, tip_joints = [], [], []
    next_hole_pos = next_hole_rot = None  # holes of module k+1 in platform k's body frame
    for k, spec in enumerate(specs):
        Tg = platform_guesses[k]
        ep = Rotation.from_matrix(Tg[:3, :3]).as_quat()  # x, y, z, w
        pn = mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=list(Tg[:3, 3]) + [ep[3], ep[0], ep[1], ep[2]]))
        I = spec.platform_inertia
        body = mbs.AddObject(
            ObjectRigidBody(mass=max(spec.platform_mass, 1e-6), inertia=[I[0], I[1], I[2], 0.0, 0.0, 0.0], nodeNumber=pn)
        )
        joints = []
        for i in range(6):
            hp = base_T[:3, :3] @ spec.hole_positions[i] + base_T[:3, 3]
            hr = base_T[:3, :3] @ spec.hole_rotations[i]
            nodes, beams = _add_leg(mbs, spec.rod, hp, hr, spec.lengths[i], leg_shapes[k][i], gravity)
            if base_body == ground:
                _hole_joint(mbs, ground, hp, hr, nodes[0])
            else:
                _hole_joint(mbs, base_body, next_hole_pos[i], next_hole_rot[i], nodes[0])
            joints.append((_clamp_joint(mbs, body, spec.attachments[i], np.eye(3), nodes[-1]), beams[-1], nodes[-1], nodes))
        tip_joints.append(joints)
        mk = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0.0, 0.0, 0.0]))
        if gravity is not None and spec.platform_mass > 0:
            mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=list(spec.platform_mass * np.asarray(gravity))))
        if wrench is not None and k == len(specs) - 1:
            mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=list(map(float, wrench[0]))))
            mbs.AddLoad(LoadTorqueVector(markerNumber=mk, loadVector=list(map(float, wrench[1]))))
        bodies.append(body)
        pnodes.append(pn)
        # holes of the next module, expressed in this platform's body frame
        if k + 1 < len(specs):
            nxt = specs[k + 1]
            Mt = spec.mount
            next_hole_pos = [Mt[:3, :3] @ nxt.hole_positions[i] + Mt[:3, 3] for i in range(6)]
            next_hole_rot = [Mt[:3, :3] @ nxt.hole_rotations[i] for i in range(6)]
            base_body = body
            base_T = platform_guesses[k] @ Mt
    out = _solve(mbs, tol, max_iter, n_load_steps)
    if not out.converged:
        return out, None, None, None, (None, None)
    return (out, *_stack_outputs(mbs, len(specs), leg_shapes[0][0].positions.shape[0], pnodes, tip_joints))


def _stack_outputs(mbs, n_modules, n_nodes, pnodes, tip_joints):
    """Platform poses, tip forces and moments on the legs, and (leg node positions, frames) of a solved stack."""
    legpos = np.zeros((n_modules, 6, n_nodes, 3))
    legrot = np.zeros((n_modules, 6, n_nodes, 3, 3))
    poses = np.tile(np.eye(4), (n_modules, 1, 1))
    forces = np.zeros((n_modules, 6, 3))
    moments = np.zeros((n_modules, 6, 3))
    for k in range(n_modules):
        p, A = node_state(mbs, pnodes[k])
        poses[k, :3, :3] = A
        poses[k, :3, 3] = p
        for i in range(6):
            # the clamp joint's marker-0 frame: platform frame @ C
            jt, bm, nd = tip_joints[k][i][:3]
            for j, q in enumerate(tip_joints[k][i][3]):
                legpos[k, i, j], Aq = node_state(mbs, q)
                legrot[k, i, j] = Aq @ C_EXU.T
            forces[k, i], moments[k, i] = _tip_wrench_on_leg(mbs, jt, A @ C_EXU, bm, 0.0, nd)
    return poses, forces, moments, (legpos, legrot)
